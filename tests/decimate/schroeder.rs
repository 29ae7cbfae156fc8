//! Schroeder vertex removal at scale: a mesh large enough that passes run in regions on
//! all cores, that the candidates on region borders and the last ones before the target
//! are planned in several batches, and that removals later in a batch find their plans
//! stale (a removal before them changed what their checks read) and plan again. What
//! a user would notice if that went wrong: a broken mesh (non-manifold, flipped or
//! degenerate triangles), a count off the target, a different result on another machine.

use decimate_core::decimate::{simplify_scene, Params, Target};
use decimate_core::mesh::{measure, shapes, Model, Scene};
use glam::Vec3;

fn run(model: Model, params: &Params) -> Model {
    let mut scene = Scene {
        models: vec![model],
    };
    simplify_scene(&mut scene, params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

/// The same mesh on 1 and 3 threads as on the default pool.
fn on_threads(threads: usize, model: &Model, params: &Params) -> Model {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| run(model.clone(), params))
}

#[test]
fn a_large_sphere_keeps_its_shape_and_count_and_is_the_same_on_any_cores() {
    let before = shapes::bumpy_sphere(150, 300);
    let n = before.positions.len();
    assert!(n > 40_000, "{n} vertices: several batches a pass");
    let params = Params {
        target: Target::RemovePercent(90.0),
        ..Params::default()
    };
    let after = run(before.clone(), &params);
    let left = n - (0.9 * n as f64).round() as usize;
    assert_eq!(after.positions.len(), left);
    assert_eq!(after.triangles.len(), 2 * left - 4, "closed genus 0");
    let broken = measure::invariant_violations(&before, &after);
    assert!(broken.is_empty(), "{broken:?}");
    // The shape: volume and area within a percent (vertex removal never moves a vertex,
    // and the accumulated error keeps the removals spread).
    let (v0, v1) = (measure::volume(&before), measure::volume(&after));
    assert!((v1 / v0 - 1.0).abs() < 0.01, "volume {v0} -> {v1}");
    let (a0, a1) = (measure::area(&before), measure::area(&after));
    assert!((a1 / a0 - 1.0).abs() < 0.01, "area {a0} -> {a1}");
    for threads in [1, 3] {
        let again = on_threads(threads, &before, &params);
        assert_eq!(again.triangles, after.triangles, "{threads} threads");
        assert_eq!(again.positions, after.positions, "{threads} threads");
    }
}

#[test]
fn an_error_bound_stops_the_passes_without_a_count() {
    // Only an error bound: the passes stop when every candidate's key is above it, and no
    // removal made is above it.
    let before = shapes::bumpy_sphere(120, 240);
    let bound = 2e-3;
    let params = Params {
        target: Target::ErrorOnly,
        max_error: Some(decimate_core::decimate::ErrorBound::Absolute(bound)),
        ..Params::default()
    };
    let mut scene = Scene {
        models: vec![before.clone()],
    };
    let report = simplify_scene(&mut scene, &params, &mut |_| {});
    let after = &scene.models[0];
    let removed = before.positions.len() - after.positions.len();
    assert!(
        removed > before.positions.len() / 2,
        "a smooth sphere loses most of its vertices within {bound}: {removed}"
    );
    assert!(
        report.models[0].max_error <= bound,
        "{:?}",
        report.models[0]
    );
    assert!(measure::invariant_violations(&before, after).is_empty());
}

#[test]
fn a_flat_double_pyramid_loses_one_apex_not_both() {
    // Two apexes on one triangle, a little above and below it (and a second, less flat such
    // pyramid, so that a pass takes both apexes of the first: it takes half the
    // candidates). Both are planned in the same batch, each filling its hole with the
    // triangle: once the first has gone that triangle exists, and the second's plan, made
    // before, must be made again — it then fails, as the fill would duplicate a face. Used
    // stale, both apexes would go and leave two faces back to back, a sliver of no volume.
    let mut before = Model {
        name: "bipyramids".into(),
        ..Model::default()
    };
    for (offset, height) in [(0.0, 0.02), (3.0, 0.2)] {
        let base = before.positions.len() as u32;
        let [a, b, c, up, down] = [0, 1, 2, 3, 4].map(|i| base + i);
        before.positions.extend([
            Vec3::new(offset + 1.0, 0.0, 0.0),
            Vec3::new(offset - 0.5, 0.866, 0.0),
            Vec3::new(offset - 0.5, -0.866, 0.0),
            Vec3::new(offset, 0.0, height),
            Vec3::new(offset, 0.0, -height),
        ]);
        before.triangles.extend([
            [a, b, up],
            [b, c, up],
            [c, a, up],
            [b, a, down],
            [c, b, down],
            [a, c, down],
        ]);
    }
    // Apex edges of the steeper pyramid bend by about 37°: not features at 60°.
    let params = Params {
        target: Target::RemovePercent(100.0),
        feature_angle_deg: 60.0,
        ..Params::default()
    };
    let after = run(before.clone(), &params);
    assert_eq!(after.positions.len(), 8, "two tetrahedra are left");
    assert_eq!(after.triangles.len(), 8);
    let broken = measure::invariant_violations(&before, &after);
    assert!(broken.is_empty(), "{broken:?}");
    assert!(measure::volume(&after) > 0.0);
}

#[test]
fn an_open_box_in_regions_keeps_its_faces_edges_and_rim_on_any_cores() {
    // A finely meshed cube without its top: flat faces, creases along its edges, corners,
    // and a boundary rim, large enough for the passes to run in regions. Vertex removal on
    // a flat face is exact, and creases, corners and the rim's corners stay, so the area and
    // the bounding box are the box's.
    let mut before = shapes::cube(70, 2.0);
    before
        .triangles
        .retain(|t| !t.iter().all(|&v| before.positions[v as usize].z > 0.999));
    let used = before.used_vertex_count();
    assert!(used > 20_000, "{used} vertices: several regions");
    let remove = used * 95 / 100;
    let params = Params {
        target: Target::RemoveVertices(remove),
        ..Params::default()
    };
    let after = run(before.clone(), &params);
    assert_eq!(after.used_vertex_count(), used - remove);
    let broken = measure::invariant_violations(&before, &after);
    assert!(broken.is_empty(), "{broken:?}");
    let (a0, a1) = (measure::area(&before), measure::area(&after));
    assert!((a1 / a0 - 1.0).abs() < 1e-4, "area {a0} -> {a1}");
    let bounds = |m: &Model| {
        m.triangles.iter().flatten().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), &v| {
                let p = m.positions[v as usize];
                (lo.min(p), hi.max(p))
            },
        )
    };
    assert_eq!(bounds(&after), bounds(&before));
    for threads in [1, 3] {
        let again = on_threads(threads, &before, &params);
        assert_eq!(again.triangles, after.triangles, "{threads} threads");
        assert_eq!(again.positions, after.positions, "{threads} threads");
    }
}

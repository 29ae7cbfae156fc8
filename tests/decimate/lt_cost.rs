//! `--cost lt` (Lindström–Turk's memoryless cost and placement in quadric edge collapse):
//! exact counts, no fold against the input, closed shapes kept closed with their volume's
//! sign and (nearly) its size, a lower mean error than the quadric cost where keeping the
//! volume matters (a torus), and texture coordinates or `--keep-features` taken along.

use std::collections::HashMap;

use crate::support::check;
use crate::support::metro::compare_models;
use decimate_core::decimate::{simplify_scene, Algorithm, Cost, Params, Target};
use decimate_core::mesh::{measure, shapes, Model, Scene};
use glam::Vec3;

fn run(model: Model, params: &Params) -> Model {
    let mut scene = Scene {
        models: vec![model],
    };
    simplify_scene(&mut scene, params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

fn params(cost: Cost, keep: usize) -> Params {
    Params {
        target: Target::KeepTriangles(keep),
        algorithm: Algorithm::Qem,
        cost,
        ..Params::default()
    }
}

/// Edges in one triangle only, counted from the triangles alone (not `measure`'s count).
fn border_edges(m: &Model) -> usize {
    let mut count: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &m.triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count.values().filter(|&&n| n == 1).count()
}

/// A torus around the y axis (radii 1 and `minor`), `rings` × `segments` quads, facing out.
fn torus(rings: u32, segments: u32, minor: f32) -> Model {
    use std::f32::consts::TAU;
    let mut positions = Vec::new();
    for i in 0..rings {
        let u = TAU * i as f32 / rings as f32;
        for j in 0..segments {
            let v = TAU * j as f32 / segments as f32;
            let r = 1.0 + minor * v.cos();
            positions.push(Vec3::new(r * u.cos(), minor * v.sin(), r * u.sin()));
        }
    }
    let at = |i: u32, j: u32| (i % rings) * segments + j % segments;
    let mut triangles = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            triangles.push([a, c, b]);
            triangles.push([a, d, c]);
        }
    }
    Model {
        name: "torus".into(),
        positions,
        triangles,
        ..Model::default()
    }
}

/// What every LT output must keep of its closed input: the exact triangle count asked
/// for, no triangle turned from the input, the volume's sign, no border edge.
fn assert_kept(before: &Model, after: &Model, keep: usize) {
    assert_eq!(after.triangles.len(), keep, "{}", before.name);
    let found = check::geometry(before, after);
    assert!(found.triangles_checked > 0 && found.folds == 0, "{found:?}");
    assert!(found.closed_checked > 0 && found.inverted == 0, "{found:?}");
    assert_eq!(border_edges(after), 0, "{}: holes opened", before.name);
    let broken = measure::invariant_violations(before, after);
    assert!(broken.is_empty(), "{}: {broken:?}", before.name);
}

#[test]
fn lt_meets_the_count_on_a_bumpy_sphere_closed_unfolded_and_keeps_its_volume() {
    let before = shapes::bumpy_sphere(40, 80);
    let keep = before.triangles.len() / 10;
    let after = run(before.clone(), &params(Cost::LindstromTurk, keep));
    assert_kept(&before, &after, keep);
    // Volume preservation is the placement's first constraint.
    let (v0, v1) = (measure::volume(&before), measure::volume(&after));
    assert!((v1 - v0).abs() < 2e-3 * v0, "volume {v0} → {v1}");
}

#[test]
fn lt_has_a_lower_mean_error_than_the_quadric_cost_on_a_torus() {
    let before = torus(80, 24, 0.3);
    let keep = before.triangles.len() / 20;
    let mean = |cost| {
        let after = run(before.clone(), &params(cost, keep));
        assert_kept(&before, &after, keep);
        compare_models(&before, &after).symmetric().mean
    };
    let (lt, quadric) = (mean(Cost::LindstromTurk), mean(Cost::Quadric));
    assert!(lt < quadric, "mean error: lt {lt} ≥ quadric {quadric}");
}

#[test]
fn lt_takes_texture_coordinates_and_kept_features_along_with_exact_counts() {
    let mut before = shapes::bumpy_sphere(30, 60);
    before.texcoords = Some(
        (before.positions.iter())
            .map(|p| [0.5 + 0.5 * p.x, 0.5 + 0.5 * p.z])
            .collect(),
    );
    let keep = before.triangles.len() / 10;
    let after = run(before.clone(), &params(Cost::LindstromTurk, keep));
    assert_kept(&before, &after, keep);
    let texcoords = after.texcoords.as_ref().map_or(0, Vec::len);
    assert_eq!(texcoords, after.positions.len());
    // A cube's corners and edges are features: kept, and the rest collapses to the count.
    let before = shapes::cube(8, 2.0);
    let keep = before.triangles.len() / 4;
    let features = Params {
        keep_features: true,
        ..params(Cost::LindstromTurk, keep)
    };
    let after = run(before.clone(), &features);
    assert_kept(&before, &after, keep);
    let corners = (after.positions.iter())
        .filter(|p| p.abs().cmpeq(Vec3::ONE).all())
        .count();
    assert_eq!(corners, 8, "a cube's corners moved or went");
}

//! Quadric edge collapse (`--algorithm qem`) on the report's test models and on spheres:
//! exact counts, the invariants every output keeps (no degenerate or flipped triangle,
//! manifold, Euler characteristic and boundary loops unchanged), flat shapes kept exactly,
//! an error bound respected, and a lower mean error than Schroeder's at the same size.

use crate::support::metro::compare_models;
use decimate_core::decimate::{simplify_scene, Algorithm, ErrorBound, Params, Report, Target};
use decimate_core::mesh::{measure, shapes, Attribute, Model, Scene};

use crate::progressive::red_above_blue_below;

fn run(model: Model, params: Params) -> (Model, Report) {
    let mut scene = Scene {
        models: vec![model],
    };
    let report = simplify_scene(&mut scene, &params, &mut |_| {});
    let name = &report.models[0].name;
    let model = scene
        .models
        .pop()
        .unwrap_or_else(|| panic!("{name} dropped"));
    (model, report)
}

fn qem(target: Target) -> Params {
    Params {
        target,
        algorithm: Algorithm::Qem,
        ..Params::default()
    }
}

/// Collapses of zero error only (up to rounding): what a flat-faced shape can lose exactly.
fn lossless() -> Params {
    Params {
        max_error: Some(ErrorBound::Absolute(1e-5)),
        ..qem(Target::ErrorOnly)
    }
}

/// The same invariants as tests/decimate/report_models.rs, except that vertices move.
fn assert_invariants(before: &Model, after: &Model) {
    let name = &before.name;
    let broken = measure::invariant_violations(before, after);
    assert!(broken.is_empty(), "{name}: {broken:?}");
}

/// Symmetric mean and max distance between two models, measured by metro.
fn distance(a: &Model, b: &Model) -> (f64, f64) {
    let s = compare_models(a, b).symmetric();
    (s.mean, s.max)
}

#[test]
fn test001_pyramid_loses_its_base_centre() {
    let before = shapes::test001();
    let (after, _) = run(before.clone(), lossless());
    assert_eq!((after.positions.len(), after.triangles.len()), (4, 4));
    assert_invariants(&before, &after);
    assert!((measure::volume(&after) - measure::volume(&before)).abs() < 1e-6);
}

#[test]
fn test002_small_cube_becomes_eight_corners() {
    let before = shapes::test002();
    let (after, _) = run(before.clone(), lossless());
    assert_eq!((after.positions.len(), after.triangles.len()), (8, 12));
    assert_invariants(&before, &after);
    assert!((measure::volume(&after) - 8.0).abs() < 1e-5);
}

#[test]
fn test003_plane_becomes_two_triangles_with_the_same_area() {
    let before = shapes::test003();
    let (after, report) = run(before.clone(), lossless());
    assert_eq!((after.positions.len(), after.triangles.len()), (4, 2));
    assert!(report.models[0].max_error < 1e-5);
    assert_invariants(&before, &after);
    assert!((measure::area(&after) - 100.0).abs() < 1e-6);
}

#[test]
fn test004_large_cube_becomes_eight_corners_with_the_same_volume() {
    let before = shapes::test004();
    let (after, _) = run(before.clone(), lossless());
    assert_eq!((after.positions.len(), after.triangles.len()), (8, 12));
    assert_invariants(&before, &after);
    assert!((measure::volume(&after) - 1000.0).abs() < 1e-3);
    assert!((measure::area(&after) - 600.0).abs() < 1e-3);
    // Count targets on the cube keep it a cube too: its faces are planes.
    let (after, _) = run(before.clone(), qem(Target::RemovePercent(90.0)));
    assert_eq!(after.positions.len(), 60);
    assert_invariants(&before, &after);
    assert!((measure::volume(&after) - 1000.0).abs() < 1e-3);
}

#[test]
fn every_report_model_keeps_the_invariants_at_every_percentage() {
    for before in shapes::all() {
        let n = before.positions.len();
        for p in [50.0, 80.0, 95.0, 100.0] {
            let (after, report) = run(before.clone(), qem(Target::RemovePercent(p)));
            assert_invariants(&before, &after);
            let m = &report.models[0];
            assert!(after.positions.len() >= 4, "{}: under four", before.name);
            if p < 100.0 {
                let left = n - (p / 100.0 * n as f64).round() as usize;
                assert!(
                    after.positions.len() == left || m.fully_decimated,
                    "{} -p {p}: {} left, expected {left}",
                    before.name,
                    after.positions.len()
                );
            }
        }
    }
}

#[test]
fn sphere_percentages_are_exact() {
    let before = shapes::uv_sphere(24, 48);
    let n = before.positions.len();
    for p in [60.0, 80.0, 90.0] {
        let (after, report) = run(before.clone(), qem(Target::RemovePercent(p)));
        let left = n - (p / 100.0 * n as f64).round() as usize;
        assert_eq!(after.positions.len(), left, "-p {p}");
        assert_eq!(report.models[0].vertices_after, left);
        assert_eq!(
            after.triangles.len(),
            2 * left - 4,
            "-p {p}: closed genus 0"
        );
        assert_invariants(&before, &after);
        assert!(report.models[0].max_error > 0.0);
    }
    let (after, _) = run(before.clone(), qem(Target::KeepVertices(100)));
    assert_eq!(after.positions.len(), 100);
    let (after, _) = run(before.clone(), qem(Target::KeepTriangles(200)));
    assert_eq!(after.triangles.len(), 200);
}

#[test]
fn the_error_bound_holds_on_the_surface() {
    let before = shapes::bumpy_sphere(32, 64);
    let diagonal = before
        .bounds()
        .map_or(0.0, |(lo, hi)| (hi - lo).length() as f64);
    let bound = 0.005 * diagonal;
    let params = Params {
        max_error: Some(ErrorBound::DiagonalFraction(0.005)),
        ..qem(Target::ErrorOnly)
    };
    let (after, report) = run(before.clone(), params);
    let m = &report.models[0];
    assert!(m.max_error <= bound, "{} > {bound}", m.max_error);
    assert!(
        after.positions.len() < before.positions.len() / 2,
        "{} of {} vertices left",
        after.positions.len(),
        before.positions.len()
    );
    assert_invariants(&before, &after);
    let (mean, max) = distance(&before, &after);
    assert!(mean <= bound, "mean {mean} > {bound}");
    assert!(max <= 4.0 * bound, "max {max} > 4 × {bound}");
}

#[test]
fn qem_beats_schroeder_by_ten_percent_on_a_bumpy_sphere() {
    let before = shapes::bumpy_sphere(48, 96);
    let target = Target::RemovePercent(90.0);
    let schroeder = Params {
        target,
        ..Params::default()
    };
    let (s, _) = run(before.clone(), schroeder);
    let (q, _) = run(before.clone(), qem(target));
    assert_eq!(s.positions.len(), q.positions.len());
    assert_invariants(&before, &q);
    let (mean_s, _) = distance(&before, &s);
    let (mean_q, _) = distance(&before, &q);
    assert!(
        mean_q <= 0.9 * mean_s,
        "qem mean {mean_q} vs schroeder {mean_s}"
    );
}

#[test]
fn runs_on_all_cores_give_the_same_mesh_every_time_and_on_any_number_of_cores() {
    // 120 × 240 gives about 29,000 vertices: the passes collapse in seven regions at once,
    // and ranking and every pass end are split into several parallel tasks, so a race
    // between threads, or a region touching another's data, would show as a different mesh
    // (or a broken invariant). Per-vertex colours and normals ride along, split with the
    // regions.
    let mut before = shapes::bumpy_sphere(120, 240);
    let n = before.positions.len();
    before.colors = Some(Attribute::PerVertex(
        before
            .positions
            .iter()
            .map(|p| [p.x.abs().min(1.0), p.y.abs().min(1.0), 0.5])
            .collect(),
    ));
    before.normals = Some(Attribute::PerVertex(
        before.positions.iter().map(|p| p.normalize()).collect(),
    ));
    assert!(n > 28_000, "{n} vertices");
    let params = qem(Target::RemovePercent(90.0));
    let (first, _) = run(before.clone(), params);
    let left = n - (0.9 * n as f64).round() as usize;
    assert_eq!(first.positions.len(), left);
    assert_eq!(first.triangles.len(), 2 * left - 4, "closed genus 0");
    assert_invariants(&before, &first);
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        pool.install(|| run(before.clone(), params).0)
    };
    for again in [run(before.clone(), params).0, on(1), on(3)] {
        assert_eq!(again.triangles, first.triangles);
        assert_eq!(again.positions, first.positions);
        assert_eq!(again.colors, first.colors);
        assert_eq!(again.normals, first.normals);
    }
}

/// An open, wavy height field of `n × n` vertices: one boundary loop, with corners.
fn wavy_sheet(n: u32) -> Model {
    let at = |i: u32, j: u32| i * n + j;
    let positions = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| {
            let (x, z) = (i as f32 / (n - 1) as f32, j as f32 / (n - 1) as f32);
            glam::Vec3::new(x, 0.05 * (9.0 * x).sin() * (7.0 * z).cos(), z)
        })
        .collect();
    let triangles = (0..n - 1)
        .flat_map(|i| (0..n - 1).map(move |j| (i, j)))
        .flat_map(|(i, j)| {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            [[a, d, c], [a, c, b]]
        })
        .collect();
    Model {
        name: "sheet".into(),
        positions,
        triangles,
        ..Model::default()
    }
}

#[test]
fn an_open_sheet_keeps_its_outline_in_regions_on_any_number_of_cores() {
    // 200 × 200 vertices: the passes run in nine regions, and the outline's vertices (held
    // on it by their constraint planes) sit on many region borders.
    let before = wavy_sheet(200);
    let n = before.positions.len();
    let params = qem(Target::RemovePercent(90.0));
    let (first, _) = run(before.clone(), params);
    assert_eq!(first.positions.len(), n - (0.9 * n as f64).round() as usize);
    assert_invariants(&before, &first);
    // The outline stays on the unit square's border (its constraint planes are weighted,
    // not exact: within 1e-4 of the sheet's size), and so do its corners.
    let on_border = |p: &glam::Vec3| {
        [p.x, p.z]
            .iter()
            .any(|&c| c.abs() < 1e-4 || (c - 1.0).abs() < 1e-4)
    };
    let mut uses = std::collections::HashMap::new();
    for t in &first.triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let outline: Vec<u32> = uses
        .iter()
        .filter(|&(_, &count)| count == 1)
        .flat_map(|(&(a, b), _)| [a, b])
        .collect();
    assert!(!outline.is_empty());
    for &v in &outline {
        let p = first.positions[v as usize];
        assert!(on_border(&p), "outline vertex {v} at {p} left the border");
    }
    for corner in [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]] {
        let found = first
            .positions
            .iter()
            .any(|p| (p.x - corner[0]).abs() < 1e-4 && (p.z - corner[1]).abs() < 1e-4);
        let nearest = first
            .positions
            .iter()
            .map(|p| ((p.x - corner[0]).powi(2) + (p.z - corner[1]).powi(2)).sqrt())
            .fold(f32::INFINITY, f32::min);
        assert!(
            found,
            "corner {corner:?} moved: nearest vertex {nearest} away"
        );
    }
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    let again = single.install(|| run(before.clone(), params).0);
    assert_eq!(again.triangles, first.triangles);
    assert_eq!(again.positions, first.positions);
}

#[test]
fn colours_follow_the_vertices_and_faces() {
    // Per-vertex: red above the equator, blue below; interpolation keeps values in range.
    let before = red_above_blue_below(shapes::uv_sphere(16, 32));
    let (after, _) = run(before.clone(), qem(Target::RemovePercent(80.0)));
    let Some(Attribute::PerVertex(c)) = &after.colors else {
        panic!("per-vertex colours lost");
    };
    assert_eq!(c.len(), after.positions.len());
    assert!(c
        .iter()
        .all(|c| c[1] == 0.0 && (c[0] + c[2] - 1.0).abs() < 1e-6));
    // Pure colours survive away from the equator.
    assert!(c.iter().any(|c| c[0] == 1.0) && c.iter().any(|c| c[2] == 1.0));
    // Per-face: one colour per surviving face, drawn from the input's.
    let mut before = shapes::test004();
    let faces = (0..before.triangles.len())
        .map(|t| [t as f32, 0.0, 0.0])
        .collect();
    before.colors = Some(Attribute::PerFace(faces));
    let (after, _) = run(before, qem(Target::RemovePercent(90.0)));
    let Some(Attribute::PerFace(c)) = &after.colors else {
        panic!("per-face colours lost");
    };
    assert_eq!(c.len(), after.triangles.len());
    let mut ids: Vec<u32> = c.iter().map(|c| c[0] as u32).collect();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), after.triangles.len(), "a face colour used twice");
}

#[test]
fn the_binary_runs_qem_end_to_end() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let input: std::path::PathBuf = [env!("CARGO_MANIFEST_DIR"), "assets", "test004.wrl"]
        .iter()
        .collect();
    let out = dir.path().join("out.wrl");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_decimate"))
        .arg(&input)
        .args(["nogui", "-a", "qem", "-p", "90", "-o"])
        .arg(&out)
        .output()
        .expect("run decimate");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let scene = decimate_core::io::read_scene(&out)
        .expect("output parses")
        .scene;
    let after = &scene.models[0];
    assert_eq!(after.positions.len(), 60);
    assert!((measure::volume(after) - 1000.0).abs() < 1e-3);
}

/// A flat square sheet of `n` × `n` squares whose per-vertex normals carry a bumpy shading
/// (as a baked or hand-made normal set does): the geometry alone says every collapse is
/// free.
fn shaded_sheet(n: u32) -> Model {
    let at = |i: u32, j: u32| j * (n + 1) + i;
    let mut m = Model {
        name: "shaded".into(),
        positions: (0..=n)
            .flat_map(|j| (0..=n).map(move |i| glam::Vec3::new(i as f32, j as f32, 0.0) / n as f32))
            .collect(),
        triangles: (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .flat_map(|(i, j)| {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                [[a, b, c], [a, c, d]]
            })
            .collect(),
        ..Model::default()
    };
    let normal = |p: glam::Vec3| {
        let k = std::f32::consts::TAU * 3.0;
        let (dx, dy) = (
            0.3 * (k * p.x).cos() * (k * p.y).sin(),
            0.3 * (k * p.x).sin() * (k * p.y).cos(),
        );
        glam::Vec3::new(-dx, -dy, 1.0).normalize()
    };
    m.normals = Some(Attribute::PerVertex(
        m.positions.iter().map(|&p| normal(p)).collect(),
    ));
    m
}

/// The mean angle (degrees) between `before`'s normals and `after`'s normals interpolated
/// at the same (x, y): both flat sheets in z = 0.
fn shading_error(before: &Model, after: &Model) -> f64 {
    let (Some(Attribute::PerVertex(n0)), Some(Attribute::PerVertex(n1))) =
        (&before.normals, &after.normals)
    else {
        panic!("per-vertex normals lost");
    };
    let mut sum = 0.0;
    for (p, n) in before.positions.iter().zip(n0) {
        let found = after.triangles.iter().find_map(|t| {
            let [a, b, c] = t.map(|v| after.positions[v as usize].truncate());
            let q = p.truncate();
            let area = (b - a).perp_dot(c - a);
            let u = (c - b).perp_dot(q - b) / area;
            let v = (a - c).perp_dot(q - c) / area;
            let w = 1.0 - u - v;
            (u >= -1e-5 && v >= -1e-5 && w >= -1e-5).then(|| {
                let [na, nb, nc] = t.map(|v| n1[v as usize]);
                (u * na + v * nb + w * nc).normalize()
            })
        });
        let Some(m) = found else {
            panic!("{p} is off the decimated sheet")
        };
        sum += f64::from(n.dot(m).clamp(-1.0, 1.0).acos().to_degrees());
    }
    sum / before.positions.len() as f64
}

#[test]
fn per_vertex_normals_weigh_in_so_a_flat_sheet_keeps_its_shading() {
    let before = shaded_sheet(40);
    let (after, _) = run(before.clone(), qem(Target::RemovePercent(90.0)));
    assert_invariants(&before, &after);
    let error = shading_error(&before, &after);
    eprintln!("mean shading error {error:.2}°");
    // Without the normals in the cost: 10.8° (shading gone: the mean tilt is about 9°).
    assert!(error < 7.0, "mean shading error {error:.2}°");
}

/// One OBJ face of `n` corners round a wavy circle: its triangulation gives vertices of
/// high valence and long fans, where a split-off part's incident lists run full.
fn huge_polygon_obj(n: u32) -> String {
    let mut obj = String::new();
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        let r = 1.0 + 0.1 * (7.0 * a).sin();
        obj += &format!("v {:.7} {:.7} 0\n", r * a.cos(), r * a.sin());
    }
    obj += "f";
    for i in 1..=n {
        obj += &format!(" {i}");
    }
    obj + "\n"
}

#[test]
fn a_polygon_of_a_hundred_thousand_corners_decimates() {
    // A 45,000-corner face once ran past a minute at -p 90: a collapse in a split-off part
    // overfilled the kept vertex's incident list for a moment (the edge's triangles left
    // it after the others had joined) and the connectivity lost triangles.
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("polygon.obj");
    std::fs::write(&path, huge_polygon_obj(100_000)).expect("write the polygon");
    let read = decimate_core::io::read_scene(&path).expect("the polygon reads");
    let before = read.scene.models[0].clone();
    assert_eq!(
        (before.positions.len(), before.triangles.len()),
        (100_000, 99_998)
    );
    let (after, report) = run(before.clone(), qem(Target::RemovePercent(90.0)));
    assert_eq!(report.models[0].vertices_after, 10_000);
    // A disk keeps its Euler characteristic: V - 2 triangles.
    assert_eq!(
        (after.positions.len(), after.triangles.len()),
        (10_000, 9_998)
    );
    // One disk, its outline whole: every kept vertex on it (edges of one triangle), none
    // shared by three triangles or flipped (the input's slivers may stay slivers).
    let e = measure::edge_counts(&after);
    assert_eq!((e.boundary, e.non_manifold, e.misoriented), (10_000, 0, 0));
    assert_eq!(e.edges, 10_000 + 9_998 - 1, "Euler: V - E + F = 1");
    assert!(after.positions.iter().all(|p| p.z == 0.0));
}

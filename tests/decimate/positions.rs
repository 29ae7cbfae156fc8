//! Counts are of positions: a texture seam's copies of one point (a vertex per side) count
//! once in `-v`, `-p`, `--keep-vertices` and the report, as MeshLab, Blender and pmp count
//! them. Positions are counted here by their bits, apart from the library's own count.

use std::collections::HashSet;

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Report, Target};
use decimate_core::io::read_scene;
use decimate_core::mesh::{Model, Scene};

use crate::seams::{lat_long_sphere_obj, scene_from};
use crate::support::binary;

/// The distinct positions of the vertices `model`'s triangles use (-0 and 0 as one), and
/// those vertices.
fn positions_and_vertices(model: &Model) -> (usize, usize) {
    let used: HashSet<u32> = model.triangles.iter().flatten().copied().collect();
    let positions: HashSet<[u32; 3]> = (used.iter())
        .map(|&v| (model.positions[v as usize].to_array()).map(|c| (c + 0.0).to_bits()))
        .collect();
    (positions.len(), used.len())
}

fn decimate(scene: &Scene, algorithm: Algorithm, target: Target) -> (Model, Report) {
    let mut out = scene.clone();
    let params = Params {
        target,
        algorithm,
        ..Params::default()
    };
    let report = simplify_scene(&mut out, &params, &mut |_| {});
    (out.models.pop().unwrap_or_default(), report)
}

#[test]
fn a_textured_sphere_is_counted_and_cut_in_positions() {
    // 6 rings of 8 quads: 2 poles and 5 rings of 8 points, held by 5 rows of 9 vertices
    // (the u = 0 / u = 1 column a seam) and 8 copies of each pole (one a slice).
    let scene = scene_from("sphere.obj", &lat_long_sphere_obj(6, 8));
    let (positions, vertices) = positions_and_vertices(&scene.models[0]);
    assert_eq!((positions, vertices), (42, 61));
    for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
        for (target, left) in [
            (Target::KeepVertices(30), 30),
            (Target::RemovePercent(25.0), 42 - 11), // 10.5 rounds to 11
            (Target::RemoveVertices(8), 34),
        ] {
            let what = format!("{algorithm:?} {target:?}");
            let (after, report) = decimate(&scene, algorithm, target);
            let (positions, vertices) = positions_and_vertices(&after);
            assert_eq!(positions, left, "{what}");
            let m = &report.models[0];
            assert_eq!((m.vertices_before, m.vertices_after), (42, left), "{what}");
            // The copies are reported apart.
            assert_eq!(m.seam_copies_before, 19, "{what}");
            assert_eq!(m.vertices_after + m.seam_copies_after, vertices, "{what}");
        }
    }
}

#[test]
fn the_binary_keeps_as_many_positions_as_asked() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join("s.obj"), lat_long_sphere_obj(6, 8)).expect("write");
    let args = [
        "s.obj",
        "nogui",
        "--keep-vertices",
        "30",
        "-a",
        "qem",
        "-o",
        "out.obj",
    ];
    let run = binary::decimate(dir.path(), &args);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(stderr.contains("vertices        42 -> 30 "), "{stderr}");
    let read = read_scene(&dir.path().join("out.obj")).expect("the output reads");
    let (positions, _) = positions_and_vertices(&read.scene.models[0]);
    assert_eq!(positions, 30);
}

//! `--keep-features` under both algorithms: a corner (three feature edges, or a crease's
//! end) never moves nor goes, and a crease shortens only along itself. Checked by the
//! positions themselves (each corner exactly where it was), through the library and once
//! through the binary.

use std::collections::HashSet;

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::io::read_scene;
use decimate_core::mesh::{measure, shapes, Attribute, Model, Scene};
use glam::Vec3;

use crate::support::binary;

/// The regular icosahedron, flat-shaded (a normal per face): every edge turns by 41.8°,
/// beyond the 30° feature angle, so all twelve vertices are corners.
fn icosahedron() -> Model {
    let g = (1.0 + 5f32.sqrt()) / 2.0;
    let positions = vec![
        Vec3::new(-1.0, g, 0.0),
        Vec3::new(1.0, g, 0.0),
        Vec3::new(-1.0, -g, 0.0),
        Vec3::new(1.0, -g, 0.0),
        Vec3::new(0.0, -1.0, g),
        Vec3::new(0.0, 1.0, g),
        Vec3::new(0.0, -1.0, -g),
        Vec3::new(0.0, 1.0, -g),
        Vec3::new(g, 0.0, -1.0),
        Vec3::new(g, 0.0, 1.0),
        Vec3::new(-g, 0.0, -1.0),
        Vec3::new(-g, 0.0, 1.0),
    ];
    let triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let p = |v: u32| positions[v as usize];
    let normals = (triangles.iter())
        .map(|&[a, b, c]| (p(b) - p(a)).cross(p(c) - p(a)).normalize())
        .collect();
    Model {
        name: "icosahedron".into(),
        positions,
        triangles,
        normals: Some(Attribute::PerFace(normals)),
        ..Model::default()
    }
}

fn decimate(model: &Model, algorithm: Algorithm, target: Target, keep: bool) -> Model {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target,
        algorithm,
        keep_features: keep,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

/// The input's positions that are also, bit for bit, positions of the output.
fn kept_exactly(input: &[Vec3], output: &Model) -> usize {
    let out: HashSet<[u32; 3]> = (output.positions.iter())
        .map(|p| p.to_array().map(f32::to_bits))
        .collect();
    (input.iter())
        .filter(|p| out.contains(&p.to_array().map(f32::to_bits)))
        .count()
}

/// The corners of `cube(n, 1.0)`: (±0.5, ±0.5, ±0.5).
fn cube_corners() -> Vec<Vec3> {
    (0..8)
        .map(|i| {
            let s = |bit: u32| if i & bit == 0 { -0.5 } else { 0.5 };
            Vec3::new(s(1), s(2), s(4))
        })
        .collect()
}

#[test]
fn an_icosahedron_asked_for_six_vertices_keeps_its_twelve_corners_where_they_are() {
    let before = icosahedron();
    for algorithm in [Algorithm::Qem, Algorithm::Schroeder] {
        let after = decimate(&before, algorithm, Target::KeepVertices(6), true);
        assert_eq!(after.positions.len(), 12, "{algorithm:?}");
        assert_eq!(after.triangles.len(), 20, "{algorithm:?}");
        assert_eq!(kept_exactly(&before.positions, &after), 12, "{algorithm:?}");
    }
    // Without the flag the count is met: the corners are what the flag keeps.
    let free = decimate(&before, Algorithm::Qem, Target::KeepVertices(6), false);
    assert_eq!(free.positions.len(), 6);
}

#[test]
fn a_cube_decimated_as_far_as_possible_stays_a_cube() {
    let before = shapes::cube(8, 1.0);
    for algorithm in [Algorithm::Qem, Algorithm::Schroeder] {
        let after = decimate(&before, algorithm, Target::RemovePercent(100.0), true);
        let name = format!("{algorithm:?}");
        assert_eq!(after.positions.len(), 8, "{name}");
        assert_eq!(after.triangles.len(), 12, "{name}");
        assert_eq!(kept_exactly(&cube_corners(), &after), 8, "{name}");
        let volume = measure::volume(&after);
        assert!((volume - 1.0).abs() < 1e-5, "{name}: volume {volume}");
        let broken = measure::invariant_violations(&before, &after);
        assert!(broken.is_empty(), "{name}: {broken:?}");
    }
}

/// A roof: two slopes rising 20° to a ridge along x = 0 (a 40° fold, a feature edge at
/// the default 30°), each slope a grid of `2n` × `n` squares, so that every triangle lies
/// in one slope.
fn roof(n: u32) -> Model {
    let slope = 20f32.to_radians().tan();
    let side = 2 * n + 1;
    let positions = (0..side * side)
        .map(|i| {
            let (x, y) = (
                (i % side) as f32 / n as f32 - 1.0,
                (i / side) as f32 / n as f32,
            );
            Vec3::new(x, y, slope * (1.0 - x.abs()))
        })
        .collect();
    let mut triangles = Vec::new();
    for j in 0..side - 1 {
        for i in 0..side - 1 {
            let a = j * side + i;
            triangles.push([a, a + 1, a + side + 1]);
            triangles.push([a, a + side + 1, a + side]);
        }
    }
    Model {
        name: "roof".into(),
        positions,
        triangles,
        ..Model::default()
    }
}

#[test]
fn a_ridge_collapses_only_along_itself() {
    // Cut hard, every triangle still lies in one slope: a ridge vertex that went into a
    // slope's vertex, or moved off the ridge, would leave a triangle across the two.
    let before = roof(8);
    let slope = 20f32.to_radians().tan();
    let on = |p: &Vec3, side: f32| (p.z - slope * (1.0 - side * p.x)).abs() < 1e-5;
    for algorithm in [Algorithm::Qem, Algorithm::Schroeder] {
        let after = decimate(&before, algorithm, Target::RemovePercent(95.0), true);
        for t in &after.triangles {
            let corners = t.map(|v| after.positions[v as usize]);
            let in_slope = |side| corners.iter().all(|p| on(p, side));
            assert!(
                in_slope(1.0) || in_slope(-1.0),
                "{algorithm:?}: {corners:?} across the ridge"
            );
        }
        // What stands on the ridge stands exactly on it (moved along it, x and z as they
        // were): not a slope's vertex pulled onto it by the two slopes' planes.
        for p in after.positions.iter().filter(|p| p.x.abs() < 1e-3) {
            assert!(
                p.x == 0.0 && p.z == slope,
                "{algorithm:?}: {p} beside the ridge"
            );
        }
        // The ridge's two ends stay: corners where it meets the border.
        let ends = [Vec3::new(0.0, 0.0, slope), Vec3::new(0.0, 2.0, slope)];
        assert_eq!(kept_exactly(&ends, &after), 2, "{algorithm:?}");
        let broken = measure::invariant_violations(&before, &after);
        assert!(broken.is_empty(), "{algorithm:?}: {broken:?}");
    }
}

#[test]
fn the_binary_keeps_the_icosahedron_s_corners_under_qem() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mut obj = String::new();
    let model = icosahedron();
    for p in &model.positions {
        obj += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for (i, t) in model.triangles.iter().enumerate() {
        obj += &format!(
            "vn 0 0 1\nf {}//{} {}//{} {}//{}\n",
            t[0] + 1,
            i + 1,
            t[1] + 1,
            i + 1,
            t[2] + 1,
            i + 1
        );
    }
    std::fs::write(dir.path().join("ico.obj"), obj).expect("write the input");
    let args = [
        "ico.obj",
        "nogui",
        "-q",
        "-a",
        "qem",
        "--keep-vertices",
        "6",
        "--keep-features",
        "-o",
        "out.ply",
    ];
    let run = binary::decimate(dir.path(), &args);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let read = read_scene(&dir.path().join("out.ply")).expect("the output reads");
    let after = &read.scene.models[0];
    assert_eq!((after.positions.len(), after.triangles.len()), (12, 20));
    // The OBJ's decimal digits read back to the same f32 the model holds.
    assert_eq!(kept_exactly(&model.positions, after), 12);
}

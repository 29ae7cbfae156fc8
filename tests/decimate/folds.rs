//! Quadric edge collapse weighs a fold as a crease by how finely the mesh is sampled: a
//! noisy sheet, whose every fold is sampling or noise, spends nothing on holding its folds
//! (the same result as with no feature edges at all), while a finely sampled box with bumps
//! keeps its corners and volume (docs/design.md#qem-fold-scale).

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::mesh::{measure, shapes, Model, Scene};
use glam::Vec3;

use crate::support::rng::Rng;

fn qem(model: &Model, triangles: usize, feature_angle_deg: f64) -> Model {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target: Target::KeepTriangles(triangles),
        algorithm: Algorithm::Qem,
        feature_angle_deg,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

/// An `n` × `n` grid of unit squares whose inner vertices are lifted at random by up to
/// `noise`: a rough scan of a flat sheet.
fn noisy_sheet(n: u32, noise: f32) -> Model {
    let mut rng = Rng(40);
    let lift: Vec<f32> = (0..(n + 1) * (n + 1))
        .map(|_| rng.signed() * noise)
        .collect();
    let inner = |i: u32, j: u32| i > 0 && j > 0 && i < n && j < n;
    let sheet = shapes::height_grid(n, |i, j| {
        if inner(i, j) {
            lift[(i * (n + 1) + j) as usize]
        } else {
            0.0
        }
    });
    Model {
        name: "noisy sheet".into(),
        ..sheet
    }
}

fn assert_invariants(before: &Model, after: &Model) {
    let broken = measure::invariant_violations(before, after);
    assert!(broken.is_empty(), "{}: {broken:?}", before.name);
}

#[test]
fn a_noisy_sheet_spends_nothing_on_its_folds() {
    let before = noisy_sheet(40, 0.6);
    let after = qem(&before, 640, 30.0);
    // An inside collapse takes two triangles: from 641 the count ends at 639.
    assert!((639..=640).contains(&after.triangles.len()));
    assert_invariants(&before, &after);
    let unconstrained = qem(&before, 640, 180.0);
    assert_eq!(after.triangles, unconstrained.triangles);
    assert_eq!(after.positions, unconstrained.positions);
}

#[test]
fn a_fine_box_with_bumps_keeps_its_corners_and_volume() {
    let mut before = shapes::cube(16, 2.0); // side 2, 16 × 16 squares a face
                                            // A bump of 0.05 at every fourth inner grid point of the +z face.
    let mut bumps = 0;
    for p in before.positions.iter_mut() {
        let on_grid = |c: f32| ((c * 8.0).round() as i32).rem_euclid(4) == 0 && c.abs() < 0.9;
        if p.z == 1.0 && on_grid(p.x) && on_grid(p.y) {
            p.z += 0.05;
            bumps += 1;
        }
    }
    assert_eq!(bumps, 9);
    let after = qem(&before, 150, 30.0);
    assert_eq!(after.triangles.len(), 150);
    assert_invariants(&before, &after);
    for i in 0..8 {
        let bit = |k: u32| if i >> k & 1 == 1 { -1.0 } else { 1.0 };
        let corner = Vec3::new(bit(0), bit(1), bit(2));
        assert!(
            after
                .positions
                .iter()
                .any(|p| (*p - corner).length() < 1e-5),
            "corner {corner} lost"
        );
    }
    let (v0, v1) = (measure::volume(&before), measure::volume(&after));
    assert!((v1 / v0 - 1.0).abs() < 0.005, "volume {v0} -> {v1}");
}

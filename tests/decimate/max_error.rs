//! `--max-error E` is a bound on the symmetric Hausdorff distance between input and output
//! as metro measures it (every sample of either surface within E of the other), for both
//! algorithms: on every report shape, on noisy grids and spheres like the random tests', on
//! a bumpy sphere and on the bundled bunny scan, at bounds that stop the run (it still
//! removes a good part of the vertices).

use decimate_core::decimate::{simplify_scene, Algorithm, ErrorBound, Params, Target};
use decimate_core::io::read_scene;
use decimate_core::mesh::{shapes, Model, Scene};
use glam::Vec3;

use crate::support::metro::compare_models;
use crate::support::rng::Rng;

/// Metro samples the surfaces; its maximum may land a little past the bound's own check.
const SAMPLING: f64 = 1.01;

/// `model` decimated by `algorithm` under `--max-error` `bound` alone (no count).
fn bounded(model: &Model, algorithm: Algorithm, bound: f64) -> Model {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target: Target::ErrorOnly,
        max_error: Some(ErrorBound::Absolute(bound)),
        algorithm,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

fn diagonal(m: &Model) -> f64 {
    m.bounds().map_or(0.0, |(lo, hi)| (hi - lo).length() as f64)
}

/// Decimates `model` both ways at `fraction` of its diagonal; asserts metro's Hausdorff
/// distance within the bound and at least `removed_share` of the vertices gone.
fn check(what: &str, model: &Model, fraction: f64, removed_share: [f64; 2]) {
    let bound = fraction * diagonal(model);
    for (algorithm, share) in [Algorithm::Schroeder, Algorithm::Qem]
        .into_iter()
        .zip(removed_share)
    {
        let after = bounded(model, algorithm, bound);
        let c = compare_models(model, &after);
        let hausdorff = c.a_to_b.max.max(c.b_to_a.max);
        let (before, left) = (model.positions.len(), after.positions.len());
        let removed = before.saturating_sub(left) as f64 / before as f64;
        eprintln!(
            "{what} {algorithm:?} {fraction}: {before} -> {left} vertices ({:.3} removed), \
             hausdorff {:.3} of the bound (in->out {:.3}, out->in {:.3})",
            removed,
            hausdorff / bound,
            c.a_to_b.max / bound,
            c.b_to_a.max / bound
        );
        assert!(
            hausdorff <= SAMPLING * bound,
            "{what} {algorithm:?}: Hausdorff {hausdorff} over the bound {bound}"
        );
        assert!(
            removed >= share,
            "{what} {algorithm:?}: only {removed:.3} of the vertices removed"
        );
    }
}

/// The report shapes at a bound of 2 % of the diagonal: the share of vertices each
/// algorithm removes at least (Schroeder, qem), a little under what it removed.
const REPORT_SHAPES: [(&str, [f64; 2]); 8] = [
    ("test001", [0.2, 0.2]),
    ("test002", [0.6, 0.6]),
    ("test003", [0.9, 0.9]),
    ("test004", [0.9, 0.9]),
    ("test005", [0.5, 0.85]),
    ("test006", [0.9, 0.9]),
    ("test007", [0.9, 0.9]),
    ("test008", [0.9, 0.9]),
];

#[test]
fn every_report_shape_stays_within_the_bound() {
    for (model, (name, share)) in shapes::all().into_iter().zip(REPORT_SHAPES) {
        assert_eq!(model.name, name);
        check(name, &model, 0.02, share);
    }
    // A bound far under the grid's spacing still lets a flat grid go.
    check("test003", &shapes::test003(), 0.002, [0.9, 0.9]);
}

#[test]
fn noisy_grids_and_spheres_stay_within_the_bound() {
    let mut rng = Rng(0x5e_ed0f_e770);
    for case in 0..4 {
        let roughness = [0.001, 0.01][case % 2];
        let mut model = if case / 2 == 0 {
            shapes::test003()
        } else {
            shapes::uv_sphere(10 + rng.below(10) as u32, 12 + rng.below(16) as u32)
        };
        for p in &mut model.positions {
            *p += Vec3::new(rng.signed(), rng.signed(), rng.signed()) * roughness;
        }
        check(&format!("case {case}"), &model, 0.02, [0.3, 0.7]);
    }
}

#[test]
fn a_bumpy_sphere_stays_within_the_bound() {
    let model = shapes::bumpy_sphere(40, 60);
    check("bumpy sphere", &model, 0.005, [0.6, 0.9]);
}

#[test]
fn the_bunny_scan_stays_within_the_bound() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.ply");
    let mut scene = read_scene(&path).expect("assets/bunny.ply").scene;
    let model = scene.models.remove(0);
    check("bunny", &model, 0.002, [0.2, 0.45]);
    check("bunny", &model, 0.01, [0.6, 0.9]);
}

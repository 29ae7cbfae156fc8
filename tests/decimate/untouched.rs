//! A model nothing is taken from comes back exactly as it was given, by both algorithms:
//! while they work the model's own positions and triangles are freed (the decimators hold
//! their own copies) and must be given back unchanged — same vertices, same triangles, in
//! the same order, unused vertices and per-face colours included — and a decimated one is
//! written back whole from the decimators' copies.

use std::collections::HashSet;

use decimate_core::decimate::{simplify_scene, Algorithm, ErrorBound, Params, Target};
use decimate_core::mesh::{measure, shapes, Attribute, Model, Scene};
use glam::Vec3;

/// A bumpy sphere with its triangles in a scrambled order, an unused vertex at the end and
/// a colour per face: nothing a decimator's internal order could hide.
fn scrambled_sphere() -> Model {
    let mut m = shapes::bumpy_sphere(12, 16);
    let n = m.triangles.len();
    m.triangles = (0..n).map(|i| m.triangles[(i * 7) % n]).collect();
    m.positions.push(Vec3::new(5.0, 5.0, 5.0));
    m.colors = Some(Attribute::PerFace(
        (0..n).map(|i| [i as f32 / n as f32, 0.5, 0.25]).collect(),
    ));
    m
}

fn decimated(model: &Model, params: Params) -> (Model, usize) {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let report = simplify_scene(&mut scene, &params, &mut |_| {});
    let removed = report.vertices_removed();
    (scene.models.pop().expect("the model is kept"), removed)
}

/// Asserts that each algorithm, run with `params`, removes nothing from `input` and gives it
/// back exactly.
fn assert_given_back(input: &Model, params: Params) {
    for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
        let (output, removed) = decimated(
            input,
            Params {
                algorithm,
                ..params
            },
        );
        assert_eq!(removed, 0, "{algorithm:?}");
        assert_eq!(&output, input, "{algorithm:?}: the model changed");
    }
}

#[test]
fn a_zero_target_gives_the_model_back_exactly() {
    let input = scrambled_sphere();
    assert_eq!(input.triangles.len(), 12 * 16 * 2 - 2 * 16);
    let params = Params {
        target: Target::RemovePercent(0.0),
        ..Params::default()
    };
    assert_given_back(&input, params);
}

#[test]
fn an_error_bound_nothing_meets_gives_the_model_back_exactly() {
    // Every vertex of the bumpy sphere is off its neighbours' planes: no removal has an
    // error of zero.
    let params = Params {
        target: Target::ErrorOnly,
        max_error: Some(ErrorBound::Absolute(0.0)),
        ..Params::default()
    };
    assert_given_back(&scrambled_sphere(), params);
}

#[test]
fn a_decimated_model_is_written_back_from_the_decimators_copies() {
    // Half the vertices go, by both algorithms, from the copies alone (the model's were
    // freed): the invariants hold, the volume stays within 3 %, Schroeder's kept vertices
    // are at input positions, and every triangle keeps a face colour.
    let input = scrambled_sphere();
    let bits = |p: &Vec3| p.to_array().map(f32::to_bits);
    let input_points: HashSet<[u32; 3]> = input.positions.iter().map(bits).collect();
    for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
        let params = Params {
            target: Target::RemovePercent(50.0),
            algorithm,
            ..Params::default()
        };
        let (output, removed) = decimated(&input, params);
        assert_eq!(removed, (input.positions.len() - 1) / 2, "{algorithm:?}");
        assert_eq!(output.positions.len(), input.positions.len() - 1 - removed);
        assert_eq!(
            measure::invariant_violations(&input, &output),
            Vec::<String>::new()
        );
        let (before, after) = (measure::volume(&input), measure::volume(&output));
        assert!(
            (after / before - 1.0).abs() < 0.03,
            "{algorithm:?}: {before} -> {after}"
        );
        if algorithm == Algorithm::Schroeder {
            assert!(output
                .positions
                .iter()
                .all(|p| input_points.contains(&bits(p))));
        }
        let Some(Attribute::PerFace(colors)) = &output.colors else {
            panic!("{algorithm:?}: per-face colours lost");
        };
        assert_eq!(colors.len(), output.triangles.len());
    }
}

#[test]
fn a_zero_target_keeps_the_feature_angle_asked() {
    // test001's five vertices are all on features: a count target would relax the angle
    // to reach it, but `-p 0` asks for nothing, so the report says nothing was relaxed.
    let input = shapes::test001();
    let mut scene = Scene {
        models: vec![input.clone()],
    };
    let params = Params {
        target: Target::RemovePercent(0.0),
        algorithm: Algorithm::Schroeder,
        ..Params::default()
    };
    let report = simplify_scene(&mut scene, &params, &mut |_| {});
    assert_eq!(report.models[0].feature_angle_deg, params.feature_angle_deg);
    assert_eq!(scene.models[0], input);
}

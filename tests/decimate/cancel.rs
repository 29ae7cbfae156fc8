//! Cancelling a decimation from another thread (the viewer's `Esc`): both algorithms stop at
//! the next pass or batch, say so (`None`), and leave a valid mesh short of the target; a
//! cancel made before the start leaves the scene as it was.

use decimate_core::decimate::{
    simplify_scene_cancellable, simplify_scene_progressive_cancellable, Algorithm, Cancel, Params,
    Target,
};
use decimate_core::mesh::{measure, shapes, Scene};

fn sphere() -> Scene {
    Scene {
        models: vec![shapes::bumpy_sphere(120, 240)],
    }
}

fn params(algorithm: Algorithm) -> Params {
    Params {
        target: Target::RemovePercent(90.0),
        algorithm,
        ..Params::default()
    }
}

#[test]
fn a_cancel_from_the_first_progress_report_stops_both_algorithms_early() {
    let original = sphere();
    let before = original.models[0].used_vertex_count();
    for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
        let mut scene = original.clone();
        let cancel = Cancel::new();
        // The first report with something removed asks to stop, as Esc would.
        let mut progress = |fraction: f32| {
            if fraction > 0.0 {
                cancel.request();
            }
        };
        let report =
            simplify_scene_cancellable(&mut scene, &params(algorithm), &mut progress, &cancel);
        assert!(
            report.is_none(),
            "{algorithm:?}: a cancelled run gave a report"
        );
        let after = scene.models[0].used_vertex_count();
        assert!(
            after < before && after > before / 2,
            "{algorithm:?}: {after} of {before} vertices left; 90 % was asked, cancelled early"
        );
        let broken = measure::invariant_violations(&original.models[0], &scene.models[0]);
        assert!(broken.is_empty(), "{algorithm:?}: {broken:?}");
    }
}

#[test]
fn a_cancel_before_the_start_changes_nothing() {
    let original = sphere();
    let cancel = Cancel::new();
    cancel.request();
    for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
        let mut scene = original.clone();
        let report =
            simplify_scene_cancellable(&mut scene, &params(algorithm), &mut |_| {}, &cancel);
        assert!(report.is_none());
        assert_eq!(scene, original, "{algorithm:?}");
    }
    let mut scene = original.clone();
    let progressive = simplify_scene_progressive_cancellable(
        &mut scene,
        &params(Algorithm::Qem),
        &mut |_| {},
        &cancel,
    );
    assert!(progressive.is_none());
    assert_eq!(scene, original);
}

#[test]
fn an_uncancelled_run_reaches_its_target() {
    let mut scene = sphere();
    let before = scene.models[0].used_vertex_count();
    let report = simplify_scene_cancellable(
        &mut scene,
        &params(Algorithm::Qem),
        &mut |_| {},
        &Cancel::new(),
    );
    let report = report.unwrap_or_else(|| panic!("not cancelled, yet no report"));
    let after = scene.models[0].used_vertex_count();
    assert_eq!(after, before - (0.9 * before as f64).round() as usize);
    assert_eq!(report.models[0].vertices_after, after);
}

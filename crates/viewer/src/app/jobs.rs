//! The viewer's long tasks as worker jobs (`worker::Job`): decimating a viewport from the
//! original, building the level-of-detail slider's progressive mesh, measuring the metro
//! error of the level shown, and the heat-map's error field of a viewport. Each takes what it reads by value (the original behind an
//! `Arc`), so the window keeps its scenes and draws them while the job runs.

use std::sync::Arc;

use decimate_core::decimate::{simplify_scene_cancellable, Params, Report};
use decimate_core::mesh::Scene;
use decimate_core::metro::field::{error_field_cancellable, ErrorField};

use super::counts::Counts;
use super::level_error::LevelError;
use super::lod::LodView;
use super::menu::DecimateEvent;
use super::worker::{spawn, Job};

/// What a job does for a viewport.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Task {
    Decimate(DecimateEvent),
    Lod,
    /// Measure the scene the viewport shows at this generation.
    Measure {
        generation: u64,
    },
}

/// What a job gives back.
#[derive(Debug)]
pub enum Done {
    Decimated {
        scene: Scene,
        report: Report,
        counts: Counts,
    },
    Lod(Box<LodView>),
    Measured(Result<LevelError, String>),
}

/// The job running for a viewport.
pub struct Running {
    /// The viewport's id (it may be removed while the job runs).
    pub viewport: u64,
    pub task: Task,
    /// Said before the result in the status line ("quadric edge collapse, border free; ").
    pub prefix: String,
    pub job: Job<Done>,
}

/// Decimates a copy of `original` with `params`; the counts of the result are taken on the
/// worker too.
pub fn decimate(what: String, original: Arc<Scene>, params: Params) -> Job<Done> {
    spawn(what, move |progress, cancel| {
        let mut scene = (*original).clone();
        let report = simplify_scene_cancellable(&mut scene, &params, progress, cancel)?;
        let counts = Counts::of(&scene);
        Some(Done::Decimated {
            scene,
            report,
            counts,
        })
    })
}

/// Builds the level-of-detail slider of `original`.
pub fn lod(what: String, original: Arc<Scene>, params: Params) -> Job<Done> {
    spawn(what, move |progress, cancel| {
        let lod = LodView::build(&original, &params, progress, cancel)?;
        Some(Done::Lod(Box::new(lod)))
    })
}

/// Measures `shown` against `original`; a cancelled measurement stops at its next chunk of
/// samples and gives nothing.
pub fn measure(what: String, original: Arc<Scene>, shown: Scene) -> Job<Done> {
    spawn(what, move |_, cancel| {
        let measured = LevelError::measure_cancellable(&original, &shown, cancel);
        (!cancel.requested()).then_some(Done::Measured(measured))
    })
}

/// Measures the heat-map's error field of `shown` against `original`, and the legend's
/// maximum: metro's, as `d` and `shot --measure` say it (the field's largest vertex distance
/// when metro cannot measure); cancelled like [`measure`].
pub fn field(what: String, original: Arc<Scene>, shown: Scene) -> Job<(ErrorField, f64)> {
    spawn(what, move |_, cancel| {
        let field = error_field_cancellable(&original, &shown, cancel)?;
        let measured = LevelError::measure_cancellable(&original, &shown, cancel);
        let max = measured.map_or(field.max, |e| e.max);
        (!cancel.requested()).then_some((field, max))
    })
}

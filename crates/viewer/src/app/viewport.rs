//! `Viewport`: one view of the window — the original scene it decimates from, the scene it
//! shows now with its counts, its draw toggles and camera, what its last decimation did and
//! its measured error. No GPU and no decimation here (the controller runs those on a worker
//! thread and hands the result in): the window re-uploads a viewport's scene when its
//! `generation` changes. With the level-of-detail slider on, the scene shown is the
//! slider's (`LodView`).

use std::sync::Arc;
use std::time::Instant;

use crate::render::camera::{Camera, Navigation};
use crate::render::draw::DrawOptions;
use crate::render::gpu_mesh::scene_bounds;
use crate::render::mesh_data::DEFAULT_CREASE_DEG;
use decimate_core::decimate::{Algorithm, Params, Report, Target};
use decimate_core::mesh::Scene;

use super::counts::Counts;
use super::labels;
use super::level_error::LevelError;
use super::lod::LodView;
use super::menu::{DecimateEvent, DecimateKind};

/// One viewport.
#[derive(Debug, Clone)]
pub struct Viewport {
    /// Unique among the viewports ever opened in this window (keys the GPU copy).
    pub id: u64,
    original: Arc<Scene>,
    scene: Scene,
    /// `scene`'s counts (welded vertices), computed when it changed.
    counts: Counts,
    pub options: DrawOptions,
    pub camera: Camera,
    /// Bumped whenever `scene` changes, so the renderer knows to upload it again.
    pub generation: u64,
    /// The last decimation's event (made again when the algorithm or the border setting
    /// changes) and report, while the scene shown is its result.
    pub last: Option<(DecimateEvent, Report)>,
    /// Algorithm, feature angle, error bound and border setting for decimate events.
    pub params: Params,
    /// The algorithm that made the decimation shown: `params` may name another already, the
    /// new one's job still running.
    shown_algorithm: Algorithm,
    /// The level-of-detail slider, when it is on.
    lod: Option<LodView>,
    /// The crease angle set with `[` / `]`, in degrees; `None`: each model's own.
    crease_deg: Option<f32>,
    /// The metro error of the scene shown at this generation, once measured (`d`).
    error: Option<(u64, LevelError)>,
}

impl Viewport {
    /// A viewport showing `original` (whose counts are `counts`), framed on it.
    pub fn new(id: u64, original: Arc<Scene>, counts: Counts, params: Params) -> Self {
        let camera = Camera::framing(scene_bounds(&original));
        Self {
            id,
            scene: (*original).clone(),
            original,
            counts,
            options: DrawOptions::default(),
            camera,
            generation: 0,
            last: None,
            shown_algorithm: params.algorithm,
            params,
            lod: None,
            crease_deg: None,
            error: None,
        }
    }

    /// The scene shown now.
    pub fn scene(&self) -> &Scene {
        self.lod.as_ref().map_or(&self.scene, LodView::scene)
    }

    pub fn lod(&self) -> Option<&LodView> {
        self.lod.as_ref()
    }

    /// Turns the level-of-detail slider on with `lod` (the original's progressive mesh,
    /// starting at the original).
    pub fn show_lod(&mut self, lod: LodView) {
        self.lod = Some(lod);
        // What is shown is the slider's level from now on, not the last decimation.
        self.last = None;
        self.generation += 1;
    }

    /// Turns the level-of-detail slider off: the level shown stays, as a decimated scene
    /// would. False when it was not on.
    pub fn lod_off(&mut self) -> bool {
        let Some(lod) = self.lod.take() else {
            return false;
        };
        self.scene = lod.scene().clone();
        self.counts = Counts::of(&self.scene);
        self.generation += 1;
        true
    }

    /// The slider moved to `vertices`: a geomorph towards that level starts at `now`.
    pub fn set_lod_vertices(&mut self, vertices: usize, now: Instant) {
        if let Some(lod) = &mut self.lod {
            if lod.set_vertices(vertices, now) {
                self.generation += 1;
            }
        }
    }

    /// Ends a running geomorph at once.
    pub fn settle(&mut self) {
        if let Some(lod) = &mut self.lod {
            if lod.settle() {
                self.generation += 1;
            }
        }
    }

    /// Advances a geomorph to `now`; true while one runs (the window keeps drawing).
    pub fn tick(&mut self, now: Instant) -> bool {
        let Some(lod) = &mut self.lod else {
            return false;
        };
        if lod.tick(now) {
            self.generation += 1;
        }
        lod.morphing()
    }

    pub fn original(&self) -> &Arc<Scene> {
        &self.original
    }

    /// The parameters of decimating for `event`. Decimation starts from the original (never
    /// from the already decimated scene), so "90 %" always means 90 % of the original's
    /// vertices.
    pub fn params_for(&self, event: DecimateEvent) -> Params {
        Params {
            target: target_of(event),
            ..self.params
        }
    }

    /// Shows `scene`, the original decimated for `event` (with [`Self::params_for`]), which
    /// `report` describes and whose counts are `counts`.
    pub fn show_decimated(
        &mut self,
        event: DecimateEvent,
        scene: Scene,
        report: Report,
        counts: Counts,
    ) {
        self.scene = scene;
        self.counts = counts;
        self.apply_crease();
        self.lod = None;
        self.generation += 1;
        self.last = Some((event, report));
        self.shown_algorithm = self.params.algorithm;
    }

    /// Notes `error`, measured on the scene shown at `generation`; false (nothing noted) when
    /// the scene changed since.
    pub fn set_error(&mut self, generation: u64, error: LevelError) -> bool {
        let current = generation == self.generation;
        if current {
            self.error = Some((generation, error));
        }
        current
    }

    /// The metro error of the scene shown, when it was measured.
    pub fn error(&self) -> Option<&LevelError> {
        self.error
            .as_ref()
            .filter(|(g, _)| *g == self.generation)
            .map(|(_, e)| e)
    }

    /// Changes the crease angle by `delta` degrees (from the first model's own, else
    /// `DEFAULT_CREASE_DEG`), kept within 0 to 180; returns it. Not while the
    /// level-of-detail slider is on (`None`): its levels keep the original's.
    pub fn change_crease(&mut self, delta: f32) -> Option<f32> {
        if self.lod.is_some() {
            return None;
        }
        let own = (self.scene.models.first())
            .and_then(|m| m.crease_angle)
            .map_or(DEFAULT_CREASE_DEG, f32::to_degrees);
        let degrees = (self.crease_deg.unwrap_or(own).round() + delta).clamp(0.0, 180.0);
        self.crease_deg = Some(degrees);
        self.apply_crease();
        // Shading only: the error measured stays that of the scene shown.
        let error = self.error().copied();
        self.generation += 1;
        self.error = error.map(|e| (self.generation, e));
        Some(degrees)
    }

    /// Gives every model of the scene shown the crease angle set with `[` / `]`, if any.
    fn apply_crease(&mut self) {
        if let Some(degrees) = self.crease_deg {
            for m in &mut self.scene.models {
                m.crease_angle = Some(degrees.to_radians());
            }
        }
    }

    /// The last decimate event, while the scene shown is its result (the level-of-detail
    /// slider forgets it).
    pub fn last_event(&self) -> Option<DecimateEvent> {
        self.last.as_ref().map(|(event, _)| *event)
    }

    /// The algorithm and border setting decimate events use, in words.
    pub fn settings(&self) -> String {
        let algorithm = match self.params.algorithm {
            Algorithm::Schroeder => "vertex removal",
            Algorithm::Qem => "quadric edge collapse",
        };
        let border = if self.params.keep_border {
            "border kept"
        } else {
            "border free"
        };
        format!("{algorithm}, {border}")
    }

    /// Vertices shown now: points used by some triangle, a texture seam's copies counted
    /// once (`Counts`); the level-of-detail slider's levels count their vertices.
    pub fn vertex_count(&self) -> usize {
        match &self.lod {
            Some(lod) => lod.vertex_count(),
            None => self.counts.vertices,
        }
    }

    pub fn triangle_count(&self) -> usize {
        match &self.lod {
            Some(lod) => lod.scene().triangle_count(),
            None => self.counts.triangles,
        }
    }

    /// The caption over the viewport: what it shows ("original", its target and algorithm,
    /// or the level-of-detail slider) and its counts.
    pub fn caption(&self) -> String {
        let what = if self.lod.is_some() {
            "level of detail (qem)".to_string()
        } else if let Some((event, _)) = &self.last {
            format!(
                "{} ({})",
                labels::target_words(target_of(*event), self.params.max_error),
                labels::algorithm_name(self.shown_algorithm)
            )
        } else {
            "original".to_string()
        };
        let mut caption = labels::caption(&what, self.vertex_count(), self.triangle_count());
        if let Some(error) = self.error() {
            caption.push('\n');
            caption.push_str(&error.words());
        }
        caption
    }

    /// The status line: counts, last decimation time, "fully decimated".
    pub fn status(&self) -> String {
        let mut s = labels::counts(self.vertex_count(), self.triangle_count());
        if let Some(lod) = &self.lod {
            s.push_str(&format!(
                ", level of detail (qem, built in {:.3} s)",
                lod.build_seconds
            ));
        } else if let Some((_, r)) = &self.last {
            let by = match self.shown_algorithm {
                Algorithm::Schroeder => "schroeder",
                Algorithm::Qem => "qem",
            };
            s.push_str(&format!(", decimated by {by} in {:.3} s", r.seconds));
            if r.fully_decimated() {
                s.push_str(" — fully decimated");
            }
        }
        s.push_str(match self.camera.navigation {
            Navigation::Model => " [model control]",
            Navigation::Eye => " [eye control]",
        });
        s
    }
}

/// The decimation target of a decimate event.
fn target_of(event: DecimateEvent) -> Target {
    match event.kind {
        DecimateKind::Percentage => Target::RemovePercent(event.amount.clamp(0.0, 100.0)),
        // The request is capped at what can be removed by the decimator itself.
        DecimateKind::Number => Target::RemoveVertices(event.amount.max(0.0) as usize),
    }
}

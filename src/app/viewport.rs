//! `Viewport`: one view of the window — the original scene it decimates from, the scene it
//! shows now, its draw toggles and camera, and what its last decimation did. No GPU here: the
//! window re-uploads a viewport's scene when its `generation` changes. With the
//! level-of-detail slider on, the scene shown is the slider's (`LodView`).

use std::sync::Arc;
use std::time::Instant;

use crate::decimate::{simplify_scene, Algorithm, Params, Report, Target};
use crate::mesh::Scene;
use crate::render::camera::{Camera, Navigation};
use crate::render::draw::DrawOptions;
use crate::render::gpu_mesh::scene_bounds;
use crate::render::mesh_data::DEFAULT_CREASE_DEG;

use super::labels;
use super::lod::LodView;
use super::menu::{DecimateEvent, DecimateKind};

/// One viewport.
#[derive(Debug, Clone)]
pub struct Viewport {
    /// Unique among the viewports ever opened in this window (keys the GPU copy).
    pub id: u64,
    original: Arc<Scene>,
    scene: Scene,
    pub options: DrawOptions,
    pub camera: Camera,
    /// Bumped whenever `scene` changes, so the renderer knows to upload it again.
    pub generation: u64,
    /// The last decimation's event (made again when the algorithm or the border setting
    /// changes) and report, while the scene shown is its result.
    pub last: Option<(DecimateEvent, Report)>,
    /// Algorithm, feature angle, error bound and border setting for decimate events.
    pub params: Params,
    /// The level-of-detail slider, when it is on.
    lod: Option<LodView>,
    /// The crease angle set with `[` / `]`, in degrees; `None`: each model's own.
    crease_deg: Option<f32>,
}

impl Viewport {
    /// A viewport showing `original`, framed on it.
    pub fn new(id: u64, original: Arc<Scene>, params: Params) -> Self {
        let camera = Camera::framing(scene_bounds(&original));
        Self {
            id,
            scene: (*original).clone(),
            original,
            options: DrawOptions::default(),
            camera,
            generation: 0,
            last: None,
            params,
            lod: None,
            crease_deg: None,
        }
    }

    /// The scene shown now.
    pub fn scene(&self) -> &Scene {
        self.lod.as_ref().map_or(&self.scene, LodView::scene)
    }

    pub fn lod(&self) -> Option<&LodView> {
        self.lod.as_ref()
    }

    /// Turns the level-of-detail slider on (building the original's progressive mesh; it
    /// starts at the original) or off (the level shown stays, as a decimated scene would).
    pub fn toggle_lod(&mut self) {
        match self.lod.take() {
            Some(lod) => self.scene = lod.scene().clone(),
            None => {
                self.lod = Some(LodView::new(&self.original, &self.params));
                // What is shown is the slider's level from now on, not the last decimation.
                self.last = None;
            }
        }
        self.generation += 1;
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

    /// Decimates from the original (never from the already decimated scene), so "90 %" always
    /// means 90 % of the original's vertices.
    pub fn decimate(&mut self, event: DecimateEvent) -> &Report {
        let params = Params {
            target: target_of(event),
            ..self.params
        };
        let mut scene = (*self.original).clone();
        let report = simplify_scene(&mut scene, &params, &mut |_| {});
        self.scene = scene;
        self.apply_crease();
        self.lod = None;
        self.generation += 1;
        &self.last.insert((event, report)).1
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
        self.generation += 1;
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

    /// Vertices shown now (used by some triangle).
    pub fn vertex_count(&self) -> usize {
        if let Some(lod) = &self.lod {
            return lod.vertex_count();
        }
        self.scene
            .models
            .iter()
            .map(crate::mesh::Model::used_vertex_count)
            .sum()
    }

    pub fn triangle_count(&self) -> usize {
        self.scene().triangle_count()
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
                labels::algorithm_name(self.params.algorithm)
            )
        } else {
            "original".to_string()
        };
        labels::caption(&what, self.vertex_count(), self.triangle_count())
    }

    /// The status line: counts, last decimation time, "fully decimated".
    pub fn status(&self) -> String {
        let mut s = format!(
            "{} vertices, {} triangles",
            self.vertex_count(),
            self.triangle_count()
        );
        if let Some(lod) = &self.lod {
            s.push_str(&format!(
                ", level of detail (qem, built in {:.3} s)",
                lod.build_seconds
            ));
        } else if let Some((_, r)) = &self.last {
            let by = match self.params.algorithm {
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

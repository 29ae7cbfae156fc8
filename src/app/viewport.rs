//! `Viewport`: one view of the window — the original scene it decimates from, the scene it
//! shows now, its draw toggles and camera, and what its last decimation did. No GPU here: the
//! window re-uploads a viewport's scene when its `generation` changes.

use std::sync::Arc;

use crate::decimate::{decimate_scene, Params, Report, Target};
use crate::mesh::Scene;
use crate::render::camera::{Camera, Navigation};
use crate::render::draw::DrawOptions;
use crate::render::gpu_mesh::scene_bounds;

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
    /// The last decimation's report.
    pub last: Option<Report>,
    /// Feature angle and error bound for decimate events.
    pub params: Params,
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
        }
    }

    /// The scene shown now.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn original(&self) -> &Arc<Scene> {
        &self.original
    }

    /// Decimates from the original (never from the already decimated scene), so "90 %" always
    /// means 90 % of the original's vertices.
    pub fn decimate(&mut self, event: DecimateEvent) -> &Report {
        let target = match event.kind {
            DecimateKind::Percentage => Target::RemovePercent(event.amount.clamp(0.0, 100.0)),
            // The request is capped at what can be removed by the decimator itself.
            DecimateKind::Number => Target::RemoveVertices(event.amount.max(0.0) as usize),
        };
        let params = Params {
            target,
            ..self.params
        };
        let mut scene = (*self.original).clone();
        let report = decimate_scene(&mut scene, &params, &mut |_| {});
        self.scene = scene;
        self.generation += 1;
        self.last.insert(report)
    }

    /// Vertices shown now (used by some triangle).
    pub fn vertex_count(&self) -> usize {
        self.scene
            .models
            .iter()
            .map(crate::mesh::Model::used_vertex_count)
            .sum()
    }

    pub fn triangle_count(&self) -> usize {
        self.scene.triangle_count()
    }

    /// The status line: counts, last decimation time, "fully decimated".
    pub fn status(&self) -> String {
        let mut s = format!(
            "{} vertices, {} triangles",
            self.vertex_count(),
            self.triangle_count()
        );
        if let Some(r) = &self.last {
            s.push_str(&format!(", decimated in {:.3} s", r.seconds));
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

//! `LodView`: a viewport's level-of-detail slider over a progressive mesh of its original
//! (quadric edge collapse all the way down, recorded as vertex splits), with geomorphs:
//! moving the slider glides the vertices between the two levels instead of popping.
//!
//! A morph is always drawn on the finer of the two levels' topology. Refining: the new
//! vertices start where the vertex they split from was and glide out. Coarsening: the fine
//! mesh's vertices glide onto their coarse ancestors, and only then does the topology drop
//! to the coarse level (the collapsed triangles have shrunk to nothing by then). No GPU here:
//! the window uploads [`LodView::scene`] with [`LodView::morph_from`] and draws it with
//! [`LodView::morph_factor`].

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec3;

use decimate_core::decimate::{
    simplify_scene_progressive, simplify_scene_progressive_cancellable, Algorithm, Cancel, Params,
    Report, Target,
};
use decimate_core::mesh::progressive::{Lod, ProgressiveModel, ProgressiveScene};
use decimate_core::mesh::Scene;

/// How long a geomorph takes.
pub const GEOMORPH: Duration = Duration::from_millis(300);

/// A geomorph in progress.
#[derive(Debug, Clone)]
struct Morph {
    started: Instant,
    /// Where each model's vertices start (indexed like the shown scene's positions).
    from: Vec<Vec<Vec3>>,
    /// For a coarsening morph: the levels to drop to once it ends.
    settle: Option<Vec<usize>>,
}

/// The slider's state for one viewport.
#[derive(Debug, Clone)]
pub struct LodView {
    lods: Vec<Lod<Arc<ProgressiveModel>>>,
    /// The scene shown: the lods' meshes, or during a coarsening morph the fine mesh at its
    /// coarse positions.
    shown: Scene,
    base_vertices: usize,
    full_vertices: usize,
    /// The vertex count the slider asks for.
    target: usize,
    morph: Option<Morph>,
    /// Seconds the progressive mesh took to build.
    pub build_seconds: f64,
}

/// The slider's progressive mesh goes as far down as quadric edge collapse goes.
fn all_the_way(params: &Params) -> Params {
    Params {
        target: Target::RemovePercent(100.0),
        algorithm: Algorithm::Qem,
        max_error: None,
        ..*params
    }
}

impl LodView {
    /// Builds the progressive mesh of `original` (every model as far down as quadric edge
    /// collapse goes) and starts at the full level, so the view does not change.
    pub fn new(original: &Scene, params: &Params) -> Self {
        let mut coarse = original.clone();
        let (report, pm) =
            simplify_scene_progressive(&mut coarse, &all_the_way(params), &mut |_| {});
        Self::from_progressive(report, pm)
    }

    /// As [`Self::new`], reporting the fraction done to `progress` and stopping (`None`) when
    /// `cancel` is requested: the viewer builds it on a worker thread.
    pub fn build(
        original: &Scene,
        params: &Params,
        progress: &mut dyn FnMut(f32),
        cancel: &Cancel,
    ) -> Option<Self> {
        let mut coarse = original.clone();
        let (report, pm) = simplify_scene_progressive_cancellable(
            &mut coarse,
            &all_the_way(params),
            progress,
            cancel,
        )?;
        Some(Self::from_progressive(report, pm))
    }

    fn from_progressive(report: Report, pm: ProgressiveScene) -> Self {
        let mut lods: Vec<_> = pm
            .models
            .into_iter()
            .map(|m| Lod::new(Arc::new(m)))
            .collect();
        for lod in &mut lods {
            lod.set_level(lod.max_level());
        }
        let base_vertices = lods
            .iter()
            .map(|l| l.progressive().base.positions.len())
            .sum();
        let full_vertices = lods
            .iter()
            .map(|l| l.progressive().full_vertex_count())
            .sum();
        let shown = Scene {
            models: lods.iter().map(|l| l.model().clone()).collect(),
        };
        Self {
            lods,
            shown,
            base_vertices,
            full_vertices,
            target: full_vertices,
            morph: None,
            build_seconds: report.seconds,
        }
    }

    /// The scene to draw now.
    pub fn scene(&self) -> &Scene {
        &self.shown
    }

    /// The slider's range: the base mesh's and the original's vertex counts.
    pub fn range(&self) -> (usize, usize) {
        (self.base_vertices, self.full_vertices)
    }

    /// The vertex count the slider asks for.
    pub fn target(&self) -> usize {
        self.target
    }

    /// Vertices at the current levels (the morph's target once it ends).
    pub fn vertex_count(&self) -> usize {
        match &self.morph {
            Some(Morph {
                settle: Some(levels),
                ..
            }) => self
                .lods
                .iter()
                .zip(levels)
                .map(|(l, &k)| l.progressive().base.positions.len() + k)
                .sum(),
            _ => self.lods.iter().map(|l| l.model().positions.len()).sum(),
        }
    }

    /// Geomorph start positions of the shown scene while a morph runs.
    pub fn morph_from(&self) -> Option<&[Vec<Vec3>]> {
        self.morph.as_ref().map(|m| m.from.as_slice())
    }

    /// How far the morph has got at `now`, 0 to 1 (1 when none runs).
    pub fn morph_factor(&self, now: Instant) -> f32 {
        self.morph.as_ref().map_or(1.0, |m| {
            (now.saturating_duration_since(m.started).as_secs_f32() / GEOMORPH.as_secs_f32())
                .min(1.0)
        })
    }

    pub fn morphing(&self) -> bool {
        self.morph.is_some()
    }

    /// Ends a finished morph at `now`; true when the shown scene changed (see
    /// [`Self::settle`]).
    pub fn tick(&mut self, now: Instant) -> bool {
        if self.morph.is_some() && self.morph_factor(now) >= 1.0 {
            return self.settle();
        }
        false
    }

    /// Ends any morph at once, the lods at their target levels (what F3 saves must not be
    /// the collapsed-flat triangles of a coarsening morph). True when the shown scene
    /// changed: a coarsening morph drops to its coarse topology. A refining morph ends on
    /// the mesh already shown — drawn with factor 1 its start positions are unused — so the
    /// window need not upload it again.
    pub fn settle(&mut self) -> bool {
        let Some(Morph {
            settle: Some(levels),
            ..
        }) = self.morph.take()
        else {
            return false;
        };
        for (lod, level) in self.lods.iter_mut().zip(levels) {
            lod.set_level(level);
        }
        self.shown = Scene {
            models: self.lods.iter().map(|l| l.model().clone()).collect(),
        };
        true
    }

    /// The slider moved to `vertices` at `now`: start a geomorph to the nearest levels (each
    /// model the same fraction of its way from base to original). Returns true when the
    /// shown scene changed.
    pub fn set_vertices(&mut self, vertices: usize, now: Instant) -> bool {
        let vertices = vertices.clamp(self.base_vertices, self.full_vertices);
        self.target = vertices;
        if self.morph.is_some() {
            self.settle();
        }
        let span = (self.full_vertices - self.base_vertices).max(1) as f64;
        let fraction = (vertices - self.base_vertices) as f64 / span;
        let levels: Vec<usize> = self
            .lods
            .iter()
            .map(|l| {
                let level = (fraction * l.max_level() as f64).round() as usize;
                l.progressive().whole_level(level)
            })
            .collect();
        if self.lods.iter().zip(&levels).all(|(l, &k)| l.level() == k) {
            return false;
        }
        let coarsening = self.lods.iter().zip(&levels).any(|(l, &k)| k < l.level());
        let mut from = Vec::with_capacity(self.lods.len());
        let mut models = Vec::with_capacity(self.lods.len());
        for (lod, &level) in self.lods.iter_mut().zip(&levels) {
            if level >= lod.level() {
                // Refine now; new vertices glide out of the vertex they split from.
                let coarse = lod.level();
                lod.set_level(level);
                from.push(lod.positions_at(coarse));
                models.push(lod.model().clone());
            } else {
                // Stay fine while the vertices glide onto their coarse ancestors.
                let mut model = lod.model().clone();
                from.push(model.positions.clone());
                model.positions = lod.positions_at(level);
                models.push(model);
            }
        }
        self.shown = Scene { models };
        self.morph = Some(Morph {
            started: now,
            from,
            settle: coarsening.then_some(levels),
        });
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use decimate_core::mesh::{measure, shapes};

    fn view() -> LodView {
        let scene = Scene {
            models: vec![shapes::bumpy_sphere(16, 24), shapes::cube(4, 1.0)],
        };
        LodView::new(&scene, &Params::default())
    }

    #[test]
    fn starts_at_the_original_and_reaches_exact_counts() {
        let mut v = view();
        let (lo, hi) = v.range();
        let original =
            shapes::bumpy_sphere(16, 24).positions.len() + shapes::cube(4, 1.0).positions.len();
        assert_eq!(hi, original);
        assert_eq!(v.vertex_count(), original);
        assert!(lo * 10 < hi, "base has {lo} of {hi} vertices");
        let t0 = Instant::now();
        assert!(v.set_vertices(lo, t0));
        // Coarsening: the fine topology is shown until the morph ends.
        assert_eq!(
            v.scene().models[0].positions.len(),
            shapes::bumpy_sphere(16, 24).positions.len()
        );
        assert!(v.tick(t0 + GEOMORPH));
        assert_eq!(v.vertex_count(), lo);
        let shown: usize = v.scene().models.iter().map(|m| m.positions.len()).sum();
        assert_eq!(shown, lo);
        for m in &v.scene().models {
            assert_eq!(measure::degenerate_triangles(m, 1e-9), 0);
            assert_eq!(measure::euler_characteristic(m), 2);
        }
    }

    #[test]
    fn a_refining_morph_starts_on_the_coarse_surface_and_ends_on_the_fine_one() {
        let mut v = view();
        let (lo, hi) = v.range();
        let t0 = Instant::now();
        v.set_vertices(lo, t0);
        v.tick(t0 + GEOMORPH);
        let coarse = v.scene().clone();
        let t1 = t0 + 2 * GEOMORPH;
        assert!(v.set_vertices((lo + hi) / 2, t1));
        assert_eq!(v.morph_factor(t1), 0.0);
        let from = v.morph_from().map(<[_]>::to_vec).unwrap_or_default();
        assert_eq!(from.len(), 2);
        for (i, m) in v.scene().models.iter().enumerate() {
            assert_eq!(from[i].len(), m.positions.len());
            // Every start position is a vertex of the coarse mesh.
            for p in &from[i] {
                assert!(coarse.models[i].positions.contains(p));
            }
        }
        assert!(v.morph_factor(t1 + GEOMORPH / 2) > 0.4);
        let fine = v.scene().clone();
        assert!(
            !v.tick(t1 + GEOMORPH),
            "the mesh shown is already the fine one"
        );
        assert_eq!(v.scene(), &fine);
        assert!(!v.morphing());
        assert_eq!(v.morph_factor(t1 + GEOMORPH), 1.0);
        let n = v.vertex_count();
        assert!(n.abs_diff((lo + hi) / 2) <= 2, "{n} vertices");
    }

    #[test]
    fn a_new_position_mid_morph_settles_the_old_one_first() {
        let mut v = view();
        let (lo, hi) = v.range();
        let t0 = Instant::now();
        v.set_vertices(lo, t0);
        v.set_vertices(hi, t0);
        v.tick(t0 + GEOMORPH);
        assert_eq!(v.vertex_count(), hi);
        assert_eq!(
            v.scene().models[1].positions.len(),
            shapes::cube(4, 1.0).positions.len()
        );
    }
}

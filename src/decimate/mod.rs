//! Decimation algorithms, one module per algorithm (`schroeder` vertex removal, `qem` quadric
//! edge collapse), over `mesh` arrays, behind one entry point: [`simplify_scene`] applies a
//! [`Params`] (target, error bound, feature angle) to every model of a scene and returns a
//! [`Report`].

mod candidates;
pub mod closed;
pub mod layout;
pub mod levels;
mod limits;
mod lists;
pub mod qem;
mod regions;
pub mod schroeder;
pub mod summary;

use std::time::Instant;

use crate::mesh::{seams, stitches, Scene};

pub use limits::{Limits, Outcome};

use crate::mesh::progressive::{ProgressiveModel, ProgressiveScene};

/// How far to decimate. Counts are over the whole scene and shared among its models in
/// proportion to their vertex counts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// Remove this percentage (0–100) of the vertices; 100 means "as far as possible".
    RemovePercent(f64),
    /// Remove this many vertices (the original's `-v`).
    RemoveVertices(usize),
    /// Stop when this many vertices are left.
    KeepVertices(usize),
    /// Stop when this many triangles are left.
    KeepTriangles(usize),
    /// No count: remove while the error bound allows (needs `Params::max_error`).
    ErrorOnly,
}

/// An error bound: stop before a removal whose error would exceed it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ErrorBound {
    /// In model units.
    Absolute(f64),
    /// As a fraction of the model's bounding-box diagonal (`E%` on the command line / 100).
    DiagonalFraction(f64),
}

/// Which decimation algorithm runs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Algorithm {
    /// Schroeder vertex removal: vertices never move (`schroeder`).
    #[default]
    Schroeder,
    /// Garland–Heckbert quadric edge collapse: vertices move to the quadric optimum (`qem`).
    Qem,
}

/// Everything a decimation run needs besides the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    pub target: Target,
    pub max_error: Option<ErrorBound>,
    /// Dihedral angle in degrees above which an edge is a feature edge.
    pub feature_angle_deg: f64,
    /// Never relax the feature angle to reach a count target (see [`simplify_scene`]).
    pub keep_features: bool,
    /// Never move or remove a vertex on a model's open border
    /// (`mesh::stitches::open_border_vertices`): pieces of one mesh decimated apart still fit.
    pub keep_border: bool,
    pub algorithm: Algorithm,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            target: Target::RemovePercent(50.0),
            max_error: None,
            feature_angle_deg: 30.0,
            keep_features: false,
            keep_border: false,
            algorithm: Algorithm::default(),
        }
    }
}

/// What happened to one model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelReport {
    pub name: String,
    pub vertices_before: usize,
    pub triangles_before: usize,
    pub vertices_after: usize,
    pub triangles_after: usize,
    /// Largest error of any removal made, in model units.
    pub max_error: f64,
    /// Feature angle in force at the end: larger than asked when it was relaxed to reach a
    /// count target.
    pub feature_angle_deg: f64,
    /// True when no further vertex of this model can be removed.
    pub fully_decimated: bool,
    /// True when the model fell under four vertices and was dropped from the scene.
    pub dropped: bool,
    /// Vertices kept because they lie on a texture seam, on a border shared with another
    /// model, or (`keep_border`) on the open border.
    pub pinned: usize,
    /// Of a fully decimated model, the vertices left on non-manifold edges: what the input
    /// holds back (counted only when nothing more could go).
    pub non_manifold_kept: usize,
    /// Of a fully decimated model, the vertices kept only so that a closed part does not
    /// turn inside out or flat (`decimate::closed`; vertex removal counts them).
    pub closed_kept: usize,
}

/// What a decimation run did, model by model.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    pub models: Vec<ModelReport>,
    pub seconds: f64,
    /// The feature angle asked for (a model's own may have been relaxed beyond it).
    pub feature_angle_deg: f64,
}

impl Report {
    pub fn vertices_removed(&self) -> usize {
        self.models
            .iter()
            .map(|m| m.vertices_before - m.vertices_after)
            .sum()
    }

    /// True when every model that remains is fully decimated.
    pub fn fully_decimated(&self) -> bool {
        self.models.iter().all(|m| m.fully_decimated || m.dropped)
    }
}

/// Decimates every model of `scene` in place with `params.algorithm` (Schroeder vertex removal
/// by default, or quadric edge collapse). Models left with
/// fewer than four vertices are dropped. `progress` is called with the fraction done (0..=1).
///
/// Count targets (`-p` below 100, `-v`, `--keep-vertices`, `--keep-triangles`) are met even
/// on scans that, once coarse, have sharp dihedral angles everywhere: when no candidate is
/// left first, the feature angle is relaxed step by step. "As far as possible" (`-p 100`),
/// an error bound alone, or `keep_features` never relax it, so features such as a cube's
/// corners survive them. Quadric edge collapse never needs to relax it.
pub fn simplify_scene(scene: &mut Scene, params: &Params, progress: &mut dyn FnMut(f32)) -> Report {
    run(scene, params, progress, None)
}

/// As [`simplify_scene`] with quadric edge collapse (whatever `params.algorithm` says: vertex
/// removal has no vertex splits to record), and records every collapse: model `i` of the
/// returned progressive scene has the decimated model `i` as its base and refines back to
/// the input's model `i`. Models the four-vertex rule drops are dropped from both.
pub fn simplify_scene_progressive(
    scene: &mut Scene,
    params: &Params,
    progress: &mut dyn FnMut(f32),
) -> (Report, ProgressiveScene) {
    let params = Params {
        algorithm: Algorithm::Qem,
        ..*params
    };
    let mut models = Vec::new();
    let report = run(scene, &params, progress, Some(&mut models));
    (report, ProgressiveScene { models })
}

fn run(
    scene: &mut Scene,
    params: &Params,
    progress: &mut dyn FnMut(f32),
    mut record: Option<&mut Vec<ProgressiveModel>>,
) -> Report {
    let start = Instant::now();
    let vertices: Vec<usize> = scene.models.iter().map(|m| m.used_vertex_count()).collect();
    let triangles: Vec<usize> = scene.models.iter().map(|m| m.triangles.len()).collect();
    let Shares {
        removals,
        keep_triangles,
    } = Shares::of(params.target, &vertices, &triangles);
    let relax_features = !params.keep_features
        && match params.target {
            Target::RemovePercent(p) => p < 100.0,
            Target::RemoveVertices(_) | Target::KeepVertices(_) | Target::KeepTriangles(_) => true,
            Target::ErrorOnly => false,
        };
    let planned: usize = removals
        .iter()
        .zip(&vertices)
        .map(|(&r, &n)| r.min(n))
        .sum::<usize>()
        .max(1);

    // Pinned: texture seams and borders shared with another model (cracks otherwise), and
    // with `keep_border` every open border.
    let shared = stitches::shared_border_vertices(scene);
    let mut reports = Vec::with_capacity(scene.models.len());
    let mut done = 0usize;
    for (i, model) in scene.models.iter_mut().enumerate() {
        // Both algorithms take a seam's two sides away together (`twins`); junctions of
        // three or more sides, shared borders and (`keep_border`) open borders are pinned.
        let border = if params.keep_border {
            stitches::open_border_vertices(model)
        } else {
            Vec::new()
        };
        let (shared, border) = (&shared[i], &border);
        let on_pinned_border = |v: u32| {
            let flag = |flags: &[bool]| flags.get(v as usize).copied().unwrap_or(false);
            flag(shared) || flag(border)
        };
        let seams = seams::find(model);
        let mut twins = seams.twin;
        for v in 0..twins.len() as u32 {
            let w = twins[v as usize];
            if w != u32::MAX && (on_pinned_border(v) || on_pinned_border(w)) {
                twins[v as usize] = u32::MAX;
            }
        }
        let pins: Vec<bool> = (0..seams.on_seam.len() as u32)
            .map(|v| {
                let paired = twins.get(v as usize).is_some_and(|&w| w != u32::MAX);
                on_pinned_border(v) || (seams.on_seam[v as usize] && !paired)
            })
            .collect();
        let max_error = match params.max_error {
            None => f64::INFINITY,
            Some(ErrorBound::Absolute(e)) => e,
            Some(ErrorBound::DiagonalFraction(f)) => {
                f * model
                    .bounds()
                    .map_or(0.0, |(lo, hi)| (hi - lo).length() as f64)
            }
        };
        let limits = Limits {
            remove: removals[i],
            keep_triangles: keep_triangles[i],
            max_error,
            feature_angle_deg: params.feature_angle_deg,
            relax_features,
        };
        let mut report_progress = |removed: usize| {
            progress(((done + removed) as f32 / planned as f32).min(1.0));
        };
        let outcome = match (params.algorithm, record.as_deref_mut()) {
            (_, Some(models)) => {
                let (outcome, pm) = qem::decimate_model_progressive(
                    model,
                    &limits,
                    &pins,
                    &twins,
                    &mut report_progress,
                );
                models.push(pm);
                outcome
            }
            (Algorithm::Schroeder, None) => {
                schroeder::decimate_model(model, &limits, &pins, &twins, &mut report_progress)
            }
            (Algorithm::Qem, None) => {
                qem::decimate_model(model, &limits, &pins, &twins, &mut report_progress)
            }
        };
        done += outcome.removed;
        let vertices_after = model.positions.len().min(vertices[i] - outcome.removed);
        reports.push(ModelReport {
            name: model.name.clone(),
            vertices_before: vertices[i],
            triangles_before: triangles[i],
            vertices_after,
            triangles_after: model.triangles.len(),
            max_error: outcome.max_error,
            feature_angle_deg: outcome.feature_angle_deg,
            fully_decimated: outcome.exhausted,
            // As the original: only a removal can drop a model, never the input itself.
            dropped: outcome.removed > 0 && vertices_after < 4,
            pinned: outcome.pinned,
            non_manifold_kept: if outcome.exhausted {
                crate::mesh::measure::non_manifold_vertices(model)
            } else {
                0
            },
            closed_kept: outcome.closed_kept,
        });
    }
    // The original program's rule: a model left with fewer than four vertices is dropped.
    let mut keep = reports.iter().map(|r| !r.dropped);
    scene.models.retain(|_| keep.next().unwrap_or(true));
    if let Some(models) = record {
        let mut keep = reports.iter().map(|r| !r.dropped);
        models.retain(|_| keep.next().unwrap_or(true));
    }
    for r in reports.iter_mut().filter(|r| r.dropped) {
        r.vertices_after = 0;
        r.triangles_after = 0;
    }
    Report {
        models: reports,
        seconds: start.elapsed().as_secs_f64(),
        feature_angle_deg: params.feature_angle_deg,
    }
}

/// A scene's count target shared among its models in proportion to their sizes.
pub(crate) struct Shares {
    /// Vertices each model is to lose (`usize::MAX`: no vertex count applies).
    pub removals: Vec<usize>,
    /// Triangles each model is to keep (0: no triangle count applies).
    pub keep_triangles: Vec<usize>,
}

impl Shares {
    /// `target` over models with these used `vertices` and `triangles`.
    pub(crate) fn of(target: Target, vertices: &[usize], triangles: &[usize]) -> Self {
        let removals = match target {
            Target::RemovePercent(p) => vertices
                .iter()
                .map(|&n| ((p / 100.0) * n as f64).round() as usize)
                .collect(),
            Target::RemoveVertices(k) => share(k, vertices),
            Target::KeepVertices(k) => {
                share(vertices.iter().sum::<usize>().saturating_sub(k), vertices)
            }
            Target::KeepTriangles(_) | Target::ErrorOnly => vec![usize::MAX; vertices.len()],
        };
        let keep_triangles = match target {
            Target::KeepTriangles(k) => share(k.min(triangles.iter().sum()), triangles),
            _ => vec![0; triangles.len()],
        };
        Self {
            removals,
            keep_triangles,
        }
    }
}

/// Splits `total` into parts proportional to `weights` that add up to exactly `total`
/// (cumulative rounding).
fn share(total: usize, weights: &[usize]) -> Vec<usize> {
    let sum: usize = weights.iter().sum();
    if sum == 0 {
        return vec![0; weights.len()];
    }
    let mut acc = 0usize;
    let mut given = 0usize;
    weights
        .iter()
        .map(|&w| {
            acc += w;
            let upto = ((total as u128 * acc as u128 + sum as u128 / 2) / sum as u128) as usize;
            let part = upto - given;
            given = upto;
            part
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::share;

    #[test]
    fn shares_add_up_exactly() {
        assert_eq!(share(10, &[1, 1, 1]), vec![3, 4, 3]);
        assert_eq!(share(10, &[0, 5]), vec![0, 10]);
        assert_eq!(share(7, &[]), Vec::<usize>::new());
        assert_eq!(share(5, &[0, 0]), vec![0, 0]);
    }
}

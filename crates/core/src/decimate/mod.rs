//! Decimation algorithms, one module per algorithm (`schroeder` vertex removal, `qem` quadric
//! edge collapse), over `mesh` arrays, behind one entry point: [`simplify_scene`] applies a
//! [`Params`] (target, error bound, feature angle) to every model of a scene and returns a
//! [`Report`].

mod candidates;
pub(crate) mod closed;
mod distance_bound;
pub(crate) mod hanging_sheets;
pub(crate) mod layout;
pub mod levels;
mod limits;
mod lists;
mod point_counts;
pub(crate) mod qem;
mod regions;
pub(crate) mod schroeder;
pub mod summary;

use std::time::Instant;

use crate::mesh::{face_colour_seams, seams, stitches, Model, Scene};

pub use limits::{Cancel, Cost, Limits, Outcome, MIN_VERTICES};

use crate::mesh::progressive::{ProgressiveModel, ProgressiveScene};

/// How far to decimate. Counts are over the whole scene and shared among its models in
/// proportion to their vertex counts; a mesh several nodes place counts once, and a mesh
/// copied through unchanged (`mesh::Instance::copied`) not at all.
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
    /// How far to decimate.
    pub target: Target,
    /// Never remove a vertex whose error would exceed this (`--max-error`).
    pub max_error: Option<ErrorBound>,
    /// Dihedral angle in degrees above which an edge is a feature edge.
    pub feature_angle_deg: f64,
    /// Never relax the feature angle to reach a count target (see [`simplify_scene`]).
    pub keep_features: bool,
    /// Never move or remove a vertex on a model's open border
    /// (`mesh::stitches::open_border_vertices`): pieces of one mesh decimated apart still fit.
    pub keep_border: bool,
    /// Vertex removal or quadric edge collapse.
    pub algorithm: Algorithm,
    /// qem: scale every fold angle to how finely the mesh is sampled before the feature test
    /// (docs/design.md#qem-fold-scale). Off where the mesh given is not the input at its own
    /// resolution: a tile, the decimated tiles welded for the merge.
    pub scale_folds: bool,
    /// qem: what a collapse costs and where its kept vertex goes (`--cost`).
    pub cost: Cost,
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
            scale_folds: true,
            cost: Cost::default(),
        }
    }
}

/// What happened to one model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelReport {
    /// The model's name (from the file, or `shape N`).
    pub name: String,
    /// Used positions: a texture seam's copies of one point count once (`point_counts`).
    pub vertices_before: usize,
    /// Triangles before.
    pub triangles_before: usize,
    /// Used positions after, counted as `vertices_before`.
    pub vertices_after: usize,
    /// Triangles after.
    pub triangles_after: usize,
    /// Used vertices beyond the first at each position of a textured model (its seams'
    /// copies, one per extra side), before and after: the vertices a file holds are these
    /// more than the positions.
    pub seam_copies_before: usize,
    /// The same after.
    pub seam_copies_after: usize,
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
    /// Another instance of the same mesh (`mesh::Instance`), by its index in the report:
    /// this model was not decimated itself but given that one's result, and totals count
    /// the mesh once.
    pub instance_of: Option<usize>,
    /// True when the model was left as read: its mesh is copied through unchanged
    /// (skinned, morph targets).
    pub copied: bool,
    /// Sheets hanging on non-manifold edges or vertices, smaller than the result's
    /// triangles, removed before quadric decimation (`decimate::hanging_sheets`).
    pub hanging_sheets: hanging_sheets::RemovedSheets,
}

/// What a decimation run did, model by model.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    /// One report per model, in scene order.
    pub models: Vec<ModelReport>,
    /// Seconds the run took.
    pub seconds: f64,
    /// The feature angle asked for (a model's own may have been relaxed beyond it).
    pub feature_angle_deg: f64,
}

impl Report {
    /// Vertices removed, a mesh several nodes place counted once.
    pub fn vertices_removed(&self) -> usize {
        self.models
            .iter()
            .filter(|m| m.instance_of.is_none())
            .map(|m| m.vertices_before - m.vertices_after)
            .sum()
    }

    /// True when every model that remains and could be decimated is fully decimated.
    pub fn fully_decimated(&self) -> bool {
        self.models
            .iter()
            .filter(|m| !m.copied && m.instance_of.is_none())
            .all(|m| m.fully_decimated || m.dropped)
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
    run(scene, params, progress, &Cancel::default(), None)
}

/// As [`simplify_scene`], stopping early when `cancel` is requested (from another thread):
/// then `None`, and `scene` is valid but only partly decimated.
pub fn simplify_scene_cancellable(
    scene: &mut Scene,
    params: &Params,
    progress: &mut dyn FnMut(f32),
    cancel: &Cancel,
) -> Option<Report> {
    let report = run(scene, params, progress, cancel, None);
    (!cancel.requested()).then_some(report)
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
    simplify_scene_progressive_cancellable(scene, params, progress, &Cancel::default())
        .unwrap_or_default()
}

/// As [`simplify_scene_progressive`], stopping early when `cancel` is requested: then
/// `None`.
pub fn simplify_scene_progressive_cancellable(
    scene: &mut Scene,
    params: &Params,
    progress: &mut dyn FnMut(f32),
    cancel: &Cancel,
) -> Option<(Report, ProgressiveScene)> {
    let params = Params {
        algorithm: Algorithm::Qem,
        ..*params
    };
    let mut models = Vec::new();
    let report = run(scene, &params, progress, cancel, Some(&mut models));
    (!cancel.requested()).then_some((report, ProgressiveScene { models }))
}

/// What a run decides for the whole scene before any model is decimated.
struct ScenePlan {
    /// Per model: used positions (a texture seam's copies once), used vertices beyond them
    /// (the copies), triangles.
    vertices: Vec<usize>,
    seam_copies: Vec<usize>,
    triangles: Vec<usize>,
    /// The earlier model whose result an instance takes, and models copied through.
    source: Vec<Option<usize>>,
    copied: Vec<bool>,
    shares: Shares,
    relax_features: bool,
    /// Removals planned over the scene (at least 1), for the progress fraction.
    planned: usize,
}

impl ScenePlan {
    fn new(scene: &Scene, params: &Params, recording: bool) -> Self {
        let seam_copies: Vec<usize> = scene.models.iter().map(point_counts::seam_copies).collect();
        let vertices: Vec<usize> = (scene.models.iter().zip(&seam_copies))
            .map(|(m, &c)| m.used_vertex_count() - c)
            .collect();
        let triangles: Vec<usize> = scene.models.iter().map(|m| m.triangles.len()).collect();
        // A mesh several nodes place is decimated once, at its first instance, and copied
        // meshes are left as read, except in a progressive record (every model has its own).
        let source = match recording {
            false => first_instances(scene),
            true => vec![None; scene.models.len()],
        };
        let copied: Vec<bool> = (scene.models.iter())
            .map(|m| !recording && m.instance.as_ref().is_some_and(|i| i.copied))
            .collect();
        let weight = |counts: &[usize]| -> Vec<usize> {
            (0..counts.len())
                .map(|i| match source[i].is_none() && !copied[i] {
                    true => counts[i],
                    false => 0,
                })
                .collect()
        };
        let shares = Shares::of(params.target, &weight(&vertices), &weight(&triangles));
        let relax_features = !params.keep_features
            && match params.target {
                Target::RemovePercent(p) => p < 100.0,
                Target::RemoveVertices(_) | Target::KeepVertices(_) | Target::KeepTriangles(_) => {
                    true
                }
                Target::ErrorOnly => false,
            };
        let planned = (shares.removals.iter().zip(weight(&vertices)))
            .map(|(&r, n)| r.min(n))
            .sum::<usize>()
            .max(1);
        Self {
            vertices,
            seam_copies,
            triangles,
            source,
            copied,
            shares,
            relax_features,
            planned,
        }
    }

    /// How many triangles model `i`'s result is expected to have, for the hanging sheets
    /// smaller than its triangles (`None`: no count; `Some(None)`: an error bound alone);
    /// `None` outside too when the run removes nothing.
    fn result_triangles(&self, i: usize, max_error: f64) -> Option<Option<usize>> {
        let (vertices, triangles) = (self.vertices[i], self.triangles[i]);
        match (self.shares.keep_triangles[i], self.shares.removals[i]) {
            (0, usize::MAX) => max_error.is_finite().then_some(None),
            (0, 0) => None,
            (0, r) => {
                let kept = vertices.saturating_sub(r) as f64;
                Some(Some(
                    (triangles as f64 * kept / vertices.max(1) as f64) as usize,
                ))
            }
            (k, _) => (k < triangles).then_some(Some(k)),
        }
    }

    /// The report of model `i`, copied through unchanged.
    fn copied_report(&self, i: usize, name: &str, params: &Params) -> ModelReport {
        ModelReport {
            name: name.to_string(),
            vertices_before: self.vertices[i],
            triangles_before: self.triangles[i],
            vertices_after: self.vertices[i],
            triangles_after: self.triangles[i],
            seam_copies_before: self.seam_copies[i],
            seam_copies_after: self.seam_copies[i],
            max_error: 0.0,
            feature_angle_deg: params.feature_angle_deg,
            fully_decimated: false,
            dropped: false,
            pinned: 0,
            non_manifold_kept: 0,
            closed_kept: 0,
            instance_of: None,
            copied: true,
            hanging_sheets: hanging_sheets::RemovedSheets::default(),
        }
    }
}

/// Where a model may not change: its pinned vertices and its texture seams' twins.
struct Pins {
    pins: Vec<bool>,
    twins: Vec<u32>,
}

impl Pins {
    /// Both algorithms take a seam's two sides away together (`twins`); junctions of three
    /// or more sides, borders `shared` with another model (cracks otherwise) and
    /// (`keep_border`) open borders are pinned.
    fn of(model: &Model, shared: &[bool], keep_border: bool) -> Self {
        let border = if keep_border {
            stitches::open_border_vertices(model)
        } else {
            Vec::new()
        };
        let on_pinned_border = |v: u32| {
            let flag = |flags: &[bool]| flags.get(v as usize).copied().unwrap_or(false);
            flag(shared) || flag(&border)
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
        Self { pins, twins }
    }

    /// Seam sides and pinned vertices: what hanging-sheet pruning leaves where it is.
    fn fixed(&self, v: u32) -> bool {
        self.pins.get(v as usize).copied().unwrap_or(false)
            || self.twins.get(v as usize).is_some_and(|&w| w != u32::MAX)
    }
}

/// `params.max_error` in model units for `model`.
fn error_bound(params: &Params, model: &Model) -> f64 {
    match params.max_error {
        None => f64::INFINITY,
        Some(ErrorBound::Absolute(e)) => e,
        Some(ErrorBound::DiagonalFraction(f)) => {
            f * model
                .bounds()
                .map_or(0.0, |(lo, hi)| (hi - lo).length() as f64)
        }
    }
}

/// Decimates model `i` of the scene with the algorithm `params` names (or records it,
/// with `record`), and reports it.
#[allow(clippy::too_many_arguments)]
fn decimate_one(
    model: &mut Model,
    i: usize,
    plan: &ScenePlan,
    params: &Params,
    shared: &[bool],
    cancel: &Cancel,
    record: Option<&mut Vec<ProgressiveModel>>,
    progress: &mut dyn FnMut(usize),
) -> ModelReport {
    let Pins { pins, twins } = Pins::of(model, shared, params.keep_border);
    let max_error = error_bound(params, model);
    // qem: hanging sheets smaller than the result's triangles go first (`hanging_sheets`;
    // the result estimated from the target). Only a run that removes something removes
    // them (`-p 0` converts a file as is), never one recording a progressive mesh (it
    // must refine back to the input).
    let result_triangles = plan.result_triangles(i, max_error);
    let mut sheets = hanging_sheets::RemovedSheets::default();
    let limits = Limits {
        remove: plan.shares.removals[i],
        seam_copies: plan.seam_copies[i],
        keep_triangles: plan.shares.keep_triangles[i],
        max_error,
        feature_angle_deg: params.feature_angle_deg,
        // Nothing to remove (`-p 0`): nothing to relax the feature angle for.
        relax_features: plan.relax_features && plan.shares.removals[i] > 0,
        keep_features: params.keep_features,
        scale_folds: params.scale_folds,
        cost: params.cost,
        cancel: cancel.clone(),
    };
    let outcome = match (params.algorithm, record) {
        (_, Some(models)) => {
            let (outcome, pm) =
                qem::decimate_model_progressive(model, &limits, &pins, &twins, progress);
            models.push(pm);
            outcome
        }
        (Algorithm::Schroeder, None) => {
            schroeder::decimate_model(model, &limits, &pins, &twins, progress)
        }
        (Algorithm::Qem, None) => match result_triangles {
            Some(result_triangles) => {
                let limit = hanging_sheets::SheetLimit {
                    result_triangles,
                    max_error,
                };
                let pinned = Pins { pins, twins };
                let fixed = |v: u32| pinned.fixed(v);
                let mut prune = |model: &mut Model| {
                    sheets = hanging_sheets::remove_hanging_sheets(model, limit, &fixed);
                    (sheets.triangles > 0).then_some(sheets.vertices)
                };
                let (pins, twins) = (&pinned.pins, &pinned.twins);
                qem::decimate_model_pruning(model, &limits, pins, twins, progress, &mut prune)
            }
            None => qem::decimate_model(model, &limits, &pins, &twins, progress),
        },
    };
    model_report(model, i, plan, &outcome, sheets)
}

/// The report of model `i` decimated with `outcome`.
fn model_report(
    model: &Model,
    i: usize,
    plan: &ScenePlan,
    outcome: &Outcome,
    sheets: hanging_sheets::RemovedSheets,
) -> ModelReport {
    let seam_copies_after = point_counts::seam_copies(model);
    // Counted where the model may have seams (a seam's sides go as one position);
    // otherwise what was removed, as the algorithms count it.
    let vertices_after = if model.has_seam_attributes() {
        model.used_vertex_count() - seam_copies_after
    } else {
        (model.positions.len())
            .min(plan.vertices[i].saturating_sub(outcome.removed + sheets.vertices))
    };
    ModelReport {
        name: model.name.clone(),
        vertices_before: plan.vertices[i],
        triangles_before: plan.triangles[i],
        vertices_after,
        triangles_after: model.triangles.len(),
        seam_copies_before: plan.seam_copies[i],
        seam_copies_after,
        max_error: outcome.max_error.max(sheets.max_diagonal),
        feature_angle_deg: outcome.feature_angle_deg,
        fully_decimated: outcome.exhausted,
        // As the original: only a removal can drop a model, never the input itself.
        dropped: outcome.removed > 0 && vertices_after < MIN_VERTICES,
        pinned: outcome.pinned,
        non_manifold_kept: if outcome.exhausted {
            crate::mesh::measure::non_manifold_vertices(model)
        } else {
            0
        },
        closed_kept: outcome.closed_kept,
        instance_of: None,
        copied: false,
        hanging_sheets: sheets,
    }
}

fn run(
    scene: &mut Scene,
    params: &Params,
    progress: &mut dyn FnMut(f32),
    cancel: &Cancel,
    mut record: Option<&mut Vec<ProgressiveModel>>,
) -> Report {
    let start = Instant::now();
    // Per-face colour borders go through as seams; the progressive record keeps its
    // faces' colours as they are.
    let split: Vec<bool> = (scene.models.iter_mut())
        .map(|m| record.is_none() && face_colour_seams::split(m))
        .collect();
    let plan = ScenePlan::new(scene, params, record.is_some());
    // Pinned: texture seams and borders shared with another model (cracks otherwise), and
    // with `keep_border` every open border.
    let shared = stitches::shared_border_vertices(scene);
    let mut reports: Vec<ModelReport> = Vec::with_capacity(scene.models.len());
    let mut done = 0usize;
    for (i, shared) in shared.iter().enumerate().take(scene.models.len()) {
        let (before, rest) = scene.models.split_at_mut(i);
        let model = &mut rest[0];
        if cancel.requested() {
            break;
        }
        if let Some(j) = plan.source[i] {
            *model = Model {
                name: std::mem::take(&mut model.name),
                transform: model.transform,
                instance: model.instance.take(),
                ..before[j].clone()
            };
            let mut report = reports[j].clone();
            report.name = model.name.clone();
            report.instance_of = Some(j);
            reports.push(report);
            continue;
        }
        if plan.copied[i] {
            reports.push(plan.copied_report(i, &model.name, params));
            continue;
        }
        let mut report_progress = |removed: usize| {
            progress(((done + removed) as f32 / plan.planned as f32).min(1.0));
        };
        let record = record.as_deref_mut();
        let report = decimate_one(
            model,
            i,
            &plan,
            params,
            shared,
            cancel,
            record,
            &mut report_progress,
        );
        done += report.vertices_before - report.vertices_after.min(report.vertices_before);
        reports.push(report);
    }
    for (m, _) in scene.models.iter_mut().zip(split).filter(|(_, s)| *s) {
        face_colour_seams::merge(m);
    }
    drop_small_models(scene, &mut reports, record);
    Report {
        models: reports,
        seconds: start.elapsed().as_secs_f64(),
        feature_angle_deg: params.feature_angle_deg,
    }
}

/// The original program's rule: a model left with fewer than four vertices is dropped
/// (from the progressive record too).
fn drop_small_models(
    scene: &mut Scene,
    reports: &mut [ModelReport],
    record: Option<&mut Vec<ProgressiveModel>>,
) {
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
}

/// For each model, the earlier model that instances the same mesh primitive of the same
/// node tree (`mesh::Instance::mesh_key`) and holds the same triangles, if any.
fn first_instances(scene: &Scene) -> Vec<Option<usize>> {
    let mut first = std::collections::HashMap::new();
    let models = &scene.models;
    models
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let key = m.instance.as_ref()?.mesh_key();
            key.1?;
            match first.entry(key) {
                std::collections::hash_map::Entry::Occupied(e) => {
                    let j: usize = *e.get();
                    let same =
                        models[j].positions == m.positions && models[j].triangles == m.triangles;
                    same.then_some(j)
                }
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(i);
                    None
                }
            }
        })
        .collect()
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
    use std::sync::Arc;

    use super::*;
    use crate::mesh::{shapes, Instance, LocalTransform, Node, NodeTree};

    /// Three nodes placing one sphere, a fourth placing a cube, as a glTF file reads.
    fn instanced() -> Scene {
        let node = |mesh| Node {
            name: None,
            local: LocalTransform::Matrix(glam::DMat4::IDENTITY),
            children: Vec::new(),
            mesh: Some(mesh),
        };
        let tree = Arc::new(NodeTree {
            nodes: vec![node(0), node(0), node(0), node(1)],
            roots: vec![0, 1, 2, 3],
            copied: None,
        });
        let placed = |model: Model, node| Model {
            name: format!("n{node}"),
            transform: glam::Mat4::from_translation(glam::Vec3::X * 3.0 * node as f32),
            instance: Some(Instance {
                tree: tree.clone(),
                node,
                primitive: 0,
                copied: false,
            }),
            ..model
        };
        let sphere = shapes::bumpy_sphere(12, 16);
        let cube = shapes::cube(8, 1.0);
        Scene {
            models: vec![
                placed(sphere.clone(), 0),
                placed(sphere.clone(), 1),
                placed(sphere, 2),
                placed(cube, 3),
            ],
        }
    }

    #[test]
    fn a_mesh_several_nodes_place_is_decimated_once_and_counted_once() {
        let mut scene = instanced();
        let before: Vec<usize> = scene.models.iter().map(|m| m.triangles.len()).collect();
        let distinct = before[0] + before[3];
        let params = Params {
            target: Target::KeepTriangles(distinct / 2),
            algorithm: Algorithm::Qem,
            ..Params::default()
        };
        let report = simplify_scene(&mut scene, &params, &mut |_| {});
        let m = &scene.models;
        // The count target is met over distinct meshes: the sphere once, and the cube.
        let kept = m[0].triangles.len() + m[3].triangles.len();
        assert!(kept.abs_diff(distinct / 2) <= 2, "{kept} of {distinct}");
        for i in [1, 2] {
            assert_eq!(m[i].positions, m[0].positions);
            assert_eq!(m[i].triangles, m[0].triangles);
            assert_eq!(m[i].name, format!("n{i}"));
            assert_eq!(m[i].transform.w_axis.x, 3.0 * i as f32, "placed as before");
            assert_eq!(report.models[i].instance_of, Some(0));
        }
        let r = &report.models;
        let removed = |k: usize| r[k].vertices_before - r[k].vertices_after;
        assert_eq!(report.vertices_removed(), removed(0) + removed(3));
        let summary = report.summary();
        assert_eq!(summary.matches("instance of n0").count(), 2, "{summary}");
        assert!(
            summary.contains(&format!(
                "total (each mesh once: 2 more instances not counted): vertices {} -> {}",
                report.models[0].vertices_before + report.models[3].vertices_before,
                report.models[0].vertices_after + report.models[3].vertices_after,
            )),
            "{summary}"
        );
    }

    #[test]
    fn a_copied_mesh_is_left_as_read() {
        let mut scene = instanced();
        for m in &mut scene.models {
            if let Some(i) = m.instance.as_mut() {
                i.copied = i.node < 3;
            }
        }
        let sphere = scene.models[0].clone();
        let report = simplify_scene(&mut scene, &Params::default(), &mut |_| {});
        for i in 0..3 {
            assert_eq!(scene.models[i].triangles, sphere.triangles);
            assert!(report.models[i].copied);
        }
        assert!(scene.models[3].triangles.len() < instanced().models[3].triangles.len());
    }

    #[test]
    fn shares_add_up_exactly() {
        assert_eq!(share(10, &[1, 1, 1]), vec![3, 4, 3]);
        assert_eq!(share(10, &[0, 5]), vec![0, 10]);
        assert_eq!(share(7, &[]), Vec::<usize>::new());
        assert_eq!(share(5, &[0, 0]), vec![0, 0]);
    }
}

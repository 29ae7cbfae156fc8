//! Quadric edge collapse (Garland, Heckbert, SIGGRAPH 1997; area weighting, colour and
//! texture after their 1998 paper and Hoppe 1999): a collapsed edge's kept vertex moves to
//! the point that minimises the area-weighted squared distance to the planes it stands for.
//!
//! Stages over flat arrays: load in Morton order (`layout`) → connect (`mesh::topology`) →
//! kinds and quadrics (`planes`, `texture_quadrics`) → rank every edge (`ranking`) →
//! collapse in passes (`collapse_passes`; `legality` checks, `part` performs) → compact back
//! into the model. Error, attributes, seams and pins: docs/design.md#qem.

mod collapse_distance;
mod collapse_passes;
mod collapse_plan;
mod collapser;
mod edge_costs;
mod features;
mod junction_collapse;
mod legality;
mod lt_cost;
mod lt_placement;
mod part;
mod planes;
mod quadric;
mod ranking;
mod texture_quadrics;

use glam::Vec3;
use rayon::prelude::*;

use super::distance_bound::DistanceBound;
use super::layout;
use super::{Limits, Outcome};
use crate::mesh::progressive::{ProgressiveModel, Recorder};
use crate::mesh::topology::Connectivity;
use crate::mesh::{Attribute, Model};
use collapse_plan::Kind;
use collapser::Collapser;

/// Decimates `model` in place by quadric edge collapse within `limits` (the feature angle
/// only picks the feature edges that are constrained; it is never relaxed — QEM needs no
/// relaxing to reach a count). Vertices flagged in `pins` (indexed like the model's
/// positions: seam junctions, shared borders) never move nor go, but may take in their
/// neighbours where they stand (a junction copy left with no triangle by a collapse across
/// the junction is dropped, `junction_collapse`); vertices `twins` pairs (the two
/// sides of a texture seam, `mesh::seams::Seams::twin`; may be empty) move only together,
/// along the seam. `progress` gets the running removal count.
pub fn decimate_model(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
) -> Outcome {
    run(model, limits, pins, twins, progress, Job::Plain).0
}

/// What [`decimate_model_pruning`] calls on a mesh with non-manifold vertices: removes
/// triangles, returns how many vertices it left unused (`None`: it removed nothing).
pub type Prune<'a> = dyn FnMut(&mut Model) -> Option<usize> + 'a;

/// As [`decimate_model`], except that where the mesh turns out to have non-manifold
/// vertices, `prune` first gets the model as it came: when it removes triangles (never
/// vertices: it returns how many it left unused, `None` when it removed nothing), the run
/// starts again on what is left, that many vertices fewer to remove. A clean mesh never
/// pays for the pruning's own pass (`decimate::hanging_sheets`).
pub fn decimate_model_pruning(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
    prune: &mut Prune<'_>,
) -> Outcome {
    run(model, limits, pins, twins, progress, Job::Prune(prune)).0
}

/// As [`decimate_model`], and records every collapse: the returned progressive model's base
/// is the decimated `model`, and refining it all the way gives the input back.
pub fn decimate_model_progressive(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
) -> (Outcome, ProgressiveModel) {
    let recorder = Recorder::new(model);
    match run(model, limits, pins, twins, progress, Job::Record(recorder)) {
        (outcome, Some(pm)) => (outcome, pm),
        (_, None) => unreachable!("a run given a recorder returns its progressive model"),
    }
}

/// What a [`run`] does besides decimating.
enum Job<'a, 'b> {
    Plain,
    /// Records every collapse: the progressive model is returned (its base is what is
    /// written back into the model).
    Record(Recorder),
    /// As in [`decimate_model_pruning`].
    Prune(&'a mut Prune<'b>),
    /// The run again after a pruning, which kept every vertex where it was: the vertices'
    /// internal order, as the first run loaded them.
    Pruned(Vec<u32>),
}

/// A job's recorder, pruning and vertex order, each where it has one.
type JobParts<'a, 'b> = (
    Option<Recorder>,
    Option<&'a mut Prune<'b>>,
    Option<Vec<u32>>,
);

impl<'a, 'b> Job<'a, 'b> {
    fn parts(self) -> JobParts<'a, 'b> {
        match self {
            Job::Plain => (None, None, None),
            Job::Record(recorder) => (Some(recorder), None, None),
            Job::Prune(prune) => (None, Some(prune), None),
            Job::Pruned(order) => (None, None, Some(order)),
        }
    }
}

/// The pipeline, doing `job` besides.
fn run(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
    job: Job<'_, '_>,
) -> (Outcome, Option<ProgressiveModel>) {
    let (recorder, prune, order) = job.parts();
    // 1. load, renumbered along a Morton curve for memory locality
    let n = model.positions.len() as u32;
    let mut loaded = order.map_or_else(|| layout::load(model), |o| layout::load_in(model, o));
    let positions: Vec<Vec3> = (loaded.order.par_iter())
        .map(|&v| model.positions[v as usize])
        .collect();
    let triangles = loaded.triangles(model);
    let pairs = loaded.pairs(twins);
    // Only loading maps the model's ids to the internal ones.
    loaded.internal = Vec::new();
    let (order, faces) = (&loaded.order, &loaded.faces);
    // The decimation works on its own copies: the model's are freed meanwhile (with a
    // recorder, which starts from the model, they stay).
    let mut released = recorder.is_none() && layout::release(model, &loaded);
    let (colors, normals) = per_vertex_attributes(model, n as usize, order);

    // 2. connect, 3. quadrics (one pass over the vertices' rings)
    let cos_feature = limits.feature_angle_deg.to_radians().cos();
    let seam = seam_flags(order, &pairs, pins);
    let constraints = planes::Constraints {
        cos_feature,
        scale_folds: limits.scale_folds,
        seam: &seam,
        result_triangles: expected_triangles(limits, positions.len(), triangles.len()),
    };
    // The distance tracker reads the input's triangles before the connectivity takes them.
    let distance = (limits.max_error.is_finite())
        .then(|| DistanceBound::new(&positions, &triangles, limits.max_error));
    // Kinds first: a mesh that gets pruned starts again, and would throw the rest of the
    // setup (closed volumes, input surface, cost cache) away.
    let conn = Connectivity::from_triangles(positions.len(), triangles);
    let start = planes::kinds_and_quadrics(&conn, &positions, constraints);
    if let Some(prune) = prune.filter(|_| start.0.contains(&Kind::Complex)) {
        if released {
            layout::restore(model, &positions, &conn, order, faces);
        }
        if let Some(unused) = prune(model) {
            drop((conn, start, distance));
            let limits = Limits {
                remove: limits.remove.saturating_sub(unused),
                ..limits.clone()
            };
            // Only triangles went: the vertices' order stands.
            let order = std::mem::take(&mut loaded.order);
            return run(model, &limits, pins, twins, progress, Job::Pruned(order));
        }
        released = layout::release(model, &loaded);
    }
    let mut d = Collapser::connected(positions, conn, start, colors, normals, cos_feature);
    d.distance = distance;
    d.lt = limits.cost == super::Cost::LindstromTurk;
    let keep_features = limits.keep_features;
    texture_and_pins(&mut d, (model, n as usize), order, pins, keep_features);
    d.set_twins(pairs);
    d.recorder = recorder;

    // 4. rank
    d.whole().rank_all();

    // 5. collapse
    let mut outcome = collapse_passes::collapse_in_passes(&mut d, limits, progress);
    outcome.pinned = pins.iter().take(n as usize).filter(|&&p| p).count();

    // 6. compact
    let pm = write_back(&mut d, model, (order, faces), outcome.removed > 0, released);
    (outcome, pm)
}

/// How many triangles the result of `limits` on a mesh of `vertices` and `triangles` is
/// expected to have: the triangle target, or the vertices' share of the triangles; `None`
/// without a count (an error bound alone).
fn expected_triangles(limits: &Limits, vertices: usize, triangles: usize) -> Option<usize> {
    if limits.keep_triangles > 0 {
        return Some(limits.keep_triangles);
    }
    (limits.remove != usize::MAX).then(|| {
        let kept = vertices.saturating_sub(limits.remove);
        (triangles as f64 * kept as f64 / vertices.max(1) as f64) as usize
    })
}

/// Writes the decimated mesh back into `model` (`order` and `faces` map the internal ids
/// back), or the model's own arrays when nothing went (`released`: they were freed); the
/// progressive record when one was kept.
fn write_back(
    d: &mut Collapser,
    model: &mut Model,
    (order, faces): (&[u32], &[u32]),
    removed_any: bool,
    released: bool,
) -> Option<ProgressiveModel> {
    if let Some(recorder) = d.recorder.take() {
        let kept = d.write_back(model, order, faces);
        return Some(recorder.finish(model.clone(), &kept, &d.conn, order, faces));
    }
    if removed_any {
        d.write_back(model, order, faces);
    } else if released {
        d.restore(model, order, faces);
    }
    None
}

/// Per internal vertex, whether it is on a texture seam: one of two sides (twinned) or where
/// more meet (pinned; shared borders are pinned too, but never collapse either). Empty
/// where there are no twins.
fn seam_flags(order: &[u32], pairs: &[u32], pins: &[bool]) -> Vec<bool> {
    if pairs.is_empty() {
        return Vec::new();
    }
    let pinned = |v: u32| pins.get(v as usize).copied().unwrap_or(false);
    (order.iter().zip(pairs))
        .map(|(&v, &w)| w != u32::MAX || pinned(v))
        .collect()
}

/// Gives `d` the texture coordinates of `model`, which had `n` vertices when loaded (its
/// positions may be released since), in the internal `order`, and its pins: the vertices
/// `pins` flags and, with `keep_features`, every feature corner.
fn texture_and_pins(
    d: &mut Collapser,
    (model, n): (&Model, usize),
    order: &[u32],
    pins: &[bool],
    keep_features: bool,
) {
    d.texcoords = model
        .texcoords
        .as_ref()
        .filter(|t| t.len() == n)
        .map(|t| order.iter().map(|&v| t[v as usize]).collect());
    d.weigh_texture();
    let pinned = |v: u32| pins.get(v as usize).copied().unwrap_or(false);
    let mut anchored: Vec<bool> = order.iter().map(|&v| pinned(v)).collect();
    if keep_features {
        for (a, corner) in anchored.iter_mut().zip(d.keep_features()) {
            *a |= corner;
        }
    }
    d.pin(&anchored);
}

/// A per-vertex attribute in the internal order, when the model has it per vertex.
type PerVertex = Option<Vec<[f32; 3]>>;

/// The model's per-vertex colours and normals (of its `n` vertices as loaded: its positions
/// may be released by now), in the internal order `order`.
fn per_vertex_attributes(model: &Model, n: usize, order: &[u32]) -> (PerVertex, PerVertex) {
    let colors = match &model.colors {
        Some(Attribute::PerVertex(c)) if c.len() == n => {
            Some(order.iter().map(|&v| c[v as usize]).collect::<Vec<_>>())
        }
        _ => None,
    };
    let normals = match &model.normals {
        Some(Attribute::PerVertex(v)) if v.len() == n => {
            Some(order.iter().map(|&i| v[i as usize].to_array()).collect())
        }
        _ => None,
    };
    (colors, normals)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decimate::{Cancel, Cost};

    fn removing(remove: usize) -> Limits {
        Limits {
            remove,
            seam_copies: 0,
            keep_triangles: 0,
            max_error: f64::INFINITY,
            feature_angle_deg: 30.0,
            relax_features: false,
            keep_features: false,
            scale_folds: true,
            cost: Cost::Quadric,
            cancel: Cancel::default(),
        }
    }

    #[test]
    fn a_pruned_run_gives_what_a_run_on_the_pruned_mesh_gives() {
        // A bumpy sphere with a flap hanging on one of its vertices (non-manifold there).
        let mut model = crate::mesh::shapes::bumpy_sphere(24, 48);
        let (v, n) = (100u32, model.positions.len() as u32);
        let p = model.positions[v as usize];
        model
            .positions
            .extend([p + Vec3::X * 0.01, p + Vec3::Y * 0.01]);
        model.triangles.push([v, n, n + 1]);
        let mut pruned = model.clone();
        pruned.triangles.pop();
        let mut prunings = 0;
        let mut prune = |m: &mut Model| {
            prunings += 1;
            assert_eq!(m.triangles.pop(), Some([v, n, n + 1]), "the flap, last");
            Some(2)
        };
        let ran = decimate_model_pruning(
            &mut model,
            &removing(500),
            &[],
            &[],
            &mut |_| {},
            &mut prune,
        );
        // The restart keeps the first run's vertex order: a fresh run on the pruned mesh,
        // its two unused vertices fewer to remove, must give the same mesh.
        let fresh = decimate_model(&mut pruned, &removing(498), &[], &[], &mut |_| {});
        assert_eq!(prunings, 1);
        assert_eq!(ran.removed, 498);
        assert_eq!(fresh.removed, 498);
        assert_eq!(model.triangles, pruned.triangles);
        assert_eq!(model.positions, pruned.positions);
    }
}

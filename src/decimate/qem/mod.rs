//! Quadric edge collapse: M. Garland, P. S. Heckbert, "Surface Simplification Using Quadric
//! Error Metrics", SIGGRAPH 1997, with the boundary constraint planes of that paper and the
//! area weighting of Garland's thesis (1999) and of "Simplifying Surfaces with Color and
//! Texture using Quadric Error Metrics" (Garland, Heckbert, IEEE Visualization 1998).
//!
//! The pipeline over flat arrays, one stage per step:
//! 1. load (`layout`): renumber vertices along a Morton curve (`mesh::spatial`) and order
//!    triangles by their first vertex, for locality; drop triangles with out-of-range
//!    indices; positions are stored in f32, as written, and worked in f64: a placement is
//!    rounded to f32 before it is checked, so every check sees what is written;
//! 2. connect: vertex → triangle incidence (`mesh::topology`);
//! 3. kinds and quadrics (`planes`, one pass over the vertices' ordered rings, on all
//!    cores; `texture_quadrics` for a textured model's): each vertex's kind (interior,
//!    boundary, complex: non-manifold) from its ring's shape; every triangle adds its plane
//!    weighted by its area;
//!    every boundary edge adds a plane through the edge perpendicular to its triangle,
//!    weighted `CONSTRAINT_WEIGHT` × length² (`SEAM_WEIGHT` on a texture seam, whose sides
//!    move together), and so does every feature edge (dihedral angle above the feature
//!    angle) on both sides, weighted by how sharp it is, so that outlines and creases stay
//!    put;
//! 4. rank (`ranking`): every edge's collapse is planned once (which end goes, where the
//!    other one moves) and its cost cached per half-edge slot; every vertex notes its
//!    cheapest edge — on all cores;
//! 5. collapse (`collapse_passes`): in passes, each over the cheapest share of the vertices' best
//!    edges in cost order: re-plan, check it is legal (`legality`: a chain of small named
//!    checks; an illegal edge is blocked until its neighbourhood changes), perform it, add
//!    the quadrics, interpolate attributes (`part`); a pass that cannot reach the target
//!    collapses in spatial regions on all cores, each a disjoint `Part` of the arrays, with
//!    the same result on any number of cores; at the end of a pass the kept vertices'
//!    edges are re-planned and the touched vertices re-pick their cheapest edge;
//! 6. compact: live vertices (at their new positions) and triangles back into the model.
//!
//! Collapses are ordered by the quadric itself, `Q(p)` (area × squared distance, as in the
//! paper), so that large flat-ish regions do not coarsen before small curved ones. The error
//! of a placement is `sqrt(Q(p) / W)`, `W` the summed triangle area behind the quadric — an
//! area-weighted RMS distance to the planes the vertex stands for, in model units. That is
//! what `--max-error` bounds (a collapse above it is skipped) and what the report gives.
//!
//! Per-vertex colours take a simpler route than the 1998 paper's extended quadric: the kept
//! vertex's colour is interpolated along the edge at the projection of its new position, and
//! the cost used to order collapses adds `W × |colour difference|² × edge length²` (colour
//! in 0..=1; the units of `Q`: as if the colour step moved the surface by that fraction of
//! the edge), so edges across colour changes go last. Per-vertex normals are interpolated
//! the same way and weigh in the same way, lightly (`NORMAL_WEIGHT` in `part`: on curved
//! surfaces the quadric already prices what the normals say; on flat stretches carrying
//! shading the normals alone order the collapses). Per-face colours stay with their
//! surviving faces.
//!
//! Texture coordinates take the 1998 paper's route, in the form of Hoppe's 1999 quadric
//! (`quadric::TextureQuadric`, built in `texture_quadrics`): every triangle's coordinates are an
//! affine map over its plane, and a vertex is priced by how far the image slides over the
//! surface from the maps of the triangles it stands for. A moved vertex is placed to keep
//! the geometric error and the slide (weighted by `TEXTURE_WEIGHT` in `part`) low together;
//! the kept end of an interior edge takes the coordinates that slide the image least, that of
//! a boundary or seam edge (or one that stays put) coordinates interpolated along the edge,
//! which keep it on the texture's outline. `--max-error` and the reported error stay
//! geometric.
//!
//! A texture seam (`mesh::seams`) is two boundaries at the same positions: where exactly
//! two sides meet, a seam edge collapses together with the other side's edge, to the same
//! position, costed by the four ends' quadrics (`Part::plan`), and a seam vertex otherwise
//! only takes in interior neighbours, unmoved; so the sides never part. Seam junctions
//! (three or more sides) and borders shared with another model (`mesh::stitches`) are
//! pinned (`Kind::Anchored`): they never move nor go, but take in neighbours where they
//! stand — an interior one, or one along the outline; on a seam both sides' edges go
//! together into the junction's copies there. A collapse into a vertex with copies (a
//! twin, a junction's) must leave the surface manifold once the seams are welded
//! (`collapse_passes::seam_stays_manifold`).
//!
//! Non-manifold input takes part, by rules in the manner of meshoptimizer's: a complex
//! vertex (on an edge of three or more triangles, or where several fans meet) never moves,
//! but takes in an interior neighbour, or a boundary one along the outline, where it stands;
//! and it goes only along a non-manifold edge into the complex vertex at the other end, so
//! that every sheet on that edge shortens together. Its quadric adds, through each such
//! edge and each outline edge, a plane perpendicular to every triangle there, so that going
//! off the edge's line costs. No collapse adds a non-manifold edge (see `Part::plan`).

mod collapse_passes;
mod collapse_plan;
mod collapser;
mod edge_costs;
mod legality;
mod part;
mod planes;
mod quadric;
mod ranking;
mod texture_quadrics;

use glam::Vec3;
use rayon::prelude::*;

use super::layout;
use super::{Limits, Outcome};
use crate::mesh::progressive::{ProgressiveModel, Recorder};
use crate::mesh::{Attribute, Model};
use collapser::Collapser;

/// Decimates `model` in place by quadric edge collapse within `limits` (the feature angle
/// only picks the feature edges that are constrained; it is never relaxed — QEM needs no
/// relaxing to reach a count). Vertices flagged in `pins` (indexed like the model's
/// positions: seam junctions, shared borders) never move nor go, but may take in their
/// neighbours where they stand; vertices `twins` pairs (the two
/// sides of a texture seam, `mesh::seams::Seams::twin`; may be empty) move only together,
/// along the seam. `progress` gets the running removal count.
pub fn decimate_model(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
) -> Outcome {
    run(model, limits, pins, twins, progress, None).0
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
    match run(model, limits, pins, twins, progress, Some(recorder)) {
        (outcome, Some(pm)) => (outcome, pm),
        (_, None) => unreachable!("a run given a recorder returns its progressive model"),
    }
}

/// The pipeline; with a `recorder`, every collapse is recorded and the progressive model
/// returned (its base is what is written back into `model`).
fn run(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
    recorder: Option<Recorder>,
) -> (Outcome, Option<ProgressiveModel>) {
    // 1. load, renumbered along a Morton curve for memory locality
    let n = model.positions.len() as u32;
    let loaded = layout::load(model);
    let (order, faces) = (&loaded.order, &loaded.faces);
    let positions: Vec<Vec3> = order
        .par_iter()
        .map(|&v| model.positions[v as usize])
        .collect();
    let triangles = loaded.triangles(model);
    let per_vertex = |a: &Option<Attribute<[f32; 3]>>| match a {
        Some(Attribute::PerVertex(c)) if c.len() == n as usize => {
            Some(order.iter().map(|&v| c[v as usize]).collect::<Vec<_>>())
        }
        _ => None,
    };
    let colors = per_vertex(&model.colors);
    let normals = match &model.normals {
        Some(Attribute::PerVertex(v)) if v.len() == n as usize => {
            Some(order.iter().map(|&i| v[i as usize].to_array()).collect())
        }
        _ => None,
    };

    // 2. connect, 3. quadrics (one pass over the vertices' rings)
    let cos_feature = limits.feature_angle_deg.to_radians().cos();
    let pinned = |v: u32| pins.get(v as usize).copied().unwrap_or(false);
    let twins = loaded.pairs(twins);
    // On a seam: one of two sides (twinned) or where more meet (pinned; shared borders are
    // pinned too, but never collapse either).
    let seam: Vec<bool> = if twins.is_empty() {
        Vec::new()
    } else {
        (order.iter().zip(&twins))
            .map(|(&v, &w)| w != u32::MAX || pinned(v))
            .collect()
    };
    let constraints = planes::Constraints {
        cos_feature,
        seam: &seam,
    };
    let mut d = Collapser::new(positions, triangles, colors, normals, constraints);
    d.texcoords = model
        .texcoords
        .as_ref()
        .filter(|t| t.len() == n as usize)
        .map(|t| order.iter().map(|&v| t[v as usize]).collect());
    d.weigh_texture();
    d.pin(&order.iter().map(|&v| pinned(v)).collect::<Vec<_>>());
    d.set_twins(twins);
    d.recorder = recorder;

    // 4. rank
    d.whole().rank_all();

    // 5. collapse
    let mut outcome = collapse_passes::collapse_in_passes(&mut d, limits, progress);
    outcome.pinned = (0..n).filter(|&v| pinned(v)).count();

    // 6. compact
    if let Some(recorder) = d.recorder.take() {
        let kept = d.write_back(model, order, faces);
        let pm = recorder.finish(model.clone(), &kept, &d.conn, order, faces);
        return (outcome, Some(pm));
    }
    if outcome.removed > 0 {
        d.write_back(model, order, faces);
    }
    (outcome, None)
}

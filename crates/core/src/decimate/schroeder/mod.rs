//! Schroeder vertex removal: W. J. Schroeder, J. A. Zarge, W. E. Lorensen, "Decimation of
//! Triangle Meshes", SIGGRAPH 1992 — the algorithm of the 2002 program, in full.
//!
//! The pipeline over flat arrays, one stage per step:
//! 1. load: drop triangles with out-of-range indices (positions stay f32 — vertex removal
//!    never moves a vertex — and all arithmetic is f64);
//! 2. connect: vertex → triangle incidence (`mesh::topology`);
//! 3. classify every vertex (`mesh::classify`) and key the removable ones by their
//!    decimation criterion, on all cores:
//!    simple → distance to the loop's average plane (area-weighted normal and centre);
//!    boundary → distance to the line through its two boundary neighbours;
//!    interior edge → distance to the line through its two feature neighbours;
//!    complex, on a non-manifold crease line or at a bowtie (`sheets`) → distance to the
//!    line its fans close on;
//!    plus the error already accumulated at the vertex by earlier removals around it, so that
//!    the key bounds the distance to the original surface (as VTK's later implementation
//!    of the paper does); pinned vertices (seam junctions, `mesh::seams`; borders shared
//!    with another model, `mesh::stitches`) are never candidates, and the two
//!    sides of a texture seam (twins) go together or not at all (`try_remove_twins`); a
//!    fill's new edge between seam vertices must not meet an edge between other copies of
//!    its ends (twins, a junction's copies, `mesh::seams::copies`), so that the welded
//!    surface stays manifold;
//! 4. remove (`removal_passes`): in passes over the cheapest share of the candidates, in key order:
//!    remove each, filling its hole by recursive loop splitting (`loop_split`, planned in
//!    `plan`), keeping creases (an interior-edge vertex's loop is first split along its
//!    feature edge; a complex vertex's fans are filled one by one) and rejecting fills that
//!    flip (against the current mesh and the input surface, `input_surface`) or degenerate
//!    a triangle, create an edge that already exists (non-manifold) or turn a closed shape
//!    inside out or flat
//!    (`decimate::closed`) — such a vertex is kept until a neighbour goes; a
//!    vertex whose ring a removal changed waits for the next pass, re-ranked at the end of
//!    this one; removals run in regions on all cores (`region_removal`) while a round of them
//!    cannot reach the target, the rest (and those on region borders) planned on all cores
//!    a batch at a time and made one by one;
//! 5. compact: live vertices and triangles (and their colours, normals and texture
//!    coordinates, which a removal never changes) back into the model's arrays.
//!
//! Nothing in the loop is quadratic in the mesh size: a removal costs O(valence²) (its
//! loop's splitting more, bounded by the valence cap of `mesh::topology`), a pass O(n) to
//! select its candidates, and a scan takes a dozen or so passes.

mod input_surface;
pub(crate) mod loop_split;
mod loosen;
mod plan;
mod region_removal;
mod removal_distance;
mod removal_passes;
mod sheets;

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use super::closed::{tet6, ClosedVolumes};
use super::distance_bound::DistanceBound;
use super::layout::{self, compact, Compacted};
use super::{Limits, Outcome, MIN_VERTICES};
use crate::mesh::classify::VertexClass;
use crate::mesh::seams::position_key;
use crate::mesh::topology::{Adjacency, Connectivity};
use crate::mesh::{Attribute, Model};
use input_surface::{InputCorners, InputSurface};
use plan::{is_ring_end, Planning, SeamSides, Surface};

/// How much the feature angle grows each time a count target could not otherwise be met.
pub const RELAX_STEP_DEG: f64 = 15.0;

/// Beside a pass in `Decimator::changed_in`: the vertex was held back in that pass, not
/// changed (see `Region::hold_neighbours`).
const HELD: u32 = 1 << 31;

/// Whether a vertex whose `changed_in` mark is `mark` waits in pass `pass`: its ring
/// changed in that pass, or it was held back.
fn waits(mark: u32, pass: u32) -> bool {
    mark & !HELD == pass
}

/// Decimates `model` in place within `limits`, never removing a vertex flagged in `pins`
/// (indexed like the model's positions: texture seams, shared borders) and removing the
/// vertices `twins` pairs (the two sides of a texture seam, `mesh::seams::Seams::twin`; may
/// be empty) only together; `progress` gets the running removal count.
pub fn decimate_model(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
) -> Outcome {
    // 1. load
    let (mut loaded, positions, triangles) = load(model);
    let pin = |&v: &u32| pins.get(v as usize).copied().unwrap_or(false);
    let pinned: Vec<bool> = loaded.order.iter().map(pin).collect();
    let twins = loaded.pairs(twins);
    let texcoords = model
        .texcoords
        .as_ref()
        .filter(|t| t.len() == model.positions.len())
        .map(|t| loaded.order.iter().map(|&v| t[v as usize]).collect());
    // Only loading maps the model's ids to the internal ones; the decimation works on its
    // own copies, so the model's are freed meanwhile.
    loaded.internal = Vec::new();
    let released = layout::release(model, &loaded);

    // 2. connect
    let pinned_count = pinned.iter().filter(|&&p| p).count();
    let copies = crate::mesh::seams::copy_cycles(&positions, &pinned);
    // A seam cuts a closed shape open: judge closedness with its copies welded.
    let seamed_closed = (!twins.is_empty() || !copies.is_empty())
        .then(|| ClosedVolumes::with_seams(&positions, &triangles, &twins, &copies));
    let facing = crate::mesh::seams::junction_normals(&positions, &triangles, &copies);
    let distance = (limits.max_error.is_finite())
        .then(|| DistanceBound::new(&positions, &triangles, limits.max_error));
    let mut d = Decimator::new(positions, triangles, limits.feature_angle_deg);
    d.distance = distance;
    d.unfold = sheets::any_non_manifold_edge(&d.conn, d.positions.len());
    d.facing = facing;
    if let Some(closed) = seamed_closed {
        d.closed = closed;
    }
    d.copies = copies;
    d.pinned = pinned;
    d.twins = twins;
    d.texcoords = texcoords;

    let (floor, floored) = floored_limits(&d, limits);

    // 3. classify and rank
    let mut outcome = Outcome::nothing_removed(limits.feature_angle_deg, pinned_count);
    let live = loosen::live_count(&d);
    d.unfold |= loosen::short_from_start(&d, limits, &outcome, live);
    if limits.relax_features {
        loosen::relax_early(&mut d, limits, &mut outcome, live);
    } else {
        d.rank_all();
    }

    // 4. remove
    removal_passes::remove_in_passes(&mut d, &floored, &mut outcome, progress);
    progress(outcome.removed);
    // Stopped by the floor short of the count asked: nothing more can go.
    outcome.exhausted |= outcome.removed >= floor
        && outcome.removed < limits.remove
        && d.conn.triangle_count() > limits.keep_triangles;
    if outcome.exhausted {
        outcome.closed_kept = d.closed_kept();
    }

    // 5. compact
    if outcome.removed > 0 {
        d.write_back(model, &loaded.order, &loaded.faces);
    } else if released {
        layout::restore(model, &d.positions, &d.conn, &loaded.order, &loaded.faces);
    }
    outcome
}

/// The most vertices a count may remove, and `limits` with it. A count short of "all of
/// them" stops at four vertices, as qem does: a model under four is dropped from the scene
/// (the original's rule, which `-p 100` and an error bound alone keep), and a plane's two
/// triangles or a tetrahedron is as far as `-p 50` or a triangle count should take it (a
/// 5-vertex fin cut at `-p 50` came out empty).
fn floored_limits(d: &Decimator, limits: &Limits) -> (usize, Limits) {
    let used = (0..d.positions.len() as u32)
        .filter(|&v| !d.conn.incident(v).is_empty())
        .count()
        .saturating_sub(limits.seam_copies);
    let floor = if limits.keep_triangles > 0 || limits.remove < used {
        used.saturating_sub(MIN_VERTICES)
    } else {
        used
    };
    let floored = Limits {
        remove: limits.remove.min(floor),
        ..limits.clone()
    };
    (floor, floored)
}

/// `model` as the decimation works on it: renumbered along a Morton curve, triangles
/// sorted by their smallest vertex (memory locality for everything after, and the order
/// `region_removal` cut by). Returns the renumbering, the positions and the triangles.
fn load(model: &Model) -> (layout::Loaded, Vec<Vec3>, Vec<[u32; 3]>) {
    let mut loaded = layout::load(model);
    let positions: Vec<Vec3> = loaded
        .order
        .iter()
        .map(|&v| model.positions[v as usize])
        .collect();
    let mut faces = std::mem::take(&mut loaded.faces);
    faces.sort_by_cached_key(|&t| loaded.triangle(model, t).into_iter().min());
    loaded.faces = faces;
    let triangles = loaded.triangles(model);
    (loaded, positions, triangles)
}

/// Six times the change of signed volume that replacing triangles `old` by `fill` makes
/// (about vertex `at`, which only shortens the sums: the change is the same about any point).
fn volume_change(
    positions: &[Vec3],
    at: u32,
    old: impl Iterator<Item = [u32; 3]>,
    fill: &[[u32; 3]],
) -> f64 {
    let p = |v: u32| positions[v as usize].as_dvec3();
    let o = p(at);
    let six = |t: [u32; 3]| tet6(o, p(t[0]), p(t[1]), p(t[2]));
    fill.iter().map(|&t| six(t)).sum::<f64>() - old.map(six).sum::<f64>()
}

/// The working state of one model's decimation.
struct Decimator {
    positions: Vec<Vec3>,
    /// One pair per vertex when the model has texture coordinates: fills are checked in
    /// the texture too.
    texcoords: Option<Vec<[f32; 2]>>,
    conn: Connectivity,
    /// Per triangle slot, the summed area vectors of the input triangles it stands for
    /// (`plan::InputSurface`): a fill faces within 90° of what it replaces in the input.
    input: Vec<Vec3>,
    /// The input triangles at each vertex: a fill faces one of them at one of its corners.
    corners: InputCorners,
    /// Error already accumulated around each vertex by earlier removals.
    accumulated: Vec<f64>,
    /// Each vertex's key (decimation criterion plus accumulated error), `NaN` when it is no
    /// candidate: not removable, pinned, removed, or its hole could not be filled (until a
    /// neighbour goes).
    keys: Vec<f64>,
    cos_feature: f64,
    /// Whether folded rings may be filled (`plan::Surface::unfold`): from the start on a
    /// mesh with non-manifold edges, else once the candidates first run out
    /// (docs/design.md#schroeder-folds).
    unfold: bool,
    planning: Planning,
    /// Vertices never removed: texture seams and shared borders.
    pinned: Vec<bool>,
    /// Each seam vertex's other side, removed only together with it (`u32::MAX`: none;
    /// empty when the model has no such pairs).
    twins: Vec<u32>,
    /// Pinned vertices' next copy at their position (`mesh::seams::copy_cycles`).
    copies: Vec<u32>,
    /// Junction copies' starting normals (`mesh::seams::junction_normals`).
    facing: Vec<Vec3>,
    /// A seam removal's second side.
    twin_planning: Planning,
    /// The pass in which each vertex's ring last changed (a removal took it or a
    /// neighbour), and the pass now running: a changed vertex's key is stale. A vertex a
    /// region held back (`HELD` beside the pass) waits like a changed one but keeps its key.
    changed_in: Vec<u32>,
    pass: u32,
    /// The vertices changed in this pass, each once: re-ranked at its end.
    changed: Vec<u32>,
    /// The batch of plans in which each vertex's neighbourhood last changed, and the batch
    /// now being made: a plan reading a vertex changed since is stale.
    touched_in: Vec<u32>,
    batch: u32,
    /// Closed components' volumes: no removal turns one inside out or flattens it.
    closed: ClosedVolumes,
    /// Under `--max-error`, the input each slot stands for (`decimate::distance_bound`):
    /// removals then run on the whole mesh only.
    distance: Option<DistanceBound>,
    /// The slots the last removal's fill took.
    added: Vec<u32>,
    /// The pass ends one triangle over a triangle count, so that the next can take only
    /// border vertices (`removal_passes`).
    end_one_over: bool,
}

/// A planned removal's ring (vertices and triangles) and fill.
#[derive(Clone, Copy)]
struct Removal<'a> {
    ring: &'a [u32],
    triangles: &'a [u32],
    fill: &'a [[u32; 3]],
    /// Per fill triangle, the input surface it stands for.
    fill_input: &'a [Vec3],
}

impl Decimator {
    fn new(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>, feature_angle_deg: f64) -> Self {
        let n = positions.len();
        let areas = input_surface::area_vectors(&positions, &triangles);
        Self {
            closed: ClosedVolumes::new(&positions, &triangles),
            input: areas.clone(),
            corners: InputCorners::new(n, &triangles, areas),
            conn: Connectivity::from_triangles(n, triangles),
            positions,
            texcoords: None,
            accumulated: vec![0.0; n],
            keys: vec![f64::NAN; n],
            cos_feature: feature_angle_deg.to_radians().cos(),
            unfold: false,
            planning: Planning::default(),
            pinned: vec![false; n],
            twins: Vec::new(),
            copies: Vec::new(),
            facing: Vec::new(),
            twin_planning: Planning::default(),
            // Marks start below the first pass and batch: nothing has changed yet.
            changed_in: vec![0; n],
            pass: 1,
            changed: Vec::new(),
            touched_in: vec![0; n],
            batch: 1,
            end_one_over: false,
            distance: None,
            added: Vec::new(),
        }
    }

    fn surface(&self) -> Surface<'_, Connectivity> {
        Surface {
            conn: &self.conn,
            positions: &self.positions,
            texcoords: self.texcoords.as_deref(),
            cos_feature: self.cos_feature,
            unfold: self.unfold,
            seams: (!self.twins.is_empty() || !self.copies.is_empty()).then(|| self.seam_sides()),
            input: InputSurface {
                t0: 0,
                vectors: &self.input,
            },
            corners: &self.corners,
        }
    }

    fn seam_sides(&self) -> SeamSides<'_> {
        SeamSides {
            twins: &self.twins,
            pinned: &self.pinned,
            copies: &self.copies,
            facing: &self.facing,
        }
    }

    /// Removals the count limits still allow, at most: a removal takes one vertex and at
    /// most two triangles (a closed ring's; an open one's takes one).
    fn removals_allowed(&self, limits: &Limits, outcome: &Outcome) -> usize {
        let over = self
            .conn
            .triangle_count()
            .saturating_sub(limits.keep_triangles);
        limits
            .remove
            .saturating_sub(outcome.removed)
            .min(over.div_ceil(2))
    }

    /// `v`'s key as its ring stands now, `NaN` when it is no candidate.
    fn key(&self, v: u32, planning: &mut Planning) -> f64 {
        match self.surface().evaluate(v, planning) {
            Some((_, distance)) if !self.pinned[v as usize] => {
                distance + self.accumulated[v as usize]
            }
            _ => f64::NAN,
        }
    }

    /// Ranks every vertex afresh, on all cores (each key depends only on its own ring);
    /// returns how many vertices, pinned ones aside, the feature angle now makes corners
    /// (never removed).
    fn rank_all(&mut self) -> usize {
        let this = &*self;
        let corners = AtomicUsize::new(0);
        let keys: Vec<f64> = (0..this.positions.len() as u32)
            .into_par_iter()
            .map_init(Planning::default, |planning, v| {
                let key = this.key(v, planning);
                if planning.corner && !this.pinned[v as usize] {
                    corners.fetch_add(1, Ordering::Relaxed);
                }
                key
            })
            .collect();
        self.keys = keys;
        corners.into_inner()
    }

    /// Ranks `vertices` (ascending) afresh, on all cores, asking for each vertex's data
    /// ahead of its turn: its incident list, then its triangles, then its neighbours'
    /// positions.
    fn rerank(&mut self, vertices: &[u32]) {
        let this = &*self;
        let keys: Vec<f64> = vertices
            .par_chunks(1024)
            .flat_map_iter(|chunk| {
                let mut planning = Planning::default();
                (0..chunk.len()).map(move |n| {
                    this.prefetch_ahead(chunk, n);
                    this.key(chunk[n], &mut planning)
                })
            })
            .collect();
        for (&v, key) in vertices.iter().zip(keys) {
            self.keys[v as usize] = key;
        }
    }

    /// Asks for the data [`Self::key`] reads of the vertices ahead of `vertices[n]`, in
    /// three stages as each becomes addressable (hints only).
    fn prefetch_ahead(&self, vertices: &[u32], n: usize) {
        const AHEAD: usize = 2;
        let conn = &self.conn;
        if let Some(&v) = vertices.get(n + 3 * AHEAD) {
            conn.prefetch_incident(v);
        }
        if let Some(&v) = vertices.get(n + 2 * AHEAD) {
            for &t in conn.incident(v) {
                conn.prefetch_triangle(t);
            }
        }
        if let Some(&v) = vertices.get(n + AHEAD) {
            for &t in conn.incident(v) {
                for u in conn.triangle(t) {
                    if let Some(p) = self.positions.get(u as usize) {
                        crate::mesh::prefetch(p);
                    }
                }
            }
        }
    }

    /// Asks for `v`'s per-vertex state ahead of a removal that reads or marks it (its
    /// marks, key, accumulated error, closed component; hints only).
    fn prefetch_vertex(&self, v: u32) {
        let i = v as usize;
        if let (Some(changed), Some(touched), Some(key), Some(acc)) = (
            self.changed_in.get(i),
            self.touched_in.get(i),
            self.keys.get(i),
            self.accumulated.get(i),
        ) {
            crate::mesh::prefetch(changed);
            crate::mesh::prefetch(touched);
            crate::mesh::prefetch(key);
            crate::mesh::prefetch(acc);
        }
        self.closed.prefetch(v);
    }

    /// `v`'s other side on a texture seam, when it has one.
    fn twin(&self, v: u32) -> Option<u32> {
        self.seam_sides().twin(v)
    }

    /// Whether `v` waits for the next pass: its ring changed in this one (its key is
    /// stale), or a region held it back.
    fn changed_now(&self, v: u32) -> bool {
        waits(self.changed_in[v as usize], self.pass)
    }

    /// Whether `v`'s ring changed in this pass (held back is not changed).
    fn ring_changed_now(&self, v: u32) -> bool {
        self.changed_in[v as usize] == self.pass
    }

    /// Whether `v`'s neighbourhood changed since this batch was planned.
    fn touched_now(&self, v: u32) -> bool {
        self.touched_in[v as usize] == self.batch
    }

    /// Notes that `v`'s ring changed: its key is stale for the rest of the pass (it is
    /// re-ranked at its end) and plans that read it for the rest of the batch.
    fn mark_changed(&mut self, v: u32) {
        self.touched_in[v as usize] = self.batch;
        // A held vertex is listed now: its ring does change.
        if !self.ring_changed_now(v) {
            self.changed_in[v as usize] = self.pass;
            self.changed.push(v);
        }
    }

    /// Removes `v` as planned (a hole's fill that is still valid): old triangles out, new
    /// ones in (reusing their slots, so per-face attributes of the region carry over), and
    /// `key` accumulated around the ring, whose vertices are re-ranked at the pass's end.
    fn apply(&mut self, v: u32, removal: Removal<'_>, key: f64) {
        if let Some(c) = self.closed.component(v) {
            let change = self.volume_change(v, removal);
            self.closed.apply(c, change);
        }
        for &t in removal.triangles {
            self.conn.remove_triangle(t);
        }
        debug_assert_eq!(removal.fill.len(), removal.fill_input.len());
        let mut added = std::mem::take(&mut self.added);
        added.clear();
        for (&tri, &input) in removal.fill.iter().zip(removal.fill_input) {
            let t = self.conn.add_triangle(tri);
            added.push(t);
            let t = t as usize;
            if t >= self.input.len() {
                self.input.resize(t + 1, Vec3::ZERO);
            }
            self.input[t] = input;
        }
        self.commit_distance(&added);
        self.added = added;
        self.mark_changed(v);
        for &u in removal.ring {
            let acc = &mut self.accumulated[u as usize];
            *acc = acc.max(key);
            self.mark_changed(u);
        }
    }

    /// Whether removing `v` as planned keeps its closed component (if any) on its side of
    /// zero and above its floor (`decimate::closed`): the fill's checks compare each new
    /// triangle with the old ones it covers, which on a small closed shape can all pass
    /// while the fill crosses the rest of the shape.
    fn keeps_closed_volume(&self, v: u32, removal: Removal<'_>) -> bool {
        self.closed
            .component(v)
            .is_none_or(|c| self.closed.allows(c, self.volume_change(v, removal), 1.0))
    }

    /// The live vertices whose removal, as the mesh stands, only the closed-volume guard
    /// refuses: the fill is valid but would take a closed part below its floor or across
    /// zero. Counted on all cores, once, when nothing more can go.
    fn closed_kept(&self) -> usize {
        (0..self.positions.len() as u32)
            .into_par_iter()
            .map_init(Planning::default, |planning, v| {
                let candidate = self.closed.component(v).is_some()
                    && !self.pinned[v as usize]
                    && self.twin(v).is_none();
                candidate
                    && self.surface().plan_removal(v, planning).is_some()
                    && !self.keeps_closed_volume(v, removal_of(planning))
            })
            .filter(|&kept| kept)
            .count()
    }

    /// Six times the change of signed volume that replacing `v`'s triangles by the fill
    /// makes.
    fn volume_change(&self, v: u32, removal: Removal<'_>) -> f64 {
        let old = removal.triangles.iter().map(|&t| self.conn.triangle(t));
        volume_change(&self.positions, v, old, removal.fill)
    }

    /// Plans `v`'s removal afresh and makes it; false (and nothing changed) when its hole
    /// cannot be filled.
    fn try_remove(&mut self, v: u32, key: f64) -> bool {
        let mut planning = std::mem::take(&mut self.planning);
        let planned = self.surface().plan_removal(v, &mut planning).is_some()
            && self.keeps_closed_volume(v, removal_of(&planning))
            && self.within_distance(removal_of(&planning), true);
        if planned {
            self.apply(v, removal_of(&planning), key);
        }
        self.planning = planning;
        planned
    }

    /// Removes the two sides `v`, `w` of a texture seam together, or neither: both must be
    /// boundary vertices whose boundary neighbours lie at the same two points, with rings
    /// apart, and both holes must fill validly. Each hole is then closed by the edge between
    /// those points, so the seam's sides stay on one line. Returns the larger key.
    fn try_remove_twins(&mut self, v: u32, w: u32, key: f64) -> Option<f64> {
        let mut first = std::mem::take(&mut self.planning);
        let mut second = std::mem::take(&mut self.twin_planning);
        let key = self
            .plan_twins(v, w, &mut first, &mut second)
            .map(|(key_v, key_w)| key.max(key_v).max(key_w))
            .filter(|_| {
                // In the order `apply` makes them; neither side's input may go near it.
                self.within_distance(removal_of(&second), false)
                    && self.within_distance(removal_of(&first), false)
            });
        if let Some(key) = key {
            self.apply(w, removal_of(&second), key);
            self.apply(v, removal_of(&first), key);
        }
        (self.planning, self.twin_planning) = (first, second);
        key
    }

    /// Plans both sides of a seam removal, `v`'s into `first` and `w`'s into `second`: their
    /// keys when both may go.
    fn plan_twins(
        &self,
        v: u32,
        w: u32,
        first: &mut Planning,
        second: &mut Planning,
    ) -> Option<(f64, f64)> {
        let surface = self.surface();
        let (class_v, distance_v) = surface.plan_removal(v, first)?;
        if class_v != VertexClass::Boundary {
            return None;
        }
        let (class_w, distance_w) = surface.plan_removal(w, second)?;
        let ends = |p: &Planning| {
            let r = &p.ring.verts;
            let at = |i: usize| position_key(self.positions[r[i] as usize]);
            let (a, b) = (at(0), at(r.len() - 1));
            (a.min(b), a.max(b))
        };
        let (ring_v, ring_w) = (&first.ring.verts, &second.ring.verts);
        let apart = !ring_w.iter().any(|u| *u == v || ring_v.contains(u)) && !ring_v.contains(&w);
        let joined = self.junctions_joined(ring_v, ring_w)
            || self.fills_join(first, second)
            || self.fills_join(second, first);
        let fits = class_w == VertexClass::Boundary && ends(first) == ends(second) && apart;
        (fits && !joined).then(|| {
            (
                distance_v + self.accumulated[v as usize],
                distance_w + self.accumulated[w as usize],
            )
        })
    }

    /// Whether the seam between two junctions that a removal's rings (`first`, `second`:
    /// both sides') end at would close onto an edge between other copies of the two — a
    /// second seam between the same junctions, or a chart's inside: welded, that edge
    /// would have more than two triangles. False when a ring does not end at two pinned
    /// vertices.
    fn junctions_joined(&self, first: &[u32], second: &[u32]) -> bool {
        let (Some(&b), Some(&c)) = (first.first(), first.last()) else {
            return false;
        };
        if !(self.pinned[b as usize] && self.pinned[c as usize]) {
            return false;
        }
        let (Some(&b_other), Some(&c_other)) = (second.first(), second.last()) else {
            return false;
        };
        let ends = [b, c, b_other, c_other];
        self.seam_sides().copy_pairs(b, c).any(|(x, y)| {
            !(ends.contains(&x) && ends.contains(&y)) && self.conn.has_edge_avoiding(x, y, u32::MAX)
        })
    }

    /// Whether a new edge of `first`'s fill between two seam vertices (other than the edge
    /// closing its hole, on the seam) meets another copy of itself (its ends' twins, a
    /// junction's other copies) in `second`'s fill: welded, that edge would have four
    /// triangles (see `Surface::joins_seam_sides`).
    fn fills_join(&self, first: &Planning, second: &Planning) -> bool {
        let r = &first.ring.verts;
        let end = |x: u32| is_ring_end(r, x);
        let ring_edge = |x: u32, y: u32| {
            r.windows(2)
                .any(|p| (p[0], p[1]) == (x, y) || (p[1], p[0]) == (x, y))
        };
        let seams = self.seam_sides();
        first.fill.iter().any(|tri| {
            (0..3).any(|i| {
                let (x, y) = (tri[i], tri[(i + 1) % 3]);
                // The hole's closing edge and the ring's own edges are not new.
                let new = !(ring_edge(x, y) || end(x) && end(y));
                new && seams.copy_pairs(x, y).any(|(x2, y2)| {
                    (x2, y2) != (x, y)
                        && (second.fill.iter()).any(|t| t.contains(&x2) && t.contains(&y2))
                })
            })
        })
    }

    /// Writes live vertices and triangles back into `model`. `order` maps internal vertex ids
    /// to the model's, `faces` internal triangle slots to the model's faces. Kept vertices
    /// keep their relative order from the input.
    fn write_back(&self, model: &mut Model, order: &[u32], faces: &[u32]) {
        // A reused slot stands in for the original face that first owned it.
        let Compacted {
            kept_vertices,
            faces,
            triangles,
        } = compact(&self.conn, order, faces);
        model.triangles = triangles;
        // Vertices never move: the kept ones' positions are the internal copies'.
        let mut internal = vec![0u32; order.len()];
        for (i, &v) in order.iter().enumerate() {
            internal[v as usize] = i as u32;
        }
        model.positions = kept_vertices
            .iter()
            .map(|&v| self.positions[internal[v as usize] as usize])
            .collect();
        model.colors = model
            .colors
            .as_ref()
            .map(|c| c.select(&kept_vertices, &faces));
        model.normals = match &model.normals {
            Some(n @ Attribute::PerVertex(_)) => Some(n.select(&kept_vertices, &faces)),
            _ => None, // face normals of refilled holes would be wrong: recomputed on display
        };
        model.texcoords = model.texcoords.as_ref().map(|t| {
            kept_vertices
                .iter()
                .map(|&v| t.get(v as usize).copied().unwrap_or_default())
                .collect()
        });
    }
}

/// The removal planned in `p`.
fn removal_of(p: &Planning) -> Removal<'_> {
    Removal {
        ring: &p.ring.verts,
        triangles: &p.ring.triangles,
        fill: &p.fill,
        fill_input: &p.fill_input,
    }
}

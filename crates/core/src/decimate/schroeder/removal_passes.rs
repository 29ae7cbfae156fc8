//! The removal loop, in passes over the cheapest candidates.
//!
//! A strict greedy loop keeps every candidate in a priority queue and re-ranks a removed
//! vertex's ring at once, one vertex at a time. Instead, each pass takes the cheapest
//! `1/PASS_SHARE` of the candidates (never more than twice what the target still needs),
//! sorted, and removes them in that order. A candidate whose ring a removal of this pass
//! changed has a stale key: it waits, and it is re-ranked with every other changed vertex
//! at the pass's end, on all cores.
//!
//! A pass runs in rounds of its cheapest candidates on all cores, in regions
//! (`schroeder::region_removal`: each plans and makes the removals whose whole neighbourhood it
//! owns), while a round cannot reach the target. The rest, and each round's candidates on
//! region borders, run on the whole mesh: planned a batch at a time on all cores (planning
//! only reads the mesh) and made one by one, in order. A plan is made again when a removal
//! before it in the pass changed the neighbourhood of one of its ring's vertices (which
//! its checks read), so every removal is made as if planned in its turn. The result is the
//! same on any number of cores, and the count stops exactly at the target.

use glam::Vec3;
use rayon::prelude::*;

use super::loosen;
use super::plan::Planning;
use super::{Decimator, Removal};
use crate::decimate::candidates::{cheapest, move_to_front, Candidate};
use crate::decimate::lists;
use crate::decimate::regions::{round_size, Regions};
use crate::decimate::{Limits, Outcome};
use crate::mesh::topology::{Adjacency, Connectivity, Ring, RingShape};

/// One pass takes the cheapest `1 / PASS_SHARE` of the candidates: as accurate as the
/// greedy queue it replaced, in about half the time (docs/design.md#schroeder-pass-share).
const PASS_SHARE: usize = 2;

/// Candidates planned together before any of them is removed.
const BATCH: usize = 4096;

/// Candidates whose incident lists are asked for from memory ahead of their removal.
const PREFETCH_AHEAD: usize = 4;

/// Candidates planned by one task of a batch.
const PER_TASK: usize = 128;

/// What planning a candidate gave.
#[derive(Debug, Clone, Copy)]
enum Planned {
    /// Not planned: its ring had changed already, or it has a twin (planned in its turn).
    Later,
    /// Its ring (and, when `fills`, its ring triangles and fill) lie between these offsets
    /// of the task's arrays.
    Ring {
        starts: [u32; 3],
        ends: [u32; 3],
        fills: bool,
    },
}

/// The plans one task made, in flat arrays.
#[derive(Debug, Default)]
struct Plans {
    entries: Vec<Planned>,
    ring: Vec<u32>,
    triangles: Vec<u32>,
    fill: Vec<[u32; 3]>,
    /// Per fill triangle, the input surface it stands for (as long as `fill`).
    fill_input: Vec<Vec3>,
}

impl Plans {
    /// Entry `i`'s removal and whether its hole fills; `None` when it was not planned.
    fn removal(&self, i: usize) -> Option<(Removal<'_>, bool)> {
        match self.entries[i] {
            Planned::Later => None,
            Planned::Ring {
                starts,
                ends,
                fills,
            } => {
                let [s0, s1, s2] = starts.map(|x| x as usize);
                let [e0, e1, e2] = ends.map(|x| x as usize);
                let removal = Removal {
                    ring: &self.ring[s0..e0],
                    triangles: &self.triangles[s1..e1],
                    fill: &self.fill[s2..e2],
                    fill_input: &self.fill_input[s2..e2],
                };
                Some((removal, fills))
            }
        }
    }

    fn offsets(&self) -> [u32; 3] {
        [self.ring.len(), self.triangles.len(), self.fill.len()].map(|x| x as u32)
    }
}

/// A batch's plans: made in vertex order (neighbours share memory), read in key order.
struct Batch {
    tasks: Vec<Plans>,
    /// The task and entry of each candidate, in the batch's (key) order.
    at: Vec<(u32, u32)>,
}

/// Removes vertices of `d` until `limits` are met or nothing can go, adding to `outcome`;
/// `progress` gets the running removal count.
pub(super) fn remove_in_passes(
    d: &mut Decimator,
    limits: &Limits,
    outcome: &mut Outcome,
    progress: &mut dyn FnMut(usize),
) {
    let mut live: Vec<u32> = (0..d.positions.len() as u32).collect();
    let regions =
        [false, true].map(|shifted| Regions::new(d.positions.len(), d.conn.triangles(), shifted));
    // Kept from pass to pass and refilled in place.
    let (mut all, mut pass, mut tied) = (Vec::new(), Vec::new(), Vec::new());
    // Only a mesh with an open border can land on every triangle count.
    let bordered = limits.keep_triangles > 0
        && live
            .par_iter()
            .map_init(Ring::default, |ring, &v| d.conn.ring(v, ring))
            .any(|shape| shape == RingShape::Open);
    loop {
        if reached(d, limits, outcome) || limits.cancel.requested() {
            break;
        }
        let conn = &d.conn;
        lists::retain(&mut live, |v| !conn.incident(v).is_empty());
        let keys = &d.keys;
        let count = lists::filter_map_into(&live, &mut all, |&v| {
            let key = keys[v as usize];
            (key <= limits.max_error).then(|| Candidate::new(key as f32, v))
        });
        if count == 0 {
            // Out of candidates: let folded rings be filled (docs/design.md#schroeder-folds),
            // re-rank what is left, and go on.
            if !d.unfold {
                d.unfold = true;
                d.rank_all();
                continue;
            }
            if live.par_iter().any(|&v| keys[v as usize].is_finite()) {
                break; // all above the error bound
            }
            // Out of candidates before the target: a coarse scan has "features"
            // everywhere. Relax the feature angle, re-rank what is left, and go on.
            if limits.relax_features && outcome.feature_angle_deg < 180.0 {
                loosen::raise_feature_angle(d, outcome);
                d.rank_all();
                continue;
            }
            outcome.exhausted = true;
            break;
        }
        let needed = d.removals_allowed(limits, outcome);
        if loosen::when_short(d, limits, outcome, count, needed) {
            continue; // re-ranked under the loosened rules
        }
        // One triangle over the count: only a border vertex's removal (one triangle fewer)
        // lands on it, so the pass takes those when there are any. A pass that gets there
        // ends there, so that the next one can.
        let at_one_over = one_over(d, limits);
        let count = match at_one_over {
            true => match border_first(&d.conn, &mut all[..count]) {
                0 => count,
                border => border,
            },
            false => count,
        };
        d.end_one_over = bordered && !at_one_over;
        let take = (count / PASS_SHARE).min(2 * needed).clamp(1, count);
        cheapest(&all[..count], take, &mut pass, &mut tied);
        d.pass += 1;
        let ended = remove_pass(d, &regions, &pass, limits, outcome, progress);
        if ended && (reached(d, limits, outcome) || limits.cancel.requested()) {
            break; // a count limit: the keys are not needed any more
        }
        // In vertex order, so that neighbours share the memory they read.
        let mut changed = std::mem::take(&mut d.changed);
        changed.par_sort_unstable();
        d.rerank(&changed);
        changed.clear();
        d.changed = changed;
    }
}

/// Moves the candidates on one open border (a vertex whose ring is one open fan: its
/// removal takes one triangle) to the front of `candidates`; returns how many.
fn border_first(conn: &Connectivity, candidates: &mut [Candidate]) -> usize {
    let mut ring = Ring::default();
    move_to_front(candidates, |c| {
        conn.ring(c.vertex(), &mut ring) == RingShape::Open
    })
}

/// True when a count limit is met.
fn reached(d: &Decimator, limits: &Limits, outcome: &Outcome) -> bool {
    outcome.removed >= limits.remove || d.conn.triangle_count() <= limits.keep_triangles
}

/// True one triangle over a triangle count.
fn one_over(d: &Decimator, limits: &Limits) -> bool {
    limits.keep_triangles > 0 && d.conn.triangle_count() == limits.keep_triangles + 1
}

/// Removes the pass's `candidates` (in key order); true when a count limit stopped it.
/// Rounds of the cheapest candidates run in `region_removal` while a round cannot reach a limit
/// (see [`allowed`]), each round's border candidates on the whole mesh after it; the rest
/// runs on the whole mesh. A seam's two sides go together on the whole mesh only: regions
/// leave them to it, as they leave border candidates.
fn remove_pass(
    d: &mut Decimator,
    regions: &[Regions; 2],
    candidates: &[Candidate],
    limits: &Limits,
    outcome: &mut Outcome,
    progress: &mut dyn FnMut(usize),
) -> bool {
    let in_regions = regions[0].count() > 1 && d.distance.is_none();
    let mut rest = candidates;
    while in_regions && !rest.is_empty() {
        let size = round_size(
            candidates.len(),
            rest.len(),
            d.removals_allowed(limits, outcome),
        );
        if size == 0 {
            break;
        }
        let (round, tail) = rest.split_at(size);
        let border = d.remove_in_regions(&regions[0], round, outcome);
        let border = d.remove_in_regions(&regions[1], &border, outcome);
        if remove_on_whole(d, &border, limits, outcome, progress) {
            return true;
        }
        progress(outcome.removed);
        rest = tail;
    }
    remove_on_whole(d, rest, limits, outcome, progress)
}

/// Removes `candidates` (in key order) on the whole mesh, a batch at a time; true when a
/// count limit or a cancel request stopped it.
fn remove_on_whole(
    d: &mut Decimator,
    candidates: &[Candidate],
    limits: &Limits,
    outcome: &mut Outcome,
    progress: &mut dyn FnMut(usize),
) -> bool {
    let mut order = Vec::with_capacity(BATCH);
    for batch in candidates.chunks(BATCH) {
        if limits.cancel.requested() {
            return true;
        }
        let plans = plan_batch(d, batch, &mut order);
        d.batch += 1; // what changes from here on, this batch's plans did not see
        if remove_planned(d, batch, &plans, limits, outcome) {
            return true;
        }
        progress(outcome.removed);
    }
    false
}

/// Plans the removal of each of `batch`, on all cores, in vertex order (`order` is
/// scratch).
fn plan_batch(d: &Decimator, batch: &[Candidate], order: &mut Vec<u32>) -> Batch {
    order.clear();
    order.extend(0..batch.len() as u32);
    order.sort_unstable_by_key(|&i| batch[i as usize].vertex());
    let surface = d.surface();
    let tasks: Vec<Plans> = order
        .par_chunks(PER_TASK)
        .map_init(Planning::default, |planning, chunk| {
            let mut plans = Plans::default();
            let mut vertices = [0u32; PER_TASK];
            for (slot, &i) in vertices.iter_mut().zip(chunk) {
                *slot = batch[i as usize].vertex();
            }
            let vertices = &vertices[..chunk.len()];
            for (n, &v) in vertices.iter().enumerate() {
                d.prefetch_ahead(vertices, n);
                let entry = if d.changed_now(v) || d.twin(v).is_some() {
                    Planned::Later
                } else {
                    let starts = plans.offsets();
                    let fills = surface.plan_removal(v, planning).is_some();
                    plans.ring.extend_from_slice(&planning.ring.verts);
                    if fills {
                        plans.triangles.extend_from_slice(&planning.ring.triangles);
                        plans.fill.extend_from_slice(&planning.fill);
                        plans.fill_input.extend_from_slice(&planning.fill_input);
                    }
                    let ends = plans.offsets();
                    Planned::Ring {
                        starts,
                        ends,
                        fills,
                    }
                };
                plans.entries.push(entry);
            }
            plans
        })
        .collect();
    let mut at = vec![(0, 0); batch.len()];
    for (k, &i) in order.iter().enumerate() {
        at[i as usize] = ((k / PER_TASK) as u32, (k % PER_TASK) as u32);
    }
    Batch { tasks, at }
}

/// Removes the candidates of `batch` as `plans` says, in order, each only if its key is
/// still current, planning again those whose plan may be stale; true when a count limit
/// stopped it.
fn remove_planned(
    d: &mut Decimator,
    batch: &[Candidate],
    plans: &Batch,
    limits: &Limits,
    outcome: &mut Outcome,
) -> bool {
    for (i, (c, &(task, entry))) in batch.iter().zip(&plans.at).enumerate() {
        if let Some(&(task, entry)) = plans.at.get(i + PREFETCH_AHEAD) {
            if let Some(c) = batch.get(i + PREFETCH_AHEAD) {
                d.prefetch_vertex(c.vertex());
            }
            if let Some((removal, _)) = plans.tasks[task as usize].removal(entry as usize) {
                for &u in removal.ring {
                    d.conn.prefetch_incident(u);
                    d.prefetch_vertex(u);
                }
                for &t in removal.triangles {
                    d.conn.prefetch_triangle(t);
                }
            }
        }
        if reached(d, limits, outcome) || (d.end_one_over && one_over(d, limits)) {
            return true;
        }
        let v = c.vertex();
        if d.changed_now(v) {
            continue; // its key is stale: re-ranked at the pass's end
        }
        let key = d.keys[v as usize];
        let planned = plans.tasks[task as usize].removal(entry as usize);
        if let Some(w) = d.twin(v) {
            remove_twins(d, v, w, key, limits, outcome);
            continue;
        }
        let removed = match planned {
            Some((removal, fills)) => {
                // A removal in this batch changed what the checks of this plan read: plan
                // again, now.
                let stale = removal.ring.iter().any(|&u| d.touched_now(u));
                if stale {
                    d.try_remove(v, key)
                } else if fills
                    && d.keeps_closed_volume(v, removal)
                    && d.within_distance(removal, true)
                {
                    d.apply(v, removal, key);
                    true
                } else {
                    false
                }
            }
            None => d.try_remove(v, key),
        };
        if removed {
            // One position: a junction copy the removal leaves with no triangle is a copy
            // of a point that stays.
            outcome.removed += 1;
            outcome.max_error = outcome.max_error.max(key);
        } else {
            d.keys[v as usize] = f64::NAN; // kept until a neighbour goes
        }
    }
    false
}

/// Removes seam vertex `v` with its twin `w` when both may go and the count leaves room
/// for two, counting them in `outcome`; when they may not, neither is a candidate until a
/// neighbour goes.
fn remove_twins(
    d: &mut Decimator,
    v: u32,
    w: u32,
    key: f64,
    limits: &Limits,
    outcome: &mut Outcome,
) {
    // Only a change waits, not a hold: the other side is held by the region that left
    // its seam neighbour here, as that neighbour holds this side, and both would wait
    // for ever (keys unchanged, nothing removed, pass after pass).
    if d.ring_changed_now(w) {
        return; // its key is stale: both wait for the next pass
    }
    // One position (two vertices) and two triangles go: only while both counts allow it.
    let room = limits.remove.saturating_sub(outcome.removed) >= 1
        && d.conn.triangle_count() >= limits.keep_triangles + 2;
    match room.then(|| d.try_remove_twins(v, w, key)).flatten() {
        Some(key) => {
            outcome.removed += 1;
            outcome.max_error = outcome.max_error.max(key);
        }
        None => {
            d.keys[v as usize] = f64::NAN;
            d.keys[w as usize] = f64::NAN;
        }
    }
}

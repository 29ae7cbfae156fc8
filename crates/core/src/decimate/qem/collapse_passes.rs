//! The collapse loop, in passes over the cheapest edges.
//!
//! A strict greedy loop re-ranks the neighbours of every collapse in a priority queue, one
//! at a time; on a scan that is several times the work of the collapse itself. Instead,
//! each pass takes the cheapest `1/PASS_SHARE` of the vertices' best edges (never more than
//! twice what the target still needs), sorts them and collapses them in order, each
//! re-planned first: a collapse whose fresh cost is above the pass's threshold waits for
//! the next pass, so no collapse ever costs more than the threshold of the pass that made
//! it. Re-planning is deferred to the end of the pass: the kept vertices' edges are planned
//! again (on all cores), the neighbours' blocked edges are released and every touched
//! vertex re-picks its cheapest edge. Within a pass the order is the cached one; across
//! passes the thresholds rise, so the sequence stays close to greedy (see `PASS_SHARE`).
//!
//! A pass runs on all cores, in rounds of its cheapest candidates (`decimate::regions`):
//! the vertices are cut into 16 ranges of ids (spatial blocks: ids follow a Morton curve) and
//! each region collapses, in cost order, those of the round's candidates whose whole
//! neighbourhood it owns (`Part::gather`). Collapses in different regions touch
//! disjoint data, so they commute: the result depends neither on the threads' timing nor
//! on how many there are. The round's candidates on region borders (about a tenth) then
//! get a second chance in fewer, larger regions shifted by half a region, and those on
//! both borders go, in cost order, on the whole mesh. A round runs in regions only when it
//! cannot reach the target; the last candidates before the target go one at a time on the
//! whole mesh, so that the count stops exactly there; one triangle over a triangle count,
//! the pass ends and the next takes only edges on an open border (a collapse of one
//! triangle) when there are any. A progressive record is kept on the whole mesh only.

use rayon::prelude::*;

use super::collapse_plan::{others, Kind, Plan};
use super::collapser::Collapser;
use super::part::Part;
use super::ranking::stored;
use crate::decimate::candidates::{cheapest, move_to_front, Candidate};
use crate::decimate::lists;
use crate::decimate::regions::{round_size, Regions};
use crate::decimate::{Limits, Outcome, MIN_VERTICES};
use crate::mesh::topology::Connectivity;

/// One pass takes the cheapest `1 / PASS_SHARE` of the candidate vertices: bigger passes
/// are faster but cost mean error (docs/design.md#qem-pass-share).
const PASS_SHARE: usize = 3;

/// Candidates whose data is requested from memory ahead of their turn.
const PREFETCH_AHEAD: usize = 4;

/// The kept vertex of a collapse: its edges are re-planned.
const REPLAN: u8 = 1;
/// A neighbour of a kept vertex: its blocked edges are released.
const RELEASE: u8 = 2;
/// A vertex with a newly blocked edge.
const RERANK: u8 = 4;

/// What one pass allows a collapse.
#[derive(Debug, Clone, Copy)]
struct PassBounds {
    /// The pass's highest cost: a candidate whose fresh cost is above it waits.
    threshold: f32,
    /// The squared error bound (`--max-error`).
    bound2: f64,
}

/// What became of a candidate.
enum Attempt {
    /// Collapsed, removing this many vertices (two on a seam: both sides), with this
    /// squared error.
    Collapsed(usize, f64),
    /// Waits for a later pass, was blocked, or has no edge to collapse.
    Skipped,
    /// Blocked because its collapse was legal but over the error bound.
    OverBound,
    /// Its neighbourhood reaches outside the part: left to the whole mesh.
    Elsewhere,
}

/// Where the whole mesh's run of a pass must stop: the removals still allowed by the
/// target and by the four-vertex floor, and the triangles to keep.
#[derive(Debug, Clone, Copy)]
struct Limit {
    remove: usize,
    removable: usize,
    keep_triangles: usize,
    /// End the pass one triangle over `keep_triangles`, for a pass of border edges only.
    end_one_over: bool,
}

/// What a run of candidates did.
#[derive(Debug, Default)]
struct Tally {
    removed: usize,
    max_error2: f64,
    /// Some collapse was legal but over the error bound.
    over_bound: bool,
    /// Candidates left to the whole mesh, in the order met.
    border: Vec<Candidate>,
    /// Stopped at the four-vertex floor.
    floor: bool,
}

/// Collapses edges of `d` until `limits` are met or nothing can go; `progress` gets the
/// running removal count.
pub(super) fn collapse_in_passes(
    d: &mut Collapser,
    limits: &Limits,
    progress: &mut dyn FnMut(usize),
) -> Outcome {
    let n = d.vertex_count() as u32;
    let mut outcome = Outcome::nothing_removed(limits.feature_angle_deg, 0);
    let bound2 = limits.max_error * limits.max_error;
    let removable = removable_count(d, limits);
    let regions =
        [false, true].map(|shifted| Regions::new(d.vertex_count(), d.conn.triangles(), shifted));
    let mut skipped_for_error = false;
    let mut live: Vec<u32> = (0..n).into_par_iter().collect();
    // The lists are kept from pass to pass and edited in place: a fresh list each pass
    // costs more in first-touch page faults than filling it does.
    let mut all_candidates: Vec<Candidate> = Vec::new();
    let (mut pass, mut tied) = (Vec::new(), Vec::new());
    let mut flagged = Flagged::default();
    let mut in_pass = vec![0u64; (n as usize).div_ceil(64)];
    // Cleared when a pass of border edges only removed nothing: it is not tried again.
    let mut border_only = true;
    while !limits.cancel.requested() {
        let count = gather_candidates(d, &mut live, &mut all_candidates);
        if count == 0 {
            outcome.exhausted = !skipped_for_error;
            break;
        }
        // One triangle over a triangle count: only a collapse of an open border's edge (in
        // one triangle) lands on it, so the pass takes those when there are any.
        let one_over = border_only
            && limits.keep_triangles > 0
            && d.conn.triangle_count() == limits.keep_triangles + 1;
        let count = match one_over {
            true => match border_edges_first(&d.conn, &d.best, &mut all_candidates[..count]) {
                0 => count,
                border => border,
            },
            false => count,
        };
        let candidates = &all_candidates[..count];
        let over = d
            .conn
            .triangle_count()
            .saturating_sub(limits.keep_triangles);
        let limit = Limit {
            remove: limits.remove.saturating_sub(outcome.removed),
            removable: removable.saturating_sub(outcome.removed),
            keep_triangles: limits.keep_triangles,
            end_one_over: border_only && !one_over && limits.keep_triangles > 0,
        };
        let needed = limit.remove.min(limit.removable).min(over.div_ceil(2));
        let take = (candidates.len() / PASS_SHARE)
            .min(2 * needed)
            .clamp(1, candidates.len());
        cheapest(candidates, take, &mut pass, &mut tied);
        let bounds = PassBounds {
            threshold: pass[take - 1].cost(),
            bound2,
        };
        drop_mutual_duplicates(&mut pass, &d.best, &mut in_pass);
        let mut tally = Tally::default();
        let stopped = collapse_pass(d, &regions, &pass, bounds, limit, &mut tally);
        outcome.removed += tally.removed;
        outcome.max_error = outcome.max_error.max(tally.max_error2.sqrt());
        outcome.exhausted |= tally.floor;
        skipped_for_error |= tally.over_bound;
        border_only &= !(one_over && tally.removed == 0);
        progress(outcome.removed);
        if stopped {
            break;
        }
        end_of_pass(&mut d.whole(), &live, &mut flagged);
    }
    progress(outcome.removed);
    outcome
}

/// How many vertices the passes may remove: never fewer than four are left (a model under
/// four is dropped from the scene, and a plane's two triangles or a tetrahedron is as far
/// as collapsing should go), a seam's copies counted once.
fn removable_count(d: &Collapser, limits: &Limits) -> usize {
    let used = (0..d.vertex_count() as u32)
        .into_par_iter()
        .filter(|&v| !d.conn.incident(v).is_empty())
        .count();
    (used.saturating_sub(limits.seam_copies)).saturating_sub(MIN_VERTICES)
}

/// Drops the fixed vertices from `live` and lists the others with a finite best cost as
/// candidates in `all` (kept from pass to pass); returns how many.
fn gather_candidates(d: &Collapser, live: &mut Vec<u32>, all: &mut Vec<Candidate>) -> usize {
    let kinds = &d.kinds;
    lists::retain(live, |v| kinds[v as usize] != Kind::Fixed);
    let best_cost = &d.best_cost;
    lists::filter_map_into(live, all, |&v| {
        let cost = best_cost[v as usize];
        cost.is_finite().then(|| Candidate::new(cost, v))
    })
}

/// Moves the candidates whose best edge lies on an open border (in one triangle: its
/// collapse takes one) to the front of `candidates`; returns how many.
fn border_edges_first(conn: &Connectivity, best: &[u32], candidates: &mut [Candidate]) -> usize {
    move_to_front(candidates, |c| {
        let v = c.vertex();
        let w = best[v as usize];
        let with_w = conn
            .incident(v)
            .iter()
            .filter(|&&t| conn.triangle(t).contains(&w));
        with_w.count() == 1
    })
}

/// Drops from `pass` (in cost order) the larger end of every edge that is the cheapest of
/// both its ends (`best`) when both are in the pass: the second try would only find its other
/// end gone, or fail as the first did (docs/design.md#qem-mutual-edges). The smaller end must
/// be in the pass: its cost may be stale (see `end_of_pass`), and a pass that dropped its only
/// try would make no progress. `in_pass` is a bit per vertex, all clear, and left so.
fn drop_mutual_duplicates(pass: &mut Vec<Candidate>, best: &[u32], in_pass: &mut [u64]) {
    let bit = |v: u32| ((v / 64) as usize, 1u64 << (v % 64));
    for c in pass.iter() {
        let (word, mask) = bit(c.vertex());
        in_pass[word] |= mask;
    }
    pass.retain(|c| {
        let v = c.vertex();
        let w = best[v as usize];
        // `w < v`: a vertex, not the no-edge mark.
        let mutual = w < v && best.get(w as usize) == Some(&v);
        !(mutual && {
            let (word, mask) = bit(w);
            in_pass[word] & mask != 0
        })
    });
    in_pass.fill(0);
}

/// Collapses the pass's `candidates` (in cost order) within `limit`, adding what became of
/// them to `tally`; returns true when a limit stopped it. Rounds of the cheapest candidates
/// run in regions while a round cannot reach a limit (each collapse removes one vertex and
/// at most two triangles); the rest runs on the whole mesh, one candidate at a time.
fn collapse_pass(
    d: &mut Collapser,
    regions: &[Regions; 2],
    candidates: &[Candidate],
    bounds: PassBounds,
    limit: Limit,
    tally: &mut Tally,
) -> bool {
    let in_regions = regions[0].count() > 1 && d.recorder.is_none() && d.distance.is_none();
    let mut rest = candidates;
    while in_regions && !rest.is_empty() {
        let over = d.conn.triangle_count().saturating_sub(limit.keep_triangles);
        // A seam collapse removes one position (two vertices) and two triangles, one a side.
        let budget = (limit.remove.min(limit.removable))
            .saturating_sub(tally.removed)
            .min(over.div_ceil(2));
        let size = round_size(candidates.len(), rest.len(), budget);
        if size == 0 {
            break;
        }
        let (chunk, tail) = rest.split_at(size);
        let border = collapse_in_regions(d, &regions[0], chunk, bounds, tally);
        let border = collapse_in_regions(d, &regions[1], &border, bounds, tally);
        let mut whole = d.whole();
        collapse_in_order(&mut whole, &border, bounds, None, tally);
        let removed = whole.conn.finish();
        d.conn.retire(&removed);
        rest = tail;
    }
    let mut whole = d.whole();
    let stopped = collapse_in_order(&mut whole, rest, bounds, Some(limit), tally);
    let removed = whole.conn.finish();
    d.conn.retire(&removed);
    stopped
}

/// Runs the pass's `candidates` (in cost order) in regions on all cores, adding what they
/// did to `tally`; returns the candidates on borders, in cost order, for the whole mesh.
fn collapse_in_regions(
    d: &mut Collapser,
    regions: &Regions,
    candidates: &[Candidate],
    bounds: PassBounds,
    tally: &mut Tally,
) -> Vec<Candidate> {
    let per_region = regions.distribute(candidates);
    let parts = d.split(&regions.vertex_starts, &regions.slot_starts);
    let results: Vec<_> = parts
        .into_par_iter()
        .zip(per_region)
        .map(|(mut part, mine)| {
            let mut tally = Tally::default();
            collapse_in_order(&mut part, &mine, bounds, None, &mut tally);
            (tally, part.conn.finish(), part.closed.into_changes())
        })
        .collect();
    let mut border = Vec::new();
    for (region, freed, volumes) in results {
        d.absorb_volume_changes(volumes);
        tally.removed += region.removed;
        tally.max_error2 = tally.max_error2.max(region.max_error2);
        tally.over_bound |= region.over_bound;
        border.extend(region.border);
        d.conn.retire(&freed);
    }
    border.sort_unstable();
    border
}

/// Tries `candidates` in order on `part`, adding what became of them to `tally`; with a
/// `limit`, stops where it says (returns true then).
fn collapse_in_order(
    part: &mut Part<'_>,
    candidates: &[Candidate],
    bounds: PassBounds,
    limit: Option<Limit>,
    tally: &mut Tally,
) -> bool {
    for (i, &candidate) in candidates.iter().enumerate() {
        prefetch_ahead(part, candidates, i);
        if let Some(limit) = limit {
            if tally.removed >= limit.remove || part.conn.triangle_count() <= limit.keep_triangles {
                return true;
            }
            if tally.removed >= limit.removable {
                tally.floor = true;
                return true;
            }
            if limit.end_one_over && part.conn.triangle_count() == limit.keep_triangles + 1 {
                return false;
            }
        }
        // Vertices the limit still allows: a seam collapse needs two.
        let room = limit.map_or(usize::MAX, |l| {
            l.remove.min(l.removable).saturating_sub(tally.removed)
        });
        match attempt(part, candidate.vertex(), bounds, room) {
            Attempt::Collapsed(removed, error2) => {
                tally.removed += removed;
                tally.max_error2 = tally.max_error2.max(error2);
            }
            Attempt::OverBound => tally.over_bound = true,
            Attempt::Elsewhere => tally.border.push(candidate),
            Attempt::Skipped => {}
        }
    }
    false
}

/// Asks for the data of the candidates ahead, in four stages: a candidate's own data, then
/// (once its cheapest edge is loaded) the other end's, then (once both incident lists are
/// loaded) their fans, then (once the fans' triangles are loaded) their neighbours'
/// positions and the incident lists of the edge's apexes.
fn prefetch_ahead(part: &Part<'_>, candidates: &[Candidate], i: usize) {
    let best = |v: u32| part.local(v).map_or(u32::MAX, |i| part.best[i]);
    let vertex_at = |j: usize| candidates.get(j).map(|c| c.vertex());
    // Most candidates that will be skipped are known by now (the other end went earlier in
    // the pass): nothing past their first loads is asked for.
    let pair_at = |j: usize| {
        let v = vertex_at(j)?;
        let w = best(v);
        (part.owns(w) && !part.is_fixed(w)).then_some((v, w))
    };
    if let Some(ahead) = vertex_at(i + 3 * PREFETCH_AHEAD) {
        part.prefetch(ahead);
    }
    if let Some(ahead) = vertex_at(i + 2 * PREFETCH_AHEAD) {
        part.prefetch(best(ahead));
    }
    if let Some((v, w)) = pair_at(i + PREFETCH_AHEAD) {
        // A collapse reads no edge costs (blocking one is rare).
        part.prefetch_fan(v, false);
        part.prefetch_fan(w, false);
    }
    if let Some((v, w)) = pair_at(i + PREFETCH_AHEAD / 2) {
        part.prefetch_neighbourhood(v, w);
    }
}

/// Re-plans candidate `v`'s cheapest edge and collapses it when it is still within the
/// pass's threshold, legal and within the error bound (and `room`, the vertices the limit
/// still allows, takes a seam's two); blocks it when it is not.
fn attempt(d: &mut Part<'_>, v: u32, bounds: PassBounds, room: usize) -> Attempt {
    let w = d.best[d.at(v)];
    if w == u32::MAX || d.is_fixed(v) {
        return Attempt::Skipped;
    }
    // Most skips are here: the best edge's other end went earlier in this pass (it is
    // re-ranked at the pass's end). Fixed is for good: asked before the ownership walk.
    if d.owns(w) && d.is_fixed(w) {
        return Attempt::Skipped;
    }
    // An edge off the outline and off seams is planned from its ends alone: one whose end
    // took a collapse in this pass and now costs over the threshold waits without its fans
    // being read (docs/design.md#qem-mutual-edges).
    // An LT plan reads the fans: never early.
    let early =
        (!d.lt && d.owns(w) && d.twins.is_empty() && plans_without_fans(d.kind(v), d.kind(w)))
            .then(|| d.plan(v.min(w), v.max(w)));
    if early.is_some_and(|p| p.is_some_and(|p| stored(p.cost) > bounds.threshold)) {
        return Attempt::Skipped;
    }
    if !d.gather(v, w) || !gather_seam_sides(d, v, w) {
        return Attempt::Elsewhere;
    }
    let mut plan = early.unwrap_or_else(|| d.plan(v.min(w), v.max(w)));
    if let Some(p) = plan.as_mut() {
        d.join_junction(p);
    }
    // A junction copy left with no triangle goes too; a progressive record cannot bring
    // back a vertex that is in no base triangle, so it keeps such collapses out.
    let drops = plan.is_some_and(|p| d.drops_junction_copy(&p));
    // Asked before anything is decided: a collapse this part cannot judge goes elsewhere.
    let Some(welded) = plan.map_or(Some(true), |p| seam_stays_manifold(d, &p)) else {
        return Attempt::Elsewhere;
    };
    if !plan.is_none_or(|p| owns_seam_neighbours_twins(d, &p)) {
        return Attempt::Elsewhere;
    }
    if let Some(p) = plan.filter(|p| stored(p.cost) > bounds.threshold) {
        wait_over_threshold(d, v, w, &p);
        return Attempt::Skipped;
    }
    // No plan (the edge's shape changed since it was planned) counts as illegal, so that
    // every candidate either goes, waits or is blocked: each pass progresses. Counts are
    // of positions: a seam's two sides are one, a dropped junction copy none.
    let removes = 1;
    let fits = plan.is_some() && room >= removes && !(drops && d.recorder.is_some());
    let legal =
        fits && welded && plan.is_some_and(|p| d.is_collapse_legal(&p) && twin_is_legal(d, &p));
    let Some(plan) = plan.filter(|p| legal && p.error2 <= bounds.bound2 && d.within_distance(p))
    else {
        // The cost weighs area and colour, not just the error: an edge over the bound is
        // skipped like an illegal one, until its neighbourhood changes.
        block(d, v, w, plan.and_then(|p| p.twin));
        return if legal {
            Attempt::OverBound
        } else {
            Attempt::Skipped
        };
    };
    collapse_with_sides(d, &plan);
    d.commit_distance();
    Attempt::Collapsed(removes, plan.error2)
}

/// A candidate whose edge now costs over the pass's threshold waits. An end took a collapse
/// in this pass: re-planned at its end. On a seam it may have been the other side's end,
/// which re-plans that side's edges only: both ends look again (the other end may have been
/// dropped from the pass as a duplicate).
fn wait_over_threshold(d: &mut Part<'_>, v: u32, w: u32, p: &Plan) {
    if p.twin.is_some() {
        for x in [v, w] {
            let i = d.at(x);
            d.flags[i] |= RERANK;
        }
    }
    // Otherwise the cost changed with no collapse at either end (a complex end made
    // manifold, see `Part::settle_complex`): `v` re-plans, or the next pass is this one.
    let (iv, iw) = (d.at(v), d.at(w));
    if (d.flags[iv] | d.flags[iw]) & REPLAN == 0 {
        d.flags[iv] |= REPLAN;
    }
}

/// Blocks edge `v`–`w` (and its seam twin) until its neighbourhood changes.
fn block(d: &mut Part<'_>, v: u32, w: u32, twin: Option<[u32; 2]>) {
    for (x, y) in [(v, w)].into_iter().chain(twin.map(|[a, b]| (a, b))) {
        d.block_edge(x, y);
        let (ix, iy) = (d.at(x), d.at(y));
        d.flags[ix] |= RERANK;
        d.flags[iy] |= RERANK;
    }
}

/// Collapses `plan` (and its seam twin on the other side), flagging for re-planning what
/// the collapse made dearer.
fn collapse_with_sides(d: &mut Part<'_>, plan: &Plan) {
    collapse_and_flag(d, plan);
    if let Some(twin) = plan.other_side() {
        d.swap_sides();
        collapse_and_flag(d, &twin);
        d.swap_sides();
    } else if let Some(k2) = d.twin(plan.keep) {
        // An interior vertex went into a seam vertex, which stays put; its quadric grew,
        // and with it the cost of the seam edges on the other side.
        let i = d.at(k2);
        d.flags[i] |= REPLAN;
    }
    if d.kind(plan.keep) == Kind::Anchored {
        // A junction's quadric grew: so did the cost of collapsing the seams that leave its
        // other copies, planned from the twins of those leaving this one (a superset).
        let twins: Vec<u32> = d.seam_neighbours_twins(plan.twin.is_some()).collect();
        for x in twins {
            let i = d.at(x);
            d.flags[i] |= REPLAN;
        }
    }
    if let Some(c) = plan.junction {
        // Its triangle with the removed end went: its edges are planned again.
        let i = d.at(c);
        d.flags[i] |= REPLAN;
    }
}

/// Whether `Part::plan` decides an edge between vertices of these kinds without counting
/// the edge's triangles: when one end is interior (the edge is inside the surface).
fn plans_without_fans(a: Kind, b: Kind) -> bool {
    a == Kind::Interior || b == Kind::Interior
}

/// For a collapse of `v`–`w` near a texture seam, reads the other side's fans (both ends
/// have twins) or checks the part owns the one twin (whose edges it re-plans): false when
/// that is outside the part. The whole owns everything.
fn gather_seam_sides(d: &mut Part<'_>, v: u32, w: u32) -> bool {
    match (d.twin(v), d.twin(w)) {
        (None, None) => true,
        // Read now, while nothing has changed; `plan` decides whether they collapse.
        (Some(v2), Some(w2)) => d.owns(v2) && d.owns(w2) && d.gather_twin(v2, w2),
        // Into a junction: the other side's edge ends at the junction's copy there.
        (Some(v2), None) if d.kind(w) == Kind::Anchored => match d.anchor_copy(v2, w) {
            Some(Some(w2)) => d.gather_twin(v2, w2),
            Some(None) => true,
            None => false,
        },
        (None, Some(w2)) if d.kind(v) == Kind::Anchored => match d.anchor_copy(w2, v) {
            Some(Some(v2)) => d.gather_twin(v2, w2),
            Some(None) => true,
            None => false,
        },
        (Some(x), None) | (None, Some(x)) => d.owns(x),
    }
}

/// Whether the part owns the other side of every seam vertex around a collapse into a
/// junction (`keep` anchored): those hold costs of seam collapses into the junction's other
/// copies, which count the junction's quadric, and are re-planned (see [`attempt`]).
fn owns_seam_neighbours_twins(d: &Part<'_>, plan: &Plan) -> bool {
    d.kind(plan.keep) != Kind::Anchored
        || d.seam_neighbours_twins(plan.twin.is_some())
            .all(|x| d.owns(x))
}

/// Whether a seam collapse's other side (read by [`gather_seam_sides`]) is legal too: the
/// two sides' neighbourhoods apart and the collapse legal there.
fn twin_is_legal(d: &mut Part<'_>, plan: &Plan) -> bool {
    let Some(twin) = plan.other_side() else {
        return true;
    };
    if !d.sides_apart() {
        return false;
    }
    d.swap_sides();
    let legal = d.is_collapse_legal(&twin);
    d.swap_sides();
    legal
}

/// Whether a collapse keeps the surface manifold once its seams are closed (welded, as a
/// viewer shows it): every edge it makes to the kept end must have as many triangles
/// welded as it will have on its side (two inside, one on the outline, doubled with a seam
/// collapse's other side). So no other copy of the kept end (its twin across a seam, a
/// junction's other copies) may be joined already to a copy of a new neighbour; and with
/// a seam collapse, the copies of a new neighbour inside one side must not reach the other
/// side's collapse, whose kept end could be joined to them too. (That kept end is joined
/// already to the copies of the new neighbours on the outline, its edge's apexes: the other
/// side's own link condition judges those.) Only a collapse into a vertex with copies can
/// make such an edge. `None` when a copy's fan is outside the part.
fn seam_stays_manifold(d: &mut Part<'_>, plan: &Plan) -> Option<bool> {
    if d.twins.is_empty() && d.copies.is_empty() {
        return Some(true);
    }
    let keeps = [plan.keep, plan.twin.map_or(plan.keep, |[_, k2]| k2)];
    let seam = plan.twin.is_some();
    let here = side_stays_manifold(d, plan, keeps, seam)?;
    let Some(twin) = plan.other_side() else {
        return Some(here);
    };
    d.swap_sides();
    let there = side_stays_manifold(d, &twin, keeps, seam);
    d.swap_sides();
    Some(here && there?)
}

/// [`seam_stays_manifold`] on the side whose fans the scratch holds (`keeps`: both sides'
/// kept ends; `seam`: a seam collapse, whose other side's fans are the scratch's other ones).
fn side_stays_manifold(d: &Part<'_>, plan: &Plan, keeps: [u32; 2], seam: bool) -> Option<bool> {
    for (x, inside) in new_neighbours(d, plan) {
        for y in d.copies(x) {
            if seam && inside && y != x && d.other_side_touches(y) {
                return Some(false);
            }
            // The kept end itself may not be joined to another copy of its new neighbour.
            let other = |c: &u32| !keeps.contains(c) || (*c == plan.keep && y != x);
            for c in d.copies(plan.keep).filter(other) {
                if d.joined(c, y)? {
                    return Some(false);
                }
            }
        }
    }
    Some(true)
}

/// The removed end's neighbours that become the kept end's, each with whether its edge to
/// the kept end will be inside the surface (two triangles; otherwise on the outline); each
/// once per triangle it is in.
fn new_neighbours<'a>(d: &'a Part<'_>, plan: &Plan) -> impl Iterator<Item = (u32, bool)> + 'a {
    let (fan_r, fan_k) = d.fans(plan);
    let (keep, remove) = (plan.keep, plan.remove);
    // Across a junction (`Part::join_junction`) an apex may be joined to the other copy
    // only: it is the kept point's neighbour already.
    let apex = move |x: u32| fan_r.iter().any(|f| f.touches(keep) && f.touches(x));
    let junction = plan.junction.is_some();
    fan_r
        .iter()
        .filter(move |f| !f.touches(keep))
        .flat_map(|f| [f.next, f.prev])
        .filter(move |&x| x != remove && !fan_k.iter().any(|g| g.touches(x)))
        .filter(move |&x| !(junction && apex(x)))
        .map(move |x| (x, fan_r.iter().filter(|f| f.touches(x)).count() == 2))
}

/// Performs the legal `plan` (its fans read into the scratch) and flags what the end of the
/// pass looks at again: the kept vertex and its neighbours after the collapse (the corners
/// of both fans' triangles off the edge).
fn collapse_and_flag(d: &mut Part<'_>, plan: &Plan) {
    let k = d.at(plan.keep);
    d.flags[k] |= REPLAN;
    let (fan_r, fan_k) = d.scratch.fans(plan);
    // The edge's apexes too: a doubled flap's apex is in no other triangle of either fan.
    for fan in [fan_r, fan_k] {
        for f in fan {
            for x in [f.next, f.prev] {
                d.flags[(x - d.v0) as usize] |= RELEASE;
            }
        }
    }
    if let Some(c) = d.closed.component(plan.remove) {
        let change = d.checked_volume_change(plan);
        d.closed.apply(c, change);
    }
    d.collapse(plan);
    if d.lt {
        flag_lt_neighbourhood(d, plan.keep);
    }
    // A complex vertex made manifold collapses freely from now on: its edges are re-planned,
    // and its neighbours whose cheapest edge it is look again (that edge's cost changed).
    for j in 0..d.scratch.settled.len() {
        let x = d.scratch.settled[j];
        let i = d.at(x);
        d.flags[i] |= REPLAN;
        for k in 0..d.conn.incident(x).len() {
            for w in others(d.conn.triangle(d.conn.incident(x)[k]), x) {
                if let Some(i) = d.local(w) {
                    d.flags[i] |= RELEASE;
                }
            }
        }
    }
}

/// Under the LT cost, which reads the triangles around both ends of an edge: the kept
/// vertex's neighbours re-plan their edges too (every edge with an end there changed its
/// star), and their neighbours look again for their cheapest edge.
fn flag_lt_neighbourhood(d: &mut Part<'_>, keep: u32) {
    for k in 0..d.conn.incident(keep).len() {
        let t = d.conn.incident(keep)[k];
        for x in others(d.costs.corners(t), keep) {
            let Some(i) = d.local(x) else { continue };
            d.flags[i] |= REPLAN;
            for j in 0..d.conn.incident(x).len() {
                let u = d.conn.incident(x)[j];
                for y in others(d.costs.corners(u), x) {
                    if let Some(i) = d.local(y) {
                        d.flags[i] |= RELEASE;
                    }
                }
            }
        }
    }
}

/// The lists of the vertices [`end_of_pass`] looks at again, kept from pass to pass: all of
/// them, the kept ones and the others.
#[derive(Debug, Default)]
struct Flagged {
    all: Vec<u32>,
    keeps: Vec<u32>,
    others: Vec<u32>,
}

/// The work deferred to the end of a pass, in vertex order (memory order): the kept
/// vertices' edges are planned again (which gives them their cheapest edge), then every
/// other flagged vertex looks for its cheapest edge again (after unblocking its edges when
/// its neighbourhood changed), both on all cores.
fn end_of_pass(d: &mut Part<'_>, live: &[u32], lists: &mut Flagged) {
    let flag = |d: &Part<'_>, v: u32| d.flags[d.at(v)];
    // A neighbour whose cheapest edge kept both its ends keeps that edge's cost, and its
    // edges to kept vertices only got dearer (a quadric only grows; a placement outside the
    // edge's box or the colour term can bend that, which leaves the order a little less
    // greedy): it need not look again. Asked before anything is re-planned: re-planning
    // writes the kept vertices' best edges and blocked marks, which this reads.
    let unchanged = |d: &Part<'_>, v: u32| {
        let i = d.at(v);
        let w = d.best[i];
        d.flags[i] == RELEASE
            && !d.has_blocked[i]
            && w != u32::MAX
            && !d.is_fixed(w)
            && flag(d, w) & REPLAN == 0
    };
    let this = &*d;
    let Flagged { all, keeps, others } = lists;
    let count = lists::filter_map_into(live, all, |&v| {
        (flag(this, v) != 0 && !this.is_fixed(v) && !unchanged(this, v)).then_some(v)
    });
    let all = &all[..count];
    // The kept vertices are all flagged (REPLAN is never unchanged).
    let kept = lists::filter_map_into(all, keeps, |&v| (flag(this, v) & REPLAN != 0).then_some(v));
    let other =
        lists::filter_map_into(all, others, |&v| (flag(this, v) & REPLAN == 0).then_some(v));
    d.replan(&keeps[..kept]);
    d.rerank(&others[..other], RELEASE);
    d.flags.fill(0);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mutual_cheapest_edge_is_tried_once_from_its_smaller_end() {
        // 0 and 3 are each other's cheapest edge, as are 4 and 5; 1's is 3 (not mutual),
        // 2 has none, 6's is 4 (whose own is 5).
        let best = [3, 3, u32::MAX, 0, 5, 4, 4];
        let mut pass: Vec<Candidate> = [(1.0, 0), (1.0, 3), (2.0, 1), (2.5, 2), (3.0, 4)]
            .into_iter()
            .chain([(3.0, 5), (4.0, 6)])
            .map(|(cost, v)| Candidate::new(cost, v))
            .collect();
        let mut in_pass = vec![0u64; 1];
        drop_mutual_duplicates(&mut pass, &best, &mut in_pass);
        let kept: Vec<u32> = pass.iter().map(|c| c.vertex()).collect();
        assert_eq!(
            kept,
            [0, 1, 2, 4, 6],
            "in cost order, each mutual pair once"
        );
        assert_eq!(in_pass, [0], "left clear");
        // A pass holding only the larger end (the smaller one's cost is stale, higher)
        // keeps it: a pass must try something.
        let mut pass = vec![Candidate::new(1.0, 3)];
        drop_mutual_duplicates(&mut pass, &best, &mut in_pass);
        assert_eq!(pass.len(), 1);
    }
}

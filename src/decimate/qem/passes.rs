//! The collapse loop, in passes over the cheapest edges.
//!
//! A strict greedy loop re-ranks the neighbours of every collapse in a priority queue, one
//! at a time; on a scan that is several times the work of the collapse itself. Instead,
//! each pass takes the cheapest `1/PASS_SHARE` of the vertices' best edges (never more than
//! twice what the target still needs), sorts them and collapses them in order, each
//! re-planned first: a
//! collapse whose fresh cost is above the pass's threshold waits for the next pass, so no
//! collapse ever costs more than the threshold of the pass that made it. Re-planning is
//! deferred to the end of the pass: the kept vertices' edges are planned again (on all
//! cores), the neighbours' blocked edges are released and every touched vertex re-picks its
//! cheapest edge. Within a pass the order is the cached one; across passes the thresholds
//! rise, so the sequence stays close to greedy (see `PASS_SHARE`).

use super::collapser::{Collapser, Kind};
use super::ranking::stored;
use crate::decimate::schroeder::{Limits, Outcome};

/// One pass takes the cheapest `1 / PASS_SHARE` of the candidate vertices. On the dragon
/// kept at 10 % (metro mean / max, time of the whole decimation on 2 cores): the greedy
/// queue this replaced 9.15e-6 / 2.39e-4 in 2.9 s; 16: 9.16e-6 / 2.41e-4, 2.1 s; 8:
/// 9.16e-6 / 2.39e-4, 1.9 s; 4: 9.16e-6 / 2.39e-4, 1.7 s; 3: 9.15e-6 / 3.28e-4, 1.6 s;
/// 2: 9.18e-6 / 3.14e-4, 1.4 s; 1 (one sort, greedy with stale costs): 1.17e-5, 1.3 s.
/// Larger passes are cheaper because a vertex kept several times in a pass is re-planned
/// once.
const PASS_SHARE: usize = 3;

/// Candidates whose data is requested from memory ahead of their turn.
const PREFETCH_AHEAD: usize = 4;

/// The kept vertex of a collapse: its edges are re-planned.
const REPLAN: u8 = 1;
/// A neighbour of a kept vertex: its blocked edges are released.
const RELEASE: u8 = 2;
/// A vertex with a newly blocked edge.
const RERANK: u8 = 4;

/// Collapses edges of `d` until `limits` are met or nothing can go; `progress` gets the
/// running removal count.
pub(super) fn collapse_in_passes(
    d: &mut Collapser,
    limits: &Limits,
    progress: &mut dyn FnMut(usize),
) -> Outcome {
    let n = d.vertex_count() as u32;
    let mut outcome = Outcome {
        removed: 0,
        max_error: 0.0,
        exhausted: false,
        feature_angle_deg: limits.feature_angle_deg,
    };
    let bound2 = limits.max_error * limits.max_error;
    // Never fewer than four vertices: a model under four is dropped from the scene, and a
    // plane's two triangles or a tetrahedron is as far as collapsing should go.
    let used = (0..n).filter(|&v| !d.conn.incident(v).is_empty()).count();
    let removable = used.saturating_sub(4);
    let mut skipped_for_error = false;
    let mut live: Vec<u32> = (0..n)
        .filter(|&v| d.kinds[v as usize] != Kind::Fixed)
        .collect();
    // What each vertex needs at the end of the pass; read and cleared only for `live` ones.
    let mut flags = vec![0u8; n as usize];
    let mut candidates: Vec<(f32, u32)> = Vec::new();
    let by_cost = |a: &(f32, u32), b: &(f32, u32)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
    'passes: loop {
        live.retain(|&v| d.kinds[v as usize] != Kind::Fixed);
        candidates.clear();
        candidates.extend(live.iter().filter_map(|&v| {
            let cost = d.best_cost[v as usize];
            cost.is_finite().then_some((cost, v))
        }));
        if candidates.is_empty() {
            outcome.exhausted = !skipped_for_error;
            break;
        }
        let over = d
            .conn
            .triangle_count()
            .saturating_sub(limits.keep_triangles);
        let needed = limits
            .remove
            .saturating_sub(outcome.removed)
            .min(removable.saturating_sub(outcome.removed))
            .min(over.div_ceil(2));
        let take = (candidates.len() / PASS_SHARE)
            .min(2 * needed)
            .clamp(1, candidates.len());
        if take < candidates.len() {
            candidates.select_nth_unstable_by(take - 1, by_cost);
            candidates.truncate(take);
        }
        candidates.sort_unstable_by(by_cost);
        let threshold = candidates[take - 1].0;
        for (i, &(_, v)) in candidates.iter().enumerate() {
            // Three stages: a candidate's own data, then (once its cheapest edge is loaded)
            // the other end's, then (once both incident lists are loaded) their fans.
            if let Some(&(_, ahead)) = candidates.get(i + 3 * PREFETCH_AHEAD) {
                d.prefetch(ahead);
            }
            if let Some(&(_, ahead)) = candidates.get(i + 2 * PREFETCH_AHEAD) {
                d.prefetch(d.best[ahead as usize]);
            }
            if let Some(&(_, ahead)) = candidates.get(i + PREFETCH_AHEAD) {
                d.prefetch_fan(ahead);
                d.prefetch_fan(d.best[ahead as usize]);
            }
            if outcome.removed >= limits.remove || d.conn.triangle_count() <= limits.keep_triangles
            {
                break 'passes;
            }
            if outcome.removed >= removable {
                outcome.exhausted = true;
                break 'passes;
            }
            let w = d.best[v as usize];
            let dead = |x: u32| d.kinds[x as usize] == Kind::Fixed;
            if w == u32::MAX || dead(v) || dead(w) {
                continue;
            }
            let plan = d.plan(v.min(w), v.max(w));
            if plan.is_some_and(|p| stored(p.cost) > threshold) {
                continue; // an end took a collapse in this pass: re-planned at its end
            }
            // No plan (the edge's shape changed since it was planned) counts as illegal, so
            // that every candidate either goes, waits or is blocked: each pass progresses.
            let legal = plan.is_some_and(|p| d.is_collapse_legal(&p));
            let Some(plan) = plan.filter(|p| legal && p.error2 <= bound2) else {
                // The cost weighs area and colour, not just the error: an edge over the
                // bound is skipped like an illegal one, until its neighbourhood changes.
                skipped_for_error |= legal;
                d.block_edge(v, w);
                flags[v as usize] |= RERANK;
                flags[w as usize] |= RERANK;
                continue;
            };
            d.collapse(&plan);
            flags[plan.keep as usize] |= REPLAN;
            for &t in d.conn.incident(plan.keep) {
                for x in d.conn.triangle(t) {
                    if x != plan.keep {
                        flags[x as usize] |= RELEASE;
                    }
                }
            }
            outcome.removed += 1;
            outcome.max_error = outcome.max_error.max(plan.error2.sqrt());
            if outcome.removed.is_multiple_of(4096) {
                progress(outcome.removed);
            }
        }
        end_of_pass(d, &live, &mut flags);
    }
    progress(outcome.removed);
    outcome
}

/// The work deferred to the end of a pass, in vertex order (memory order): the kept
/// vertices' edges are planned again, then every flagged vertex looks for its cheapest edge
/// again (after unblocking its edges when its neighbourhood changed), both on all cores.
fn end_of_pass(d: &mut Collapser, live: &[u32], flags: &mut [u8]) {
    let alive = |v: u32| d.kinds[v as usize] != Kind::Fixed;
    let flag = |v: u32| flags[v as usize];
    let kept = |v: u32| flag(v) & REPLAN != 0 && alive(v);
    let keeps: Vec<u32> = live.iter().copied().filter(|&v| kept(v)).collect();
    d.replan(&keeps, kept);
    let flagged: Vec<u32> = live
        .iter()
        .copied()
        .filter(|&v| flag(v) != 0 && alive(v))
        .collect();
    d.rerank(&flagged, |v| flag(v) & RELEASE != 0);
    for &v in live {
        flags[v as usize] = 0;
    }
}

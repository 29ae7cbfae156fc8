//! The cost cache of planned collapses and each vertex's cheapest edge.
//!
//! One entry per half-edge: entry `i` of triangle slot `t` is the edge from corner `i` to
//! corner `i + 1` (slots are never reused: collapses rename corners in place), stored beside
//! a copy of the slot's corners (see [`EdgeCosts`]; docs/design.md#qem-cost-cache). Both
//! entries of an edge lie in the fans of both its ends and hold the same cost, planned once,
//! always as `plan(min, max)`, so that whichever end plans it the value is the same. A
//! blocked entry (the collapse was illegal or over the error bound; cleared when the
//! neighbourhood changes) has its sign bit set.
//!
//! Entries are atomics so that ranking runs on every core: each fan is planned by one
//! thread, and two threads that meet on an edge write the same value. On x86 a relaxed
//! atomic load or store is a plain move.

use rayon::prelude::*;

use super::collapse_plan::others;
use super::part::Part;
use crate::mesh::topology::{corner_of, split_mut};

/// Fans longer than this are planned without sharing an edge's cost between its two slots.
const FAN_MEMO: usize = 24;

/// Vertices per rayon task: planning one fan takes well under a microsecond.
const MIN_PER_TASK: usize = 2048;

/// How many vertices ahead of its turn a vertex's data is asked for, per stage of
/// [`Part::pipelined`]: enough to overlap the cache misses (docs/design.md#qem-cost-cache).
const AHEAD: usize = 2;

/// The costs a fan planned so far, by their other end: each edge of a closed fan is in two
/// of its triangles, and is planned once.
struct FanMemo {
    ends: [(u32, f32); FAN_MEMO],
    len: usize,
    /// One bit per other end, by its id's low bits: an end's first slot skips the search.
    seen: u64,
}

impl Default for FanMemo {
    fn default() -> Self {
        Self {
            ends: [(u32::MAX, 0.0); FAN_MEMO],
            len: 0,
            seen: 0,
        }
    }
}

impl FanMemo {
    /// The cost of the edge to `w`: as planned before in this fan, or `plan()`'s, noted
    /// (while there is room).
    #[inline(always)]
    fn cost(&mut self, w: u32, plan: impl FnOnce() -> f32) -> f32 {
        let bit = 1u64 << (w & 63);
        let known = self.seen & bit != 0;
        self.seen |= bit;
        if known {
            if let Some(&(_, cost)) = self.ends[..self.len].iter().find(|m| m.0 == w) {
                return cost;
            }
        }
        let cost = plan();
        if self.len < FAN_MEMO {
            self.ends[self.len] = (w, cost);
            self.len += 1;
        }
        cost
    }
}

/// Whether an edge to `w` costing `cost` beats `best` (other end, cost) as a vertex's
/// cheapest edge: finite, cheaper, or as cheap to a smaller vertex. Every way of picking a
/// vertex's best edge uses this one order, so that they all pick the same.
#[inline(always)]
fn cheaper(w: u32, cost: f32, best: (u32, f32)) -> bool {
    cost.is_finite() && (cost < best.1 || (cost == best.1 && w < best.0))
}

/// A plan's cost as stored: f32, finite.
pub(super) fn stored(cost: f64) -> f32 {
    (cost as f32).min(f32::MAX)
}

impl Part<'_> {
    /// Calls `f(triangle slot, edge, other end)` for every half-edge on an edge of `v`: in
    /// each incident triangle, the edge leaving `v` and the edge coming into it.
    #[inline(always)]
    fn for_each_edge(&self, v: u32, mut f: impl FnMut(u32, usize, u32)) {
        for &t in self.conn.incident(v) {
            debug_assert_eq!(self.costs.corners(t), self.conn.triangle(t), "slot {t}");
            let (i, next, prev) = corner_of(self.costs.corners(t), v);
            const PREV: [usize; 3] = [2, 0, 1];
            f(t, i, next);
            f(t, PREV[i], prev);
        }
    }

    /// The stored cost of collapsing `a`–`b`: infinite when the kinds of its ends forbid it.
    fn edge_cost(&self, a: u32, b: u32) -> f32 {
        self.plan(a.min(b), a.max(b))
            .map_or(f32::INFINITY, |p| stored(p.cost))
    }

    /// Calls `f(v)` for each of `vertices` in order, first asking the CPU for each vertex's data in
    /// three stages, as each becomes addressable: its incident list `4 × AHEAD` vertices
    /// ahead, its triangles and edge costs `2 × AHEAD` ahead, and (with `ends`) what
    /// planning its edges reads of its neighbours `AHEAD` ahead. The loads then overlap
    /// instead of each fan waiting on three round trips to memory. Hints only: `f` sees the
    /// same data either way.
    fn pipelined(&self, vertices: &[u32], ends: bool, mut f: impl FnMut(u32)) {
        for (i, &v) in vertices.iter().enumerate() {
            if let Some(&a) = vertices.get(i + 4 * AHEAD) {
                self.conn.prefetch_incident(a);
            }
            if let Some(&a) = vertices.get(i + 2 * AHEAD) {
                self.prefetch_fan(a, true);
            }
            if ends {
                if let Some(&a) = vertices.get(i + AHEAD) {
                    // The corner after `a` in each triangle: every neighbour once in a
                    // closed fan.
                    for &t in self.conn.incident(a) {
                        self.prefetch_end(others(self.costs.corners(t), a)[0]);
                    }
                }
            }
            f(v);
        }
    }

    /// Plans every edge of `v` and stores each edge's cost in its slots, unblocked. Returns
    /// the cheapest, as [`Self::best_edge`] would pick it: its other end (`u32::MAX` when
    /// none) and cost.
    fn plan_fan(&self, v: u32) -> (u32, f32) {
        let mut best = (u32::MAX, f32::INFINITY);
        let mut memo = FanMemo::default();
        self.for_each_edge(v, |t, i, w| {
            let cost = memo.cost(w, || self.edge_cost(v, w));
            self.costs.set(t, i, cost);
            if cheaper(w, cost, best) {
                best = (w, cost);
            }
        });
        best
    }

    /// The cheapest unblocked edge of `v`: its other end (`u32::MAX` when none) and cost.
    pub fn best_edge(&self, v: u32) -> (u32, f32) {
        let mut best = (u32::MAX, f32::INFINITY);
        self.for_each_edge(v, |t, i, w| {
            if let Some(cost) = self.costs.get(t, i) {
                if cheaper(w, cost, best) {
                    best = (w, cost);
                }
            }
        });
        best
    }

    /// Plans every edge once and gives every vertex its cheapest edge, on all cores.
    ///
    /// An edge is planned from its smaller end. A task plans an ascending range of vertices
    /// in order, so a vertex finds its edges to smaller vertices of its own range planned
    /// already and reads their costs; only a vertex with a neighbour below its range looks
    /// at its edges again, once every range is done (docs/design.md#qem-cost-cache).
    pub fn rank_all(&mut self) {
        let best = std::mem::take(&mut self.best);
        let best_cost = std::mem::take(&mut self.best_cost);
        let this = &*self;
        let incomplete: Vec<Vec<u32>> = best
            .par_chunks_mut(MIN_PER_TASK)
            .zip(best_cost.par_chunks_mut(MIN_PER_TASK))
            .enumerate()
            .map(|(c, (best, best_cost))| {
                let lo = this.v0 + (c * MIN_PER_TASK) as u32;
                let range: Vec<u32> = (lo..lo + best.len() as u32).collect();
                let mut incomplete = Vec::new();
                this.pipelined(&range, true, |v| {
                    let (found, complete) = this.plan_fan_from(v, lo);
                    let i = (v - lo) as usize;
                    (best[i], best_cost[i]) = found;
                    if !complete {
                        incomplete.push(v);
                    }
                });
                incomplete
            })
            .collect();
        (self.best, self.best_cost) = (best, best_cost);
        self.rerank(&incomplete.concat(), 0);
    }

    /// Plans `v`'s edges to larger vertices and reads those to vertices from `lo` up to `v`
    /// (planned already), as [`Self::plan_fan`] does. Returns the cheapest of them, as
    /// [`Self::best_edge`] would pick it, and whether they were all of `v`'s edges.
    fn plan_fan_from(&self, v: u32, lo: u32) -> ((u32, f32), bool) {
        let mut best = (u32::MAX, f32::INFINITY);
        let mut complete = true;
        let mut memo = FanMemo::default();
        self.for_each_edge(v, |t, i, w| {
            let cost = if w > v {
                let cost = memo.cost(w, || self.edge_cost(v, w));
                self.costs.set(t, i, cost);
                cost
            } else if lo <= w && w < v {
                self.costs.get(t, i).unwrap_or(f32::INFINITY)
            } else {
                // Below the range: planned by another task, perhaps not yet. (`w == v`: a
                // degenerate triangle's, never collapsed.)
                complete &= w == v;
                return;
            };
            if cheaper(w, cost, best) {
                best = (w, cost);
            }
        });
        (best, complete)
    }

    /// Re-plans every edge of each of `vertices` (ascending; their quadrics or positions
    /// changed) and gives each its cheapest edge, on all cores. An edge between two of them
    /// is planned from both ends: each then knows all its costs without waiting for the
    /// other, and both store the same value.
    ///
    /// Every edge of the fan, in one batch at the end of the pass: a fan's plans do not depend
    /// on each other, so they overlap and the pipelined loads hide the misses. Re-planning at
    /// each collapse, or lazily, was slower (docs/design.md#qem-replan).
    pub fn replan(&mut self, vertices: &[u32]) {
        self.update_best(vertices, MIN_PER_TASK / 4, true, |this, v| {
            (this.plan_fan(v), true)
        });
    }

    /// Re-picks the cheapest edge of each of `vertices` (ascending) among all its edges,
    /// first unblocking every edge of those whose neighbourhood changed (a flag in
    /// `release` set), on all cores. The unblocking is finished before any vertex looks: an
    /// edge is in two fans.
    pub fn rerank(&mut self, vertices: &[u32], release: u8) {
        let this = &*self;
        let released = |v: u32| {
            let i = this.at(v);
            this.has_blocked[i] && this.flags[i] & release != 0
        };
        vertices
            .par_iter()
            .with_min_len(MIN_PER_TASK)
            .filter(|&&v| released(v))
            .for_each(|&v| this.unblock_fan(v));
        self.update_best(vertices, MIN_PER_TASK, false, |this, v| {
            (this.best_edge(v), this.flags[this.at(v)] & release != 0)
        });
    }

    /// Sets each of `vertices`' (ascending) cheapest edge to what `pick` finds, and clears
    /// its blocked mark when `pick` says its edges were all unblocked, `per_task` vertices
    /// to a task on all cores (`ends`: as [`Self::pipelined`]).
    fn update_best(
        &mut self,
        vertices: &[u32],
        per_task: usize,
        ends: bool,
        pick: impl Fn(&Self, u32) -> ((u32, f32), bool) + Sync,
    ) {
        // `vertices` ascend, so a chunk's lie from its first up to the next chunk's first:
        // the per-vertex arrays split there, and each chunk writes its own piece.
        debug_assert!(vertices.windows(2).all(|w| w[0] < w[1]));
        let chunks: Vec<&[u32]> = vertices.chunks(per_task).collect();
        let starts: Vec<usize> = chunks
            .iter()
            .enumerate()
            .map(|(c, chunk)| if c == 0 { 0 } else { self.at(chunk[0]) })
            .collect();
        let best = std::mem::take(&mut self.best);
        let best_cost = std::mem::take(&mut self.best_cost);
        let has_blocked = std::mem::take(&mut self.has_blocked);
        let pieces = split_mut(best, &starts)
            .into_iter()
            .zip(split_mut(best_cost, &starts))
            .zip(split_mut(has_blocked, &starts))
            .zip(starts.iter().zip(chunks));
        let this = &*self;
        pieces.collect::<Vec<_>>().into_par_iter().for_each(
            |(((best, best_cost), has_blocked), (&start, chunk))| {
                this.pipelined(chunk, ends, |v| {
                    let i = this.at(v) - start;
                    let ((w, cost), unblocked) = pick(this, v);
                    if unblocked {
                        has_blocked[i] = false;
                    }
                    best[i] = w;
                    best_cost[i] = cost;
                });
            },
        );
        (self.best, self.best_cost, self.has_blocked) = (best, best_cost, has_blocked);
    }

    /// Blocks the edge `v`–`w` until a neighbour of either end changes.
    pub fn block_edge(&mut self, v: u32, w: u32) {
        self.for_each_edge(v, |t, i, x| {
            if x == w {
                self.costs.block(t, i);
            }
        });
        let (iv, iw) = (self.at(v), self.at(w));
        self.has_blocked[iv] = true;
        self.has_blocked[iw] = true;
    }

    /// Unblocks every edge of `v`: its neighbourhood changed.
    fn unblock_fan(&self, v: u32) {
        self.for_each_edge(v, |t, i, _| self.costs.unblock(t, i));
    }
}

#[cfg(test)]
mod tests {
    use crate::decimate::qem::collapser::Collapser;
    use crate::mesh::shapes;

    #[test]
    fn ranking_gives_every_vertex_its_cheapest_edge_across_task_ranges() {
        // Many task ranges, renumbered along the Morton curve as a decimation does: vertices
        // on a range's edge have neighbours in earlier ranges, planned by other tasks.
        let mut d = Collapser::from_model(&shapes::bumpy_sphere(80, 160));
        let n = d.vertex_count();
        assert!(n > 6 * super::MIN_PER_TASK, "{n} vertices");
        let mut whole = d.whole();
        whole.rank_all();
        let mut with_edge = 0;
        for v in 0..n as u32 {
            let i = v as usize;
            // A fresh look at every slot, as each pass's re-ranking takes it.
            let (w, cost) = whole.best_edge(v);
            assert_eq!((whole.best[i], whole.best_cost[i]), (w, cost), "vertex {v}");
            with_edge += usize::from(w != u32::MAX);
            // And every edge was planned: its stored cost is what planning it gives.
            if w != u32::MAX {
                assert_eq!(cost, whole.edge_cost(v, w), "edge {v}–{w}");
            }
        }
        assert_eq!(with_edge, n, "a closed surface: every vertex has an edge");
    }
}

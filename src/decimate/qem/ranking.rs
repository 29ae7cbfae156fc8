//! The cost cache of planned collapses and each vertex's cheapest edge.
//!
//! One entry per half-edge slot: slot `3t + i` is the edge from corner `i` to corner
//! `i + 1` of triangle slot `t` (slots are never reused: collapses rename corners in
//! place). Both slots of an edge lie in the fans of both its ends and hold the same cost,
//! planned once, always as `plan(min, max)`, so that whichever end plans it the value is the
//! same. A blocked entry (the collapse was illegal or over the error bound; cleared when the
//! neighbourhood changes) has its sign bit set.
//!
//! Entries are atomics so that ranking runs on every core: each fan is planned by one
//! thread, and two threads that meet on an edge write the same value. On x86 a relaxed
//! atomic load or store is a plain move.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use rayon::prelude::*;

use super::collapser::others;
use super::part::Part;
use crate::mesh::topology::split_mut;

const BLOCKED: u32 = 1 << 31;

/// Fans longer than this are planned without sharing an edge's cost between its two slots.
const FAN_MEMO: usize = 24;

/// Vertices per rayon task: planning one fan takes well under a microsecond.
const MIN_PER_TASK: usize = 2048;

/// How many vertices ahead of its turn a vertex's data is asked for, per stage of
/// [`Part::pipelined`]. On the dragon kept at 10 % (one core), re-planning the kept
/// vertices took 0.49 s without asking ahead, 0.40 s with only the neighbours' quadrics
/// asked for before a fan is planned, 0.30 s with the three stages.
const AHEAD: usize = 2;

/// Planned costs of every edge, per half-edge slot.
pub(super) struct EdgeCosts {
    slots: Vec<AtomicU32>,
}

impl EdgeCosts {
    pub fn new(triangle_slots: usize) -> Self {
        Self {
            slots: (0..3 * triangle_slots)
                .into_par_iter()
                .with_min_len(1 << 16)
                .map(|_| AtomicU32::new(f32::INFINITY.to_bits()))
                .collect(),
        }
    }

    /// The cost of `slot`, or `None` when it is blocked or the edge may not collapse.
    fn get(&self, slot: usize) -> Option<f32> {
        let bits = self.slots[slot].load(Relaxed);
        let cost = f32::from_bits(bits);
        (bits & BLOCKED == 0 && cost.is_finite()).then_some(cost)
    }

    /// Asks the CPU to start loading `slot` (a hint).
    pub fn prefetch(&self, slot: usize) {
        if let Some(s) = self.slots.get(slot) {
            crate::mesh::prefetch(s);
        }
    }

    fn set(&self, slot: usize, cost: f32) {
        self.slots[slot].store(cost.to_bits(), Relaxed);
    }

    fn block(&self, slot: usize) {
        self.slots[slot].fetch_or(BLOCKED, Relaxed);
    }

    fn unblock(&self, slot: usize) {
        let bits = self.slots[slot].load(Relaxed);
        if bits & BLOCKED != 0 {
            self.slots[slot].store(bits & !BLOCKED, Relaxed);
        }
    }
}

/// A plan's cost as stored: f32, finite.
pub(super) fn stored(cost: f64) -> f32 {
    (cost as f32).min(f32::MAX)
}

impl Part<'_> {
    /// Calls `f(slot, other end)` for every half-edge slot on an edge of `v`: in each
    /// incident triangle, the edge leaving `v` and the edge coming into it.
    fn for_each_edge(&self, v: u32, mut f: impl FnMut(usize, u32)) {
        for &t in self.conn.incident(v) {
            let tri = self.conn.triangle(t);
            let i = if tri[0] == v {
                0
            } else if tri[1] == v {
                1
            } else {
                2
            };
            let base = 3 * t as usize;
            f(base + i, tri[(i + 1) % 3]);
            f(base + (i + 2) % 3, tri[(i + 2) % 3]);
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
                        self.prefetch_end(others(self.conn.triangle(t), a)[0]);
                    }
                }
            }
            f(v);
        }
    }

    /// Plans the edges of `v` except those to a vertex `w` for which `skip(w)` (planned from
    /// there) and stores each edge's cost in its slots, unblocked. Returns the cheapest of
    /// the edges it planned, as [`Self::best_edge`] would pick it: its other end (`u32::MAX`
    /// when none) and cost.
    pub fn plan_fan(&self, v: u32, skip: impl Fn(u32) -> bool) -> (u32, f32) {
        let mut best = (u32::MAX, f32::INFINITY);
        let mut memo = [(u32::MAX, 0.0f32); FAN_MEMO];
        let mut len = 0;
        // A neighbour's first slot (its bit not yet in the mask) skips the memo's search.
        let mut seen = 0u64;
        self.for_each_edge(v, |slot, w| {
            if skip(w) {
                return;
            }
            let bit = 1u64 << (w & 63);
            let known = seen & bit != 0;
            seen |= bit;
            let cached = if known {
                memo[..len].iter().find(|m| m.0 == w)
            } else {
                None
            };
            let cost = match cached {
                Some(&(_, cost)) => cost,
                None => {
                    let cost = self.edge_cost(v, w);
                    if len < FAN_MEMO {
                        memo[len] = (w, cost);
                        len += 1;
                    }
                    cost
                }
            };
            self.costs.set(slot, cost);
            if cost.is_finite() && (cost < best.1 || (cost == best.1 && w < best.0)) {
                best = (w, cost);
            }
        });
        best
    }

    /// The cheapest unblocked edge of `v`: its other end (`u32::MAX` when none) and cost.
    pub fn best_edge(&self, v: u32) -> (u32, f32) {
        let mut best = (u32::MAX, f32::INFINITY);
        self.for_each_edge(v, |slot, w| {
            if let Some(cost) = self.costs.get(slot) {
                if cost < best.1 || (cost == best.1 && w < best.0) {
                    best = (w, cost);
                }
            }
        });
        best
    }

    /// Plans every edge once and gives every vertex its cheapest edge, on all cores.
    pub fn rank_all(&mut self) {
        let n = self.positions.len() as u32;
        let all: Vec<u32> = (0..n).into_par_iter().collect();
        let this = &*self;
        all.par_chunks(MIN_PER_TASK).for_each(|chunk| {
            this.pipelined(chunk, true, |v| {
                this.plan_fan(v, |w| w <= v);
            });
        });
        self.rerank(&all, 0);
    }

    /// Re-plans every edge of each of `vertices` (ascending; their quadrics or positions
    /// changed) and gives each its cheapest edge, on all cores. An edge between two of them
    /// is planned from both ends: each then knows all its costs without waiting for the
    /// other, and both store the same value.
    pub fn replan(&mut self, vertices: &[u32]) {
        self.update_best(vertices, MIN_PER_TASK / 4, true, |this, v| {
            (this.plan_fan(v, |_| false), true)
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
        self.for_each_edge(v, |slot, x| {
            if x == w {
                self.costs.block(slot);
            }
        });
        let (iv, iw) = (self.at(v), self.at(w));
        self.has_blocked[iv] = true;
        self.has_blocked[iw] = true;
    }

    /// Unblocks every edge of `v`: its neighbourhood changed.
    fn unblock_fan(&self, v: u32) {
        self.for_each_edge(v, |slot, _| self.costs.unblock(slot));
    }
}

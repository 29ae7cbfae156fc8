//! The cost cache's storage: per triangle slot, the planned costs of its three edges beside
//! a copy of its corners. A blocked entry (the collapse was illegal or over the error bound)
//! has its sign bit set. What is planned and when is `ranking`'s.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use rayon::prelude::*;

/// Sign bit of a blocked entry.
const BLOCKED: u32 = 1 << 31;

/// One triangle slot's corners and the planned costs of its three edges (cost `i` is the
/// edge from corner `i` to corner `i + 1`), in one 24-byte record: a fan walk loads one
/// record per triangle instead of the corners from one array and the costs from another.
/// The corners are a copy of the connectivity's, kept in step by
/// [`EdgeCosts::set_corners`] at every collapse (only planning reads them).
#[repr(C)]
struct Slot {
    corners: [AtomicU32; 3],
    costs: [AtomicU32; 3],
}

/// Planned costs of every edge, per half-edge slot, beside a copy of each triangle's
/// corners.
pub(super) struct EdgeCosts {
    slots: Vec<Slot>,
}

impl EdgeCosts {
    /// Every slot of `triangles` (dead ones too: no incident list names them), unplanned.
    pub fn new(triangles: &[[u32; 3]]) -> Self {
        let unplanned = || AtomicU32::new(f32::INFINITY.to_bits());
        Self {
            slots: triangles
                .par_iter()
                .with_min_len(1 << 14)
                .map(|tri| Slot {
                    corners: tri.map(AtomicU32::new),
                    costs: [unplanned(), unplanned(), unplanned()],
                })
                .collect(),
        }
    }

    /// The corners of triangle slot `t`, as the connectivity has them.
    #[inline]
    pub fn corners(&self, t: u32) -> [u32; 3] {
        let c = &self.slots[t as usize].corners;
        [c[0].load(Relaxed), c[1].load(Relaxed), c[2].load(Relaxed)]
    }

    /// Notes that the connectivity's triangle slot `t` now has these corners.
    pub fn set_corners(&self, t: u32, tri: [u32; 3]) {
        for (c, v) in self.slots[t as usize].corners.iter().zip(tri) {
            c.store(v, Relaxed);
        }
    }

    #[inline]
    pub(super) fn cost(&self, t: u32, i: usize) -> &AtomicU32 {
        &self.slots[t as usize].costs[i]
    }

    /// The cost of edge `i` of slot `t`, or `None` when it is blocked or the edge may not
    /// collapse.
    pub(super) fn get(&self, t: u32, i: usize) -> Option<f32> {
        let bits = self.cost(t, i).load(Relaxed);
        let cost = f32::from_bits(bits);
        (bits & BLOCKED == 0 && cost.is_finite()).then_some(cost)
    }

    /// Asks the CPU to start loading slot `t` (a hint).
    pub fn prefetch(&self, t: u32) {
        if let Some(s) = self.slots.get(t as usize) {
            crate::mesh::prefetch_all(s);
        }
    }

    pub(super) fn set(&self, t: u32, i: usize, cost: f32) {
        self.cost(t, i).store(cost.to_bits(), Relaxed);
    }

    pub(super) fn block(&self, t: u32, i: usize) {
        self.cost(t, i).fetch_or(BLOCKED, Relaxed);
    }

    pub(super) fn unblock(&self, t: u32, i: usize) {
        let cost = self.cost(t, i);
        let bits = cost.load(Relaxed);
        if bits & BLOCKED != 0 {
            cost.store(bits & !BLOCKED, Relaxed);
        }
    }
}

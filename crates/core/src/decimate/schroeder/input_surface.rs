//! The input surface that fills are checked against, so that turns do not add up over
//! removals in a row (docs/design.md#schroeder-input-surface): per live triangle slot, the
//! summed area vectors of the input triangles it stands for, carried through every fill;
//! and per vertex, the input triangles at it.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// Each triangle's area vector (its normal, twice its area long), on all cores.
pub(super) fn area_vectors(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let p = |v: u32| positions[v as usize].as_dvec3();
    triangles
        .par_iter()
        .map(|&[a, b, c]| (p(b) - p(a)).cross(p(c) - p(a)).as_vec3())
        .collect()
}

/// The input surface each triangle slot stands for, by slot from `t0` (a region's first
/// slot, or 0).
#[derive(Debug, Clone, Copy)]
pub(super) struct InputSurface<'a> {
    pub t0: u32,
    pub vectors: &'a [Vec3],
}

impl InputSurface<'_> {
    /// Slot `t`'s input surface; zero (which no fill faces) for a slot not held.
    pub fn of(&self, t: u32) -> DVec3 {
        let i = t.wrapping_sub(self.t0) as usize;
        self.vectors.get(i).map_or(DVec3::ZERO, |v| v.as_dvec3())
    }
}

/// The input triangles' area vectors at each vertex, never changed: a new triangle must
/// face within 90° of one of them at one of its corners.
#[derive(Debug, Default)]
pub(super) struct InputCorners {
    /// Vertex `v`'s triangles are `triangles[offsets[v]..offsets[v + 1]]`.
    offsets: Vec<u32>,
    triangles: Vec<u32>,
    areas: Vec<Vec3>,
    /// Per vertex, its input triangles' area vectors summed: facing within 90° of the sum
    /// faces so of one of them, which is all most checks need to read.
    sums: Vec<Vec3>,
}

impl InputCorners {
    pub fn new(vertex_count: usize, triangles: &[[u32; 3]], areas: Vec<Vec3>) -> Self {
        let mut offsets = vec![0u32; vertex_count + 1];
        for t in triangles {
            for &v in t {
                offsets[v as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            offsets[v + 1] += offsets[v];
        }
        let mut next = offsets.clone();
        let mut at = vec![0u32; offsets[vertex_count] as usize];
        for (i, t) in triangles.iter().enumerate() {
            for &v in t {
                at[next[v as usize] as usize] = i as u32;
                next[v as usize] += 1;
            }
        }
        drop(next);
        // Each vertex's list is in triangle order: summed in that order, on all cores.
        let sums = (0..vertex_count)
            .into_par_iter()
            .map(|v| {
                let list = &at[offsets[v] as usize..offsets[v + 1] as usize];
                let sum: DVec3 = list.iter().map(|&t| areas[t as usize].as_dvec3()).sum();
                sum.as_vec3()
            })
            .collect();
        Self {
            offsets,
            triangles: at,
            areas,
            sums,
        }
    }

    /// Asks for vertex `v`'s summed input areas ahead of a check at it (a hint only).
    pub fn prefetch(&self, v: u32) {
        if let Some(sum) = self.sums.get(v as usize) {
            crate::mesh::prefetch(sum);
        }
    }

    /// Whether a triangle of area vector `cross` at the corners `tri` faces within 90° of
    /// some input triangle at one of them (vacuously true when nothing is known).
    pub fn faces(&self, cross: DVec3, tri: &[u32; 3]) -> bool {
        if self.offsets.is_empty() {
            return true;
        }
        let by_sum = |v: u32| {
            self.sums
                .get(v as usize)
                .is_some_and(|s| cross.dot(s.as_dvec3()) > 0.0)
        };
        tri.iter().any(|&v| by_sum(v))
            || tri.iter().any(|&v| {
                let (Some(&from), Some(&to)) = (
                    self.offsets.get(v as usize),
                    self.offsets.get(v as usize + 1),
                ) else {
                    return false;
                };
                self.triangles[from as usize..to as usize]
                    .iter()
                    .any(|&t| cross.dot(self.areas[t as usize].as_dvec3()) > 0.0)
            })
    }
}

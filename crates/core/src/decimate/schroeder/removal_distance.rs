//! The vertex-removal side of `--max-error` as a surface distance
//! (`decimate::distance_bound`): a planned removal's ring triangles as the slots it changes
//! and its fill as the triangles it leaves. Vertices never move: only the fill's new
//! edges (diagonals, and the edge closing an open ring) and insides are new.

use glam::DVec3;

use super::{Decimator, Removal};
use crate::decimate::distance_bound::{Near, NewTriangle};

/// Rings longer than this mark every fill edge new rather than look each one up.
const LOOKED_UP: usize = 64;

impl Decimator {
    /// Whether `removal` keeps the surface within `--max-error` of the input; always true
    /// without it. With `near`, input may go to the unchanged triangles around it (not for
    /// a seam's first side: the second's may take them). When true, the next `apply`
    /// records it.
    pub(super) fn within_distance(&mut self, removal: Removal<'_>, near: bool) -> bool {
        let Self {
            distance,
            positions,
            conn,
            ..
        } = self;
        let Some(bound) = distance.as_mut() else {
            return true;
        };
        let point = |v: u32| (positions.get(v as usize)).map_or(DVec3::ZERO, |p| p.as_dvec3());
        let ring = removal.ring;
        let open = removal.triangles.len() < ring.len();
        let ring_edge = |x: u32, y: u32| {
            let (Some(i), Some(j)) = (
                ring.iter().position(|&u| u == x),
                ring.iter().position(|&u| u == y),
            ) else {
                return false;
            };
            let n = ring.len();
            i.abs_diff(j) == 1 || (!open && i.abs_diff(j) == n - 1)
        };
        let short = ring.len() <= LOOKED_UP;
        let new: Vec<NewTriangle> = (removal.fill.iter().enumerate())
            .map(|(j, tri)| {
                let mut fresh = 0u8;
                for e in 0..3 {
                    if !(short && ring_edge(tri[e], tri[(e + 1) % 3])) {
                        fresh |= 1 << (3 + e);
                    }
                }
                NewTriangle {
                    id: j as u32,
                    corners: tri.map(point),
                    fresh,
                }
            })
            .collect();
        let mut around = |list: &mut Vec<(u32, [DVec3; 3])>| {
            for &x in ring {
                for &t in conn.incident(x) {
                    list.push((t, conn.triangle(t).map(point)));
                }
            }
        };
        let near: Option<Near<'_>> = if near { Some(&mut around) } else { None };
        let within = bound.check(removal.triangles, &new, near);
        if !within {
            bound.discard();
        }
        within
    }

    /// Records the removal `within_distance` allowed last, now made: its fill took the
    /// slots `added`.
    pub(super) fn commit_distance(&mut self, added: &[u32]) {
        if let Some(bound) = self.distance.as_mut() {
            bound.commit(|j| added.get(j as usize).copied().unwrap_or(u32::MAX));
        }
    }
}

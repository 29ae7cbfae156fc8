//! The qem side of `--max-error` as a surface distance (`decimate::distance_bound`): a
//! planned collapse's fans as the slots it changes and the triangles it leaves.

use glam::DVec3;

use super::collapse_plan::Plan;
use super::part::Part;
use crate::decimate::distance_bound::{Near, NewTriangle};

/// A fan triangle after the collapse: its moved corner (0) and the two edges there are new;
/// the edge between its other corners stays.
const FRESH: u8 = 1 | 1 << 3 | 1 << 5;

impl Part<'_> {
    /// Whether the planned collapse (its fans read by `gather`, the other side's too on a
    /// seam) keeps the surface within `--max-error` of the input; always true without it.
    /// When true, [`Self::commit_distance`] records it once made.
    pub fn within_distance(&mut self, plan: &Plan) -> bool {
        if self.distance.is_none() {
            return true;
        }
        // A seam collapse's two sides are checked before either is made: neither may hand
        // its input to slots near it, which the other side may change.
        let mut within = self.side_within_distance(plan, plan.twin.is_none());
        if let (true, Some(twin)) = (within, plan.other_side()) {
            self.swap_sides();
            within = self.side_within_distance(&twin, false);
            self.swap_sides();
        }
        if !within {
            if let Some(bound) = self.distance.as_deref_mut() {
                bound.discard();
            }
        }
        within
    }

    /// Records the collapses [`Self::within_distance`] allowed, now made.
    pub fn commit_distance(&mut self) {
        if let Some(bound) = self.distance.as_deref_mut() {
            bound.commit_all(|t| t);
        }
    }

    /// One side of [`Self::within_distance`]; with `near`, input may go to the unchanged
    /// triangles around the collapse.
    fn side_within_distance(&mut self, plan: &Plan, near: bool) -> bool {
        let (fan_r, fan_k) = self.fans(plan);
        let at = plan.position.as_vec3().as_dvec3();
        let mut old = Vec::with_capacity(fan_r.len() + fan_k.len());
        let mut new = Vec::with_capacity(fan_r.len() + fan_k.len());
        for (fan, other, removed) in [(fan_r, plan.keep, true), (fan_k, plan.remove, false)] {
            for f in fan {
                old.push(f.t);
                let junction = removed && plan.junction.is_some_and(|c| f.touches(c));
                if f.touches(other) || junction {
                    continue; // deleted with the edge
                }
                new.push(NewTriangle {
                    id: f.t,
                    corners: [at, self.position(f.next), self.position(f.prev)],
                    fresh: FRESH,
                });
            }
        }
        let ring: Vec<u32> = (fan_r.iter().chain(fan_k))
            .flat_map(|f| [f.next, f.prev])
            .collect();
        let Part {
            distance,
            conn,
            positions,
            v0,
            ..
        } = self;
        let Some(bound) = distance.as_deref_mut() else {
            return true;
        };
        let v0 = *v0;
        let point = |v: u32| {
            let i = v.wrapping_sub(v0) as usize;
            positions.get(i).map_or(DVec3::ZERO, |p| p.as_dvec3())
        };
        let mut around = |list: &mut Vec<(u32, [DVec3; 3])>| {
            for &x in &ring {
                for &t in conn.incident(x) {
                    list.push((t, conn.triangle(t).map(point)));
                }
            }
        };
        let near: Option<Near<'_>> = if near { Some(&mut around) } else { None };
        bound.check(&old, &new, near)
    }
}

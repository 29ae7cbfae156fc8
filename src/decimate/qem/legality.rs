//! pmp's `is_collapse_legal` for a planned collapse, as a chain of small checks: the link
//! condition (no non-manifold result), no duplicate triangle, no flipped or degenerate
//! triangle. Vertex kinds (boundary, complex) were already applied by `plan`.

use super::collapser::{others, Plan};
use super::part::Part;

/// A triangle is degenerate when its area is this small relative to its longest edge².
const MIN_RELATIVE_AREA: f64 = 1e-8;

impl Part<'_> {
    pub fn is_collapse_legal(&mut self, plan: &Plan) -> bool {
        self.link_condition_holds(plan)
            && self.no_duplicate_triangle(plan)
            && self.no_triangle_flips_or_degenerates(plan)
    }

    /// Link condition (Dey et al.): the ends share no neighbour but the apexes of the
    /// triangles on the edge — otherwise the result would be non-manifold. A boundary edge
    /// also must not be the last edge of a triangle whose other two edges are on the boundary.
    /// Leaves the common neighbours in `scratch.common`. Neighbourhoods are small, so the
    /// lists are searched linearly (no per-vertex marks to keep, nothing shared to write),
    /// behind a 64-bit mask of the removed end's neighbours that turns most misses away.
    fn link_condition_holds(&mut self, plan: &Plan) -> bool {
        let (r, k) = (plan.remove, plan.keep);
        let mut neighbours = std::mem::take(&mut self.scratch.ring);
        let mut common = std::mem::take(&mut self.scratch.common);
        neighbours.clear();
        common.clear();
        let mut on_edge = 0;
        let mut edge_triangle = u32::MAX;
        let mut mask = 0u64;
        for &t in self.conn.incident(r) {
            let tri = self.conn.triangle(t);
            if tri.contains(&k) {
                on_edge += 1;
                edge_triangle = t;
            }
            // With repeats: each neighbour once per triangle it is in.
            for w in others(tri, r) {
                mask |= 1 << (w & 63);
                neighbours.push(w);
            }
        }
        for &t in self.conn.incident(k) {
            for w in others(self.conn.triangle(t), k) {
                if mask & 1 << (w & 63) != 0
                    && w != r
                    && neighbours.contains(&w)
                    && !common.contains(&w)
                {
                    common.push(w);
                }
            }
        }
        let shares_only_apexes = common.len() == on_edge && (1..=2).contains(&on_edge);
        self.scratch.ring = neighbours;
        self.scratch.common = common;
        if !shares_only_apexes {
            return false;
        }
        if on_edge == 1 {
            let apex = self
                .conn
                .triangle(edge_triangle)
                .into_iter()
                .find(|&w| w != r && w != k);
            if let Some(w) = apex {
                if self.edge_triangles(r, w).0 == 1 && self.edge_triangles(k, w).0 == 1 {
                    return false;
                }
            }
        }
        true
    }

    /// A triangle of the removed end, renamed to the kept end, must not already exist (the
    /// last step before a tetrahedron folds flat). Once the link condition holds, only a
    /// triangle on two common neighbours (`scratch.common`) can be duplicated.
    fn no_duplicate_triangle(&self, plan: &Plan) -> bool {
        let common = &self.scratch.common;
        self.conn.incident(plan.remove).iter().all(|&t| {
            let tri = self.conn.triangle(t);
            if tri.contains(&plan.keep) {
                return true;
            }
            let [x, y] = others(tri, plan.remove);
            let both_common = common.contains(&x) && common.contains(&y);
            !both_common || !self.conn.has_triangle(plan.keep, x, y)
        })
    }

    /// Every triangle that survives around either end keeps facing the same way and keeps
    /// an area. Such a triangle has exactly one of the ends, `v`: it turns about the other
    /// two corners as `v` moves to the plan's position.
    fn no_triangle_flips_or_degenerates(&self, plan: &Plan) -> bool {
        let p = plan.position;
        let min2 = MIN_RELATIVE_AREA * MIN_RELATIVE_AREA;
        [plan.remove, plan.keep].iter().all(|&v| {
            let other = if v == plan.remove {
                plan.keep
            } else {
                plan.remove
            };
            let pv = self.position(v);
            self.conn.incident(v).iter().all(|&t| {
                let tri = self.conn.triangle(t);
                if tri.contains(&other) {
                    return true; // collapses away
                }
                let [x, y] = others(tri, v).map(|w| self.position(w));
                let old_cross = (x - pv).cross(y - pv);
                let new_cross = (x - p).cross(y - p);
                let longest = (x - p)
                    .length_squared()
                    .max((y - x).length_squared())
                    .max((p - y).length_squared());
                new_cross.length_squared() > min2 * longest * longest
                    && new_cross.dot(old_cross) > 0.0
            })
        })
    }
}

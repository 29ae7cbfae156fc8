//! pmp's `is_collapse_legal` for a planned collapse, as a chain of small checks: the link
//! condition (no non-manifold result), no duplicate triangle, no flipped or degenerate
//! triangle. Vertex kinds (boundary, complex) were already applied by `plan`.

use super::collapser::{others, Collapser, Plan};

/// A triangle is degenerate when its area is this small relative to its longest edge².
const MIN_RELATIVE_AREA: f64 = 1e-8;

impl Collapser {
    pub fn is_collapse_legal(&mut self, plan: &Plan) -> bool {
        let Some(common) = self.link_condition_holds(plan) else {
            return false;
        };
        self.no_duplicate_triangle(plan, common) && self.no_triangle_flips_or_degenerates(plan)
    }

    /// Two fresh visit stamps: `s` for "neighbour of the removed end", `s + 1` for "common
    /// neighbour".
    fn fresh_stamps(&mut self) -> u32 {
        if self.stamp >= u32::MAX - 2 {
            self.stamps.fill(0);
            self.stamp = 0;
        }
        self.stamp += 2;
        self.stamp - 1
    }

    /// Link condition (Dey et al.): the ends share no neighbour but the apexes of the
    /// triangles on the edge — otherwise the result would be non-manifold. A boundary edge
    /// also must not be the last edge of a triangle whose other two edges are on the boundary.
    /// Returns the stamp that marks the common neighbours.
    fn link_condition_holds(&mut self, plan: &Plan) -> Option<u32> {
        let (r, k) = (plan.remove, plan.keep);
        let s = self.fresh_stamps();
        let mut on_edge = 0;
        let mut edge_triangle = u32::MAX;
        for &t in self.conn.incident(r) {
            let tri = self.conn.triangle(t);
            if tri.contains(&k) {
                on_edge += 1;
                edge_triangle = t;
            }
            for w in tri {
                if w != r {
                    self.stamps[w as usize] = s;
                }
            }
        }
        let mut common = 0;
        for &t in self.conn.incident(k) {
            for w in self.conn.triangle(t) {
                if w != k && self.stamps[w as usize] == s {
                    self.stamps[w as usize] = s + 1;
                    common += 1;
                }
            }
        }
        if common != on_edge || !(1..=2).contains(&on_edge) {
            return None;
        }
        if on_edge == 1 {
            let apex = self
                .conn
                .triangle(edge_triangle)
                .into_iter()
                .find(|&w| w != r && w != k);
            if let Some(w) = apex {
                if self.edge_triangles(r, w).0 == 1 && self.edge_triangles(k, w).0 == 1 {
                    return None;
                }
            }
        }
        Some(s + 1)
    }

    /// A triangle of the removed end, renamed to the kept end, must not already exist (the
    /// last step before a tetrahedron folds flat). Once the link condition holds, only a
    /// triangle on two common neighbours (stamped `common`) can be duplicated.
    fn no_duplicate_triangle(&self, plan: &Plan, common: u32) -> bool {
        self.conn.incident(plan.remove).iter().all(|&t| {
            let tri = self.conn.triangle(t);
            if tri.contains(&plan.keep) {
                return true;
            }
            let [x, y] = others(tri, plan.remove);
            let both_common =
                self.stamps[x as usize] == common && self.stamps[y as usize] == common;
            !both_common || !self.conn.has_triangle(plan.keep, x, y)
        })
    }

    /// Every triangle that survives around either end keeps facing the same way and keeps
    /// an area.
    fn no_triangle_flips_or_degenerates(&self, plan: &Plan) -> bool {
        let ends = [plan.remove, plan.keep];
        ends.iter().all(|&v| {
            self.conn.incident(v).iter().all(|&t| {
                let tri = self.conn.triangle(t);
                if tri.contains(&plan.remove) && tri.contains(&plan.keep) {
                    return true; // collapses away
                }
                let old = self.corners(t);
                let new = tri.map(|w| {
                    if w == plan.remove || w == plan.keep {
                        plan.position
                    } else {
                        self.position(w)
                    }
                });
                let old_cross = (old[1] - old[0]).cross(old[2] - old[0]);
                let new_cross = (new[1] - new[0]).cross(new[2] - new[0]);
                let longest = (new[1] - new[0])
                    .length_squared()
                    .max((new[2] - new[1]).length_squared())
                    .max((new[0] - new[2]).length_squared());
                new_cross.length() > MIN_RELATIVE_AREA * longest && new_cross.dot(old_cross) > 0.0
            })
        })
    }
}

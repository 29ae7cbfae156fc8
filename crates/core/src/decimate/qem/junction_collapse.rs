//! Collapses into a texture-seam junction whose copies all sit at one point: a textured
//! sphere's pole, a cone's apex. There every copy is in a triangle or few, so a vertex of
//! the first ring is on the outline of the split surface between two copies, `keep` and
//! `other`. Collapsed into `keep` alone, its triangle with `other` would keep two corners
//! at one point and no area; welded, the vertex is an interior one and its collapse removes
//! both triangles on the edge. So it is made as the welded collapse: the triangle with
//! `other` goes too, and `other` is dropped when that was its last
//! (docs/design.md#texture-seams).

use super::collapse_plan::{Kind, Plan};
use super::part::Part;
use crate::mesh::seams::position_key;

impl Part<'_> {
    /// Makes `plan` a collapse across a junction when it takes a boundary vertex with no
    /// twin into a junction copy (`keep`, anchored) and the vertex's other outline edge
    /// runs to another copy at the same point: `plan.junction` names that copy, and the
    /// removed end's fan (read by `gather`) names `keep` in its place, so that every check
    /// and the collapse see the welded edge with its two triangles. A vertex in three
    /// triangles goes only when its third does not exist at the junction already.
    pub fn join_junction(&mut self, plan: &mut Plan) {
        let (remove, keep) = (plan.remove, plan.keep);
        if plan.twin.is_some()
            || self.twin(remove).is_some()
            || self.kind(remove) != Kind::Boundary
            || self.kind(keep) != Kind::Anchored
        {
            return;
        }
        let at_keep = position_key(self.positions[self.at(keep)]);
        let (fan_r, _) = self.fans(plan);
        if fan_r.len() < 3 {
            return;
        }
        let edge_count = |x: u32| fan_r.iter().filter(|f| f.touches(x)).count();
        if edge_count(keep) != 1 {
            return;
        }
        let other = fan_r.iter().flat_map(|f| [f.next, f.prev]).find(|&c| {
            c != keep
                && self.owns(c)
                && self.kind(c) == Kind::Anchored
                && position_key(self.positions[self.at(c)]) == at_keep
        });
        let Some(other) = other.filter(|&c| edge_count(c) == 1) else {
            return;
        };
        // Into the copy with one triangle, when one of the two has one: that copy goes
        // (the other way round, this edge's reverse, drops it).
        let alone = |c: u32| self.conn.has_room(c, 0) && self.conn.incident(c).len() == 1;
        if alone(keep) && !alone(other) {
            return;
        }
        // In three triangles, the one left joins the two apexes to the junction: it must
        // not be there already, at any copy.
        let last = fan_r.iter().find(|f| !f.touches(keep) && !f.touches(other));
        if fan_r.len() == 3 && last.is_none_or(|f| self.joins_junction(f.next, f.prev, at_keep)) {
            return;
        }
        for f in self.fan_mut(remove).iter_mut() {
            for x in [&mut f.next, &mut f.prev] {
                if *x == other {
                    *x = keep;
                }
            }
        }
        plan.junction = Some(other);
    }

    /// Whether a triangle joins `x`, `y` and a junction copy at the point `at` (or `x`'s
    /// triangles are not all this part's, which says the same: the collapse waits).
    fn joins_junction(&self, x: u32, y: u32, at: [u32; 3]) -> bool {
        let owned = self.owns(x)
            && self.conn.has_room(x, 0)
            && (self.conn.incident(x).iter()).all(|&t| self.conn.owns_slot(t));
        !owned
            || self.conn.incident(x).iter().any(|&t| {
                let tri = self.conn.triangle(t);
                tri.contains(&y)
                    && tri.iter().any(|&c| {
                        self.owns(c)
                            && self.kind(c) == Kind::Anchored
                            && position_key(self.positions[self.at(c)]) == at
                    })
            })
    }

    /// Whether the junction collapse `plan` leaves its other copy with no triangle (it
    /// is then dropped, a vertex less).
    pub fn drops_junction_copy(&self, plan: &Plan) -> bool {
        plan.junction
            .is_some_and(|c| self.conn.has_room(c, 0) && self.conn.incident(c).len() == 1)
    }
}

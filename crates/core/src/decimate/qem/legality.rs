//! pmp's `is_collapse_legal` for a planned collapse, as a chain of small checks: the link
//! condition (no non-manifold result), no duplicate triangle, no flipped or degenerate
//! triangle, in space and (with texture coordinates) in the texture, and no closed shape
//! turned inside out or flattened (`decimate::closed`). Vertex kinds (boundary,
//! complex) were already applied by `plan`.

use glam::{DVec2, DVec3, DVec4};

use super::collapse_plan::Plan;
use super::part::Part;
use crate::decimate::closed::tet6;
use crate::mesh::topology::FanTriangle;

/// A triangle is degenerate when its area is this small relative to its longest edge².
const MIN_RELATIVE_AREA: f64 = 1e-8;

/// A triangle's area in the texture may shrink to this fraction of what it was, no further.
const MIN_TEXTURE_AREA: f64 = 1e-6;

/// The input surface under a triangle's corners is judged only where it faces one way: its
/// summed area vector at least this share of its area (docs/design.md#qem-input-surface).
const MIN_INPUT_COHERENCE: f64 = 0.75;

impl Part<'_> {
    /// Whether the planned collapse of the edge [`Part::gather`] read last is legal.
    pub fn is_collapse_legal(&mut self, plan: &Plan) -> bool {
        self.link_condition_holds(plan)
            && self.leaves_a_triangle(plan)
            && self.no_duplicate_triangle(plan)
            && self.no_triangle_flips_or_degenerates(plan)
            && self.no_texture_flips(plan)
            && self.keeps_closed_volume(plan)
    }

    /// The collapse leaves a triangle at the kept end: when every triangle of both ends lies
    /// on the edge (a doubled triangle, the last of a loose speck), collapsing it would delete
    /// that piece of surface whole, and its distance to the rest becomes the result's error.
    fn leaves_a_triangle(&self, plan: &Plan) -> bool {
        let (fan_r, fan_k) = self.fans(plan);
        fan_r.iter().any(|f| !f.touches(plan.keep)) || fan_k.iter().any(|f| !f.touches(plan.remove))
    }

    /// On a closed component, the collapse keeps the component's volume on its side of
    /// zero and above its floor: the per-triangle flip test lets each triangle turn by up to
    /// a right angle, which on a small closed shape can carry it through itself.
    /// The change is kept for the collapse that follows ([`Self::checked_volume_change`]).
    fn keeps_closed_volume(&mut self, plan: &Plan) -> bool {
        let Some(c) = self.closed.component(plan.remove) else {
            return true;
        };
        let change = self.volume_change(plan);
        self.scratch.volume_change = Some(([plan.remove, plan.keep], plan.position, change));
        self.closed.allows(c, change)
    }

    /// [`Self::volume_change`] of `plan`, as the legality check just worked it out when it
    /// was the last collapse checked (the other side of a seam collapse may have been).
    pub fn checked_volume_change(&mut self, plan: &Plan) -> f64 {
        match self.scratch.volume_change.take() {
            Some((ends, at, change)) if ends == [plan.remove, plan.keep] && at == plan.position => {
                change
            }
            _ => self.volume_change(plan),
        }
    }

    /// Six times the change of signed volume the planned collapse makes: the removed end's
    /// and the kept end's triangles as they will be, less as they are (those on the edge
    /// go), about the kept end's old position.
    pub fn volume_change(&self, plan: &Plan) -> f64 {
        let o = self.position(plan.keep);
        let (fan_r, fan_k) = self.fans(plan);
        let mut change = 0.0;
        for (v, fan, other) in [
            (plan.remove, fan_r, plan.keep),
            (plan.keep, fan_k, plan.remove),
        ] {
            let pv = self.position(v);
            for f in fan {
                let [x, y] = [f.next, f.prev].map(|w| self.position(w));
                if !f.touches(other) {
                    change += tet6(o, plan.position, x, y) - tet6(o, pv, x, y);
                } else if v == plan.remove {
                    change -= tet6(o, pv, x, y);
                }
            }
        }
        change
    }

    /// Link condition (Dey et al.): the ends share no neighbour but the apexes of the
    /// triangles on the edge — otherwise the result would be non-manifold (or, on
    /// non-manifold input, have more non-manifold edges: an edge merged into another has
    /// the two's triangles less those on the collapsed edge, so it has three or more only
    /// when one of the two had). A boundary edge
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
        let (fan_r, fan_k) = self.fans(plan);
        let mut on_edge = 0;
        let mut apexes = 0;
        let mut apex = u32::MAX;
        let mut mask = 0u64;
        for (i, f) in fan_r.iter().enumerate() {
            if f.touches(k) {
                on_edge += 1;
                apex = if f.next == k { f.prev } else { f.next };
                // Counted once: a triangle and its reversed copy on the edge share an apex.
                let seen = fan_r[..i].iter().any(|g| g.touches(k) && g.touches(apex));
                apexes += usize::from(!seen);
            }
            // With repeats: each neighbour once per triangle it is in.
            for w in [f.next, f.prev] {
                mask |= 1 << (w & 63);
                neighbours.push(w);
            }
        }
        for f in fan_k {
            for w in [f.next, f.prev] {
                if mask & 1 << (w & 63) != 0
                    && w != r
                    && neighbours.contains(&w)
                    && !common.contains(&w)
                {
                    common.push(w);
                }
            }
        }
        if plan.junction.is_some() {
            // Across a junction the apex beyond the other copy is the kept point's
            // neighbour already, welded (its other neighbours: `seam_stays_manifold`).
            for f in fan_r.iter().filter(|f| f.touches(k)) {
                let apex = if f.next == k { f.prev } else { f.next };
                if !common.contains(&apex) {
                    common.push(apex);
                }
            }
        }
        // Three or more apexes on a non-manifold edge; fewer than triangles where the input
        // doubled some (a triangle and its reversed copy), which go together.
        let shares_only_apexes = common.len() == apexes && apexes >= 1;
        // The one triangle on a boundary edge must keep an edge off the boundary.
        let edge_count = |fan: &[FanTriangle], w: u32| fan.iter().filter(|f| f.touches(w)).count();
        let legal = shares_only_apexes
            && (on_edge != 1 || edge_count(fan_r, apex) != 1 || edge_count(fan_k, apex) != 1);
        self.scratch.ring = neighbours;
        self.scratch.common = common;
        legal
    }

    /// A triangle of the removed end, renamed to the kept end, must not already exist (the
    /// last step before a tetrahedron folds flat). Once the link condition holds, only a
    /// triangle on two common neighbours (`scratch.common`) can be duplicated.
    fn no_duplicate_triangle(&self, plan: &Plan) -> bool {
        let common = &self.scratch.common;
        let (fan_r, fan_k) = self.fans(plan);
        fan_r.iter().all(|f| {
            if f.touches(plan.keep) {
                return true;
            }
            let both_common = common.contains(&f.next) && common.contains(&f.prev);
            !both_common || !fan_k.iter().any(|g| g.touches(f.next) && g.touches(f.prev))
        })
    }

    /// With texture coordinates, every triangle that survives around either end keeps its
    /// orientation in the texture and some of its area there, the kept vertex taking the
    /// coordinates `collapse` gives it (interpolated along the edge): otherwise the image
    /// would show mirrored or smeared across it. A triangle with no area in the texture
    /// already is left alone.
    fn no_texture_flips(&self, plan: &Plan) -> bool {
        let Some(t) = self.texcoords.as_deref() else {
            return true;
        };
        let uv = |v: u32| {
            let [u, v] = t[self.at(v)];
            DVec2::new(f64::from(u), f64::from(v))
        };
        let Some([u, v]) = self.new_texcoords(plan) else {
            return true;
        };
        let new = DVec2::new(f64::from(u), f64::from(v));
        let (fan_r, fan_k) = self.fans(plan);
        [
            (plan.remove, fan_r, plan.keep),
            (plan.keep, fan_k, plan.remove),
        ]
        .iter()
        .all(|&(v, fan, other)| {
            let old = uv(v);
            fan.iter().all(|f| {
                if f.touches(other) {
                    return true; // collapses away
                }
                let [x, y] = [f.next, f.prev].map(uv);
                let before = (x - old).perp_dot(y - old);
                let after = (x - new).perp_dot(y - new);
                before == 0.0 || after * before.signum() > MIN_TEXTURE_AREA * before.abs()
            })
        })
    }

    /// Every triangle that survives around either end keeps facing the same way, keeps
    /// an area, and faces within 90° of the input surface its corners stand for (so that
    /// turns do not add up over collapses in a row). Such a triangle has exactly one of the
    /// ends, `v`: it turns about the other two corners as `v` moves to the plan's position.
    fn no_triangle_flips_or_degenerates(&self, plan: &Plan) -> bool {
        let p = plan.position;
        let min2 = MIN_RELATIVE_AREA * MIN_RELATIVE_AREA;
        let (fan_r, fan_k) = self.fans(plan);
        let junctions = !self.copies.is_empty();
        let surface = |w: u32| self.input_surface[self.at(w)].as_dvec4();
        let kept = surface(plan.remove) + surface(plan.keep);
        [
            (plan.remove, fan_r, plan.keep),
            (plan.keep, fan_k, plan.remove),
        ]
        .iter()
        .all(|&(v, fan, other)| {
            let pv = self.position(v);
            fan.iter().all(|f| {
                if f.touches(other) {
                    return true; // collapses away
                }
                let [x, y] = [f.next, f.prev].map(|w| self.position(w));
                let old_cross = (x - pv).cross(y - pv);
                let new_cross = (x - p).cross(y - p);
                let longest = (x - p)
                    .length_squared()
                    .max((y - x).length_squared())
                    .max((p - y).length_squared());
                // A junction never moves to even out a turn: a triangle at one keeps
                // facing the way the junction faced (docs/design.md#texture-seams).
                let faces_out = !junctions
                    || [f.next, f.prev, plan.keep].iter().all(|&w| {
                        self.copies[w as usize] == u32::MAX
                            || new_cross.dot(self.facing[w as usize].as_dvec3()) > 0.0
                    });
                new_cross.length_squared() > min2 * longest * longest
                    && new_cross.dot(old_cross) > 0.0
                    && faces_out
                    && faces_input(new_cross, surface(f.next) + surface(f.prev) + kept)
            })
        })
    }
}

/// Whether a triangle of area vector `cross` faces within 90° of `input`, its corners'
/// input surface (summed area vectors, and their lengths summed in `w`); vacuously true
/// where that surface faces no one way (a thin part's two sides, a crumpled patch).
fn faces_input(cross: DVec3, input: DVec4) -> bool {
    let sum = input.truncate();
    sum.length() < MIN_INPUT_COHERENCE * input.w || cross.dot(sum) >= 0.0
}

//! Lindström–Turk cost (`--cost lt`; Lindström, Turk 1998, and "Evaluation of memoryless
//! simplification", 1999): memoryless, a collapse is judged against the current triangles
//! around its edge alone, not against quadrics carried from the input. Moving the edge's
//! ends to `v` sweeps, per triangle of the edge's star, a tetrahedron (the volume the
//! surface gains or loses there), and per boundary edge of the star, a triangle (the area
//! the outline gains or loses). The placement keeps the volume and the outline's area,
//! then makes their squared changes least, then shapes the triangles (`lt_placement`);
//! the cost is the squared changes at that point: ½ Σ V² + ½ L² Σ A², `L` the edge's
//! length, so that both terms are in length⁶. (`Part::plan` takes its cube root and adds
//! the quadrics' distance, weighted, which holds the max error down.)
//!
//! Costs change with every collapse nearby: `collapse_passes` re-plans the kept vertex's
//! neighbours' edges too under this cost.

use glam::{DMat3, DVec3};

use super::collapse_plan::Kind;
use super::lt_placement::Constraints;
use super::part::Part;

/// Weight of the volume term and of the boundary term in the cost (the paper's ½ each).
const VOLUME_WEIGHT: f64 = 0.5;
const BOUNDARY_WEIGHT: f64 = 0.5;

/// A placement may leave the edge's bounding box by at most this many edge lengths (as
/// qem's own placement).
const BOX_MARGIN: f64 = 1.0;

/// A quadratic form `vᵀHv − 2c·v + k` in coordinates relative to an origin.
#[derive(Debug, Clone, Copy)]
struct Form {
    h: DMat3,
    c: DVec3,
    k: f64,
}

impl Default for Form {
    fn default() -> Self {
        Self {
            h: DMat3::ZERO,
            c: DVec3::ZERO,
            k: 0.0,
        }
    }
}

impl Form {
    /// Adds `(a · v − b)²`.
    fn add_plane(&mut self, a: DVec3, b: f64) {
        self.h += outer(a, a);
        self.c += b * a;
        self.k += b * b;
    }

    /// Adds `|e × v + w|²`.
    fn add_cross(&mut self, e: DVec3, w: DVec3) {
        self.h += DMat3::from_diagonal(DVec3::splat(e.length_squared())) - outer(e, e);
        self.c += e.cross(w);
        self.k += w.length_squared();
    }

    fn eval(&self, v: DVec3) -> f64 {
        (v.dot(self.h * v) - 2.0 * self.c.dot(v) + self.k).max(0.0)
    }

    fn scaled(&self, s: f64) -> Self {
        Self {
            h: self.h * s,
            c: self.c * s,
            k: self.k * s,
        }
    }

    fn plus(&self, o: &Self) -> Self {
        Self {
            h: self.h + o.h,
            c: self.c + o.c,
            k: self.k + o.k,
        }
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// What the star of a collapse gives its placement and cost, relative to the kept end.
#[derive(Debug, Default)]
struct Star {
    /// Σ of six times the swept volumes, as one constraint (kept volume: `n · v = d`).
    normal_sum: DVec3,
    det_sum: f64,
    /// Σ of the triangles' area vectors' lengths: how large `normal_sum` could be.
    normal_lengths: f64,
    /// Σ (6V)²: the volume objective.
    volume: Form,
    /// Σ e and Σ a × b over the boundary edges (kept area: `e × v + w = 0`).
    edge_sum: DVec3,
    cross_sum: DVec3,
    boundary_edges: usize,
    /// Σ (2A)²: the boundary objective.
    boundary: Form,
    /// Σ |v − x|² over the star's other corners (each once per triangle): the shape
    /// objective, as their count and sum.
    corners: f64,
    corner_sum: DVec3,
    /// Whether an end may be on a border (not both interior): only then are the star's
    /// edges looked at.
    border: bool,
}

/// An LT plan's placement and the cost of collapsing there (a function of the position:
/// the cost is priced again where the f32 rounding puts the vertex).
pub(super) struct LtPlan {
    pub position: DVec3,
    origin: DVec3,
    cost: Form,
}

impl LtPlan {
    /// The cost with the kept vertex at `p`.
    pub fn cost_at(&self, p: DVec3) -> f64 {
        self.cost.eval(p - self.origin)
    }
}

impl Part<'_> {
    /// The LT placement and cost of collapsing `remove` into `keep` (and, on a seam, the
    /// other side's `twin` edge in the same step): at the constraints' solution when `free`,
    /// the cheapest point of the edge when `on_crease`, otherwise the kept end. `None` when
    /// a corner of the star is not this part's.
    pub(super) fn lt_plan(
        &self,
        [remove, keep]: [u32; 2],
        twin: Option<[u32; 2]>,
        free: bool,
        on_crease: bool,
    ) -> Option<LtPlan> {
        let origin = self.position(keep);
        let pr = self.position(remove) - origin;
        let interior = |v: u32| self.kind(v) == Kind::Interior;
        let mut star = Star {
            border: !(interior(remove) && interior(keep)) || twin.is_some(),
            ..Star::default()
        };
        self.add_star(&mut star, [remove, keep], origin)?;
        if let Some(ends) = twin {
            self.add_star(&mut star, ends, origin)?;
        }
        let edge2 = pr.length_squared();
        let cost = star
            .volume
            .scaled(VOLUME_WEIGHT / 36.0)
            .plus(&star.boundary.scaled(BOUNDARY_WEIGHT * edge2 / 4.0));
        let local = if on_crease {
            along_edge(&cost, pr)
        } else if free {
            place(&star, &cost, pr).unwrap_or_else(|| best_of_ends(&cost, pr))
        } else {
            DVec3::ZERO
        };
        Some(LtPlan {
            position: origin + local,
            origin,
            cost,
        })
    }

    /// Adds the triangles around `remove` and `keep` (each once) to `star`, relative to
    /// `origin`; `None` when a corner is not this part's.
    fn add_star(&self, star: &mut Star, [remove, keep]: [u32; 2], origin: DVec3) -> Option<()> {
        let ends = [remove, keep];
        for (j, &x) in ends.iter().enumerate() {
            if !self.owns(x) {
                return None;
            }
            for &t in self.conn.incident(x) {
                let tri = self.costs.corners(t);
                // The edge's own triangles are in both fans: taken from the removed end's.
                if j == 1 && tri.contains(&remove) {
                    continue;
                }
                let mut p = [DVec3::ZERO; 3];
                for (p, &c) in p.iter_mut().zip(&tri) {
                    *p = self.positions[self.local(c)?].as_dvec3() - origin;
                }
                self.add_triangle(star, tri, p, ends);
            }
        }
        Some(())
    }

    /// Adds one triangle `tri` (corners at `p`) of the star of the edge `ends`: its swept
    /// volume, its boundary edges at an end, its corners off the edge.
    fn add_triangle(&self, star: &mut Star, tri: [u32; 3], p: [DVec3; 3], ends: [u32; 2]) {
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let d = n.dot(p[0]);
        star.normal_sum += n;
        star.det_sum += d;
        star.normal_lengths += n.length();
        star.volume.add_plane(n, d);
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            if !ends.contains(&a) {
                star.corners += 1.0;
                star.corner_sum += p[i];
            }
            let at_end = ends.contains(&a) || ends.contains(&b);
            if star.border && at_end && self.is_border_edge(a, b, ends) {
                let (pa, pb) = (p[i], p[(i + 1) % 3]);
                let (e, w) = (pb - pa, pa.cross(pb));
                star.edge_sum += e;
                star.cross_sum += w;
                star.boundary_edges += 1;
                star.boundary.add_cross(e, w);
            }
        }
    }

    /// Whether the edge `a`–`b`, one end among `ends` (whose fans are this part's), is in
    /// one triangle only.
    fn is_border_edge(&self, a: u32, b: u32, ends: [u32; 2]) -> bool {
        let (x, y) = if ends.contains(&a) { (a, b) } else { (b, a) };
        let on = |t: &&u32| self.costs.corners(**t).contains(&y);
        self.conn.incident(x).iter().filter(on).count() == 1
    }
}

/// The constraints' solution, in order: volume kept, boundary kept, the weighted volume
/// and boundary change least, triangle shape; `None` when it is degenerate or leaves the
/// edge's box (coordinates relative to the kept end; `pr`, the removed end).
fn place(star: &Star, cost: &Form, pr: DVec3) -> Option<DVec3> {
    let mut c = Constraints::default();
    // The surface around the edge encloses no direction (a closed or flat-folded star):
    // there is no volume to keep.
    if star.normal_sum.length() > 1e-6 * star.normal_lengths {
        c.add(star.normal_sum, star.det_sum);
    }
    if star.boundary_edges > 0 {
        let mut kept = Form::default();
        kept.add_cross(star.edge_sum, star.cross_sum);
        c.add_objective(kept.h, kept.c);
    }
    if !c.full() {
        c.add_objective(cost.h, cost.c);
    }
    if !c.full() {
        c.add_objective(
            DMat3::from_diagonal(DVec3::splat(star.corners)),
            star.corner_sum,
        );
    }
    let p = c.solve()?;
    let margin = DVec3::splat(BOX_MARGIN * pr.length());
    let (lo, hi) = (pr.min(DVec3::ZERO) - margin, pr.max(DVec3::ZERO) + margin);
    (p.cmpge(lo).all() && p.cmple(hi).all()).then_some(p)
}

/// The cheapest of the kept end, the removed end and the midpoint.
fn best_of_ends(cost: &Form, pr: DVec3) -> DVec3 {
    [DVec3::ZERO, pr, 0.5 * pr]
        .into_iter()
        .min_by(|a, b| cost.eval(*a).total_cmp(&cost.eval(*b)))
        .unwrap_or(DVec3::ZERO)
}

/// The cheapest point of the segment from the kept end (the origin) to `pr`: the cost is a
/// parabola along it.
fn along_edge(cost: &Form, pr: DVec3) -> DVec3 {
    let (f0, fh, f1) = (cost.eval(DVec3::ZERO), cost.eval(0.5 * pr), cost.eval(pr));
    super::part::parabola_minimum(f0, fh, f1) * pr
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decimate::qem::collapser::Collapser;
    use crate::decimate::qem::planes::Constraints;
    use glam::Vec3;

    /// The bipyramid's triangles: four around the apex 4, four around the apex 5, with the
    /// square's edge 0–1 split at vertex 6.
    const BIPYRAMID: [[usize; 3]; 10] = [
        [0, 6, 4],
        [6, 1, 4],
        [1, 2, 4],
        [2, 3, 4],
        [3, 0, 4],
        [6, 0, 5],
        [1, 6, 5],
        [2, 1, 5],
        [3, 2, 5],
        [0, 3, 5],
    ];

    /// A closed octahedron-like bipyramid: a square of four around the z axis, an apex at
    /// `z = top` above and `z = -1` below, with vertex 6 on the square's edge 0–1, pulled out
    /// by `bulge` (so that collapsing it changes the volume unless the kept end moves).
    fn bipyramid(top: f32, bulge: f32) -> Collapser {
        let positions = vec![
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(0.0, 0.0, top),
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.5 + bulge, 0.5 + bulge, 0.0),
        ];
        let triangles = BIPYRAMID.iter().map(|t| t.map(|v| v as u32)).collect();
        let constraints = Constraints {
            cos_feature: 0.5,
            scale_folds: false,
            seam: &[],
            result_triangles: None,
        };
        let mut d = Collapser::new(positions, triangles, None, None, constraints);
        d.lt = true;
        d
    }

    /// Six times the signed volume enclosed by the closed `triangles` over `p`.
    fn volume6(p: &[DVec3], triangles: &[[usize; 3]]) -> f64 {
        (triangles.iter())
            .map(|t| p[t[0]].dot(p[t[1]].cross(p[t[2]])))
            .sum()
    }

    #[test]
    fn an_lt_collapse_keeps_a_closed_volume_and_costs_what_it_sweeps() {
        let mut d = bipyramid(1.0, 0.2);
        let before: Vec<DVec3> = (0..7).map(|v| d.whole().position(v)).collect();
        let all = BIPYRAMID;
        let part = d.whole();
        let plan = part.plan(0, 6).expect("an interior edge");
        // The triangles left once the removed end is renamed to the kept one.
        let mut after = before.clone();
        after[plan.keep as usize] = plan.position;
        let renamed: Vec<[usize; 3]> = (all.iter())
            .map(|t| {
                t.map(|v| {
                    if v == plan.remove as usize {
                        plan.keep as usize
                    } else {
                        v
                    }
                })
            })
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
            .collect();
        let (v0, v1) = (volume6(&before, &all), volume6(&after, &renamed));
        assert!((v1 - v0).abs() < 1e-6 * v0, "volume ×6: {v0} → {v1}");
        // Placed so, it costs less than with the kept end left where it was.
        let lt = part.lt_plan([plan.remove, plan.keep], None, false, false);
        let lt = lt.expect("owned");
        let (placed, unmoved) = (
            lt.cost_at(plan.position),
            lt.cost_at(before[plan.keep as usize]),
        );
        assert!(placed < unmoved, "{placed} ≥ {unmoved} unmoved");
    }

    #[test]
    fn a_flat_collapse_costs_nothing_and_stays_in_its_plane() {
        // The bulge's vertex on the square's edge, not pulled out: 0–6–1 is straight, and
        // collapsing 6 into 0 or 1 changes neither the volume nor the surface.
        let mut d = bipyramid(1.0, 0.0);
        let plan = d.whole().plan(0, 6).expect("an interior edge");
        assert!(plan.cost.abs() < 1e-9, "{}", plan.cost);
        assert!(plan.position.z.abs() < 1e-6, "{}", plan.position);
    }

    #[test]
    fn the_forms_price_what_they_stand_for() {
        let mut f = Form::default();
        f.add_plane(DVec3::new(0.0, 0.0, 2.0), 4.0);
        assert!((f.eval(DVec3::new(7.0, -1.0, 3.0)) - 4.0).abs() < 1e-12);
        let mut g = Form::default();
        let (e, w) = (DVec3::X, DVec3::new(0.0, 0.0, -1.0));
        g.add_cross(e, w);
        let v = DVec3::new(0.3, 2.0, 0.5);
        let direct = (e.cross(v) + w).length_squared();
        assert!(
            (g.eval(v) - direct).abs() < 1e-12,
            "{} vs {direct}",
            g.eval(v)
        );
    }
}

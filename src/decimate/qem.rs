//! Quadric edge collapse: M. Garland, P. S. Heckbert, "Surface Simplification Using Quadric
//! Error Metrics", SIGGRAPH 1997, with the boundary constraint planes of that paper and the
//! area weighting of Garland's thesis (1999) and of "Simplifying Surfaces with Color and
//! Texture using Quadric Error Metrics" (Garland, Heckbert, IEEE Visualization 1998).
//!
//! The pipeline over flat arrays, one stage per step:
//! 1. load: renumber vertices along a Morton curve (`mesh::spatial`) for locality, drop
//!    triangles with out-of-range indices; positions are worked in f64, rounded to f32 as
//!    soon as a vertex moves so that every check sees what is written;
//! 2. connect: vertex → triangle incidence (`mesh::topology`) and each vertex's kind
//!    (interior, boundary, complex) from its one-ring shape;
//! 3. quadrics: every triangle adds its plane weighted by its area; every boundary edge adds
//!    a plane through the edge perpendicular to its triangle, weighted `CONSTRAINT_WEIGHT` ×
//!    length², and so does every feature edge (dihedral angle above the feature angle) on
//!    both sides, weighted by how sharp it is, so that outlines and creases stay put;
//! 4. rank: every edge's collapse is planned (which end goes, where the other one moves);
//!    each vertex is queued in an indexed min-heap (`queue::VertexQueue`, keys updated in
//!    place) under its cheapest edge — no stale entries to pop;
//! 5. collapse: take the cheapest, re-plan it, check it is legal (`is_collapse_legal`: a
//!    chain of small named checks; an illegal edge sends its vertex back under its cheapest
//!    legal edge), perform it, add the quadrics, interpolate attributes and re-rank the
//!    kept vertex and its neighbours (a neighbour is re-ranked over all its edges only when
//!    its cheapest edge went to either end);
//! 6. compact: live vertices (at their new positions) and triangles back into the model.
//!
//! Collapses are ordered by the quadric itself, `Q(p)` (area × squared distance, as in the
//! paper), so that large flat-ish regions do not coarsen before small curved ones. The error
//! of a placement is `sqrt(Q(p) / W)`, `W` the summed triangle area behind the quadric — an
//! area-weighted RMS distance to the planes the vertex stands for, in model units. That is
//! what `--max-error` bounds (a collapse above it is skipped) and what the report gives.
//!
//! Per-vertex colours take a simpler route than the 1998 paper's extended quadric: the kept
//! vertex's colour is interpolated along the edge at the projection of its new position, and
//! the cost used to order collapses adds `W × |colour difference|² × edge length²` (colour
//! in 0..=1; the units of `Q`: as if the colour step moved the surface by that fraction of
//! the edge), so edges across colour changes go last. Per-vertex normals are interpolated the
//! same way; per-face colours stay with their surviving faces.

use glam::{DVec3, Vec3};

use super::layout::{self, compact, Compacted};
use super::progressive::{CollapseRecord, ProgressiveModel, Recorder};
use super::queue::VertexQueue;
use super::schroeder::{Limits, Outcome};
use crate::mesh::topology::{Connectivity, Ring, RingShape};
use crate::mesh::{Attribute, Model};

/// Weight of boundary and feature constraint planes relative to an area-weighted face plane.
const CONSTRAINT_WEIGHT: f64 = 100.0;

/// Weight of a feature edge's planes, times `(1 - cos(dihedral))⁶` (15 at a right angle,
/// 0.2 at 60°, 0.01 at 45°): a scan's many mild "features" barely constrain — any real
/// weight on them raises the mean error — while sharp creases hold and keep the maximum
/// down. On the dragon kept at 10 % (metro, 10⁶ samples): with no feature planes mean
/// 9.08e-6 / max 1.10e-3; 400·(1 - cos)² 9.43e-6 / 1.47e-4; this 9.15e-6 / 2.39e-4
/// (vtkQuadricDecimation 9.19e-6 / 1.01e-3, MeshLab 1.04e-5 / 4.97e-4).
const FEATURE_WEIGHT: f64 = 15.0;

/// A triangle is degenerate when its area is this small relative to its longest edge².
const MIN_RELATIVE_AREA: f64 = 1e-8;

/// A placement may leave the edge's bounding box by at most this many edge lengths.
const BOX_MARGIN: f64 = 1.0;

/// Decimates `model` in place by quadric edge collapse within `limits` (the feature angle
/// only picks the feature edges that are constrained; it is never relaxed — QEM needs no
/// relaxing to reach a count). `progress` gets the running removal count.
pub fn decimate_model(
    model: &mut Model,
    limits: &Limits,
    progress: &mut dyn FnMut(usize),
) -> Outcome {
    run(model, limits, progress, None).0
}

/// As [`decimate_model`], and records every collapse: the returned progressive model's base
/// is the decimated `model`, and refining it all the way gives the input back.
pub fn decimate_model_progressive(
    model: &mut Model,
    limits: &Limits,
    progress: &mut dyn FnMut(usize),
) -> (Outcome, ProgressiveModel) {
    let recorder = Recorder::new(model);
    match run(model, limits, progress, Some(recorder)) {
        (outcome, Some(pm)) => (outcome, pm),
        (_, None) => unreachable!("a run given a recorder returns its progressive model"),
    }
}

/// The pipeline; with a `recorder`, every collapse is recorded and the progressive model
/// returned (its base is what is written back into `model`).
fn run(
    model: &mut Model,
    limits: &Limits,
    progress: &mut dyn FnMut(usize),
    recorder: Option<Recorder>,
) -> (Outcome, Option<ProgressiveModel>) {
    // 1. load, renumbered along a Morton curve for memory locality
    let n = model.positions.len() as u32;
    let loaded = layout::load(model);
    let (order, faces) = (&loaded.order, &loaded.faces);
    let positions: Vec<DVec3> = order
        .iter()
        .map(|&v| model.positions[v as usize].as_dvec3())
        .collect();
    let triangles = loaded.triangles(model);
    let per_vertex = |a: &Option<Attribute<[f32; 3]>>| match a {
        Some(Attribute::PerVertex(c)) if c.len() == n as usize => {
            Some(order.iter().map(|&v| c[v as usize]).collect::<Vec<_>>())
        }
        _ => None,
    };
    let colors = per_vertex(&model.colors);
    let normals = match &model.normals {
        Some(Attribute::PerVertex(v)) if v.len() == n as usize => {
            Some(order.iter().map(|&i| v[i as usize].to_array()).collect())
        }
        _ => None,
    };

    // 2. connect
    let mut d = Collapser::new(positions, &triangles, colors, normals);
    d.recorder = recorder;

    // 3. quadrics
    d.fill_quadrics(limits.feature_angle_deg.to_radians().cos());

    // 4. rank
    d.rank_all();

    // 5. collapse
    let mut outcome = Outcome {
        removed: 0,
        max_error: 0.0,
        exhausted: false,
        feature_angle_deg: limits.feature_angle_deg,
    };
    let bound2 = limits.max_error * limits.max_error;
    // Never fewer than four vertices: a model under four is dropped from the scene, and a
    // plane's two triangles or a tetrahedron is as far as collapsing should go.
    let used = (0..n).filter(|&v| !d.conn.incident(v).is_empty()).count();
    let removable = used.saturating_sub(4);
    let mut skipped_for_error = false;
    loop {
        if outcome.removed >= limits.remove || d.conn.triangle_count() <= limits.keep_triangles {
            break;
        }
        if outcome.removed >= removable {
            outcome.exhausted = true;
            break;
        }
        let Some((_, v)) = d.queue.peek() else {
            outcome.exhausted = !skipped_for_error;
            break;
        };
        let plan = d.plan(v, d.best[v as usize]);
        let Some(plan) = plan.filter(|p| d.is_collapse_legal(p)) else {
            d.rank_legal(v);
            continue;
        };
        if plan.error2 > bound2 {
            // The cost weighs area and colour, not just the error: skip the edge; it is
            // re-ranked should its ends change.
            d.queue.remove(v);
            skipped_for_error = true;
            continue;
        }
        d.collapse(&plan);
        outcome.removed += 1;
        outcome.max_error = outcome.max_error.max(plan.error2.sqrt());
        if outcome.removed.is_multiple_of(4096) {
            progress(outcome.removed);
        }
    }
    progress(outcome.removed);

    // 6. compact
    if let Some(recorder) = d.recorder.take() {
        let kept = d.write_back(model, order, faces);
        let pm = recorder.finish(model.clone(), &kept, &d.conn, order, faces);
        return (outcome, Some(pm));
    }
    if outcome.removed > 0 {
        d.write_back(model, order, faces);
    }
    (outcome, None)
}

/// A symmetric 4×4 quadric `Q(p) = pᵀAp + 2b·p + c`, with the area behind it.
#[derive(Debug, Clone, Copy, Default)]
struct Quadric {
    /// `a00 a01 a02 a11 a12 a22`.
    a: [f64; 6],
    b: [f64; 3],
    c: f64,
    area: f64,
}

impl Quadric {
    /// The plane `n·p + d = 0` (unit `n`) with `weight`.
    fn plane(n: DVec3, d: f64, weight: f64) -> Self {
        Self {
            a: [
                weight * n.x * n.x,
                weight * n.x * n.y,
                weight * n.x * n.z,
                weight * n.y * n.y,
                weight * n.y * n.z,
                weight * n.z * n.z,
            ],
            b: [weight * n.x * d, weight * n.y * d, weight * n.z * d],
            c: weight * d * d,
            area: 0.0,
        }
    }

    fn add(&mut self, o: &Self) {
        for i in 0..6 {
            self.a[i] += o.a[i];
        }
        for i in 0..3 {
            self.b[i] += o.b[i];
        }
        self.c += o.c;
        self.area += o.area;
    }

    fn sum(&self, o: &Self) -> Self {
        let mut s = *self;
        s.add(o);
        s
    }

    /// `Q(p)`, never negative.
    fn eval(&self, p: DVec3) -> f64 {
        let [a00, a01, a02, a11, a12, a22] = self.a;
        let ap = DVec3::new(
            a00 * p.x + a01 * p.y + a02 * p.z,
            a01 * p.x + a11 * p.y + a12 * p.z,
            a02 * p.x + a12 * p.y + a22 * p.z,
        );
        let b = DVec3::from_array(self.b);
        (p.dot(ap) + 2.0 * b.dot(p) + self.c).max(0.0)
    }

    /// The minimiser `-A⁻¹b`, or `None` when `A` is (nearly) singular.
    fn minimum(&self) -> Option<DVec3> {
        let [a00, a01, a02, a11, a12, a22] = self.a;
        let c0 = a11 * a22 - a12 * a12;
        let c1 = a02 * a12 - a01 * a22;
        let c2 = a01 * a12 - a02 * a11;
        let det = a00 * c0 + a01 * c1 + a02 * c2;
        let trace = a00 + a11 + a22;
        let singular = det.abs() <= 1e-9 * trace * trace * trace;
        if singular || !det.is_finite() {
            return None;
        }
        // Inverse of a symmetric matrix from its cofactors.
        let i01 = c1;
        let i02 = c2;
        let i11 = a00 * a22 - a02 * a02;
        let i12 = a01 * a02 - a00 * a12;
        let i22 = a00 * a11 - a01 * a01;
        let [b0, b1, b2] = self.b;
        let x = -(c0 * b0 + i01 * b1 + i02 * b2) / det;
        let y = -(i01 * b0 + i11 * b1 + i12 * b2) / det;
        let z = -(i02 * b0 + i12 * b1 + i22 * b2) / det;
        let p = DVec3::new(x, y, z);
        p.is_finite().then_some(p)
    }
}

/// What a vertex's one-ring says about where it may go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Interior,
    Boundary,
    /// Non-manifold, inconsistently oriented, too high a valence, or unused: never moved.
    Fixed,
}

/// A planned collapse: `remove` goes, `keep` moves to `position`.
#[derive(Debug, Clone, Copy)]
struct Plan {
    remove: u32,
    keep: u32,
    position: DVec3,
    /// Squared geometric error of the placement.
    error2: f64,
    /// Cost that orders the queue: the quadric plus the colour term.
    cost: f64,
}

/// The working state of one model's decimation.
struct Collapser {
    positions: Vec<DVec3>,
    conn: Connectivity,
    kinds: Vec<Kind>,
    quadrics: Vec<Quadric>,
    colors: Option<Vec<[f32; 3]>>,
    normals: Option<Vec<[f32; 3]>>,
    /// Each vertex's cheapest edge: the other end, and the cost the queue holds.
    best: Vec<u32>,
    cost: Vec<f64>,
    queue: VertexQueue,
    around_remove: Vec<u32>,
    around_keep: Vec<u32>,
    /// Set when the collapses are recorded for a progressive mesh.
    recorder: Option<Recorder>,
}

impl Collapser {
    fn new(
        positions: Vec<DVec3>,
        triangles: &[[u32; 3]],
        colors: Option<Vec<[f32; 3]>>,
        normals: Option<Vec<[f32; 3]>>,
    ) -> Self {
        let n = positions.len();
        let conn = Connectivity::new(n, triangles);
        let mut ring = Ring::default();
        let kinds = (0..n as u32)
            .map(|v| match conn.ring(v, &mut ring) {
                RingShape::Closed => Kind::Interior,
                RingShape::Open => Kind::Boundary,
                RingShape::Isolated | RingShape::Complex => Kind::Fixed,
            })
            .collect();
        Self {
            positions,
            conn,
            kinds,
            quadrics: vec![Quadric::default(); n],
            colors,
            normals,
            best: vec![u32::MAX; n],
            cost: vec![f64::INFINITY; n],
            queue: VertexQueue::new(n),
            around_remove: Vec::new(),
            around_keep: Vec::new(),
            recorder: None,
        }
    }

    fn corners(&self, t: u32) -> [DVec3; 3] {
        self.conn.triangle(t).map(|v| self.positions[v as usize])
    }

    /// Triangles on the edge `a`–`b`: how many, and the last one found.
    fn edge_triangles(&self, a: u32, b: u32) -> (usize, u32) {
        let mut count = 0;
        let mut last = u32::MAX;
        for &t in self.conn.incident(a) {
            if self.conn.triangle(t).contains(&b) {
                count += 1;
                last = t;
            }
        }
        (count, last)
    }

    /// Area-weighted face planes, plus constraint planes along boundary and feature edges.
    fn fill_quadrics(&mut self, cos_feature: f64) {
        let slots = self.conn.triangles().len() as u32;
        for t in 0..slots {
            let [a, b, c] = self.corners(t);
            let cross = (b - a).cross(c - a);
            let len = cross.length();
            if len <= 0.0 {
                continue;
            }
            let normal = cross / len;
            let area = 0.5 * len;
            let mut q = Quadric::plane(normal, -normal.dot(a), area);
            q.area = area;
            for v in self.conn.triangle(t) {
                self.quadrics[v as usize].add(&q);
            }
            // Each directed edge of the triangle: constrained when it is on the boundary, or
            // a feature edge (seen once, from the triangle whose id is smaller).
            let tri = self.conn.triangle(t);
            for i in 0..3 {
                let (u, w) = (tri[i], tri[(i + 1) % 3]);
                let (count, other) = self.other_triangle(u, w, t);
                let scale = match (count, other) {
                    (1, _) => CONSTRAINT_WEIGHT,
                    (2, Some(o)) if o > t => {
                        let [p, q2, r] = self.corners(o);
                        let cos = normal.dot((q2 - p).cross(r - p).normalize_or_zero());
                        if cos >= cos_feature {
                            continue;
                        }
                        FEATURE_WEIGHT * (1.0 - cos).powi(6)
                    }
                    _ => continue,
                };
                let (pu, pw) = (self.positions[u as usize], self.positions[w as usize]);
                let edge = pw - pu;
                let side = edge.cross(normal).normalize_or_zero();
                let weight = scale * edge.length_squared();
                let q = Quadric::plane(side, -side.dot(pu), weight);
                self.quadrics[u as usize].add(&q);
                self.quadrics[w as usize].add(&q);
                if count == 2 {
                    // A crease is constrained from both of its sides.
                    if let Some(o) = other {
                        let [p, q2, r] = self.corners(o);
                        let n2 = (q2 - p).cross(r - p).normalize_or_zero();
                        let side = edge.cross(n2).normalize_or_zero();
                        let q = Quadric::plane(side, -side.dot(pu), weight);
                        self.quadrics[u as usize].add(&q);
                        self.quadrics[w as usize].add(&q);
                    }
                }
            }
        }
    }

    /// Triangles on edge `u`–`w`, and the one that is not `t` if there are exactly two.
    fn other_triangle(&self, u: u32, w: u32, t: u32) -> (usize, Option<u32>) {
        let mut count = 0;
        let mut other = None;
        for &s in self.conn.incident(u) {
            if self.conn.triangle(s).contains(&w) {
                count += 1;
                if s != t {
                    other = Some(s);
                }
            }
        }
        (count, other)
    }

    /// Queues every vertex under its cheapest edge, planning each edge once (from its
    /// smaller end) for both of its ends.
    fn rank_all(&mut self) {
        let n = self.positions.len() as u32;
        let mut around = Vec::new();
        for v in 0..n {
            self.neighbours_of(v, &mut around);
            for &w in around.iter().filter(|&&w| w > v) {
                let Some(plan) = self.plan(v, w) else {
                    continue;
                };
                for (x, y) in [(v, w), (w, v)] {
                    if plan.cost < self.cost[x as usize] {
                        self.best[x as usize] = y;
                        self.cost[x as usize] = plan.cost;
                    }
                }
            }
        }
        for v in 0..n {
            if self.best[v as usize] != u32::MAX {
                self.queue.set(v, self.cost[v as usize]);
            }
        }
    }

    /// Queues `v` under its cheapest edge (only legal ones when `legal`), or takes it out
    /// when it has none.
    fn rank(&mut self, v: u32, legal: bool) {
        let mut around = std::mem::take(&mut self.around_keep);
        self.neighbours_of(v, &mut around);
        let mut best = (f64::INFINITY, u32::MAX);
        for &w in &around {
            if let Some(plan) = self.plan(v, w) {
                if plan.cost < best.0 && (!legal || self.is_collapse_legal(&plan)) {
                    best = (plan.cost, w);
                }
            }
        }
        self.around_keep = around;
        self.set_best(v, best.1, best.0);
    }

    /// Re-ranks `v` after its cheapest edge turned out illegal.
    fn rank_legal(&mut self, v: u32) {
        self.rank(v, true);
    }

    fn set_best(&mut self, v: u32, w: u32, cost: f64) {
        self.best[v as usize] = w;
        self.cost[v as usize] = cost;
        if w == u32::MAX {
            self.queue.remove(v);
        } else {
            self.queue.set(v, cost);
        }
    }

    /// Distinct vertices sharing a triangle with `v`.
    fn neighbours_of(&self, v: u32, out: &mut Vec<u32>) {
        out.clear();
        for &t in self.conn.incident(v) {
            for w in self.conn.triangle(t) {
                if w != v && !out.contains(&w) {
                    out.push(w);
                }
            }
        }
    }

    /// Which end of `a`–`b` goes and where the other moves, or `None` when the kinds of the
    /// ends forbid any collapse of this edge. The table, from the ends' kinds:
    ///
    /// | a        | b        | edge      | collapse                                          |
    /// |----------|----------|-----------|---------------------------------------------------|
    /// | fixed    | any      | any       | none: a complex vertex never moves                |
    /// | interior | interior | interior  | either way, to the quadric's optimum              |
    /// | interior | boundary | interior  | the interior end into the boundary end, unmoved: a boundary vertex moves only along its boundary |
    /// | boundary | boundary | boundary  | either way, to the optimum (the constraint planes keep it on the outline) |
    /// | boundary | boundary | interior  | none: it would pinch the surface                  |
    fn plan(&self, a: u32, b: u32) -> Option<Plan> {
        let (ka, kb) = (self.kinds[a as usize], self.kinds[b as usize]);
        let (remove, keep, free) = match (ka, kb) {
            (Kind::Fixed, _) | (_, Kind::Fixed) => return None,
            (Kind::Interior, Kind::Interior) => (a, b, true),
            (Kind::Interior, Kind::Boundary) => (a, b, false),
            (Kind::Boundary, Kind::Interior) => (b, a, false),
            (Kind::Boundary, Kind::Boundary) => {
                if self.edge_triangles(a, b).0 != 1 {
                    return None;
                }
                (a, b, true)
            }
        };
        let q = self.quadrics[a as usize].sum(&self.quadrics[b as usize]);
        let (pr, pk) = (
            self.positions[remove as usize],
            self.positions[keep as usize],
        );
        let position = if free { self.place(&q, pr, pk) } else { pk };
        // What is written is f32: plan with exactly that.
        let position = position.as_vec3().as_dvec3();
        let mut cost = q.eval(position);
        let error2 = cost / q.area.max(f64::MIN_POSITIVE);
        if let Some(c) = &self.colors {
            let (cr, ck) = (c[remove as usize], c[keep as usize]);
            let dc = Vec3::from_array(cr) - Vec3::from_array(ck);
            cost += q.area * dc.length_squared() as f64 * (pk - pr).length_squared();
        }
        Some(Plan {
            remove,
            keep,
            position,
            error2,
            cost,
        })
    }

    /// The quadric's minimum when it exists and stays within a box around the edge `pr`–`pk`;
    /// otherwise the best of the kept end, the removed end and the midpoint.
    fn place(&self, q: &Quadric, pr: DVec3, pk: DVec3) -> DVec3 {
        let margin = DVec3::splat(BOX_MARGIN * (pk - pr).length());
        let (lo, hi) = (pr.min(pk) - margin, pr.max(pk) + margin);
        if let Some(p) = q.minimum() {
            if p.cmpge(lo).all() && p.cmple(hi).all() {
                return p;
            }
        }
        let mut best = pk;
        let mut best_error = q.eval(pk);
        for p in [pr, 0.5 * (pr + pk)] {
            let e = q.eval(p);
            if e < best_error {
                best = p;
                best_error = e;
            }
        }
        best
    }

    /// pmp's `is_collapse_legal`, as a chain of small checks.
    fn is_collapse_legal(&mut self, plan: &Plan) -> bool {
        self.link_condition_holds(plan)
            && self.no_duplicate_triangle(plan)
            && self.no_triangle_flips_or_degenerates(plan)
    }

    /// Link condition (Dey et al.): the ends share no neighbour but the apexes of the
    /// triangles on the edge — otherwise the result would be non-manifold. A boundary edge
    /// also must not be the last edge of a triangle whose other two edges are on the boundary.
    fn link_condition_holds(&mut self, plan: &Plan) -> bool {
        let mut around_remove = std::mem::take(&mut self.around_remove);
        let mut around_keep = std::mem::take(&mut self.around_keep);
        self.neighbours_of(plan.remove, &mut around_remove);
        self.neighbours_of(plan.keep, &mut around_keep);
        let common = around_remove
            .iter()
            .filter(|w| around_keep.contains(w))
            .count();
        let (on_edge, t) = self.edge_triangles(plan.remove, plan.keep);
        self.around_remove = around_remove;
        self.around_keep = around_keep;
        if common != on_edge || !(1..=2).contains(&on_edge) {
            return false;
        }
        if on_edge == 1 {
            let apex = self
                .conn
                .triangle(t)
                .into_iter()
                .find(|&w| w != plan.remove && w != plan.keep);
            if let Some(w) = apex {
                let lone = self.edge_triangles(plan.remove, w).0 == 1
                    && self.edge_triangles(plan.keep, w).0 == 1;
                if lone {
                    return false;
                }
            }
        }
        true
    }

    /// A triangle of the removed end, renamed to the kept end, must not already exist (the
    /// last step before a tetrahedron folds flat).
    fn no_duplicate_triangle(&self, plan: &Plan) -> bool {
        self.conn.incident(plan.remove).iter().all(|&t| {
            let tri = self.conn.triangle(t);
            if tri.contains(&plan.keep) {
                return true;
            }
            let [x, y] = others(tri, plan.remove);
            !self.conn.has_triangle(plan.keep, x, y)
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
                        self.positions[w as usize]
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

    /// Performs a legal collapse and re-ranks the edges around the kept vertex.
    fn collapse(&mut self, plan: &Plan) {
        let (r, k) = (plan.remove as usize, plan.keep as usize);
        // Attributes at the projection of the new position on the edge.
        let (pr, pk) = (self.positions[r], self.positions[k]);
        let edge = pr - pk;
        let s = if edge.length_squared() > 0.0 {
            ((plan.position - pk).dot(edge) / edge.length_squared()).clamp(0.0, 1.0) as f32
        } else {
            0.0
        };
        let lerp = |x: [f32; 3], y: [f32; 3]| {
            (Vec3::from_array(y) + s * (Vec3::from_array(x) - Vec3::from_array(y))).to_array()
        };
        let colors_before = self.colors.as_ref().map(|c| (c[k], c[r]));
        let normals_before = self.normals.as_ref().map(|n| (n[k], n[r]));
        if let Some(c) = &mut self.colors {
            c[k] = lerp(c[r], c[k]);
        }
        if let Some(n) = &mut self.normals {
            n[k] = Vec3::from_array(lerp(n[r], n[k]))
                .normalize_or_zero()
                .to_array();
        }
        // Topology: the edge's triangles go, the removed end's others are renamed in place,
        // so per-face attributes stay with their faces and no slot is ever reused.
        let incident: Vec<u32> = self.conn.incident(plan.remove).to_vec();
        let mut renamed = Vec::with_capacity(incident.len());
        let mut deleted = Vec::with_capacity(2);
        for t in incident {
            let tri = self.conn.triangle(t);
            if tri.contains(&plan.keep) {
                self.conn.remove_triangle(t);
                deleted.push((t, tri));
            } else {
                self.conn.rename_corner(t, plan.remove, plan.keep);
                renamed.push(t);
            }
        }
        if let Some(recorder) = &mut self.recorder {
            recorder.collapse(CollapseRecord {
                keep: plan.keep,
                remove: plan.remove,
                keep_before: pk.as_vec3(),
                keep_after: plan.position.as_vec3(),
                removed_position: pr.as_vec3(),
                colors: colors_before
                    .zip(self.colors.as_ref())
                    .map(|((ck, cr), c)| [ck, c[k], cr]),
                normals: normals_before
                    .zip(self.normals.as_ref())
                    .map(|((nk, nr), n)| [nk, n[k], nr].map(Vec3::from_array)),
                renamed: &renamed,
                deleted: &deleted,
            });
        }
        self.positions[k] = plan.position;
        let q = self.quadrics[r];
        self.quadrics[k].add(&q);
        self.kinds[r] = Kind::Fixed;
        self.set_best(plan.remove, u32::MAX, f64::INFINITY);
        // Re-rank: the kept vertex over all its edges; a neighbour fully only when its
        // cheapest edge led to either end, otherwise its edge to the kept vertex may now be
        // cheaper. Edges elsewhere did not change.
        let mut around = std::mem::take(&mut self.around_remove);
        self.neighbours_of(plan.keep, &mut around);
        let mut best = (f64::INFINITY, u32::MAX);
        for &w in &around {
            let cost = self.plan(plan.keep, w).map_or(f64::INFINITY, |p| p.cost);
            if cost < best.0 {
                best = (cost, w);
            }
            let b = self.best[w as usize];
            if b == plan.keep || b == plan.remove || b == u32::MAX {
                self.rank(w, false);
            } else if cost < self.cost[w as usize] {
                self.set_best(w, plan.keep, cost);
            }
        }
        self.around_remove = around;
        self.set_best(plan.keep, best.1, best.0);
    }

    /// Writes live vertices (at their new positions) and triangles back into `model`.
    /// `order` maps internal vertex ids to the model's, `faces` internal triangle slots to the
    /// model's faces. Kept vertices keep their relative order from the input.
    /// Returns the kept vertices' internal ids, in the written order.
    fn write_back(&self, model: &mut Model, order: &[u32], faces: &[u32]) -> Vec<u32> {
        let mut inverse = vec![0u32; order.len()];
        for (i, &v) in order.iter().enumerate() {
            inverse[v as usize] = i as u32;
        }
        let Compacted {
            kept_vertices,
            faces,
            triangles,
        } = compact(&self.conn, order, faces);
        model.triangles = triangles;
        model.positions = kept_vertices
            .iter()
            .map(|&v| self.positions[inverse[v as usize] as usize].as_vec3())
            .collect();
        let internal_of = |v: &u32| inverse[*v as usize] as usize;
        model.colors = match (&self.colors, &model.colors) {
            (Some(c), _) => Some(Attribute::PerVertex(
                kept_vertices.iter().map(|v| c[internal_of(v)]).collect(),
            )),
            (None, Some(a @ Attribute::PerFace(_))) => Some(a.select(&kept_vertices, &faces)),
            (None, _) => None,
        };
        model.normals = self.normals.as_ref().map(|n| {
            Attribute::PerVertex(
                kept_vertices
                    .iter()
                    .map(|v| Vec3::from_array(n[internal_of(v)]))
                    .collect(),
            )
        });
        kept_vertices
            .iter()
            .map(internal_of)
            .map(|i| i as u32)
            .collect()
    }
}

/// The two corners of `tri` other than `v`, in the triangle's cyclic order after `v`.
fn others(tri: [u32; 3], v: u32) -> [u32; 2] {
    match tri.iter().position(|&w| w == v) {
        Some(0) => [tri[1], tri[2]],
        Some(1) => [tri[2], tri[0]],
        _ => [tri[0], tri[1]],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_planes_meet_at_their_corner() {
        let mut q = Quadric::default();
        for (n, d) in [(DVec3::X, -1.0), (DVec3::Y, -2.0), (DVec3::Z, -3.0)] {
            q.add(&Quadric::plane(n, d, 1.0));
        }
        let p = q.minimum().unwrap_or(DVec3::ZERO);
        assert!((p - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
        assert!(q.eval(p) < 1e-12);
        // Two planes leave a line: singular.
        let mut line = Quadric::default();
        line.add(&Quadric::plane(DVec3::X, 0.0, 1.0));
        line.add(&Quadric::plane(DVec3::Y, 0.0, 1.0));
        assert!(line.minimum().is_none());
        assert_eq!(line.eval(DVec3::new(0.0, 0.0, 5.0)), 0.0);
        assert_eq!(line.eval(DVec3::new(3.0, 4.0, 0.0)), 25.0);
    }
}

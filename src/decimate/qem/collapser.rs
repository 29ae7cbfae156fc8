//! The working state of one model's quadric decimation and the operations on it: which
//! way an edge collapses and where the kept vertex goes (`plan`), performing a collapse
//! (topology, quadrics, attributes, the progressive record) and writing the result back.
//! The checks live in `legality`, the cost cache in `ranking`, the loop in `passes`.

use glam::{DVec3, Vec3};

use super::planes;
use super::quadric::Quadric;
use super::ranking::EdgeCosts;
use crate::decimate::layout::{compact, Compacted};
use crate::decimate::progressive::{CollapseRecord, Recorder};
use crate::mesh::topology::Connectivity;
use crate::mesh::{Attribute, Model};

/// A placement may leave the edge's bounding box by at most this many edge lengths.
const BOX_MARGIN: f64 = 1.0;

/// What a vertex's one-ring says about where it may go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Interior,
    Boundary,
    /// Non-manifold, inconsistently oriented, too high a valence, or unused: never moved.
    Fixed,
}

/// A planned collapse: `remove` goes, `keep` moves to `position`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plan {
    pub remove: u32,
    pub keep: u32,
    pub position: DVec3,
    /// Squared geometric error of the placement.
    pub error2: f64,
    /// Cost that orders the collapses: the quadric plus the colour term.
    pub cost: f64,
}

/// The working state of one model's decimation.
pub(super) struct Collapser {
    /// f32 as written: a moved vertex is placed at an f32 position (see `plan`).
    positions: Vec<Vec3>,
    pub conn: Connectivity,
    pub kinds: Vec<Kind>,
    quadrics: Vec<Quadric>,
    colors: Option<Vec<[f32; 3]>>,
    normals: Option<Vec<[f32; 3]>>,
    /// Planned cost of every edge, per half-edge slot.
    pub costs: EdgeCosts,
    /// Each vertex's cheapest unblocked edge: the other end (`u32::MAX`: none) and its cost.
    pub best: Vec<u32>,
    pub best_cost: Vec<f32>,
    /// Vertices with a blocked edge.
    pub has_blocked: Vec<bool>,
    /// Visit stamps per vertex for the link condition, and the next stamp.
    pub stamps: Vec<u32>,
    pub stamp: u32,
    /// Scratch list of a vertex's incident triangles.
    incident: Vec<u32>,
    /// Scratch lists of a collapse's renamed and deleted triangles.
    scratch: (Vec<u32>, Vec<(u32, [u32; 3])>),
    /// Set when the collapses are recorded for a progressive mesh.
    pub recorder: Option<Recorder>,
}

impl Collapser {
    /// The state for `triangles` over `positions`: connectivity, every vertex's kind and
    /// starting quadric (`planes`; `cos_feature` picks the constrained feature edges).
    pub fn new(
        positions: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
        colors: Option<Vec<[f32; 3]>>,
        normals: Option<Vec<[f32; 3]>>,
        cos_feature: f64,
    ) -> Self {
        let n = positions.len();
        let conn = Connectivity::from_triangles(n, triangles);
        let (kinds, quadrics) = planes::kinds_and_quadrics(&conn, &positions, cos_feature);
        Self {
            positions,
            costs: EdgeCosts::new(conn.triangles().len()),
            conn,
            kinds,
            quadrics,
            colors,
            normals,
            best: vec![u32::MAX; n],
            best_cost: vec![f32::INFINITY; n],
            has_blocked: vec![false; n],
            stamps: vec![0; n],
            stamp: 0,
            incident: Vec::new(),
            scratch: (Vec::new(), Vec::new()),
            recorder: None,
        }
    }

    /// Starts loading what collapsing an edge of `v` reads first (a hint).
    pub fn prefetch(&self, v: u32) {
        let i = v as usize;
        if i < self.positions.len() {
            crate::mesh::prefetch(&self.quadrics[i]);
            crate::mesh::prefetch(&self.positions[i]);
            crate::mesh::prefetch(&self.best[i]);
            self.conn.prefetch_incident(v);
        }
    }

    /// Starts loading `v`'s incident triangles, their corners' positions and their edge
    /// costs (a hint; `v`'s incident list should be loaded by now).
    pub fn prefetch_fan(&self, v: u32) {
        if (v as usize) < self.positions.len() {
            for &t in self.conn.incident(v) {
                self.conn.prefetch_triangle(t);
                self.costs.prefetch(3 * t as usize);
            }
        }
    }

    /// Vertex count.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn position(&self, v: u32) -> DVec3 {
        self.positions[v as usize].as_dvec3()
    }

    pub fn corners(&self, t: u32) -> [DVec3; 3] {
        self.conn.triangle(t).map(|v| self.position(v))
    }

    /// Triangles on the edge `a`–`b`: how many, and the last one found.
    pub fn edge_triangles(&self, a: u32, b: u32) -> (usize, u32) {
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
    pub fn plan(&self, a: u32, b: u32) -> Option<Plan> {
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
        let (pr, pk) = (self.position(remove), self.position(keep));
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

    /// Performs a legal collapse; the kept vertex's edges are left to be re-planned.
    pub fn collapse(&mut self, plan: &Plan) {
        let (r, k) = (plan.remove as usize, plan.keep as usize);
        // Attributes at the projection of the new position on the edge.
        let (pr, pk) = (self.position(plan.remove), self.position(plan.keep));
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
        let mut incident = std::mem::take(&mut self.incident);
        incident.clear();
        incident.extend_from_slice(self.conn.incident(plan.remove));
        let (mut renamed, mut deleted) = std::mem::take(&mut self.scratch);
        renamed.clear();
        deleted.clear();
        for &t in &incident {
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
        self.positions[k] = plan.position.as_vec3();
        let q = self.quadrics[r];
        self.quadrics[k].add(&q);
        self.kinds[r] = Kind::Fixed;
        self.incident = incident;
        self.scratch = (renamed, deleted);
    }

    /// Writes live vertices (at their new positions) and triangles back into `model`.
    /// `order` maps internal vertex ids to the model's, `faces` internal triangle slots to the
    /// model's faces. Kept vertices keep their relative order from the input.
    /// Returns the kept vertices' internal ids, in the written order.
    pub fn write_back(&self, model: &mut Model, order: &[u32], faces: &[u32]) -> Vec<u32> {
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
            .map(|&v| self.positions[inverse[v as usize] as usize])
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
pub(super) fn others(tri: [u32; 3], v: u32) -> [u32; 2] {
    match tri.iter().position(|&w| w == v) {
        Some(0) => [tri[1], tri[2]],
        Some(1) => [tri[2], tri[0]],
        _ => [tri[0], tri[1]],
    }
}

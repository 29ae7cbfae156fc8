//! Schroeder vertex removal: W. J. Schroeder, J. A. Zarge, W. E. Lorensen, "Decimation of
//! Triangle Meshes", SIGGRAPH 1992 — the algorithm of the 2002 program, in full.
//!
//! The pipeline over flat arrays, one stage per step:
//! 1. load: drop triangles with out-of-range indices (positions stay f32 — vertex removal
//!    never moves a vertex — and all arithmetic is f64);
//! 2. connect: vertex → triangle incidence (`mesh::topology`);
//! 3. classify every vertex (`mesh::classify`) and rank the removable ones by their
//!    decimation criterion in a priority queue:
//!    simple → distance to the loop's average plane (area-weighted normal and centre);
//!    boundary → distance to the line through its two boundary neighbours;
//!    interior edge → distance to the line through its two feature neighbours;
//!    plus the error already accumulated at the vertex by earlier removals around it, so that
//!    the queue's key bounds the distance to the original surface (as VTK's later
//!    implementation of the paper does); pinned vertices (seam junctions, `mesh::seams`;
//!    borders shared with another model, `mesh::stitches`) are never queued, and the two
//!    sides of a texture seam (twins) go together or not at all (`try_remove_twins`);
//! 4. remove: pop the smallest, fill its hole by recursive loop splitting
//!    (`loop_split`), keeping creases (an interior-edge vertex's loop is first split along its
//!    feature edge) and rejecting fills that flip or degenerate a triangle or create an edge
//!    that already exists (non-manifold) — such a vertex is kept; then re-rank the loop;
//! 5. compact: live vertices and triangles (and their colours, normals and texture
//!    coordinates, which a removal never changes) back into the model's arrays.
//!
//! Entries in the queue are invalidated lazily by a per-vertex version number, so each
//! removal costs O(valence² + log n) and nothing in the loop is quadratic in the mesh size.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::layout::{self, compact, Compacted};
use super::loop_split;
use super::queue::VertexQueue;
use crate::mesh::classify::{classify, RingGeometry, VertexClass};
use crate::mesh::topology::{Connectivity, Ring};
use crate::mesh::{Attribute, Model};

/// How far one model may be decimated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Most vertices to remove.
    pub remove: usize,
    /// Stop once this many triangles or fewer are left.
    pub keep_triangles: usize,
    /// Never make a removal whose error exceeds this (model units).
    pub max_error: f64,
    /// Dihedral angle in degrees above which an edge is a feature edge.
    pub feature_angle_deg: f64,
    /// When no candidate is left before `remove`/`keep_triangles` is reached, raise the
    /// feature angle in `RELAX_STEP_DEG` steps (up to 180°) and go on.
    pub relax_features: bool,
}

/// How much the feature angle grows each time a count target could not otherwise be met.
pub const RELAX_STEP_DEG: f64 = 15.0;

/// What decimating one model did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    pub removed: usize,
    /// Largest queue key of a removal made (accumulated distance, model units).
    pub max_error: f64,
    /// True when no candidate was left: nothing more can be removed.
    pub exhausted: bool,
    /// The feature angle in force at the end (larger than asked when relaxed).
    pub feature_angle_deg: f64,
    /// Vertices never removed because they were pinned (texture seams, `mesh::seams`, and
    /// borders shared with another model, `mesh::stitches`).
    pub pinned: usize,
}

/// Decimates `model` in place within `limits`, never removing a vertex flagged in `pins`
/// (indexed like the model's positions: texture seams, shared borders) and removing the
/// vertices `twins` pairs (the two sides of a texture seam, `mesh::seams::Seams::twin`; may
/// be empty) only together; `progress` gets the running removal count.
pub fn decimate_model(
    model: &mut Model,
    limits: &Limits,
    pins: &[bool],
    twins: &[u32],
    progress: &mut dyn FnMut(usize),
) -> Outcome {
    // 1. load, renumbered along a Morton curve, triangles sorted by their first vertex:
    //    memory locality for everything below
    let mut loaded = layout::load(model);
    let positions: Vec<Vec3> = loaded
        .order
        .iter()
        .map(|&v| model.positions[v as usize])
        .collect();
    let mut faces = std::mem::take(&mut loaded.faces);
    faces.sort_by_cached_key(|&t| loaded.triangle(model, t).into_iter().min());
    loaded.faces = faces;
    let triangles = loaded.triangles(model);
    let pinned: Vec<bool> = loaded
        .order
        .iter()
        .map(|&v| pins.get(v as usize).copied().unwrap_or(false))
        .collect();

    // 2. connect
    let mut d = Decimator::new(positions, &triangles, limits.feature_angle_deg);
    let pinned_count = pinned.iter().filter(|&&p| p).count();
    d.pinned = pinned;
    d.twins = loaded.pairs(twins);

    // 3. classify and rank
    d.rank_all();

    // 4. remove
    let mut outcome = Outcome {
        removed: 0,
        max_error: 0.0,
        exhausted: false,
        feature_angle_deg: limits.feature_angle_deg,
        pinned: pinned_count,
    };
    loop {
        if outcome.removed >= limits.remove || d.conn.triangle_count() <= limits.keep_triangles {
            break;
        }
        let Some((key, v)) = d.queue.peek() else {
            // Out of candidates before the target: a coarse scan has "features" everywhere.
            // Relax the feature angle, re-rank what is left, and go on.
            if limits.relax_features && outcome.feature_angle_deg < 180.0 {
                outcome.feature_angle_deg = (outcome.feature_angle_deg + RELAX_STEP_DEG).min(180.0);
                d.cos_feature = outcome.feature_angle_deg.to_radians().cos();
                d.rank_all();
                continue;
            }
            outcome.exhausted = true;
            break;
        };
        if key > limits.max_error {
            break;
        }
        d.queue.remove(v);
        let twin = d.twins.get(v as usize).copied().unwrap_or(u32::MAX);
        let removed = if twin == u32::MAX {
            d.try_remove(v, key).then_some((1, key))
        } else {
            // Two vertices and two triangles go: only while both counts allow it.
            let room = limits.remove - outcome.removed >= 2
                && d.conn.triangle_count() >= limits.keep_triangles + 2;
            d.queue.remove(twin);
            room.then(|| d.try_remove_twins(v, twin, key))
                .flatten()
                .map(|key| (2, key))
        };
        if let Some((count, key)) = removed {
            outcome.removed += count;
            outcome.max_error = outcome.max_error.max(key);
            if outcome.removed % 4096 < count {
                progress(outcome.removed);
            }
        }
    }
    progress(outcome.removed);

    // 5. compact
    if outcome.removed > 0 {
        d.write_back(model, &loaded.order, &loaded.faces);
    }
    outcome
}

/// The working state of one model's decimation.
struct Decimator {
    positions: Vec<Vec3>,
    conn: Connectivity,
    /// Error already accumulated around each vertex by earlier removals.
    accumulated: Vec<f64>,
    queue: VertexQueue,
    cos_feature: f64,
    scratch: Scratch,
    fill: Vec<[u32; 3]>,
    /// Which ring triangles each stretch of `fill` replaces: one region for a closed or open
    /// ring, one per side of a crease.
    regions: Vec<FillRegion>,
    loop_buf: Vec<u32>,
    neighbours: Vec<u32>,
    /// Vertices never removed: texture seams and shared borders.
    pinned: Vec<bool>,
    /// Each seam vertex's other side, removed only together with it (`u32::MAX`: none;
    /// empty when the model has no such pairs).
    twins: Vec<u32>,
    /// The first twin's plan while the second is planned: ring vertices, ring triangles,
    /// fill.
    twin_plan: (Vec<u32>, Vec<u32>, Vec<[u32; 3]>),
}

/// The fill triangles from the previous region's `end` up to this `end` replace the ring
/// triangles `from..to` (indices modulo the ring's length).
#[derive(Debug, Clone, Copy)]
struct FillRegion {
    end: usize,
    from: usize,
    to: usize,
}

/// A fill is rejected when a new triangle's area is this small relative to its longest edge².
const MIN_RELATIVE_AREA: f64 = 1e-10;

impl Decimator {
    fn new(positions: Vec<Vec3>, triangles: &[[u32; 3]], feature_angle_deg: f64) -> Self {
        let n = positions.len();
        Self {
            conn: Connectivity::new(n, triangles),
            positions,
            accumulated: vec![0.0; n],
            queue: VertexQueue::new(n),
            cos_feature: feature_angle_deg.to_radians().cos(),
            scratch: Scratch::default(),
            fill: Vec::new(),
            regions: Vec::new(),
            loop_buf: Vec::new(),
            neighbours: Vec::new(),
            pinned: vec![false; n],
            twins: Vec::new(),
            twin_plan: Default::default(),
        }
    }

    /// Classifies `v` into the scratch ring and returns its class and criterion distance.
    fn evaluate(&mut self, v: u32) -> Option<(VertexClass, f64)> {
        evaluate(
            &self.conn,
            &self.positions,
            self.cos_feature,
            v,
            &mut self.scratch,
        )
    }

    fn average_plane(
        &self,
        p: DVec3,
        indices: impl Iterator<Item = usize>,
    ) -> Option<(DVec3, DVec3)> {
        average_plane(&self.positions, &self.scratch, p, indices)
    }

    /// Ranks every vertex afresh, in parallel (each key depends only on its own ring), and
    /// rebuilds the queue from the keys in linear time.
    fn rank_all(&mut self) {
        let (conn, positions, cos_feature) = (&self.conn, &self.positions, self.cos_feature);
        let (accumulated, pinned) = (&self.accumulated, &self.pinned);
        // An indexed collect writes straight into one vector of exactly n keys.
        let keys: Vec<f64> = (0..positions.len() as u32)
            .into_par_iter()
            .map_init(Scratch::default, |scratch, v| {
                match evaluate(conn, positions, cos_feature, v, scratch) {
                    Some((class, distance)) if class.removable() && !pinned[v as usize] => {
                        distance + accumulated[v as usize]
                    }
                    _ => f64::NAN, // not queued
                }
            })
            .collect();
        let entries: Vec<(f64, u32)> = (0..keys.len() as u32)
            .filter(|&v| !keys[v as usize].is_nan())
            .map(|v| (keys[v as usize], v))
            .collect();
        drop(keys);
        self.queue = VertexQueue::from_entries(positions.len(), entries);
    }

    /// (Re)computes `v`'s queue key; queues `v` when removable, takes it out otherwise.
    fn rank(&mut self, v: u32) {
        match self.evaluate(v) {
            Some((class, distance)) if class.removable() && !self.pinned[v as usize] => {
                self.queue.set(v, distance + self.accumulated[v as usize]);
            }
            _ => self.queue.remove(v),
        }
    }

    /// Removes `v` and fills its hole; false (and nothing changed) when it cannot be filled.
    fn try_remove(&mut self, v: u32, key: f64) -> bool {
        if self.plan_removal(v).is_none() {
            return false;
        }
        self.apply_plan(key);
        true
    }

    /// Classifies `v` and plans its removal into the scratch ring and `fill`: its class and
    /// key (distance plus accumulated error) when the hole can be filled validly.
    fn plan_removal(&mut self, v: u32) -> Option<(VertexClass, f64)> {
        let (class, distance) = self.evaluate(v)?;
        self.fill.clear();
        self.regions.clear();
        let ok = match class {
            VertexClass::Simple => self.fill_closed(v),
            VertexClass::Boundary => self.fill_open(v),
            VertexClass::InteriorEdge { first, second } => self.fill_crease(v, first, second),
            _ => false,
        };
        (ok && self.fill_is_valid(v)).then_some((class, distance + self.accumulated[v as usize]))
    }

    /// Applies the planned removal (scratch ring, `fill`): old triangles out, new ones in
    /// (reusing their slots, so per-face attributes of the region carry over), and the
    /// ring re-ranked with `key` as the error accumulated around it.
    fn apply_plan(&mut self, key: f64) {
        self.neighbours.clear();
        self.neighbours.extend_from_slice(&self.scratch.ring.verts);
        for i in 0..self.scratch.ring.triangles.len() {
            let t = self.scratch.ring.triangles[i];
            self.conn.remove_triangle(t);
        }
        for i in 0..self.fill.len() {
            let tri = self.fill[i];
            self.conn.add_triangle(tri);
        }
        for i in 0..self.neighbours.len() {
            let u = self.neighbours[i];
            let acc = &mut self.accumulated[u as usize];
            *acc = acc.max(key);
            self.rank(u);
        }
    }

    /// Removes the two sides `v`, `w` of a texture seam together, or neither: both must be
    /// boundary vertices whose boundary neighbours lie at the same two points, with rings
    /// apart, and both holes must fill validly. Each hole is then closed by the edge between
    /// those points, so the seam's sides stay on one line. Returns the larger key.
    fn try_remove_twins(&mut self, v: u32, w: u32, key: f64) -> Option<f64> {
        let (class, key_v) = self.plan_removal(v)?;
        if class != VertexClass::Boundary {
            return None;
        }
        let ends = |d: &Self| {
            let r = &d.scratch.ring.verts;
            let at = |i: usize| {
                d.positions[r[i] as usize]
                    .to_array()
                    .map(|x| (x + 0.0).to_bits())
            };
            let (a, b) = (at(0), at(r.len() - 1));
            (a.min(b), a.max(b))
        };
        let v_ends = ends(self);
        let (mut verts, mut tris, mut fill) = std::mem::take(&mut self.twin_plan);
        verts.clone_from(&self.scratch.ring.verts);
        tris.clone_from(&self.scratch.ring.triangles);
        fill.clone_from(&self.fill);
        let planned = self.plan_removal(w).filter(|&(class, _)| {
            class == VertexClass::Boundary
                && ends(self) == v_ends
                && !self
                    .scratch
                    .ring
                    .verts
                    .iter()
                    .any(|u| *u == v || verts.contains(u))
                && !verts.contains(&w)
        });
        let result = planned.map(|(_, key_w)| {
            let key = key.max(key_v).max(key_w);
            self.apply_plan(key);
            std::mem::swap(&mut self.scratch.ring.verts, &mut verts);
            std::mem::swap(&mut self.scratch.ring.triangles, &mut tris);
            std::mem::swap(&mut self.fill, &mut fill);
            self.apply_plan(key);
            key
        });
        self.twin_plan = (verts, tris, fill);
        result
    }

    /// Interior vertex: triangulate the whole closed loop over its average plane.
    fn fill_closed(&mut self, v: u32) -> bool {
        let p = self.positions[v as usize].as_dvec3();
        let Some((normal, _)) = self.average_plane(p, 0..self.scratch.geometry.crosses.len())
        else {
            return false;
        };
        let r = &self.scratch.ring.verts;
        if r.len() == 3 && self.conn.has_triangle(r[0], r[1], r[2]) {
            return false; // would duplicate a face: the last step before a tetrahedron
        }
        self.fill_whole_ring(normal)
    }

    /// Triangulates the whole ring over the plane of `normal`, as one region.
    fn fill_whole_ring(&mut self, normal: DVec3) -> bool {
        let filled = loop_split::triangulate(
            &self.positions,
            &self.scratch.ring.verts,
            normal,
            &mut self.fill,
        );
        self.regions.push(FillRegion {
            end: self.fill.len(),
            from: 0,
            to: self.scratch.ring.triangles.len(),
        });
        filled
    }

    /// Boundary vertex: the open path plus the closing edge between its ends.
    fn fill_open(&mut self, v: u32) -> bool {
        let r = &self.scratch.ring.verts;
        let (first, last) = (r[0], r[r.len() - 1]);
        if r.len() == 2 {
            // A lone triangle: removing it leaves its far edge on the boundary, which must
            // then still belong to another triangle.
            return self.conn.has_edge_avoiding(first, last, v);
        }
        if self.conn.has_edge_avoiding(first, last, v) {
            return false;
        }
        let p = self.positions[v as usize].as_dvec3();
        let Some((normal, _)) = self.average_plane(p, 0..self.scratch.geometry.crosses.len())
        else {
            return false;
        };
        self.fill_whole_ring(normal)
    }

    /// Interior-edge vertex: split along the crease first, then fill each side on its own
    /// average plane, so the crease line survives.
    fn fill_crease(&mut self, v: u32, first: usize, second: usize) -> bool {
        let r = &self.scratch.ring.verts;
        let k = r.len();
        if second - first < 2 || k - second + first < 2 {
            return false; // one side is a single triangle: no room to split
        }
        if self.conn.has_edge_avoiding(r[first], r[second], v) {
            return false;
        }
        let p = self.positions[v as usize].as_dvec3();
        let sides = [(first, second), (second, first + k)];
        for (from, to) in sides {
            let Some((normal, _)) = self.average_plane(p, (from..to).map(|i| i % k)) else {
                return false;
            };
            self.loop_buf.clear();
            self.loop_buf
                .extend((from..=to).map(|i| self.scratch.ring.verts[i % k]));
            if !loop_split::triangulate(&self.positions, &self.loop_buf, normal, &mut self.fill) {
                return false;
            }
            self.regions.push(FillRegion {
                end: self.fill.len(),
                from,
                to,
            });
        }
        true
    }

    /// The fill must not flip or degenerate a triangle and must not create an edge that
    /// already exists elsewhere (the result would be non-manifold). A new triangle is
    /// compared with the old triangles of its own region only: across a crease the two sides
    /// may face apart by up to 180°.
    fn fill_is_valid(&self, v: u32) -> bool {
        let r = &self.scratch.ring.verts;
        let k = r.len();
        let closed = k == self.scratch.ring.triangles.len();
        let is_ring_edge = |a: u32, b: u32| {
            let (Some(i), Some(j)) = (
                r.iter().position(|&x| x == a),
                r.iter().position(|&x| x == b),
            ) else {
                return false;
            };
            let d = i.abs_diff(j);
            d == 1 || (closed && d == k - 1)
        };
        let crosses = &self.scratch.geometry.crosses;
        let mut start = 0;
        for &region in &self.regions {
            // Normal of the old region: the sum of its ring triangles' area vectors.
            let old: DVec3 = (region.from..region.to).map(|i| crosses[i % k]).sum();
            for tri in &self.fill[start..region.end] {
                let [a, b, c] = tri.map(|i| self.positions[i as usize].as_dvec3());
                let cross = (b - a).cross(c - a);
                let longest = (b - a)
                    .length_squared()
                    .max((c - b).length_squared())
                    .max((a - c).length_squared());
                if cross.length() <= MIN_RELATIVE_AREA * longest {
                    return false;
                }
                // Flip test against the old triangles this one covers: it must face the same
                // way as at least the region as a whole and as the nearest old triangle.
                if cross.dot(old) <= 0.0 || !self.faces_like_old(cross, tri, region) {
                    return false;
                }
                for (x, y) in [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])] {
                    if !is_ring_edge(x, y) && self.conn.has_edge_avoiding(x, y, v) {
                        return false;
                    }
                }
            }
            start = region.end;
        }
        true
    }

    /// A new triangle faces like the old ring triangles of its region that share one of its
    /// vertices.
    fn faces_like_old(&self, cross: DVec3, tri: &[u32; 3], region: FillRegion) -> bool {
        let r = &self.scratch.ring.verts;
        let k = r.len();
        let crosses = &self.scratch.geometry.crosses;
        (region.from..region.to).all(|i| {
            let (i, c) = (i % k, crosses[i % k]);
            let next = if i + 1 == k { r[0] } else { r[i + 1] };
            let touches = tri.contains(&r[i]) || tri.contains(&next);
            !touches || cross.dot(c) > -0.5 * cross.length() * c.length()
        })
    }

    /// Writes live vertices and triangles back into `model`. `order` maps internal vertex ids
    /// to the model's, `faces` internal triangle slots to the model's faces. Kept vertices
    /// keep their relative order from the input.
    fn write_back(&self, model: &mut Model, order: &[u32], faces: &[u32]) {
        // A reused slot stands in for the original face that first owned it.
        let Compacted {
            kept_vertices,
            faces,
            triangles,
        } = compact(&self.conn, order, faces);
        model.triangles = triangles;
        model.positions = kept_vertices
            .iter()
            .map(|&v| model.positions[v as usize])
            .collect();
        model.colors = model
            .colors
            .as_ref()
            .map(|c| c.select(&kept_vertices, &faces));
        model.normals = match &model.normals {
            Some(n @ Attribute::PerVertex(_)) => Some(n.select(&kept_vertices, &faces)),
            _ => None, // face normals of refilled holes would be wrong: recomputed on display
        };
        model.texcoords = model.texcoords.as_ref().map(|t| {
            kept_vertices
                .iter()
                .map(|&v| t.get(v as usize).copied().unwrap_or_default())
                .collect()
        });
    }
}

/// Scratch for evaluating one vertex: its ring and the ring's triangle geometry.
#[derive(Debug, Clone, Default)]
struct Scratch {
    ring: Ring,
    geometry: RingGeometry,
}

/// Classifies `v` into `scratch` and returns its class and decimation criterion: distance to
/// the loop's average plane (simple), or to the line through its boundary / feature
/// neighbours (boundary, interior edge). `None` for vertices that are never removed.
fn evaluate(
    conn: &Connectivity,
    positions: &[Vec3],
    cos_feature: f64,
    v: u32,
    scratch: &mut Scratch,
) -> Option<(VertexClass, f64)> {
    let class = classify(
        conn,
        positions,
        v,
        cos_feature,
        &mut scratch.ring,
        &mut scratch.geometry,
    );
    let p = positions[v as usize].as_dvec3();
    let verts = &scratch.ring.verts;
    let distance = match class {
        VertexClass::Simple => {
            let all = 0..scratch.geometry.crosses.len();
            let (normal, centre) = average_plane(positions, scratch, p, all)?;
            normal.dot(p - centre).abs()
        }
        VertexClass::Boundary => line_distance(positions, p, verts[0], verts[verts.len() - 1]),
        VertexClass::InteriorEdge { first, second } => {
            line_distance(positions, p, verts[first], verts[second])
        }
        _ => return None,
    };
    distance.is_finite().then_some((class, distance))
}

/// Area-weighted unit normal and centre of the ring triangles `indices` around the vertex at
/// `p` (the ring and its geometry in `scratch`).
fn average_plane(
    positions: &[Vec3],
    scratch: &Scratch,
    p: DVec3,
    indices: impl Iterator<Item = usize>,
) -> Option<(DVec3, DVec3)> {
    let verts = &scratch.ring.verts;
    let mut normal = DVec3::ZERO;
    let mut centre = DVec3::ZERO;
    let mut area = 0.0;
    for i in indices {
        let a = scratch.geometry.lengths[i];
        normal += scratch.geometry.crosses[i];
        let pa = positions[verts[i] as usize].as_dvec3();
        let next = verts.get(i + 1).unwrap_or(&verts[0]);
        let pb = positions[*next as usize].as_dvec3();
        centre += a * (p + pa + pb);
        area += a;
    }
    let centre = centre / 3.0;
    let len = normal.length();
    if area <= 0.0 || len <= 1e-12 * area {
        return None;
    }
    Some((normal / len, centre / area))
}

/// Distance from `p` to the line through vertices `a` and `b`.
fn line_distance(positions: &[Vec3], p: DVec3, a: u32, b: u32) -> f64 {
    let (a, b) = (
        positions[a as usize].as_dvec3(),
        positions[b as usize].as_dvec3(),
    );
    let dir = b - a;
    let len2 = dir.length_squared();
    if len2 <= 0.0 {
        return (p - a).length();
    }
    (p - a).cross(dir).length() / len2.sqrt()
}

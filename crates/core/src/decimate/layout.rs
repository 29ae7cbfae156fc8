//! The first and last stages shared by every algorithm: [`load`] renumbers a model's
//! vertices along a Morton curve (memory locality) and keeps its valid triangles in that
//! numbering; [`compact`] brings the live triangles of a decimated `Connectivity` back to the
//! model's numbering, with the kept vertices in their input order. While a decimator works
//! on its own copies, [`release`] frees the model's and [`restore`] brings them back when
//! nothing was removed (docs/design.md#in-core-memory).

use glam::Vec3;
use rayon::prelude::*;

use crate::mesh::spatial;
use crate::mesh::topology::Connectivity;
use crate::mesh::Model;

/// A model's triangles in internal (Morton) vertex numbering.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Loaded {
    /// Internal vertex id -> model vertex id.
    pub order: Vec<u32>,
    /// Internal triangle -> model face (faces with an out-of-range index are left out).
    pub faces: Vec<u32>,
    /// Model vertex id -> internal vertex id.
    pub internal: Vec<u32>,
}

impl Loaded {
    /// The model's face `t` in internal numbering.
    pub fn triangle(&self, model: &Model, t: u32) -> [u32; 3] {
        model.triangles[t as usize].map(|v| self.internal[v as usize])
    }

    /// A vertex pairing given in the model's numbering (`pairs[v]` is `v`'s partner or
    /// `u32::MAX`: texture-seam twins), in internal numbering; empty when nothing is paired.
    pub fn pairs(&self, pairs: &[u32]) -> Vec<u32> {
        if pairs.iter().all(|&w| w == u32::MAX) {
            return Vec::new();
        }
        let internal = |w: u32| self.internal.get(w as usize).copied().unwrap_or(u32::MAX);
        self.order
            .iter()
            .map(|&v| pairs.get(v as usize).map_or(u32::MAX, |&w| internal(w)))
            .collect()
    }

    /// Every loaded face in internal numbering, in `faces` order.
    pub fn triangles(&self, model: &Model) -> Vec<[u32; 3]> {
        self.faces
            .par_iter()
            .map(|&t| self.triangle(model, t))
            .collect()
    }
}

/// Renumbers `model`'s vertices along a Morton curve and lists its valid faces, ordered by
/// their smallest internal vertex: a vertex's fan then lies in a few cache lines, next to
/// its neighbours' fans.
pub fn load(model: &Model) -> Loaded {
    load_in(model, spatial::morton_order(&model.positions))
}

/// As [`load`], with the vertices in `order`, [`load`]'s order for these positions: a model
/// that only lost triangles since (hanging sheets pruned) keeps its vertices' order, and
/// skips the sort.
pub fn load_in(model: &Model, order: Vec<u32>) -> Loaded {
    let n = model.positions.len() as u32;
    debug_assert_eq!(order.len(), n as usize);
    let mut internal = vec![0u32; n as usize];
    for (i, &v) in order.iter().enumerate() {
        internal[v as usize] = i as u32;
    }
    let faces = faces_by_first_vertex(model, &internal);
    Loaded {
        order,
        faces,
        internal,
    }
}

/// The valid faces of `model` (every index in range), sorted by their smallest vertex in
/// the `internal` numbering (a counting sort, stable), input order within a vertex.
fn faces_by_first_vertex(model: &Model, internal: &[u32]) -> Vec<u32> {
    let n = internal.len();
    let key = |tri: &[u32; 3]| -> Option<usize> {
        let first = tri
            .iter()
            .map(|&v| internal.get(v as usize).copied())
            .min()??;
        Some(first as usize)
    };
    let mut start = vec![0u32; n + 1];
    for tri in &model.triangles {
        if let Some(k) = key(tri) {
            start[k + 1] += 1;
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut faces = vec![0u32; start[n] as usize];
    for (t, tri) in model.triangles.iter().enumerate() {
        if let Some(k) = key(tri) {
            faces[start[k] as usize] = t as u32;
            start[k] += 1;
        }
    }
    faces
}

/// Frees `model`'s positions and triangles once a decimator holds its own copies of them
/// in `loaded`'s numbering: no second copy of the input while it works. True when they
/// were freed (every face was loaded, so the copies hold all of them); the decimator then
/// writes its result back, or calls [`restore`].
pub fn release(model: &mut Model, loaded: &Loaded) -> bool {
    if loaded.faces.len() != model.triangles.len() || loaded.order.len() != model.positions.len() {
        return false;
    }
    model.positions = Vec::new();
    model.triangles = Vec::new();
    true
}

/// Undoes [`release`] from the decimator's unchanged copies: `positions` and `conn`'s
/// triangle slots in internal numbering, `order` and `faces` as [`load`] made them. The
/// model gets back exactly the arrays it had.
pub fn restore(
    model: &mut Model,
    positions: &[Vec3],
    conn: &Connectivity,
    order: &[u32],
    faces: &[u32],
) {
    let mut restored = vec![Vec3::ZERO; order.len()];
    for (&v, &p) in order.iter().zip(positions) {
        restored[v as usize] = p;
    }
    model.positions = restored;
    let mut triangles = vec![[0u32; 3]; faces.len()];
    for (t, &f) in faces.iter().enumerate() {
        triangles[f as usize] = conn.triangle(t as u32).map(|v| order[v as usize]);
    }
    model.triangles = triangles;
}

/// The live mesh in the model's numbering.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Compacted {
    /// Model vertex ids that survive, ascending: new vertex `i` is old `kept_vertices[i]`.
    pub kept_vertices: Vec<u32>,
    /// The model face each surviving triangle stands for (for per-face attributes).
    pub faces: Vec<u32>,
    /// Surviving triangles over the new vertex ids.
    pub triangles: Vec<[u32; 3]>,
}

/// Compacts `conn`. `order` maps internal vertex ids to the model's; `faces` maps internal
/// triangle slots to the model face that first owned the slot.
pub fn compact(conn: &Connectivity, order: &[u32], faces: &[u32]) -> Compacted {
    let slots: Vec<u32> = conn.alive_ids().collect();
    // Model vertex id -> new id, u32::MAX while unused.
    let mut remap = vec![u32::MAX; order.len()];
    for &t in &slots {
        for v in conn.triangle(t) {
            remap[order[v as usize] as usize] = 0;
        }
    }
    let mut kept_vertices: Vec<u32> = Vec::new();
    for (v, r) in remap.iter_mut().enumerate() {
        if *r == 0 {
            *r = kept_vertices.len() as u32;
            kept_vertices.push(v as u32);
        }
    }
    Compacted {
        faces: slots.iter().map(|&t| faces[t as usize]).collect(),
        triangles: slots
            .iter()
            .map(|&t| conn.triangle(t).map(|v| remap[order[v as usize] as usize]))
            .collect(),
        kept_vertices,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_input_order_and_maps_faces_through_slots() {
        // Internal vertex i is model vertex order[i]; triangle slot 1 is removed.
        let order = [3, 0, 2, 1];
        let mut conn = Connectivity::new(4, &[[0, 1, 2], [1, 2, 3], [0, 2, 3]]);
        conn.remove_triangle(1);
        let c = compact(&conn, &order, &[10, 11, 12]);
        // Model vertices used: 3, 0, 2 (internal 0, 1, 2) and 3, 2, 1 (internal 0, 2, 3).
        assert_eq!(c.kept_vertices, vec![0, 1, 2, 3]);
        assert_eq!(c.faces, vec![10, 12]);
        assert_eq!(c.triangles, vec![[3, 0, 2], [3, 2, 1]]);
    }
}

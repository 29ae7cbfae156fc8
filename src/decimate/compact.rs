//! The shared last stage of every algorithm: the live triangles of a decimated
//! `Connectivity`, back in the model's own vertex numbering, with the kept vertices in their
//! input order.

use crate::mesh::topology::Connectivity;

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

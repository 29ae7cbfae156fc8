//! Welding: merging vertices that a file repeats per face, so that faces share vertices and
//! the mesh has the connectivity decimation needs.
//!
//! Exact positions are matched through a hash map (linear time); triangles that become
//! degenerate after the merge are dropped. Per-vertex attributes keep the first vertex's
//! value.

use std::collections::HashMap;

use super::Model;

/// Merges vertices with bit-identical positions (after `-0.0` → `0.0`); drops unused
/// vertices and triangles that become degenerate. Returns how many vertices were removed.
pub fn weld(model: &mut Model) -> usize {
    let n = model.positions.len();
    let mut first_of: HashMap<[u32; 3], u32> = HashMap::with_capacity(n);
    let mut remap = vec![0u32; n];
    let mut keep: Vec<u32> = Vec::with_capacity(n);
    let mut used = vec![false; n];
    for t in &model.triangles {
        for &v in t {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    }
    for (i, p) in model.positions.iter().enumerate() {
        if !used[i] {
            continue;
        }
        let key = [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits());
        let next = keep.len() as u32;
        let id = *first_of.entry(key).or_insert(next);
        if id == next {
            keep.push(i as u32);
        }
        remap[i] = id;
    }
    let removed = n - keep.len();
    if removed == 0 {
        return 0;
    }
    model.positions = keep.iter().map(|&i| model.positions[i as usize]).collect();
    let mut kept_faces: Vec<u32> = Vec::with_capacity(model.triangles.len());
    for (f, t) in model.triangles.iter_mut().enumerate() {
        *t = t.map(|v| remap[v as usize]);
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            kept_faces.push(f as u32);
        }
    }
    if kept_faces.len() != model.triangles.len() {
        model.triangles = kept_faces
            .iter()
            .map(|&f| model.triangles[f as usize])
            .collect();
    }
    model.colors = model.colors.as_ref().map(|c| c.select(&keep, &kept_faces));
    model.normals = model.normals.as_ref().map(|c| c.select(&keep, &kept_faces));
    removed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Attribute;
    use glam::Vec3;

    #[test]
    fn quad_with_duplicated_corners_welds_to_four_vertices() {
        // Two triangles of a unit square, each with its own three vertices.
        let p = |x, y| Vec3::new(x, y, 0.0);
        let mut m = Model {
            positions: vec![
                p(0., 0.),
                p(1., 0.),
                p(1., 1.),
                p(0., 0.),
                p(1., 1.),
                p(0., 1.),
            ],
            triangles: vec![[0, 1, 2], [3, 4, 5]],
            colors: Some(Attribute::PerFace(vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])),
            ..Model::default()
        };
        assert_eq!(weld(&mut m), 2);
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.colors.as_ref().map(|c| c.values().len()), Some(2));
    }

    #[test]
    fn collapsed_triangles_are_dropped() {
        let mut m = Model {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::X, Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 1, 3]],
            ..Model::default()
        };
        assert_eq!(weld(&mut m), 1);
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }
}

//! The counts a caption and the status line show: vertices as the file's points — the
//! copies a texture seam makes of one point counted once, as the welded surface has it —
//! and triangles. Computed once per scene shown (on the worker thread for a decimation's
//! result), never per frame.

use std::collections::HashSet;

use decimate_core::mesh::seams::position_key;
use decimate_core::mesh::{Model, Scene};

/// Vertices and triangles of a scene as a user counts them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    /// Distinct points used by some triangle, summed over the models.
    pub vertices: usize,
    pub triangles: usize,
}

impl Counts {
    pub fn of(scene: &Scene) -> Self {
        Self {
            vertices: scene.models.iter().map(welded_vertices).sum(),
            triangles: scene.triangle_count(),
        }
    }
}

/// Points of `model` used by some triangle. Only a textured model holds two vertices at one
/// point (the sides of a seam, `mesh::seams`): the scene builder welds every other
/// coincident pair, unless `--no-weld` asked to keep them apart.
pub fn welded_vertices(model: &Model) -> usize {
    if model.texcoords.is_none() {
        return model.used_vertex_count();
    }
    let mut used = vec![false; model.positions.len()];
    for &v in model.triangles.iter().flatten() {
        if let Some(u) = used.get_mut(v as usize) {
            *u = true;
        }
    }
    let points: HashSet<[u32; 3]> = (model.positions.iter().zip(&used))
        .filter(|(_, &u)| u)
        .map(|(&p, _)| position_key(p))
        .collect();
    points.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use decimate_core::mesh::shapes;

    #[test]
    fn a_seam_copy_is_one_point() {
        // A 2×1 strip of quads whose middle column is cut by a texture seam: the two
        // copies of its two points are one point each.
        let mut m = Model::default();
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            m.positions.push(glam::Vec3::new(x, y, 0.0));
        }
        for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0)] {
            m.positions.push(glam::Vec3::new(x, y, 0.0));
        }
        m.triangles = vec![[0, 1, 3], [0, 3, 2], [4, 5, 7], [4, 7, 6]];
        m.texcoords = Some(vec![[0.0, 0.0]; 8]);
        assert_eq!(m.used_vertex_count(), 8);
        assert_eq!(welded_vertices(&m), 6);
        // An unused vertex at a new point counts for nothing.
        m.positions.push(glam::Vec3::new(9.0, 9.0, 9.0));
        m.texcoords = Some(vec![[0.0, 0.0]; 9]);
        assert_eq!(welded_vertices(&m), 6);
        let scene = Scene {
            models: vec![m, shapes::test004()],
        };
        assert_eq!(
            Counts::of(&scene),
            Counts {
                vertices: 6 + 602,
                triangles: 4 + 1200
            }
        );
    }
}

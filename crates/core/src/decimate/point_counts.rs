//! What decimation counts as a model's vertices: its used positions, the copies a texture
//! or colour seam makes of one point (a vertex per side, `mesh::seams`) counted once, as MeshLab,
//! Blender and pmp count them. The copies themselves are counted apart.

use std::collections::HashSet;

use crate::mesh::seams::position_key;
use crate::mesh::Model;

/// The used vertices beyond the first at each position of a model with seam attributes
/// (its seams' copies); 0 without them, whose coincident vertices are not seams
/// (`mesh::seams::find`).
pub(crate) fn seam_copies(model: &Model) -> usize {
    if !model.has_seam_attributes() {
        return 0;
    }
    let mut used = vec![false; model.positions.len()];
    for &v in model.triangles.iter().flatten() {
        if let Some(u) = used.get_mut(v as usize) {
            *u = true;
        }
    }
    let mut seen = HashSet::new();
    let mut copies = 0;
    for (p, _) in model.positions.iter().zip(&used).filter(|(_, &u)| u) {
        if !seen.insert(position_key(*p)) {
            copies += 1;
        }
    }
    copies
}

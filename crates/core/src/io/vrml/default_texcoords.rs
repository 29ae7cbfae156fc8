//! Default texture coordinates for shapes under a texture that give none of their own:
//! VRML 2.0's IndexedFaceSet (§6.23) and Inventor's vertex shapes (its default texture
//! coordinate function) map the shape's bounding box; an ElevationGrid (§6.18) spans its
//! grid. Both are functions of the position, so they need no seams.

use glam::Vec3;

use crate::mesh::Model;

/// The model's bounding box in its own frame: (lowest corner, size); `None` when empty.
fn bounds(model: &Model) -> Option<(Vec3, Vec3)> {
    let first = *model.positions.first()?;
    let (lo, hi) = model
        .positions
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    Some((lo, hi - lo))
}

/// The bounding-box mapping: s runs 0..1 along the box's longest side, t along the next
/// longest from 0 to its length over the longest's; ties go to x, then y, then z.
pub fn bounding_box(model: &mut Model) {
    let Some((lo, size)) = bounds(model) else {
        return;
    };
    let mut axes = [0, 1, 2];
    // A stable sort keeps x before y before z among equal sides.
    axes.sort_by(|&a, &b| size[b].total_cmp(&size[a]));
    let (s, t) = (axes[0], axes[1]);
    let scale = if size[s] > 0.0 { 1.0 / size[s] } else { 0.0 };
    model.texcoords = Some(
        model
            .positions
            .iter()
            .map(|&p| [(p[s] - lo[s]) * scale, (p[t] - lo[t]) * scale])
            .collect(),
    );
}

/// An ElevationGrid's mapping: s from 0 at its first column to 1 at its last (along +x), t
/// from 0 at its first row to 1 at its last (along +z).
pub fn elevation_grid(model: &mut Model) {
    let Some((lo, size)) = bounds(model) else {
        return;
    };
    let inv = |d: f32| if d > 0.0 { 1.0 / d } else { 0.0 };
    let (sx, sz) = (inv(size.x), inv(size.z));
    model.texcoords = Some(
        model
            .positions
            .iter()
            .map(|&p| [(p.x - lo.x) * sx, (p.z - lo.z) * sz])
            .collect(),
    );
}

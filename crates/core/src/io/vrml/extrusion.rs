//! VRML 2.0's `Extrusion`: a 2D cross-section swept along a 3D spine, scaled and rotated at
//! each spine point, closed by caps (VRML97 section 6.18). Each spine point gets its
//! spine-aligned cross-section plane: Y along the spine, Z normal to the spine's bend (kept
//! from the previous point where the spine is straight, flipped to stay continuous), X = Y × Z.
//! Rings share their vertices with the caps, and a closed cross-section or spine shares its
//! first and last points, so a closed extrusion is a closed surface. Under a texture it gets
//! the specification's default coordinates: u along the cross-section, v along the spine
//! (each by length, 0 to 1), the caps mapping the cross-section's square; its corners then
//! split where the sides meet the caps and where a closed curve meets itself.

use glam::{DVec3, Mat3, Quat, Vec2, Vec3};

use super::lexer::{PResult, ParseError};
use super::parse::Node;
use super::vrml1::rotation;

/// An extrusion's points (flat x y z) and polygons (corner lists and ends), with texture
/// coordinates (flat u v) and each corner's pair when made textured (else both empty).
/// A far spine's extrusion also has its points in f64 (`far_points`; `points` are then
/// relative to the spine's first point).
pub struct Swept {
    pub points: Vec<f32>,
    pub far_points: Option<Vec<f64>>,
    pub corners: Vec<u32>,
    pub ends: Vec<u32>,
    pub texcoords: Vec<f32>,
    pub texcoord_index: Vec<u32>,
}

/// Each point's distance along the polyline from its first point, over the whole length
/// (0 to 1; all 0 for a polyline of no length).
fn along<T: Copy>(points: &[T], distance: impl Fn(T, T) -> f32) -> Vec<f32> {
    let mut total = 0.0;
    let mut at = vec![0.0];
    for w in points.windows(2) {
        total += distance(w[0], w[1]);
        at.push(total);
    }
    let scale = if total > 0.0 { 1.0 / total } else { 0.0 };
    at.iter().map(|d| d * scale).collect()
}

fn vec2s(v: &[f32]) -> Vec<Vec2> {
    v.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect()
}

fn vec3s(v: &[f32]) -> Vec<Vec3> {
    v.chunks_exact(3).map(Vec3::from_slice).collect()
}

/// The spine-aligned cross-section plane of each spine point, as rotations of the x-z plane.
fn planes(spine: &[Vec3], closed: bool) -> Vec<Mat3> {
    let n = spine.len();
    let y_axis = |i: usize| -> Vec3 {
        let (a, b) = match (i, closed) {
            (0, true) => (spine[1], spine[n - 2]),
            (0, false) => (spine[1], spine[0]),
            (i, true) if i == n - 1 => (spine[1], spine[n - 2]),
            (i, false) if i == n - 1 => (spine[n - 1], spine[n - 2]),
            (i, _) => (spine[i + 1], spine[i - 1]),
        };
        (a - b).normalize_or_zero()
    };
    let z_axis = |i: usize| -> Vec3 {
        let (prev, here, next) = match i {
            0 if closed => (spine[n - 2], spine[0], spine[1]),
            i if i == n - 1 && closed => (spine[n - 2], spine[0], spine[1]),
            0 => return Vec3::ZERO,
            i if i == n - 1 => return Vec3::ZERO,
            i => (spine[i - 1], spine[i], spine[i + 1]),
        };
        (next - here).cross(prev - here).normalize_or_zero()
    };
    let mut zs: Vec<Vec3> = (0..n).map(z_axis).collect();
    // Straight stretches take the previous Z (the first bend's for the start); a spine
    // straight throughout turns the plane from +Y onto its direction.
    let Some(first) = zs.iter().copied().find(|z| *z != Vec3::ZERO) else {
        let dir = (spine[n - 1] - spine[0]).normalize_or_zero();
        let turn = if dir == Vec3::ZERO {
            Quat::IDENTITY
        } else {
            Quat::from_rotation_arc(Vec3::Y, dir)
        };
        return vec![Mat3::from_quat(turn); n];
    };
    let mut last = first;
    for z in &mut zs {
        if *z == Vec3::ZERO {
            *z = last;
        } else if z.dot(last) < 0.0 {
            *z = -*z;
        }
        last = *z;
    }
    (0..n)
        .map(|i| {
            let y = match y_axis(i) {
                y if y == Vec3::ZERO => Vec3::Y,
                y => y,
            };
            let z = zs[i];
            Mat3::from_cols(y.cross(z).normalize_or_zero(), y, z)
        })
        .collect()
}

/// Sweeps the Extrusion node `g` into points and polygons (the caps as single polygons),
/// with texture coordinates when `textured`.
pub fn extrude(g: &Node, textured: bool) -> PResult<Swept> {
    let square = [1.0, 1.0, 1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
    let section = vec2s(g.floats("crossSection").unwrap_or(&square));
    let (spine, far_base) = spine_of(g);
    let scales = vec2s(g.floats("scale").unwrap_or(&[1.0, 1.0]));
    let turns: Vec<Quat> = g
        .floats("orientation")
        .unwrap_or(&[0.0, 0.0, 1.0, 0.0])
        .chunks_exact(4)
        .map(|r| rotation(Some(r)))
        .collect();
    if scales.is_empty() || turns.is_empty() {
        return Err(ParseError::new(
            g.line,
            "Extrusion needs at least one 'scale' and one 'orientation' value",
        ));
    }
    let mut out = Swept {
        points: Vec::new(),
        corners: Vec::new(),
        ends: Vec::new(),
        texcoords: Vec::new(),
        texcoord_index: Vec::new(),
        far_points: None,
    };
    if section.len() < 2 || spine.len() < 2 {
        return Ok(out);
    }
    let section_closed = section.len() > 2 && section[0] == section[section.len() - 1];
    let spine_closed = spine.len() > 2 && spine[0] == spine[spine.len() - 1];
    let m = section.len() - usize::from(section_closed);
    let n = spine.len() - usize::from(spine_closed);
    let frames = planes(&spine, spine_closed);
    for i in 0..n {
        let s = scales[i.min(scales.len() - 1)];
        let turn = turns[i.min(turns.len() - 1)];
        for c in &section[..m] {
            let local = turn * Vec3::new(c.x * s.x, 0.0, c.y * s.y);
            out.points.extend((spine[i] + frames[i] * local).to_array());
        }
    }
    let at = |i: usize, j: usize| ((i % n) * m + j % m) as u32;
    // Texture pairs: one per (spine point, cross-section point) as listed, then the caps'
    // one per cross-section point.
    let pairs = section.len();
    let tc = |i: usize, j: usize| (i * pairs + j) as u32;
    let cap_tc = |j: usize| (spine.len() * pairs + j) as u32;
    for i in 0..spine.len() - 1 {
        for j in 0..section.len() - 1 {
            out.corners
                .extend([at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)]);
            out.texcoord_index
                .extend([tc(i, j), tc(i, j + 1), tc(i + 1, j + 1), tc(i + 1, j)]);
            out.ends.push(out.corners.len() as u32);
        }
    }
    let cap = |field: &str| g.boolean(field).unwrap_or(true) && !spine_closed && m > 2;
    if cap("beginCap") {
        out.corners.extend((0..m).rev().map(|j| at(0, j)));
        out.texcoord_index.extend((0..m).rev().map(cap_tc));
        out.ends.push(out.corners.len() as u32);
    }
    if cap("endCap") {
        out.corners.extend((0..m).map(|j| at(n - 1, j)));
        out.texcoord_index.extend((0..m).map(cap_tc));
        out.ends.push(out.corners.len() as u32);
    }
    if textured {
        out.texcoords = texcoords(&section, &spine);
    } else {
        out.texcoord_index.clear();
    }
    out.far_points = far_base.map(|base| {
        let b = base.to_array();
        let at = |k: usize| b[k % 3] + f64::from(out.points[k]);
        (0..out.points.len()).map(at).collect()
    });
    Ok(out)
}

/// The spine's points, and where they are far from zero (see `io::origin`), its first point
/// in f64: the points are then taken relative to it (their differences in f64), so the
/// sweep is made near zero and moved there in f64 after.
fn spine_of(g: &Node) -> (Vec<Vec3>, Option<DVec3>) {
    if let Some(far) = g.far("spine").filter(|p| p.len() >= 3) {
        let base = DVec3::new(far[0], far[1], far[2]);
        let points = far
            .chunks_exact(3)
            .map(|p| (DVec3::new(p[0], p[1], p[2]) - base).as_vec3())
            .collect();
        return (points, Some(base));
    }
    let points = vec3s(g.floats("spine").unwrap_or(&[0.0, 0.0, 0.0, 0.0, 1.0, 0.0]));
    (points, None)
}

/// VRML 2.0 §6.18's default texture coordinates of an extrusion: the sides' pairs (spine
/// point by cross-section point, u along the cross-section, v along the spine), then the
/// caps' (the cross-section scaled and moved so that its larger side spans 0 to 1, u along
/// its x and v along its z).
fn texcoords(section: &[Vec2], spine: &[Vec3]) -> Vec<f32> {
    let u = along(section, Vec2::distance);
    let v = along(spine, Vec3::distance);
    let mut out = Vec::with_capacity((spine.len() + 1) * section.len() * 2);
    for &v in &v {
        for &u in &u {
            out.extend([u, v]);
        }
    }
    let lo = section.iter().fold(Vec2::splat(f32::MAX), |a, &c| a.min(c));
    let hi = section.iter().fold(Vec2::splat(f32::MIN), |a, &c| a.max(c));
    let larger = (hi - lo).max_element();
    let scale = if larger > 0.0 { 1.0 / larger } else { 0.0 };
    for &c in section {
        out.extend(((c - lo) * scale).to_array());
    }
    out
}

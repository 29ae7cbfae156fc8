//! The round primitives of VRML 1.0, Open Inventor and VRML 2.0 (`Sphere`, `Cone`,
//! `Cylinder`) as triangle meshes over shared vertices.
//!
//! Slice and stack counts follow Coin's tessellation at a given complexity (see
//! docs/design.md#primitives), so triangle counts match Coin's. Unlike Coin, each ring's
//! vertices are shared by the side and the caps and a sphere's poles are single vertices: a
//! full shape is a closed surface that decimation can treat as one. Axes are along y, shapes
//! centred on the origin, triangles counter-clockwise seen from outside.

use std::f32::consts::{PI, TAU};

use glam::Mat4;

use super::bindings::Geo;
use crate::io::shape_to_model::{Bind, ShapeSpec};

/// Which parts of a cone or cylinder to make (a cone has no top).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Parts {
    pub side: bool,
    pub top: bool,
    pub bottom: bool,
}

impl Parts {
    pub const ALL: Self = Self {
        side: true,
        top: true,
        bottom: true,
    };

    /// Parts from an Inventor `parts` value: `ALL`, `SIDES`, `TOP`, `BOTTOM` or a mask such
    /// as `SIDES|TOP` (as the parser joins `( SIDES | TOP )`); `None` for an unknown name.
    pub fn from_mask(mask: &str) -> Option<Self> {
        let mut p = Self {
            side: false,
            top: false,
            bottom: false,
        };
        for name in mask.split('|').map(str::trim) {
            match name {
                "ALL" => p = Self::ALL,
                "SIDES" => p.side = true,
                "TOP" => p.top = true,
                "BOTTOM" => p.bottom = true,
                "" => {}
                _ => return None,
            }
        }
        Some(p)
    }
}

/// A tessellated primitive: flat x y z coordinates and triangles, with the part each
/// triangle belongs to (numbered in Coin's order: side, bottom, top; only made parts count).
#[derive(Debug, Clone, Default)]
pub struct Tessellation {
    pub coords: Vec<f32>,
    pub triangles: Vec<[u32; 3]>,
    pub part: Vec<u32>,
    /// True when the parts make a closed surface.
    pub closed: bool,
}

impl Tessellation {
    /// Triangles of a tessellated primitive, each part (side, bottom, top) a PER_PART value.
    pub fn to_geo(&self) -> Geo {
        let corners: Vec<u32> = self.triangles.iter().flatten().copied().collect();
        let n = self.triangles.len() as u32;
        Geo {
            seq_no: corners.clone(),
            raw_pos: corners.clone(),
            corners,
            ends: (1..=n).map(|i| i * 3).collect(),
            face_no: (0..n).collect(),
            part_no: self.part.clone(),
        }
    }

    fn vertex(&mut self, x: f32, y: f32, z: f32) -> u32 {
        self.coords.extend([x, y, z]);
        (self.coords.len() / 3 - 1) as u32
    }

    /// `slices` vertices on a circle of `radius` at height `y`, starting at -z and turning
    /// towards -x (Coin's order); returns the first vertex's index.
    fn ring(&mut self, slices: u32, radius: f32, y: f32) -> u32 {
        let first = (self.coords.len() / 3) as u32;
        for j in 0..slices {
            let a = TAU * j as f32 / slices as f32;
            self.vertex(-a.sin() * radius, y, -a.cos() * radius);
        }
        first
    }

    /// A fan over ring `first..first+n`, facing +y (`up`) or -y.
    fn cap(&mut self, first: u32, n: u32, up: bool, part: u32) {
        for m in 1..n.saturating_sub(1) {
            let (b, c) = (first + m, first + m + 1);
            self.triangles
                .push(if up { [first, b, c] } else { [first, c, b] });
            self.part.push(part);
        }
    }

    /// Triangles joining `apex` to ring `first..first+n`, counter-clockwise seen from outside
    /// when the apex is above the ring (`up`) or below it.
    fn apex_fan(&mut self, apex: u32, first: u32, n: u32, up: bool, part: u32) {
        for j in 0..n {
            let (a, b) = (first + j, first + (j + 1) % n);
            self.triangles
                .push(if up { [apex, a, b] } else { [apex, b, a] });
            self.part.push(part);
        }
    }

    /// Two triangles per slice between ring `upper` and ring `lower` (same size `n`).
    fn band(&mut self, upper: u32, lower: u32, n: u32, part: u32) {
        for j in 0..n {
            let k = (j + 1) % n;
            self.triangles.push([upper + j, lower + j, upper + k]);
            self.triangles.push([upper + k, lower + j, lower + k]);
            self.part.extend([part, part]);
        }
    }
}

/// Crease angle of primitives' generated normals (radians): facets of the default
/// tessellations are smoothed, the rims of caps stay sharp; see docs/design.md#primitives.
pub const CREASE_ANGLE: f32 = 1.0;
/// The shape of a tessellated primitive over `coords` (its `Geo::triangles`): counter-clockwise,
/// creased at [`CREASE_ANGLE`]; the caller says whether it is solid (closed).
pub fn shape_spec<'a>(
    name: String,
    transform: Mat4,
    coords: &'a [f32],
    geo: Geo,
    colors: Bind<'a>,
    diffuse: [f32; 3],
    line: usize,
) -> ShapeSpec<'a> {
    ShapeSpec {
        name,
        transform,
        coords,
        corners: geo.corners,
        ends: geo.ends,
        colors,
        normals: Bind::None,
        texcoords: None,
        ccw: true,
        solid: false,
        crease_angle: Some(CREASE_ANGLE),
        diffuse,
        line,
        index_field: "its parts",
    }
}

/// Coin's default complexity, used where no `Complexity` node says otherwise (VRML 2.0 has
/// none); see docs/design.md#primitives.
pub const DEFAULT_COMPLEXITY: f32 = 0.5;
/// Slices of a cone or cylinder at complexity 1 (Coin's `CONE_SIDE_NUMTRIS`,
/// `CYL_SIDE_NUMTRIS`).
const ROUND_SLICES_AT_ONE: f32 = 40.0;
/// Slices and stacks of a sphere at complexity 1 (Coin's `SPHERE_NUM_SLICES`/`_STACKS`).
const SPHERE_STEPS_AT_ONE: f32 = 30.0;
/// Most slices around any primitive (Coin's bound).
const MAX_SLICES: u32 = 128;

/// Slices around a cone or cylinder at `complexity` (clamped to 0..=1).
pub fn round_slices(complexity: f32) -> u32 {
    ((ROUND_SLICES_AT_ONE * complexity.clamp(0.0, 1.0)) as u32).clamp(4, MAX_SLICES)
}

/// (stacks, slices) of a sphere at `complexity`: `stacks` counts the poles as stacks, so a
/// sphere has `stacks - 2` rings of `slices` vertices.
pub fn sphere_steps(complexity: f32) -> (u32, u32) {
    let n = (SPHERE_STEPS_AT_ONE * complexity.clamp(0.0, 1.0)) as u32;
    (n.max(3), n.clamp(4, MAX_SLICES))
}

/// The shapes below are empty when a size is zero (they would be degenerate).
/// A sphere of `radius`: `2 * slices * (stacks - 2)` triangles, closed.
pub fn sphere(radius: f32, complexity: f32) -> Tessellation {
    let (stacks, slices) = sphere_steps(complexity);
    let mut t = Tessellation::default();
    if radius == 0.0 {
        return t;
    }
    let top = t.vertex(0.0, radius, 0.0);
    let rings = stacks - 2;
    let mut first = Vec::with_capacity(rings as usize);
    for i in 1..=rings {
        let rho = PI * i as f32 / (stacks - 1) as f32;
        first.push(t.ring(slices, radius * rho.sin(), radius * rho.cos()));
    }
    let bottom = t.vertex(0.0, -radius, 0.0);
    t.apex_fan(top, first[0], slices, true, 0);
    for w in first.windows(2) {
        t.band(w[0], w[1], slices, 0);
    }
    t.apex_fan(bottom, first[first.len() - 1], slices, false, 0);
    t.closed = true;
    t
}

/// A cylinder of `radius` and `height`: the side is `2 * slices` triangles, each cap
/// `slices - 2`; closed with all parts.
pub fn cylinder(radius: f32, height: f32, complexity: f32, parts: Parts) -> Tessellation {
    let n = round_slices(complexity);
    let h = height * 0.5;
    let mut t = Tessellation::default();
    if radius == 0.0 || height == 0.0 {
        return t;
    }
    let lower = t.ring(n, radius, -h);
    let upper = t.ring(n, radius, h);
    let mut part = 0;
    if parts.side {
        t.band(upper, lower, n, part);
        part += 1;
    }
    if parts.bottom {
        t.cap(lower, n, false, part);
        part += 1;
    }
    if parts.top {
        t.cap(upper, n, true, part);
    }
    t.closed = parts == Parts::ALL;
    t
}

/// A cone of `bottom_radius` and `height`, apex up: the side is `slices` triangles, the
/// bottom `slices - 2`; closed with both parts.
pub fn cone(bottom_radius: f32, height: f32, complexity: f32, parts: Parts) -> Tessellation {
    let n = round_slices(complexity);
    let h = height * 0.5;
    let mut t = Tessellation::default();
    if bottom_radius == 0.0 || height == 0.0 {
        return t;
    }
    let ring = t.ring(n, bottom_radius, -h);
    let mut part = 0;
    if parts.side {
        let apex = t.vertex(0.0, h, 0.0);
        t.apex_fan(apex, ring, n, true, part);
        part += 1;
    }
    if parts.bottom {
        t.cap(ring, n, false, part);
    }
    t.closed = parts.side && parts.bottom;
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn signed_volume(t: &Tessellation) -> f32 {
        let p = |i: u32| Vec3::from_slice(&t.coords[i as usize * 3..i as usize * 3 + 3]);
        t.triangles
            .iter()
            .map(|tr| p(tr[0]).dot(p(tr[1]).cross(p(tr[2]))) / 6.0)
            .sum()
    }

    /// Every edge used exactly once in each direction: closed and consistently oriented.
    fn closed(t: &Tessellation) -> bool {
        let mut edges = std::collections::HashMap::new();
        for tr in &t.triangles {
            for k in 0..3 {
                *edges.entry((tr[k], tr[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        edges
            .iter()
            .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
    }

    #[test]
    fn coin_counts_at_the_default_complexity() {
        assert_eq!(sphere(1.0, 0.5).triangles.len(), 390);
        assert_eq!(
            cylinder(1.0, 2.0, 0.5, Parts::ALL).triangles.len(),
            40 + 18 + 18
        );
        assert_eq!(cone(1.0, 2.0, 0.5, Parts::ALL).triangles.len(), 20 + 18);
    }

    #[test]
    fn full_shapes_are_closed_outward_and_near_their_volume() {
        let s = sphere(2.0, 1.0);
        assert!(closed(&s));
        let v = signed_volume(&s);
        assert!(
            v > 0.95 * 4.0 / 3.0 * PI * 8.0 && v < 4.0 / 3.0 * PI * 8.0,
            "{v}"
        );
        let c = cylinder(1.0, 3.0, 1.0, Parts::ALL);
        assert!(closed(&c));
        let v = signed_volume(&c);
        assert!(v > 0.98 * PI * 3.0 && v < PI * 3.0, "{v}");
        let k = cone(1.0, 3.0, 1.0, Parts::ALL);
        assert!(closed(&k));
        let v = signed_volume(&k);
        assert!(v > 0.98 * PI && v < PI, "{v}");
    }

    #[test]
    fn parts_masks() {
        assert_eq!(Parts::from_mask("ALL"), Some(Parts::ALL));
        let p = Parts::from_mask("SIDES|TOP").unwrap();
        assert!(p.side && p.top && !p.bottom);
        assert_eq!(Parts::from_mask("SIDE"), None);
    }
}

//! The primitives of VRML 1.0, Open Inventor and VRML 2.0 (`Sphere`, `Cone`, `Cylinder`,
//! and the corners and faces of `Cube` / `Box`) as triangle meshes, with the texture
//! coordinates the specifications define when the shape has a texture.
//!
//! Slice and stack counts follow Coin's tessellation at a given complexity (see
//! docs/design.md#primitives), so triangle counts match Coin's. Untextured, each ring's
//! vertices are shared by the side and the caps and a sphere's poles are single vertices: a
//! full shape is a closed surface that decimation can treat as one. Textured, a vertex is
//! split where the texture jumps (the seam at the back, per-slice copies at poles and apex,
//! caps' rims), as `Model::texcoords` represents seams. Axes are along y, shapes centred on
//! the origin, triangles counter-clockwise seen from outside.

use std::f32::consts::{PI, TAU};

use glam::{Mat4, Vec3};

use super::bindings::Geo;
use crate::io::shape_to_model::{Bind, ShapeSpec, TexCoords};
use crate::mesh::shapes::BOX_QUADS;

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
    /// Texture coordinates, flat u v, one pair per vertex; empty when made untextured.
    pub texcoords: Vec<f32>,
    pub triangles: Vec<[u32; 3]>,
    pub part: Vec<u32>,
    /// True when the parts make a closed surface.
    pub closed: bool,
}

/// A ring of `slices` vertices from `first`; with a seam, a copy of the first vertex ends
/// it (same position, u = 1), so the ring does not wrap around.
#[derive(Debug, Clone, Copy)]
struct Ring {
    first: u32,
    slices: u32,
    seam: bool,
}

impl Ring {
    /// The ring's `j`-th vertex, `j` in `0..=slices` (the last is the seam copy, or the first).
    fn at(self, j: u32) -> u32 {
        if self.seam {
            self.first + j
        } else {
            self.first + j % self.slices
        }
    }
}

/// Which texture coordinates a ring's vertices get.
#[derive(Debug, Clone, Copy)]
enum RingUv {
    None,
    /// A side's: u = j / slices around from the back, this v; the ring gets a seam copy.
    Side(f32),
    /// A cap's circle cut out of the unit square, upright with the top tilted towards +z
    /// (`top`) or with the top tilted towards -z (the bottom cap).
    Cap {
        top: bool,
    },
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

    /// The texture coordinates bound to the corners of [`Self::to_geo`], when made textured.
    pub fn texcoords_of(&self, geo: &Geo) -> Option<TexCoords<'_>> {
        // Made textured, every vertex has its pair.
        debug_assert!(
            self.texcoords.is_empty() || self.texcoords.len() / 2 == self.coords.len() / 3
        );
        (!self.texcoords.is_empty()).then(|| TexCoords {
            values: &self.texcoords,
            index: geo.corners.clone(),
        })
    }

    fn vertex(&mut self, x: f32, y: f32, z: f32) -> u32 {
        self.coords.extend([x, y, z]);
        (self.coords.len() / 3 - 1) as u32
    }

    fn textured_vertex(&mut self, p: [f32; 3], uv: [f32; 2]) -> u32 {
        self.texcoords.extend(uv);
        self.vertex(p[0], p[1], p[2])
    }

    /// `slices` vertices on a circle of `radius` at height `y`, starting at -z and turning
    /// towards -x (Coin's order, and VRML's texture direction: counter-clockwise seen from
    /// above, from the back).
    fn ring(&mut self, slices: u32, radius: f32, y: f32, uv: RingUv) -> Ring {
        let first = (self.coords.len() / 3) as u32;
        for j in 0..slices {
            let a = TAU * j as f32 / slices as f32;
            let (s, c) = (-a.sin(), -a.cos());
            self.vertex(s * radius, y, c * radius);
            match uv {
                RingUv::None => {}
                RingUv::Side(v) => self.texcoords.extend([j as f32 / slices as f32, v]),
                RingUv::Cap { top } => {
                    let v = if top { 0.5 - 0.5 * c } else { 0.5 + 0.5 * c };
                    self.texcoords.extend([0.5 + 0.5 * s, v]);
                }
            }
        }
        let seam = matches!(uv, RingUv::Side(_));
        if let RingUv::Side(v) = uv {
            // The seam's copy is bit-equal to the first vertex, so seams are found by position.
            let i = first as usize * 3;
            let p = [self.coords[i], self.coords[i + 1], self.coords[i + 2]];
            self.textured_vertex(p, [1.0, v]);
        }
        Ring {
            first,
            slices,
            seam,
        }
    }

    /// One vertex at `(0, y, 0)`, or with `uv_v`, one per slice (u at the slice's middle),
    /// for a pole or an apex where the texture's row `v` shrinks to a point.
    fn apex(&mut self, slices: u32, y: f32, uv_v: Option<f32>) -> (u32, u32) {
        let Some(v) = uv_v else {
            return (self.vertex(0.0, y, 0.0), 0);
        };
        let first = (self.coords.len() / 3) as u32;
        for j in 0..slices {
            self.textured_vertex([0.0, y, 0.0], [(j as f32 + 0.5) / slices as f32, v]);
        }
        (first, 1)
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

    /// Triangles joining the apex (`apex + j * step` for slice `j`) to `ring`,
    /// counter-clockwise seen from outside when the apex is above the ring (`up`) or below.
    fn apex_fan(&mut self, (apex, step): (u32, u32), ring: Ring, up: bool, part: u32) {
        for j in 0..ring.slices {
            let (a, b, p) = (ring.at(j), ring.at(j + 1), apex + j * step);
            self.triangles.push(if up { [p, a, b] } else { [p, b, a] });
            self.part.push(part);
        }
    }

    /// Two triangles per slice between ring `upper` and ring `lower` (same size).
    fn band(&mut self, upper: Ring, lower: Ring, part: u32) {
        for j in 0..upper.slices {
            let (u0, u1, l0, l1) = (upper.at(j), upper.at(j + 1), lower.at(j), lower.at(j + 1));
            self.triangles.push([u0, l0, u1]);
            self.triangles.push([u1, l0, l1]);
            self.part.extend([part, part]);
        }
    }
}

/// Crease angle of primitives' generated normals (radians): facets of the default
/// tessellations are smoothed, the rims of caps stay sharp; see docs/design.md#primitives.
pub const CREASE_ANGLE: f32 = 1.0;
/// The shape of tessellation `t` over its `geo` (`t.to_geo()` with the bindings resolved):
/// counter-clockwise, creased at [`CREASE_ANGLE`], solid when closed, with `t`'s texture
/// coordinates when made textured.
pub fn shape_spec<'a>(
    name: String,
    transform: Mat4,
    t: &'a Tessellation,
    geo: Geo,
    colors: Bind<'a>,
    diffuse: [f32; 3],
    line: usize,
) -> ShapeSpec<'a> {
    ShapeSpec {
        name,
        transform,
        coords: &t.coords,
        texcoords: t.texcoords_of(&geo),
        corners: geo.corners,
        ends: geo.ends,
        colors,
        normals: Bind::None,
        ccw: true,
        solid: t.closed,
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

/// The shapes below are empty when a size is zero (they would be degenerate). `textured`
/// adds texture coordinates as VRML 2.0 defines them (§6.42 Sphere, §6.11 Cylinder, §6.8
/// Cone; Inventor's SoSphere, SoCylinder, SoCone agree), splitting vertices at the seams.
///
/// A sphere of `radius`: `2 * slices * (stacks - 2)` triangles, closed. Textured, u runs
/// around from the back (-z, then -x, +z, +x) and v from the bottom pole (0) to the top (1).
pub fn sphere(radius: f32, complexity: f32, textured: bool) -> Tessellation {
    let (stacks, slices) = sphere_steps(complexity);
    let mut t = Tessellation::default();
    if radius == 0.0 {
        return t;
    }
    let v_of = |i: u32| textured.then(|| 1.0 - i as f32 / (stacks - 1) as f32);
    let top = t.apex(slices, radius, v_of(0));
    let rings = stacks - 2;
    let mut ring = Vec::with_capacity(rings as usize);
    for i in 1..=rings {
        let rho = PI * i as f32 / (stacks - 1) as f32;
        let uv = v_of(i).map_or(RingUv::None, RingUv::Side);
        ring.push(t.ring(slices, radius * rho.sin(), radius * rho.cos(), uv));
    }
    let bottom = t.apex(slices, -radius, v_of(stacks - 1));
    t.apex_fan(top, ring[0], true, 0);
    for w in ring.windows(2) {
        t.band(w[0], w[1], 0);
    }
    t.apex_fan(bottom, ring[ring.len() - 1], false, 0);
    t.closed = true;
    t
}

/// A cylinder of `radius` and `height`: the side is `2 * slices` triangles, each cap
/// `slices - 2`; closed with all parts. Textured, the side's u runs as a sphere's and v from
/// bottom to top; each cap is a circle cut out of the texture's unit square.
pub fn cylinder(
    radius: f32,
    height: f32,
    complexity: f32,
    parts: Parts,
    textured: bool,
) -> Tessellation {
    let n = round_slices(complexity);
    let h = height * 0.5;
    let mut t = Tessellation::default();
    if radius == 0.0 || height == 0.0 {
        return t;
    }
    let (side, bottom, top) = if textured {
        // The side's rings and each cap's own ring: their texture coordinates differ.
        let side = parts.side.then(|| {
            let lower = t.ring(n, radius, -h, RingUv::Side(0.0));
            (t.ring(n, radius, h, RingUv::Side(1.0)), lower)
        });
        let bottom = parts
            .bottom
            .then(|| t.ring(n, radius, -h, RingUv::Cap { top: false }));
        let top = parts
            .top
            .then(|| t.ring(n, radius, h, RingUv::Cap { top: true }));
        (side, bottom, top)
    } else {
        let lower = t.ring(n, radius, -h, RingUv::None);
        let upper = t.ring(n, radius, h, RingUv::None);
        (
            parts.side.then_some((upper, lower)),
            parts.bottom.then_some(lower),
            parts.top.then_some(upper),
        )
    };
    let mut part = 0;
    if let Some((upper, lower)) = side {
        t.band(upper, lower, part);
        part += 1;
    }
    if let Some(ring) = bottom {
        t.cap(ring.first, n, false, part);
        part += 1;
    }
    if let Some(ring) = top {
        t.cap(ring.first, n, true, part);
    }
    t.closed = parts == Parts::ALL;
    t
}

/// A cone of `bottom_radius` and `height`, apex up: the side is `slices` triangles, the
/// bottom `slices - 2`; closed with both parts. Textured, the side's u runs as a sphere's
/// and v from the bottom (0) to the apex (1); the bottom is a cylinder's bottom cap.
pub fn cone(
    bottom_radius: f32,
    height: f32,
    complexity: f32,
    parts: Parts,
    textured: bool,
) -> Tessellation {
    let n = round_slices(complexity);
    let h = height * 0.5;
    let mut t = Tessellation::default();
    if bottom_radius == 0.0 || height == 0.0 {
        return t;
    }
    let side_uv = if textured {
        RingUv::Side(0.0)
    } else {
        RingUv::None
    };
    let ring = t.ring(n, bottom_radius, -h, side_uv);
    let mut part = 0;
    if parts.side {
        let apex = t.apex(n, h, textured.then_some(1.0));
        t.apex_fan(apex, ring, true, part);
        part += 1;
    }
    if parts.bottom {
        let cap = if textured {
            t.ring(n, bottom_radius, -h, RingUv::Cap { top: false })
        } else {
            ring
        };
        t.cap(cap.first, n, false, part);
    }
    t.closed = parts.side && parts.bottom;
    t
}

/// The directions of u and v on each face of [`BOX_QUADS`] (VRML 2.0 §6.4, Inventor's
/// SoCube): the sides upright seen from outside, the top seen from above with -z up, the
/// bottom seen from below with +z up.
const BOX_FACE_AXES: [[Vec3; 2]; 6] = [
    [Vec3::X, Vec3::Y],
    [Vec3::NEG_X, Vec3::Y],
    [Vec3::NEG_Z, Vec3::Y],
    [Vec3::Z, Vec3::Y],
    [Vec3::X, Vec3::NEG_Z],
    [Vec3::X, Vec3::Z],
];

/// Corner `i` of a box (0..8) as signs: +x when bit 0 is set, +y for bit 1, +z for bit 2.
fn box_corner(i: u32) -> Vec3 {
    let sign = |bit: u32| if i & bit != 0 { 1.0 } else { -1.0 };
    Vec3::new(sign(1), sign(2), sign(4))
}

/// The points of a centred box of half sizes `half`, flat x y z: its eight corners, or
/// textured, each face's four corners of its own (24 points, in [`box_quads`]'s order).
pub fn box_coords(half: Vec3, textured: bool) -> Vec<f32> {
    let corner = |i: u32| (box_corner(i) * half).to_array();
    if textured {
        BOX_QUADS
            .iter()
            .flatten()
            .flat_map(|&i| corner(i))
            .collect()
    } else {
        (0..8).flat_map(corner).collect()
    }
}

/// The corners of a box's six quads over [`box_coords`] (4 each).
pub fn box_quads(textured: bool) -> Vec<u32> {
    if textured {
        (0..24).collect()
    } else {
        BOX_QUADS.iter().flatten().copied().collect()
    }
}

/// The texture coordinates of a textured box's 24 points, flat u v: each face maps the
/// whole texture (0..1), oriented as [`BOX_FACE_AXES`] says.
pub fn box_texcoords() -> Vec<f32> {
    let mut uv = Vec::with_capacity(48);
    for (face, [u, v]) in BOX_QUADS.iter().zip(BOX_FACE_AXES) {
        for &i in face {
            let p = box_corner(i);
            uv.extend([0.5 + 0.5 * p.dot(u), 0.5 + 0.5 * p.dot(v)]);
        }
    }
    uv
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
        assert_eq!(sphere(1.0, 0.5, false).triangles.len(), 390);
        assert_eq!(
            cylinder(1.0, 2.0, 0.5, Parts::ALL, false).triangles.len(),
            40 + 18 + 18
        );
        assert_eq!(
            cone(1.0, 2.0, 0.5, Parts::ALL, false).triangles.len(),
            20 + 18
        );
    }

    #[test]
    fn full_shapes_are_closed_outward_and_near_their_volume() {
        let s = sphere(2.0, 1.0, false);
        assert!(closed(&s));
        let v = signed_volume(&s);
        assert!(
            v > 0.95 * 4.0 / 3.0 * PI * 8.0 && v < 4.0 / 3.0 * PI * 8.0,
            "{v}"
        );
        let c = cylinder(1.0, 3.0, 1.0, Parts::ALL, false);
        assert!(closed(&c));
        let v = signed_volume(&c);
        assert!(v > 0.98 * PI * 3.0 && v < PI * 3.0, "{v}");
        let k = cone(1.0, 3.0, 1.0, Parts::ALL, false);
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

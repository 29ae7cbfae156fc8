//! The report's test models (test001–test008) built in code, so tests can use them directly
//! and `tools/dev/gen_models.rs` can write them to `assets/`. Each is welded, counter-clockwise
//! seen from outside, with the vertex and triangle counts the report gives, and stands along
//! +y (VRML's up), so any viewer shows it upright.

use std::collections::HashMap;

use glam::Vec3;

use super::Model;

/// test001: a three-sided pyramid with one extra vertex in the middle of its base (5 / 6).
pub fn test001() -> Model {
    let s = 3f32.sqrt();
    let positions = vec![
        Vec3::new(-1.0, 0.0, -s / 3.0),
        Vec3::new(1.0, 0.0, -s / 3.0),
        Vec3::new(0.0, 0.0, 2.0 * s / 3.0),
        Vec3::new(0.0, 1.5, 0.0), // apex
        Vec3::new(0.0, 0.0, 0.0), // centre of the base
    ];
    // Base seen from below (normal -y), sides seen from outside.
    let triangles = vec![
        [4, 0, 1],
        [4, 1, 2],
        [4, 2, 0],
        [0, 3, 1],
        [1, 3, 2],
        [2, 3, 0],
    ];
    named("test001", positions, triangles)
}

/// test002: a 2×2 cube — each face a 2×2 grid of quads (26 / 48).
pub fn test002() -> Model {
    named_cube("test002", 2, 2.0)
}

/// test003: a one-sided 10×10 plane in z = 0, facing +z (121 / 200).
pub fn test003() -> Model {
    Model {
        name: "test003".into(),
        ..height_grid(10, |_, _| 0.0)
    }
}

/// An `n`×`n` grid of unit quads over x, y in 0..=n, each point raised to z = `height(x, y)`;
/// two triangles a quad, counter-clockwise seen from +z.
pub fn height_grid(n: u32, height: impl Fn(u32, u32) -> f32) -> Model {
    let mut positions = Vec::new();
    for y in 0..=n {
        for x in 0..=n {
            positions.push(Vec3::new(x as f32, y as f32, height(x, y)));
        }
    }
    let mut triangles = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let a = y * (n + 1) + x;
            triangles.push([a, a + 1, a + n + 2]);
            triangles.push([a, a + n + 2, a + n + 1]);
        }
    }
    named("grid", positions, triangles)
}

/// test004: a 10×10 cube — each face a 10×10 grid of quads (602 / 1200).
pub fn test004() -> Model {
    named_cube("test004", 10, 10.0)
}

/// test005: a hollow cylinder with thick walls along +y — outer (radius 2) and inner (1.5)
/// wall of 24 segments × 11 rings, joined by flat annular rims at y = 0 and y = 5 (528 /
/// 1056). The rims meet the walls at right angles: feature edges that must survive.
pub fn test005() -> Model {
    let (segments, rings) = (24u32, 11u32);
    let (outer, inner, height) = (2.0f32, 1.5f32, 5.0f32);
    let mut positions = Vec::new();
    for (radius, _) in [(outer, 0), (inner, 1)] {
        for r in 0..rings {
            let z = height * r as f32 / (rings - 1) as f32;
            for s in 0..segments {
                let a = std::f32::consts::TAU * s as f32 / segments as f32;
                positions.push(Vec3::new(radius * a.cos(), radius * a.sin(), z));
            }
        }
    }
    let id = |wall: u32, r: u32, s: u32| wall * rings * segments + r * segments + s % segments;
    let mut triangles = Vec::new();
    for r in 0..rings - 1 {
        for s in 0..segments {
            // Outer wall faces outwards, inner wall faces the axis.
            let (a, b, c, d) = (
                id(0, r, s),
                id(0, r, s + 1),
                id(0, r + 1, s + 1),
                id(0, r + 1, s),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
            let (a, b, c, d) = (
                id(1, r, s),
                id(1, r, s + 1),
                id(1, r + 1, s + 1),
                id(1, r + 1, s),
            );
            triangles.push([a, c, b]);
            triangles.push([a, d, c]);
        }
    }
    let top = rings - 1;
    for s in 0..segments {
        // Top rim faces +z, bottom rim faces -z.
        let (o0, o1, i0, i1) = (
            id(0, top, s),
            id(0, top, s + 1),
            id(1, top, s),
            id(1, top, s + 1),
        );
        triangles.push([o0, o1, i1]);
        triangles.push([o0, i1, i0]);
        let (o0, o1, i0, i1) = (id(0, 0, s), id(0, 0, s + 1), id(1, 0, s), id(1, 0, s + 1));
        triangles.push([o0, i1, o1]);
        triangles.push([o0, i0, i1]);
    }
    named("test005", z_up_to_y_up(positions), triangles)
}

/// test006: a squashed four-sided pyramid (a dome) over a square base in y = 0, apex at
/// y = 2.5: 48 points on each of 50 square rings plus apex and base centre (2402 / 4800). 40
/// rings rise as a dome, 10 rings close the flat base.
pub fn test006() -> Model {
    let (per_side, dome_rings, base_rings) = (12u32, 40u32, 10u32);
    let segments = 4 * per_side;
    let (half, height) = (5.0f32, 2.5f32);
    // A point on the square of half-size 1 at parameter s in 0..segments.
    let square = |s: u32| {
        let side = s / per_side;
        let t = (s % per_side) as f32 / per_side as f32 * 2.0 - 1.0;
        match side {
            0 => (1.0, t),
            1 => (-t, 1.0),
            2 => (-1.0, -t),
            _ => (t, -1.0),
        }
    };
    let mut positions = vec![Vec3::new(0.0, 0.0, height)]; // apex
    for r in 1..=dome_rings {
        let f = r as f32 / dome_rings as f32;
        let z = height * (1.0 - f * f);
        for s in 0..segments {
            let (x, y) = square(s);
            positions.push(Vec3::new(half * f * x, half * f * y, z));
        }
    }
    for r in 1..=base_rings {
        let f = 1.0 - r as f32 / (base_rings + 1) as f32;
        for s in 0..segments {
            let (x, y) = square(s);
            positions.push(Vec3::new(half * f * x, half * f * y, 0.0));
        }
    }
    let bottom = positions.len() as u32;
    positions.push(Vec3::ZERO);
    let rings = dome_rings + base_rings;
    let id = |r: u32, s: u32| 1 + (r - 1) * segments + s % segments;
    let mut triangles = Vec::new();
    for s in 0..segments {
        triangles.push([0, id(1, s), id(1, s + 1)]);
        triangles.push([bottom, id(rings, s + 1), id(rings, s)]);
    }
    for r in 1..rings {
        for s in 0..segments {
            let (a, b, c, d) = (id(r, s), id(r + 1, s), id(r + 1, s + 1), id(r, s + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    named("test006", z_up_to_y_up(positions), triangles)
}

/// test007: a washer (inner radius 1, outer 2, thickness 0.4, around +y) distorted by waves
/// around it and by a little deterministic noise: 134 segments × a 72-point rectangular
/// cross-section (9,648 / 19,296), closed, genus 1.
pub fn test007() -> Model {
    let (segments, across) = (134u32, 72u32);
    let (inner, outer, half) = (1.0f32, 2.0f32, 0.2f32);
    // The cross-section, counter-clockwise in (r, y): top inwards-out, outer wall down,
    // bottom outwards-in, inner wall up; each corner once.
    let section: Vec<(f32, f32)> = (0..across)
        .map(|k| {
            let (side, t) = match k {
                0..24 => (0, k as f32 / 24.0),
                24..36 => (1, (k - 24) as f32 / 12.0),
                36..60 => (2, (k - 36) as f32 / 24.0),
                _ => (3, (k - 60) as f32 / 12.0),
            };
            match side {
                0 => (outer + (inner - outer) * t, half),
                1 => (inner, half - 2.0 * half * t),
                2 => (inner + (outer - inner) * t, -half),
                _ => (outer, -half + 2.0 * half * t),
            }
        })
        .collect();
    let mut positions = Vec::with_capacity((segments * across) as usize);
    for s in 0..segments {
        let theta = std::f32::consts::TAU * s as f32 / segments as f32;
        for (k, &(r, y)) in section.iter().enumerate() {
            let noise = |salt: u32| 0.006 * hash_unit(s * across + k as u32, salt);
            let wave = 0.15 * (3.0 * theta).sin() + 0.04 * (7.0 * theta + 2.0 * r).sin();
            let r = r + noise(1);
            positions.push(Vec3::new(
                r * theta.cos(),
                y + wave + noise(2),
                r * theta.sin(),
            ));
        }
    }
    let id = |s: u32, k: u32| (s % segments) * across + k % across;
    let mut triangles = Vec::with_capacity((2 * segments * across) as usize);
    for s in 0..segments {
        for k in 0..across {
            let (a, b, c, d) = (id(s, k), id(s, k + 1), id(s + 1, k + 1), id(s + 1, k));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    named("test007", positions, triangles)
}

/// test008: a stretched box, 1 × 8 × 1 along +y, each face a grid of quads 0.25 on a side
/// (546 / 1088).
pub fn test008() -> Model {
    grid_box("test008", [4, 32, 4], Vec3::new(1.0, 8.0, 1.0))
}

/// A value in [-1, 1] from `index` and `salt`, the same on every machine (the generated
/// files must not change from run to run).
fn hash_unit(index: u32, salt: u32) -> f32 {
    let mut x = index.wrapping_mul(0x9E37_79B1) ^ salt.wrapping_mul(0x85EB_CA77);
    x ^= x >> 15;
    x = x.wrapping_mul(0x2C1B_3C6D);
    x ^= x >> 12;
    x = x.wrapping_mul(0x297A_2D39);
    x ^= x >> 15;
    (x as f32 / u32::MAX as f32) * 2.0 - 1.0
}

/// The report's (vertices, triangles) of test001–test008, in order: what [`all`] builds.
pub const REPORTED_COUNTS: [(usize, usize); 8] = [
    (5, 6),
    (26, 48),
    (121, 200),
    (602, 1200),
    (528, 1056),
    (2402, 4800),
    (9648, 19296),
    (546, 1088),
];

/// Every report model, in order.
pub fn all() -> Vec<Model> {
    vec![
        test001(),
        test002(),
        test003(),
        test004(),
        test005(),
        test006(),
        test007(),
        test008(),
    ]
}

/// A box's six faces as quads over its eight corners numbered by bits (the +x side for bit
/// 0, +y for bit 1, +z for bit 2), counter-clockwise seen from outside, in the order +z, -z,
/// +x, -x, +y, -y.
pub const BOX_QUADS: [[u32; 4]; 6] = [
    [4, 5, 7, 6],
    [0, 2, 3, 1],
    [1, 3, 7, 5],
    [0, 4, 6, 2],
    [2, 6, 7, 3],
    [0, 1, 5, 4],
];

/// The unit box [0, 1]³: 8 corners, 12 triangles, outward.
pub fn unit_box() -> Model {
    let corner = |i: u32| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32);
    Model {
        name: "box".into(),
        positions: (0..8).map(corner).collect(),
        triangles: BOX_QUADS
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect(),
        ..Model::default()
    }
}

/// The octahedron with corners ±x, ±y, ±z: 6 corners, 8 triangles, outward.
pub fn octahedron() -> Model {
    Model {
        name: "octahedron".into(),
        positions: vec![Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z],
        triangles: vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
        ..Model::default()
    }
}

/// An axis-aligned cube of side `size` centred at the origin, each face an `n`×`n` grid of
/// quads split into two triangles; shared edge and corner vertices are merged.
pub fn cube(n: u32, size: f32) -> Model {
    named_cube("cube", n, size)
}

fn named_cube(name: &str, n: u32, size: f32) -> Model {
    grid_box(name, [n; 3], Vec3::splat(size))
}

/// A box of `size` centred at the origin, each face a grid of quads (`counts[a]` along axis
/// `a`) split into two triangles, facing outwards; shared edge and corner vertices are merged.
fn grid_box(name: &str, counts: [u32; 3], size: Vec3) -> Model {
    let n = counts.map(|c| c as i32);
    let mut index: HashMap<[i32; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    // Each face: a fixed axis at ±n, two running axes chosen so (u × v) points outwards.
    let faces: [(usize, i32, usize, usize); 6] = [
        (0, 1, 1, 2),
        (0, -1, 2, 1),
        (1, 1, 2, 0),
        (1, -1, 0, 2),
        (2, 1, 0, 1),
        (2, -1, 1, 0),
    ];
    for (axis, sign, u, v) in faces {
        let mut id = |i: i32, j: i32| {
            let mut c = [0i32; 3];
            c[axis] = sign * n[axis];
            c[u] = 2 * i - n[u];
            c[v] = 2 * j - n[v];
            *index.entry(c).or_insert_with(|| {
                // `c` runs from -n to n in steps of 2 (two per quad): c · size / 2n spans the box.
                let at = |a: usize| c[a] as f32 * (size[a] / (2 * n[a]) as f32);
                positions.push(Vec3::new(at(0), at(1), at(2)));
                (positions.len() - 1) as u32
            })
        };
        for j in 0..n[v] {
            for i in 0..n[u] {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
    }
    named(name, positions, triangles)
}

/// Turns a shape built along +z to stand along +y: a rotation (not a mirror), so the
/// triangles stay counter-clockwise seen from outside.
fn z_up_to_y_up(positions: Vec<Vec3>) -> Vec<Vec3> {
    positions
        .into_iter()
        .map(|p| Vec3::new(p.x, p.z, -p.y))
        .collect()
}

fn named(name: &str, positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Model {
    Model {
        name: name.to_string(),
        positions,
        triangles,
        ..Model::default()
    }
}

/// A unit UV sphere around the y axis: poles at ±y, `rings` bands of `segments` quads
/// (2 · `segments` · (`rings` − 1) triangles), counter-clockwise seen from outside.
pub fn uv_sphere(rings: u32, segments: u32) -> Model {
    let (rings, segments) = (rings.max(2), segments.max(3));
    let mut positions = vec![Vec3::Y];
    for r in 1..rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            positions.push(Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ));
        }
    }
    positions.push(-Vec3::Y);
    let bottom = positions.len() as u32 - 1;
    let ring = |r: u32, s: u32| 1 + (r - 1) * segments + s % segments;
    let mut triangles = Vec::with_capacity(2 * (rings * segments) as usize);
    for s in 0..segments {
        triangles.push([0, ring(1, s), ring(1, s + 1)]);
        triangles.push([bottom, ring(rings - 1, s + 1), ring(rings - 1, s)]);
    }
    for r in 1..rings - 1 {
        for s in 0..segments {
            let (a, b, c, d) = (
                ring(r, s),
                ring(r, s + 1),
                ring(r + 1, s + 1),
                ring(r + 1, s),
            );
            triangles.push([a, d, c]);
            triangles.push([a, c, b]);
        }
    }
    named("sphere", positions, triangles)
}

/// [`uv_sphere`] with gentle bumps: low-frequency waves plus a small deterministic roughness,
/// radius about 1 — a stand-in for a large smooth scan in benchmarks and tests.
pub fn bumpy_sphere(rings: u32, segments: u32) -> Model {
    let mut m = uv_sphere(rings, segments);
    let segments = segments.max(3);
    let last = m.positions.len() - 1;
    for (i, p) in m.positions.iter_mut().enumerate().take(last).skip(1) {
        // Ring r, segment s of vertex i, and its angles.
        let (r, s) = ((i as u32 - 1) / segments + 1, (i as u32 - 1) % segments);
        let theta = p.y.clamp(-1.0, 1.0).acos();
        let phi = (-p.z).atan2(p.x);
        let hash = (r.wrapping_mul(7919) ^ s.wrapping_mul(104_729)) % 97;
        *p *= 1.0 + 0.02 * (7.0 * theta).sin() * (5.0 * phi).cos() + 0.0003 * hash as f32 / 97.0;
    }
    m
}

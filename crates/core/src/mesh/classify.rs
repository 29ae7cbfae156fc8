//! Vertex classification of Schroeder, Zarge and Lorensen, "Decimation of Triangle Meshes"
//! (SIGGRAPH 1992), shared by every algorithm:
//!
//! | class          | one-ring                      | feature edges at the vertex        |
//! |----------------|-------------------------------|------------------------------------|
//! | simple         | closed                        | none or one                        |
//! | interior edge  | closed                        | exactly two, turning less than the feature angle |
//! | boundary       | open                          | none inside, boundary turning less than the feature angle |
//! | corner         | closed or open                | three or more, or a sharp turn     |
//! | complex        | non-manifold                  | —                                  |
//!
//! A feature edge is one whose dihedral angle (between its two triangles' normals) exceeds
//! the feature angle. Corners and complex vertices are never removed; the "sharp turn" rule
//! keeps the corners of a plane's outline and of a crease line, which the 2002 program lost.

use glam::{DVec3, Vec3};

use super::topology::{Adjacency, Ring, RingShape};

/// What a vertex is, for decimation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VertexClass {
    Simple,
    /// Manifold boundary vertex; its boundary neighbours are the ring's ends.
    Boundary,
    /// On a crease: ring positions of the two feature neighbours, `first < second`.
    InteriorEdge {
        first: usize,
        second: usize,
    },
    Corner,
    Complex,
    /// Used by no triangle.
    Isolated,
}

/// Per-triangle geometry of a ring, filled by [`classify`] for the caller's error terms.
#[derive(Debug, Clone, Default)]
pub struct RingGeometry {
    /// Unnormalised normal of ring triangle `i` (length = twice its area).
    pub crosses: Vec<DVec3>,
    /// `crosses[i].length()`.
    pub lengths: Vec<f64>,
}

/// Classifies `v`. Fills `ring` with its one-ring and `geometry` with its triangles'
/// normals and areas. `conn` is the whole mesh or a part owning `v`'s triangles.
///
/// With `seam_side` (`v` is one side of a two-sided texture seam), an open ring's outline
/// may turn freely: no sharp turn makes a corner, only a crease. A chart's outline follows
/// the triangles it was cut along and zig-zags; its two sides go together, so the surface
/// stays whole whatever the outline does, and kept as corners every turn would keep the
/// seams dense while the charts' insides went.
pub fn classify(
    conn: &impl Adjacency,
    positions: &[Vec3],
    v: u32,
    cos_feature: f64,
    seam_side: bool,
    ring: &mut Ring,
    geometry: &mut RingGeometry,
) -> VertexClass {
    let shape = conn.ring(v, ring);
    classify_ring(positions, v, cos_feature, seam_side, shape, ring, geometry)
}

/// As [`classify`], for `v`'s one-ring `ring` of shape `shape` as read already (or
/// reshaped: a ring whose two ends are copies of one seam junction, closed there).
pub fn classify_ring(
    positions: &[Vec3],
    v: u32,
    cos_feature: f64,
    seam_side: bool,
    shape: RingShape,
    ring: &Ring,
    geometry: &mut RingGeometry,
) -> VertexClass {
    let RingGeometry { crosses, lengths } = geometry;
    crosses.clear();
    lengths.clear();
    match shape {
        RingShape::Isolated => return VertexClass::Isolated,
        RingShape::Complex => return VertexClass::Complex,
        RingShape::Closed | RingShape::Open => {}
    }
    let p = positions[v as usize].as_dvec3();
    // Closed rings wrap around: the last triangle ends at the first neighbour.
    let mut a = positions[ring.verts[0] as usize].as_dvec3() - p;
    for i in 0..ring.triangles.len() {
        let next = ring.verts.get(i + 1).unwrap_or(&ring.verts[0]);
        let b = positions[*next as usize].as_dvec3() - p;
        let c = a.cross(b);
        crosses.push(c);
        lengths.push(c.length());
        a = b;
    }
    let is_feature = |i: usize, j: usize| {
        let len = lengths[i] * lengths[j];
        len > 0.0 && crosses[i].dot(crosses[j]) < cos_feature * len
    };
    let sharp_turn = |a: u32, b: u32| {
        let d1 = (p - positions[a as usize].as_dvec3()).normalize_or_zero();
        let d2 = (positions[b as usize].as_dvec3() - p).normalize_or_zero();
        d1.dot(d2) < cos_feature
    };
    let k = crosses.len();
    if shape == RingShape::Open {
        // Interior ring edges are verts[1..k]; each lies between ring triangles i-1 and i.
        if (1..k).any(|i| is_feature(i - 1, i)) {
            return VertexClass::Corner;
        }
        return if !seam_side && sharp_turn(ring.verts[0], ring.verts[k]) {
            VertexClass::Corner
        } else {
            VertexClass::Boundary
        };
    }
    // Closed: ring edge to verts[i] lies between triangles i-1 and i.
    let mut features = [0usize; 2];
    let mut count = 0;
    for i in 0..k {
        if is_feature(if i == 0 { k - 1 } else { i - 1 }, i) {
            if count < 2 {
                features[count] = i;
            }
            count += 1;
        }
    }
    match count {
        0 | 1 => VertexClass::Simple,
        2 => {
            let (first, second) = (features[0], features[1]);
            if sharp_turn(ring.verts[first], ring.verts[second]) {
                VertexClass::Corner
            } else {
                VertexClass::InteriorEdge { first, second }
            }
        }
        _ => VertexClass::Corner,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::topology::Connectivity;

    fn classify_vertex(positions: &[Vec3], tris: &[[u32; 3]], v: u32) -> VertexClass {
        classify_side(positions, tris, v, false)
    }

    /// As [`classify_vertex`], saying whether `v` is one side of a texture seam.
    fn classify_side(positions: &[Vec3], tris: &[[u32; 3]], v: u32, seam: bool) -> VertexClass {
        let conn = Connectivity::new(positions.len(), tris);
        let cos = 30f64.to_radians().cos();
        classify(
            &conn,
            positions,
            v,
            cos,
            seam,
            &mut Ring::default(),
            &mut RingGeometry::default(),
        )
    }

    // A unit-spaced 3x3 grid, vertex ids row by row:
    //   6 7 8
    //   3 4 5
    //   0 1 2
    fn grid(z: impl Fn(f32, f32) -> f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let mut p = Vec::new();
        for y in 0..3 {
            for x in 0..3 {
                p.push(Vec3::new(x as f32, y as f32, z(x as f32, y as f32)));
            }
        }
        let mut t = Vec::new();
        for y in 0..2u32 {
            for x in 0..2u32 {
                let a = y * 3 + x;
                t.push([a, a + 1, a + 4]);
                t.push([a, a + 4, a + 3]);
            }
        }
        (p, t)
    }

    #[test]
    fn flat_grid_classes() {
        let (p, t) = grid(|_, _| 0.0);
        assert_eq!(classify_vertex(&p, &t, 4), VertexClass::Simple);
        assert_eq!(classify_vertex(&p, &t, 1), VertexClass::Boundary);
        assert_eq!(classify_vertex(&p, &t, 0), VertexClass::Corner);
        assert_eq!(classify_vertex(&p, &t, 8), VertexClass::Corner);
    }

    #[test]
    fn crease_makes_interior_edge_vertex() {
        // Folded 90 degrees along the line x = 1.
        let (p, t) = grid(|x, _| if x > 1.0 { x - 1.0 } else { 0.0 });
        let c = classify_vertex(&p, &t, 4);
        assert!(matches!(c, VertexClass::InteriorEdge { .. }), "{c:?}");
        // A boundary vertex on the crease has a feature edge inside its ring: corner.
        assert_eq!(classify_vertex(&p, &t, 1), VertexClass::Corner);
    }

    #[test]
    fn a_seam_sides_outline_turns_freely_but_a_crease_stays_a_corner() {
        // The flat grid's corner turns 90° along its outline: on a seam, no corner.
        let (p, t) = grid(|_, _| 0.0);
        assert_eq!(classify_side(&p, &t, 0, true), VertexClass::Boundary);
        // The folded grid's vertex 1 has a crease inside its ring: a corner still.
        let (p, t) = grid(|x, _| if x > 1.0 { x - 1.0 } else { 0.0 });
        assert_eq!(classify_side(&p, &t, 1, true), VertexClass::Corner);
    }

    #[test]
    fn cube_corner_is_corner() {
        let p = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
        ];
        // The three faces meeting at the origin, seen from outside.
        let t = [
            [0, 2, 4],
            [0, 4, 1],
            [0, 1, 6],
            [0, 6, 3],
            [0, 3, 5],
            [0, 5, 2],
        ];
        assert_eq!(classify_vertex(&p, &t, 0), VertexClass::Corner);
    }
}

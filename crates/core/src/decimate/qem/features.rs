//! What `--keep-features` holds in place under quadric edge collapse: every vertex's feature
//! class, read off the input's feature edges (an edge of two triangles whose normals turn by
//! more than the feature angle). A corner (one feature edge: a crease's end, or three and
//! more) never moves nor goes; a crease vertex (two) goes only along its crease into another
//! vertex of the same crease, the kept one staying on the line between them (`Part::plan`).

use glam::{DVec3, Vec3};

use crate::mesh::topology::Connectivity;
use crate::mesh::union_find;

/// A vertex on no feature edge.
pub(super) const NONE: u32 = u32::MAX;
/// A vertex that never moves nor goes.
pub(super) const CORNER: u32 = u32::MAX - 1;

/// Per vertex, [`NONE`], [`CORNER`] or the id of the crease it is on (a crease: the vertices
/// of two feature edges each, joined by feature edges).
pub(super) fn classify(conn: &Connectivity, positions: &[Vec3], cos_feature: f64) -> Vec<u32> {
    let edges = feature_edges(conn, positions, cos_feature);
    let mut count = vec![0u32; positions.len()];
    for &(a, b) in &edges {
        count[a as usize] += 1;
        count[b as usize] += 1;
    }
    let mut parent = union_find::singletons(positions.len());
    for &(a, b) in &edges {
        if count[a as usize] == 2 && count[b as usize] == 2 {
            let (ra, rb) = (
                union_find::root(&mut parent, a),
                union_find::root(&mut parent, b),
            );
            parent[rb as usize] = ra;
        }
    }
    (0..positions.len() as u32)
        .map(|v| match count[v as usize] {
            0 => NONE,
            2 => union_find::root(&mut parent, v),
            _ => CORNER,
        })
        .collect()
}

/// The feature edges (smaller end first), each once: sorted half-edges paired up, so that
/// the cost is the triangles' count's logarithm per triangle whatever the valences.
fn feature_edges(conn: &Connectivity, positions: &[Vec3], cos_feature: f64) -> Vec<(u32, u32)> {
    let mut half: Vec<(u32, u32, u32)> = Vec::new();
    for t in conn.alive_ids() {
        let tri = conn.triangle(t);
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            half.push((a.min(b), a.max(b), t));
        }
    }
    half.sort_unstable();
    let normal = |t: u32| {
        let [a, b, c] = conn.triangle(t).map(|v| positions[v as usize].as_dvec3());
        (b - a).cross(c - a).normalize_or_zero()
    };
    half.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1))
        .filter_map(|edge| match edge {
            [(a, b, s), (_, _, t)] => {
                folded(normal(*s), normal(*t), cos_feature).then_some((*a, *b))
            }
            _ => None,
        })
        .collect()
}

/// True when two unit normals (zero: a triangle with no area) turn by more than the
/// feature angle whose cosine is `cos_feature`.
pub(super) fn folded(n1: DVec3, n2: DVec3, cos_feature: f64) -> bool {
    n1 != DVec3::ZERO && n2 != DVec3::ZERO && n1.dot(n2) < cos_feature
}

//! Welding: merging coincident vertices of a model so that faces which duplicate their
//! corners (common in VRML/Inventor files) share vertices, as decimation needs.
//!
//! Exact at tolerance 0 (bit-equal positions, with -0 equal to +0), by sorting the vertices'
//! keys on all cores; within a tolerance by hashing positions into a grid of cells of that
//! size and looking at the 27 cells around each vertex (expected linear time). The first
//! vertex of a group is kept (with its per-vertex attributes); triangles are remapped, and
//! those that collapse are dropped along with their per-face attributes. Vertices with
//! different texture coordinates or per-vertex colours never merge: they are the two sides
//! of a seam (`mesh::seams`).

use std::collections::HashMap;

use glam::Vec3;
use rayon::prelude::*;

use super::{Attribute, Model};

fn key_exact(p: Vec3) -> [u32; 3] {
    // +0.0 folds -0.0 into 0.0; NaNs keep their bits (and never weld with numbers).
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}

/// What keeps coincident vertices apart: their texture coordinates' and per-vertex
/// colours' bits (as `key_exact`), where the model has them.
#[derive(Clone, Copy)]
struct Sides<'a> {
    texcoords: Option<&'a [[f32; 2]]>,
    colors: Option<&'a [[f32; 3]]>,
}

impl<'a> Sides<'a> {
    fn of(model: &'a Model) -> Self {
        let colors = match &model.colors {
            Some(Attribute::PerVertex(c)) => Some(c.as_slice()),
            _ => None,
        };
        Self {
            texcoords: model.texcoords.as_deref(),
            colors,
        }
    }

    const NONE: Sides<'static> = Sides {
        texcoords: None,
        colors: None,
    };

    /// Vertex `i`'s side key: texture coordinates, then colour (zero where absent).
    fn key(&self, i: usize) -> [u32; 5] {
        let bits = |x: f32| (x + 0.0).to_bits();
        let uv = self
            .texcoords
            .and_then(|t| t.get(i))
            .map_or([0; 2], |t| t.map(bits));
        let rgb = self
            .colors
            .and_then(|c| c.get(i))
            .map_or([0; 3], |c| c.map(bits));
        [uv[0], uv[1], rgb[0], rgb[1], rgb[2]]
    }
}

fn cell(p: Vec3, inv: f32) -> [i64; 3] {
    let c = (p * inv).floor();
    [c.x as i64, c.y as i64, c.z as i64]
}

/// Groups bit-equal vertices (position and side key, as `key_exact`): returns each
/// vertex's group, numbered in the order of the groups' first vertices, and those first
/// vertices. The keys are sorted with their indices on all cores, so that each run of equal
/// keys starts at its group's first vertex: faster than a hash map (docs/design.md#weld).
fn exact_groups(positions: &[Vec3], sides: Sides<'_>) -> (Vec<u32>, Vec<u32>) {
    // The smallest key that tells the model's vertices apart: sorting moves less memory.
    if sides.colors.is_some() {
        exact_groups_by(positions, |i| sides.key(i))
    } else if let Some(t) = sides.texcoords {
        exact_groups_by(positions, |i| {
            t.get(i)
                .map_or([0; 2], |uv| uv.map(|x| (x + 0.0).to_bits()))
        })
    } else {
        exact_groups_by(positions, |_| ())
    }
}

/// `exact_groups` with the side key `side` of each vertex.
fn exact_groups_by<K: Ord + Copy + Send>(
    positions: &[Vec3],
    side: impl Fn(usize) -> K + Sync,
) -> (Vec<u32>, Vec<u32>) {
    let mut keyed: Vec<([u32; 3], K, u32)> = positions
        .par_iter()
        .enumerate()
        .map(|(i, &p)| (key_exact(p), side(i), i as u32))
        .collect();
    keyed.par_sort_unstable();
    // Each vertex's group's first vertex.
    let mut first = vec![0u32; positions.len()];
    let mut start = 0;
    for (j, k) in keyed.iter().enumerate() {
        if (k.0, k.1) != (keyed[start].0, keyed[start].1) {
            start = j;
        }
        first[k.2 as usize] = keyed[start].2;
    }
    // Groups numbered by their first vertex, in input order.
    let mut map = vec![0u32; positions.len()];
    let mut kept = Vec::new();
    for i in 0..positions.len() {
        let f = first[i] as usize;
        map[i] = if f == i {
            kept.push(i as u32);
            kept.len() as u32 - 1
        } else {
            map[f]
        };
    }
    (map, kept)
}

/// Each vertex's point: vertices at the same position, bit for bit (`-0` as `0`), share
/// one number, numbered in the order of their first vertices.
pub fn point_ids(positions: &[Vec3]) -> Vec<u32> {
    exact_groups(positions, Sides::NONE).0
}

/// Groups vertices within `tolerance` of a group's first vertex (and with its side key),
/// in input order, as [`exact_groups`] returns them.
fn near_groups(positions: &[Vec3], sides: Sides<'_>, tolerance: f32) -> (Vec<u32>, Vec<u32>) {
    let n = positions.len();
    let mut map = vec![0u32; n];
    let mut kept: Vec<u32> = Vec::with_capacity(n);
    let inv = 1.0 / tolerance;
    let tol2 = tolerance * tolerance;
    // Cell -> most recent kept vertex in it; `chain` links kept vertices of the same cell.
    let mut heads: HashMap<[i64; 3], u32> = HashMap::with_capacity(n);
    let mut chain: Vec<u32> = Vec::with_capacity(n);
    for (i, &p) in positions.iter().enumerate() {
        let c = cell(p, inv);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    // Wrapping: huge coordinates saturate the cell numbers.
                    let k = [
                        c[0].wrapping_add(dx),
                        c[1].wrapping_add(dy),
                        c[2].wrapping_add(dz),
                    ];
                    let mut at = heads.get(&k).copied();
                    while let Some(j) = at {
                        let other = kept[j as usize] as usize;
                        let q = positions[other];
                        if p.distance_squared(q) <= tol2 && sides.key(i) == sides.key(other) {
                            found = Some(j);
                            break 'search;
                        }
                        at = match chain[j as usize] {
                            u32::MAX => None,
                            next => Some(next),
                        };
                    }
                }
            }
        }
        map[i] = match found {
            Some(j) => j,
            None => {
                let j = kept.len() as u32;
                kept.push(i as u32);
                chain.push(heads.insert(c, j).unwrap_or(u32::MAX));
                j
            }
        };
    }
    (map, kept)
}

/// Merges vertices closer than `tolerance` (exactly equal at 0), remaps the triangles, drops
/// the triangles that became degenerate; returns how many vertices were merged away.
pub fn weld(model: &mut Model, tolerance: f32) -> usize {
    let n = model.positions.len();
    let sides = Sides::of(model);
    // old vertex -> new vertex; `kept` lists the old indices that survive, in order.
    let (map, kept) = if tolerance > 0.0 && tolerance.is_finite() {
        near_groups(&model.positions, sides, tolerance)
    } else {
        exact_groups(&model.positions, sides)
    };
    let merged = n - kept.len();
    if merged == 0 {
        return 0;
    }
    model.positions = kept.iter().map(|&i| model.positions[i as usize]).collect();
    let mut keep_face = Vec::with_capacity(model.triangles.len());
    let mut triangles = Vec::with_capacity(model.triangles.len());
    for t in &model.triangles {
        let r = t.map(|v| map.get(v as usize).copied().unwrap_or(v));
        let ok = r[0] != r[1] && r[1] != r[2] && r[0] != r[2];
        keep_face.push(ok);
        if ok {
            triangles.push(r);
        }
    }
    model.triangles = triangles;
    fn fix<T: Copy>(attr: &mut Option<Attribute<T>>, kept: &[u32], keep_face: &[bool]) {
        if let Some(a) = attr {
            match a {
                Attribute::PerVertex(v) => {
                    *v = kept
                        .iter()
                        .filter_map(|&i| v.get(i as usize).copied())
                        .collect();
                }
                Attribute::PerFace(v) => {
                    let mut k = keep_face.iter();
                    v.retain(|_| k.next().copied().unwrap_or(false));
                }
            }
        }
    }
    fix(&mut model.colors, &kept, &keep_face);
    fix(&mut model.normals, &kept, &keep_face);
    if let Some(t) = &mut model.texcoords {
        *t = kept
            .iter()
            .filter_map(|&i| t.get(i as usize).copied())
            .collect();
    }
    merged
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube whose six faces each have their own four corners (24 vertices), coloured
    /// by point (copies of a point share a colour).
    fn split_cube() -> Model {
        let corner =
            |i: u32| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32);
        let mut m = Model::default();
        for f in crate::mesh::shapes::BOX_QUADS {
            let b = m.positions.len() as u32;
            m.positions.extend(f.map(corner));
            m.triangles.push([b, b + 1, b + 2]);
            m.triangles.push([b, b + 2, b + 3]);
        }
        let colors = m.positions.iter().map(|p| p.to_array()).collect();
        m.colors = Some(Attribute::PerVertex(colors));
        m
    }

    #[test]
    fn exact_weld_of_a_split_cube_gives_eight_vertices() {
        let mut m = split_cube();
        assert_eq!(weld(&mut m, 0.0), 16);
        assert_eq!(m.positions.len(), 8);
        assert_eq!(m.triangles.len(), 12);
        assert_eq!(m.used_vertex_count(), 8);
        // Each point keeps its colour.
        let Some(Attribute::PerVertex(c)) = &m.colors else {
            panic!()
        };
        assert_eq!(c.len(), 8);
        for (p, c) in m.positions.iter().zip(c) {
            assert_eq!(p.to_array(), *c);
        }
        assert_eq!(weld(&mut m, 0.0), 0);
    }

    #[test]
    fn vertices_on_a_colour_seam_stay_apart() {
        // Every face its own colour: a colour jump along every edge, nothing merges.
        let mut m = split_cube();
        m.colors = Some(Attribute::PerVertex(
            (0..24).map(|i| [(i / 4) as f32, 0.0, 0.0]).collect(),
        ));
        assert_eq!(weld(&mut m.clone(), 0.0), 0);
        assert_eq!(weld(&mut m, 1e-3), 0);
        // Face 0 red, the rest white: the other five faces' 20 corners close up into the
        // cube's 8 points; face 0's 4 corners stay apart, the seam's red side.
        let mut lid = split_cube();
        lid.colors = Some(Attribute::PerVertex(
            (0..24)
                .map(|i| if i < 4 { [1.0, 0.0, 0.0] } else { [1.0; 3] })
                .collect(),
        ));
        assert_eq!(weld(&mut lid, 0.0), 12);
        assert_eq!(lid.used_vertex_count(), 12);
    }

    #[test]
    fn tolerance_weld_merges_near_points_and_drops_collapsed_triangles() {
        let mut m = Model {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::new(1e-4, 0.0, 0.0),   // near 0
                Vec3::new(1.0, 1e-4, -1e-4), // near 1
                Vec3::new(-0.0, 1.0, 0.0),   // exactly 2 (-0)
            ],
            triangles: vec![[0, 1, 2], [3, 4, 5], [0, 3, 1]],
            colors: Some(Attribute::PerFace(vec![[1.0; 3], [2.0; 3], [3.0; 3]])),
            ..Model::default()
        };
        let mut exact = m.clone();
        assert_eq!(weld(&mut exact, 0.0), 1, "only -0 equals +0 exactly");
        assert_eq!(weld(&mut m, 1e-3), 3);
        assert_eq!(m.positions.len(), 3);
        // The second triangle duplicates the first; the third collapses and goes.
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 1, 2]]);
        assert_eq!(m.colors, Some(Attribute::PerFace(vec![[1.0; 3], [2.0; 3]])));
    }

    #[test]
    fn vertices_on_a_texture_seam_stay_apart() {
        let mut m = split_cube();
        // The first two faces' corners share u = 0; the others have their own u.
        m.texcoords = Some(
            (0..24)
                .map(|i| if i < 8 { [0.0, 0.5] } else { [i as f32, 0.5] })
                .collect(),
        );
        // Faces 0 and 1 share no corner point: nothing merges, at either tolerance.
        let mut exact = m.clone();
        assert_eq!(weld(&mut exact, 0.0), 0);
        assert_eq!(weld(&mut m, 1e-3), 0);
        // Same coordinates everywhere: the cube closes up, with its coordinates.
        let mut same = split_cube();
        same.texcoords = Some(vec![[0.25, 0.75]; 24]);
        assert_eq!(weld(&mut same, 0.0), 16);
        assert_eq!(same.texcoords, Some(vec![[0.25, 0.75]; 8]));
    }

    #[test]
    fn sorted_exact_groups_match_first_come_numbering() {
        // Many repeats, -0 against +0, a NaN twice, and texture coordinates that split
        // some positions: every vertex goes to the group of the first vertex with its key,
        // and groups are numbered as their first vertices come.
        let mut state = 12345u32;
        let mut next = |m: u32| {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) % m
        };
        let points = [0.0, -0.0, 1.0, 2.5, f32::NAN];
        let n = 5000;
        let positions: Vec<Vec3> = (0..n)
            .map(|_| Vec3::new(points[next(5) as usize], points[next(3) as usize], 7.0))
            .collect();
        let uvs: Vec<[f32; 2]> = (0..n).map(|_| [next(2) as f32, 0.0]).collect();
        let rgbs: Vec<[f32; 3]> = (0..n).map(|_| [0.5, next(2) as f32, 0.0]).collect();
        let sides = [
            Sides::NONE,
            Sides {
                texcoords: Some(uvs.as_slice()),
                colors: None,
            },
            Sides {
                texcoords: Some(uvs.as_slice()),
                colors: Some(rgbs.as_slice()),
            },
        ];
        for sides in sides {
            let mut first_of = HashMap::new();
            let (mut want_map, mut want_kept) = (Vec::new(), Vec::new());
            for (i, &p) in positions.iter().enumerate() {
                let group = *first_of
                    .entry((key_exact(p), sides.key(i)))
                    .or_insert_with(|| {
                        want_kept.push(i as u32);
                        want_kept.len() as u32 - 1
                    });
                want_map.push(group);
            }
            let (map, kept) = exact_groups(&positions, sides);
            assert_eq!(kept, want_kept);
            assert_eq!(map, want_map);
            // -0 and +0 are one value: x takes 4 (NaN, with its bits, is one), y 2.
            if sides.texcoords.is_none() {
                assert_eq!(kept.len(), 8);
            }
        }
    }

    #[test]
    fn huge_and_non_finite_coordinates_do_not_panic() {
        let mut m = Model {
            positions: vec![
                Vec3::splat(1e30),
                Vec3::splat(-1e30),
                Vec3::NAN,
                Vec3::splat(1e30),
            ],
            ..Model::default()
        };
        assert_eq!(weld(&mut m, 1e-6), 1);
    }

    #[test]
    fn points_across_a_cell_border_still_weld() {
        let mut m = Model {
            positions: vec![Vec3::splat(0.999_9), Vec3::splat(1.000_1)],
            ..Model::default()
        };
        assert_eq!(weld(&mut m, 1e-3), 1);
    }
}

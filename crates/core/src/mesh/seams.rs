//! Seams: where a model's texture coordinates or per-vertex colours jump, its file gives one
//! point two or more coordinate pairs or colours, and the model holds one vertex per side,
//! at the same position (see `Model::texcoords`, `mesh::weld`). The surface is cut there. Were the sides simplified on their own,
//! their outlines would part and open a crack: decimation takes a seam's two sides away
//! together (vertex removal removes both, edge collapse collapses both edges to one point),
//! and pins the junctions where three or more sides meet; a vertex between two copies of a
//! junction (a pole's first ring) goes into it as the welded surface's step would.

use std::collections::HashMap;

use glam::Vec3;

use super::Model;

/// A model's texture seams, found in one pass over its used vertices' positions.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Seams {
    /// One flag per vertex: true for a vertex that a triangle uses and whose exact position
    /// another used vertex shares.
    pub on_seam: Vec<bool>,
    /// For each vertex on a seam where exactly two used vertices share the position (the
    /// seam's two sides, away from junctions of three or more charts), the other one;
    /// `u32::MAX` for every other vertex. Such pairs may go together: removing both sides
    /// at once keeps the seam closed (see `decimate::schroeder`; `decimate::qem` collapses
    /// both sides' edges together).
    pub twin: Vec<u32>,
}

/// The seams of `model`; none without seam attributes (`Model::has_seam_attributes`: an
/// unwelded model's duplicates are not seams).
pub fn find(model: &Model) -> Seams {
    let n = model.positions.len();
    let mut seams = Seams {
        on_seam: vec![false; n],
        twin: vec![u32::MAX; n],
    };
    if !model.has_seam_attributes() {
        return seams;
    }
    let used = used_vertices(model);
    // Position (bits, -0 folded into +0) -> the used vertices there: the first, the second,
    // and how many in all.
    let mut at: HashMap<[u32; 3], (u32, u32, u32)> = HashMap::new();
    for (v, p) in model.positions.iter().enumerate() {
        if !used[v] {
            continue;
        }
        let key = position_key(*p);
        let entry = at.entry(key).or_insert((v as u32, u32::MAX, 0));
        entry.2 += 1;
        if entry.2 >= 2 {
            seams.on_seam[v] = true;
            seams.on_seam[entry.0 as usize] = true;
        }
        if entry.2 == 2 {
            entry.1 = v as u32;
        }
    }
    for &(a, b, count) in at.values() {
        if count == 2 {
            seams.twin[a as usize] = b;
            seams.twin[b as usize] = a;
        }
    }
    seams
}

/// The pinned vertices (`pinned`, by vertex) that share a position, linked in cycles: entry
/// `v` is the next one at `v`'s position (a junction's copies, one per side), `u32::MAX`
/// for a vertex that shares it with no other. Empty when no two share a position.
pub fn copy_cycles(positions: &[Vec3], pinned: &[bool]) -> Vec<u32> {
    let mut cycles = Vec::new();
    // Position key -> the first and the last pinned vertex there.
    let mut at: HashMap<[u32; 3], (u32, u32)> = HashMap::new();
    for (v, p) in positions.iter().enumerate() {
        if !pinned.get(v).copied().unwrap_or(false) {
            continue;
        }
        let v = v as u32;
        let key = position_key(*p);
        let (first, last) = at.entry(key).or_insert((v, v));
        if *last != v {
            if cycles.is_empty() {
                cycles = vec![u32::MAX; positions.len()];
            }
            // Close the cycle through the new copy.
            cycles[*last as usize] = v;
            cycles[v as usize] = *first;
            *last = v;
        }
    }
    cycles
}

/// Each junction copy's starting normal: the unit area-weighted normal of all the
/// triangles at any of its copies (`cycles`, from [`copy_cycles`]), the way the surface
/// faces there; zero for other vertices, empty when `cycles` is. A junction never moves,
/// so decimation keeps the triangles at it facing this way.
pub fn junction_normals(positions: &[Vec3], triangles: &[[u32; 3]], cycles: &[u32]) -> Vec<Vec3> {
    if cycles.is_empty() {
        return Vec::new();
    }
    let at_junction = |v: u32| cycles.get(v as usize).is_some_and(|&c| c != u32::MAX);
    let mut sum = vec![glam::DVec3::ZERO; cycles.len()];
    for tri in triangles
        .iter()
        .filter(|t| t.iter().any(|&v| at_junction(v)))
    {
        let [a, b, c] = tri.map(|v| positions[v as usize].as_dvec3());
        let cross = (b - a).cross(c - a);
        for &v in tri {
            sum[v as usize] += cross;
        }
    }
    let mut normals = vec![Vec3::ZERO; cycles.len()];
    let mut done = vec![false; cycles.len()];
    for v in 0..cycles.len() as u32 {
        if done[v as usize] || !at_junction(v) {
            continue;
        }
        // Walked once per junction, along its cycle of copies.
        let total: glam::DVec3 = copies(v, &[], cycles).map(|c| sum[c as usize]).sum();
        for c in copies(v, &[], cycles) {
            normals[c as usize] = total.normalize_or_zero().as_vec3();
            done[c as usize] = true;
        }
    }
    normals
}

/// `v` and the other vertices at its position that stand for the same point of the
/// surface: its twin across a seam (`twins`, `u32::MAX`: none), or the other copies of a
/// pinned junction (`cycles`, from [`copy_cycles`]). Either slice may be empty.
pub fn copies<'a>(v: u32, twins: &'a [u32], cycles: &'a [u32]) -> impl Iterator<Item = u32> + 'a {
    let twin = twins.get(v as usize).copied().filter(|&t| t != u32::MAX);
    let mut next = Some(v);
    std::iter::from_fn(move || {
        let c = next?;
        next = match twin {
            Some(t) => (c == v).then_some(t),
            None => cycles
                .get(c as usize)
                .copied()
                .filter(|&n| n != v && n != u32::MAX),
        };
        Some(c)
    })
}

/// The bits of position `p`, `-0` folded into `0`: equal keys, the same point exactly.
pub fn position_key(p: Vec3) -> [u32; 3] {
    [p.x, p.y, p.z].map(|x| (x + 0.0).to_bits())
}

/// One flag per vertex: true when a triangle uses it.
fn used_vertices(model: &Model) -> Vec<bool> {
    let mut used = vec![false; model.positions.len()];
    for t in &model.triangles {
        for &v in t {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    }
    used
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_two_sides_of_a_seam_are_flagged_and_nothing_else() {
        let m = Model {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::new(-0.0, 0.0, 0.0), // 0 again, the other side
                Vec3::NEG_Y,
                Vec3::X, // a copy no triangle uses
            ],
            triangles: vec![[0, 1, 2], [3, 4, 1]],
            texcoords: Some(vec![[0.0; 2]; 6]),
            ..Model::default()
        };
        // Vertex 1 is shared by both triangles (one vertex), 0 and 3 are the seam's sides.
        assert_eq!(
            find(&m).on_seam,
            vec![true, false, false, true, false, false]
        );
        let untextured = Model {
            texcoords: None,
            ..m
        };
        let none = find(&untextured);
        assert!(none.on_seam.iter().all(|&s| !s));
        assert!(none.twin.iter().all(|&t| t == u32::MAX));
    }

    #[test]
    fn pinned_vertices_at_one_point_are_copies_of_each_other() {
        // A junction's three copies (0, 3, 6), a lone pinned vertex (8), twins (1, 4).
        let positions = [
            [0, 0],
            [1, 0],
            [0, 1],
            [0, 0],
            [1, 0],
            [0, -1],
            [0, 0],
            [1, -1],
        ]
        .into_iter()
        .map(|[x, y]| Vec3::new(x as f32, y as f32, 0.0))
        .chain([Vec3::ONE])
        .collect::<Vec<_>>();
        let pinned: Vec<bool> = (0..9).map(|v| [0, 3, 6, 8].contains(&v)).collect();
        let cycles = copy_cycles(&positions, &pinned);
        let mut twins = vec![u32::MAX; 9];
        (twins[1], twins[4]) = (4, 1);
        let of = |v: u32| copies(v, &twins, &cycles).collect::<Vec<_>>();
        let mut junction = of(3);
        assert_eq!(junction[0], 3, "itself first");
        junction.sort_unstable();
        assert_eq!(junction, [0, 3, 6]);
        assert_eq!(of(8), [8], "alone at its point");
        assert_eq!(of(4), [4, 1], "a twin");
        assert_eq!(of(2), [2], "neither");
        assert!(copy_cycles(&positions, &[false; 9]).is_empty());
    }

    #[test]
    fn a_junction_faces_the_way_all_its_copies_triangles_do() {
        // A pyramid's apex split in two copies (0, 4), each in two of its four faces, over
        // the square 1, 2, 3, 5; a lone pinned vertex (6) has no copy.
        let positions = vec![
            Vec3::Z,
            Vec3::X,
            Vec3::Y,
            Vec3::NEG_X,
            Vec3::Z,
            Vec3::NEG_Y,
            Vec3::ONE,
        ];
        let triangles = [[0, 1, 2], [0, 2, 3], [4, 3, 5], [4, 5, 1]];
        let pinned = [true, false, false, false, true, false, true];
        let cycles = copy_cycles(&positions, &pinned);
        let normals = junction_normals(&positions, &triangles, &cycles);
        for v in [0, 4] {
            assert!((normals[v] - Vec3::Z).length() < 1e-6, "{:?}", normals[v]);
        }
        assert!([1, 2, 3, 5, 6].iter().all(|&v| normals[v] == Vec3::ZERO));
        assert!(junction_normals(&positions, &triangles, &[]).is_empty());
    }

    #[test]
    fn twins_are_the_two_sides_of_a_seam_and_junctions_have_none() {
        let m = Model {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::ZERO, // 0's other side
                Vec3::X,    // 1 again, and again below: a junction of three
                Vec3::X,
                Vec3::NEG_Y,
            ],
            triangles: vec![[0, 1, 2], [3, 4, 6], [5, 6, 3]],
            texcoords: Some(vec![[0.0; 2]; 7]),
            ..Model::default()
        };
        // Position 0 holds two vertices (0, 3): twins; X holds three (1, 4, 5): a junction.
        let found = find(&m);
        let twins = &found.twin;
        assert_eq!(
            found.on_seam,
            vec![true, true, false, true, true, true, false]
        );
        assert_eq!(twins[0], 3);
        assert_eq!(twins[3], 0);
        assert!(
            [1, 2, 4, 5, 6].iter().all(|&v| twins[v] == u32::MAX),
            "{twins:?}"
        );
    }
}

//! Texture seams: where a model's texture coordinates jump, its file gives one point two or
//! more coordinate pairs, and the model holds one vertex per side, at the same position (see
//! `Model::texcoords`). The surface is cut there. Were the sides simplified on their own,
//! their outlines would part and open a crack: decimation takes a seam's two sides away
//! together (vertex removal removes both, edge collapse collapses both edges to one point),
//! and pins the junctions where three or more sides meet.

use std::collections::HashMap;

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

/// The seams of `model`; none without texture coordinates (an unwelded model's duplicates
/// are not seams).
pub fn find(model: &Model) -> Seams {
    let n = model.positions.len();
    let mut seams = Seams {
        on_seam: vec![false; n],
        twin: vec![u32::MAX; n],
    };
    if model.texcoords.is_none() {
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
        let key = [p.x, p.y, p.z].map(|x| (x + 0.0).to_bits());
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
    use glam::Vec3;

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

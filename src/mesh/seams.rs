//! Texture seams: where a model's texture coordinates jump, its file gives one point two or
//! more coordinate pairs, and the model holds one vertex per side, at the same position (see
//! `Model::texcoords`). The surface is cut there. Decimation pins these vertices: were the
//! sides simplified on their own, their outlines would part and open a crack.

use std::collections::HashMap;

use super::Model;

/// One flag per vertex: true for a vertex that a triangle uses and whose exact position
/// another used vertex shares, when the model has texture coordinates (all false without
/// them: an unwelded model's duplicates are not seams).
pub fn seam_vertices(model: &Model) -> Vec<bool> {
    let n = model.positions.len();
    let mut seam = vec![false; n];
    if model.texcoords.is_none() {
        return seam;
    }
    let mut used = vec![false; n];
    for t in &model.triangles {
        for &v in t {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    }
    // Position (bits, -0 folded into +0) -> first used vertex there.
    let mut first: HashMap<[u32; 3], u32> = HashMap::new();
    for (v, p) in model.positions.iter().enumerate() {
        if !used[v] {
            continue;
        }
        let key = [p.x, p.y, p.z].map(|x| (x + 0.0).to_bits());
        match first.get(&key) {
            Some(&w) => {
                seam[v] = true;
                seam[w as usize] = true;
            }
            None => {
                first.insert(key, v as u32);
            }
        }
    }
    seam
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
            seam_vertices(&m),
            vec![true, false, false, true, false, false]
        );
        let untextured = Model {
            texcoords: None,
            ..m
        };
        assert!(seam_vertices(&untextured).iter().all(|&s| !s));
    }
}

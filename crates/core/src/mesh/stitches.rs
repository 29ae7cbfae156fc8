//! Borders that models of one scene share: a CAD part split by colour, an OBJ split by
//! material, a scan delivered in tiles. Each model is decimated on its own, so were a shared
//! border simplified from both sides, each side would take its own shortcuts and the seam
//! between them would open into a crack. Decimation pins the vertices found here, as it pins
//! texture seams (`mesh::seams`).
//!
//! A vertex is on a shared border when it lies on a boundary edge of its model (an edge one
//! triangle uses) and a boundary vertex of another model has exactly the same world position
//! (the model's transform applied, `-0` taken as `0`). Exact equality is what exporters give
//! when they cut one mesh in parts; parts merely close to each other are not stitched.
//!
//! With `--keep-border` the whole open border of every model is pinned
//! ([`open_border_vertices`]): pieces of one mesh decimated in separate runs (tiles of a
//! terrain, chunks of a scan) then still fit together.

use std::collections::hash_map::Entry;
use std::collections::HashMap;

use rayon::prelude::*;

use super::{Model, Scene};

/// One flag per vertex of each model of `scene` (indexed like `Model::positions`): true for
/// a vertex on a border the model shares with another model. All false in a one-model scene.
pub fn shared_border_vertices(scene: &Scene) -> Vec<Vec<bool>> {
    let mut shared: Vec<Vec<bool>> = scene
        .models
        .iter()
        .map(|m| vec![false; m.positions.len()])
        .collect();
    if scene.models.len() < 2 {
        return shared;
    }
    let borders: Vec<Vec<u32>> = scene.models.par_iter().map(border_vertices).collect();
    // World position -> the one model whose border has it, or `SHARED` once a second has.
    const SHARED: usize = usize::MAX;
    let mut owner: HashMap<[u32; 3], usize> = HashMap::new();
    for (i, (model, border)) in scene.models.iter().zip(&borders).enumerate() {
        for &v in border {
            match owner.entry(world_key(model, v)) {
                Entry::Vacant(e) => {
                    e.insert(i);
                }
                Entry::Occupied(mut e) => {
                    if *e.get() != i {
                        e.insert(SHARED);
                    }
                }
            }
        }
    }
    for ((model, border), flags) in scene.models.iter().zip(&borders).zip(&mut shared) {
        for &v in border {
            if owner.get(&world_key(model, v)) == Some(&SHARED) {
                flags[v as usize] = true;
            }
        }
    }
    shared
}

/// One flag per vertex of `model` (indexed like its positions): true for a vertex on its
/// open border, the edges that one triangle uses once vertices at the same position are
/// taken as one. The two sides of a texture seam, or a normal's crease, split in the file
/// but closed on screen, are not a border; an outline is.
pub fn open_border_vertices(model: &Model) -> Vec<bool> {
    // Each vertex's point: the first vertex at its position.
    let mut first: HashMap<[u32; 3], u32> = HashMap::with_capacity(model.positions.len());
    let point: Vec<u32> = (0..model.positions.len() as u32)
        .map(|v| {
            let key = super::seams::position_key(model.positions[v as usize]);
            *first.entry(key).or_insert(v)
        })
        .collect();
    let on_border = border_flags(model, &point);
    point.iter().map(|&p| on_border[p as usize]).collect()
}

/// The vertices of `model`'s boundary edges (edges that one triangle uses), each once.
fn border_vertices(model: &Model) -> Vec<u32> {
    let identity: Vec<u32> = (0..model.positions.len() as u32).collect();
    let on_border = border_flags(model, &identity);
    (0..on_border.len() as u32)
        .filter(|&v| on_border[v as usize])
        .collect()
}

/// One flag per vertex: true for an end of an edge that one triangle uses, vertices taken
/// as their `point` (a vertex id each, indexed like the positions).
fn border_flags(model: &Model, point: &[u32]) -> Vec<bool> {
    let n = point.len();
    let mut edges: Vec<u64> = model
        .triangles
        .iter()
        .filter_map(|t| {
            let [a, b, c] = t.map(|v| point.get(v as usize).copied());
            Some([a?, b?, c?])
        })
        .flat_map(|[a, b, c]| [(a, b), (b, c), (c, a)])
        .filter(|(a, b)| a != b)
        .map(|(a, b)| u64::from(a.min(b)) << 32 | u64::from(a.max(b)))
        .collect();
    edges.par_sort_unstable();
    let mut on_border = vec![false; n];
    for run in edges.chunk_by(|a, b| a == b) {
        if let [edge] = run {
            on_border[(edge >> 32) as usize] = true;
            on_border[*edge as u32 as usize] = true;
        }
    }
    on_border
}

/// The bits of vertex `v`'s world position, `-0` folded into `0`.
fn world_key(model: &Model, v: u32) -> [u32; 3] {
    super::seams::position_key(
        model
            .transform
            .transform_point3(model.positions[v as usize]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Mat4, Vec3};

    /// A unit square in the z = 0 plane from `x0` to `x0 + 1`, as two triangles.
    fn square(x0: f32) -> Model {
        Model {
            positions: vec![
                Vec3::new(x0, 0.0, 0.0),
                Vec3::new(x0 + 1.0, 0.0, 0.0),
                Vec3::new(x0 + 1.0, 1.0, 0.0),
                Vec3::new(x0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..Model::default()
        }
    }

    #[test]
    fn two_squares_side_by_side_share_their_common_edge_only() {
        let scene = Scene {
            models: vec![square(0.0), square(1.0), square(5.0)],
        };
        let shared = shared_border_vertices(&scene);
        // x = 1 is the first square's right edge (vertices 1, 2) and the second's left (0, 3).
        assert_eq!(shared[0], vec![false, true, true, false]);
        assert_eq!(shared[1], vec![true, false, false, true]);
        assert_eq!(shared[2], vec![false; 4]);
    }

    #[test]
    fn the_open_border_is_the_outline_not_a_seam_split_in_the_file() {
        // A 2 × 1 strip of unit squares whose middle column (x = 1) is split in the file,
        // as a texture seam is: 1 and 2 at x = 1 for the left square, 4 and 5 for the right.
        let strip = Model {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(2.0, 1.0, 0.0),
                Vec3::new(0.5, 0.5, 7.0), // unused
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3], [4, 6, 7], [4, 7, 5]],
            ..Model::default()
        };
        // Every used vertex is on the outline of the strip: the seam's copies are too (at
        // its ends), and a vertex inside would not be.
        let expected = [true, true, true, true, true, true, true, true, false];
        assert_eq!(open_border_vertices(&strip), expected);
        // Index by index, the seam is a border too (each side's edge has one triangle):
        // the shared-border search (between models) keeps that view.
        assert_eq!(border_vertices(&strip), vec![0, 1, 2, 3, 4, 5, 6, 7]);
        // A 3 × 3 grid's middle point is inside; welded, its split copies are too.
        let mut grid = Model::default();
        for y in 0..3 {
            for x in 0..3 {
                grid.positions.push(Vec3::new(x as f32, y as f32, 0.0));
            }
        }
        grid.positions.push(Vec3::new(1.0, 1.0, 0.0)); // 9: a copy of 4
        for (y, x) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            let a = 3 * y + x;
            let centre_copy = |v: u32| if v == 4 && x == 1 { 9 } else { v };
            grid.triangles.push([a, a + 1, a + 4].map(centre_copy));
            grid.triangles.push([a, a + 4, a + 3].map(centre_copy));
        }
        let flags = open_border_vertices(&grid);
        assert!(
            !flags[4] && !flags[9],
            "the middle point and its copy are inside"
        );
        assert_eq!(
            flags.iter().filter(|&&f| f).count(),
            8,
            "the outline's 8 points"
        );
    }

    #[test]
    fn transforms_are_applied_and_one_model_shares_nothing() {
        let mut moved = square(0.0);
        moved.transform = Mat4::from_translation(Vec3::new(1.0, 0.0, 0.0));
        let scene = Scene {
            models: vec![square(0.0), moved],
        };
        let shared = shared_border_vertices(&scene);
        assert_eq!(shared[0], vec![false, true, true, false]);
        assert_eq!(shared[1], vec![true, false, false, true]);
        let alone = Scene {
            models: vec![square(0.0)],
        };
        assert_eq!(shared_border_vertices(&alone), vec![vec![false; 4]]);
    }

    #[test]
    fn interior_vertices_are_not_borders() {
        // A closed tetrahedron touching a square's corner: no boundary, nothing shared.
        let tetra = Model {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
            ..Model::default()
        };
        let scene = Scene {
            models: vec![tetra, square(0.0)],
        };
        let shared = shared_border_vertices(&scene);
        assert!(shared.iter().flatten().all(|&s| !s));
    }
}

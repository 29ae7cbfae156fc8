//! Folded triangles (`metro --folds`, docs/design.md#folds): an output triangle whose normal
//! turns more than 90° from the input it stands for is counted exactly once, sound
//! decimations by both algorithms count none, and a thin sheet whose sides came close counts
//! none either.

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::mesh::{shapes, Model, Scene};
use decimate_core::metro::folds::{self, Folds};
use decimate_core::metro::{compare, Options, Surface};
use glam::DVec3;

use crate::support::rng::Rng;
use crate::support::shapes::Grid;

/// An `n`×`n` grid of unit cells in the plane z = `z`, facing +z (or -z when `down`).
fn sheet(n: u32, z: f64, down: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let grid = Grid::square(n as usize);
    let p = (grid.points())
        .map(|(i, j)| DVec3::new(i as f64, j as f64, z))
        .collect();
    let t = (grid.triangles())
        .map(|t| t.map(|v| v as u32))
        .map(|tri| if down { [tri[0], tri[2], tri[1]] } else { tri })
        .collect();
    (p, t)
}

fn folds_with(input: &Surface, output: &Surface, reach: f64) -> Folds {
    let options = Options {
        samples: Some(20_000),
        folds: true,
        fold_reach: reach,
        ..Options::default()
    };
    compare(input, output, &options)
        .expect("both have triangles")
        .folds
        .expect("folds were asked for")
}

fn folds_of(input: &Surface, output: &Surface) -> Folds {
    folds_with(input, output, folds::DEFAULT_REACH)
}

#[test]
fn one_reversed_triangle_of_a_plane_is_one_fold() {
    let (p, t) = sheet(10, 0.0, false);
    let input = Surface::new(&p, &t);
    assert_eq!(folds_of(&input, &input).triangles, 0);
    let mut flipped = t.clone();
    flipped[37].swap(1, 2);
    let f = folds_of(&input, &Surface::new(&p, &flipped));
    assert_eq!(f.triangles, 1);
    assert_eq!(f.degenerate, 0);
    assert_eq!(f.checked, 200);
    assert!((f.area_fraction - 1.0 / 200.0).abs() < 1e-12, "{f:?}");
    let centroid = flipped[37].iter().map(|&v| p[v as usize]).sum::<DVec3>() / 3.0;
    assert_eq!(f.largest_at, Some(centroid));
}

#[test]
fn moved_vertices_fold_exactly_the_triangles_turned_over() {
    // Inner vertices of a plane pushed around within it: the triangles whose normal now
    // points down, and only those, are folded (counted independently from the winding).
    let (p, t) = sheet(12, 0.0, false);
    let input = Surface::new(&p, &t);
    let mut rng = Rng(7);
    let mut moved = p.clone();
    for (k, q) in moved.iter_mut().enumerate() {
        let (i, j) = (k % 13, k / 13);
        if i > 0 && j > 0 && i < 12 && j < 12 {
            q.x += 1.2 * f64::from(rng.signed());
            q.y += 1.2 * f64::from(rng.signed());
        }
    }
    let down = t
        .iter()
        .filter(|tri| {
            let [a, b, c] = tri.map(|v| moved[v as usize]);
            (b - a).cross(c - a).z < 0.0
        })
        .count();
    assert!(down > 5, "the shuffle turns some triangles over: {down}");
    let f = folds_of(&input, &Surface::new(&moved, &t));
    assert_eq!(f.triangles, down);
    assert_eq!(f.degenerate, 0);
}

fn decimated(model: &Model, algorithm: Algorithm, triangles: usize) -> Model {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target: Target::KeepTriangles(triangles),
        algorithm,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

fn surface(m: &Model) -> Surface {
    Surface::from_scene(&Scene {
        models: vec![m.clone()],
    })
}

#[test]
fn closed_shapes_decimated_by_both_algorithms_have_no_folds() {
    let cube = shapes::cube(12, 2.0);
    let sphere = shapes::bumpy_sphere(40, 80);
    for (model, keep) in [(&cube, 96), (&sphere, 600)] {
        let input = surface(model);
        for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
            let out = decimated(model, algorithm, keep);
            assert_eq!(out.triangles.len(), keep, "{} {algorithm:?}", model.name);
            let output = surface(&out);
            assert!(output.is_closed(), "{} {algorithm:?}", model.name);
            let f = folds_of(&input, &output);
            assert_eq!(
                (f.triangles, f.degenerate, f.checked),
                (0, 0, keep),
                "{} {algorithm:?}",
                model.name
            );
            // The same output turned inside out: every triangle folds.
            let inside_out: Vec<[u32; 3]> = output
                .triangles
                .iter()
                .map(|t| [t[0], t[2], t[1]])
                .collect();
            let f = folds_of(&input, &Surface::new(&output.positions, &inside_out));
            assert_eq!(f.triangles, keep, "{} {algorithm:?}", model.name);
            assert!((f.area_fraction - 1.0).abs() < 1e-9);
        }
    }
}

/// A sheet folded on itself: the unit square at z = 0 facing down and at z = `gap` facing up,
/// each cut into 40×40 cells (a flattened hairpin, as a fin or an ear of a scan is).
fn hairpin(gap: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mut p, mut t) = sheet(40, 0.0, true);
    let (q, u) = sheet(40, gap, false);
    let offset = p.len() as u32;
    p.extend(q);
    t.extend(u.iter().map(|tri| tri.map(|v| v + offset)));
    let p = p
        .into_iter()
        .map(|v| DVec3::new(v.x / 40.0, v.y / 40.0, v.z))
        .collect();
    (p, t)
}

/// `positions` with every vertex above z = 0 moved to height `z`.
fn top_at(positions: &[DVec3], z: f64) -> Vec<DVec3> {
    positions
        .iter()
        .map(|&v| {
            if v.z > 0.0 {
                DVec3::new(v.x, v.y, z)
            } else {
                v
            }
        })
        .collect()
}

#[test]
fn a_thin_sheet_whose_sides_came_close_is_not_folded() {
    let (p, mut t) = hairpin(0.2);
    let input = Surface::new(&p, &t);
    // The output's top side lowered past the middle of the gap, to 0.08: its samples are
    // nearer the bottom side (which faces the other way) than the top (0.12 away), and the
    // top, within twice the nearest distance, backs them.
    let output = Surface::new(&top_at(&p, 0.08), &t);
    assert_eq!(folds_of(&input, &output).triangles, 0);
    // The nearest input triangles alone (reach 0) would call the whole lowered top folded.
    assert_eq!(folds_with(&input, &output, 0.0).triangles, 3200);
    // A triangle of the top side really turned over is one fold, though the bottom side,
    // facing like it, is only the gap away.
    assert!(t[5000].iter().all(|&v| p[v as usize].z > 0.0));
    t[5000].swap(1, 2);
    let f = folds_of(&input, &Surface::new(&p, &t));
    assert_eq!(f.triangles, 1);
}

#[test]
fn two_sides_closer_than_their_triangles_are_one_sheet() {
    // A double-layered scan: the sides 1/1000 of a cell apart. The output's top lies below
    // both, nearest the bottom side and three times as far from its own: backed still, as
    // the sides are closer than the input's triangles are long.
    let gap = 0.025e-3;
    let (p, t) = hairpin(gap);
    let input = Surface::new(&p, &t);
    let below = Surface::new(&top_at(&p, -0.5 * gap), &t);
    let f = folds_of(&input, &below);
    assert_eq!(
        (f.triangles, f.degenerate, f.checked),
        (0, 0, 6400),
        "{f:?}"
    );
}

#[test]
fn zero_area_triangles_are_degenerate_not_folded() {
    let (p, mut t) = sheet(4, 0.0, false);
    let input = Surface::new(&p, &t);
    // Three corners on one grid line, and one repeated corner.
    t.push([0, 1, 2]);
    t.push([5, 5, 6]);
    let f = folds_of(&input, &Surface::new(&p, &t));
    assert_eq!((f.triangles, f.degenerate, f.checked), (0, 2, 32));
}

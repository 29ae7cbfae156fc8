//! `qem` on open surfaces: a head-like cap (a scan's open border, curved in space) kept at
//! 1 % stays close to the original and its outline stays on the original's; a plane with a
//! hole keeps the hole where it was and its area (docs/design.md#qem-constraint-weight,
//! docs/design.md#qem-border-placement); either algorithm asked for fewer triangles than a
//! surface can keep stops at four vertices.

use crate::support::metro::compare_models;
use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::mesh::{measure, shapes, Model, Scene};
use glam::Vec3;

fn qem(model: &Model, target: Target) -> Model {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target,
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().expect("the model is kept")
}

/// An `n × n` grid of vertices over `[-1, 1]²` (`keep` picks the cells kept), each cell cut
/// along its diagonal, lifted by `at(x, y)`.
fn grid(n: u32, at: impl Fn(f32, f32) -> Vec3, keep: impl Fn(u32, u32) -> bool) -> Model {
    let step = 2.0 / (n - 1) as f32;
    let positions = (0..n * n)
        .map(|v| at(-1.0 + step * (v / n) as f32, -1.0 + step * (v % n) as f32))
        .collect();
    let triangles = (0..n - 1)
        .flat_map(|i| (0..n - 1).map(move |j| (i, j)))
        .filter(|&(i, j)| keep(i, j))
        .flat_map(|(i, j)| {
            let (a, b) = (i * n + j, (i + 1) * n + j);
            [[a, b, b + 1], [a, b + 1, a + 1]]
        })
        .collect();
    Model {
        name: "grid".into(),
        positions,
        triangles,
        ..Model::default()
    }
}

/// A head-like cap of 40 × 40 vertices (3,042 triangles): a sphere's patch seen from its
/// centre over a wide angle, with a nose and a ripple, its open border curved in space.
fn cap() -> Model {
    grid(
        40,
        |x, y| {
            let (u, v) = (2.5 * x, 2.5 * y);
            let nose = 0.25 * (-u * u / 0.02 - (v - 0.1).powi(2) / 0.1).exp();
            let r = 1.0 + nose + 0.05 * (5.0 * u).sin() * (4.0 * v).cos();
            r * Vec3::new(u, v, 1.0).normalize()
        },
        |_, _| true,
    )
}

/// The edges of one triangle (the open border).
fn outline(m: &Model) -> Vec<[u32; 2]> {
    let counts = measure::edge_counts(m);
    let mut uses = std::collections::HashMap::new();
    for t in &m.triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let edges: Vec<[u32; 2]> = uses
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|((a, b), _)| [a, b])
        .collect();
    assert_eq!(edges.len(), counts.boundary, "{}", m.name);
    edges
}

/// The distance from `p` to the nearest of `m`'s edges `edges`.
fn distance_to(p: Vec3, m: &Model, edges: &[[u32; 2]]) -> f32 {
    edges
        .iter()
        .map(|&[a, b]| {
            let (a, b) = (m.positions[a as usize], m.positions[b as usize]);
            let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            (a + t * (b - a)).distance(p)
        })
        .fold(f32::INFINITY, f32::min)
}

/// Symmetric mean distance between two models by metro, as a fraction of `a`'s diagonal.
fn mean_error(a: &Model, b: &Model) -> f64 {
    let c = compare_models(a, b);
    c.relative(c.symmetric().mean)
}

#[test]
fn a_head_like_cap_at_one_percent_stays_close_and_keeps_its_outline() {
    let before = cap();
    assert_eq!(before.triangles.len(), 3042);
    // Exactly: an inner collapse takes two triangles, so from 31 left only a border edge's
    // (one) lands on the count; without that rule this cap gave 29.
    for keep in [31, 61, 304] {
        let kept = qem(&before, Target::KeepTriangles(keep)).triangles.len();
        assert_eq!(kept, keep, "{kept} triangles for {keep} asked");
    }
    let after = qem(&before, Target::KeepTriangles(30));
    assert_eq!(after.triangles.len(), 30);
    let broken = measure::invariant_violations(&before, &after);
    assert!(broken.is_empty(), "{broken:?}");
    // A bound the outline held harder (constraint weight 100, its vertices unmoved when
    // they take in an interior neighbour) does not meet (experiments.md#qem-open-borders).
    let mean = mean_error(&before, &after);
    assert!(
        mean < 0.008,
        "mean error {:.3} % of the diagonal",
        100.0 * mean
    );
    // Every outline vertex stays near the original outline: within 3 % of the diagonal (a
    // weighted constraint, not an exact one: with 30 triangles left, the outline's corners
    // are cut, as vtkQuadricDecimation cuts them on the heads).
    let (old, new) = (outline(&before), outline(&after));
    let diagonal = before.bounds().map_or(0.0, |(lo, hi)| (hi - lo).length());
    for v in new.iter().flatten() {
        let p = after.positions[*v as usize];
        let d = distance_to(p, &before, &old);
        assert!(
            d < 0.03 * diagonal,
            "outline vertex at {p} is {d} off the outline"
        );
    }
}

#[test]
fn a_plane_with_a_hole_keeps_its_hole_where_it_was() {
    // 31 × 31 vertices over [-1, 1]² in z = 0, the middle 10 × 10 cells left out: a square
    // hole from -1/3 to 1/3.
    let before = grid(
        31,
        |x, y| Vec3::new(x, y, 0.0),
        |i, j| !((10..20).contains(&i) && (10..20).contains(&j)),
    );
    assert_eq!(before.triangles.len(), 2 * (30 * 30 - 100));
    let after = qem(&before, Target::RemovePercent(90.0));
    let broken = measure::invariant_violations(&before, &after);
    assert!(broken.is_empty(), "{broken:?}");
    assert_eq!(
        measure::boundary_loops(&after),
        2,
        "the outline and the hole"
    );
    let area = measure::area(&after);
    assert!((area - (4.0 - 4.0 / 9.0)).abs() < 1e-4, "area {area}");
    // Every outline vertex is on the square or on the hole, exactly where it was (the plane
    // is flat: the constraint planes hold it without error), and the hole's four corners stay.
    for v in outline(&after).iter().flatten() {
        let p = after.positions[*v as usize];
        let m = p.x.abs().max(p.y.abs());
        let on = (m - 1.0).abs() < 1e-5 || (m - 1.0 / 3.0).abs() < 1e-5;
        assert!(on, "outline vertex at {p} left the outlines");
        assert!(p.z.abs() < 1e-6, "outline vertex at {p} left the plane");
    }
    for corner in [[-1.0, -1.0], [-1.0, 1.0], [1.0, -1.0], [1.0, 1.0]] {
        let corner = Vec3::new(corner[0], corner[1], 0.0) / 3.0;
        let found = after.positions.iter().any(|p| p.distance(corner) < 1e-5);
        assert!(found, "the hole's corner {corner} moved");
    }
}

/// Asked for fewer triangles than a surface can keep, either algorithm stops at four
/// vertices, says the model is fully decimated (when short of the count) and keeps it: a model under four vertices
/// is dropped from the scene (the original program's rule), which no count asked for
/// should cause. A flat sheet and a triangle split at an inner point, asked for 1 and 2.
#[test]
fn a_surface_asked_for_one_triangle_keeps_four_vertices_with_either_algorithm() {
    let sheet = shapes::height_grid(4, |_, _| 0.0);
    let split_triangle = Model {
        name: "split triangle".into(),
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.3, 0.3, 0.0)],
        triangles: vec![[0, 1, 3], [1, 2, 3], [2, 0, 3]],
        ..Model::default()
    };
    let mut checked = 0;
    for (model, left) in [(&sheet, 2), (&split_triangle, 3)] {
        for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
            for keep in [1, 2] {
                let mut scene = Scene {
                    models: vec![model.clone()],
                };
                let params = Params {
                    target: Target::KeepTriangles(keep),
                    algorithm,
                    ..Params::default()
                };
                let report = simplify_scene(&mut scene, &params, &mut |_| {});
                let what = format!("{} by {algorithm:?} asked for {keep}", model.name);
                let r = &report.models[0];
                // "Fully decimated" only where the count was not reached.
                assert!(!r.dropped, "{what}: {r:?}");
                assert_eq!(r.fully_decimated, left > keep, "{what}: {r:?}");
                let after = scene
                    .models
                    .first()
                    .unwrap_or_else(|| panic!("{what}: dropped"));
                let counts = (after.positions.len(), after.triangles.len());
                assert_eq!(counts, (4, left), "{what}");
                assert_eq!(measure::degenerate_triangles(after, 1e-9), 0, "{what}");
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 8);
}

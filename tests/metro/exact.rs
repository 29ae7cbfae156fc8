//! Metro (Cignoni, Rocchini, Scopigno 1998) against answers known in closed form: parallel
//! planes, a sphere against its inscribed icosahedron, identical and shifted meshes, areas and
//! volumes of a cube, an icosahedron and a geodesic sphere, and determinism of the sampling.

use std::collections::HashMap;

use crate::support::shapes::Grid;
use decimate_core::mesh::{Model, Scene};
use decimate_core::metro::bvh::closest_point_on_triangle;
use decimate_core::metro::{compare, Comparison, Options, Surface};
use glam::{DVec3, Mat4, Vec3};

/// A `w`×`h` rectangle in the plane through `origin` spanned by `u` and `v`, cut into
/// `nu`×`nv` cells of two triangles each, facing `u × v`.
fn grid(origin: DVec3, u: DVec3, v: DVec3, nu: u32, nv: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let grid = Grid {
        nu: nu as usize,
        nv: nv as usize,
    };
    let p = (grid.points())
        .map(|(i, j)| origin + u * (i as f64 / f64::from(nu)) + v * (j as f64 / f64::from(nv)))
        .collect();
    let t = grid.triangles().map(|t| t.map(|v| v as u32)).collect();
    (p, t)
}

/// The regular icosahedron inscribed in the unit sphere, faces outward.
fn icosahedron() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let mut p = Vec::new();
    for s1 in [-1.0, 1.0] {
        for s2 in [-1.0, 1.0] {
            p.push(DVec3::new(0.0, s1, s2 * phi));
            p.push(DVec3::new(s1, s2 * phi, 0.0));
            p.push(DVec3::new(s2 * phi, 0.0, s1));
        }
    }
    let p: Vec<DVec3> = p.into_iter().map(DVec3::normalize).collect();
    let edge = p
        .iter()
        .skip(1)
        .map(|q| q.distance(p[0]))
        .fold(f64::INFINITY, f64::min);
    let close = |a: usize, b: usize| (p[a].distance(p[b]) - edge).abs() < 1e-9;
    let mut t = Vec::new();
    for a in 0..12 {
        for b in a + 1..12 {
            for c in b + 1..12 {
                if close(a, b) && close(b, c) && close(a, c) {
                    let n = (p[b] - p[a]).cross(p[c] - p[a]);
                    let f = if n.dot(p[a]) > 0.0 {
                        [a, b, c]
                    } else {
                        [a, c, b]
                    };
                    t.push(f.map(|x| x as u32));
                }
            }
        }
    }
    assert_eq!(t.len(), 20);
    (p, t)
}

/// Class I geodesic sphere: each icosahedron face cut into `n`² triangles by a barycentric
/// grid, every grid point pushed onto the unit sphere. A point is computed once from its
/// integer weights over the icosahedron's vertex ids, so faces sharing it agree to the bit.
fn geodesic(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (ico, faces) = icosahedron();
    let mut p = Vec::new();
    let mut ids: HashMap<Vec<(u32, u32)>, u32> = HashMap::new();
    let mut id = |weights: [(u32, u32); 3]| -> u32 {
        let mut key: Vec<(u32, u32)> = weights.into_iter().filter(|w| w.1 > 0).collect();
        key.sort_unstable();
        *ids.entry(key.clone()).or_insert_with(|| {
            let s = key
                .iter()
                .fold(DVec3::ZERO, |s, &(v, w)| s + ico[v as usize] * f64::from(w));
            p.push(s.normalize());
            (p.len() - 1) as u32
        })
    };
    let mut t = Vec::new();
    for &[a, b, c] in &faces {
        let at = |i: u32, j: u32| [(a, n - i - j), (b, i), (c, j)];
        let mut idx = HashMap::new();
        for i in 0..=n {
            for j in 0..=n - i {
                idx.insert((i, j), id(at(i, j)));
            }
        }
        for i in 0..n {
            for j in 0..n - i {
                t.push([idx[&(i, j)], idx[&(i + 1, j)], idx[&(i, j + 1)]]);
                if i + j + 1 < n {
                    t.push([idx[&(i + 1, j)], idx[&(i + 1, j + 1)], idx[&(i, j + 1)]]);
                }
            }
        }
    }
    (p, t)
}

/// A closed axis-aligned cube of side `s` at the origin, `n` segments per edge, faces outward.
fn cube(s: f64, n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    let mut t = Vec::new();
    let x = DVec3::X * s;
    let y = DVec3::Y * s;
    let z = DVec3::Z * s;
    let o = DVec3::ZERO;
    // (origin, u, v) with u × v pointing out of the cube.
    for (origin, u, v) in [
        (o, y, x),
        (o + z, x, y),
        (o, x, z),
        (o + y, z, x),
        (o, z, y),
        (o + x, y, z),
    ] {
        let (gp, gt) = grid(origin, u, v, n, n);
        let base = p.len() as u32;
        p.extend(gp);
        t.extend(gt.into_iter().map(|f| f.map(|i| i + base)));
    }
    (p, t)
}

fn surface((p, t): (Vec<DVec3>, Vec<[u32; 3]>)) -> Surface {
    Surface::new(&p, &t)
}

fn shifted((p, t): (Vec<DVec3>, Vec<[u32; 3]>), v: DVec3) -> Surface {
    let p: Vec<DVec3> = p.into_iter().map(|q| q + v).collect();
    Surface::new(&p, &t)
}

fn measure(a: &Surface, b: &Surface, samples: usize, seed: u64) -> Comparison {
    let options = Options {
        samples: Some(samples),
        seed,
        ..Options::default()
    };
    compare(a, b, &options).unwrap()
}

fn close(actual: f64, expected: f64, relative: f64) -> bool {
    (actual - expected).abs() <= relative * expected.abs()
}

/// Inradius of the regular icosahedron of circumradius 1: sqrt((5 + 2√5) / 15).
fn icosahedron_inradius() -> f64 {
    ((5.0 + 2.0 * 5f64.sqrt()) / 15.0).sqrt()
}

#[test]
fn parallel_planes_are_their_distance_apart_everywhere() {
    let d = 0.25;
    // Different triangulations of the same unit square, one lifted by d.
    let a = surface(grid(DVec3::ZERO, DVec3::X, DVec3::Y, 10, 10));
    let b = surface(grid(DVec3::Z * d, DVec3::X, DVec3::Y, 7, 13));
    let c = measure(&a, &b, 50_000, 3);
    for dir in [c.a_to_b, c.b_to_a] {
        assert!(close(dir.max, d, 1e-5), "max {}", dir.max);
        assert!(close(dir.mean, d, 1e-5), "mean {}", dir.mean);
        assert!(close(dir.rms, d, 1e-5), "rms {}", dir.rms);
    }
    assert!(close(c.hausdorff(), d, 1e-5));
    assert!(close(c.relative(d), d / 2f64.sqrt(), 1e-12));
    assert_eq!(c.a_to_b.face_samples, 50_000);
    assert_eq!(c.a_to_b.edge_samples, 5_000);
    assert_eq!(c.a_to_b.vertex_samples, 121);
}

#[test]
fn tilted_plane_shifted_along_its_normal_is_exactly_the_shift_away() {
    let u = DVec3::new(1.0, 0.5, 0.25);
    let v = DVec3::new(-0.2, 1.0, 0.7);
    let n = u.cross(v).normalize();
    let shift = n * 0.03;
    let mesh = grid(DVec3::new(0.3, -0.2, 0.1), u, v, 12, 9);
    let a = surface(mesh.clone());
    let b = shifted(mesh, shift);
    let c = measure(&a, &b, 20_000, 11);
    let s = shift.length();
    for dir in [c.a_to_b, c.b_to_a] {
        assert!(close(dir.max, s, 1e-9), "max {} vs {s}", dir.max);
        assert!(close(dir.mean, s, 1e-9), "mean {} vs {s}", dir.mean);
    }
}

#[test]
fn sphere_against_inscribed_icosahedron_peaks_over_face_centres() {
    // n divisible by 3 puts a vertex of A exactly over each face centre of B.
    let a = surface(geodesic(30));
    let b = surface(icosahedron());
    let c = measure(&a, &b, 200_000, 5);
    let expected = 1.0 - icosahedron_inradius(); // 0.2053…
    assert!(
        (c.a_to_b.max - expected).abs() < 1e-12,
        "A->B max {} vs {expected}",
        c.a_to_b.max
    );
    // B lies inside A, whose faces are at least `1 - sag` from the centre: B's face centres
    // (the farthest points of B from the sphere) are within [1 - r - sag, 1 - r] of A.
    let sag = 1.0
        - a.triangles
            .iter()
            .map(|t| {
                let [p, q, r] = t.map(|i| a.positions[i as usize]);
                (q - p).cross(r - p).normalize().dot(p)
            })
            .fold(f64::INFINITY, f64::min);
    assert!(sag > 0.0 && sag < 1e-3, "sag {sag}");
    assert!(
        c.b_to_a.max <= expected + 1e-12,
        "B->A max {}",
        c.b_to_a.max
    );
    assert!(
        c.b_to_a.max >= expected - sag - 1e-4,
        "B->A max {} below {}",
        c.b_to_a.max,
        expected - sag
    );
    assert_eq!(c.hausdorff(), c.a_to_b.max);
    // The sampled mean against an independent quadrature: each of A's triangles cut into
    // 16 sub-triangles, the distance at each sub-triangle's centroid found by brute force over
    // B's 20 faces, weighted by area.
    let (mut integral, mut area) = (0.0, 0.0);
    for t in &a.triangles {
        let [p, q, r] = t.map(|i| a.positions[i as usize]);
        let k = 4;
        for i in 0..k {
            for j in 0..k - i {
                let at = |u: f64, v: f64| p + (q - p) * (u / k as f64) + (r - p) * (v / k as f64);
                let (i, j) = (i as f64, j as f64);
                let mut subs = vec![[at(i, j), at(i + 1.0, j), at(i, j + 1.0)]];
                if i + j + 1.0 < k as f64 {
                    subs.push([at(i + 1.0, j), at(i + 1.0, j + 1.0), at(i, j + 1.0)]);
                }
                for [x, y, z] in subs {
                    let centre = (x + y + z) / 3.0;
                    let w = 0.5 * (y - x).cross(z - x).length();
                    let d = b
                        .triangles
                        .iter()
                        .map(|f| {
                            let [u, v, s] = f.map(|i| b.positions[i as usize]);
                            closest_point_on_triangle(centre, u, v, s).distance(centre)
                        })
                        .fold(f64::INFINITY, f64::min);
                    integral += w * d;
                    area += w;
                }
            }
        }
    }
    let quadrature = integral / area;
    assert!(
        close(c.a_to_b.mean, quadrature, 2e-3),
        "sampled mean {} vs quadrature {quadrature}",
        c.a_to_b.mean
    );
}

#[test]
fn identical_meshes_are_exactly_zero_apart() {
    // Far from the origin, so coordinates carry large rounding on their own.
    let offset = DVec3::new(1000.0, -2000.0, 500.0);
    for mesh in [geodesic(12), grid(DVec3::ZERO, DVec3::X, DVec3::Y, 9, 4)] {
        let a = shifted(mesh.clone(), offset);
        let b = shifted(mesh, offset);
        let c = measure(&a, &b, 30_000, 9);
        for dir in [c.a_to_b, c.b_to_a] {
            assert_eq!((dir.max, dir.mean, dir.rms), (0.0, 0.0, 0.0));
        }
        assert_eq!(c.hausdorff(), 0.0);
    }
}

#[test]
fn shifted_mesh_is_at_most_the_shift_away() {
    let v = DVec3::new(0.05, 0.02, -0.03);
    let a = surface(geodesic(15));
    let b = shifted(geodesic(15), v);
    let c = measure(&a, &b, 50_000, 2);
    let s = v.length();
    for dir in [c.a_to_b, c.b_to_a] {
        assert!(dir.max <= s * (1.0 + 1e-12), "max {} > |v| {s}", dir.max);
        assert!(dir.max > 0.5 * s, "max {}", dir.max);
        assert!(dir.mean > 0.0 && dir.mean < dir.max);
        assert!(dir.rms >= dir.mean && dir.rms <= dir.max);
    }
}

#[test]
fn cube_area_and_volume() {
    let s = 2.0;
    let cube = surface(cube(s, 2));
    // test002's shape: 26 vertices, 48 triangles once the shared edges are welded.
    assert_eq!(cube.used_vertices.len(), 26);
    assert_eq!(cube.triangles.len(), 48);
    assert!(cube.is_closed());
    assert!(close(cube.area(), 6.0 * s * s, 1e-14));
    assert!(close(cube.volume().unwrap(), s * s * s, 1e-14));

    // Turned inside out, the same solid has negative volume.
    let inverted: Vec<[u32; 3]> = cube.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect();
    let inside_out = Surface::new(&cube.positions, &inverted);
    assert!(close(inside_out.volume().unwrap(), -s * s * s, 1e-14));

    // One face missing: open, no volume, the rim of 8 edges is boundary.
    let open = Surface::new(&cube.positions, &cube.triangles[8..]);
    assert_eq!(open.volume(), None);
    assert_eq!(open.boundary_edges, 8);
}

#[test]
fn pieces_are_counted_through_shared_positions_not_indices() {
    // The cube's six faces are separate grids, one piece once their edges are welded.
    let (p, t) = cube(2.0, 3);
    assert_eq!(Surface::new(&p, &t).components, 1);
    // A second cube beside it, and a lone triangle: three pieces.
    let (mut p2, mut t2) = (p.clone(), t.clone());
    let base = p2.len() as u32;
    p2.extend(p.iter().map(|&q| q + DVec3::new(5.0, 0.0, 0.0)));
    t2.extend(t.iter().map(|f| f.map(|i| i + base)));
    let base = p2.len() as u32;
    p2.extend([
        DVec3::new(0.0, 9.0, 0.0),
        DVec3::new(1.0, 9.0, 0.0),
        DVec3::Y * 10.0,
    ]);
    t2.push([base, base + 1, base + 2]);
    assert_eq!(Surface::new(&p2, &t2).components, 3);
    // Two triangles meeting at one corner only (a bowtie) are one piece; moved apart, two.
    let bowtie = [
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(-1.0, 1.0, 0.0),
        DVec3::new(-1.0, -1.0, 0.0),
    ];
    assert_eq!(Surface::new(&bowtie, &[[0, 1, 2], [0, 4, 3]]).components, 1);
    let mut apart = bowtie.to_vec();
    apart.push(DVec3::new(-0.1, 0.0, 0.0));
    assert_eq!(Surface::new(&apart, &[[0, 1, 2], [5, 4, 3]]).components, 2);
    // Unused positions are no piece.
    assert_eq!(Surface::new(&apart, &[[0, 1, 2]]).info().components, 1);
}

#[test]
fn icosahedron_and_sphere_areas_and_volumes() {
    let ico = surface(icosahedron());
    let a = 4.0 / (10.0 + 2.0 * 5f64.sqrt()).sqrt(); // edge for circumradius 1
    assert!(close(ico.area(), 5.0 * 3f64.sqrt() * a * a, 1e-14));
    let v = 5.0 / 12.0 * (3.0 + 5f64.sqrt()) * a * a * a;
    assert!(close(ico.volume().unwrap(), v, 1e-14));

    // A geodesic sphere lies between the unit sphere and the ball of radius 1 - sag.
    let sphere = surface(geodesic(24));
    assert!(sphere.is_closed());
    let pi = std::f64::consts::PI;
    let r = 1.0 - 2e-3;
    assert!(sphere.area() < 4.0 * pi && sphere.area() > 4.0 * pi * r * r);
    let vol = sphere.volume().unwrap();
    assert!(vol < 4.0 / 3.0 * pi && vol > 4.0 / 3.0 * pi * r * r * r);
}

#[test]
fn scene_models_are_flattened_into_world_space() {
    let (p, t) = cube(1.0, 1);
    let model = Model {
        name: "cube".into(),
        transform: Mat4::from_translation(Vec3::new(5.0, 0.0, 0.0))
            * Mat4::from_scale(Vec3::splat(3.0)),
        positions: p.iter().map(|q| q.as_vec3()).collect(),
        triangles: t,
        ..Model::default()
    };
    let mut second = model.clone();
    second.transform = Mat4::IDENTITY;
    let scene = Scene {
        models: vec![model, second],
    };
    let s = Surface::from_scene(&scene);
    assert!(close(s.area(), 6.0 * 9.0 + 6.0, 1e-6));
    assert!(close(s.volume().unwrap(), 27.0 + 1.0, 1e-6));
    let (lo, hi) = s.bounds().unwrap();
    assert_eq!((lo, hi), (DVec3::ZERO, DVec3::new(8.0, 3.0, 3.0)));
}

#[test]
fn degenerate_triangles_are_skipped_not_fatal() {
    let p = [
        DVec3::ZERO,
        DVec3::X,
        DVec3::Y,
        DVec3::new(f64::NAN, 0.0, 0.0),
    ];
    let s = Surface::new(&p, &[[0, 1, 2], [0, 0, 1], [0, 1, 3], [0, 1, 9]]);
    assert_eq!(s.triangles.len(), 1);
    assert_eq!(s.skipped_triangles, 3);
}

#[test]
fn same_seed_same_numbers_whatever_the_threads() {
    let a = surface(geodesic(9));
    let b = shifted(geodesic(6), DVec3::new(0.01, 0.0, 0.02));
    let run = |threads: usize, seed: u64| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let c = pool.install(|| measure(&a, &b, 40_000, seed));
        (c.a_to_b, c.b_to_a)
    };
    let first = run(2, 42);
    assert_eq!(first, run(2, 42));
    assert_eq!(first, run(1, 42));
    assert_eq!(first, run(3, 42));
    let other = run(2, 43);
    assert_ne!(first.0.mean, other.0.mean);
    // Different seeds estimate the same integral.
    assert!(close(other.0.mean, first.0.mean, 1e-2));
}

#[test]
fn a_cancelled_comparison_stops_with_cancelled_and_an_uncancelled_one_measures_as_before() {
    use decimate_core::decimate::Cancel;
    use decimate_core::metro::{compare_cancellable, MetroError};
    let a = surface(grid(DVec3::ZERO, DVec3::X, DVec3::Y, 10, 10));
    let b = surface(grid(DVec3::Z * 0.25, DVec3::X, DVec3::Y, 7, 13));
    let options = Options {
        samples: Some(20_000),
        seed: 5,
        ..Options::default()
    };
    let cancel = Cancel::new();
    let whole = compare_cancellable(&a, &b, &options, &cancel).unwrap();
    let plain = compare(&a, &b, &options).unwrap();
    assert_eq!(whole.a_to_b, plain.a_to_b);
    assert_eq!(whole.b_to_a, plain.b_to_a);
    assert!(close(whole.a_to_b.mean, 0.25, 1e-9));
    cancel.request();
    let stopped = compare_cancellable(&a, &b, &options, &cancel).map(|_| ());
    assert_eq!(stopped, Err(MetroError::Cancelled));
}

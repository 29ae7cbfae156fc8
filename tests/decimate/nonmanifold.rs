//! Non-manifold input decimated by quadric edge collapse (`--algorithm qem`) and by vertex
//! removal (`schroeder`): generated shapes whose vertices on an edge of three or more
//! triangles, or where two fans meet, used to be frozen. Flat-faced, so lossless steps take
//! each one down to its corners: exact counts, every triangle still in one of the input's
//! face planes facing the same way (no flip), area and volume kept, and never more
//! non-manifold edges than the input had.

use std::collections::HashMap;

use crate::support::metro::compare_models;
use decimate_core::decimate::{simplify_scene, Algorithm, ErrorBound, Params, Target};
use decimate_core::mesh::{measure, shapes, Model, Scene};
use glam::{DVec3, Vec3};

fn run(model: Model, params: &Params) -> Model {
    let mut scene = Scene {
        models: vec![model],
    };
    simplify_scene(&mut scene, params, &mut |_| {});
    scene.models.pop().expect("the model is kept")
}

/// Collapses of zero error only (up to rounding).
fn lossless() -> Params {
    lossless_by(Algorithm::Qem)
}

/// Steps of zero error only (up to rounding) by `algorithm`.
fn lossless_by(algorithm: Algorithm) -> Params {
    Params {
        target: Target::ErrorOnly,
        max_error: Some(ErrorBound::Absolute(1e-5)),
        algorithm,
        ..Params::default()
    }
}

/// Builds a model from flat sheets, merging the vertices at the same position.
#[derive(Default)]
struct Builder {
    index: HashMap<[u32; 3], u32>,
    model: Model,
}

impl Builder {
    fn vertex(&mut self, p: Vec3) -> u32 {
        let positions = &mut self.model.positions;
        *self
            .index
            .entry(p.to_array().map(f32::to_bits))
            .or_insert_with(|| {
                positions.push(p);
                (positions.len() - 1) as u32
            })
    }

    /// An `n`×`n` grid over the parallelogram `o + s·u + t·v` (s, t in 0..=1), facing
    /// `u × v`.
    fn sheet(&mut self, o: Vec3, u: Vec3, v: Vec3, n: u32) {
        self.grid(n, |i, j| {
            o + u * (i as f32 / n as f32) + v * (j as f32 / n as f32)
        });
    }

    /// An `n`×`n` grid whose point `(i, j)` is `at(i, j)`.
    fn grid(&mut self, n: u32, at: impl Fn(u32, u32) -> Vec3) {
        for j in 0..n {
            for i in 0..n {
                let [a, b, c, d] =
                    [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(i, j)| at(i, j));
                let [a, b, c, d] = [a, b, c, d].map(|p| self.vertex(p));
                self.model.triangles.push([a, b, c]);
                self.model.triangles.push([a, c, d]);
            }
        }
    }

    /// Adds `m`'s triangles moved by `offset`.
    fn add(&mut self, m: &Model, offset: Vec3) {
        for t in &m.triangles {
            let t = t.map(|v| self.vertex(m.positions[v as usize] + offset));
            self.model.triangles.push(t);
        }
    }

    fn build(self, name: &str) -> Model {
        Model {
            name: name.to_string(),
            ..self.model
        }
    }
}

/// Each triangle's unit normal and plane offset.
fn planes(m: &Model) -> Vec<(DVec3, f64)> {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| m.positions[v as usize].as_dvec3());
            let n = (b - a).cross(c - a).normalize_or_zero();
            (n, n.dot(a))
        })
        .collect()
}

/// What a user would notice after a lossless decimation of a flat-faced `before`: a
/// degenerate triangle, one that left the input's face planes or faces the other way
/// (flipped), more non-manifold or misoriented edges, or a changed area or volume.
fn assert_kept(before: &Model, after: &Model) {
    let name = &before.name;
    assert_eq!(measure::degenerate_triangles(after, 1e-9), 0, "{name}");
    let input = planes(before);
    for (t, (n, d)) in planes(after).into_iter().enumerate() {
        assert!(
            input
                .iter()
                .any(|&(m, e)| n.dot(m) > 1.0 - 1e-9 && (d - e).abs() < 1e-5),
            "{name}: triangle {t} left the input's faces or flipped"
        );
    }
    let (e0, e1) = (measure::edge_counts(before), measure::edge_counts(after));
    assert!(
        e1.non_manifold <= e0.non_manifold,
        "{name}: {e0:?} -> {e1:?}"
    );
    assert_eq!(e1.misoriented, e0.misoriented, "{name}");
    let (a0, a1) = (measure::area(before), measure::area(after));
    assert!((a0 - a1).abs() < 1e-5 * a0, "{name}: area {a0} -> {a1}");
    let (v0, v1) = (measure::volume(before), measure::volume(after));
    assert!((v0 - v1).abs() < 1e-5 * a0, "{name}: volume {v0} -> {v1}");
}

/// (used vertices, triangles, non-manifold edges) of a model.
fn counts(m: &Model) -> (usize, usize, usize) {
    (
        m.used_vertex_count(),
        m.triangles.len(),
        measure::edge_counts(m).non_manifold,
    )
}

/// Decimates `before` by `params`' lossless steps and asserts what is left: `left` (used
/// vertices, triangles, non-manifold edges) and nothing a user would notice (`assert_kept`).
fn assert_lossless(before: &Model, params: &Params, left: (usize, usize, usize)) -> Model {
    let after = run(before.clone(), params);
    assert_eq!(counts(&after), left, "{}", before.name);
    assert_kept(before, &after);
    after
}

/// Decimates `before` by quadric collapses to `keep` triangles and asserts it gets within 2 %
/// of them, with no misoriented edge and no degenerate triangle.
fn assert_keeps(before: &Model, keep: usize) -> Model {
    let params = Params {
        target: Target::KeepTriangles(keep),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let after = run(before.clone(), &params);
    let left = after.triangles.len();
    assert!(
        left <= keep && left * 50 >= keep * 49,
        "{left} triangles, {keep} asked"
    );
    assert_eq!(measure::edge_counts(&after).misoriented, 0);
    assert_eq!(measure::degenerate_triangles(&after, 1e-9), 0);
    after
}

/// Three 4×4 sheets on one spine (see the drawing below).
fn three_sheets() -> Model {
    let mut b = Builder::default();
    for k in 0..3 {
        let angle = k as f32 * std::f32::consts::TAU / 3.0;
        let out = Vec3::new(angle.cos(), angle.sin(), 0.0);
        b.sheet(Vec3::ZERO, Vec3::Z, out, 4);
    }
    b.build("three sheets")
}

/// Two 4×4×4-gridded cubes of side 2 sharing one edge (`edge`) or one corner.
fn two_cubes(edge: bool) -> Model {
    let cube = shapes::cube(4, 2.0);
    let mut b = Builder::default();
    b.add(&cube, Vec3::ZERO);
    let (offset, name) = if edge {
        (Vec3::new(2.0, 2.0, 0.0), "two cubes on an edge")
    } else {
        (Vec3::splat(2.0), "two cubes on a vertex")
    };
    b.add(&cube, offset);
    b.build(name)
}

//   Three 4×4 sheets on one spine, seen from its end:
//
//          \   /
//           \ /
//            +----
//
// The spine's four edges each have three triangles. Each sheet keeps its two outer corners
// and the spine its two ends: 8 vertices, two triangles a sheet, one non-manifold edge.
#[test]
fn three_sheets_on_one_edge_become_three_quads_on_one_edge() {
    let before = three_sheets();
    assert_eq!(counts(&before), (65, 96, 4));
    assert_lossless(&before, &lossless(), (8, 6, 1));
}

// Two 4×4×4-gridded cubes of side 2 sharing one edge (four triangles on each of its four
// edges): each keeps its 8 corners, two shared, and its 12 triangles.
#[test]
fn two_cubes_sharing_an_edge_become_two_boxes_on_one_edge() {
    let before = two_cubes(true);
    assert_eq!(counts(&before), (2 * 98 - 5, 2 * 192, 4));
    let after = assert_lossless(&before, &lossless(), (14, 24, 1));
    assert!((measure::volume(&after) - 16.0).abs() < 1e-4);
}

// Two cubes sharing one corner: that vertex has two closed fans. 15 corners, 24 triangles.
#[test]
fn two_cubes_sharing_a_vertex_become_two_boxes_on_one_point() {
    let before = two_cubes(false);
    assert_eq!(counts(&before), (2 * 98 - 1, 2 * 192, 0));
    let after = assert_lossless(&before, &lossless(), (15, 24, 0));
    assert!((measure::volume(&after) - 16.0).abs() < 1e-4);
}

//   A bowtie: two flat 4×4 squares meeting at one corner (two open fans there).
//
//          +---+
//          |   |
//      +---+---+
//      |   |
//      +---+
//
// Each keeps its four corners, one shared: 7 vertices, 4 triangles.
#[test]
fn a_bowtie_of_two_squares_becomes_four_triangles() {
    let mut b = Builder::default();
    b.sheet(Vec3::ZERO, Vec3::X, Vec3::Y, 4);
    b.sheet(Vec3::ZERO, -Vec3::X, -Vec3::Y, 4);
    let before = b.build("bowtie");
    assert_eq!(counts(&before), (49, 64, 0));
    assert_lossless(&before, &lossless(), (7, 4, 0));
}

// A curved shape with a fin: a bumpy sphere with a sheet standing out of one meridian,
// from pole to pole (three triangles on each of the meridian's 24 edges). Kept at 5 % of its
// triangles, it reaches the count, and the fin's foot is simplified with the rest, not
// frozen: fewer non-manifold edges than before, none added, no flipped triangle.
#[test]
fn a_finned_sphere_reaches_its_count_and_simplifies_the_fin() {
    let (rings, segments) = (24, 48);
    let sphere = shapes::bumpy_sphere(rings, segments);
    let mut b = Builder::default();
    b.add(&sphere, Vec3::ZERO);
    // The meridian at segment 0, pole to pole (see `shapes::uv_sphere`'s numbering).
    let last = sphere.positions.len() - 1;
    let meridian: Vec<Vec3> = std::iter::once(0)
        .chain((1..rings as usize).map(|r| 1 + (r - 1) * segments as usize))
        .chain(std::iter::once(last))
        // As `add` placed them (adding the zero offset turns -0 into 0).
        .map(|v| sphere.positions[v] + Vec3::ZERO)
        .collect();
    for pair in meridian.windows(2) {
        let [a, c] = [pair[0], pair[1]];
        let [a, c, d, e] = [a, c, c * 1.3, a * 1.3].map(|p| b.vertex(p));
        b.model.triangles.push([a, c, d]);
        b.model.triangles.push([a, d, e]);
    }
    let before = b.build("finned sphere");
    let (_, triangles, non_manifold) = counts(&before);
    assert_eq!((triangles, non_manifold), (2 * 48 * 23 + 48, 24));
    let after = assert_keeps(&before, triangles / 20);
    let (_, _, non_manifold) = counts(&after);
    assert!(
        (1..24).contains(&non_manifold),
        "{non_manifold} non-manifold edges"
    );
}

/// Segments of the bumpy sphere the fin tests build on.
const SEGMENTS: u32 = 48;

/// A builder holding `shapes::bumpy_sphere(24, SEGMENTS)`, and the sphere.
fn bumpy_sphere_builder() -> (Builder, Model) {
    let sphere = shapes::bumpy_sphere(24, SEGMENTS);
    let mut b = Builder::default();
    b.add(&sphere, Vec3::ZERO);
    (b, sphere)
}

/// The sphere's vertex on parallel `r`, segment `s` (see `shapes::uv_sphere`'s numbering),
/// as `Builder::add` placed it (adding the zero offset turns -0 into 0).
fn on_parallel(sphere: &Model, r: u32, s: u32) -> Vec3 {
    sphere.positions[(1 + (r - 1) * SEGMENTS + s % SEGMENTS) as usize] + Vec3::ZERO
}

//   A bumpy sphere with 60 fins: single triangles standing on edges of its surface, as a
//   scan's reconstruction leaves them (each fin's foot has three triangles, its two other
//   edges are open):
//
//            /\
//        ___/__\___
//
// Kept at 10 %, the count is reached within 2 %, the fins go with the rest (they used to
// stay to the end, their rims priced as a border), none of their non-manifold edges is
// left, and the sphere keeps its area within 3 %, without a flipped or degenerate triangle.
#[test]
fn a_sphere_with_fins_loses_its_fins_and_keeps_its_area() {
    let (mut b, sphere) = bumpy_sphere_builder();
    // Every fourth edge of every fourth parallel.
    let at = |r: u32, s: u32| on_parallel(&sphere, r, s);
    for r in (4..=20).step_by(4) {
        for s in (0..SEGMENTS).step_by(4) {
            let (p, q) = (at(r, s), at(r, s + 1));
            let apex = (p + q) * 0.5 * 1.08;
            let t = [p, q, apex].map(|x| b.vertex(x));
            b.model.triangles.push(t);
        }
    }
    let before = b.build("finned sphere");
    let (_, triangles, non_manifold) = counts(&before);
    assert_eq!((triangles, non_manifold), (2 * 48 * 23 + 60, 60));
    let after = assert_keeps(&before, triangles / 10);
    let (_, _, non_manifold) = counts(&after);
    assert_eq!(non_manifold, 0, "fins left");
    let (a0, a1) = (measure::area(&sphere), measure::area(&after));
    assert!((a1 - a0).abs() < 0.03 * a0, "area {a0} -> {a1}");
}

// Decimated as far as vertex removal goes, three sheets on one edge keep the spine's two
// ends (each where a non-manifold edge meets the sheets' borders, kept), and the summary
// says so.
#[test]
fn a_fully_decimated_model_says_its_non_manifold_edges_hold_it_back() {
    let mut scene = Scene {
        models: vec![three_sheets()],
    };
    let params = Params {
        target: Target::RemovePercent(100.0),
        algorithm: Algorithm::Schroeder,
        ..Params::default()
    };
    let report = simplify_scene(&mut scene, &params, &mut |_| {});
    let m = &report.models[0];
    assert!(m.fully_decimated);
    let left = measure::non_manifold_vertices(&scene.models[0]);
    assert_eq!(m.non_manifold_kept, left);
    assert_eq!(left, 2, "the shared edge's two ends");
    assert!(
        report
            .summary()
            .contains("2 vertices on non-manifold edges of the input hold it back"),
        "{}",
        report.summary()
    );
}

// Vertex removal through a non-manifold crease line: the spine's three inner vertices each
// lie on two edges of three triangles, every sheet's fan running from one to the other, so
// each goes with its three fans filled apart and closed on one new spine edge. Left: the
// spine's ends and each sheet's two outer corners, two triangles a sheet, one spine edge
// (frozen before: 11 vertices, 15 triangles, the spine's four edges).
#[test]
fn vertex_removal_takes_three_sheets_on_one_edge_down_to_three_quads() {
    let before = three_sheets();
    assert_lossless(&before, &lossless_by(Algorithm::Schroeder), (8, 6, 1));
}

// The edge the cubes share has four fans at each inner vertex (two faces of each cube):
// removed like the other edge vertices, each cube is left its corners and 12 triangles on
// one shared edge (frozen before: 17 vertices, 36 triangles, four shared edges).
#[test]
fn vertex_removal_takes_two_cubes_sharing_an_edge_down_to_two_boxes() {
    let before = two_cubes(true);
    let after = assert_lossless(&before, &lossless_by(Algorithm::Schroeder), (14, 24, 1));
    assert!((measure::volume(&after) - 16.0).abs() < 1e-4);
}

// The shared corner is a corner of both cubes (three creases in each fan): kept, and the
// rest goes as on one cube.
#[test]
fn vertex_removal_takes_two_cubes_sharing_a_vertex_down_to_two_boxes() {
    let before = two_cubes(false);
    let after = assert_lossless(&before, &lossless_by(Algorithm::Schroeder), (15, 24, 0));
    assert!((measure::volume(&after) - 16.0).abs() < 1e-4);
}

//   A straight bowtie: two flat 4×4 squares at right angles, each with the shared vertex in
//   the middle of one side, meeting only there (two open fans, each straight along its
//   border):
//
//          +-------+          the first in the plane z = 0, x in -1..1, y in 0..2;
//          |       |          the second in the plane x = 0, y in -2..0, z in -1..1
//          +---o---+
//              |\
//              | \   ...
//
// The shared vertex goes with each fan filled apart: two squares of four corners and two
// triangles each, apart (kept before: 9 vertices, 6 triangles).
#[test]
fn vertex_removal_takes_a_straight_bowtie_apart_into_two_squares() {
    let mut b = Builder::default();
    b.sheet(Vec3::new(-1.0, 0.0, 0.0), 2.0 * Vec3::X, 2.0 * Vec3::Y, 4);
    b.sheet(Vec3::new(0.0, 0.0, -1.0), -2.0 * Vec3::Y, 2.0 * Vec3::Z, 4);
    let before = b.build("straight bowtie");
    assert_eq!(counts(&before), (49, 64, 0));
    let pinch =
        |m: &Model| (m.triangles.iter().flatten()).any(|&v| m.positions[v as usize] == Vec3::ZERO);
    assert!(pinch(&before));
    let after = assert_lossless(&before, &lossless_by(Algorithm::Schroeder), (8, 4, 0));
    assert!(!pinch(&after), "the shared vertex is gone");
}

// Two squares meeting at one corner each: the shared corner turns a right angle in both
// fans, a corner kept as on one square; the rest goes: 7 vertices, 4 triangles.
#[test]
fn vertex_removal_keeps_a_corner_bowtie_and_takes_the_rest() {
    let mut b = Builder::default();
    b.sheet(Vec3::ZERO, Vec3::X, Vec3::Y, 4);
    b.sheet(Vec3::ZERO, -Vec3::X, -Vec3::Y, 4);
    let before = b.build("bowtie");
    assert_lossless(&before, &lossless_by(Algorithm::Schroeder), (7, 4, 0));
}

//   A pinch: two flat 4×4 squares crossing at right angles, the first in the plane z = 0,
//   the second in y = 0, sharing one edge from the origin to (0.5, 0, 0) — the second's
//   other points on the x axis are moved up by 0.01 in its own plane, so it stays flat and
//   shares nothing else. Each end of the shared edge is inside both squares: two closed
//   fans through the edge's other end. Each goes with each fan filled apart, and the two
//   squares come apart: four corners and two triangles each, no non-manifold edge.
#[test]
fn vertex_removal_takes_a_pinch_along_one_edge_apart_into_two_squares() {
    let mut b = Builder::default();
    b.sheet(Vec3::new(-1.0, -1.0, 0.0), 2.0 * Vec3::X, 2.0 * Vec3::Y, 4);
    b.grid(4, |i, j| {
        let (x, z) = (i as f32 * 0.5 - 1.0, j as f32 * 0.5 - 1.0);
        let shared = z == 0.0 && (x == 0.0 || x == 0.5);
        let lift = if z == 0.0 && !shared { 0.01 } else { 0.0 };
        Vec3::new(x, 0.0, z + lift)
    });
    let before = b.build("pinch");
    assert_eq!(counts(&before), (48, 64, 1));
    assert_lossless(&before, &lossless_by(Algorithm::Schroeder), (8, 4, 0));
}

/// A flat 4×4 sheet over the unit square (facing +z) and one more triangle, its corners
/// merged with the sheet's where they meet.
fn sheet_with(extra: [Vec3; 3]) -> Model {
    let mut b = Builder::default();
    b.sheet(Vec3::ZERO, Vec3::X, Vec3::Y, 4);
    let t = extra.map(|p| b.vertex(p));
    b.model.triangles.push(t);
    b.build("sheet with a flap")
}

/// The sheet's grid point `(i, j)`, raised by `z`.
fn grid(i: u32, j: u32, z: f32) -> Vec3 {
    Vec3::new(i as f32 / 4.0, j as f32 / 4.0, z)
}

//   A sliver flap lying on a flat sheet, as reconstructed scans leave them: the triangle
//   v-a-x over two of the sheet's edges (v-a, a-x: three triangles each), its third edge
//   v-x open (a fin's end meeting its border at v and at x):
//
//      +---+---+---+---+
//      |   |   |  /|   |
//      +---+---+-x-+---+
//      |   | / |/  |   |
//      +---v---a---+---+
//
// v and x each end a non-manifold edge and meet a border; removed, the flap goes with
// them and its two edges are left with the sheet's two triangles: the sheet's four corners,
// two triangles, no non-manifold edge (v, a and x were frozen before).
#[test]
fn vertex_removal_drops_a_sliver_flap_lying_on_a_sheet() {
    let before = sheet_with([grid(1, 1, 0.0), grid(2, 1, 0.0), grid(3, 2, 0.0)]);
    assert_eq!(counts(&before), (25, 33, 2));
    let after = run(before.clone(), &lossless_by(Algorithm::Schroeder));
    assert_eq!(counts(&after), (4, 2, 0));
    assert_flat_sheet_kept(&before, &after);
}

//   A flap standing on an interior edge of a flat sheet: the triangle v-a-x, x a tenth of
//   the sheet's side above the middle of v-a, in no other triangle (a dangling fin of
//   one triangle; v-a has three triangles, its ends each meet the fin's border):
//
//             x
//            / \
//      +---v---a---+---+   (seen from the side)
//
// x is a corner by its sharp turn, and v and a fin ends whose flap cannot go (its edge a-x
// would be left with no triangle): all three were kept. Decimated as far as it goes, x
// goes first, dropping the flap (its height is the error), then v and a as flat vertices:
// the sheet's four corners and two triangles are left, no non-manifold edge.
#[test]
fn vertex_removal_drops_a_flap_standing_on_a_sheet() {
    let before = sheet_with([grid(1, 2, 0.0), grid(2, 2, 0.0), Vec3::new(0.375, 0.5, 0.1)]);
    assert_eq!(counts(&before), (26, 33, 1));
    let params = Params {
        target: Target::RemovePercent(100.0),
        algorithm: Algorithm::Schroeder,
        ..Params::default()
    };
    let after = run(before.clone(), &params);
    assert_eq!(counts(&after), (4, 2, 0));
    assert_flat_sheet_kept(&before, &after);
}

/// What a user would notice after a flap is dropped from a flat sheet: the sheet left
/// whole (its area, every triangle facing +z in its plane, no degenerate one) and no
/// non-manifold edge added.
fn assert_flat_sheet_kept(before: &Model, after: &Model) {
    assert_eq!(measure::degenerate_triangles(after, 1e-9), 0);
    for (n, d) in planes(after) {
        assert!(n.dot(DVec3::Z) > 1.0 - 1e-9 && d.abs() < 1e-6, "{n} {d}");
    }
    let (e0, e1) = (measure::edge_counts(before), measure::edge_counts(after));
    assert!(e1.non_manifold <= e0.non_manifold, "{e0:?} -> {e1:?}");
    assert_eq!(e1.misoriented, 0);
    assert!((measure::area(after) - 1.0).abs() < 1e-6);
}

//   A flat 4×4 sheet with one inner vertex v pulled over its ring's edge a-b, as
//   reconstructed scans leave them: the triangle v-a-b faces down, folded back under the
//   others (seen from above, v lies outside its own ring):
//
//      +---+---+---b-+-+
//      |   |   | / | v |
//      +---+---+---a---+
//
// No fill of v's ring (nor of a's or b's) faces like both sides of the fold, so all three
// were kept for ever. Once nothing else can go the folded triangle is left out of the flip
// check (at 180°, where no edge is a feature): lossless steps leave the sheet's four
// corners and two triangles, every one facing up, the area the unit square's.
#[test]
fn vertex_removal_takes_out_a_fold_in_a_flat_sheet() {
    let mut b = Builder::default();
    b.grid(4, |i, j| match (i, j) {
        (2, 2) => Vec3::new(0.8, 0.6, 0.0),
        _ => grid(i, j, 0.0),
    });
    let before = b.build("folded sheet");
    let down = planes(&before).iter().filter(|(n, _)| n.z < 0.0).count();
    assert_eq!((counts(&before), down), ((25, 32, 0), 1));
    let params = Params {
        feature_angle_deg: 180.0,
        ..lossless_by(Algorithm::Schroeder)
    };
    let after = run(before.clone(), &params);
    assert_eq!(counts(&after), (4, 2, 0));
    assert_flat_sheet_kept(&before, &after);
}

//   A bumpy sphere carrying what a reconstructed scan leaves on its surface: 10 closed
//   tetrahedra ("pockets") and 10 single-triangle flaps, each hanging on one edge of the
//   surface (that edge then has four or three triangles), each its edge's length across.
fn sphere_with_pockets_and_flaps() -> (Model, Model) {
    let (mut b, sphere) = bumpy_sphere_builder();
    let at = |r: u32, s: u32| on_parallel(&sphere, r, s);
    for (k, r) in (3..=21).step_by(2).enumerate() {
        for (flap, s) in [(false, k as u32 * 4), (true, k as u32 * 4 + 24)] {
            let (p, q) = (at(r, s), at(r, s + 1));
            let mid = (p + q) * 0.5;
            let side = (q - p).cross(mid).normalize() * (q - p).length() * 0.05;
            let [p, q] = [p, q].map(|x| b.vertex(x));
            if !flap {
                // A flat tetrahedron over the edge, facing out.
                let [x, y] = [mid * 1.02 + side, mid * 1.02 - side].map(|x| b.vertex(x));
                let tetra = [[q, p, x], [p, q, y], [p, y, x], [q, x, y]];
                b.model.triangles.extend(tetra);
            } else {
                let apex = b.vertex(mid * 1.05);
                b.model.triangles.push([p, q, apex]);
            }
        }
    }
    (b.build("sphere with pockets and flaps"), sphere)
}

// Kept at 2 %, the pockets and flaps go before decimating (each smaller than what a result
// triangle covers), the count is reached and the result has no non-manifold edge left and
// the bare sphere's area, every triangle facing out. At 50 % they are larger than that and
// stay for the collapses.
#[test]
fn pockets_and_flaps_smaller_than_the_result_triangles_go_before_decimating() {
    let (before, sphere) = sphere_with_pockets_and_flaps();
    let (_, triangles, non_manifold) = counts(&before);
    assert_eq!((triangles, non_manifold), (2 * 48 * 23 + 50, 20));
    let mut scene = Scene {
        models: vec![before.clone()],
    };
    let params = |keep| Params {
        target: Target::KeepTriangles(keep),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let report = simplify_scene(&mut scene, &params(44), &mut |_| {});
    let sheets = report.models[0].hanging_sheets;
    assert_eq!(
        (sheets.sheets, sheets.pockets, sheets.triangles),
        (20, 10, 50)
    );
    assert!(
        report.summary().contains(
            "20 sheets hanging on non-manifold edges, smaller than the result's triangles, \
             removed: 50 triangles, 10 closed pockets among them"
        ),
        "{}",
        report.summary()
    );
    let after = scene.models.pop().expect("kept");
    let bare = assert_keeps(&sphere, 44);
    assert_eq!(after.triangles.len(), bare.triangles.len());
    assert_eq!(measure::edge_counts(&after).non_manifold, 0);
    assert_eq!(measure::edge_counts(&after).misoriented, 0);
    assert_eq!(measure::degenerate_triangles(&after, 1e-9), 0);
    let (a0, a1) = (measure::area(&bare), measure::area(&after));
    assert!(
        (a1 - a0).abs() < 0.02 * a0,
        "area {a1}, the bare sphere's {a0}"
    );
    assert!(measure::volume(&after) > 0.9 * measure::volume(&bare));
    for t in &after.triangles {
        let [a, b, c] = t.map(|v| after.positions[v as usize]);
        let outward = (b - a).cross(c - a).dot(a + b + c);
        assert!(outward > 0.0, "a triangle turned in: {t:?}");
    }

    let mut scene = Scene {
        models: vec![before.clone()],
    };
    let report = simplify_scene(&mut scene, &params(triangles / 2), &mut |_| {});
    assert_eq!(report.models[0].hanging_sheets.sheets, 0);
    assert!(measure::edge_counts(&scene.models[0]).non_manifold <= non_manifold);
}

//   The bumpy sphere with 40 doubled fins: a triangle standing on an edge of the surface and
//   its reversed twin, a zero-thickness flap that is closed (its two free edges on both
//   triangles), as a coarse scan reconstruction leaves them where a thin part falls between
//   its grid's samples (dragon_res3 carries 857). Together they are about 2 % of the area.
fn sphere_with_doubled_fins() -> (Model, Model) {
    let (mut b, sphere) = bumpy_sphere_builder();
    let at = |r: u32, s: u32| on_parallel(&sphere, r, s);
    for r in (3..=21).step_by(2) {
        for s in (0..SEGMENTS).step_by(12) {
            let (p, q) = (at(r, s), at(r, s + 1));
            let [p, q, apex] = [p, q, (p + q) * 0.5 * 1.06].map(|x| b.vertex(x));
            b.model.triangles.extend([[p, q, apex], [q, p, apex]]);
        }
    }
    (b.build("sphere with doubled fins"), sphere)
}

// Kept at 2 %, the doubled fins go before decimating, although together they are more than
// 1 % of the area (sheets that many and that small are a scan's debris, not the cells of a
// voxel model, which stay): the result has the bare sphere's count, neither border nor
// non-manifold edges (closed stays closed), and is as close to its input as the bare
// sphere's result is to the sphere. They used to stay, each holding result triangles.
#[test]
fn doubled_fins_over_one_percent_of_the_area_go_and_the_sphere_stays_closed() {
    let (before, sphere) = sphere_with_doubled_fins();
    let (_, triangles, non_manifold) = counts(&before);
    assert_eq!((triangles, non_manifold), (2 * 48 * 23 + 80, 40));
    let share = 1.0 - measure::area(&sphere) / measure::area(&before);
    assert!((0.01..0.05).contains(&share), "fins' share {share}");
    let mut scene = Scene {
        models: vec![before.clone()],
    };
    let params = Params {
        target: Target::KeepTriangles(44),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let report = simplify_scene(&mut scene, &params, &mut |_| {});
    let sheets = report.models[0].hanging_sheets;
    assert_eq!(
        (sheets.sheets, sheets.pockets, sheets.triangles),
        (40, 40, 80)
    );
    let after = scene.models.pop().expect("kept");
    let bare = assert_keeps(&sphere, 44);
    assert_eq!(after.triangles.len(), bare.triangles.len());
    let edges = measure::edge_counts(&after);
    assert_eq!((edges.boundary, edges.non_manifold), (0, 0));
    let error = compare_models(&before, &after).symmetric().mean;
    let bare_error = compare_models(&sphere, &bare).symmetric().mean;
    assert!(
        error < 1.1 * bare_error,
        "mean error {error}, the bare sphere's {bare_error}"
    );
}

// The same sphere kept at 60 %: its doubled fins are far larger than the result's
// triangles, so they are surface to keep, not debris. Each fin's apex stays where it was
// and the farthest input point is less than twice as far as on the bare sphere kept at
// 60 % (a fin's height is eight times that). A fin's two
// sides are folded flat onto each other; on this coarse sphere every fold used to be scaled
// down to nothing, so the apex slid to the foot for free and the fins went first, leaving
// input points a whole fin's height (0.06) from the result.
#[test]
fn doubled_fins_larger_than_the_result_triangles_stay_where_they_stand() {
    let (before, sphere) = sphere_with_doubled_fins();
    let keep = before.triangles.len() * 6 / 10;
    let after = assert_keeps(&before, keep);
    let apexes: Vec<Vec3> = (3..=21)
        .step_by(2)
        .flat_map(|r| (0..SEGMENTS).step_by(12).map(move |s| (r, s)))
        .map(|(r, s)| (on_parallel(&sphere, r, s) + on_parallel(&sphere, r, s + 1)) * 0.5 * 1.06)
        .collect();
    assert_eq!(apexes.len(), 40);
    let kept = apexes
        .iter()
        .filter(|a| after.positions.iter().any(|p| p.distance(**a) < 1e-6))
        .count();
    assert_eq!(kept, 40, "fin apexes left in place");
    let farthest = compare_models(&before, &after).a_to_b.max;
    let bare = assert_keeps(&sphere, sphere.triangles.len() * 6 / 10);
    let bare_farthest = compare_models(&sphere, &bare).a_to_b.max;
    assert!(
        farthest < 2.0 * bare_farthest,
        "an input point {farthest} from the result, {bare_farthest} on the bare sphere"
    );
    let edges = measure::edge_counts(&after);
    assert_eq!(edges.boundary, 0);
}

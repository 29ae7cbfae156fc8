//! Colour seams: a colour jump that a file gives as two vertices at one point (a PLY with
//! duplicated vertices, a VRML `colorIndex` giving one point two colours) stays a sharp,
//! straight jump through decimation by either algorithm: the sides are never welded into
//! one vertex, every output triangle keeps one side's colour, the sides' areas stay where
//! they were, the surface does not crack along the jump, and the count target is met in
//! positions (a seam's copies counted once). A border between per-face colours (OFF, PLY)
//! is kept the same way, and comes out with one vertex per point and colours on the faces.

use std::fmt::Write as _;

use decimate_core::io::read_scene;
use decimate_core::mesh::build::build_scene;
use decimate_core::mesh::{Attribute, Scene};

use crate::support::binary;
use crate::support::plain_files::{read_ply, Plain};

const RED: [u8; 3] = [255, 0, 0];
const BLUE: [u8; 3] = [0, 0, 255];

/// A gently waved sheet over [-1, 1]², `n` × `n` squares (`n` even), red for x < 0 and blue
/// for x > 0: the column at x = 0 is written twice, a red copy and a blue copy.
fn two_colour_sheet_ply(n: usize) -> String {
    let height = |x: f64, y: f64| 0.08 * (2.5 * x).sin() * (3.0 * y).cos();
    let coordinate = |i: usize| -1.0 + 2.0 * i as f64 / n as f64;
    let (mut vertices, mut count) = (String::new(), 0usize);
    // Vertex of column `i` (0..=n), row `j`, on side `blue` of the seam column n / 2.
    let mut index = std::collections::HashMap::new();
    for i in 0..=n {
        for blue in [false, true] {
            let on_side = if blue { i >= n / 2 } else { i <= n / 2 };
            if !on_side {
                continue;
            }
            for j in 0..=n {
                let (x, y) = (coordinate(i), coordinate(j));
                let [r, g, b] = if blue { BLUE } else { RED };
                let z = height(x, y);
                writeln!(vertices, "{x} {y} {z} {r} {g} {b}").expect("a String takes text");
                index.insert((i, j, blue), count);
                count += 1;
            }
        }
    }
    let mut faces = String::new();
    for i in 0..n {
        let blue = i >= n / 2;
        for j in 0..n {
            let v = |di: usize, dj: usize| index[&(i + di, j + dj, blue)];
            let (a, b, c, d) = (v(0, 0), v(1, 0), v(1, 1), v(0, 1));
            writeln!(faces, "3 {a} {b} {c}\n3 {a} {c} {d}").expect("a String takes text");
        }
    }
    format!(
        "ply\nformat ascii 1.0\nelement vertex {count}\nproperty float x\nproperty float y\n\
         property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n{vertices}{faces}",
        2 * n * n
    )
}

/// Decimates `input` with `args` through the binary and reads `out.ply` back with the
/// tests' own reader.
fn decimate_ply(input: &str, args: &[&str]) -> Plain {
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join("in.ply"), input).expect("the input written");
    let mut all = vec!["in.ply", "nogui"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", "out.ply"]);
    let run = binary::decimate(dir.path(), &all);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{all:?}: {stderr}");
    let bytes = std::fs::read(dir.path().join("out.ply")).expect("the output");
    read_ply(&bytes).unwrap_or_else(|e| panic!("{all:?}: out.ply: {e}"))
}

/// The projected (x, y) area of the triangles all of whose corners have `colour`, and the
/// number of triangles whose corners mix colours.
fn area_of(plain: &Plain, colour: [u8; 3]) -> (f64, usize) {
    let colors = plain.colors.as_ref().expect("the output has colours");
    let byte = |c: [f32; 3]| c.map(|x| (x * 255.0).round() as u8);
    let (mut area, mut mixed) = (0.0, 0);
    for t in &plain.triangles {
        let corners = t.map(|v| byte(colors[v as usize]));
        if corners.iter().all(|&c| c == colour) {
            let [a, b, c] = t.map(|v| plain.points[v as usize].map(f64::from));
            area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
        } else if corners.contains(&colour) {
            mixed += 1;
        }
    }
    (area, mixed)
}

/// Edges with one triangle once corners are joined by position whose middle is inside the
/// sheet (not within 1 % of its outer square, along which qem slides border points):
/// cracks.
fn inner_border_edges(plain: &Plain) -> usize {
    let key = |v: u32| plain.points[v as usize].map(f32::to_bits);
    let mut count = std::collections::HashMap::new();
    for t in &plain.triangles {
        for k in 0..3 {
            let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
            *count
                .entry(if a < b { (a, b) } else { (b, a) })
                .or_insert(0) += 1;
        }
    }
    let inside = |a: [u32; 3], b: [u32; 3]| {
        let middle = |k: usize| 0.5 * (f32::from_bits(a[k]) + f32::from_bits(b[k]));
        middle(0).abs() < 0.99 && middle(1).abs() < 0.99
    };
    count
        .iter()
        .filter(|(&(a, b), &n)| n == 1 && inside(a, b))
        .count()
}

fn distinct_points(plain: &Plain) -> usize {
    let used: std::collections::HashSet<[u32; 3]> = plain
        .triangles
        .iter()
        .flatten()
        .map(|&v| plain.points[v as usize].map(f32::to_bits))
        .collect();
    used.len()
}

#[test]
fn a_colour_jump_given_as_two_vertices_stays_sharp_straight_and_closed() {
    let n = 24;
    let input = two_colour_sheet_ply(n);
    let points = (n + 1) * (n + 1);
    for algorithm in ["schroeder", "qem"] {
        for keep in [points / 4, points / 10] {
            let what = format!("{algorithm} keeping {keep} of {points} points");
            let keep_arg = keep.to_string();
            let out = decimate_ply(&input, &["-a", algorithm, "--keep-vertices", &keep_arg]);
            assert_eq!(distinct_points(&out), keep, "{what}");
            let (red, mixed_red) = area_of(&out, RED);
            let (blue, mixed_blue) = area_of(&out, BLUE);
            assert_eq!((mixed_red, mixed_blue), (0, 0), "{what}: smeared triangles");
            // Each half is 2 × 1 in (x, y); the jump stays on x = 0.
            assert!((red - 2.0).abs() < 1e-3, "{what}: red area {red}");
            assert!((blue - 2.0).abs() < 1e-3, "{what}: blue area {blue}");
            assert_eq!(inner_border_edges(&out), 0, "{what}: cracks");
        }
    }
}

/// Two unit squares side by side in VRML 2.0, `colorPerVertex` with a `colorIndex` that
/// gives the shared edge's two points red in the left face and blue in the right one.
const TWO_FACES_WRL: &str = "#VRML V2.0 utf8
Shape { geometry IndexedFaceSet {
  coord Coordinate { point [ 0 0 0, 1 0 0, 2 0 0, 0 1 0, 1 1 0, 2 1 0 ] }
  coordIndex [ 0 1 4 3 -1, 1 2 5 4 -1 ]
  color Color { color [ 1 0 0, 0 0 1 ] }
  colorPerVertex TRUE
  colorIndex [ 0 0 0 0 -1, 1 1 1 1 -1 ]
} }
";

#[test]
fn a_point_with_two_colours_in_a_vrml_file_keeps_both() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join("two.wrl");
    std::fs::write(&path, TWO_FACES_WRL).expect("the scene written");
    let read = read_scene(&path).expect("the scene reads");
    let scene: Scene = build_scene(read.scene, true);
    let m = &scene.models[0];
    let Some(Attribute::PerVertex(colors)) = &m.colors else {
        panic!("per-vertex colours expected, got {:?}", m.colors)
    };
    // 6 points, the shared edge's two as a red and a blue copy each.
    assert_eq!(m.used_vertex_count(), 8);
    for t in &m.triangles {
        let left = t.iter().all(|&v| m.positions[v as usize].x <= 1.0);
        let want = if left {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 0.0, 1.0]
        };
        for &v in t {
            assert_eq!(colors[v as usize], want, "triangle {t:?}");
        }
    }
}

/// The same waved sheet as [`two_colour_sheet_ply`], as OFF with one vertex per point and a
/// colour on each face line: red for x < 0, blue for x > 0.
fn face_coloured_sheet_off(n: usize) -> String {
    let height = |x: f64, y: f64| 0.08 * (2.5 * x).sin() * (3.0 * y).cos();
    let coordinate = |i: usize| -1.0 + 2.0 * i as f64 / n as f64;
    let mut text = format!("OFF\n{} {} 0\n", (n + 1) * (n + 1), 2 * n * n);
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (coordinate(i), coordinate(j));
            writeln!(text, "{x} {y} {}", height(x, y)).expect("a String takes text");
        }
    }
    for i in 0..n {
        let [r, g, b] = if i < n / 2 { RED } else { BLUE };
        for j in 0..n {
            let v = |di: usize, dj: usize| (i + di) * (n + 1) + j + dj;
            let (a, b2, c, d) = (v(0, 0), v(1, 0), v(1, 1), v(0, 1));
            writeln!(
                text,
                "3 {a} {b2} {c} {r} {g} {b}\n3 {a} {c} {d} {r} {g} {b}"
            )
            .expect("a String takes text");
        }
    }
    text
}

/// An OFF file's points, triangles and face colours.
type FaceColouredOff = (Vec<[f64; 3]>, Vec<[usize; 3]>, Vec<Option<[u8; 3]>>);

/// An OFF file's points, triangles and face colours (bytes; `None` for a face without one),
/// read by the test itself.
fn read_face_coloured_off(text: &str) -> FaceColouredOff {
    let mut lines = (text.lines())
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|l| !l.is_empty());
    assert_eq!(lines.next(), Some("OFF"), "an OFF header");
    let counts: Vec<usize> = (lines.next().expect("a counts line").split_whitespace())
        .map(|w| w.parse().expect("a count"))
        .collect();
    let number = |w: &str| w.parse::<f64>().expect("a number");
    let points = (0..counts[0])
        .map(|_| {
            let w: Vec<f64> = lines
                .next()
                .expect("a vertex")
                .split_whitespace()
                .map(number)
                .collect();
            [w[0], w[1], w[2]]
        })
        .collect();
    let (mut triangles, mut colours) = (Vec::new(), Vec::new());
    for _ in 0..counts[1] {
        let w: Vec<&str> = lines.next().expect("a face").split_whitespace().collect();
        assert_eq!(w[0], "3", "a triangle");
        triangles.push([1, 2, 3].map(|k| w[k].parse().expect("an index")));
        colours
            .push((w.len() >= 7).then(|| [4, 5, 6].map(|k| (number(w[k]) * 255.0).round() as u8)));
    }
    (points, triangles, colours)
}

/// [`face_coloured_sheet_off`] as an ASCII PLY with `red`, `green` and `blue` on each face.
fn face_coloured_sheet_ply(n: usize) -> String {
    let off = face_coloured_sheet_off(n);
    let lines = off.lines().skip(2);
    let (points, faces) = ((n + 1) * (n + 1), 2 * n * n);
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {points}\nproperty float x\nproperty float y\n\
         property float z\nelement face {faces}\nproperty list uchar int vertex_indices\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
    );
    for line in lines.take(points + faces) {
        writeln!(text, "{line}").expect("a String takes text");
    }
    text
}

#[test]
fn a_border_between_face_colours_stays_sharp_and_straight_with_one_vertex_per_point() {
    let n = 24;
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join("in.off"), face_coloured_sheet_off(n)).expect("the input");
    std::fs::write(dir.path().join("in.ply"), face_coloured_sheet_ply(n)).expect("the input");
    let points = (n + 1) * (n + 1);
    let cases = [("in.off", "out.off"), ("in.ply", "out.ply")];
    for ((input, output), algorithm) in cases
        .iter()
        .zip(["schroeder", "qem"])
        .chain(cases.iter().zip(["qem", "schroeder"]))
    {
        for keep in [points / 4, points / 10] {
            let what =
                format!("{input} to {output}, {algorithm} keeping {keep} of {points} points");
            let keep_arg = keep.to_string();
            let args = [
                *input,
                "nogui",
                "-a",
                algorithm,
                "--keep-vertices",
                &keep_arg,
            ];
            let run = binary::decimate(dir.path(), &[&args[..], &["-o", output]].concat());
            assert!(
                run.status.success(),
                "{what}: {}",
                String::from_utf8_lossy(&run.stderr)
            );
            // A PLY is turned into OFF for the test's reader, nothing removed.
            let back = ["out.ply", "nogui", "-p", "0", "-o", "back.off"];
            let off = if *output == "out.ply" {
                let run = binary::decimate(dir.path(), &back);
                assert!(
                    run.status.success(),
                    "{what}: {}",
                    String::from_utf8_lossy(&run.stderr)
                );
                "back.off"
            } else {
                "out.off"
            };
            let text = std::fs::read_to_string(dir.path().join(off)).expect("the OFF output");
            check_face_coloured_sheet(&what, &text, keep);
        }
    }
}

/// Checks a decimated [`face_coloured_sheet_off`]: `keep` vertices in the file (one per
/// point), every face red or blue, each colour's area where it was, no crack.
fn check_face_coloured_sheet(what: &str, text: &str, keep: usize) {
    let (p, triangles, colours) = read_face_coloured_off(text);
    assert_eq!(p.len(), keep, "{what}: vertices in the file");
    let (mut red, mut blue) = (0.0, 0.0);
    for (t, colour) in triangles.iter().zip(&colours) {
        let [a, b, c] = t.map(|v| p[v]);
        let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
        match colour {
            Some(RED) => red += area,
            Some(BLUE) => blue += area,
            other => panic!("{what}: a face coloured {other:?}"),
        }
    }
    // Each half is 2 × 1 in (x, y): the border stays on x = 0.
    assert!((red - 2.0).abs() < 1e-3, "{what}: red area {red}");
    assert!((blue - 2.0).abs() < 1e-3, "{what}: blue area {blue}");
    let plain = Plain {
        points: p.iter().map(|q| q.map(|x| x as f32)).collect(),
        triangles: triangles.iter().map(|t| t.map(|v| v as u32)).collect(),
        colors: None,
    };
    assert_eq!(inner_border_edges(&plain), 0, "{what}: cracks");
}

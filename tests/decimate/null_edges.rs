//! Closed surfaces whose file joins two copies of a point by zero-area triangles (a null
//! edge, as exporters leave along a UV seam): without welding, the null edges are collapsed,
//! not deleted, so the result stays closed and keeps its genus; a two-sided sheet (each
//! triangle beside its reversed twin) keeps both sides. Checked on the written OBJ by an
//! edge count of the test's own.

use std::collections::HashMap;

use crate::support::binary::decimate;

/// A torus of `nu` × `nv` quads whose column 0 is written twice at the same points, the two
/// copies joined by a strip of zero-area triangles: `nv` null edges, `2 nv` such triangles.
fn torus_with_null_edges(nu: usize, nv: usize) -> String {
    let mut text = String::new();
    let point = |i: usize, j: usize| {
        let (u, v) = (
            std::f64::consts::TAU * i as f64 / nu as f64,
            std::f64::consts::TAU * j as f64 / nv as f64,
        );
        let r = 1.0 + 0.35 * v.cos();
        [r * u.cos(), r * u.sin(), 0.35 * v.sin()]
    };
    // Points 0 .. nu*nv: (i, j) at i * nv + j; then the copy of column 0.
    for i in 0..nu {
        for j in 0..nv {
            let [x, y, z] = point(i, j);
            text += &format!("v {x:.6} {y:.6} {z:.6}\n");
        }
    }
    for j in 0..nv {
        let [x, y, z] = point(0, j);
        text += &format!("v {x:.6} {y:.6} {z:.6}\n");
    }
    let id = |i: usize, j: usize| i * nv + j % nv + 1;
    let copy = |j: usize| nu * nv + j % nv + 1;
    for i in 0..nu {
        for j in 0..nv {
            // The last column of quads closes onto the copy of column 0.
            let right = |j| if i + 1 == nu { copy(j) } else { id(i + 1, j) };
            let [a, b, c, d] = [id(i, j), right(j), right(j + 1), id(i, j + 1)];
            text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        }
    }
    for j in 0..nv {
        let [a, b, c, d] = [copy(j), id(0, j), id(0, j + 1), copy(j + 1)];
        text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
    }
    text
}

/// Vertices, edges, triangles and border edges (on one triangle) of an OBJ, by index.
fn census(obj: &str) -> (usize, usize, usize, usize) {
    let vertices = obj.lines().filter(|l| l.starts_with("v ")).count();
    let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
    let mut triangles = 0;
    for line in obj.lines().filter(|l| l.starts_with("f ")) {
        let corners: Vec<usize> = line[2..]
            .split_whitespace()
            .map(|c| {
                c.split('/')
                    .next()
                    .and_then(|v| v.parse().ok())
                    .expect("an index")
            })
            .collect();
        assert_eq!(corners.len(), 3, "{line}");
        triangles += 1;
        for k in 0..3 {
            let (a, b) = (corners[k], corners[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let border = edges.values().filter(|&&n| n == 1).count();
    (vertices, edges.len(), triangles, border)
}

fn run(input: &str, name: &str, args: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("a temporary folder");
    std::fs::write(dir.path().join(name), input).expect("the input written");
    let mut all = vec![name, "nogui", "-o", "out.obj"];
    all.extend_from_slice(args);
    let out = decimate(dir.path(), &all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::read_to_string(dir.path().join("out.obj")).expect("the output read")
}

#[test]
fn null_edges_are_collapsed_so_a_torus_stays_a_closed_torus() {
    let input = torus_with_null_edges(24, 12);
    let (v, e, f, border) = census(&input);
    assert_eq!((v, f, border), (24 * 12 + 12, 2 * 24 * 12 + 24, 0));
    assert_eq!(v + f - e, 0, "the input is a torus");
    let mut checked = 0;
    for weld in [true, false] {
        for algorithm in ["schroeder", "qem"] {
            let mut args = vec!["-a", algorithm, "-p", "50"];
            if !weld {
                args.push("--no-weld");
            }
            let (v, e, f, border) = census(&run(&input, "torus.obj", &args));
            assert_eq!(border, 0, "{args:?}: the torus was cut open");
            assert_eq!(v + f - e, 0, "{args:?}: the genus changed");
            assert!(v <= (24 * 12) / 2 + 1, "{args:?}: {v} vertices left");
            checked += 1;
        }
    }
    assert_eq!(checked, 4);
}

#[test]
fn a_two_sided_sheet_keeps_both_sides_and_stays_closed() {
    // A 6×6 grid written once each way round: every edge on two triangles.
    let n = 6;
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            text += &format!("v {i} {j} {}\n", 0.1 * ((i * j) % 3) as f64);
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            text += &format!("f {a} {b} {c}\nf {a} {c} {d}\nf {a} {c} {b}\nf {a} {d} {c}\n");
        }
    }
    for algorithm in ["schroeder", "qem"] {
        let (_, _, f, border) = census(&run(&text, "leaf.obj", &["-a", algorithm, "-p", "0"]));
        assert_eq!(
            (f, border),
            (4 * n * n, 0),
            "{algorithm}: a side was removed"
        );
    }
}

#[test]
fn a_closed_box_with_a_two_sided_fin_comes_out_closed() {
    // A 4×4×4 grid box (closed) and, standing on its top face's middle line, a fin of 4×2
    // squares written once each way round: the fin's foot edges are on four triangles.
    let mut text = String::new();
    let mut points: Vec<[i32; 3]> = Vec::new();
    let mut id = |p: [i32; 3], text: &mut String| match points.iter().position(|&q| q == p) {
        Some(i) => i + 1,
        None => {
            points.push(p);
            *text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
            points.len()
        }
    };
    let mut faces = String::new();
    // The box's six faces, each a 4×4 grid, outward.
    let faces_of: [([i32; 3], [i32; 3], [i32; 3]); 6] = [
        ([0, 0, 0], [0, 1, 0], [1, 0, 0]),
        ([0, 0, 4], [1, 0, 0], [0, 1, 0]),
        ([0, 0, 0], [1, 0, 0], [0, 0, 1]),
        ([0, 4, 0], [0, 0, 1], [1, 0, 0]),
        ([0, 0, 0], [0, 0, 1], [0, 1, 0]),
        ([4, 0, 0], [0, 1, 0], [0, 0, 1]),
    ];
    for (origin, u, v) in faces_of {
        let at = |i: i32, j: i32| [0, 1, 2].map(|k| origin[k] + i * u[k] + j * v[k]);
        for j in 0..4 {
            for i in 0..4 {
                let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                let [a, b, c, d] = q.map(|p| id(p, &mut text));
                faces += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
            }
        }
    }
    // The fin over x = 0..4 at y = 2, z = 4..6, both sides.
    for j in 0..2 {
        for i in 0..4 {
            let q = [
                [i, 2, 4 + j],
                [i + 1, 2, 4 + j],
                [i + 1, 2, 5 + j],
                [i, 2, 5 + j],
            ];
            let [a, b, c, d] = q.map(|p| id(p, &mut text));
            faces += &format!("f {a} {b} {c}\nf {a} {c} {d}\nf {a} {c} {b}\nf {a} {d} {c}\n");
        }
    }
    let input = text + &faces;
    assert_eq!(census(&input).3, 0, "the input is closed");
    for algorithm in ["schroeder", "qem"] {
        let (_, _, f, border) = census(&run(&input, "fin.obj", &["-a", algorithm, "-p", "60"]));
        assert_eq!(
            border, 0,
            "{algorithm}: {f} triangles, the surface was opened"
        );
        assert!(f < 6 * 32 + 32, "{algorithm}: nothing decimated");
    }
}

#[test]
fn qem_keeps_loose_doubled_specks_beside_a_sphere() {
    // A closed lat-long sphere of radius 1 and, floating 0.5 off it, three specks: a square
    // of two triangles written once each way round (a scan's loose doubled flake). Deleting a
    // speck whole makes its distance to the sphere the result's error.
    let (rings, segments) = (12, 24);
    let mut text = String::new();
    let pole = |z: f64| format!("v 0 0 {z}\n");
    text += &pole(1.0);
    for r in 1..rings {
        let theta = std::f64::consts::PI * r as f64 / rings as f64;
        for s in 0..segments {
            let phi = std::f64::consts::TAU * s as f64 / segments as f64;
            let [x, y, z] = [
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ];
            text += &format!("v {x:.6} {y:.6} {z:.6}\n");
        }
    }
    text += &pole(-1.0);
    let south = 1 + (rings - 1) * segments + 1;
    let id = |r: usize, s: usize| 2 + (r - 1) * segments + s % segments;
    let mut faces = String::new();
    for s in 0..segments {
        faces += &format!("f 1 {} {}\n", id(1, s), id(1, s + 1));
        faces += &format!("f {south} {} {}\n", id(rings - 1, s + 1), id(rings - 1, s));
        for r in 1..rings - 1 {
            let [a, b, c, d] = [id(r, s), id(r + 1, s), id(r + 1, s + 1), id(r, s + 1)];
            faces += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        }
    }
    let centres = [[1.5, 0.0, 0.0], [0.0, -1.5, 0.0], [0.0, 0.0, 1.5]];
    for (k, c) in centres.iter().enumerate() {
        let first = south + 1 + 4 * k;
        for [dx, dy] in [[0.0, 0.0], [0.05, 0.0], [0.05, 0.05], [0.0, 0.05]] {
            text += &format!("v {} {} {}\n", c[0] + dx, c[1] + dy, c[2]);
        }
        let [a, b, c, d] = [first, first + 1, first + 2, first + 3];
        faces += &format!("f {a} {b} {c}\nf {a} {c} {d}\nf {a} {c} {b}\nf {a} {d} {c}\n");
    }
    let input = text + &faces;
    assert_eq!(census(&input).3, 0, "the input is closed");
    let output = run(&input, "specks.obj", &["-a", "qem", "-p", "80"]);
    let points: Vec<[f64; 3]> = output
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    let (_, _, f, border) = census(&output);
    assert!(
        f < (2 * (rings - 1) * segments) / 2,
        "nothing decimated: {f} triangles"
    );
    assert_eq!(border, 0, "the result was opened");
    for c in centres {
        let near = points
            .iter()
            .any(|p| (0..3).all(|i| (p[i] - c[i]).abs() < 0.1));
        assert!(near, "the speck at {c:?} was deleted");
    }
}

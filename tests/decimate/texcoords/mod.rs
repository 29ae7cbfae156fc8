//! Texture coordinates survive decimation end to end: an OBJ with `vt` goes through the
//! binary with either algorithm and comes out with one coordinate pair per vertex that still
//! maps the surface as the input did, with every texture seam in place and closed (its two
//! sides pinned, so the surface never cracks along it). A PLY with per-vertex coordinates
//! comes out of qem as a PLY with one `s t` pair per vertex.

use crate::support::shapes::{split, Grid};
use std::collections::HashMap;
use std::process::Command;

mod charts;
mod formats;
mod grid;
mod lat_long;

/// An OBJ as read back by this test's own reader: positions, texture coordinates and
/// triangles as `(vertex, texcoord)` corners (0-based).
struct Obj {
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    triangles: Vec<[(usize, usize); 3]>,
}

/// The distinct points among `positions` (-0 and 0 as one): what counts name vertices, a
/// texture seam's copies of a point once.
fn distinct_positions(positions: &[[f32; 3]]) -> usize {
    (positions.iter())
        .map(|p| p.map(|c| (c + 0.0).to_bits()))
        .collect::<std::collections::HashSet<_>>()
        .len()
}

fn read_obj(text: &str) -> Obj {
    let mut obj = Obj {
        positions: Vec::new(),
        texcoords: Vec::new(),
        triangles: Vec::new(),
    };
    for line in text.lines() {
        let mut w = line.split_whitespace();
        let numbers = |w: std::str::SplitWhitespace| -> Vec<f32> {
            w.map(|x| x.parse().expect("a number")).collect()
        };
        match w.next() {
            Some("v") => {
                let n = numbers(w);
                obj.positions.push([n[0], n[1], n[2]]);
            }
            Some("vt") => {
                let n = numbers(w);
                obj.texcoords.push([n[0], n[1]]);
            }
            Some("f") => {
                let corners: Vec<(usize, usize)> = w
                    .map(|c| {
                        let (v, t) = c.split_once('/').expect("every corner has a vt");
                        (
                            v.parse::<usize>().unwrap() - 1,
                            t.parse::<usize>().unwrap() - 1,
                        )
                    })
                    .collect();
                assert_eq!(corners.len(), 3, "triangles only");
                obj.triangles.push([corners[0], corners[1], corners[2]]);
            }
            _ => {}
        }
    }
    obj
}

/// A grid of `n` × `n` squares over the unit square (each cut in two), its points at
/// `surface(x, y)`, textured by `uv(x, y)` and cut by a seam down x = 0.5: the squares right
/// of it map to a second island, `uv` shifted by 2 in u.
fn grid_obj(n: usize, surface: impl Fn(f32, f32) -> [f32; 3]) -> String {
    let mut text = String::new();
    let grid = Grid::square(n);
    let at = |i: usize| i as f32 / n as f32;
    for (i, j) in grid.points() {
        let [x, y, z] = surface(at(i), at(j));
        text += &format!("v {x} {y} {z}\n");
    }
    for island in 0..2 {
        for (i, j) in grid.points() {
            text += &format!("vt {} {}\n", at(i) + 2.0 * island as f32, at(j));
        }
    }
    for (i, _, square) in grid.squares() {
        let island = usize::from(i >= n / 2);
        let corner = |p: usize| format!("{}/{}", p + 1, p + 1 + island * grid.point_count());
        for t in split(square) {
            let [a, b, c] = t.map(corner);
            text += &format!("f {a} {b} {c}\n");
        }
    }
    text
}

/// Runs `decimate IN nogui ARGS -o OUT.obj` in a fresh directory; returns the output read back.
fn decimate(name: &str, obj: &str, args: &[&str]) -> Obj {
    let out = run(name, "obj", obj, args);
    read_obj(&String::from_utf8(out).expect("OBJ is text"))
}

/// Runs `decimate in.EXT nogui ARGS -o out.EXT` in a fresh directory; returns the output.
fn run(name: &str, ext: &str, input_text: &str, args: &[&str]) -> Vec<u8> {
    let dir =
        std::env::temp_dir().join(format!("decimate-texcoords-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (input, output) = (
        dir.join(format!("in.{ext}")),
        dir.join(format!("out.{ext}")),
    );
    std::fs::write(&input, input_text).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .arg(&input)
        .arg("nogui")
        .args(args)
        .arg("-o")
        .arg(&output)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "decimate failed: {stderr}");
    assert!(!stderr.contains("warning"), "unexpected warning: {stderr}");
    let out = std::fs::read(&output).expect("the output exists");
    std::fs::remove_dir_all(&dir).ok();
    out
}

/// Checks what every textured output must hold: one pair per vertex, numbered as the
/// vertices; no triangle spanning the two islands.
fn check_layout(out: &Obj) {
    assert_eq!(out.texcoords.len(), out.positions.len());
    for t in &out.triangles {
        for &(v, vt) in t {
            assert_eq!(v, vt, "the writer numbers pairs as vertices");
        }
        let islands: Vec<bool> = t
            .iter()
            .map(|&(_, vt)| out.texcoords[vt][0] > 1.5)
            .collect();
        assert!(
            islands.iter().all(|&i| i == islands[0]),
            "a triangle spans the seam: {t:?}"
        );
    }
}

/// How many vertices lie on the seam line x = 0.5, by island.
fn seam_vertices(out: &Obj) -> [usize; 2] {
    let mut count = [0; 2];
    for (p, uv) in out.positions.iter().zip(&out.texcoords) {
        if p[0] == 0.5 {
            count[usize::from(uv[0] > 1.5)] += 1;
        }
    }
    count
}

/// Checks the seam (x = 0.5) of an `n` × `n` grid, given as each output vertex's position
/// and texture pair: both algorithms take its two sides away in pairs (vertex removal
/// removes both, an edge collapse collapses both edges to one point), so it is simplified,
/// its sides holding the same points.
fn check_seam(vertices: impl Iterator<Item = ([f32; 3], [f32; 2])>, n: usize, label: &str) {
    let mut sides: [Vec<[u32; 3]>; 2] = [Vec::new(), Vec::new()];
    for (p, uv) in vertices {
        if p[0] == 0.5 {
            sides[usize::from(uv[0] > 1.5)].push(p.map(f32::to_bits));
        }
    }
    sides.iter_mut().for_each(|s| s.sort_unstable());
    assert_eq!(sides[0], sides[1], "{label}: the seam's sides part");
    assert!(
        sides[0].len() < n + 1,
        "{label}: the seam was not simplified ({} points)",
        sides[0].len()
    );
}

/// [`check_seam`] on an OBJ read back.
fn check_obj_seam(out: &Obj, n: usize, algorithm: &str) {
    let vertices = out
        .positions
        .iter()
        .copied()
        .zip(out.texcoords.iter().copied());
    check_seam(vertices, n, algorithm);
}

/// The triangles on each edge of `obj` once its vertices are welded by position: an edge
/// as the pair of its ends' first vertices at their positions, and its triangle count.
fn welded_edges(obj: &Obj) -> HashMap<(usize, usize), usize> {
    let mut first: HashMap<[u32; 3], usize> = HashMap::new();
    let welded: Vec<usize> = obj
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| *first.entry(p.map(f32::to_bits)).or_insert(i))
        .collect();
    let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
    for t in &obj.triangles {
        for k in 0..3 {
            let (a, b) = (welded[t[k].0], welded[t[(k + 1) % 3].0]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    edges
}

/// Calls `f(area, point, coordinates)` at four points of every triangle of `obj` (its
/// centre and a point leaning towards each corner), with the triangle's area: for
/// area-weighted means over the surface.
fn for_each_sample(obj: &Obj, mut f: impl FnMut(f64, [f64; 3], [f64; 2])) {
    for tri in &obj.triangles {
        let p = tri.map(|(v, _)| obj.positions[v].map(f64::from));
        let t = tri.map(|(_, t)| obj.texcoords[t].map(f64::from));
        let (e1, e2) = (sub(p[1], p[0]), sub(p[2], p[0]));
        let cross = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let area = 0.5 * cross.iter().map(|c| c * c).sum::<f64>().sqrt();
        for w in [
            [1.0 / 3.0; 3],
            [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
            [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
            [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
        ] {
            let point = [0, 1, 2].map(|k| w[0] * p[0][k] + w[1] * p[1][k] + w[2] * p[2][k]);
            let coordinates = [0, 1].map(|k| w[0] * t[0][k] + w[1] * t[1][k] + w[2] * t[2][k]);
            f(area, point, coordinates);
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Runs `command` (output discarded) and returns its exit status; fails the test, naming
/// `what`, when it runs for over two minutes (each run here takes well under a second).
fn run_for_at_most_two_minutes(mut command: Command, what: &str) -> std::process::ExitStatus {
    let mut child = command
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        if start.elapsed() > std::time::Duration::from_secs(120) {
            child.kill().ok();
            panic!("{what} did not finish in two minutes");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

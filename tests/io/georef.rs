//! Georeferenced input: a bumpy 0.35-unit scan patch written at the origin and far from it
//! (UTM-like and 1e7 coordinates), decimated by the binary with both algorithms. The far
//! runs' outputs, read back by this file's own parsers in f64 and moved back by the
//! translation, must be the origin run's output, and their f64 Hausdorff error no larger
//! than 1.1 times the origin run's. With f32 coordinates the patch at y = 1.2e6 was moved by
//! up to 0.06 by rounding alone (f32's step there is 0.125).

use std::path::Path;

use decimate_core::io::{read_scene, write_obj};

use crate::support::binary::decimate;
use crate::support::rng::Rng;

const N: usize = 33;
const SIZE: f64 = 0.35;
pub(super) const FAR: [[f64; 3]; 2] = [[3.0e5, 1.2e6, 50.0], [1.0e7, -1.0e7, 1.0e7]];

/// A mesh in f64: positions and triangles (0-based).
#[derive(Debug, Clone, Default)]
pub(super) struct Mesh {
    pub(super) points: Vec<[f64; 3]>,
    pub(super) triangles: Vec<[usize; 3]>,
}

/// The patch: a 33 x 33 grid with bumps and seeded noise of a few millimetres, 2048 triangles.
pub(super) fn patch(t: [f64; 3]) -> Mesh {
    grid_patch(N, t)
}

/// The patch as a grid of `n` x `n` points over the same square.
pub(super) fn grid_patch(n: usize, t: [f64; 3]) -> Mesh {
    let mut rng = Rng(53);
    let mut m = Mesh::default();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (
                i as f64 * SIZE / (n - 1) as f64,
                j as f64 * SIZE / (n - 1) as f64,
            );
            let bump = 0.01 * ((x * 40.0).sin() * (y * 30.0).cos());
            let z = bump + 0.002 * f64::from(rng.signed());
            m.points.push([x + t[0], y + t[1], z + t[2]]);
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i;
            m.triangles.push([a, a + 1, a + n + 1]);
            m.triangles.push([a, a + n + 1, a + n]);
        }
    }
    m
}

pub(super) fn write_input(m: &Mesh, path: &Path) {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let mut out: Vec<u8> = Vec::new();
    let (nv, nf) = (m.points.len(), m.triangles.len());
    let text = |out: &mut Vec<u8>, s: String| out.extend_from_slice(s.as_bytes());
    match ext {
        "obj" => {
            for [x, y, z] in &m.points {
                text(&mut out, format!("v {x} {y} {z}\n"));
            }
            for [a, b, c] in &m.triangles {
                text(&mut out, format!("f {} {} {}\n", a + 1, b + 1, c + 1));
            }
        }
        "off" => {
            text(&mut out, format!("OFF\n{nv} {nf} 0\n"));
            for [x, y, z] in &m.points {
                text(&mut out, format!("{x} {y} {z}\n"));
            }
            for [a, b, c] in &m.triangles {
                text(&mut out, format!("3 {a} {b} {c}\n"));
            }
        }
        _ => write_ply_input(m, path, &mut out),
    }
    std::fs::write(path, out).unwrap();
}

/// `*.ascii.ply` or `*.ply` (binary little-endian), with double coordinates.
fn write_ply_input(m: &Mesh, path: &Path, out: &mut Vec<u8>) {
    let ascii = path.to_string_lossy().ends_with(".ascii.ply");
    let format = if ascii {
        "ascii"
    } else {
        "binary_little_endian"
    };
    out.extend_from_slice(
        format!(
            "ply\nformat {format} 1.0\nelement vertex {}\nproperty double x\n\
             property double y\nproperty double z\nelement face {}\n\
             property list uchar int vertex_indices\nend_header\n",
            m.points.len(),
            m.triangles.len()
        )
        .as_bytes(),
    );
    for p in &m.points {
        if ascii {
            out.extend_from_slice(format!("{} {} {}\n", p[0], p[1], p[2]).as_bytes());
        } else {
            p.iter()
                .for_each(|v| out.extend_from_slice(&v.to_le_bytes()));
        }
    }
    for t in &m.triangles {
        if ascii {
            out.extend_from_slice(format!("3 {} {} {}\n", t[0], t[1], t[2]).as_bytes());
        } else {
            out.push(3);
            t.iter()
                .for_each(|&v| out.extend_from_slice(&(v as i32).to_le_bytes()));
        }
    }
}

/// Reads our output back with a parser of a few lines per format, in f64.
pub(super) fn read_output(path: &Path) -> Mesh {
    let bytes = std::fs::read(path).unwrap();
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    if ext == "ply" {
        return read_binary_ply(&bytes);
    }
    let text = String::from_utf8(bytes).unwrap();
    let num = |w: &str| w.parse::<f64>().unwrap();
    let mut m = Mesh::default();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    if ext == "off" {
        assert_eq!(lines.next(), Some("OFF"));
        let counts: Vec<usize> = lines
            .next()
            .unwrap()
            .split(' ')
            .map(|w| w.parse().unwrap())
            .collect();
        for _ in 0..counts[0] {
            let w: Vec<f64> = lines.next().unwrap().split(' ').map(num).collect();
            m.points.push([w[0], w[1], w[2]]);
        }
        for _ in 0..counts[1] {
            let w: Vec<usize> = lines
                .next()
                .unwrap()
                .split(' ')
                .map(|w| w.parse().unwrap())
                .collect();
            assert_eq!(w[0], 3);
            m.triangles.push([w[1], w[2], w[3]]);
        }
        return m;
    }
    for l in lines {
        let w: Vec<&str> = l.split(' ').collect();
        match w[0] {
            "v" => m.points.push([num(w[1]), num(w[2]), num(w[3])]),
            "f" => m
                .triangles
                .push([1, 2, 3].map(|k| w[k].parse::<usize>().unwrap() - 1)),
            _ => {}
        }
    }
    m
}

/// Our PLY output: binary little-endian, x y z as doubles (or floats), triangles as
/// `uchar int` lists.
fn read_binary_ply(bytes: &[u8]) -> Mesh {
    let end = b"end_header\n";
    let at = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
    let header = std::str::from_utf8(&bytes[..at]).unwrap();
    let count = |name: &str| -> usize {
        let line = header.lines().find(|l| l.starts_with(name)).unwrap();
        line.rsplit(' ').next().unwrap().parse().unwrap()
    };
    let (nv, nf) = (count("element vertex"), count("element face"));
    let double = header.contains("property double x");
    assert!(
        !header.contains("property uchar red"),
        "no colours expected"
    );
    let mut pos = at;
    let mut m = Mesh::default();
    for _ in 0..nv {
        m.points.push(std::array::from_fn(|_| {
            if double {
                pos += 8;
                f64::from_le_bytes(bytes[pos - 8..pos].try_into().unwrap())
            } else {
                pos += 4;
                f64::from(f32::from_le_bytes(bytes[pos - 4..pos].try_into().unwrap()))
            }
        }));
    }
    for _ in 0..nf {
        assert_eq!(bytes[pos], 3);
        pos += 1;
        m.triangles.push(std::array::from_fn(|_| {
            pos += 4;
            i32::from_le_bytes(bytes[pos - 4..pos].try_into().unwrap()) as usize
        }));
    }
    assert_eq!(pos, bytes.len());
    m
}

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Distance from `p` to triangle `abc` (Ericson's closest-point regions, in f64).
fn point_triangle(p: [f64; 3], [a, b, c]: [[f64; 3]; 3]) -> f64 {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let lerp =
        |o: [f64; 3], d: [f64; 3], s: f64| [o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]];
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let q = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        let cp = sub(p, c);
        let (d5, d6) = (dot(ab, cp), dot(ac, cp));
        let (va, vb, vc) = (d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2);
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else if d6 >= 0.0 && d5 <= d6 {
            c
        } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            lerp(a, ab, d1 / (d1 - d3))
        } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            lerp(a, ac, d2 / (d2 - d6))
        } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
            lerp(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))
        } else {
            let denom = 1.0 / (va + vb + vc);
            lerp(lerp(a, ab, vb * denom), ac, vc * denom)
        }
    };
    dot(sub(p, q), sub(p, q)).sqrt()
}

/// Each vertex and 3 interior points per triangle of `from`, to their nearest point of `to`
/// (brute force over the triangles, skipping those whose bounding sphere is farther than the
/// best so far: the meshes have a few thousand triangles).
fn one_sided(from: &Mesh, to: &Mesh) -> f64 {
    let tri = |m: &Mesh, t: [usize; 3]| t.map(|v| m.points[v]);
    let mut samples = from.points.clone();
    for &t in &from.triangles {
        let [a, b, c] = tri(from, t);
        for (u, v) in [(1.0 / 3.0, 1.0 / 3.0), (0.6, 0.2), (0.2, 0.6)] {
            samples.push(std::array::from_fn(|k| {
                a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k])
            }));
        }
    }
    let spheres: Vec<([f64; 3], f64)> = (to.triangles.iter())
        .map(|&t| {
            let [a, b, c] = tri(to, t);
            let m: [f64; 3] = std::array::from_fn(|k| (a[k] + b[k] + c[k]) / 3.0);
            let r = [a, b, c].map(|q| dot(sub(q, m), sub(q, m)).sqrt());
            (m, r[0].max(r[1]).max(r[2]))
        })
        .collect();
    let nearest = |p: [f64; 3]| {
        let mut best = f64::INFINITY;
        for (&t, &(m, r)) in to.triangles.iter().zip(&spheres) {
            if dot(sub(p, m), sub(p, m)).sqrt() - r < best {
                best = best.min(point_triangle(p, tri(to, t)));
            }
        }
        best
    };
    samples.into_iter().map(nearest).fold(0.0, f64::max)
}

pub(super) fn hausdorff(a: &Mesh, b: &Mesh) -> f64 {
    one_sided(a, b).max(one_sided(b, a))
}

/// Asserts that `far` (a far run's output, moved back to the origin) is `near` (the origin
/// run's), and its error against `input` at most 1.1 times the origin run's.
pub(super) fn assert_lands_like_the_origin_run(what: &str, input: &Mesh, near: &Mesh, far: &Mesh) {
    assert_same_as_the_origin_run(what, near, far);
    let (far_error, near_error) = (hausdorff(input, far), hausdorff(input, near));
    assert!(
        far_error <= 1.1 * near_error,
        "{what}: error {far_error} against {near_error} at the origin"
    );
}

/// Asserts that `far` (moved back to the origin) has `near`'s triangles and every point
/// within 1e-6 of `near`'s.
pub(super) fn assert_same_as_the_origin_run(what: &str, near: &Mesh, far: &Mesh) {
    assert!(
        far.triangles == near.triangles,
        "{what}: {} triangles, other than the {} at the origin",
        far.triangles.len(),
        near.triangles.len()
    );
    for (p, q) in far.points.iter().zip(&near.points) {
        let d = dot(sub(*p, *q), sub(*p, *q)).sqrt();
        assert!(d < 1e-6, "{what}: {p:?} against {q:?}");
    }
}

/// Runs the binary on the patch at `t` and returns its output moved back by `t`.
fn run(dir: &Path, file: &str, t: [f64; 3], algorithm: &[&str]) -> Mesh {
    let input = dir.join(file);
    write_input(&patch(t), &input);
    let ext = input.extension().unwrap().to_str().unwrap();
    decimated_moved_back(dir, file, &format!("out.{ext}"), t, algorithm)
}

/// `decimate FILE nogui -p 80 -o OUTPUT ALGORITHM` in `dir`, which must succeed, and its
/// output read back and moved by `-t`.
pub(super) fn decimated_moved_back(
    dir: &Path,
    file: &str,
    output: &str,
    t: [f64; 3],
    algorithm: &[&str],
) -> Mesh {
    let mut args = vec![file, "nogui", "-p", "80", "-o", output];
    args.extend_from_slice(algorithm);
    let out = decimate(dir, &args);
    assert!(
        out.status.success(),
        "{file}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut m = read_output(&dir.join(output));
    for p in &mut m.points {
        *p = sub(*p, t);
    }
    m
}

#[test]
fn a_far_patch_decimates_as_it_does_at_the_origin_in_every_text_and_binary_format() {
    let dir = tempfile::tempdir().unwrap();
    let input = patch([0.0; 3]);
    for file in ["patch.ascii.ply", "patch.ply", "patch.obj", "patch.off"] {
        for algorithm in [&[][..], &["-a", "qem"][..]] {
            let what = format!("{file} {algorithm:?}");
            let near = run(dir.path(), file, [0.0; 3], algorithm);
            assert!(
                near.triangles.len() > 250 && near.triangles.len() < 500,
                "{what}"
            );
            for t in FAR {
                let far = run(dir.path(), file, t, algorithm);
                assert_lands_like_the_origin_run(&format!("{what} at {t:?}"), &input, &near, &far);
            }
        }
    }
}

#[test]
fn far_coordinates_are_kept_relative_to_an_origin_and_written_back_with_their_digits() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("far.obj");
    let text = "v 300000.125 1200000.35 50.5\nv 300000.475 1200000.35 50.5\n\
                v 300000.125 1200000.7 50.25\nf 1 2 3\n";
    std::fs::write(&src, text).unwrap();
    let scene = read_scene(&src).unwrap().scene;
    let m = &scene.models[0];
    assert_eq!(m.origin.to_array(), [300000.0, 1200000.0, 51.0]);
    // Relative to the origin, the positions are small and exact to f32's resolution there.
    let p = m.positions[0];
    assert!(
        (p.y - 0.35).abs() < 1e-7 && (p.z + 0.5).abs() < 1e-7,
        "{p:?}"
    );
    let out = dir.path().join("back.obj");
    write_obj(&scene, &out).unwrap();
    let written: Vec<String> = std::fs::read_to_string(&out)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(str::to_string)
        .collect();
    let expected: Vec<&str> = text.lines().filter(|l| l.starts_with("v ")).collect();
    assert_eq!(written, expected);
}

#[test]
fn a_patch_near_zero_keeps_a_zero_origin() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("near.obj");
    std::fs::write(&src, "v 8191 0 0\nv 8192 0 0\nv 8191 1 0\nf 1 2 3\n").unwrap();
    let m = &read_scene(&src).unwrap().scene.models[0];
    assert_eq!(m.origin.to_array(), [0.0; 3]);
    assert_eq!(m.positions[1].x, 8192.0);
}

#[test]
fn binary_stl_output_of_a_far_model_warns_that_it_rounds() {
    let dir = tempfile::tempdir().unwrap();
    write_input(&patch(FAR[0]), &dir.path().join("far.obj"));
    let out = decimate(
        dir.path(),
        &["far.obj", "nogui", "-p", "50", "-o", "far.stl"],
    );
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("binary STL holds 32-bit coordinates"),
        "{stderr}"
    );
    // The same patch near zero says nothing of the kind.
    write_input(&patch([0.0; 3]), &dir.path().join("near.obj"));
    let out = decimate(
        dir.path(),
        &["near.obj", "nogui", "-p", "50", "-o", "near.stl"],
    );
    assert!(!String::from_utf8_lossy(&out.stderr).contains("32-bit"));
}

#[test]
fn gltf_output_puts_a_far_origin_in_a_node_translation() {
    let dir = tempfile::tempdir().unwrap();
    write_input(&patch(FAR[0]), &dir.path().join("far.obj"));
    let out = decimate(
        dir.path(),
        &["far.obj", "nogui", "-p", "50", "-o", "far.gltf"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("far.gltf")).unwrap()).unwrap();
    let nodes = json["nodes"].as_array().unwrap();
    let origin = nodes.iter().find_map(|n| n.get("translation")).unwrap();
    assert_eq!(origin, &serde_json::json!([300000.0, 1200000.0, 50.0]));
}

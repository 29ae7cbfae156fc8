//! Text encodings through tiling's streamed readers (`--tiles`, which never hold the whole
//! file) and through the ordinary readers: OBJ, PLY (ASCII, and binary with a CR-only
//! header), STL (ASCII, and binary with a header that looks like text) and OFF (of
//! triangles, of quads) with a UTF-8
//! byte-order mark, CR-only or CRLF line ends, or in UTF-16 or UTF-32. Both runs must give
//! the same: the same triangles at `-p 0` (read back from the PLY outputs in f64 and
//! compared as sets, so a binary body's 0x0D bytes taken for line ends would show), or the
//! same refusal, exit 1, naming the file and the line.

use std::path::Path;
use std::process::Output;

use crate::georef::{read_output, Mesh};
use crate::support::binary::decimate;

/// What a file must give, tiled or not.
enum Expect {
    /// Read whole: this many triangles out at `-p 0`.
    Triangles(usize),
    /// Refused: exit 1, saying this (the file name, the line, what is wrong).
    Refused(&'static str),
}

/// A grid of 6 x 6 squares as OBJ text (72 triangles), with a last face naming vertex
/// `bad` when given.
fn grid_obj(bad: Option<u32>) -> String {
    let (points, triangles) = grid();
    let mut s = String::from("# a grid\n");
    points
        .iter()
        .for_each(|p| s += &format!("v {} {} {}\n", p[0], p[1], p[2]));
    for t in &triangles {
        s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    if let Some(bad) = bad {
        s += &format!("f 1 2 {bad}\n");
    }
    s
}

/// The grid as OFF text: its squares as quads when `quads`, and a last face naming vertex
/// `bad` when given. (A coloured OFF's whole read keeps its colours, which tiles do not:
/// `io::off`'s own tests stream one.)
fn grid_off(quads: bool, bad: Option<u32>) -> String {
    let (points, triangles) = grid();
    let faces = triangles.len() / if quads { 2 } else { 1 } + usize::from(bad.is_some());
    let mut s = format!("OFF\n# a grid\n{} {faces} 0\n", points.len());
    points
        .iter()
        .for_each(|p| s += &format!("{} {} {}\n", p[0], p[1], p[2]));
    if quads {
        for t in triangles.chunks(2) {
            let [a, b, c] = t[0];
            s += &format!("4 {a} {b} {c} {}\n", t[1][2]);
        }
    } else {
        for t in &triangles {
            s += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
        }
    }
    if let Some(bad) = bad {
        s += &format!("3 0 1 {bad}\n");
    }
    s
}

/// The grid as ASCII PLY.
fn grid_ply_ascii() -> String {
    let (points, triangles) = grid();
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar int vertex_indices\n\
         end_header\n",
        points.len(),
        triangles.len()
    );
    points
        .iter()
        .for_each(|p| s += &format!("{} {} {}\n", p[0], p[1], p[2]));
    triangles
        .iter()
        .for_each(|t| s += &format!("3 {} {} {}\n", t[0], t[1], t[2]));
    s
}

/// A grid of 6 x 6 squares, each split in two: its points and triangles. Its heights are
/// made of bytes 0x0D (a carriage return) and 0x0A, and vertex 13 is used, so that a binary
/// body read as text would change.
fn grid() -> (Vec<[f32; 3]>, Vec<[i32; 3]>) {
    let n = 7;
    let lift = f32::from_le_bytes([0x0D, 0x0D, 0x0A, 0x3D]);
    let mut points = Vec::new();
    for j in 0..n {
        for i in 0..n {
            points.push([i as f32, j as f32, lift * ((i * j) % 3) as f32]);
        }
    }
    let mut triangles = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i;
            triangles.push([a, a + 1, a + n + 1]);
            triangles.push([a, a + n + 1, a + n]);
        }
    }
    (points, triangles)
}

/// The grid as binary little-endian PLY, its header's lines ended by lone carriage returns.
fn grid_ply_binary_cr() -> Vec<u8> {
    let (points, triangles) = grid();
    let header = format!(
        "ply\rformat binary_little_endian 1.0\relement vertex {}\rproperty float x\r\
         property float y\rproperty float z\relement face {}\r\
         property list uchar int vertex_indices\rend_header\r",
        points.len(),
        triangles.len()
    );
    let mut b = header.into_bytes();
    points
        .iter()
        .flatten()
        .for_each(|x| b.extend(x.to_le_bytes()));
    for t in &triangles {
        b.push(3);
        t.iter().for_each(|i| b.extend(i.to_le_bytes()));
    }
    b
}

/// The grid's triangles as corner points.
fn grid_triangles() -> Vec<[[f32; 3]; 3]> {
    let (points, triangles) = grid();
    triangles
        .iter()
        .map(|t| t.map(|i| points[i as usize]))
        .collect()
}

/// The grid as ASCII STL.
fn grid_stl_ascii() -> String {
    let mut s = String::from("solid grid\n");
    for t in grid_triangles() {
        s += "facet normal 0 0 1\nouter loop\n";
        t.iter()
            .for_each(|p| s += &format!("vertex {} {} {}\n", p[0], p[1], p[2]));
        s += "endloop\nendfacet\n";
    }
    s + "endsolid grid\n"
}

/// The grid as binary STL whose 80-byte header starts like UTF-8 text with a byte-order
/// mark and `solid`, with lone carriage returns in it.
fn grid_stl_binary() -> Vec<u8> {
    let triangles = grid_triangles();
    let mut b = b"\xEF\xBB\xBFsolid grid\r\rmade by hand\r".to_vec();
    b.resize(80, b'\r');
    b.extend((triangles.len() as u32).to_le_bytes());
    for t in &triangles {
        [0f32, 0., 1.]
            .iter()
            .for_each(|x| b.extend(x.to_le_bytes()));
        t.iter().flatten().for_each(|x| b.extend(x.to_le_bytes()));
        b.extend([0x0D, 0x0D]);
    }
    b
}

fn with_bom(text: &str) -> Vec<u8> {
    [&[0xEF, 0xBB, 0xBF][..], text.as_bytes()].concat()
}

fn cr(text: &str) -> String {
    text.replace('\n', "\r")
}

fn utf16(text: &str, big: bool) -> Vec<u8> {
    let mut b = if big {
        vec![0xFE, 0xFF]
    } else {
        vec![0xFF, 0xFE]
    };
    for u in text.encode_utf16() {
        b.extend(if big {
            u.to_be_bytes()
        } else {
            u.to_le_bytes()
        });
    }
    b
}

fn utf32(text: &str) -> Vec<u8> {
    let mut b = vec![0xFF, 0xFE, 0, 0];
    text.chars()
        .for_each(|c| b.extend((c as u32).to_le_bytes()));
    b
}

/// The output's triangles as sets of corner points (each listed from its smallest corner
/// on, the list sorted): the same surface gives the same list whatever the order and the
/// vertex numbering.
fn triangle_set(m: &Mesh) -> Vec<[[u64; 3]; 3]> {
    let mut out: Vec<[[u64; 3]; 3]> = m
        .triangles
        .iter()
        .map(|t| {
            let c = t.map(|i| m.points[i].map(f64::to_bits));
            let first = (0..3).min_by_key(|&k| c[k]).unwrap_or(0);
            [c[first], c[(first + 1) % 3], c[(first + 2) % 3]]
        })
        .collect();
    out.sort_unstable();
    out
}

fn said(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs one case whole and tiled; what is wrong, if anything.
fn check(dir: &Path, name: &str, expect: &Expect) -> Option<String> {
    let whole = decimate(dir, &[name, "nogui", "-p", "0", "-o", "whole.ply"]);
    let tiled = decimate(
        dir,
        &[
            name,
            "nogui",
            "--tiles",
            "2",
            "--memory",
            "1M",
            "-p",
            "0",
            "-o",
            "tiled.ply",
        ],
    );
    match *expect {
        Expect::Triangles(n) => {
            if !whole.status.success() || !tiled.status.success() {
                return Some(format!(
                    "{name}: refused: whole {}, tiled {}",
                    said(&whole),
                    said(&tiled)
                ));
            }
            let whole = triangle_set(&read_output(&dir.join("whole.ply")));
            let tiled = triangle_set(&read_output(&dir.join("tiled.ply")));
            if whole.len() != n || tiled.len() != n {
                return Some(format!(
                    "{name}: {} triangles whole, {} tiled, not {n}",
                    whole.len(),
                    tiled.len()
                ));
            }
            (whole != tiled).then(|| format!("{name}: the tiled triangles are other ones"))
        }
        Expect::Refused(what) => {
            let bad = |o: &Output| o.status.code() != Some(1) || !said(o).contains(what);
            (bad(&whole) || bad(&tiled)).then(|| {
                format!(
                    "{name}: expected exit 1 saying '{what}'; whole: {:?} {}; tiled: {:?} {}",
                    whole.status.code(),
                    said(&whole),
                    tiled.status.code(),
                    said(&tiled)
                )
            })
        }
    }
}

#[test]
fn tiled_and_whole_reads_agree_on_marks_line_ends_and_wide_text() {
    use Expect::*;
    let obj = grid_obj(None);
    let ply = grid_ply_ascii();
    let stl = grid_stl_ascii();
    let off = grid_off(false, None);
    let bad = cr(&grid_obj(Some(99)));
    // The bad face is the last line: 1 comment, 49 vertices, 72 faces, then it.
    let cases: Vec<(&str, Vec<u8>, Expect)> = vec![
        ("plain.obj", obj.clone().into(), Triangles(72)),
        ("cr.obj", cr(&obj).into(), Triangles(72)),
        ("crlf.obj", obj.replace('\n', "\r\n").into(), Triangles(72)),
        ("bom.obj", with_bom(&obj), Triangles(72)),
        ("bom_cr.obj", with_bom(&cr(&obj)), Triangles(72)),
        (
            "cr_range.obj",
            bad.into(),
            Refused("cr_range.obj:123: vertex index 99 is out of range"),
        ),
        (
            "utf16.obj",
            utf16(&obj, false),
            Refused("utf16.obj:1: the file is UTF-16 text"),
        ),
        (
            "utf16be.obj",
            utf16(&obj, true),
            Refused("utf16be.obj:1: the file is UTF-16 text"),
        ),
        (
            "utf32.obj",
            utf32(&obj),
            Refused("utf32.obj:1: the file is UTF-32 text"),
        ),
        ("ascii.ply", ply.clone().into(), Triangles(72)),
        ("cr.ply", cr(&ply).into(), Triangles(72)),
        ("bom_cr.ply", with_bom(&cr(&ply)), Triangles(72)),
        ("binary_cr.ply", grid_ply_binary_cr(), Triangles(72)),
        (
            "utf16.ply",
            utf16(&ply, false),
            Refused("utf16.ply:1: the file is UTF-16 text"),
        ),
        ("ascii.stl", stl.clone().into(), Triangles(72)),
        ("cr.stl", cr(&stl).into(), Triangles(72)),
        ("bom.stl", with_bom(&stl), Triangles(72)),
        ("binary.stl", grid_stl_binary(), Triangles(72)),
        (
            "utf16.stl",
            utf16(&stl, false),
            Refused("utf16.stl:1: the file is UTF-16 text"),
        ),
        ("plain.off", off.clone().into(), Triangles(72)),
        ("cr.off", cr(&off).into(), Triangles(72)),
        ("crlf.off", off.replace('\n', "\r\n").into(), Triangles(72)),
        ("bom.off", with_bom(&off), Triangles(72)),
        ("quads.off", grid_off(true, None).into(), Triangles(72)),
        // 2 header lines, 1 comment, 49 vertices, 72 faces, then the bad one.
        (
            "cr_range.off",
            cr(&grid_off(false, Some(99))).into(),
            Refused("cr_range.off:125: face 72: vertex index '99' is not in 0..49"),
        ),
        (
            "utf16.off",
            utf16(&off, false),
            Refused("utf16.off:1: the file is UTF-16 text"),
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    let mut wrong = Vec::new();
    for (name, bytes, expect) in &cases {
        std::fs::write(dir.path().join(name), bytes).unwrap();
        wrong.extend(check(dir.path(), name, expect));
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

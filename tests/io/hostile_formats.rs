//! Hostile and odd files of every format but VRML (PLY ascii and binary both ways, OBJ, STL
//! ascii and binary, OFF, glTF and GLB, `.pm`), run through the binary with both algorithms
//! under a watch: no crash, no run past [`TIME_LIMIT`] or [`MEMORY_LIMIT`], every refusal an
//! exit 1 naming the file and where (line, byte, JSON path), every valid file read whole
//! (its vertex and triangle counts, as the binary reports them at `-p 0`). Header counts far
//! larger than the file, indices out of range, non-finite coordinates, faces of 0 to 2 and
//! of 20,000 corners, deep JSON, lying chunk and accessor lengths, damaged data URIs, byte
//! order marks, NUL bytes, CR-only and CRLF line ends, extra PLY properties and elements,
//! OBJ relative indices and line continuations, binary STL headers starting with "solid".

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

/// The longest one run may take (debug build, loaded machine; release runs take under 1 s).
const TIME_LIMIT: Duration = Duration::from_secs(30);

/// The most resident memory one run may reach.
const MEMORY_LIMIT: u64 = 1 << 30;

/// What a file must give.
enum Expect {
    /// Read whole: this many vertices and triangles in.
    Read(usize, usize),
    /// Read whole, with a warning that says this.
    ReadWarned(usize, usize, &'static str),
    /// Refused: exit 1, the message names the file and says this (a line, a byte, a
    /// JSON path and what is wrong).
    Refused(&'static str),
    /// Not run: a file the others refer to.
    Beside,
}

/// A file to write into the test's folder and what it must give.
struct Case {
    name: &'static str,
    bytes: Vec<u8>,
    expect: Expect,
}

fn case(name: &'static str, bytes: impl Into<Vec<u8>>, expect: Expect) -> Case {
    Case {
        name,
        bytes: bytes.into(),
        expect,
    }
}

/// What one watched run gave.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    peak: u64,
    took: Duration,
}

/// The peak resident memory of process `pid` so far (bytes; 0 where /proc says nothing).
fn peak_memory(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// Runs `decimate FILE nogui -p 0 -a ALGORITHM -o out.ply` in `dir` (see [`watched_to`]).
fn watched(dir: &Path, file: &str, algorithm: &str) -> Run {
    watched_to(dir, file, algorithm, "out.ply")
}

/// Runs `decimate FILE nogui -p 0 -a ALGORITHM -o OUT` in `dir`, killed past the time or
/// memory limit; the peak memory is sampled every few milliseconds.
fn watched_to(dir: &Path, file: &str, algorithm: &str, out: &str) -> Run {
    let mut child = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args([file, "nogui", "-p", "0", "-a", algorithm, "-o", out])
        .env_remove("DECIMATE_ALLOW_OUTSIDE")
        .env_remove("DECIMATE_MAX_FILE_BYTES")
        .env_remove("DECIMATE_MAX_TRIANGLES")
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot run decimate: {e}"));
    // Drained on their own threads, so a full pipe never stalls the child.
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = Vec::new();
            let _ = r.read_to_end(&mut s);
            String::from_utf8_lossy(&s).into_owned()
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("piped stdout")));
    let err = drain(Box::new(child.stderr.take().expect("piped stderr")));
    let start = Instant::now();
    let mut peak = 0;
    let code = loop {
        peak = peak.max(peak_memory(child.id()));
        if let Some(status) = child.try_wait().expect("wait for decimate") {
            break status.code();
        }
        if start.elapsed() > TIME_LIMIT || peak > MEMORY_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(3));
    };
    Run {
        code,
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
        peak,
        took: start.elapsed(),
    }
}

/// The report's `total: vertices A -> B, triangles C -> D` line's A and C.
fn counts_in(stdout: &str) -> Option<(usize, usize)> {
    let line = stdout.lines().find(|l| l.starts_with("total: vertices"))?;
    let words: Vec<&str> = line.split([' ', ',']).filter(|w| !w.is_empty()).collect();
    let vertices = words.get(2)?.parse().ok()?;
    let triangles = words.get(6)?.parse().ok()?;
    Some((vertices, triangles))
}

/// What is wrong with `run` of `c` (none: `None`).
fn judge(c: &Case, algorithm: &str, run: &Run) -> Option<String> {
    let head = format!(
        "{} ({algorithm}, {:.1?}, {} MiB)",
        c.name,
        run.took,
        run.peak >> 20
    );
    let Some(code) = run.code else {
        return Some(format!("{head}: killed or crashed: {}", run.stderr));
    };
    match c.expect {
        Expect::Read(v, t) | Expect::ReadWarned(v, t, _) => {
            if code != 0 {
                return Some(format!("{head}: refused: {}", run.stderr));
            }
            let got = counts_in(&run.stderr).or_else(|| counts_in(&run.stdout));
            if got != Some((v, t)) {
                return Some(format!("{head}: read {got:?}, not ({v}, {t})"));
            }
            if let Expect::ReadWarned(_, _, what) = c.expect {
                if !run.stderr.contains(what) {
                    return Some(format!("{head}: no warning '{what}': {}", run.stderr));
                }
            }
            None
        }
        Expect::Beside => None,
        Expect::Refused(what) => {
            let named = run.stderr.contains(c.name);
            (code != 1 || !named || !run.stderr.contains(what)).then(|| {
                format!(
                    "{head}: exit {code}, expected 1 naming the file and saying '{what}': {}",
                    run.stderr
                )
            })
        }
    }
}

/// Writes every case into a fresh folder (beside an empty folder `sub`) and runs each with
/// both algorithms; panics with the list of everything wrong.
fn check_all(cases: Vec<Case>) {
    let dir = tempfile::tempdir().expect("temporary folder");
    std::fs::create_dir(dir.path().join("sub")).expect("a folder");
    for c in &cases {
        let path = dir.path().join(c.name);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).expect("a case's folder");
        }
        std::fs::write(&path, &c.bytes).expect("a case's file");
    }
    let mut wrong = Vec::new();
    for c in cases.iter().filter(|c| !matches!(c.expect, Expect::Beside)) {
        for algorithm in ["schroeder", "qem"] {
            let run = watched(dir.path(), c.name, algorithm);
            if run.peak > MEMORY_LIMIT {
                wrong.push(format!("{}: {} MiB", c.name, run.peak >> 20));
            }
            wrong.extend(judge(c, algorithm, &run));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

const PLY_VERTEX: &str = "property float x\nproperty float y\nproperty float z\n";
const QUAD: &str = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
const FACE_LIST: &str = "property list uchar int vertex_indices\n";

/// An ASCII PLY header of `vertices` and `faces`.
fn ply_header(format: &str, vertices: u64, faces: u64) -> String {
    format!(
        "ply\nformat {format} 1.0\nelement vertex {vertices}\n{PLY_VERTEX}\
         element face {faces}\n{FACE_LIST}end_header\n"
    )
}

/// A binary PLY (`big` endian or little) of `points` and `faces` with the header's counts
/// `counts` (vertices, faces), which may lie.
fn binary_ply(big: bool, counts: (u64, u64), points: &[[f32; 3]], faces: &[&[i32]]) -> Vec<u8> {
    let format = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut b = ply_header(format, counts.0, counts.1).into_bytes();
    let f32s = |v: f32| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let i32s = |v: i32| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    for p in points {
        p.iter().for_each(|&x| b.extend(f32s(x)));
    }
    for f in faces {
        b.push(f.len() as u8);
        f.iter().for_each(|&i| b.extend(i32s(i)));
    }
    b
}

const SQUARE: [[f32; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];

/// A binary little-endian PLY of one polygon of `n` corners on a circle (`int` list
/// counts): n − 2 triangles.
fn ply_polygon(n: usize) -> Vec<u8> {
    let header = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {n}\n{PLY_VERTEX}\
         element face 1\nproperty list int int vertex_indices\nend_header\n"
    );
    let mut b = header.into_bytes();
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        for x in [a.cos() as f32, a.sin() as f32, 0.0] {
            b.extend(x.to_le_bytes());
        }
    }
    b.extend((n as i32).to_le_bytes());
    (0..n as i32).for_each(|i| b.extend(i.to_le_bytes()));
    b
}

fn utf16(text: &str) -> Vec<u8> {
    let mut b = vec![0xFF, 0xFE];
    text.encode_utf16().for_each(|u| b.extend(u.to_le_bytes()));
    b
}

fn with_bom(text: &str) -> Vec<u8> {
    [&[0xEF, 0xBB, 0xBF][..], text.as_bytes()].concat()
}

#[test]
fn hostile_and_odd_ply_files() {
    use Expect::*;
    let quad = format!("{}{QUAD}3 0 1 2\n3 0 2 3\n", ply_header("ascii", 4, 2));
    // 255 corners a face, 2,000 faces, all of them the same four points over and over.
    let mut face = vec![255u8];
    (0..255).for_each(|i: i32| face.extend((i % 4).to_le_bytes()));
    let list255 = [
        binary_ply(false, (4, 2000), &SQUARE, &[]),
        face.repeat(2000),
    ]
    .concat();
    let extra = format!(
        "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\n{PLY_VERTEX}\
         property float nx\nproperty uchar flag\nelement face 2\n{FACE_LIST}property int tag\n\
         element edge 1\nproperty int a\nproperty int b\nelement material 0\nproperty float r\n\
         end_header\n0 0 0 0 1\n1 0 0 0 1\n1 1 0 0 1\n0 1 0 0 1\n3 0 1 2 7\n3 0 2 3 8\n0 1\n"
    );
    let nan = [
        [0., 0., 0.],
        [f32::NAN, 0., 0.],
        [1., f32::INFINITY, 0.],
        [0., 1., 0.],
    ];
    check_all(vec![
        case("ascii.ply", quad.clone(), Read(4, 2)),
        case(
            "le.ply",
            binary_ply(false, (4, 2), &SQUARE, &[&[0, 1, 2], &[0, 2, 3]]),
            Read(4, 2),
        ),
        case(
            "be.ply",
            binary_ply(true, (4, 2), &SQUARE, &[&[0, 1, 2], &[0, 2, 3]]),
            Read(4, 2),
        ),
        case("extra.ply", extra, Read(4, 2)),
        case("crlf.ply", quad.replace('\n', "\r\n"), Read(4, 2)),
        case("cr.ply", quad.replace('\n', "\r"), Read(4, 2)),
        case("bom.ply", with_bom(&quad), Read(4, 2)),
        case("polygon.ply", ply_polygon(20_000), Read(20_000, 19_998)),
        case(
            "short.ply",
            format!(
                "{}{QUAD}0\n1 0\n2 0 1\n3 0 1 2\n",
                ply_header("ascii", 4, 4)
            ),
            ReadWarned(3, 1, "3 face(s) with fewer than 3 corners skipped"),
        ),
        case("list255.ply", list255, Read(4, 2)),
        case(
            "huge.ply",
            format!("{}{QUAD}3 0 1 2\n", ply_header("ascii", 4_000_000_000, 2)),
            Refused("vertex 0 of 4000000000"),
        ),
        case(
            "huge_le.ply",
            binary_ply(false, (4_000_000_000, 2), &SQUARE, &[&[0, 1, 2]]),
            Refused("of 4000000000"),
        ),
        case(
            "huge_be.ply",
            binary_ply(true, (4, 4_000_000_000), &SQUARE, &[&[0, 1, 2]]),
            Refused("huge_be.ply:10: unexpected end of file: the PLY body ends inside face 0 of"),
        ),
        case(
            "range.ply",
            format!("{}{QUAD}3 0 1 9\n3 0 2 3\n", ply_header("ascii", 4, 2)),
            Refused("index 9 in 'vertex_indices' is out of range"),
        ),
        case(
            "negative.ply",
            format!("{}{QUAD}3 0 1 -1\n3 0 2 3\n", ply_header("ascii", 4, 2)),
            Refused("negative.ply:14: expected a non-negative integer"),
        ),
        case(
            "big_index.ply",
            binary_ply(false, (4, 1), &SQUARE, &[&[0, 1, i32::MAX]]),
            Refused("index 2147483647"),
        ),
        case(
            "nan.ply",
            format!(
                "{}0 0 0\nnan 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n",
                ply_header("ascii", 4, 1)
            ),
            Refused("nan.ply:11: vertex 1 is not finite"),
        ),
        case(
            "nan_le.ply",
            binary_ply(false, (4, 1), &nan, &[&[0, 1, 2]]),
            Refused("vertex 1 is not finite"),
        ),
        case(
            "utf16.ply",
            utf16(&quad),
            Refused("utf16.ply:1: the file is UTF-16 text"),
        ),
        case(
            "nul.ply",
            quad.replace("1 0 0\n", "1 0\0 0\n"),
            Refused("nul.ply:11: expected a number"),
        ),
        case("empty.ply", "", Refused("no 'end_header'")),
    ]);
}

#[test]
fn hostile_and_odd_obj_files() {
    use Expect::*;
    let tri = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf -4 -2 -1\n";
    let n = 20_000;
    let mut polygon: String = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            format!("v {} {} 0\n", a.cos() as f32, a.sin() as f32)
        })
        .collect();
    polygon.push('f');
    (1..=n).for_each(|i| polygon.push_str(&format!(" {i}")));
    polygon.push('\n');
    let mut be16 = vec![0xFE, 0xFF];
    tri.encode_utf16()
        .for_each(|u| be16.extend(u.to_be_bytes()));
    check_all(vec![
        case("relative.obj", square, Read(4, 2)),
        case(
            "continued.obj",
            "v 0 0 0\nv 1 \\\n 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\n3\nf 1 3 4\n",
            Read(4, 2),
        ),
        case("crlf.obj", square.replace('\n', "\r\n"), Read(4, 2)),
        case("cr.obj", square.replace('\n', "\r"), Read(4, 2)),
        case("bom.obj", with_bom(tri), Read(3, 1)),
        case("polygon.obj", polygon, Read(n, n - 2)),
        case(
            "short.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nf\nf 1\nf 1 2\nf 1 2 3\n",
            ReadWarned(3, 1, "3 face(s) with fewer than 3 corners skipped"),
        ),
        case(
            "zero.obj",
            tri.replace("f 1", "f 0"),
            Refused("zero.obj:4: vertex index 0"),
        ),
        case(
            "range.obj",
            tri.replace("f 1 2 3", "f 1 2 99"),
            Refused("range.obj:4: vertex index 99 is out of range"),
        ),
        case(
            "negative.obj",
            tri.replace("f 1 2 3", "f -1 -2 -9"),
            Refused("negative.obj:4: vertex index -9 is out of range"),
        ),
        case(
            "huge.obj",
            tri.replace("f 1 2 3", "f 1 2 99999999999999999999999"),
            Refused("huge.obj:4: expected a vertex index"),
        ),
        case(
            "nan.obj",
            "v 0 0 0\nv nan 0 0\nv 1 inf 0\nf 1 2 3\n",
            Refused("nan.obj:2: a vertex's x is not a finite number"),
        ),
        case(
            "mtl_folder.obj",
            format!("mtllib sub\n{tri}"),
            Refused("sub: not a regular file (a folder)"),
        ),
        case(
            "utf16.obj",
            utf16(tri),
            Refused("utf16.obj:1: the file is UTF-16 text"),
        ),
        case(
            "utf16be.obj",
            be16,
            Refused("utf16be.obj:1: the file is UTF-16 text"),
        ),
        case(
            "nul.obj",
            tri.replace("v 1 0 0", "v 1 0\0 0"),
            Refused("nul.obj:2:"),
        ),
        case("empty.obj", "", Refused("no faces")),
    ]);
}

/// A binary STL of `triangles` whose header starts with `header` and stores `count`.
fn binary_stl(header: &[u8], count: u32, triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = header.to_vec();
    b.resize(80, b' ');
    b.extend(count.to_le_bytes());
    for t in triangles {
        [0f32, 0., 1.]
            .iter()
            .for_each(|x| b.extend(x.to_le_bytes()));
        t.iter().flatten().for_each(|x| b.extend(x.to_le_bytes()));
        b.extend([0, 0]);
    }
    b
}

#[test]
fn hostile_and_odd_stl_files() {
    use Expect::*;
    let two = [
        [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.]],
        [[0., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
    ];
    let ascii = "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
                 vertex 1 1 0\nendloop\nendfacet\nendsolid a\n";
    let nan = [[[0., 0., 0.], [f32::NAN, 0., 0.], [1., f32::INFINITY, 0.]]];
    check_all(vec![
        case("binary.stl", binary_stl(b"binary", 2, &two), Read(4, 2)),
        case("solid.stl", binary_stl(b"solid thing", 2, &two), Read(4, 2)),
        case("ascii.stl", ascii, Read(3, 1)),
        case("crlf.stl", ascii.replace('\n', "\r\n"), Read(3, 1)),
        case("cr.stl", ascii.replace('\n', "\r"), Read(3, 1)),
        case("bom.stl", with_bom(ascii), Read(3, 1)),
        case(
            "lying.stl",
            binary_stl(b"binary", 4_000_000_000, &two),
            Refused("announces 4000000000 triangles"),
        ),
        case(
            "short_count.stl",
            binary_stl(b"binary", 1, &two),
            Refused("short_count.stl:1: the binary STL has 50 bytes after its last record"),
        ),
        case(
            "nan.stl",
            binary_stl(b"binary", 1, &nan),
            Refused("record 1: a vertex coordinate is not finite"),
        ),
        case("cut.stl", &ascii[..60], Refused("cut.stl:5:")),
        case(
            "four.stl",
            ascii.replace("endloop", "vertex 0 1 0\nendloop"),
            Refused("four.stl:3: a facet has 4 vertices"),
        ),
        case(
            "utf16.stl",
            utf16(ascii),
            Refused("utf16.stl:1: the file is UTF-16 text"),
        ),
        case(
            "nul.stl",
            ascii.replace("vertex 1 0 0", "vertex 1 0\0 0"),
            Refused("nul.stl:5: the file starts with 'solid' and facets"),
        ),
        case("empty.stl", "", Refused("0 bytes is too short")),
    ]);
}

#[test]
fn hostile_and_odd_off_files() {
    use Expect::*;
    let quad = format!("OFF\n4 2 0\n{QUAD}3 0 1 2\n3 0 2 3\n");
    check_all(vec![
        case("plain.off", quad.clone(), Read(4, 2)),
        case(
            "crlf.off",
            format!("OFF\n# made by hand\n4 2 0\n{QUAD}3 0 1 2\n3 0 2 3\n").replace('\n', "\r\n"),
            Read(4, 2),
        ),
        case("cr.off", quad.replace('\n', "\r"), Read(4, 2)),
        case("bom.off", with_bom(&quad), Read(4, 2)),
        case(
            "huge.off",
            format!("OFF\n4000000000 4000000000 0\n{QUAD}3 0 1 2\n"),
            Refused("huge.off:2: the file declares 4000000000 vertices"),
        ),
        case(
            "negative.off",
            quad.replace("4 2 0", "-4 2 0"),
            Refused("negative.off:2: expected a vertex count"),
        ),
        case(
            "range.off",
            quad.replace("3 0 1 2", "3 0 1 9"),
            Refused("range.off:7: face 0: vertex index '9'"),
        ),
        case(
            "nan.off",
            quad.replace("1 0 0\n", "nan 0 0\n"),
            Refused("nan.off:4: a vertex's x is not a finite number"),
        ),
        case(
            "corners.off",
            format!("OFF\n4 2 0\n{QUAD}4000000000 0 1 2\n1000000 0 1 2\n"),
            Refused("corners.off:7: expected 'n i1"),
        ),
        case(
            "utf16.off",
            utf16(&quad),
            Refused("utf16.off:1: the file is UTF-16 text"),
        ),
        case(
            "nul.off",
            quad.replace("1 0 0\n", "1 0\0 0\n"),
            Refused("nul.off:4:"),
        ),
        case("empty.off", "", Refused("the OFF file is empty")),
    ]);
}

/// A glTF document of one triangle whose buffer is `buffer` (its `uri` set by the caller,
/// or none for a GLB): positions at 0, 16-bit indices at 36, a sparse substitute's index at
/// 44 and its value at 48 (used only where an accessor asks).
fn gltf_doc(byte_length: usize) -> Value {
    json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": byte_length }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": 6 },
            { "buffer": 0, "byteOffset": 44, "byteLength": 2 },
            { "buffer": 0, "byteOffset": 48, "byteLength": 12 }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR" }
        ]
    })
}

/// The buffer [`gltf_doc`] describes (60 bytes).
fn gltf_buffer() -> Vec<u8> {
    let mut b = Vec::new();
    for x in [0f32, 0., 0., 1., 0., 0., 1., 1., 0.] {
        b.extend(x.to_le_bytes());
    }
    [0u16, 1, 2, 0, 2, 0]
        .iter()
        .for_each(|i| b.extend(i.to_le_bytes()));
    [0.5f32, 1., 0.]
        .iter()
        .for_each(|x| b.extend(x.to_le_bytes()));
    b
}

/// `doc` with its buffer as a base64 data URI of `bytes`, as JSON text.
fn with_data_uri(mut doc: Value, bytes: &[u8]) -> Vec<u8> {
    use base64::Engine;
    let data = base64::engine::general_purpose::STANDARD.encode(bytes);
    doc["buffers"][0]["uri"] = json!(format!("data:application/octet-stream;base64,{data}"));
    serde_json::to_vec(&doc).expect("JSON")
}

/// A GLB of `doc` and `bin`, whose chunks' stored lengths may lie (`json_len`, `bin_len`).
fn glb_of(doc: &Value, bin: &[u8], json_len: Option<u32>, bin_len: Option<u32>) -> Vec<u8> {
    let mut text = serde_json::to_vec(doc).expect("JSON");
    text.resize(text.len().next_multiple_of(4), b' ');
    let json_len = json_len.unwrap_or(text.len() as u32);
    let bin_len = bin_len.unwrap_or(bin.len() as u32);
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend(json_len.to_le_bytes());
    out.extend(b"JSON");
    out.extend(text);
    out.extend(bin_len.to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

#[test]
fn hostile_and_odd_gltf_files() {
    use Expect::*;
    let bin = gltf_buffer();
    let plain = with_data_uri(gltf_doc(60), &bin);
    let edited = |edit: &dyn Fn(&mut Value)| {
        let mut doc = gltf_doc(60);
        edit(&mut doc);
        with_data_uri(doc, &bin)
    };
    let external = |uri: &str, length: usize| {
        let mut doc = gltf_doc(length);
        doc["buffers"][0]["uri"] = json!(uri);
        serde_json::to_vec(&doc).expect("JSON")
    };
    let sparse = edited(&|d| {
        d["accessors"][0]["sparse"] = json!({
            "count": 1,
            "indices": { "bufferView": 2, "componentType": 5123 },
            "values": { "bufferView": 3 }
        });
    });
    let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
    let deep_extras =
        String::from_utf8_lossy(&plain).replacen('{', &format!("{{\"extras\":{deep},"), 1);
    let glb_doc = gltf_doc(60);
    check_all(vec![
        case("plain.gltf", plain.clone(), Read(3, 1)),
        case(
            "bom.gltf",
            with_bom(&String::from_utf8_lossy(&plain)),
            Read(3, 1),
        ),
        case("sparse.gltf", sparse, Read(3, 1)),
        case("sub/external.gltf", external("b.bin", 60), Read(3, 1)),
        case("sub/b.bin", bin.clone(), Beside),
        case("plain.glb", glb_of(&glb_doc, &bin, None, None), Read(3, 1)),
        case(
            "base64.gltf",
            serde_json::to_vec(&{
                let mut d = gltf_doc(60);
                d["buffers"][0]["uri"] = json!("data:application/octet-stream;base64,@@@!");
                d
            })
            .expect("JSON"),
            Refused("buffer 0: a data: URI's base64 is damaged"),
        ),
        case(
            "count.gltf",
            edited(&|d| d["accessors"][0]["count"] = json!(1_000_000)),
            Refused("accessor 0: 1000000 elements of 12 bytes"),
        ),
        case(
            "misaligned.gltf",
            edited(&|d| d["bufferViews"][0]["byteOffset"] = json!(1)),
            Refused("accessors[0].byteOffset"),
        ),
        case(
            "up.gltf",
            external("../../x.bin", 60),
            Refused("buffers[0].uri: '../../x.bin' is outside the model's folder"),
        ),
        case(
            "short.gltf",
            external("sub/b.bin", 6000),
            Refused("buffer 0 holds 60 bytes, but the file says 6000"),
        ),
        case(
            "deep.gltf",
            deep,
            Refused("deep.gltf:1: not valid glTF JSON"),
        ),
        case(
            "deep_extras.gltf",
            deep_extras,
            Refused("recursion limit exceeded"),
        ),
        case(
            "json_chunk.glb",
            glb_of(&glb_doc, &bin, Some(0xFFFF_FFF0), None),
            Refused("byte 12: GLB chunk 0 says 4294967280 bytes"),
        ),
        case(
            "bin_chunk.glb",
            glb_of(&glb_doc, &bin, None, Some(1 << 30)),
            Refused("GLB chunk 1 says 1073741824 bytes"),
        ),
        case(
            "empty.gltf",
            "",
            Refused("empty.gltf:1: not valid glTF JSON"),
        ),
        case("empty.glb", "", Refused("empty.glb:1: not valid glTF JSON")),
    ]);
}

#[test]
fn hostile_progressive_mesh_files() {
    use Expect::*;
    let pm = |rest: &[u32]| {
        let mut b = b"DECIMPM\0".to_vec();
        rest.iter().for_each(|x| b.extend(x.to_le_bytes()));
        b
    };
    check_all(vec![
        case(
            "models.pm",
            pm(&[1, u32::MAX]),
            Refused("byte 12: the model count is 4294967295"),
        ),
        case(
            "name.pm",
            [pm(&[1, 1, u32::MAX]), b"abc".to_vec()].concat(),
            Refused("byte 12:"),
        ),
        case(
            "version.pm",
            pm(&[99, 1]),
            Refused("byte 8: format version 99"),
        ),
        case(
            "cut.pm",
            b"DECIMPM\0\x01".to_vec(),
            Refused("byte 8: the file ends"),
        ),
        case("empty.pm", "", Refused("the file is empty")),
    ]);
}

/// A folder and links to /dev/zero named like every format: refused before they are read.
#[cfg(unix)]
#[test]
fn folders_and_devices_named_like_models_are_refused() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let names = [
        "zero.ply",
        "zero.stl",
        "zero.off",
        "zero.glb",
        "zero.gltf",
        "zero.pm",
    ];
    for name in names {
        std::os::unix::fs::symlink("/dev/zero", dir.path().join(name)).expect("a link");
    }
    std::fs::create_dir(dir.path().join("folder.ply")).expect("a folder");
    let mut wrong = Vec::new();
    for (name, what) in names
        .iter()
        .map(|&n| (n, "not a regular file (a device)"))
        .chain([("folder.ply", "not a regular file (a folder)")])
    {
        let c = case(name, "", Expect::Refused(what));
        for algorithm in ["schroeder", "qem"] {
            wrong.extend(judge(&c, algorithm, &watched(dir.path(), name, algorithm)));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// A texture image that is a FIFO, which a glTF output would embed: never opened (it would
/// block forever), the model written without it, the image named in a warning.
#[cfg(unix)]
#[test]
fn a_fifo_named_as_a_texture_is_never_opened() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let made = Command::new("mkfifo")
        .arg(dir.path().join("tex.png"))
        .status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    let wrl = "#VRML V2.0 utf8\nShape { appearance Appearance { texture ImageTexture { \
               url \"tex.png\" } } geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0, \
               1 0 0, 0 1 0 ] } coordIndex [ 0 1 2 -1 ] texCoord TextureCoordinate { \
               point [ 0 0, 1 0, 0 1 ] } } }\n";
    std::fs::write(dir.path().join("t.wrl"), wrl).expect("the model");
    let run = watched_to(dir.path(), "t.wrl", "qem", "out.glb");
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stderr.contains("tex.png") && run.stderr.contains("not a regular file (a FIFO)"),
        "{}",
        run.stderr
    );
    assert_eq!(counts_in(&run.stderr), Some((3, 1)), "{}", run.stderr);
}

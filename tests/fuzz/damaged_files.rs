//! Damaged files of every format the program reads, one test per reader: seeded mutations
//! of small valid files (bytes flipped, spans cut or repeated, numbers made huge, negative,
//! NaN, tokens out of place, files truncated). Each must either fail with an error that
//! names the file, or read as a scene that both algorithms decimate, keeping every
//! invariant of `support::check` (indices in range, no triangle turned from the input, no
//! closed part inverted, no vertex far off the input, counts never past the target), and
//! that our OBJ and PLY writers write point for point as the tests' own reader reads it —
//! never a panic (an overflow in this debug build too), a hang or an allocation over
//! `ALLOC_PER_BYTE` times the file's size plus `ALLOC_SLACK` (the counting allocator of
//! `alloc_cap`). A failure names the seed file and mutation number, and leaves the mutant
//! under the target's temporary folder to reproduce it.
//!
//! `FUZZ_MUTANTS=N` runs N mutants per seed instead of the default (a longer hunt:
//! `FUZZ_MUTANTS=20000 cargo test --release --test fuzz`).

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use decimate_core::decimate::{
    simplify_scene, simplify_scene_progressive, Algorithm, ErrorBound, Params, Report, Target,
};
use decimate_core::io::{self, parse_bytes};
use decimate_core::mesh::{measure, Attribute, Model, Scene};

use crate::alloc_cap;
use crate::seeds::seeds;
use crate::support::check;
use crate::support::plain_files::{round_trip, Format};
use crate::support::rng::Rng;

/// Mutants per seed file in the default run.
const MUTANTS: usize = 16;

/// Tokens a damaged or hostile file might hold where a number or keyword was.
const TOKENS: &[&str] = &[
    "-1",
    "0",
    "-0",
    "1",
    "3",
    "65535",
    "2147483647",
    "2147483648",
    "4294967295",
    "4294967296",
    "18446744073709551615",
    "99999999999999999999",
    "1e39",
    "1e309",
    "-1e309",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "0x10",
    "1.5",
    "-2.5e-320",
    "",
    " ",
    "\n",
    "\r\n",
    "\0",
    "{",
    "}",
    "[",
    "]",
    ",",
    "#",
    "\"",
    "/",
    "//",
    "\\",
    "DEF A",
    "USE A",
    "DEF A Separator {",
    "USE Missing",
    "Separator {",
    "Transform { children [",
    "Shape { geometry IndexedFaceSet { coordIndex [ 0 1 2 -1 ] } }",
    "coordIndex [ 0 1 99999 -1 ]",
    "point [ 1 2 3 ]",
    "f 1 2 3",
    "f -1 -2 -3",
    "f 0 0 0",
    "f 1/1/1 2/2/2 3/3/3",
    "v 1 2 3",
    "vt 0.5 0.5",
    "usemtl m",
    "mtllib missing.mtl",
    "element vertex 4000000000",
    "element face 2000000000",
    "property list uchar int vertex_indices",
    "property list uint uint vertex_indices",
    "property float x",
    "format binary_big_endian 1.0",
    "format ascii 1.0",
    "end_header\n",
    "facet normal 0 0 1",
    "outer loop",
    "vertex 1 2 3",
    "endloop",
    "endfacet",
    "OFF",
    "COFF",
    "4000000000 1 0",
    "ImageTexture { url \"a.png\" }",
    "TextureCoordinate2 { point [ 0 0, 1 0 ] }",
    "texCoordIndex [ 0 1 2 -1 ]",
    "colorPerVertex FALSE",
    "normalPerVertex TRUE",
    "MaterialBinding { value PER_FACE_INDEXED }",
    "NormalBinding { value PER_VERTEX }",
    "Scale { scaleFactor 0 0 0 }",
    "MatrixTransform { matrix 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 }",
    "Rotation { rotation 0 0 0 1 }",
    "\u{feff}",
    "é",
    "\"bufferView\": 0",
    "\"byteStride\": 3",
    "\"count\": 4294967295",
    "\"componentType\": 5120",
    "\"type\": \"VEC2\"",
    "\"mode\": 5",
    "\"children\": [0]",
    "\"matrix\": [0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]",
    "\"normalized\": true",
    "data:application/octet-stream;base64,AAAA",
];

/// One mutation of `bytes`.
fn mutate(rng: &mut Rng, bytes: &mut Vec<u8>) {
    let len = bytes.len();
    let at = rng.index(len + 1);
    match rng.index(9) {
        // A byte changed.
        0 if len > 0 => {
            let i = rng.index(len);
            bytes[i] = rng.next() as u8;
        }
        // A bit flipped (a binary file's count or index off by a power of two).
        1 if len > 0 => {
            let i = rng.index(len);
            bytes[i] ^= 1 << rng.index(8);
        }
        // A span cut.
        2 => {
            let end = (at + 1 + rng.index(64)).min(len);
            bytes.drain(at.min(end)..end);
        }
        // A span repeated elsewhere.
        3 if len > 0 => {
            let start = rng.index(len);
            let end = (start + 1 + rng.index(128)).min(len);
            let span = bytes[start..end].to_vec();
            bytes.splice(at..at, span);
        }
        // Truncated.
        4 => bytes.truncate(at),
        // A number replaced by a hostile one.
        5 => {
            let digits: Vec<usize> = (0..len).filter(|&i| bytes[i].is_ascii_digit()).collect();
            if let Some(&i) = digits.get(rng.index(digits.len())) {
                let mut end = i;
                while end < len && (bytes[end].is_ascii_digit() || b".eE-+".contains(&bytes[end])) {
                    end += 1;
                }
                let token = TOKENS[rng.index(12)];
                bytes.splice(i..end, token.bytes());
            }
        }
        // Four random little-endian bytes (a binary count or index).
        6 if len >= 4 => {
            let i = rng.index(len - 3);
            let value = match rng.index(4) {
                0 => u32::MAX,
                1 => u32::MAX / 2 + 1,
                2 => rng.next() as u32,
                _ => (rng.next() % 64) as u32,
            };
            bytes[i..i + 4].copy_from_slice(&value.to_le_bytes());
        }
        // A token inserted.
        _ => {
            let token = TOKENS[rng.index(TOKENS.len())];
            bytes.splice(at..at, token.bytes());
        }
    }
}

/// A single case taking longer than this is a hang.
const HANG: Duration = Duration::from_secs(20);

/// One case may allocate this many times its file's size ...
pub const ALLOC_PER_BYTE: usize = 64;

/// ... plus this (the decimators' fixed tables, the writers' buffers).
pub const ALLOC_SLACK: usize = 16 << 20;

/// What the checks of many cases saw.
#[derive(Debug, Default)]
pub struct Tally {
    /// Files read and decimated.
    pub read: usize,
    /// Files refused with an error naming them.
    pub refused: usize,
    /// Decimated models checked.
    pub models: usize,
    /// Output triangles compared with the input surface.
    pub triangles: usize,
    /// Closed parts whose volume sign was compared.
    pub closed: usize,
    /// Decimated scenes written and read back by the tests' own reader.
    pub round_trips: usize,
    /// The most one case allocated, over its file's size.
    pub most_per_byte: f64,
}

/// What must hold for a scene that read: both algorithms decimate it, to a percentage, to
/// counts and under an error bound, every result keeps the invariants, and every writer
/// writes it.
fn exercise(scene: &Scene, tally: &mut Tally) -> Result<(), String> {
    assert_finite(scene);
    let targets = [
        (Target::RemovePercent(50.0), None),
        (Target::RemovePercent(100.0), None),
        (Target::KeepVertices(5), None),
        (Target::KeepTriangles(3), None),
        (Target::ErrorOnly, Some(ErrorBound::DiagonalFraction(0.01))),
    ];
    for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
        for (target, max_error) in targets {
            let mut copy = scene.clone();
            let params = Params {
                target,
                max_error,
                algorithm,
                ..Params::default()
            };
            let report = simplify_scene(&mut copy, &params, &mut |_| {});
            let what = format!("{algorithm:?} to {target:?}");
            check_result(scene, &copy, &report, target, tally)
                .map_err(|e| format!("{what}: {e}"))?;
            write_everything(&copy);
        }
    }
    let mut copy = scene.clone();
    let params = Params {
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let (_, pm) = simplify_scene_progressive(&mut copy, &params, &mut |_| {});
    let mut bytes = Vec::new();
    io::progressive_file::write_progressive_to(&mut bytes, &pm).expect("writes to memory");
    // What was written reads back.
    if let Err(e) = io::progressive_file::parse_progressive(&bytes, Path::new("again.pm")) {
        return Err(format!(
            "a written progressive mesh does not read back: {e}"
        ));
    }
    Ok(())
}

/// The invariants of one decimated scene against the scene it came from.
fn check_result(
    before: &Scene,
    after: &Scene,
    report: &Report,
    target: Target,
    tally: &mut Tally,
) -> Result<(), String> {
    let dropped = report.models.iter().filter(|m| m.dropped).count();
    if report.models.len() != after.models.len() + dropped {
        return Err(format!(
            "{} reports, {} models, {dropped} dropped",
            report.models.len(),
            after.models.len()
        ));
    }
    // The models kept, in order, beside what they were.
    let kept = before
        .models
        .iter()
        .zip(&report.models)
        .filter(|(_, r)| !r.dropped);
    for ((b, _), a) in kept.zip(&after.models) {
        check::index_range(a)?;
        if a.triangles.len() > b.triangles.len() {
            return Err(format!(
                "{}: {} triangles from {}",
                a.name,
                a.triangles.len(),
                b.triangles.len()
            ));
        }
        let found = check::geometry(b, a);
        if clean(b) && found.folds > 0 {
            return Err(format!(
                "{}: triangles turned from the input: {found:?}",
                a.name
            ));
        }
        if found.inverted > 0 {
            return Err(format!(
                "{}: a closed part turned inside out: {found:?}",
                a.name
            ));
        }
        // A vertex may move (qem) but never beyond the model's size.
        if found.farthest > 1.0 {
            return Err(format!(
                "{}: a vertex moved off the input: {found:?}",
                a.name
            ));
        }
        tally.models += 1;
        tally.triangles += if clean(b) { found.triangles_checked } else { 0 };
        tally.closed += found.closed_checked;
    }
    if let Target::RemovePercent(p) = target {
        let before_v: usize = report.models.iter().map(|m| m.vertices_before).sum();
        let after_v: usize = report.models.iter().map(|m| m.vertices_after).sum();
        // Rounded once per model at most.
        let asked = (p / 100.0 * before_v as f64).round() as usize + report.models.len();
        if before_v.saturating_sub(after_v) > asked {
            return Err(format!("{before_v} -> {after_v} vertices for {p} %"));
        }
    }
    for format in [Format::Obj, Format::Ply] {
        round_trip(after, format)?;
        tally.round_trips += 1;
    }
    Ok(())
}

/// An input whose surface says which way it faces everywhere: no non-manifold or
/// misoriented edge, no triangle without an area.
fn clean(m: &Model) -> bool {
    let e = measure::edge_counts(m);
    e.non_manifold == 0 && e.misoriented == 0 && measure::degenerate_triangles(m, 1e-6) == 0
}

/// Every number a scene that read holds is finite: a reader refuses what is not.
fn assert_finite(scene: &Scene) {
    for m in &scene.models {
        let finite = |values: &[f32]| values.iter().all(|x| x.is_finite());
        assert!(
            m.positions.iter().all(|p| p.is_finite()),
            "{}: a position",
            m.name
        );
        let attribute = |a: &Option<Attribute<[f32; 3]>>| match a {
            Some(Attribute::PerVertex(v) | Attribute::PerFace(v)) => v.iter().all(|x| finite(x)),
            None => true,
        };
        assert!(attribute(&m.colors), "{}: a colour", m.name);
        let normals = match &m.normals {
            Some(Attribute::PerVertex(v) | Attribute::PerFace(v)) => {
                v.iter().all(|n| n.is_finite())
            }
            None => true,
        };
        assert!(normals, "{}: a normal", m.name);
        let texcoords = m
            .texcoords
            .as_deref()
            .is_none_or(|t| t.iter().all(|x| finite(x)));
        assert!(texcoords, "{}: texture coordinates", m.name);
        assert!(finite(&m.diffuse), "{}: the diffuse colour", m.name);
        assert!(m.transform.is_finite(), "{}: the transform", m.name);
    }
}

/// Writes `scene` in every format, to memory.
fn write_everything(scene: &Scene) {
    let mut out = Vec::new();
    io::write_vrml2_to(&mut out, scene).expect("writes to memory");
    out.clear();
    io::ply::write_ply_to(&mut out, scene).expect("writes to memory");
    out.clear();
    io::obj::write_obj_to(&mut out, scene).expect("writes to memory");
    out.clear();
    io::stl::write_stl_to(&mut out, scene).expect("writes to memory");
    out.clear();
    io::off::write_off_to(&mut out, scene).expect("writes to memory");
}

/// One test at a time: the allocation counts and the panic hook are the process's.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// A fuzz run in progress: holds the process to itself, silences panics' reports and
/// exits the process when one case runs past `HANG`.
pub struct Harness {
    current: Arc<Mutex<(String, Instant)>>,
    done: Arc<AtomicBool>,
    watchdog: Option<std::thread::JoinHandle<()>>,
    _alone: MutexGuard<'static, ()>,
}

impl Harness {
    pub fn start() -> Self {
        let alone = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
        // Panics are caught and counted; their default report would flood the output.
        std::panic::set_hook(Box::new(|_| {}));
        let current = Arc::new(Mutex::new((String::new(), Instant::now())));
        let done = Arc::new(AtomicBool::new(false));
        let watchdog = {
            let (current, done) = (Arc::clone(&current), Arc::clone(&done));
            std::thread::spawn(move || {
                while !done.load(Ordering::Relaxed) {
                    std::thread::sleep(Duration::from_millis(200));
                    let Some((name, since)) = current.lock().ok().map(|c| c.clone()) else {
                        continue;
                    };
                    if since.elapsed() > HANG {
                        eprintln!("{name} ran for over {HANG:?}: a hang");
                        std::process::exit(1);
                    }
                }
            })
        };
        Self {
            current,
            done,
            watchdog: Some(watchdog),
            _alone: alone,
        }
    }

    /// Runs one file: `Ok` when it read and kept every invariant, or was refused with an
    /// error naming `name`; the failure otherwise.
    pub fn case(
        &self,
        what: &str,
        name: &str,
        bytes: &[u8],
        tally: &mut Tally,
    ) -> Result<(), String> {
        if let Ok(mut c) = self.current.lock() {
            *c = (what.to_string(), Instant::now());
        }
        let base = alloc_cap::start();
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            match parse_bytes(bytes.to_vec(), Path::new(name)) {
                Ok(outcome) => exercise(&outcome.scene, tally).map(|()| true),
                Err(e) => {
                    let message = e.to_string();
                    if message.starts_with(name) {
                        Ok(false)
                    } else {
                        Err(format!("does not name the file: {message}"))
                    }
                }
            }
        }));
        let peak = alloc_cap::peak_since(base);
        let cap = ALLOC_PER_BYTE * bytes.len() + ALLOC_SLACK;
        let read = match outcome {
            Ok(Ok(read)) => read,
            Ok(Err(e)) => return Err(e),
            Err(panic) => {
                let what = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                return Err(format!("panicked: {what}"));
            }
        };
        if peak > cap {
            return Err(format!(
                "allocated {peak} bytes for {} bytes of file (cap {cap})",
                bytes.len()
            ));
        }
        let per_byte = peak.saturating_sub(ALLOC_SLACK) as f64 / bytes.len().max(1) as f64;
        tally.most_per_byte = tally.most_per_byte.max(per_byte);
        if read {
            tally.read += 1;
        } else {
            tally.refused += 1;
        }
        Ok(())
    }
}

impl Drop for Harness {
    fn drop(&mut self) {
        self.done.store(true, Ordering::Relaxed);
        if let Some(w) = self.watchdog.take() {
            let _ = w.join();
        }
        let _ = std::panic::take_hook();
    }
}

/// Fuzzes the reader of the seeds named `names`: `FUZZ_MUTANTS` (or `MUTANTS`) mutants of
/// each, every one through [`Harness::case`]. Panics with every failure; returns the tally.
fn fuzz(names: &[&str]) -> Tally {
    let mutants = std::env::var("FUZZ_MUTANTS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(MUTANTS);
    let chosen: Vec<(&str, Vec<u8>)> = seeds()
        .into_iter()
        .filter(|(n, _)| names.contains(n))
        .collect();
    assert_eq!(chosen.len(), names.len(), "a seed is missing: {names:?}");
    let harness = Harness::start();
    let keep = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz_inputs");
    let mut failures = Vec::new();
    let mut tally = Tally::default();
    for (name, seed) in chosen {
        // The seed itself reads and keeps every invariant.
        if let Err(e) = harness.case(&format!("the seed {name}"), name, &seed, &mut tally) {
            failures.push(format!("the seed {name}: {e}"));
        }
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ seed.len() as u64);
        for i in 0..mutants {
            let mut bytes = seed.clone();
            for _ in 0..1 + rng.index(3) {
                mutate(&mut rng, &mut bytes);
            }
            let what = format!("mutant {i} of {name}");
            if let Err(e) = harness.case(&what, name, &bytes, &mut tally) {
                let _ = std::fs::create_dir_all(&keep);
                let file = keep.join(format!("{i}-{name}"));
                let _ = std::fs::write(&file, &bytes);
                failures.push(format!("{what} ({}): {e}", file.display()));
            }
        }
    }
    drop(harness);
    eprintln!("{names:?}: {tally:?}");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    // Both outcomes are exercised: a fuzz run that refuses everything tests little.
    assert!(tally.read > 0 && tally.refused > 0, "{tally:?}");
    // Every decimated scene was checked and read back (ten decimations a file read).
    assert!(tally.models >= 10 * tally.read, "{tally:?}");
    assert_eq!(tally.round_trips, 20 * tally.read, "{tally:?}");
    tally
}

#[test]
fn ply_ascii() {
    let t = fuzz(&["ascii.ply"]);
    assert!(t.triangles > 0, "{t:?}");
}

#[test]
fn ply_binary() {
    let t = fuzz(&["seed.ply"]);
    assert!(t.triangles > 0 && t.closed > 0, "{t:?}");
}

#[test]
fn obj() {
    let t = fuzz(&["seed.obj", "faces.obj"]);
    assert!(t.triangles > 0 && t.closed > 0, "{t:?}");
}

#[test]
fn stl_ascii() {
    let t = fuzz(&["ascii.stl"]);
    assert!(t.triangles > 0, "{t:?}");
}

#[test]
fn stl_binary() {
    // An STL's triangles share no vertex: no closed part to compare.
    let t = fuzz(&["seed.stl"]);
    assert!(t.triangles > 0, "{t:?}");
}

#[test]
fn off() {
    let t = fuzz(&["seed.off", "colour.off"]);
    assert!(t.triangles > 0 && t.closed > 0, "{t:?}");
}

#[test]
fn gltf_text() {
    let t = fuzz(&["seed.gltf", "carried.gltf"]);
    assert!(t.triangles > 0 && t.closed > 0, "{t:?}");
}

#[test]
fn glb() {
    let t = fuzz(&["seed.glb", "skinned.glb"]);
    assert!(t.triangles > 0 && t.closed > 0, "{t:?}");
}

#[test]
fn vrml1() {
    let t = fuzz(&["vrml1.wrl"]);
    assert!(t.triangles > 0, "{t:?}");
}

#[test]
fn vrml2() {
    let t = fuzz(&["seed.wrl", "nodes.wrl"]);
    assert!(t.triangles > 0 && t.closed > 0, "{t:?}");
}

#[test]
fn inventor() {
    let t = fuzz(&["inventor.iv", "nodes.iv"]);
    assert!(t.triangles > 0, "{t:?}");
}

#[test]
fn progressive_mesh() {
    let t = fuzz(&["seed.pm"]);
    assert!(t.triangles > 0, "{t:?}");
}

//! Damaged files of every format the program reads: thousands of seeded mutations of small
//! valid files (bytes flipped, spans cut or repeated, numbers made huge, negative, NaN,
//! tokens out of place, files truncated). Each must either fail with an error that names
//! the file, or read as a scene that both algorithms decimate and every writer writes —
//! never a panic (an overflow in this debug build too), a hang or an allocation the file's
//! size does not justify. A failure names the seed file and mutation number, and leaves the
//! mutant under the target's temporary folder to reproduce it.
//!
//! `FUZZ_MUTANTS=N` runs N mutants per seed instead of the default (a longer hunt:
//! `FUZZ_MUTANTS=20000 cargo test --release --test fuzz`).

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use decimate_core::decimate::{
    simplify_scene, simplify_scene_progressive, Algorithm, ErrorBound, Params, Target,
};
use decimate_core::io::{self, parse_bytes};
use decimate_core::mesh::{Attribute, Scene};

use crate::seeds::seeds;
use crate::support::rng::Rng;

/// Mutants per seed file in the default run.
const MUTANTS: usize = 150;

/// A single mutant taking longer than this is a hang.
const HANG: Duration = Duration::from_secs(20);

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

/// What must hold for a scene that read: both algorithms decimate it, to a percentage, to
/// counts and under an error bound, and every writer writes the result.
fn exercise(scene: &Scene) {
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
            assert_eq!(report.models.len(), copy.models.len() + dropped(&report));
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
        panic!("a written progressive mesh does not read back: {e}");
    }
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

fn dropped(report: &decimate_core::decimate::Report) -> usize {
    report.models.iter().filter(|m| m.dropped).count()
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

#[test]
fn damaged_files_of_every_format_never_panic_hang_or_lose_the_file_name() {
    let mutants = std::env::var("FUZZ_MUTANTS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(MUTANTS);
    // Panics are caught and counted; their default report would flood the output.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let current: Arc<Mutex<(String, usize, Instant)>> =
        Arc::new(Mutex::new((String::new(), 0, Instant::now())));
    let done = Arc::new(AtomicBool::new(false));
    let watchdog = {
        let (current, done) = (Arc::clone(&current), Arc::clone(&done));
        std::thread::spawn(move || {
            while !done.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(200));
                let Some((name, i, since)) = current.lock().ok().map(|c| c.clone()) else {
                    continue;
                };
                if since.elapsed() > HANG {
                    eprintln!("mutant {i} of {name} ran for over {HANG:?}: a hang");
                    std::process::exit(1);
                }
            }
        })
    };
    let keep = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz_inputs");
    let mut failures = Vec::new();
    let (mut read, mut refused) = (0usize, 0usize);
    for (name, seed) in seeds() {
        let path = Path::new(name);
        // The seed itself reads.
        assert!(
            parse_bytes(seed.clone(), path).is_ok(),
            "the seed {name} does not read"
        );
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ seed.len() as u64);
        for i in 0..mutants {
            let mut bytes = seed.clone();
            for _ in 0..1 + rng.index(3) {
                mutate(&mut rng, &mut bytes);
            }
            if let Ok(mut c) = current.lock() {
                *c = (name.to_string(), i, Instant::now());
            }
            let outcome = catch_unwind(AssertUnwindSafe(|| {
                match parse_bytes(bytes.clone(), path) {
                    Ok(outcome) => {
                        exercise(&outcome.scene);
                        Ok(())
                    }
                    Err(e) => {
                        let message = e.to_string();
                        assert!(
                            message.starts_with(name),
                            "does not name the file: {message}"
                        );
                        Err(())
                    }
                }
            }));
            match outcome {
                Ok(Ok(())) => read += 1,
                Ok(Err(())) => refused += 1,
                Err(panic) => {
                    let what = panic
                        .downcast_ref::<String>()
                        .cloned()
                        .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                        .unwrap_or_default();
                    let _ = std::fs::create_dir_all(&keep);
                    let file = keep.join(format!("{i}-{name}"));
                    let _ = std::fs::write(&file, &bytes);
                    failures.push(format!("{name} mutant {i} ({}): {what}", file.display()));
                }
            }
        }
    }
    done.store(true, Ordering::Relaxed);
    let _ = watchdog.join();
    std::panic::set_hook(hook);
    eprintln!("{read} mutants read and decimated, {refused} refused with an error");
    assert!(
        failures.is_empty(),
        "{} of {} mutants panicked:\n{}",
        failures.len(),
        read + refused + failures.len(),
        failures.join("\n")
    );
    // Both outcomes are exercised: a fuzz run that refuses everything tests little.
    assert!(read > 0 && refused > 0, "read {read}, refused {refused}");
}

//! The seed corpus replayed: every file under `tests/fuzz/corpus/<reader>/` (the seeds, and
//! what `tools/check/fuzz-coverage` kept: inputs that reached new code, and any that
//! failed once) goes through the same case as a mutant, each read under its own name (the
//! extension says the format). `FUZZ_WRITE_SEEDS=DIR` writes the seeds there instead, one
//! folder per reader, for the coverage-guided fuzzer to start from.

use std::path::{Path, PathBuf};

use crate::damaged_files::{Harness, Tally};
use crate::seeds::seeds;

/// The folder a seed's reader has in the corpus.
pub fn reader_of(name: &str) -> &'static str {
    match Path::new(name).extension().and_then(|e| e.to_str()) {
        Some("ply") => "ply",
        Some("obj") => "obj",
        Some("stl") => "stl",
        Some("off") => "off",
        Some("gltf" | "glb") => "gltf",
        Some("wrl") => "vrml",
        Some("iv") => "inventor",
        Some("pm") => "pm",
        _ => "other",
    }
}

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz/corpus")
}

/// Every file of the corpus, as (reader's folder, path), sorted.
fn files() -> Vec<(String, PathBuf)> {
    let mut found = Vec::new();
    let Ok(readers) = std::fs::read_dir(corpus()) else {
        return found;
    };
    for reader in readers.flatten() {
        let Ok(entries) = std::fs::read_dir(reader.path()) else {
            continue;
        };
        for e in entries.flatten() {
            found.push((reader.file_name().to_string_lossy().into_owned(), e.path()));
        }
    }
    found.sort();
    found
}

#[test]
fn the_seed_corpus_replays_without_a_failure() {
    if let Ok(dir) = std::env::var("FUZZ_WRITE_SEEDS") {
        for (name, bytes) in seeds() {
            let folder = Path::new(&dir).join(reader_of(name));
            std::fs::create_dir_all(&folder).expect("the seed folder can be made");
            std::fs::write(folder.join(name), bytes).expect("a seed can be written");
        }
        return;
    }
    let files = files();
    let harness = Harness::start();
    let mut tally = Tally::default();
    let mut failures = Vec::new();
    for (reader, path) in &files {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let bytes = match std::fs::read(path) {
            Ok(b) => b,
            Err(e) => {
                failures.push(format!("{}: {e}", path.display()));
                continue;
            }
        };
        if let Err(e) = harness.case(&format!("{reader}/{name}"), &name, &bytes, &mut tally) {
            failures.push(format!("{reader}/{name}: {e}"));
        }
    }
    drop(harness);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // Every reader's folder is there, and every seed with it.
    let readers: std::collections::BTreeSet<&str> = files.iter().map(|(r, _)| r.as_str()).collect();
    let expected: std::collections::BTreeSet<&str> =
        seeds().iter().map(|(n, _)| reader_of(n)).collect();
    assert_eq!(readers, expected);
    assert!(files.len() >= seeds().len(), "{} files", files.len());
    assert_eq!(tally.read + tally.refused, files.len(), "{tally:?}");
    assert!(tally.read >= seeds().len(), "{tally:?}");
}

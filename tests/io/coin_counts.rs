//! Every scene of Debian's `inventor-data` that Coin reads gives us at least 95 % of the
//! triangles Coin makes of it (text, NURBS and zero-area triangles left out, which we skip),
//! and exactly Coin's count but on six scenes listed with the count they give.
//!
//! The reference, tests/data/coin_counts.tsv, is Coin 4.0's count written by
//! `tools/check/coin-table --reference` (Coin's `SoCallbackAction` through tools/check/coin-count): it
//! is kept in the repository because the scenes are a fixed Debian package, so the test
//! needs no C++ toolchain or Coin library. Binary scenes are converted with `ivcat` first.

use std::path::{Path, PathBuf};
use std::process::Command;

use decimate_core::io::read_scene;
use decimate_core::mesh::build::build_scene;

const MODELS: &str = "/usr/share/inventor/data/models";

fn install_hint() -> &'static str {
    "this test needs Debian's Open Inventor sample data and tools: run \
     `apt-get install inventor-data inventor-clients`"
}

/// Copies every scene under MODELS into `dst` as ASCII (binary ones through `ivcat`), so
/// `File` nodes find the files they name beside them.
fn ascii_tree(dst: &Path) {
    let mut folders = vec![PathBuf::from(MODELS)];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "iv") {
                continue;
            }
            let out = dst.join(path.strip_prefix(MODELS).unwrap());
            std::fs::create_dir_all(out.parent().unwrap()).unwrap();
            let bytes = std::fs::read(&path).unwrap();
            let header = bytes.split(|&b| b == b'\n').next().unwrap_or(&[]);
            let ascii = if header.windows(6).any(|w| w == b"binary") {
                let o = Command::new("ivcat")
                    .arg(&path)
                    .output()
                    .unwrap_or_else(|e| panic!("cannot run ivcat ({e}); {}", install_hint()));
                o.stdout
            } else {
                bytes
            };
            std::fs::write(out, ascii).unwrap();
        }
    }
}

/// Each reference scene with Coin's triangle count and ours.
fn counts() -> Vec<(String, usize, usize)> {
    assert!(
        Path::new(MODELS).is_dir(),
        "{MODELS} is missing; {}",
        install_hint()
    );
    let reference = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/coin_counts.tsv"),
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    ascii_tree(dir.path());
    let mut counts = Vec::new();
    for line in reference.lines().filter(|l| !l.starts_with('#')) {
        let (scene, coin) = line.split_once('\t').expect("scene<TAB>count");
        let coin: usize = coin.parse().unwrap();
        let path = dir.path().join(scene);
        let ours = match read_scene(&path) {
            Ok(o) => build_scene(o.scene, true).triangle_count(),
            // A scene of text or NURBS only: nothing to read, and Coin agrees.
            Err(_) if coin == 0 => 0,
            Err(e) => panic!("{scene}: {e}"),
        };
        counts.push((scene.to_string(), coin, ours));
    }
    counts
}

#[test]
fn every_scene_coin_reads_gives_at_least_95_percent_of_coins_triangles() {
    let counts = counts();
    assert!(
        counts.len() >= 90,
        "only {} scenes in the reference",
        counts.len()
    );
    let short: Vec<String> = counts
        .iter()
        .filter(|(_, coin, ours)| (*ours as f64) < 0.95 * *coin as f64)
        .map(|(scene, coin, ours)| format!("{scene}: ours {ours}, Coin {coin}"))
        .collect();
    assert!(
        short.is_empty(),
        "under 95 % of Coin's triangles: {short:#?}"
    );
}

/// The scenes where our count is not Coin's: (scene, Coin's count, ours). Every other
/// scene of the reference must give Coin's count exactly, and these exactly what they give
/// now, so that a change either way is seen.
const DIFFERENT: [(&str, usize, usize); 6] = [
    // Coin makes 1,715 triangles of its 2,672 quads; its own VRML 2.0 conversion gives
    // 5,336 (docs/design.md, "Against Coin on inventor-data").
    ("buildings/Barcelona.iv", 1715, 5335),
    // Faces listed twice: Coin draws both, our repair keeps one (the summary says "22
    // duplicate triangles removed"; the 767's "4").
    ("household/plant.iv", 1284, 1262),
    ("vehicles/767.iv", 1691, 1687),
    // Not yet explained: more triangles than Coin's of non-zero area.
    ("furniture/table.iv", 3600, 3680),
    ("machines/compressor.iv", 147, 148),
    ("sgi/indigo.iv", 10174, 10178),
];

#[test]
fn every_scene_gives_coins_count_exactly_but_the_known_differences() {
    let counts = counts();
    let mut wrong = Vec::new();
    for (scene, coin, ours) in &counts {
        let want = match DIFFERENT.iter().find(|(s, _, _)| s == scene) {
            Some(&(_, known_coin, known_ours)) => {
                assert_eq!(*coin, known_coin, "{scene}: the reference changed");
                known_ours
            }
            None => *coin,
        };
        if *ours != want {
            wrong.push(format!(
                "{scene}: ours {ours}, expected {want} (Coin {coin})"
            ));
        }
    }
    for (scene, _, _) in DIFFERENT {
        assert!(
            counts.iter().any(|(s, _, _)| s == scene),
            "{scene} is not in the reference"
        );
    }
    assert!(wrong.is_empty(), "triangle counts changed: {wrong:#?}");
}

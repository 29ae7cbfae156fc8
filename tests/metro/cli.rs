//! The `metro` command line (Metro, Cignoni–Rocchini–Scopigno 1998): usage, and clear
//! failures that name the file at fault.

use crate::support::shapes::Grid;
use std::process::Command;

fn metro(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_metro"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn help_prints_usage_and_succeeds() {
    let (code, out, _) = metro(&["--help"]);
    assert_eq!(code, 0);
    assert!(out.starts_with("usage: metro [options] A B"));
    assert!(out.contains("--samples N"));
}

#[test]
fn wrong_usage_exits_2() {
    let (code, _, err) = metro(&["only-one.wrl"]);
    assert_eq!(code, 2);
    assert!(err.contains("expected two files, got 1"), "{err}");
    let (code, _, err) = metro(&["a.wrl", "b.wrl", "--samples", "many"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("'many' is not a positive whole number"),
        "{err}"
    );
}

#[test]
fn unreadable_file_is_named() {
    let dir = std::env::temp_dir().join(format!("metro-cli-{}", std::process::id()));
    let missing = dir.join("no-such-mesh.wrl");
    let path = missing.to_string_lossy().into_owned();
    let (code, out, err) = metro(&[&path, &path]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    assert!(err.starts_with("metro: "), "{err}");
    assert!(err.contains("no-such-mesh.wrl"), "{err}");
}

/// The number after `"key": ` inside the JSON object that follows `"section": `.
fn json_number(json: &str, section: &str, key: &str) -> f64 {
    let start = json
        .find(&format!("\"{section}\": "))
        .unwrap_or_else(|| panic!("no {section} in {json}"));
    let rest = &json[start..];
    let at = rest.find(&format!("\"{key}\": ")).unwrap() + key.len() + 4;
    let end = rest[at..].find([',', '}']).unwrap();
    rest[at..at + end].trim().parse().unwrap()
}

#[test]
fn concentric_cubes_from_the_bundled_assets() {
    // test002 is the cube [-1, 1]³, test004 the cube [-5, 5]³ (both closed, outward).
    let (code, out, err) = metro(&[
        "--json",
        "--samples",
        "200000",
        "assets/test002.wrl",
        "assets/test004.wrl",
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(json_number(&out, "a", "area"), 24.0);
    assert_eq!(json_number(&out, "a", "volume"), 8.0);
    assert_eq!(json_number(&out, "b", "area"), 600.0);
    assert_eq!(json_number(&out, "b", "volume"), 1000.0);
    assert_eq!(json_number(&out, "a", "components"), 1.0);
    // Every point of the small cube is exactly 4 inside the big one's faces.
    for key in ["max", "mean", "rms"] {
        assert!((json_number(&out, "a_to_b", key) - 4.0).abs() < 1e-12);
    }
    // The big cube's corners are 4√3 from the small cube's corners.
    let hausdorff = json_number(&out, "symmetric", "max");
    assert!((hausdorff - 4.0 * 3f64.sqrt()).abs() < 1e-12, "{hausdorff}");
    // Mean over a face of the big cube, by a 1000×1000 midpoint rule.
    let n = 1000;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -5.0 + 10.0 * (i as f64 + 0.5) / n as f64;
            let y = -5.0 + 10.0 * (j as f64 + 0.5) / n as f64;
            let dx = (x.abs() - 1.0).max(0.0);
            let dy = (y.abs() - 1.0).max(0.0);
            sum += (dx * dx + dy * dy + 16.0).sqrt();
        }
    }
    let mean = sum / (n * n) as f64;
    let sampled = json_number(&out, "b_to_a", "mean");
    assert!((sampled - mean).abs() < 2e-3 * mean, "{sampled} vs {mean}");
}

#[test]
fn same_seed_same_output_other_seed_other_output() {
    let args = ["assets/test006.wrl", "assets/test002.wrl"];
    let run = |seed: &str| metro(&["--seed", seed, "--samples", "20000", args[0], args[1]]).1;
    let first = run("7");
    assert!(first.contains("Hausdorff distance"));
    assert_eq!(first, run("7"));
    assert_ne!(first, run("8"));
}

/// A 4×4 grid of unit squares facing +z as OBJ text, with triangle `flip` (if any) reversed.
fn grid_obj(flip: Option<usize>) -> String {
    let mut s = String::new();
    let grid = Grid::square(4);
    for (i, j) in grid.points() {
        s += &format!("v {i} {j} 0\n");
    }
    for (k, t) in grid.triangles().enumerate() {
        let [x, y, z] = t.map(|p| p + 1);
        if flip == Some(k) {
            s += &format!("f {x} {z} {y}\n");
        } else {
            s += &format!("f {x} {y} {z}\n");
        }
    }
    s
}

#[test]
fn folds_are_counted_in_json_and_table_when_asked() {
    let dir = std::env::temp_dir().join(format!("metro-folds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (a, b) = (dir.join("plane.obj"), dir.join("flipped.obj"));
    std::fs::write(&a, grid_obj(None)).unwrap();
    std::fs::write(&b, grid_obj(Some(5))).unwrap();
    let (a, b) = (a.to_string_lossy(), b.to_string_lossy());
    let (code, out, err) = metro(&["--json", "--folds", &a, &b]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(json_number(&out, "folded", "triangles"), 1.0);
    assert_eq!(json_number(&out, "folded", "area_fraction"), 1.0 / 32.0);
    assert_eq!(json_number(&out, "folded", "degenerate"), 0.0);
    assert_eq!(json_number(&out, "folded", "checked"), 32.0);
    // The flipped triangle, (2, 0) (3, 1) (2, 1): centroid (7/3, 2/3, 0).
    assert!(
        out.contains("\"largest_at\": [2.3333333333333335e0, 6.666666666666666e-1, 0e0]"),
        "{out}"
    );
    let (code, out, _) = metro(&["--folds", &a, &b]);
    assert_eq!(code, 0);
    assert!(
        out.contains("folded triangles of B over A: 1 (3.1250 % of B's area); degenerate: 0"),
        "{out}"
    );
    // Not asked: not measured, not printed.
    let (_, out, _) = metro(&["--json", &a, &b]);
    assert!(!out.contains("folded"), "{out}");
    let (code, _, err) = metro(&["--folds", "--fold-reach", "-1", &a, &b]);
    assert_eq!(code, 2);
    assert!(err.contains("'-1' is not a number of at least 0"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

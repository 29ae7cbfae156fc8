//! The `shot` action end to end, through the built binary on lavapipe: a scene file written by
//! the test, decimated with `-p`, pictured before (viewport 1) and after (the others).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::support::shot::*;

const LAVAPIPE: &str = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

/// A fresh scratch folder under target/, so parallel tests never share files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("shot_cli-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

fn cube_file(dir: &Path) -> PathBuf {
    let path = dir.join("cube.wrl");
    decimate_core::io::write_vrml2(&cube(10), &path).unwrap_or_else(|e| panic!("{e}"));
    path
}

fn decimate_cmd(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(args)
        .current_dir(dir)
        .env("VK_ICD_FILENAMES", LAVAPIPE)
        .env("VK_DRIVER_FILES", LAVAPIPE)
        .output()
        .unwrap_or_else(|e| panic!("cannot run decimate: {e}"))
}

fn assert_success(out: &Output) {
    assert!(
        out.status.success(),
        "decimate failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Pixels of `(x0..x1) × all rows` that are not background.
fn covered_columns(image: &decimate_viewer::render::offscreen::RgbaImage, x0: u32, x1: u32) -> f64 {
    coverage(image, x0, 0, x1, image.height)
}

#[test]
fn before_and_after_decimation_side_by_side() {
    let dir = scratch("before-after");
    let input = cube_file(&dir);
    let out = decimate_cmd(
        &dir,
        &[
            input.to_str().unwrap_or_default(),
            "shot",
            "-o",
            "before-after.png",
            "--size",
            "320x240",
            "--viewports",
            "2",
            "--mode",
            "edges",
            "-p",
            "90",
            // Edge coverage is measured per half: no captions over them.
            "--no-labels",
            "--msaa",
            "1",
        ],
    );
    assert_success(&out);
    let image = read_png(&dir.join("before-after.png"));
    assert_eq!((image.width, image.height), (320, 240));
    assert_background_corners(&image);
    // 90 % of the vertices gone: far fewer edges on the right than on the left.
    let before = covered_columns(&image, 0, 159);
    let after = covered_columns(&image, 161, 320);
    assert!(after > 0.01, "the decimated cube vanished ({after})");
    assert!(
        after < before * 0.6,
        "edges before {before:.3}, after {after:.3}"
    );
    assert!(
        !dir.join("before-after.png.tmp").exists(),
        "temporary file left behind"
    );
    assert_matches_golden("cube10_before_after_p90", &image);
}

#[test]
fn four_viewports_default_mode() {
    let dir = scratch("four");
    let input = cube_file(&dir);
    let out = decimate_cmd(
        &dir,
        &[
            input.to_str().unwrap_or_default(),
            "shot",
            "--size",
            "320x240",
            "--viewports",
            "4",
            "-q",
            "--msaa",
            "1",
        ],
    );
    assert_success(&out);
    let image = read_png(&dir.join("shot.png"));
    assert_background_corners(&image);
    assert_matches_golden("cube10_cli_4viewports", &image);
}

#[test]
fn without_vulkan_the_shot_fails_and_says_why() {
    let dir = scratch("no-vulkan");
    let input = cube_file(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args([input.to_str().unwrap_or_default(), "shot", "-q"])
        .current_dir(&dir)
        .env("VK_ICD_FILENAMES", dir.join("no-such-driver.json"))
        .env("VK_DRIVER_FILES", dir.join("no-such-driver.json"))
        .output()
        .unwrap_or_else(|e| panic!("cannot run decimate: {e}"));
    assert!(
        !out.status.success(),
        "a shot without any Vulkan driver must fail"
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("Vulkan"), "unclear message: {stderr}");
    assert!(!dir.join("shot.png").exists());
}

#[test]
fn the_crease_angle_smooths_a_cube_at_180_degrees() {
    // At the default 45° a cube's edges stay sharp (smooth shading looks flat); at 180° its
    // faces' normals are averaged across the edges, so each face shades as a gradient.
    let dir = scratch("crease");
    let input = cube_file(&dir);
    let shoot = |name: &str, extra: &[&str]| {
        let mut args = vec![input.to_str().unwrap_or_default(), "shot", "-q", "-o", name];
        args.extend_from_slice(&["--size", "320x240"]);
        args.extend_from_slice(extra);
        assert_success(&decimate_cmd(&dir, &args));
        read_png(&dir.join(name))
    };
    let default = shoot("default.png", &[]);
    let sharp = shoot("sharp.png", &["--crease-angle", "45"]);
    let smooth = shoot("smooth.png", &["--crease-angle", "180"]);
    assert!(different_fraction(&default, &sharp, 2) < 0.0005);
    let changed = different_fraction(&default, &smooth, 8);
    assert!(
        changed > 0.05,
        "only {:.2} % of the picture changed at 180°",
        changed * 100.0
    );
}

//! A decimation in the window takes about as long as the same one from the command line:
//! a generated sphere of 1,000,000 triangles, drawn as a user sees it, loses 90 % of its
//! vertices by key `9` in the viewer and by `nogui -p 90` beside it, alternating, best of
//! two each; the viewer's time (as it reports it, the job alone) is within 1.3x of nogui's
//! (as it reports it, the decimation alone). While a job runs the window draws the picture
//! it kept of the viewports, not the triangles; drawn again at every frame they took
//! lavapipe seconds from the job (tools/bench/viewer-jobs measures the dragon).
//!
//! The million triangles: the test profile optimises decimate-core (Cargo.toml), so
//! the four runs of a test build take seconds each; what is compared is a ratio, not a time.

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use super::xvfb::{display_or_skip, hold_x_connection, read_log, run, scratch, start_traced};

/// The sphere's size: 2 · segments · (rings − 1) triangles.
const RINGS: u32 = 501;
const SEGMENTS: u32 = 1000;
const TRIANGLES: usize = 1_000_000;

/// The bar: the viewer within this factor of nogui.
const RATIO: f64 = 1.3;

/// The seconds in `text` after its last `marker`, up to the next " s".
fn seconds_after(text: &str, marker: &str) -> Option<f64> {
    let at = text.rfind(marker)? + marker.len();
    text[at..].split(" s").next()?.trim().parse().ok()
}

/// nogui's own time for `-p 90` of `model` with `algorithm`, in seconds.
fn nogui_seconds(dir: &Path, algorithm: &str) -> f64 {
    let out = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(["sphere.ply", "nogui", "-p", "90", "-a", algorithm])
        .args(["-o", "nogui.wrl"])
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run nogui: {e}"));
    let text =
        String::from_utf8_lossy(&out.stderr).into_owned() + &String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "nogui failed:\n{text}");
    // "total: vertices A -> B, ...; removed N vertices in X s (...)"
    let total = text
        .lines()
        .rfind(|l| l.starts_with("total:"))
        .unwrap_or("");
    seconds_after(total, " vertices in ")
        .unwrap_or_else(|| panic!("no time in nogui's output:\n{text}"))
}

/// The viewer's own time for key `9` on `model` with `algorithm`, in seconds; the window
/// drew the sphere first, as a user sees it.
fn viewer_seconds(dir: &Path, algorithm: &str) -> f64 {
    let log = dir.join("viewer.log");
    let (viewer, wid) = start_traced(dir, &["sphere.ply", "-a", algorithm], &log);
    let _ = Command::new("xdotool")
        .args(["windowfocus", "--sync", &wid])
        .status();
    // The first frames (upload, shaders, fonts) land before the key.
    let start = Instant::now();
    while !read_log(&log).contains("frame in") && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(100));
    }
    std::thread::sleep(Duration::from_secs(2));
    run("xdotool", &["key", "--window", &wid, "9"]);
    let start = Instant::now();
    let seconds = loop {
        let text = read_log(&log);
        if let Some(s) = seconds_after(&text, " triangles left in ") {
            break s;
        }
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "the decimation did not end in 300 s; viewer log:\n{text}"
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    assert!(
        read_log(&log).contains("kept picture"),
        "no frame drew the kept picture while the job ran; viewer log:\n{}",
        read_log(&log)
    );
    // The result is unsaved: q asks, y answers. The viewer is killed when dropped anyway.
    let _ = Command::new("xdotool")
        .args(["key", "--window", &wid, "q"])
        .status();
    std::thread::sleep(Duration::from_millis(500));
    let _ = Command::new("xdotool")
        .args(["key", "--window", &wid, "y"])
        .status();
    drop(viewer);
    seconds
}

#[test]
fn a_decimation_in_the_window_takes_about_as_long_as_from_the_command_line() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let dir = scratch("gui_job_speed");
    let sphere = decimate_core::mesh::shapes::uv_sphere(RINGS, SEGMENTS);
    assert_eq!(sphere.triangles.len(), TRIANGLES);
    let scene = decimate_core::mesh::Scene {
        models: vec![sphere],
    };
    decimate_core::io::write_ply(&scene, &dir.join("sphere.ply")).unwrap_or_else(|e| panic!("{e}"));
    let algorithm = "qem";
    let (mut nogui, mut viewer) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..2 {
        nogui = nogui.min(nogui_seconds(&dir, algorithm));
        viewer = viewer.min(viewer_seconds(&dir, algorithm));
    }
    eprintln!(
        "gui_job_speed: {algorithm}, best of 2: viewer {viewer:.3} s, nogui {nogui:.3} s, {:.2}x",
        viewer / nogui
    );
    assert!(
        viewer <= RATIO * nogui,
        "the viewer took {viewer:.3} s against nogui's {nogui:.3} s ({:.2}x > {RATIO}x)",
        viewer / nogui
    );
}

//! Save as… in a real window: `O` opens the dialog, a new name is typed and Enter writes
//! the decimated viewport in the format the extension names (a PLY, read back with its exact
//! counts); the same name again asks before replacing, `n` keeps the file as it was, and
//! `Esc` closes the dialog with the window still up. Open… (`o`) refuses a missing and a
//! corrupt file in the status line, the cube staying, then shows a PLY picked by name (its
//! exact counts in the status line, and a 90 % decimation of it, not of the cube).

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use super::xvfb::{
    display_or_skip, hold_x_connection, quit, read_log, run, scratch, start_traced, write_cube,
    Viewer,
};

/// Waits up to 30 s for `what` in the viewer's log and returns the first line holding it;
/// fails with the log otherwise.
fn wait_for_log(log: &Path, what: &str) -> String {
    let start = Instant::now();
    loop {
        let text = read_log(log);
        if let Some(line) = text.lines().find(|l| l.contains(what)) {
            return line.to_string();
        }
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "no {what:?} in 30 s; viewer log:\n{text}"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// Opens Save as… in window `wid` and types `name` over the name it suggests, then Enter.
fn save_as(wid: &str, name: &str) {
    run("xdotool", &["key", "--window", wid, "O"]);
    std::thread::sleep(Duration::from_millis(800));
    type_name(wid, name);
}

/// Opens Open… in window `wid` and types `name`, then Enter.
fn open_file(wid: &str, name: &str) {
    run("xdotool", &["key", "--window", wid, "o"]);
    std::thread::sleep(Duration::from_millis(800));
    type_name(wid, name);
}

/// Types `name` over what the shown dialog's name field holds, then Enter.
fn type_name(wid: &str, name: &str) {
    run("xdotool", &["key", "--window", wid, "ctrl+a", "BackSpace"]);
    run("xdotool", &["type", "--window", wid, "--delay", "80", name]);
    std::thread::sleep(Duration::from_millis(300));
    run("xdotool", &["key", "--window", wid, "Return"]);
}

#[test]
fn save_as_writes_the_format_its_extension_names_and_asks_before_replacing() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let (dir, log, viewer, wid) = start_on_cube("gui_dialogs");
    run("xdotool", &["key", "--window", &wid, "9"]);
    wait_for_log(&log, "removed 90 %");

    save_as(&wid, "saved.ply");
    let saved = dir.join("saved.ply");
    wait_for_log(&log, "saved viewport 1 as");
    let bytes = std::fs::read(&saved).unwrap_or_else(|e| panic!("{}: {e}", saved.display()));
    assert!(bytes.starts_with(b"ply\n"), "saved.ply is not a PLY file");
    let scene = decimate_core::io::read_scene(&saved).unwrap_or_else(|e| panic!("{e}"));
    let model = &scene.scene.models[0];
    assert_eq!(
        (model.positions.len(), model.triangles.len()),
        (60, 116),
        "the cube's 90 % decimation, as its caption says"
    );

    // The same name again: the dialog asks, n keeps the file, Esc closes the dialog.
    save_as(&wid, "saved.ply");
    wait_for_log(&log, "saved.ply exists: replace it?");
    run("xdotool", &["key", "--window", &wid, "n"]);
    wait_for_log(&log, "saved.ply kept");
    run("xdotool", &["key", "--window", &wid, "Escape"]);
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        std::fs::read(&saved).unwrap_or_default(),
        bytes,
        "saved.ply was written over without a yes"
    );
    let whole = std::fs::read_to_string(&log).unwrap_or_default();
    assert_eq!(whole.matches("saved viewport 1 as").count(), 1, "{whole}");
    quit(viewer, &wid, &log);
}

/// The viewer, started on the 602-vertex cube in a new folder `name` and drawn once, with
/// the keyboard: (folder, log, viewer, window id).
fn start_on_cube(name: &str) -> (std::path::PathBuf, std::path::PathBuf, Viewer, String) {
    let dir = scratch(name);
    write_cube(&dir.join("cube.wrl"));
    let log = dir.join("viewer.log");
    let (viewer, wid) = start_traced(&dir, &["cube.wrl"], &log);
    let _ = Command::new("xdotool")
        .args(["windowfocus", "--sync", &wid])
        .status();
    wait_for_log(&log, "frame in");
    (dir, log, viewer, wid)
}

#[test]
fn open_refuses_missing_and_corrupt_files_then_shows_the_ply_picked() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let (dir, log, mut viewer, wid) = start_on_cube("gui_open");
    // A 4×4-quads-a-face cube: 6·16 + 2 vertices, 6·16·2 triangles, nothing like the 602.
    let small = decimate_core::mesh::Scene {
        models: vec![decimate_core::mesh::shapes::cube(4, 2.0)],
    };
    decimate_core::io::write_scene(&small, &dir.join("small.ply"))
        .unwrap_or_else(|e| panic!("{e}"));
    std::fs::write(
        dir.join("broken.ply"),
        b"ply\nformat ascii 1.0\nelement vertex 3\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));

    // A name that is not there: the dialog stays, and the status line says why.
    open_file(&wid, "missing.ply");
    wait_for_log(&log, "missing.ply does not exist");
    // A corrupt PLY: refused with the reader's reason, the window and the cube stay.
    type_name(&wid, "broken.ply");
    let refusal = wait_for_log(&log, "cannot open");
    let text = read_log(&log);
    assert!(
        refusal.contains("broken.ply"),
        "the refusal names no file: {refusal}"
    );
    assert!(
        matches!(viewer.0.try_wait(), Ok(None)),
        "the viewer exited on a corrupt file:\n{text}"
    );
    assert!(
        !text.contains("opened"),
        "a refused file was shown:\n{text}"
    );

    // The PLY picked by name: its exact counts in the status line, and what 9 decimates.
    open_file(&wid, "small.ply");
    wait_for_log(&log, "small.ply: 98 vertices, 192 triangles");
    run("xdotool", &["key", "--window", &wid, "9"]);
    let done = wait_for_log(&log, "removed 90 %");
    assert!(
        done.contains("removed 90 %: 10 vertices, 16 triangles"),
        "9 did not decimate the opened 98-vertex cube as nogui -p 90 does (10, 16): {done}"
    );
    // Unsaved: the first q asks, the second quits.
    run("xdotool", &["key", "--window", &wid, "q"]);
    wait_for_log(&log, "not saved");
    quit(viewer, &wid, &log);
}

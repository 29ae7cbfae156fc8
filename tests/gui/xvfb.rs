//! The interactive viewer end to end in a real X window (Xvfb), driven the way a user drives
//! it: key `9` decimates the current viewport by 90 %, F3 saves it as `out.wrl` in the working
//! directory — or, the input being `out.wrl` there, as `out-1.wrl`, and again as `out-2.wrl`
//! — the vertex-count field takes a number and Enter, the right mouse button opens the popup
//! menu. Run under `xvfb-run -a -s "-screen 0 1024x768x24 -noreset" cargo test`. Without
//! `DISPLAY` the test is skipped with a notice, except when `CI` is set: there it fails.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

pub(crate) const LAVAPIPE: &str = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

/// Kills the viewer if the test fails half-way.
pub(crate) struct Viewer(pub(crate) Child);

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

pub(crate) fn display_or_skip() -> bool {
    if std::env::var_os("DISPLAY").is_some() {
        return true;
    }
    if std::env::var_os("CI").is_some() {
        panic!("DISPLAY is not set: run the tests under xvfb-run -a -s \"-screen 0 1024x768x24 -noreset\"");
    }
    eprintln!("gui_xvfb: DISPLAY is not set, skipping (CI runs this under xvfb-run)");
    false
}

pub(crate) fn run(program: &str, args: &[&str]) -> String {
    let out = Command::new(program)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {program} (install xdotool and imagemagick): {e}"));
    assert!(
        out.status.success(),
        "{program} {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn wait_for(what: &str, timeout: Duration, log: &Path, mut ready: impl FnMut() -> bool) {
    let start = Instant::now();
    while !ready() {
        assert!(
            start.elapsed() < timeout,
            "timed out waiting for {what}; viewer log:\n{}",
            read_log(log)
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// The viewer's window id, once it is mapped; `None` when none showed within `timeout`.
/// Fails at once, with the viewer's log, when the viewer exits before its window shows.
pub(crate) fn window_of(viewer: &mut Viewer, log: &Path, timeout: Duration) -> Option<String> {
    let pid = viewer.0.id().to_string();
    let start = Instant::now();
    loop {
        // By the _NET_WM_PID property winit sets, or by the WM_CLASS it sets.
        for args in [
            ["search", "--onlyvisible", "--pid", pid.as_str()],
            ["search", "--onlyvisible", "--class", "decimate"],
        ] {
            if let Ok(out) = Command::new("xdotool").args(args).output() {
                if let Some(line) = String::from_utf8_lossy(&out.stdout).lines().last() {
                    if !line.trim().is_empty() {
                        return Some(line.trim().to_string());
                    }
                }
            }
        }
        if let Ok(Some(status)) = viewer.0.try_wait() {
            panic!(
                "the viewer exited with {status} before its window showed:\n{}",
                read_log(log)
            );
        }
        if start.elapsed() > timeout {
            return None;
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// An X client that stays connected for the whole test: `xprop -root -spy`, which watches the
/// root window until it is killed.
///
/// Xvfb, unless started with `-noreset`, resets itself each time its last client leaves, and
/// a client that connects during the reset is refused ("unable to open display"). Measured on
/// a loaded 2-core machine: 8 refusals in 2,400 connections that each followed the last
/// client's exit, none with `-noreset`. The viewer was such a client, right after the
/// `xdpyinfo` that checked the server; while this one is held the server has no reason to
/// reset, however the test is run.
pub(crate) struct HeldConnection(Child);

impl Drop for HeldConnection {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Connects the held client to the X server on `DISPLAY`, waiting for a server that is slow
/// to start; fails, naming the server and what `xdpyinfo` said, when none answers within
/// `timeout`, so that a server that is gone is not blamed on the viewer.
pub(crate) fn hold_x_connection(timeout: Duration) -> HeldConnection {
    let display = std::env::var("DISPLAY").unwrap_or_default();
    let start = Instant::now();
    loop {
        let child = Command::new("xprop")
            .args(["-root", "-spy"])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot run xprop (install x11-utils): {e}"));
        let mut held = HeldConnection(child);
        // xprop exits at once when it cannot connect; one still running after this while
        // has connected, and the server answering xdpyinfo now confirms it.
        std::thread::sleep(Duration::from_millis(300));
        let running = matches!(held.0.try_wait(), Ok(None));
        let out = Command::new("xdpyinfo")
            .output()
            .unwrap_or_else(|e| panic!("cannot run xdpyinfo (install x11-utils): {e}"));
        if running && out.status.success() {
            return held;
        }
        drop(held);
        assert!(
            start.elapsed() < timeout,
            "the X server on DISPLAY={display} does not answer (not the viewer's fault): {}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::thread::sleep(Duration::from_millis(250));
    }
}

/// The last lines of the viewer's stderr, for failure messages.
pub(crate) fn read_log(log: &Path) -> String {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(15)..].join("\n")
}

fn screenshot(path: &Path) -> Vec<u8> {
    run(
        "import",
        &[
            "-window",
            "root",
            "-depth",
            "8",
            &format!("rgb:{}", path.display()),
        ],
    );
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A fresh folder `name` under the test target's temp folder (left for a look after a failure).
pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// A 2×2×2 cube of 10×10 quads a face (test004's mesh), 602 vertices.
pub(crate) fn write_cube(path: &Path) {
    let model = decimate_core::mesh::shapes::cube(10, 2.0);
    assert_eq!(model.positions.len(), 602);
    let scene = decimate_core::mesh::Scene {
        models: vec![model],
    };
    decimate_core::io::write_vrml2(&scene, path).unwrap_or_else(|e| panic!("{e}"));
}

/// Vertices used by the scene F3 saved, once its writer has renamed it into place.
fn saved_vertices(out: &Path) -> usize {
    std::thread::sleep(Duration::from_millis(300));
    let saved = decimate_core::io::read_scene(out).unwrap_or_else(|e| panic!("{e}"));
    saved
        .scene
        .models
        .iter()
        .map(|m| m.used_vertex_count())
        .sum()
}

/// Pixels of the 1024-wide RGB screenshots `a` and `b` that differ in the given area.
fn changed_pixels(
    a: &[u8],
    b: &[u8],
    xs: std::ops::Range<usize>,
    ys: std::ops::Range<usize>,
) -> usize {
    let mut changed = 0;
    for y in ys {
        for x in xs.clone() {
            let i = (y * 1024 + x) * 3;
            if i + 2 < a.len()
                && i + 2 < b.len()
                && (0..3).any(|c| a[i + c].abs_diff(b[i + c]) > 16)
            {
                changed += 1;
            }
        }
    }
    changed
}

/// The mean x of the pixels of the 1024-wide RGB screenshot `shot` in rows `ys` that are
/// not the background (the commonest colour there): where the model is drawn.
fn drawn_centre_x(shot: &[u8], ys: std::ops::Range<usize>) -> f64 {
    let pixel = |x: usize, y: usize| {
        let i = (y * 1024 + x) * 3;
        shot.get(i..i + 3).map(|p| [p[0], p[1], p[2]])
    };
    let mut counts = std::collections::HashMap::new();
    for y in ys.clone() {
        for x in 0..1024 {
            if let Some(p) = pixel(x, y) {
                *counts.entry(p).or_insert(0usize) += 1;
            }
        }
    }
    let background = counts.into_iter().max_by_key(|&(_, n)| n).map(|(p, _)| p);
    let (mut sum, mut n) = (0.0, 0usize);
    for y in ys {
        for x in 0..1024 {
            if let (Some(p), Some(b)) = (pixel(x, y), background) {
                if (0..3).any(|c| p[c].abs_diff(b[c]) > 16) {
                    sum += x as f64;
                    n += 1;
                }
            }
        }
    }
    assert!(n > 100, "nothing drawn in the screenshot ({n} pixels)");
    sum / n as f64
}

/// Drags the pointer in window `wid` from `from` to `to` in small steps between the `press`
/// and `release` xdotool commands, then lets a frame land.
pub(crate) fn drag_with(
    wid: &str,
    press: &[&str],
    release: &[&str],
    from: (i32, i32),
    to: (i32, i32),
) {
    let at = |(x, y): (i32, i32)| {
        run(
            "xdotool",
            &["mousemove", "--window", wid, &x.to_string(), &y.to_string()],
        )
    };
    at(from);
    std::thread::sleep(Duration::from_millis(300));
    run("xdotool", press);
    std::thread::sleep(Duration::from_millis(200));
    for step in 1..=10 {
        let between = |a: i32, b: i32| a + (b - a) * step / 10;
        at((between(from.0, to.0), between(from.1, to.1)));
        std::thread::sleep(Duration::from_millis(50));
    }
    run("xdotool", release);
    std::thread::sleep(Duration::from_millis(800));
}

/// Starts the viewer as `decimate ARGS` in `dir` on lavapipe, its stderr going to `log`;
/// `trace`: with its `DECIMATE_TRACE` lines there.
fn spawn_viewer(
    dir: &Path,
    args: &[&str],
    trace: bool,
    log: &Path,
    env: &[(&str, &str)],
) -> Viewer {
    let file = std::fs::File::create(log)
        .unwrap_or_else(|e| panic!("cannot create {}: {e}", log.display()));
    let mut command = Command::new(env!("CARGO_BIN_EXE_decimate"));
    if trace {
        command.env("DECIMATE_TRACE", "1");
    }
    command.envs(env.iter().copied());
    let child = command
        .args(args)
        .current_dir(dir)
        .env("VK_ICD_FILENAMES", LAVAPIPE)
        .env("VK_DRIVER_FILES", LAVAPIPE)
        .env_remove("WAYLAND_DISPLAY")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(file)
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start the viewer: {e}"));
    Viewer(child)
}

/// Starts the viewer as `decimate ARGS` in `dir` with its trace going to `log` (see
/// [`spawn_viewer`]), and waits up to 60 s for its window: the viewer and the window's id.
/// Waits up to `timeout` for `what` in the viewer's log.
pub(crate) fn logged(log: &Path, what: &str, timeout: Duration) -> bool {
    let start = Instant::now();
    while start.elapsed() < timeout {
        if std::fs::read_to_string(log).is_ok_and(|t| t.contains(what)) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    false
}

/// The viewer started on a 10×10 cube in a new scratch folder `name`, traced to
/// `viewer.log` there, its window given the keyboard: (folder, log, viewer, window id).
pub(crate) fn start_cube_focused(name: &str) -> (PathBuf, PathBuf, Viewer, String) {
    let dir = scratch(name);
    write_cube(&dir.join("cube.wrl"));
    let log = dir.join("viewer.log");
    let (viewer, wid) = start_traced(&dir, &["cube.wrl"], &log);
    std::thread::sleep(Duration::from_secs(2));
    let _ = std::process::Command::new("xdotool")
        .args(["windowfocus", "--sync", &wid])
        .status();
    (dir, log, viewer, wid)
}

pub(crate) fn start_traced(dir: &Path, args: &[&str], log: &Path) -> (Viewer, String) {
    start_traced_with(dir, args, log, &[])
}

/// As [`start_traced`], with environment variables `env` set for the viewer.
pub(crate) fn start_traced_with(
    dir: &Path,
    args: &[&str],
    log: &Path,
    env: &[(&str, &str)],
) -> (Viewer, String) {
    let mut viewer = spawn_viewer(dir, args, true, log, env);
    let wid = window_of(&mut viewer, log, Duration::from_secs(60))
        .unwrap_or_else(|| panic!("no window in 60 s; viewer log:\n{}", read_log(log)));
    (viewer, wid)
}

/// Presses q in window `wid` and asserts that the viewer quits, successfully, within 20 s.
pub(crate) fn quit(mut viewer: Viewer, wid: &str, log: &Path) {
    // xdotool sends the key's press and release as two events; a viewer that quits on the
    // press may destroy its window before the release is sent, and xdotool then fails with
    // BadWindow. So its status is not asserted: the viewer's exit is.
    let sent = Command::new("xdotool")
        .args(["key", "--window", wid, "q"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stderr).into_owned())
        .unwrap_or_else(|e| format!("cannot run xdotool: {e}"));
    let start = Instant::now();
    loop {
        if let Ok(Some(status)) = viewer.0.try_wait() {
            assert!(
                status.success(),
                "the viewer exited with {status}; viewer log:\n{}",
                read_log(log)
            );
            return;
        }
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "q did not quit the viewer (xdotool said: {sent}); viewer log:\n{}",
            read_log(log)
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

#[test]
fn keys_decimate_and_save_and_right_click_opens_the_menu() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let dir = scratch("gui_xvfb");
    // The input is named as F3's output: F3 must write beside it, never over it.
    let input = dir.join("out.wrl");
    write_cube(&input);
    let input_bytes = std::fs::read(&input).unwrap_or_else(|e| panic!("{e}"));
    // A viewer whose window never shows is reported with its log and the X window tree; it
    // is started a second time first, so that one slow start on a loaded machine is told
    // apart from a viewer that cannot open its window.
    let mut attempts = Vec::new();
    let (viewer, wid, log_path) = loop {
        let log_path = dir.join(format!("viewer-{}.log", attempts.len() + 1));
        let mut viewer = spawn_viewer(&dir, &["out.wrl"], false, &log_path, &[]);
        if let Some(wid) = window_of(&mut viewer, &log_path, Duration::from_secs(45)) {
            break (viewer, wid, log_path);
        }
        let tree = Command::new("xwininfo")
            .args(["-root", "-tree"])
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
            .unwrap_or_default();
        attempts.push(format!(
            "attempt {}: no window in 45 s\nwindows:\n{tree}\nviewer log:\n{}",
            attempts.len() + 1,
            read_log(&log_path)
        ));
        drop(viewer);
        assert!(attempts.len() < 2, "{}", attempts.join("\n\n"));
    };
    for a in &attempts {
        eprintln!("gui_xvfb: {a}");
    }
    // Let the first frames (shader compilation, fonts) land.
    std::thread::sleep(Duration::from_secs(2));
    let _ = Command::new("xdotool")
        .args(["windowfocus", "--sync", &wid])
        .status();

    // 9: remove 90 % of the vertices; F3: save the current viewport, as out-1.wrl since
    // out.wrl is the input.
    run("xdotool", &["key", "--window", &wid, "9"]);
    std::thread::sleep(Duration::from_secs(1));
    run("xdotool", &["key", "--window", &wid, "F3"]);
    let out = dir.join("out-1.wrl");
    wait_for("out-1.wrl", Duration::from_secs(30), &log_path, || {
        out.exists()
    });
    // F3 waits for the decimation to end (the controller settles first): 602 less 90 %
    // (542, rounded) leaves exactly 60, as `nogui -p 90` does.
    let vertices = saved_vertices(&out);
    assert_eq!(
        vertices, 60,
        "out-1.wrl has {vertices} vertices; 602 less 90 % is 60"
    );
    assert_eq!(
        std::fs::read(&input).unwrap_or_else(|e| panic!("{e}")),
        input_bytes,
        "F3 wrote over the input"
    );
    assert!(
        read_log(&log_path).contains("out.wrl is the input file"),
        "the viewer did not say why it saved as out-1.wrl:\n{}",
        read_log(&log_path)
    );
    // F3 twice, two files: the second save goes to out-2.wrl, out-1.wrl kept as it was.
    let first = std::fs::read(&out).unwrap_or_else(|e| panic!("{e}"));
    run("xdotool", &["key", "--window", &wid, "F3"]);
    let second = dir.join("out-2.wrl");
    wait_for("out-2.wrl", Duration::from_secs(30), &log_path, || {
        second.exists()
    });
    assert_eq!(
        saved_vertices(&second),
        60,
        "out-2.wrl is not the same result"
    );
    assert_eq!(
        std::fs::read(&out).unwrap_or_default(),
        first,
        "the second F3 wrote over out-1.wrl"
    );

    // F2: a picture of the window as window.png: the window's size, the model on it.
    run("xdotool", &["key", "--window", &wid, "F2"]);
    let picture = dir.join("window.png");
    wait_for("window.png", Duration::from_secs(30), &log_path, || {
        picture.exists()
    });
    std::thread::sleep(Duration::from_millis(300));
    let file = std::fs::File::open(&picture).unwrap_or_else(|e| panic!("{e}"));
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap_or_else(|e| panic!("window.png: {e}"));
    let mut pixels = vec![0; reader.output_buffer_size().unwrap_or(0)];
    let info = reader
        .next_frame(&mut pixels)
        .unwrap_or_else(|e| panic!("window.png: {e}"));
    assert!(
        info.width >= 800 && info.height >= 600,
        "window.png is {}x{}",
        info.width,
        info.height
    );
    let corner = &pixels[..4];
    let drawn = pixels
        .chunks(4)
        .filter(|p| p.iter().zip(corner).any(|(a, b)| a.abs_diff(*b) > 16))
        .count();
    assert!(
        drawn * 20 > (info.width * info.height) as usize,
        "window.png shows little but background: {drawn} pixels"
    );
    // The status line is in the picture, as in the window: light text in the bottom strip.
    let row = 4 * info.width as usize;
    let strip = &pixels[pixels.len() - 20 * row..];
    let text = strip
        .chunks(4)
        .filter(|p| p[..3].iter().all(|&c| c > 150))
        .count();
    assert!(
        text > 50,
        "window.png's status strip is empty: {text} light pixels in its bottom 20 rows"
    );

    // v opens "Decimate to N vertices": a word is refused and the field stays open (else the
    // digits typed next would be decimate keys), Enter submits 100, F3 saves exactly that.
    run("xdotool", &["key", "--window", &wid, "v"]);
    std::thread::sleep(Duration::from_millis(800));
    run(
        "xdotool",
        &["type", "--window", &wid, "--delay", "80", "abc"],
    );
    run("xdotool", &["key", "--window", &wid, "Return"]);
    std::thread::sleep(Duration::from_millis(500));
    for _ in 0..3 {
        run("xdotool", &["key", "--window", &wid, "BackSpace"]);
    }
    run(
        "xdotool",
        &["type", "--window", &wid, "--delay", "80", "100"],
    );
    run("xdotool", &["key", "--window", &wid, "Return"]);
    std::thread::sleep(Duration::from_secs(1));
    let _ = std::fs::remove_file(&out);
    run("xdotool", &["key", "--window", &wid, "F3"]);
    wait_for(
        "out-1.wrl after the field",
        Duration::from_secs(30),
        &log_path,
        || out.exists(),
    );
    assert_eq!(saved_vertices(&out), 100, "Decimate to 100 vertices");

    // Right click: the popup menu appears around the pointer.
    let before = screenshot(&dir.join("before.rgb"));
    run(
        "xdotool",
        &["mousemove", "--window", &wid, "300", "300", "click", "3"],
    );
    std::thread::sleep(Duration::from_secs(2));
    let after = screenshot(&dir.join("after.rgb"));
    assert_eq!(before.len(), after.len(), "screen size changed");
    // Compare the area right and below of the click (where egui places the menu).
    let changed = changed_pixels(&before, &after, 300..450, 300..420);
    let total = 150 * 120;
    assert!(
        changed * 4 > total,
        "the menu did not appear: {changed} of {total} pixels changed near the click"
    );

    // Escape closes the popup; L opens the level-of-detail slider at the top left, showing
    // the original (602 vertices); dragging it coarsens the mesh, and F3 saves that level.
    // Key 1 first (about 540 vertices), so that a slider that does nothing is caught.
    run("xdotool", &["key", "--window", &wid, "Escape"]);
    run("xdotool", &["key", "--window", &wid, "1"]);
    std::thread::sleep(Duration::from_millis(800));
    let before = screenshot(&dir.join("before-lod.rgb"));
    run("xdotool", &["key", "--window", &wid, "L"]);
    std::thread::sleep(Duration::from_secs(3));
    let after = screenshot(&dir.join("after-lod.rgb"));
    let changed = changed_pixels(&before, &after, 10..370, 10..50);
    assert!(
        changed * 10 > 360 * 40,
        "the level-of-detail slider did not appear: {changed} pixels changed"
    );
    drag_with(
        &wid,
        &["mousedown", "1"],
        &["mouseup", "1"],
        (100, 40),
        (120, 40),
    );
    // Let the geomorph end (0.3 s) before saving.
    std::thread::sleep(Duration::from_secs(1));
    let _ = std::fs::remove_file(&out);
    run("xdotool", &["key", "--window", &wid, "F3"]);
    wait_for(
        "out-1.wrl after the slider",
        Duration::from_secs(30),
        &log_path,
        || out.exists(),
    );
    let vertices = saved_vertices(&out);
    assert!(
        (8..300).contains(&vertices),
        "out-1.wrl has {vertices} vertices after dragging the slider to the left"
    );

    // t hides the triangles, e shows the edges: a list the viewer had not uploaded (it
    // uploads only what the draw modes need), so it must upload the scene again.
    run("xdotool", &["key", "--window", &wid, "t"]);
    std::thread::sleep(Duration::from_millis(800));
    let bare = screenshot(&dir.join("no-triangles.rgb"));
    run("xdotool", &["key", "--window", &wid, "e"]);
    std::thread::sleep(Duration::from_millis(800));
    let wire = screenshot(&dir.join("edges.rgb"));
    let changed = changed_pixels(&bare, &wire, 212..812, 84..684);
    assert!(
        changed > 500,
        "the edges did not appear: {changed} pixels changed in the middle of the window"
    );

    // The middle button drags the view across the window: the wireframe follows the pointer
    // 200 px to the right (the point under it at the model centre's depth exactly; the cube's
    // nearer front faces, most of its lines, a little more). Shift + left drag (for a
    // touchpad: no middle button) brings it back where it was. Rows between the
    // level-of-detail slider and the status line.
    let centre = |shot: &[u8]| drawn_centre_x(shot, 84..640);
    let start = centre(&wire);
    let middle = (["mousedown", "2"], ["mouseup", "2"]);
    drag_with(&wid, &middle.0, &middle.1, (400, 380), (600, 380));
    let panned = centre(&screenshot(&dir.join("panned.rgb")));
    assert!(
        (170.0..260.0).contains(&(panned - start)),
        "a 200 px middle drag moved the model from x {start:.0} to {panned:.0}"
    );
    run("xdotool", &["keydown", "Shift_L"]);
    std::thread::sleep(Duration::from_millis(300));
    let left = (["mousedown", "1"], ["mouseup", "1"]);
    drag_with(&wid, &left.0, &left.1, (600, 380), (400, 380));
    run("xdotool", &["keyup", "Shift_L"]);
    let back = centre(&screenshot(&dir.join("panned-back.rgb")));
    assert!(
        (back - start).abs() < 3.0,
        "Shift + left drag back: the model is at x {back:.0}, it started at {start:.0}"
    );

    // q quits.
    quit(viewer, &wid, &log_path);
    assert_eq!(
        std::fs::read(&input).unwrap_or_else(|e| panic!("{e}")),
        input_bytes,
        "the input changed while the viewer ran"
    );
}

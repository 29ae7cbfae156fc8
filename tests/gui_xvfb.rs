//! The interactive viewer end to end in a real X window (Xvfb), driven the way a user drives
//! it: key `9` decimates the current viewport by 90 %, F3 saves it as `out.wrl` in the working
//! directory, the right mouse button opens the popup menu. Run under
//! `xvfb-run -a -s "-screen 0 1024x768x24" cargo test`. Without `DISPLAY` the test is skipped
//! with a notice, except when `CI` is set: there it fails.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const LAVAPIPE: &str = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

/// Kills the viewer if the test fails half-way.
struct Viewer(Child);

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn display_or_skip() -> bool {
    if std::env::var_os("DISPLAY").is_some() {
        return true;
    }
    if std::env::var_os("CI").is_some() {
        panic!("DISPLAY is not set: run the tests under xvfb-run -a -s \"-screen 0 1024x768x24\"");
    }
    eprintln!("gui_xvfb: DISPLAY is not set, skipping (CI runs this under xvfb-run)");
    false
}

fn run(program: &str, args: &[&str]) -> String {
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

fn wait_for(what: &str, timeout: Duration, mut ready: impl FnMut() -> bool) {
    let start = Instant::now();
    while !ready() {
        assert!(start.elapsed() < timeout, "timed out waiting for {what}");
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// The viewer's window id, once it is mapped.
fn window_of(pid: u32) -> String {
    let mut id = String::new();
    wait_for("the viewer's window", Duration::from_secs(30), || {
        let out = Command::new("xdotool")
            .args(["search", "--onlyvisible", "--pid", &pid.to_string()])
            .output();
        if let Ok(out) = out {
            if let Some(line) = String::from_utf8_lossy(&out.stdout).lines().last() {
                id = line.trim().to_string();
            }
        }
        !id.is_empty()
    });
    id
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

fn scratch() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gui_xvfb");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// test004: a 10×10-segment cube, 602 vertices.
fn write_cube(path: &Path) {
    use decimate::mesh::{Model, Scene};
    use glam::Vec3;
    let n = 10u32;
    let mut model = Model::default();
    let mut index = std::collections::HashMap::new();
    for (normal, u, v) in [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (-Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (-Vec3::Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (-Vec3::Z, Vec3::Y, Vec3::X),
    ] {
        let mut ids = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let p = normal + u * (i as f32 / 5.0 - 1.0) + v * (j as f32 / 5.0 - 1.0);
                let key = (p * 5.0).round().as_ivec3().to_array();
                ids.push(*index.entry(key).or_insert_with(|| {
                    model.positions.push(p);
                    model.positions.len() as u32 - 1
                }));
            }
        }
        let at = |i: u32, j: u32| ids[(j * (n + 1) + i) as usize];
        for j in 0..n {
            for i in 0..n {
                model
                    .triangles
                    .push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                model
                    .triangles
                    .push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    assert_eq!(model.positions.len(), 602);
    let scene = Scene {
        models: vec![model],
    };
    decimate::io::write_vrml2(&scene, path).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn keys_decimate_and_save_and_right_click_opens_the_menu() {
    if !display_or_skip() {
        return;
    }
    let dir = scratch();
    write_cube(&dir.join("cube.wrl"));
    let child = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .arg("cube.wrl")
        .current_dir(&dir)
        .env("VK_ICD_FILENAMES", LAVAPIPE)
        .env("VK_DRIVER_FILES", LAVAPIPE)
        .env_remove("WAYLAND_DISPLAY")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start the viewer: {e}"));
    let mut viewer = Viewer(child);
    let wid = window_of(viewer.0.id());
    // Let the first frames (shader compilation, fonts) land.
    std::thread::sleep(Duration::from_secs(2));
    let _ = Command::new("xdotool")
        .args(["windowfocus", "--sync", &wid])
        .status();

    // 9: remove 90 % of the vertices; F3: save the current viewport as out.wrl.
    run("xdotool", &["key", "--window", &wid, "9"]);
    std::thread::sleep(Duration::from_secs(1));
    run("xdotool", &["key", "--window", &wid, "F3"]);
    let out = dir.join("out.wrl");
    wait_for("out.wrl", Duration::from_secs(20), || out.exists());
    std::thread::sleep(Duration::from_millis(300));
    let saved = decimate::io::read_scene(&out).unwrap_or_else(|e| panic!("{e}"));
    let vertices: usize = saved
        .scene
        .models
        .iter()
        .map(|m| m.used_vertex_count())
        .sum();
    assert!(
        (30..=90).contains(&vertices),
        "out.wrl has {vertices} vertices; about 10 % of 602 expected"
    );

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
    let width = 1024usize;
    let mut changed = 0;
    let mut total = 0;
    for y in 300..420usize {
        for x in 300..450usize {
            let i = (y * width + x) * 3;
            if i + 2 < before.len() {
                total += 1;
                if (0..3).any(|c| before[i + c].abs_diff(after[i + c]) > 16) {
                    changed += 1;
                }
            }
        }
    }
    assert!(
        changed * 4 > total,
        "the menu did not appear: {changed} of {total} pixels changed near the click"
    );

    // q quits.
    run("xdotool", &["key", "--window", &wid, "Escape"]);
    run("xdotool", &["key", "--window", &wid, "q"]);
    let start = Instant::now();
    loop {
        if let Ok(Some(status)) = viewer.0.try_wait() {
            assert!(status.success(), "the viewer exited with {status}");
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "q did not quit the viewer"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

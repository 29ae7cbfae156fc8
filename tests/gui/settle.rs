//! Anti-aliasing at interactive speed: while the left button turns the model the window
//! draws single-sampled frames, and once the view rests one 4× frame (lavapipe offers 4
//! samples). The viewer's `DECIMATE_TRACE` lines give each frame's sample count.

use std::path::Path;
use std::time::Duration;

use super::xvfb::{display_or_skip, drag_with, hold_x_connection, read_log, scratch, start_traced};

/// The sample counts of the frames traced in `log`, in order.
fn frame_samples(log: &Path) -> Vec<u32> {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    text.lines()
        .filter(|l| l.starts_with("decimate: trace ") && l.contains(": frame in "))
        .filter_map(|l| {
            l.strip_suffix("x samples")?
                .rsplit(", ")
                .next()?
                .parse()
                .ok()
        })
        .collect()
}

#[test]
fn turning_the_model_draws_single_sampled_then_one_4x_frame_at_rest() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let dir = scratch("gui_settle");
    let scene = decimate_core::mesh::Scene {
        models: vec![decimate_core::mesh::shapes::uv_sphere(30, 60)],
    };
    decimate_core::io::write_ply(&scene, &dir.join("sphere.ply")).unwrap_or_else(|e| panic!("{e}"));
    let log = dir.join("viewer.log");
    let (_viewer, wid) = start_traced(&dir, &["sphere.ply", "gui", "--msaa", "4"], &log);
    std::thread::sleep(Duration::from_secs(2));
    let before = frame_samples(&log);
    assert_eq!(
        before.last(),
        Some(&4),
        "the view at rest is not drawn with 4 samples; viewer log:\n{}",
        read_log(&log)
    );
    // A left drag turns the model; drag_with waits 800 ms after the release.
    let left = (["mousedown", "1"], ["mouseup", "1"]);
    drag_with(&wid, &left.0, &left.1, (400, 380), (600, 380));
    let after = frame_samples(&log);
    let during = &after[before.len()..];
    assert!(
        during.iter().filter(|&&s| s == 1).count() >= 3,
        "the drag's frames were not single-sampled: {during:?}; viewer log:\n{}",
        read_log(&log)
    );
    assert_eq!(
        during.last(),
        Some(&4),
        "no 4x frame once the view rested: {during:?}"
    );
}

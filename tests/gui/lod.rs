//! The level-of-detail slider sits inside its own viewport: in viewport 2 of 2 it is dragged
//! there (not in viewport 1's corner, where it used to be), and F3 saves viewport 2 at the
//! level it was dragged to.

use std::time::Duration;

use super::xvfb::{display_or_skip, drag_with, hold_x_connection, logged, read_log, run};

#[test]
fn the_slider_of_viewport_2_is_dragged_inside_viewport_2() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let (dir, log, viewer, wid) = super::xvfb::start_cube_focused("gui_lod");
    let key = |k: &str| run("xdotool", &["key", "--window", &wid, k]);
    // a: viewport 2 (the right half, from x 513), current; L: its slider.
    key("a");
    std::thread::sleep(Duration::from_millis(500));
    key("L");
    assert!(
        logged(&log, "level of detail", Duration::from_secs(30)),
        "the slider was not built; log:\n{}",
        read_log(&log)
    );
    std::thread::sleep(Duration::from_secs(1));
    // Drag its knob (at the right end: the original's 602 vertices) well to the left.
    drag_with(
        &wid,
        &["mousedown", "1"],
        &["mouseup", "1"],
        (513 + 6 + 8 + 236, 40),
        (513 + 6 + 8 + 40, 40),
    );
    std::thread::sleep(Duration::from_secs(1));
    key("F3");
    let out = dir.join("out.wrl");
    assert!(
        logged(&log, "saved viewport 2 as out.wrl", Duration::from_secs(30)),
        "F3 did not save viewport 2; log:\n{}",
        read_log(&log)
    );
    std::thread::sleep(Duration::from_millis(300));
    let saved = decimate_core::io::read_scene(&out).unwrap_or_else(|e| panic!("{e}"));
    let vertices: usize = (saved.scene.models.iter())
        .map(|m| m.used_vertex_count())
        .sum();
    assert!(
        (8..400).contains(&vertices),
        "viewport 2 saved with {vertices} vertices after its slider was dragged left"
    );
    super::xvfb::quit(viewer, &wid, &log);
}

//! Each viewport has its own panel (collapsed until opened): in viewport 2 of 2, a click on
//! its header opens it, its algorithm switch picks edge collapse and its Decimate button
//! removes 90 % — of viewport 2, not of viewport 1 — and F3 saves viewport 2 with the
//! cube's 90 % count. Positions: the window is 1024 wide, viewport 2 starts at x 513, and
//! the panel's rows are 21 px apart from y 22 (text at its unscaled size at 720 px high).

use std::time::Duration;

use super::xvfb::{display_or_skip, hold_x_connection, logged, read_log, run};

#[test]
fn the_panel_of_viewport_2_decimates_viewport_2_with_the_algorithm_picked() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let (dir, log, viewer, wid) = super::xvfb::start_cube_focused("gui_panel");
    let key = |k: &str| run("xdotool", &["key", "--window", &wid, k]);
    let click = |x: u32, y: u32| {
        let (x, y) = (x.to_string(), y.to_string());
        run(
            "xdotool",
            &["mousemove", "--window", &wid, &x, &y, "click", "1"],
        );
        std::thread::sleep(Duration::from_millis(700));
    };
    key("a");
    std::thread::sleep(Duration::from_millis(700));
    // Tab: viewport 1 current, so that the panel's own viewport is seen to be taken.
    key("Tab");
    std::thread::sleep(Duration::from_millis(300));
    click(513 + 50, 22); // the header "Viewport 2"
    click(513 + 219, 43); // "edge collapse (qem)"
    click(513 + 256, 64); // "Decimate" (at 90 %)
    let wanted = [
        "panel of viewport 2: ToggleAlgorithm",
        "panel of viewport 2: Decimate",
        "viewport 2: removed 90 %: 60 vertices",
    ];
    for what in wanted {
        assert!(
            logged(&log, what, Duration::from_secs(30)),
            "no {what:?}; viewer log:\n{}",
            read_log(&log)
        );
    }
    let whole = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(!whole.contains("viewport 1: removed"), "{whole}");
    key("F3");
    assert!(
        logged(&log, "saved viewport 2 as out.wrl", Duration::from_secs(30)),
        "F3 did not save viewport 2; viewer log:\n{}",
        read_log(&log)
    );
    std::thread::sleep(Duration::from_millis(300));
    let saved = decimate_core::io::read_scene(&dir.join("out.wrl"));
    let saved = saved.unwrap_or_else(|e| panic!("{e}"));
    let vertices: usize = (saved.scene.models.iter())
        .map(|m| m.used_vertex_count())
        .sum();
    assert_eq!(vertices, 60, "the cube's 602 vertices less 90 %");
    super::xvfb::quit(viewer, &wid, &log);
}

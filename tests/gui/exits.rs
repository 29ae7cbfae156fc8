//! Leaving the viewer loses nothing by accident: Esc closes the help overlay and never quits;
//! q with a decimated viewport unsaved asks first (y answers); F3 twice writes two files,
//! the second numbered, never over the first; the start prints one line, not the usage.

use std::time::Duration;

use super::xvfb::{
    display_or_skip, hold_x_connection, logged, read_log, run, scratch, start_traced,
};

fn still_running(viewer: &mut super::xvfb::Viewer) -> bool {
    matches!(viewer.0.try_wait(), Ok(None))
}

#[test]
fn esc_never_quits_q_asks_for_unsaved_work_and_f3_numbers_its_saves() {
    if !display_or_skip() {
        return;
    }
    let _window = super::ONE_WINDOW.lock();
    let _held = hold_x_connection(Duration::from_secs(20));
    let dir = scratch("gui_exits");
    let input = dir.join("cube.wrl");
    super::xvfb::write_cube(&input);
    let log = dir.join("viewer.log");
    let (mut viewer, wid) = start_traced(&dir, &["cube.wrl"], &log);
    std::thread::sleep(Duration::from_secs(2));
    let _ = std::process::Command::new("xdotool")
        .args(["windowfocus", "--sync", &wid])
        .status();
    let key = |k: &str| run("xdotool", &["key", "--window", &wid, k]);
    // The start prints a one-line hint, not the command line's usage.
    let started = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(
        !started.contains("action-options") && started.contains("h shows the keys"),
        "the viewer's start printed:\n{started}"
    );

    // h opens the help overlay; Esc closes it and the window stays.
    key("h");
    std::thread::sleep(Duration::from_millis(500));
    key("Escape");
    assert!(logged(&log, "key Escape", Duration::from_secs(10)));
    // A second Esc with nothing open, nothing running: still no quit.
    key("Escape");
    std::thread::sleep(Duration::from_secs(2));
    assert!(
        still_running(&mut viewer),
        "Esc quit the viewer; log:\n{}",
        read_log(&log)
    );

    // 9 decimates; q asks instead of quitting, n stays.
    key("9");
    assert!(
        logged(&log, "removed 90 %", Duration::from_secs(30)),
        "the decimation did not end; log:\n{}",
        read_log(&log)
    );
    key("q");
    assert!(
        logged(&log, "viewport 1 not saved", Duration::from_secs(10)),
        "q did not ask; log:\n{}",
        read_log(&log)
    );
    std::thread::sleep(Duration::from_secs(1));
    assert!(still_running(&mut viewer), "q quit with an unsaved result");
    key("n");
    std::thread::sleep(Duration::from_millis(500));

    // F3 twice: out.wrl, then out-1.wrl beside it; the first stays as it was.
    key("F3");
    let (first, second) = (dir.join("out.wrl"), dir.join("out-1.wrl"));
    assert!(logged(&log, "as out.wrl", Duration::from_secs(30)));
    let first_bytes = std::fs::read(&first).unwrap_or_else(|e| panic!("out.wrl: {e}"));
    key("F3");
    assert!(
        logged(&log, "as out-1.wrl", Duration::from_secs(30)),
        "the second F3 did not save as out-1.wrl; log:\n{}",
        read_log(&log)
    );
    assert!(second.exists(), "out-1.wrl missing");
    assert_eq!(
        std::fs::read(&first).unwrap_or_else(|e| panic!("out.wrl: {e}")),
        first_bytes,
        "the second F3 wrote over out.wrl"
    );

    // Saved: q quits at once.
    super::xvfb::quit(viewer, &wid, &log);
}

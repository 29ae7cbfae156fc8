//! The interactive viewer in a real X window (Xvfb). A crate of its own, so that its window
//! test runs alone, not beside the screenshot tests, as `cargo test` runs crates one by one.

mod busy;
mod dialogs;
mod exits;
mod job_speed;
mod lod;
mod panel;
mod settle;
mod xvfb;

/// Held by each window test: one viewer at a time on the X server (the tests of a crate run
/// in parallel threads).
static ONE_WINDOW: std::sync::Mutex<()> = std::sync::Mutex::new(());

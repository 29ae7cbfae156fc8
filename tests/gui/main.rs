//! The interactive viewer in a real X window (Xvfb). A crate of its own, so that its window
//! test runs alone, not beside the screenshot tests, as `cargo test` runs crates one by one.

mod xvfb;

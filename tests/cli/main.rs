//! The `decimate` command line as a user runs it, and the bundled models it is shown with.

#[path = "../support/mod.rs"]
mod support;

mod assets;
mod repair;
mod threads;
mod usage;

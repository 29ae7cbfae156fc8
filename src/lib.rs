//! The `decimate` command line, on top of `decimate-core` (the algorithms and formats) and
//! `decimate-viewer` (the Vulkan viewer): `cli` parses the original program's usage, `batch`
//! runs the `nogui` action, `tile_command` the tiled steps; `viewer_start` hands the `gui` and
//! `shot` actions to the viewer. The binaries are src/main.rs (`decimate`) and
//! src/bin/metro.rs (`metro`).
#![warn(
    rust_2018_idioms,
    trivial_casts,
    unused_qualifications,
    clippy::use_self
)]

pub mod batch;
pub mod cli;
pub mod tile_command;
pub mod viewer_start;

//! Mesh decimation: scenes read from VRML 1.0 / 2.0, Open Inventor ASCII, PLY, OBJ (with MTL),
//! STL, OFF and glTF 2.0 files, simplified by Schroeder–Zarge–Lorensen vertex removal or
//! Garland–Heckbert quadric edge collapse (with a progressive-mesh record), written back in any
//! of those formats, drawn by a Vulkan viewer and measured by `metro` (Hausdorff distance).
//!
//! Programs start at [`api`]: [`api::simplify`] takes arrays of positions and indices,
//! [`api::simplify_file`] a file in any of those formats.
//!
//! Layers, bottom to top (checked by tests/layers.rs): `mesh` (the data model: scenes,
//! topology, progressive meshes, images); `io` (readers and writers) beside `decimate` (one
//! module per algorithm behind [`decimate::simplify_scene`]); `metro` (surface distance);
//! `render` (Vulkan drawing of what it is given); `cli` (the parsed command line); `app` (the
//! viewer and `shot`) beside `batch` (`nogui`) and `api` (the library's entry point for
//! programs); the binaries in src/main.rs and src/bin/.
//! `alloc`, `threads` and `progress_bar` are process plumbing under all of them.
#![warn(
    rust_2018_idioms,
    trivial_casts,
    unused_qualifications,
    clippy::use_self
)]

pub mod alloc;
pub mod api;
pub mod app;
pub mod batch;
pub mod cancel;
pub mod cli;
pub mod decimate;
pub mod io;
pub mod mesh;
pub mod metro;
pub mod progress_bar;
pub mod render;
pub mod threads;
pub mod tile;

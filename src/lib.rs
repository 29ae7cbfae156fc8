//! Mesh decimation library: scenes read from VRML 1.0 / 2.0, Open Inventor, PLY, OBJ, STL,
//! OFF and glTF 2.0 files, decimated by Schroeder–Zarge–Lorensen vertex removal or
//! Garland–Heckbert quadric edge collapse, and written back in any of those formats.
//!
//! Programs start at [`api`]: [`api::simplify`] takes arrays of positions and indices,
//! [`api::simplify_file`] a file. The binary `decimate` (src/main.rs) is a thin start-up
//! over this crate: `cli` parses the original program's usage, `io` reads and writes
//! scenes, `mesh` holds the shared data model and topology, `decimate` holds one module per
//! algorithm.
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
pub mod cli;
pub mod decimate;
pub mod io;
pub mod mesh;
pub mod metro;
pub mod render;
pub mod threads;

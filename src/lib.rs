//! Mesh decimation library: scenes read from VRML 1.0 / 2.0 and Open Inventor ASCII files,
//! decimated by Schroeder–Zarge–Lorensen vertex removal, and written back as VRML 2.0.
//!
//! The binary `decimate` (src/main.rs) is a thin start-up over this crate: `cli` parses the
//! original program's usage, `io` reads and writes scenes, `mesh` holds the shared data model
//! and topology, `decimate` holds one module per algorithm.
#![warn(
    rust_2018_idioms,
    trivial_casts,
    unused_qualifications,
    clippy::use_self
)]

pub mod alloc;
pub mod app;
pub mod batch;
pub mod cli;
pub mod decimate;
pub mod io;
pub mod mesh;
pub mod metro;
pub mod render;
pub mod threads;
pub mod tile;

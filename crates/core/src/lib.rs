//! decimate-core: mesh decimation without a GPU. Scenes are read from VRML 1.0 / 2.0, Open
//! Inventor ASCII, PLY, OBJ (with MTL), STL, OFF and glTF 2.0 files, simplified by
//! Schroeder–Zarge–Lorensen vertex removal or Garland–Heckbert quadric edge collapse (with a
//! progressive-mesh record), written back in any of those formats, measured by `metro`
//! (Hausdorff distance) and, for meshes larger than memory, decimated in tiles.
//!
//! Programs start at [`api`]: [`api::simplify`] takes arrays of positions and indices,
//! [`api::simplify_file`] a file in any of those formats.
//!
//! Layers, bottom to top (checked by tests/layers.rs): `mesh` (the data model: scenes,
//! topology, progressive meshes, images); `io` (readers and writers) beside `decimate` (one
//! module per algorithm behind [`decimate::simplify_scene`]); `metro` (surface distance);
//! `tile` (tiled decimation) beside `api` (the entry point for programs).
//! `alloc`, `threads`, `progress_bar` and `cancel` are process plumbing under all of them.
#![deny(missing_docs)]
#![warn(
    rust_2018_idioms,
    trivial_casts,
    unused_qualifications,
    clippy::use_self
)]

pub mod alloc;
pub mod api;
pub mod cancel;
pub mod decimate;
pub mod io;
pub mod mesh;
pub mod metro;
pub mod progress_bar;
pub mod threads;
pub mod tile;

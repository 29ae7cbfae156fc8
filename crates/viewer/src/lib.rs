//! decimate-viewer: the Vulkan side of decimate, on top of `decimate-core`. `render` draws
//! what it is given (an ash renderer: context, swapchain, pipelines, meshes, offscreen
//! targets); `app` is the GLUT-style viewer (a `ViewportController` dispatching decimate
//! events to `Viewport`s, menus, jobs on worker threads) and the offscreen `shot`.
//!
//! Layers (checked by tests/layers.rs): `render` < `app`; neither reads the command line,
//! which the `decimate` binary parses and hands over as plain options.
#![warn(
    rust_2018_idioms,
    trivial_casts,
    unused_qualifications,
    clippy::use_self
)]

pub mod app;
pub mod render;

//! The data model shared by every reader, writer, algorithm and the viewer: a `Scene` of
//! `Model`s over flat arrays, plus topology (adjacency, vertex classification), normals and
//! welding built on top of them.

pub mod build;
pub mod classify;
pub mod measure;
pub mod scene;
pub mod shapes;
pub mod spatial;
pub mod topology;
pub mod weld;

pub use scene::{Attribute, Model, Scene};

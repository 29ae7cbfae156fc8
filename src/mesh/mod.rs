//! The data model shared by every reader, writer, algorithm and the viewer: a `Scene` of
//! `Model`s over flat arrays, plus topology (adjacency, vertex classification), normals and
//! welding built on top of them.

pub mod scene;
pub mod weld;

pub use scene::{Attribute, Model, Scene};

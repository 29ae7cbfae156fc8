//! The `metro` error tool: distances against answers known in closed form, its count of
//! folded triangles, and its command line.

#[path = "../support/mod.rs"]
mod support;

mod cli;
mod exact;
mod folded;

//! Helpers shared by the test crates, included by each as
//! `#[path = "../support/mod.rs"] mod support;`: the binary run in a folder, Debian's
//! Inventor sample data, seeded random numbers, the screenshot tests' scenes and golden
//! comparison, the texture tests' corner lists, the geometric checks of decimated models
//! and an independent reader of our OBJ and PLY output.
// Each crate uses only part of it.
#![allow(dead_code)]

pub mod binary;
pub mod check;
pub mod inventor;
pub mod metro;
pub mod plain_files;
pub mod rng;
pub mod shapes;
pub mod shot;
pub mod texture;

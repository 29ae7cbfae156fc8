//! Helpers shared by the test crates, included by each as
//! `#[path = "../support/mod.rs"] mod support;`: the binary run in a folder, Debian's
//! Inventor sample data, seeded random numbers, the screenshot tests' scenes and golden
//! comparison, and the texture tests' corner lists.
// Each crate uses only part of it.
#![allow(dead_code)]

pub mod binary;
pub mod inventor;
pub mod metro;
pub mod rng;
pub mod shapes;
pub mod shot;
pub mod texture;

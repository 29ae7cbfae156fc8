//! Decimation by both algorithms: exact counts on the report's models, the invariants every
//! output keeps (on random meshes too), creases, models stitched along shared borders,
//! texture coordinates and seams, and progressive meshes.

#[path = "../support/mod.rs"]
mod support;

mod creases;
mod progressive;
mod qem;
mod random;
mod report_models;
mod schroeder;
mod stitches;
mod texcoords;

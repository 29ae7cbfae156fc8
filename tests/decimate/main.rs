//! Decimation by both algorithms: exact counts on the report's models, the invariants every
//! output keeps (on random meshes too), creases, models stitched along shared borders,
//! texture coordinates and seams, progressive meshes, non-manifold shapes, open borders, and
//! closed shapes never turned inside out or flat; a model nothing is taken from given back
//! exactly.

#[path = "../support/mod.rs"]
mod support;

mod cancel;
mod closed_shapes;
mod colour_seams;
mod colours;
mod creases;
mod features;
mod folds;
mod lt_cost;
mod max_error;
mod nonmanifold;
mod null_edges;
mod open_borders;
mod open_scan;
mod positions;
mod progressive;
mod qem;
mod random;
mod report_models;
mod schroeder;
mod seams;
mod stitches;
mod texcoords;
mod tiny;
mod turned_from_input;
mod untouched;

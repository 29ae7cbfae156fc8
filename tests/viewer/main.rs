//! The renderer's pictures on lavapipe, without a window: golden screenshots of each draw
//! mode and of tiled viewports, decimated meshes beside their originals, textures and their
//! filtering, and the `shot` action.

#[path = "../support/mod.rs"]
mod support;

mod anisotropy;
mod decimated;
mod error_map;
mod layout;
mod measure_summary;
mod menu;
mod modes;
mod msaa;
mod shot_command;
mod textures;
mod viewports;

//! Step (3) of start-up, "build the model": make every model of a freshly parsed scene ready
//! for decimation and display — weld duplicated vertices, drop empty models, and name the
//! unnamed ones.

use super::{weld, Scene};

/// Welds (unless `weld` is false), drops models with no triangles and names unnamed models
/// `shape N` after their position in the file.
pub fn build_scene(mut scene: Scene, weld: bool) -> Scene {
    for (i, m) in scene.models.iter_mut().enumerate() {
        if m.name.is_empty() {
            m.name = format!("shape {}", i + 1);
        }
        if weld {
            weld::weld(m, 0.0);
        }
    }
    scene.models.retain(|m| !m.triangles.is_empty());
    scene
}

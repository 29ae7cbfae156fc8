//! Step (3) of start-up, "build the model": make every model of a freshly parsed scene ready
//! for decimation and display — weld duplicated vertices, repair damaged input
//! (`mesh::repair`), drop empty models, and name the unnamed ones.

use super::repair::{self, Repairs, Tolerance};
use super::{weld, Scene};

/// How models are built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BuildOptions {
    /// Merge bit-equal vertices (`--no-weld` turns it off).
    pub weld: bool,
    /// Also merge vertices this close (`--weld-tolerance`); off when `None`.
    pub weld_tolerance: Option<Tolerance>,
}

/// Welds (unless `weld` is false), repairs, drops models with no triangles and names
/// unnamed models `shape N` after their position in the file.
pub fn build_scene(scene: Scene, weld: bool) -> Scene {
    let options = BuildOptions {
        weld,
        weld_tolerance: None,
    };
    build_scene_with(scene, &options).0
}

/// As [`build_scene`], with `options`; also returns what the repair changed, summed over the
/// models.
pub fn build_scene_with(mut scene: Scene, options: &BuildOptions) -> (Scene, Repairs) {
    let mut repairs = Repairs::default();
    for (i, m) in scene.models.iter_mut().enumerate() {
        if m.name.is_empty() {
            m.name = format!("shape {}", i + 1);
        }
        if options.weld {
            weld::weld(m, 0.0);
        }
        let tolerance = options.weld_tolerance.map_or(0.0, |t| t.for_model(m));
        repairs.add(&repair::repair(m, tolerance));
    }
    scene.models.retain(|m| !m.triangles.is_empty());
    (scene, repairs)
}

//! `decimate tile merge`: the decimated tiles appended into one model, welded by exact
//! position (their locked borders are the same bits on both sides), then decimated again
//! as a whole, borders free, to the final target — the seams the tiles had to keep are the
//! densest, cheapest part, so they go first and leave no trace of the tiling.

use std::path::Path;

use super::{Manifest, TileError};
use crate::decimate::{simplify_scene, Algorithm, Params, Report, Target};
use crate::mesh::{weld, Model, Scene};

/// Reads every tile output of `dir` and returns them welded into one model; refuses, naming
/// them, when some tiles have not been run.
pub fn stitch(dir: &Path) -> Result<Scene, TileError> {
    let manifest = Manifest::read(dir)?;
    let missing: Vec<String> = (0..manifest.tiles.len())
        .filter(|&i| !Manifest::tile_output(dir, i).is_file())
        .map(|i| i.to_string())
        .collect();
    if !missing.is_empty() {
        return Err(TileError::Request(format!(
            "{}: tiles not run yet: {} (decimate tile run {} INDEX)",
            dir.display(),
            missing.join(", "),
            dir.display()
        )));
    }
    let mut model = Model {
        name: "merged tiles".into(),
        ..Model::default()
    };
    for i in 0..manifest.tiles.len() {
        let outcome = crate::io::read_scene(&Manifest::tile_output(dir, i))?;
        for m in outcome.scene.models {
            let base = model.positions.len() as u32;
            model.positions.extend(m.positions);
            model
                .triangles
                .extend(m.triangles.iter().map(|t| t.map(|v| v + base)));
        }
    }
    weld::weld(&mut model, 0.0);
    Ok(Scene {
        models: vec![model],
    })
}

/// Stitches the tiles of `dir`, decimates the whole to `target` (the plan's target when
/// `None`) and writes `output` (its extension says the format).
pub fn merge(
    dir: &Path,
    output: &Path,
    target: Option<Target>,
    progress: &mut dyn FnMut(f32),
) -> Result<Report, TileError> {
    let manifest = Manifest::read(dir)?;
    let keep = match target {
        Some(t) => super::cut::target_of(t, manifest.triangles)?,
        None => manifest.target_triangles,
    };
    let mut scene = stitch(dir)?;
    let params = Params {
        target: Target::KeepTriangles(keep),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let report = simplify_scene(&mut scene, &params, progress);
    crate::io::write_scene(&scene, output)?;
    Ok(report)
}

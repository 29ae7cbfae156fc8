//! `decimate tile run` and `decimate tile status`: one tile decimated to its share by
//! quadric edge collapse with every border vertex and its neighbours locked, written
//! through a temporary file and a rename — a job killed half-way leaves no output, and a
//! re-run replaces the old one. Which tile: the argument, else the scheduler's index.

use std::path::Path;

use super::{Manifest, TileError};
use crate::decimate::{qem, Limits};
use crate::mesh::{stitches, Model};

/// Environment variables that carry a job's array index: Slurm job arrays, then Kubernetes
/// Indexed Jobs.
pub const INDEX_VARIABLES: [&str; 2] = ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"];

/// The tile index: `given`, else the first of [`INDEX_VARIABLES`] that is set.
pub fn tile_index(given: Option<usize>) -> Result<usize, TileError> {
    if let Some(i) = given {
        return Ok(i);
    }
    for name in INDEX_VARIABLES {
        if let Ok(v) = std::env::var(name) {
            return v
                .trim()
                .parse()
                .map_err(|_| TileError::Request(format!("{name}='{v}' is not a tile index")));
        }
    }
    Err(TileError::Request(format!(
        "no tile index: give INDEX or set {}",
        INDEX_VARIABLES.join(" or ")
    )))
}

/// Triangles before and after one tile's run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TileRun {
    /// Triangles before.
    pub before: usize,
    /// Triangles after.
    pub after: usize,
}

/// Decimates tile `index` of work folder `dir` and writes its output.
pub fn run_tile(dir: &Path, index: usize) -> Result<TileRun, TileError> {
    let manifest = Manifest::read(dir)?;
    let Some(tile) = manifest.tiles.get(index) else {
        return Err(TileError::Request(format!(
            "{}: tile {index} does not exist (the plan has tiles 0 to {})",
            dir.display(),
            manifest.tiles.len().saturating_sub(1)
        )));
    };
    let input = Manifest::tile_input(dir, index);
    let outcome = crate::io::read_scene(&input)?;
    // Tiles were welded by exact position when planned: nothing left to weld.
    let mut scene = crate::mesh::build::build_scene(outcome.scene, false);
    let before = scene.triangle_count();
    for model in &mut scene.models {
        let pins = border_and_ring(model);
        // The locked band cannot shrink: the interior alone takes the share, or a small
        // tile with a long border would be crushed inside to pay for its band.
        let band = model
            .triangles
            .iter()
            .filter(|t| t.iter().any(|&v| pins[v as usize]))
            .count();
        let limits = Limits {
            remove: usize::MAX,
            seam_copies: 0,
            keep_triangles: tile.target + band,
            max_error: f64::INFINITY,
            feature_angle_deg: crate::decimate::Params::default().feature_angle_deg,
            relax_features: true,
            keep_features: false,
            // A tile is a piece of the input: its own folds are not the input's.
            scale_folds: false,
            cost: Default::default(),
            cancel: Default::default(),
        };
        // No texture seams in a tile (positions only): no twins.
        qem::decimate_model(model, &limits, &pins, &[], &mut |_| {});
    }
    crate::io::write_ply(&scene, &Manifest::tile_output(dir, index))?;
    Ok(TileRun {
        before,
        after: scene.triangle_count(),
    })
}

/// The open border's vertices and their neighbours. Locking the border alone is not enough:
/// two tiles could each join the same two border vertices by a new chord through their
/// interior, an edge of four triangles once welded. With the neighbours locked too, no
/// collapse can join two border vertices, so the welded tiles stay manifold.
fn border_and_ring(model: &Model) -> Vec<bool> {
    let border = stitches::open_border_vertices(model);
    let mut pins = border.clone();
    for t in &model.triangles {
        if t.iter().any(|&v| border[v as usize]) {
            for &v in t {
                pins[v as usize] = true;
            }
        }
    }
    pins
}

/// Per tile of work folder `dir`: whether its output exists.
pub fn status(dir: &Path) -> Result<Vec<bool>, TileError> {
    let manifest = Manifest::read(dir)?;
    Ok((0..manifest.tiles.len())
        .map(|i| Manifest::tile_output(dir, i).is_file())
        .collect())
}

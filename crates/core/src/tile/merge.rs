//! `decimate tile merge`: the decimated tiles appended into one model, welded by exact
//! position (their locked borders are the same bits on both sides), then decimated again
//! as a whole, borders free, to the final target — the seams the tiles had to keep are the
//! densest, cheapest part, so they go first and leave no trace of the tiling.
//!
//! When the welded tiles would not fit the memory budget in one piece, they are first cut
//! again on a grid shifted by half a cell (`cut::retile`, in `DIR/merge/`) and each new
//! tile decimated to its exact share, the old seams now free inside it; the last pass over
//! the whole then only has the new, thin seams to free.

use std::io::BufRead;
use std::path::{Path, PathBuf};

use glam::DVec3;

use super::schedule::{auto_tile_triangles, fits, run_all, BYTES_PER_TRIANGLE};
use super::{cut, Manifest, TileError};
use crate::decimate::{simplify_scene, Algorithm, Params, Report, Target};
use crate::mesh::{weld, Model, Scene};
use crate::progress_bar::Progress;

/// The work folder a re-tiling merge cuts into, inside the first plan's.
pub const RETILE_DIR: &str = "merge";

/// Refuses, naming them, when some tiles of `dir` have not been run.
fn all_run(dir: &Path, manifest: &Manifest) -> Result<(), TileError> {
    let missing: Vec<String> = (0..manifest.tiles.len())
        .filter(|&i| !Manifest::tile_output(dir, i).is_file())
        .map(|i| i.to_string())
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    Err(TileError::Request(format!(
        "{}: tiles not run yet: {} (decimate tile run {} INDEX)",
        dir.display(),
        missing.join(", "),
        dir.display()
    )))
}

/// Reads every tile output of `dir` and returns them welded into one model; refuses, naming
/// them, when some tiles have not been run.
pub fn stitch(dir: &Path) -> Result<Scene, TileError> {
    let manifest = Manifest::read(dir)?;
    all_run(dir, &manifest)?;
    let mut model = Model {
        name: "merged tiles".into(),
        ..Model::default()
    };
    for i in 0..manifest.tiles.len() {
        let outcome = crate::io::read_scene(&Manifest::tile_output(dir, i))?;
        for m in outcome.scene.models {
            let base = model.positions.len() as u32;
            // A tile output far from the tiles' frame was read relative to an origin of
            // its own: put back in the frame, where the same vertex has the same bits.
            let shift = m.origin;
            model
                .positions
                .extend(m.positions.iter().map(|&p| match shift {
                    DVec3::ZERO => p,
                    o => (o + p.as_dvec3()).as_vec3(),
                }));
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
/// `None`) and writes `output` (its extension says the format). Welded tiles that would
/// not fit `memory` bytes are re-tiled first (see the file's doc). `progress` hears the
/// steps, and the fraction done mapped into `span` of the whole run.
pub fn merge(
    dir: &Path,
    output: &Path,
    target: Option<Target>,
    memory: u64,
    progress: &Progress,
    span: (f32, f32),
) -> Result<Report, TileError> {
    let manifest = Manifest::read(dir)?;
    let keep = match target {
        Some(t) => cut::target_of(t, manifest.triangles)?,
        None => manifest.target_triangles,
    };
    refuse_unless_fits(keep, memory)?;
    all_run(dir, &manifest)?;
    let outputs: Vec<PathBuf> = (0..manifest.tiles.len())
        .map(|i| Manifest::tile_output(dir, i))
        .collect();
    let mut welded = 0;
    for path in &outputs {
        welded += face_count(path)?;
    }
    let at = |f: f32| span.0 + (span.1 - span.0) * f;
    let last = if fits(welded, memory) {
        dir.to_path_buf()
    } else {
        progress.say(&format!(
            "merge: {welded} triangles do not fit the memory budget in one piece: cutting \
             them again on a shifted grid"
        ));
        let sub = dir.join(RETILE_DIR);
        let again = cut::retile(
            &outputs,
            dir,
            &sub,
            super::TileCount::TrianglesEach(auto_tile_triangles(memory)),
            keep,
            (manifest.origin, (manifest.min, manifest.max)),
            &mut |s| progress.say(s),
        )?;
        run_all(&sub, &again, memory, progress, (at(0.0), at(0.5)))?;
        sub
    };
    progress.say("merge: welding the tiles and freeing their seams");
    let mut scene = stitch(&last)?;
    // The tiles are relative to the input's origin: the output goes back to its frame.
    scene.models[0].origin = DVec3::from_array(manifest.origin);
    let params = Params {
        target: Target::KeepTriangles(keep),
        algorithm: Algorithm::Qem,
        // Decimated tiles are coarser than the input: their folds are not its sampling.
        scale_folds: false,
        ..Params::default()
    };
    let from = if last == dir { 0.0 } else { 0.5 };
    let report = simplify_scene(&mut scene, &params, &mut |f| {
        progress.set(at(from + (0.95 - from) * f));
    });
    crate::io::write_scene(&scene, output)?;
    progress.set(span.1);
    Ok(report)
}

/// Refuses a final target that could not be decimated within `memory` at all.
pub fn refuse_unless_fits(keep: usize, memory: u64) -> Result<(), TileError> {
    if fits(keep, memory) {
        return Ok(());
    }
    let mib = |bytes: u64| bytes as f64 / f64::from(1 << 20);
    Err(TileError::Request(format!(
        "keeping {keep} triangles needs about {:.1} MiB for the last pass, more than the \
         memory budget of {:.1} MiB: raise --memory or keep fewer triangles",
        mib(keep as u64 * BYTES_PER_TRIANGLE),
        mib(memory)
    )))
}

/// The face count in the header of a PLY that `tile run` wrote.
fn face_count(path: &Path) -> Result<usize, TileError> {
    let file = std::fs::File::open(path).map_err(|e| TileError::io(path, e))?;
    let mut reader = std::io::BufReader::new(file);
    let mut line = Vec::new();
    loop {
        line.clear();
        let n = reader
            .read_until(b'\n', &mut line)
            .map_err(|e| TileError::io(path, e))?;
        let text = String::from_utf8_lossy(&line);
        if n == 0 || text.trim_end() == "end_header" {
            break;
        }
        if let Some(count) = text.trim_end().strip_prefix("element face ") {
            if let Ok(count) = count.parse() {
                return Ok(count);
            }
        }
    }
    Err(TileError::Manifest {
        file: path.to_path_buf(),
        message: "not a tile output: no 'element face' in its PLY header".into(),
    })
}

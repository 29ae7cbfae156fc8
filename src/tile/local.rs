//! `decimate IN nogui --tiles auto|N`: plan, every tile, and merge in one process, in a work
//! folder beside the output that is removed afterwards. `auto` sizes tiles so that one tile
//! in memory stays under the `--memory` budget (default: a quarter of the machine's RAM).

use std::path::{Path, PathBuf};

use super::cut::plan;
use super::{merge, run, TileError};
use crate::cli::{TileCount, Tiles};
use crate::decimate::{Report, Target};

/// Bytes one triangle costs while decimated in memory (docs/design.md, "Tiled decimation").
pub const BYTES_PER_TRIANGLE: u64 = 178;

/// A quarter of the machine's RAM (`MemTotal` of /proc/meminfo), or 1 GiB where unknown.
pub fn default_memory() -> u64 {
    let total = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("MemTotal:"))?;
            let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kib * 1024)
        })
        .unwrap_or(4 << 30);
    total / 4
}

/// The tile count to plan with under a `memory` budget in bytes.
pub fn count_for(tiles: Tiles, memory: u64) -> TileCount {
    match tiles {
        Tiles::Count(n) => TileCount::Tiles(n),
        Tiles::Auto => {
            let fits = (memory / BYTES_PER_TRIANGLE).max(1024) as usize;
            TileCount::TrianglesEach(fits.min(crate::cli::DEFAULT_TILE_TRIANGLES))
        }
    }
}

/// The work folder for `output`: beside it, named after it and this process.
pub fn work_dir_for(output: &Path) -> PathBuf {
    let name = output
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    output.with_file_name(format!(".{name}.tiles-{}", std::process::id()))
}

/// Plans `input` into `dir`, runs every tile, merges into `output`; `say` hears each step.
pub fn run_local(
    input: &Path,
    output: &Path,
    dir: &Path,
    count: TileCount,
    target: Target,
    say: &mut dyn FnMut(&str),
) -> Result<Report, TileError> {
    let manifest = plan(input, dir, count, target, say)?;
    let n = manifest.tiles.len();
    for i in 0..n {
        let r = run::run_tile(dir, i)?;
        say(&format!(
            "tile {} of {n}: triangles {} -> {}",
            i + 1,
            r.before,
            r.after
        ));
    }
    say("merge: welding the tiles and freeing their seams");
    merge::merge(dir, output, None, &mut |_| {})
}

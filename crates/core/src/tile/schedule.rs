//! The memory budget of a tiled run on one machine, and every tile of a work folder run on
//! the local cores: as many tiles at once as the budget allows (tiles at once × the largest
//! tile's in-memory peak ≤ budget), at most one per core, the largest first so that the
//! last to finish are small.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use super::{run, Manifest, TileError};
use super::{TileCount, Tiles};
use crate::progress_bar::Progress;

/// Bytes one triangle costs while decimated in memory, rounded up from the largest
/// measured (docs/design.md, "Tiled decimation").
pub const BYTES_PER_TRIANGLE: u64 = 200;

/// Smallest tile `--tiles auto` cuts, however small the budget: below it the locked bands
/// would be most of a tile (docs/design.md, "Tiled decimation").
const MIN_TILE_TRIANGLES: usize = 1024;

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

/// Triangles a mesh of `triangles` can hold and still be decimated in `memory` bytes.
pub fn fits(triangles: usize, memory: u64) -> bool {
    triangles as u64 * BYTES_PER_TRIANGLE <= memory
}

/// The tile count to plan with under a `memory` budget in bytes: `auto` cuts tiles small
/// enough that one per core fits at once (and no larger than the default tile).
pub fn count_for(tiles: Tiles, memory: u64) -> TileCount {
    match tiles {
        Tiles::Count(n) => TileCount::Tiles(n),
        Tiles::Auto => TileCount::TrianglesEach(auto_tile_triangles(memory)),
    }
}

/// The tile size of `--tiles auto` under `memory`.
pub fn auto_tile_triangles(memory: u64) -> usize {
    let cores = rayon::current_num_threads().max(1) as u64;
    let each = (memory / BYTES_PER_TRIANGLE / cores) as usize;
    each.clamp(MIN_TILE_TRIANGLES, super::DEFAULT_TILE_TRIANGLES)
}

/// How many tiles of `manifest` run at once in `memory`: at least one, at most one per core.
pub fn at_once(manifest: &Manifest, memory: u64) -> usize {
    let largest = manifest
        .tiles
        .iter()
        .map(|t| t.triangles)
        .max()
        .unwrap_or(1) as u64;
    let fit = memory / (largest * BYTES_PER_TRIANGLE).max(1);
    (fit as usize).clamp(1, rayon::current_num_threads().max(1))
}

/// Runs every tile of work folder `dir` (planned as `manifest`), [`at_once`] at a time;
/// `progress` hears each tile and the fraction done, mapped into `span` of the whole run.
/// The first failure stops the tiles not yet started and is returned.
pub fn run_all(
    dir: &Path,
    manifest: &Manifest,
    memory: u64,
    progress: &Progress,
    span: (f32, f32),
) -> Result<(), TileError> {
    let n = manifest.tiles.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(manifest.tiles[i].triangles));
    let total: usize = manifest.tiles.iter().map(|t| t.triangles).sum();
    let workers = at_once(manifest, memory);
    progress.say(&format!("running {n} tiles, {workers} at once"));
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let failure: Mutex<Option<TileError>> = Mutex::new(None);
    let failed = || failure.lock().map(|f| f.is_some()).unwrap_or(true);
    // Tasks on rayon's pool, so that the calling thread (a pool worker, `threads`) works
    // too and each tile's own parallel steps share the same cores.
    rayon::scope(|s| {
        for _ in 0..workers {
            s.spawn(|_| {
                while !failed() {
                    let Some(&i) = order.get(next.fetch_add(1, Ordering::Relaxed)) else {
                        break;
                    };
                    match run::run_tile(dir, i) {
                        Ok(r) => {
                            let triangles = manifest.tiles[i].triangles;
                            let sum = done.fetch_add(triangles, Ordering::Relaxed) + triangles;
                            progress.say(&format!(
                                "tile {} of {n}: triangles {} -> {}",
                                i + 1,
                                r.before,
                                r.after
                            ));
                            let f = sum as f32 / total.max(1) as f32;
                            progress.set(span.0 + (span.1 - span.0) * f);
                        }
                        Err(e) => {
                            if let Ok(mut first) = failure.lock() {
                                first.get_or_insert(e);
                            }
                        }
                    }
                }
            });
        }
    });
    match failure.into_inner() {
        Ok(None) => Ok(()),
        Ok(Some(e)) => Err(e),
        Err(poisoned) => poisoned.into_inner().map_or(Ok(()), Err),
    }
}

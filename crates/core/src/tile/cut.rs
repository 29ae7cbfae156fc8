//! `decimate tile plan`: three streaming passes over the input (`io::stream`), never the
//! whole mesh in memory — (1) bounds and count, (2) a histogram of triangle centroids on a
//! fixed grid, split k-d style into boxes of nearly equal counts, (3) each triangle appended
//! to the raw file of the box its centroid falls in. Each raw file is then welded by exact
//! position into a binary PLY. Positions are copied bit for bit, so a vertex on a tile's
//! border is the same number in every tile that has it. A far input (see `io::origin`) is
//! read relative to the origin its first vertex gives, which the manifest keeps: the tiles
//! hold small f32 positions, and `merge` writes the output back in the input's frame.

use std::collections::HashMap;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};

use super::manifest::{Manifest, Tile};
use super::TileCount;
use super::TileError;
use crate::decimate::Target;
use crate::io::origin::Recentre;
use crate::io::stream::{for_each_triangle, Corners};
use crate::mesh::{Model, Scene};

/// Histogram cells per axis: fine enough to balance a few thousand tiles, small enough
/// (4 bytes a cell, twice) to cost nothing beside the input.
const GRID: usize = 64;

/// Extra triangles a tile keeps beyond its share of the target, so that `merge` has room to
/// free the locked seams (docs/design.md, "Tiled decimation").
pub const SEAM_SLACK: f64 = 2.0;

/// Bytes a raw triangle takes in a bucket file: three positions of three `f32`.
const RAW: usize = 36;

/// Cuts `input` into tiles in work folder `dir` (created if missing; a previous plan's
/// tiles in it are removed) and writes the manifest. `progress` hears each step.
pub fn plan(
    input: &Path,
    dir: &Path,
    count: TileCount,
    target: Target,
    progress: &mut dyn FnMut(&str),
) -> Result<Manifest, TileError> {
    let cutting = Cutting {
        count,
        target,
        slack: SEAM_SLACK,
        shifted_from: None,
        origin: None,
    };
    plan_files(&[input.to_path_buf()], input, dir, &cutting, progress)
}

/// Cuts the decimated tiles of a first plan (`inputs`, bounds `min`..`max`, positions
/// relative to `origin`) again, on the
/// first plan's grid shifted by half a cell: every new cut lies half a cell from every old
/// one, so the old locked seams fall inside the new tiles and are decimated. Each new tile
/// keeps its exact share of `keep` (no slack: this pass makes the final count).
pub fn retile(
    inputs: &[PathBuf],
    first: &Path,
    dir: &Path,
    count: TileCount,
    keep: usize,
    (origin, bounds): ([f64; 3], ([f32; 3], [f32; 3])),
    progress: &mut dyn FnMut(&str),
) -> Result<Manifest, TileError> {
    let cutting = Cutting {
        count,
        target: Target::KeepTriangles(keep),
        slack: 1.0,
        shifted_from: Some(bounds),
        origin: Some(origin),
    };
    plan_files(inputs, first, dir, &cutting, progress)
}

/// How a plan cuts: into how many tiles, to which final target, how much more than its
/// share each tile keeps, and (for a re-tiling) the bounds whose grid is shifted and the
/// origin the inputs are already relative to (else the inputs' own is picked).
struct Cutting {
    count: TileCount,
    target: Target,
    slack: f64,
    shifted_from: Option<([f32; 3], [f32; 3])>,
    origin: Option<[f64; 3]>,
}

/// Every triangle of the inputs, in file order, handed to a callback.
type EachTriangle<'a> = dyn Fn(&mut dyn FnMut(Corners)) -> Result<(), TileError> + 'a;

/// Streams every triangle of `inputs` into tiles in `dir`; `source` is what the manifest
/// names as its input. Three passes over the input: bounds and count, a histogram of the
/// centroids split into boxes, the triangles bucketed into one raw file a box; then each
/// bucket is welded into its tile.
fn plan_files(
    inputs: &[PathBuf],
    source: &Path,
    dir: &Path,
    cutting: &Cutting,
    progress: &mut dyn FnMut(&str),
) -> Result<Manifest, TileError> {
    std::fs::create_dir_all(dir).map_err(|e| TileError::io(dir, e))?;
    remove_old_tiles(dir)?;
    // Every pass reads the same first vertex, so picks the same origin.
    let start = match cutting.origin {
        Some(_) => Recentre::at_zero(),
        None => Recentre::default(),
    };
    let origin = std::cell::Cell::new(DVec3::ZERO);
    let each = |f: &mut dyn FnMut(Corners)| -> Result<(), TileError> {
        let mut recentre = start;
        for input in inputs {
            for_each_triangle(input, &mut recentre, f)?;
        }
        origin.set(recentre.origin());
        Ok(())
    };
    let (lo, hi, triangles) = bounds(&each, source)?;
    let target_triangles = target_of(cutting.target, triangles)?;
    let wanted = match cutting.count {
        TileCount::Tiles(n) => n.max(1),
        TileCount::TrianglesEach(m) => triangles.div_ceil(m.max(1)),
    };
    progress(&format!(
        "plan: {triangles} triangles, cutting {wanted} tiles"
    ));
    let grid = match cutting.shifted_from {
        Some((min, max)) => Grid::new(Vec3::from(min), Vec3::from(max)).shifted_half_a_cell(),
        None => Grid::new(lo, hi),
    };
    let (boxes, cell_tile) = cut_boxes(&each, &grid, wanted)?;
    let counts = bucket(&each, dir, &grid, &cell_tile, boxes.len())?;
    let ratio = target_triangles as f64 / triangles as f64;
    let tiles = weld_buckets(
        dir,
        &grid,
        &boxes,
        &counts,
        (ratio, cutting.slack),
        progress,
    )?;
    let manifest = Manifest {
        input: source.to_path_buf(),
        triangles,
        target_triangles,
        origin: cutting.origin.unwrap_or(origin.get().to_array()),
        min: lo.to_array(),
        max: hi.to_array(),
        tiles,
    };
    let path = dir.join(super::manifest::FILE);
    crate::io::replace::replace_file(&path, |w| w.write_all(manifest.to_json().as_bytes()))
        .map_err(|e| TileError::io(&path, e))?;
    Ok(manifest)
}

/// Pass 1: the bounds of the finite corners and the triangle count.
fn bounds(each: &EachTriangle<'_>, source: &Path) -> Result<(Vec3, Vec3, usize), TileError> {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let mut triangles = 0usize;
    each(&mut |t| {
        for p in t {
            let p = Vec3::from(p);
            if p.is_finite() {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        triangles += 1;
    })?;
    if triangles == 0 || !lo.is_finite() {
        return Err(TileError::Request(format!(
            "{}: the file has no triangles to tile",
            source.display()
        )));
    }
    Ok((lo, hi, triangles))
}

/// Pass 2: the centroids' histogram split into `wanted` boxes, and each cell's box.
fn cut_boxes(
    each: &EachTriangle<'_>,
    grid: &Grid,
    wanted: usize,
) -> Result<(Vec<CellBox>, Vec<u32>), TileError> {
    let mut histogram = vec![0u32; GRID * GRID * GRID];
    each(&mut |t| {
        let c = grid.cell(&t);
        histogram[c] = histogram[c].saturating_add(1);
    })?;
    let mut boxes = Vec::new();
    split(&histogram, [[0, GRID]; 3], wanted, &mut boxes);
    let mut cell_tile = vec![0u32; GRID * GRID * GRID];
    for (i, b) in boxes.iter().enumerate() {
        for_cells(*b, |c| cell_tile[c] = i as u32);
    }
    Ok((boxes, cell_tile))
}

/// The raw file box `i`'s triangles are bucketed into.
fn raw_path(dir: &Path, i: usize) -> PathBuf {
    dir.join(format!("tile-{i:05}.raw"))
}

/// Pass 3: every triangle appended to its box's raw file; the count of each box.
fn bucket(
    each: &EachTriangle<'_>,
    dir: &Path,
    grid: &Grid,
    cell_tile: &[u32],
    boxes: usize,
) -> Result<Vec<usize>, TileError> {
    let mut writers = Vec::with_capacity(boxes);
    for i in 0..boxes {
        let path = raw_path(dir, i);
        let f = File::create(&path).map_err(|e| TileError::io(&path, e))?;
        writers.push(BufWriter::with_capacity(1 << 15, f));
    }
    let mut counts = vec![0usize; boxes];
    let mut failed: Option<(usize, std::io::Error)> = None;
    each(&mut |t| {
        let i = cell_tile[grid.cell(&t)] as usize;
        counts[i] += 1;
        if failed.is_none() {
            let mut bytes = [0u8; RAW];
            for (chunk, x) in bytes.chunks_exact_mut(4).zip(t.iter().flatten()) {
                chunk.copy_from_slice(&x.to_le_bytes());
            }
            if let Err(e) = writers[i].write_all(&bytes) {
                failed = Some((i, e));
            }
        }
    })?;
    if let Some((i, e)) = failed {
        return Err(TileError::io(&raw_path(dir, i), e));
    }
    for (i, w) in writers.into_iter().enumerate() {
        w.into_inner()
            .map_err(|e| TileError::io(&raw_path(dir, i), e.into_error()))?;
    }
    Ok(counts)
}

/// Each non-empty bucket welded into its tile PLY, with its share of the target (its
/// triangles times the target's ratio, times the seam slack); the raw files are removed,
/// empty boxes dropped.
fn weld_buckets(
    dir: &Path,
    grid: &Grid,
    boxes: &[CellBox],
    counts: &[usize],
    (ratio, slack): (f64, f64),
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<Tile>, TileError> {
    let mut tiles = Vec::new();
    for (i, b) in boxes.iter().enumerate() {
        let raw = raw_path(dir, i);
        if counts[i] > 0 {
            let index = tiles.len();
            progress(&format!("plan: tile {index}: {} triangles", counts[i]));
            let scene = Scene {
                models: vec![weld_raw(&raw)?],
            };
            crate::io::write_ply(&scene, &Manifest::tile_input(dir, index))?;
            let (min, max) = grid.world_box(*b);
            tiles.push(Tile {
                min,
                max,
                triangles: counts[i],
                target: ((counts[i] as f64 * ratio * slack).ceil() as usize).clamp(1, counts[i]),
            });
        }
        std::fs::remove_file(&raw).map_err(|e| TileError::io(&raw, e))?;
    }
    Ok(tiles)
}

/// The final triangle count `target` asks of a mesh of `triangles`: tiling knows triangles,
/// so `-p P` keeps `100 - P` percent of them.
pub fn target_of(target: Target, triangles: usize) -> Result<usize, TileError> {
    match target {
        Target::KeepTriangles(t) => Ok(t.min(triangles)),
        Target::RemovePercent(p) => Ok((triangles as f64 * (1.0 - p / 100.0)).round() as usize),
        _ => Err(TileError::Request(
            "tiled decimation takes -p or --keep-triangles as its target".into(),
        )),
    }
}

/// Removes the tile files (`tile-NNNNN.*`) and manifest a previous plan left in `dir`.
fn remove_old_tiles(dir: &Path) -> Result<(), TileError> {
    let entries = std::fs::read_dir(dir).map_err(|e| TileError::io(dir, e))?;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let ours = name.starts_with("tile-") && (name.ends_with(".ply") || name.ends_with(".raw"))
            || name == super::manifest::FILE;
        if ours {
            let p = entry.path();
            std::fs::remove_file(&p).map_err(|e| TileError::io(&p, e))?;
        }
    }
    Ok(())
}

/// Reads a raw bucket and merges its corners by exact position into one model.
fn weld_raw(raw: &Path) -> Result<Model, TileError> {
    let f = File::open(raw).map_err(|e| TileError::io(raw, e))?;
    let mut r = BufReader::with_capacity(1 << 20, f);
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut model = Model::default();
    let mut rec = [0u8; RAW];
    loop {
        match r.read_exact(&mut rec) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => break,
            Err(e) => return Err(TileError::io(raw, e)),
        }
        let mut tri = [0u32; 3];
        for (k, v) in tri.iter_mut().enumerate() {
            let bits: [u32; 3] = std::array::from_fn(|a| {
                let o = 12 * k + 4 * a;
                u32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]])
            });
            let next = model.positions.len() as u32;
            *v = *index.entry(bits).or_insert_with(|| {
                model.positions.push(Vec3::from(bits.map(f32::from_bits)));
                next
            });
        }
        model.triangles.push(tri);
    }
    Ok(model)
}

/// Maps positions to histogram cells over the input's bounds.
struct Grid {
    lo: [f64; 3],
    size: [f64; 3],
}

impl Grid {
    fn new(lo: Vec3, hi: Vec3) -> Self {
        let lo = lo.as_dvec3().to_array();
        let hi = hi.as_dvec3().to_array();
        Self {
            lo,
            size: std::array::from_fn(|a| (hi[a] - lo[a]).max(f64::MIN_POSITIVE)),
        }
    }

    /// The cell of a triangle's centroid (clamped: a non-finite corner lands in cell 0).
    fn cell(&self, t: &Corners) -> usize {
        let mut c = 0;
        for (a, (lo, size)) in self.lo.iter().zip(&self.size).enumerate() {
            let mid = (f64::from(t[0][a]) + f64::from(t[1][a]) + f64::from(t[2][a])) / 3.0;
            let f = ((mid - lo) / size * GRID as f64).floor();
            let i = if f.is_finite() {
                f.clamp(0.0, (GRID - 1) as f64) as usize
            } else {
                0
            };
            c = c * GRID + i;
        }
        c
    }

    /// The same cells moved down by half a cell on every axis: no cell boundary of the
    /// result is one of this grid's (the top half cell is clamped into the last cell).
    fn shifted_half_a_cell(mut self) -> Self {
        for (lo, size) in self.lo.iter_mut().zip(&self.size) {
            *lo -= size / GRID as f64 / 2.0;
        }
        self
    }

    fn world_box(&self, b: CellBox) -> ([f64; 3], [f64; 3]) {
        let at = |a: usize, i: usize| self.lo[a] + self.size[a] * i as f64 / GRID as f64;
        (
            std::array::from_fn(|a| at(a, b[a][0])),
            std::array::from_fn(|a| at(a, b[a][1])),
        )
    }
}

/// A box of histogram cells: per axis the half-open range `[from, to)`.
type CellBox = [[usize; 2]; 3];

fn for_cells(b: CellBox, mut f: impl FnMut(usize)) {
    for x in b[0][0]..b[0][1] {
        for y in b[1][0]..b[1][1] {
            for z in b[2][0]..b[2][1] {
                f((x * GRID + y) * GRID + z);
            }
        }
    }
}

/// Splits box `b` into `leaves` boxes of nearly equal histogram counts: across the axis
/// where the box's content spans most cells, at the plane that gives each side its share.
fn split(histogram: &[u32], b: CellBox, leaves: usize, out: &mut Vec<CellBox>) {
    // Per-axis profile of the box's counts.
    let mut profile: [Vec<u64>; 3] = std::array::from_fn(|a| vec![0u64; b[a][1] - b[a][0]]);
    for x in b[0][0]..b[0][1] {
        for y in b[1][0]..b[1][1] {
            for z in b[2][0]..b[2][1] {
                let n = u64::from(histogram[(x * GRID + y) * GRID + z]);
                profile[0][x - b[0][0]] += n;
                profile[1][y - b[1][0]] += n;
                profile[2][z - b[2][0]] += n;
            }
        }
    }
    let span = |p: &Vec<u64>| {
        let first = p.iter().position(|&n| n > 0);
        let last = p.iter().rposition(|&n| n > 0);
        match (first, last) {
            (Some(f), Some(l)) => l - f + 1,
            _ => 0,
        }
    };
    let axis = (0..3).max_by_key(|&a| span(&profile[a])).unwrap_or(0);
    if leaves <= 1 || span(&profile[axis]) < 2 {
        out.push(b);
        return;
    }
    let left_leaves = leaves / 2;
    let total: u64 = profile[axis].iter().sum();
    let want = total as f64 * left_leaves as f64 / leaves as f64;
    let p = &profile[axis];
    let first = p.iter().position(|&n| n > 0).unwrap_or(0);
    let last = p.iter().rposition(|&n| n > 0).unwrap_or(0);
    // The cut after cell `k` (relative), kept so that both sides hold content.
    let mut acc = 0u64;
    let mut cut = first + 1;
    for (k, &n) in p.iter().enumerate().take(last).skip(first) {
        acc += n;
        cut = k + 1;
        if acc as f64 >= want {
            break;
        }
    }
    let at = b[axis][0] + cut;
    let (mut left, mut right) = (b, b);
    left[axis][1] = at;
    right[axis][0] = at;
    split(histogram, left, left_leaves, out);
    split(histogram, right, leaves - left_leaves, out);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_balances_a_skewed_histogram() {
        let mut h = vec![0u32; GRID * GRID * GRID];
        for x in 0..GRID {
            // Counts grow along x: equal widths would be far from equal counts.
            h[(x * GRID + 3) * GRID + 5] = (x as u32 + 1) * 10;
        }
        let mut boxes = Vec::new();
        split(&h, [[0, GRID]; 3], 4, &mut boxes);
        assert_eq!(boxes.len(), 4);
        let total: u64 = h.iter().map(|&n| u64::from(n)).sum();
        for b in &boxes {
            let mut n = 0u64;
            for_cells(*b, |c| n += u64::from(h[c]));
            assert!(
                n * 4 > total * 3 / 4 && n * 4 < total * 5 / 4,
                "{n} of {total}"
            );
        }
    }
}

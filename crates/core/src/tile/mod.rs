//! Tiled decimation for meshes bigger than memory, as independent jobs: `plan` streams the
//! input into spatial tiles on disk (binary PLY each, plus `manifest.json`), `run` decimates
//! one tile with its border locked (any order, any machine, again when pre-empted), `merge`
//! welds the tiles and decimates the whole again so that the locked seams are freed.
//! `local` does all three in one process (`decimate IN nogui --tiles auto`), the tiles in
//! parallel within a memory budget (`schedule`), reporting through `bar`.
//! docs/cluster.md shows the jobs under Slurm, Kubernetes and GNU parallel.

pub mod cut;
pub mod local;
pub(crate) mod manifest;
pub mod merge;
pub mod run;
pub mod schedule;

use std::path::PathBuf;

pub use manifest::Manifest;

/// `--tiles` of nogui: how many tiles were asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tiles {
    /// Sized from the memory budget (`schedule::count_for`).
    Auto,
    /// This many tiles.
    Count(usize),
}

/// How many tiles `tile plan` cuts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TileCount {
    /// This many (fewer when the mesh has fewer cells).
    Tiles(usize),
    /// As many as needed for about this many triangles each.
    TrianglesEach(usize),
}

/// Largest tile `tile plan` and `--tiles auto` cut unless told otherwise: small tiles bound
/// the peak at little cost, since the seams are decimated again at merge (docs/design.md,
/// "Tiled decimation").
pub const DEFAULT_TILE_TRIANGLES: usize = 1 << 20;

/// What went wrong in a tiling step; every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum TileError {
    /// An input could not be read.
    #[error("{0}")]
    Read(#[from] crate::io::ReadError),
    /// An output could not be written.
    #[error("cannot write {0}")]
    Write(#[from] crate::io::WriteError),
    /// A file operation failed.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The manifest is missing, unreadable or not one of ours.
    #[error("{file}: {message}")]
    Manifest {
        /// The manifest file.
        file: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The request does not fit the work folder (a tile index out of range, tiles not run).
    #[error("{0}")]
    Request(String),
}

impl TileError {
    pub(crate) fn io(file: &std::path::Path, source: std::io::Error) -> Self {
        Self::Io {
            file: file.to_path_buf(),
            source,
        }
    }
}

//! Reading and writing scenes. One module per format; all readers produce the same `Scene`.
//!
//! Entry points: [`read_scene`] (format sniffed from the header, gzip handled) and
//! [`write_vrml2`] (temporary file, then rename).

use std::path::{Path, PathBuf};

use crate::mesh::Scene;

/// What went wrong reading a scene: always names the file, and the line where there is one.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    #[error("{file}: {source}")]
    Io {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{file}:{line}: {message}")]
    Syntax {
        file: PathBuf,
        line: usize,
        message: String,
    },
    #[error("{file}: {message}")]
    Unsupported { file: PathBuf, message: String },
}

/// What went wrong writing a scene.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {source}")]
pub struct WriteError {
    pub file: PathBuf,
    #[source]
    pub source: std::io::Error,
}

/// A parsed scene and the warnings met on the way (one per kind of skipped node, etc.).
#[derive(Debug, Clone, Default)]
pub struct ReadOutcome {
    pub scene: Scene,
    pub warnings: Vec<String>,
}

/// Reads a VRML 1.0, VRML 2.0 or Open Inventor ASCII file (optionally gzipped).
pub fn read_scene(path: &Path) -> Result<ReadOutcome, ReadError> {
    Err(ReadError::Unsupported {
        file: path.to_path_buf(),
        message: "readers are not built yet".into(),
    })
}

/// Writes `scene` as VRML 2.0 to `path` via a temporary file in the same folder and a rename.
pub fn write_vrml2(_scene: &Scene, path: &Path) -> Result<(), WriteError> {
    Err(WriteError {
        file: path.to_path_buf(),
        source: std::io::Error::other("writer is not built yet"),
    })
}

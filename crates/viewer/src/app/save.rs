//! Where the viewer saves: the path asked for (`out.wrl`), unless a file is there already (an
//! earlier save, or one of the files the scene was read from) — then the first free
//! `out-1.wrl`, `out-2.wrl`… beside it. The viewer never writes over a file; it has no
//! `--overwrite`.

use std::path::{Path, PathBuf};

/// How many numbered alternatives are tried before giving up (a folder holding this many
/// saves already is the user's to tidy).
const MAX_ALTERNATIVES: u32 = 10_000;

/// Where a save asked to go to `wanted` will go.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SavePath {
    /// `wanted` is no input: write there.
    AsAsked(PathBuf),
    /// `wanted` is an input file: write to this numbered sibling instead.
    Instead(PathBuf),
    /// `wanted` exists (an earlier save): write to this numbered sibling, the first free one.
    Numbered(PathBuf),
}

impl SavePath {
    pub fn path(&self) -> &Path {
        match self {
            Self::AsAsked(p) | Self::Instead(p) | Self::Numbered(p) => p,
        }
    }
}

/// The path a save to `wanted` uses: no existing file, and never one of `inputs`; `None`
/// when every alternative is taken.
pub fn save_path(wanted: &Path, inputs: &[PathBuf]) -> Option<SavePath> {
    let is_input = |p: &Path| inputs.iter().any(|i| same_file(i, p));
    let taken = |p: &Path| is_input(p) || p.exists();
    if !taken(wanted) {
        return Some(SavePath::AsAsked(wanted.to_path_buf()));
    }
    let stem = wanted
        .file_stem()
        .map_or_else(|| "out".to_string(), |s| s.to_string_lossy().into_owned());
    let extension = wanted
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    (1..=MAX_ALTERNATIVES)
        .map(|k| wanted.with_file_name(format!("{stem}-{k}{extension}")))
        .find(|p| !taken(p))
        .map(|p| match is_input(wanted) {
            true => SavePath::Instead(p),
            false => SavePath::Numbered(p),
        })
}

/// True when both paths name the same existing file (a path that does not exist yet can be
/// no input).
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("decimate-save-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        dir
    }

    #[test]
    fn a_path_that_is_no_input_is_used_as_asked() {
        let dir = scratch("free");
        let input = dir.join("model.wrl");
        std::fs::write(&input, "#VRML V2.0 utf8\n").unwrap_or_else(|e| panic!("{e}"));
        let wanted = dir.join("out.wrl");
        assert_eq!(
            save_path(&wanted, std::slice::from_ref(&input)),
            Some(SavePath::AsAsked(wanted.clone()))
        );
        // An earlier save stays: the next one is numbered, then the next free number.
        std::fs::write(&wanted, "old").unwrap_or_else(|e| panic!("{e}"));
        let first = dir.join("out-1.wrl");
        assert_eq!(
            save_path(&wanted, std::slice::from_ref(&input)),
            Some(SavePath::Numbered(first.clone()))
        );
        std::fs::write(&first, "old").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            save_path(&wanted, &[input]),
            Some(SavePath::Numbered(dir.join("out-2.wrl")))
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_input_named_like_the_output_gets_the_first_free_number() {
        let dir = scratch("taken");
        let input = dir.join("out.wrl");
        let second = dir.join("out-1.wrl");
        std::fs::write(&input, "#VRML V2.0 utf8\n").unwrap_or_else(|e| panic!("{e}"));
        // Reached by another spelling of the same file.
        let wanted = dir.join(".").join("out.wrl");
        assert_eq!(
            save_path(&wanted, std::slice::from_ref(&input)),
            Some(SavePath::Instead(dir.join(".").join("out-1.wrl")))
        );
        std::fs::write(&second, "#VRML V2.0 utf8\n").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            save_path(&wanted, &[input, second]),
            Some(SavePath::Instead(dir.join(".").join("out-2.wrl")))
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}

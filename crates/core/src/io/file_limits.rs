//! What a reader may open and how much it may read: only regular files (a FIFO, a device or
//! a folder is refused before it is opened, so a FIFO cannot block and `/dev/zero` cannot
//! fill memory), at most [`max_file_bytes`] bytes from any one file and from a gzip stream's
//! decompression, and files a model names (glTF buffers and images, OBJ `mtllib`, VRML
//! `Inline`/`File`, textures) only inside the model's folder.
//!
//! Defaults and overrides (this list is their documentation):
//! - `DECIMATE_MAX_FILE_BYTES` (bytes, or with a `K`, `M` or `G` suffix): the byte limit,
//!   [`DEFAULT_MAX_FILE_BYTES`] (1 GiB) when unset. Larger meshes are tiled (`--tiles`), which
//!   streams them instead.
//! - `DECIMATE_ALLOW_OUTSIDE=1`: references may leave the model's folder (absolute paths and
//!   `..`); `file://` URIs stay refused.
//! - `DECIMATE_MAX_TRIANGLES`: the most triangles a glTF scene may expand to by placing
//!   meshes with many nodes, 16 per byte of its files (at least 4 million) when unset.

use std::fs::File;
use std::io::{self, Read};
use std::path::{Component, Path, PathBuf};

/// The byte limit when `DECIMATE_MAX_FILE_BYTES` is unset.
pub const DEFAULT_MAX_FILE_BYTES: u64 = 1 << 30;
/// The environment variable that sets the byte limit.
pub const MAX_FILE_BYTES_VAR: &str = "DECIMATE_MAX_FILE_BYTES";
/// The environment variable that lets references leave the model's folder.
pub const ALLOW_OUTSIDE_VAR: &str = "DECIMATE_ALLOW_OUTSIDE";

/// The environment variable that sets the most triangles a scene may expand to.
pub const MAX_TRIANGLES_VAR: &str = "DECIMATE_MAX_TRIANGLES";
/// Triangles a scene may expand to per byte of its files, and at least.
const TRIANGLES_PER_BYTE: usize = 16;
const MIN_EXPANSION: usize = 4_000_000;
/// What an expansion error says to do.
pub const EXPANSION_HINT: &str =
    "set DECIMATE_MAX_TRIANGLES to allow more than 16 triangles per byte of the file";

/// The most triangles a scene read from `file_bytes` bytes (its file and the files it loads)
/// may expand to by instancing: 16 per byte, at least 4 million, at most
/// [`super::MAX_TRIANGLES`]; `DECIMATE_MAX_TRIANGLES` overrides it.
pub fn max_instanced_triangles(file_bytes: usize) -> usize {
    if let Some(n) = std::env::var(MAX_TRIANGLES_VAR)
        .ok()
        .and_then(|v| v.trim().parse().ok())
    {
        return n;
    }
    file_bytes
        .saturating_mul(TRIANGLES_PER_BYTE)
        .clamp(MIN_EXPANSION, super::MAX_TRIANGLES)
}

/// The most bytes read from one file or inflated from one gzip stream.
pub fn max_file_bytes() -> u64 {
    std::env::var(MAX_FILE_BYTES_VAR)
        .ok()
        .and_then(|v| parse_size(&v))
        .unwrap_or(DEFAULT_MAX_FILE_BYTES)
}

/// A size such as `123`, `64K`, `1.5M`, `2G` or `1T` (powers of 1024) in bytes; `None`
/// unless it is a positive, finite number with one of those suffixes or none. The
/// command line's `--memory` reads sizes the same way.
pub fn parse_size(text: &str) -> Option<u64> {
    let t = text.trim();
    let (digits, unit) = match t.char_indices().last()? {
        (i, c) if c.is_ascii_alphabetic() => (&t[..i], c.to_ascii_uppercase()),
        _ => (t, 'B'),
    };
    let shift = match unit {
        'B' => 0,
        'K' => 10,
        'M' => 20,
        'G' => 30,
        'T' => 40,
        _ => return None,
    };
    let v: f64 = digits.trim().parse().ok()?;
    (v.is_finite() && v > 0.0).then(|| (v * f64::from(1u32 << 10).powi(shift / 10)) as u64)
}

/// True when references may leave the model's folder.
pub fn outside_allowed() -> bool {
    std::env::var(ALLOW_OUTSIDE_VAR).is_ok_and(|v| !v.is_empty() && v != "0")
}

/// An error that says what the limit is and how to raise it.
fn refused(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// Fails unless `path` (links followed) is a regular file: a FIFO, a device, a socket or a
/// folder is refused before anything opens it.
pub fn check_regular(path: &Path) -> io::Result<u64> {
    let meta = std::fs::metadata(path)?;
    if meta.is_file() {
        return Ok(meta.len());
    }
    let what = kind_of(&meta);
    Err(refused(format!(
        "not a regular file ({what}): only regular files are read"
    )))
}

#[cfg(unix)]
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = meta.file_type();
    if t.is_dir() {
        "a folder"
    } else if t.is_fifo() {
        "a FIFO"
    } else if t.is_char_device() || t.is_block_device() {
        "a device"
    } else if t.is_socket() {
        "a socket"
    } else {
        "not a file"
    }
}

#[cfg(not(unix))]
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    if meta.is_dir() {
        "a folder"
    } else {
        "not a file"
    }
}

/// Opens a regular file for reading (see [`check_regular`]), with its length.
pub fn open_regular(path: &Path) -> io::Result<(File, u64)> {
    let len = check_regular(path)?;
    Ok((File::open(path)?, len))
}

/// Reads a whole regular file of at most [`max_file_bytes`] bytes.
pub fn read_regular(path: &Path) -> io::Result<Vec<u8>> {
    let limit = max_file_bytes();
    let (file, len) = open_regular(path)?;
    if len > limit {
        return Err(over_limit(len, limit));
    }
    let mut out = Vec::with_capacity(len as usize);
    // The file may grow while it is read: never more than the limit.
    file.take(limit + 1).read_to_end(&mut out)?;
    if out.len() as u64 > limit {
        return Err(over_limit(out.len() as u64, limit));
    }
    Ok(out)
}

fn over_limit(len: u64, limit: u64) -> io::Error {
    refused(format!(
        "{len} bytes is over the limit of {limit} bytes a file may have \
         (set {MAX_FILE_BYTES_VAR} to raise it, or tile the mesh with --tiles)"
    ))
}

/// Inflates a gzip stream (several members allowed) to at most [`max_file_bytes`] bytes.
pub fn gunzip_limited(bytes: &[u8]) -> Result<Vec<u8>, String> {
    let limit = max_file_bytes();
    let mut out = Vec::with_capacity(bytes.len().saturating_mul(4).min(limit as usize));
    flate2::read::MultiGzDecoder::new(bytes)
        .take(limit + 1)
        .read_to_end(&mut out)
        .map_err(|e| format!("the gzip stream is damaged or truncated: {e}"))?;
    if out.len() as u64 > limit {
        return Err(format!(
            "the gzip stream inflates to more than {limit} bytes \
             (set {MAX_FILE_BYTES_VAR} to raise the limit)"
        ));
    }
    Ok(out)
}

/// The file a model in `folder` names by `reference` (a relative path, already
/// percent-decoded where the format encodes it): absolute paths, `file:` URIs and paths
/// that climb out of `folder` are refused unless [`outside_allowed`] (`file:` always).
pub fn resolve_reference(folder: &Path, reference: &str) -> Result<PathBuf, String> {
    let lower = reference.trim_start().to_ascii_lowercase();
    if lower.starts_with("file:") {
        return Err(format!(
            "'{reference}' is a file: URI: only paths relative to the model's folder are read"
        ));
    }
    let path = Path::new(reference);
    let outside = path.is_absolute() || climbs_out(path);
    if outside && !outside_allowed() {
        return Err(format!(
            "'{reference}' is outside the model's folder: only files in it are read \
             (set {ALLOW_OUTSIDE_VAR}=1 to allow others)"
        ));
    }
    Ok(folder.join(path))
}

/// True when the relative `path` goes above its starting folder at some point (`..` more
/// often than the folders before it), or names a root or drive prefix.
fn climbs_out(path: &Path) -> bool {
    let mut depth = 0usize;
    for c in path.components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir => match depth.checked_sub(1) {
                Some(d) => depth = d,
                None => return true,
            },
            Component::RootDir | Component::Prefix(_) => return true,
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_take_binary_suffixes() {
        assert_eq!(parse_size("123"), Some(123));
        assert_eq!(parse_size("64k"), Some(64 << 10));
        assert_eq!(parse_size("2G"), Some(2 << 30));
        assert_eq!(parse_size("1.5M"), Some(3 << 19));
        assert_eq!(parse_size("5T"), Some(5 << 40));
        assert_eq!(parse_size("x"), None);
        assert_eq!(parse_size("0"), None);
        assert_eq!(parse_size("5P"), None);
    }

    #[test]
    fn references_stay_in_the_folder() {
        let f = Path::new("models");
        assert_eq!(resolve_reference(f, "a/b.bin").unwrap(), f.join("a/b.bin"));
        assert_eq!(
            resolve_reference(f, "a/../b.bin").unwrap(),
            f.join("a/../b.bin")
        );
        for bad in ["../b.bin", "a/../../b", "/etc/passwd", "file:///etc/passwd"] {
            assert!(resolve_reference(f, bad).is_err(), "{bad}");
        }
    }
}

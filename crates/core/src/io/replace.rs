//! Replacing a file's content without ever leaving half a file under its name: every
//! writer (scenes, progressive records, screenshots) goes through [`replace_file`].
//!
//! What a user of `-o` expects, beyond the temporary file and the rename:
//! - a symbolic link is followed: the file it names is replaced and the link stays a link;
//! - a replaced file keeps its permissions (`chmod 600 out.wrl` stays 600);
//! - a device, FIFO or socket (`-o /dev/null`, `-o /dev/stdout`, a named pipe) is written
//!   into directly: there is no whole file to swap, and renaming over it would replace the
//!   device node itself.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Links followed before giving up (the kernel's own limit for a path).
const MAX_LINKS: usize = 40;

/// Writes through `write` into `path`: into a temporary file beside it, then renamed over
/// it; on any error the temporary file is removed and `path` is left as it was. See the
/// module's doc for links, permissions and special files.
pub fn replace_file<E: From<std::io::Error>>(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), E>,
) -> Result<(), E> {
    let target = follow_links(path)?;
    let existing = std::fs::metadata(&target).ok();
    if let Some(meta) = &existing {
        if !meta.is_file() && !meta.is_dir() {
            let file = std::fs::OpenOptions::new().write(true).open(&target)?;
            let mut w = BufWriter::with_capacity(1 << 16, file);
            write(&mut w)?;
            w.flush()?;
            return Ok(());
        }
    }
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let file = File::create(&tmp)?;
        let mut w = BufWriter::with_capacity(1 << 16, file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        if let Some(meta) = existing.as_ref().filter(|m| m.is_file()) {
            file.set_permissions(meta.permissions())?;
        }
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, &target)?;
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// The file `path` names once every symbolic link on its last component is followed (a
/// relative link is relative to the link's folder); `path` itself when it is no link or
/// does not exist yet. A loop of links is an error.
fn follow_links(path: &Path) -> std::io::Result<PathBuf> {
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&current) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = std::fs::read_link(&current)?;
                current = match current.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(current),
        }
    }
    Err(std::io::Error::other(format!(
        "more than {MAX_LINKS} symbolic links to follow"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::fs::PermissionsExt;

    fn write_text(path: &Path, text: &str) -> std::io::Result<()> {
        replace_file(path, |w| w.write_all(text.as_bytes()))
    }

    #[test]
    fn a_link_is_followed_and_stays_a_link() {
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().join("real.wrl");
        std::fs::write(&real, "old").unwrap();
        let sub = dir.path().join("sub");
        std::fs::create_dir(&sub).unwrap();
        let link = sub.join("link.wrl");
        std::os::unix::fs::symlink("../real.wrl", &link).unwrap();
        write_text(&link, "new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read_to_string(&real).unwrap(), "new");
        // A dangling link gets its file created.
        let dangling = dir.path().join("dangling.wrl");
        std::os::unix::fs::symlink("made.wrl", &dangling).unwrap();
        write_text(&dangling, "made").unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.path().join("made.wrl")).unwrap(),
            "made"
        );
        // A loop is an error, and nothing is left behind.
        let a = dir.path().join("a.wrl");
        let b = dir.path().join("b.wrl");
        std::os::unix::fs::symlink("b.wrl", &a).unwrap();
        std::os::unix::fs::symlink("a.wrl", &b).unwrap();
        assert!(write_text(&a, "x").is_err());
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
    }

    #[test]
    fn a_replaced_file_keeps_its_permissions() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.wrl");
        std::fs::write(&path, "old").unwrap();
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o640)).unwrap();
        write_text(&path, "new").unwrap();
        let mode = std::fs::metadata(&path).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o640);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
    }

    #[test]
    fn a_fifo_is_written_into_not_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("pipe.wrl");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo (coreutils)");
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || std::fs::read_to_string(fifo))
        };
        write_text(&fifo, "through the pipe").unwrap();
        assert_eq!(reader.join().unwrap().unwrap(), "through the pipe");
        let meta = std::fs::symlink_metadata(&fifo).unwrap();
        assert!(!meta.is_file(), "the FIFO was replaced by a file");
    }

    #[test]
    fn a_failed_write_leaves_the_old_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.wrl");
        std::fs::write(&path, "old").unwrap();
        let failed = replace_file(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("the writer failed"))
        });
        assert!(failed.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}

//! Debian's Open Inventor sample data (`inventor-data`) as the tests read it: binary files
//! converted to ASCII with `ivcat` (`inventor-clients`), which CI installs.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Where `inventor-data` puts its models.
pub const MODELS: &str = "/usr/share/inventor/data/models";

/// What to install when the data or `ivcat` is missing.
pub fn install_hint() -> String {
    "this test needs Debian's Open Inventor sample data and tools: run \
     `apt-get install inventor-data inventor-clients`"
        .to_string()
}

/// An ASCII version of `src`: the file itself, or its `ivcat` conversion in `dir`.
pub fn ascii_copy(src: &Path, dir: &Path) -> PathBuf {
    let head =
        std::fs::read(src).unwrap_or_else(|e| panic!("{}: {e}; {}", src.display(), install_hint()));
    let first_line = head.split(|&b| b == b'\n').next().unwrap_or(&[]);
    if !first_line.windows(6).any(|w| w == b"binary") {
        return src.to_path_buf();
    }
    let out = Command::new("ivcat")
        .arg(src)
        .output()
        .unwrap_or_else(|e| panic!("cannot run ivcat ({e}); {}", install_hint()));
    assert!(
        out.status.success() && !out.stdout.is_empty(),
        "ivcat {} failed: {}",
        src.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let dst = dir.join(src.file_name().unwrap());
    std::fs::write(&dst, out.stdout).unwrap();
    dst
}

//! The `decimate` binary run from a test, in a folder of the test's own.

use std::path::Path;
use std::process::{Command, Output};

/// Runs `decimate ARGS` in `dir` and returns what it did; fails only when it cannot start.
pub fn decimate(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run decimate: {e}"))
}

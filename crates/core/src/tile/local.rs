//! `decimate IN nogui --tiles auto|N`: plan, every tile on the local cores, and merge in one
//! process, in a work folder beside the output that is removed afterwards. The `--memory`
//! budget (default: a quarter of the machine's RAM) sizes `auto` tiles, how many run at
//! once, and whether the merge must re-tile (`schedule`, `merge`).

use std::path::{Path, PathBuf};

use super::cut::plan;
use super::TileCount;
use super::{merge, schedule, TileError};
use crate::decimate::{Report, Target};
use crate::progress_bar::Progress;

/// The work folder for `output`: beside it, named after it and this process.
pub fn work_dir_for(output: &Path) -> PathBuf {
    let name = output
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    output.with_file_name(format!(".{name}.tiles-{}", std::process::id()))
}

/// Plans `input` into `dir`, runs every tile, merges into `output`, all within `memory`
/// bytes; `progress` hears each step.
pub fn run_local(
    input: &Path,
    output: &Path,
    dir: &Path,
    count: TileCount,
    target: Target,
    memory: u64,
    progress: &Progress,
) -> Result<Report, TileError> {
    let manifest = plan(input, dir, count, target, &mut |s| progress.say(s))?;
    merge::refuse_unless_fits(manifest.target_triangles, memory)?;
    progress.set(0.1);
    schedule::run_all(dir, &manifest, memory, progress, (0.1, 0.7))?;
    merge::merge(dir, output, None, memory, progress, (0.7, 1.0))
}

//! Command-line parsing: the original program's usage (`algo filename [action]
//! [action-options]`), kept word for word where it can be, plus what ours adds.
//!
//! Hand-written rather than clap-derived because the original's shape — a file, then an
//! optional positional action whose options follow it — is its users' habit and the usage
//! text is part of the product.

use std::path::PathBuf;

use decimate_core::decimate::{Params, Target};
use decimate_core::mesh::repair::Tolerance;
pub use decimate_core::tile::{TileCount, Tiles, DEFAULT_TILE_TRIANGLES};
use decimate_viewer::app::shot::ShotOptions;

/// What the program does after reading the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Interactive viewer (the default).
    Gui,
    /// Decimate and write a VRML 2.0 file.
    NoGui,
    /// Render offscreen to a PNG, no window.
    Shot,
}

/// A fully parsed command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Args {
    pub input: PathBuf,
    pub action: Action,
    /// `-o`: defaults to `out.wrl` (nogui) or `shot.png` (shot).
    pub output: PathBuf,
    /// Decimation parameters; `target_given` says whether the user asked for any.
    pub params: Params,
    pub target_given: bool,
    /// Merge coincident vertices before decimating (`--no-weld` turns it off).
    pub weld: bool,
    /// `--weld-tolerance`: also merge vertices this close before decimating.
    pub weld_tolerance: Option<Tolerance>,
    /// Allow `-o` (and `--progressive`) to name the input file.
    pub overwrite: bool,
    /// `--progressive`: also write the collapses as vertex splits to this file (nogui; the
    /// algorithm is then quadric edge collapse).
    pub progressive: Option<PathBuf>,
    /// No summary or progress on stderr (warnings that mean lost data are still printed).
    pub quiet: bool,
    /// `--crease-angle`: degrees between faces above which smooth shading keeps an edge
    /// sharp, for every model (the viewer and shot; 180 is fully smooth).
    pub crease_angle: Option<f32>,
    /// `--lenient`: an unknown field of a known node is a warning, not an error.
    pub lenient: bool,
    pub shot: ShotOptions,
    /// `--tiles auto|N` (nogui): decimate in tiles (`tile::local`), never the whole input
    /// in memory.
    pub tiles: Option<Tiles>,
    /// `--memory SIZE`: the budget of a tiled run, in bytes: how big `auto` tiles are, how
    /// many run at once, whether the merge re-tiles (`tile::schedule`).
    pub memory: Option<u64>,
    /// `--threads N`: the pool's threads, the main one included (`threads::join_pool_of`).
    pub threads: Option<usize>,
}

/// `decimate tile ...`: one step of tiled decimation (`tile`), for a scheduler's jobs.
#[derive(Debug, Clone, PartialEq)]
pub enum TileCommand {
    Plan {
        input: PathBuf,
        dir: PathBuf,
        count: TileCount,
        target: Target,
    },
    Run {
        dir: PathBuf,
        index: Option<usize>,
    },
    Status {
        dir: PathBuf,
    },
    Merge {
        dir: PathBuf,
        output: PathBuf,
        target: Option<Target>,
        /// `--memory SIZE`: the budget that decides whether the merge re-tiles.
        memory: Option<u64>,
    },
}

/// What the command line asks for.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    Run(Box<Args>),
    Tile(TileCommand),
    Help,
    Version,
}

/// A bad command line: the message says which argument and why.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct CliError(pub String);

mod finish;
mod options;
mod tile_args;
mod values;

pub use values::draw_modes;

/// The usage text, printed by `-h`/`--help`, on errors and (as the original did) at start:
/// made from the table of options (`options`).
pub fn usage() -> &'static str {
    options::usage()
}

/// Parses the arguments after the program name.
pub fn parse<I, S>(args: I) -> Result<Command, CliError>
where
    I: IntoIterator<Item = S>,
    S: Into<String>,
{
    let args: Vec<String> = args.into_iter().map(Into::into).collect();
    let steps = ["plan", "run", "status", "merge"];
    if args.len() >= 2 && args[0] == "tile" && steps.contains(&args[1].as_str()) {
        return tile_args::parse_tile(&args[1..]).map(Command::Tile);
    }
    let mut pending = options::Pending::default();
    let mut it = args.into_iter();
    while let Some(arg) = it.next() {
        let Some(option) = options::find(&arg) else {
            positional(&mut pending, &arg)?;
            continue;
        };
        match &option.apply {
            options::Apply::Flag(set) => set(&mut pending),
            options::Apply::Value(set) => {
                let value = it
                    .next()
                    .ok_or_else(|| CliError(format!("{arg} needs a value")))?;
                set(&mut pending, &arg, &value)?;
            }
            options::Apply::Stop(options::Early::Help) => return Ok(Command::Help),
            options::Apply::Stop(options::Early::Version) => return Ok(Command::Version),
            options::Apply::Text => positional(&mut pending, &arg)?,
        }
    }
    finish::finish(pending).map(|args| Command::Run(Box::new(args)))
}

/// A word that is no option: the file, then the action.
fn positional(pending: &mut options::Pending, word: &str) -> Result<(), CliError> {
    if word.starts_with('-') && word.len() > 1 {
        return Err(CliError(format!("unknown option '{word}'")));
    }
    if pending.input.is_none() {
        pending.input = Some(PathBuf::from(word));
    } else if pending.action.is_none() {
        pending.action = Some(match word {
            "gui" => Action::Gui,
            "nogui" => Action::NoGui,
            "shot" => Action::Shot,
            other => {
                return Err(CliError(format!(
                    "unknown action '{other}' (expected gui, nogui or shot)"
                )))
            }
        });
    } else {
        return Err(CliError(format!("unexpected argument '{word}'")));
    }
    Ok(())
}

#[cfg(test)]
mod tests;

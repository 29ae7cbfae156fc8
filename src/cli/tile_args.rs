//! The words after `decimate tile`: the steps of a tiled decimation run as separate jobs.

use std::path::PathBuf;

use super::values::{bytes, number, positive, set_target};
use super::{CliError, TileCommand};
use decimate_core::decimate::Target;
use decimate_core::tile::{TileCount, DEFAULT_TILE_TRIANGLES};

/// Parses the words after `decimate tile`.
pub(super) fn parse_tile(args: &[String]) -> Result<TileCommand, CliError> {
    let step = args[0].as_str();
    let words = read_words(step, &args[1..])?;
    command_of(step, words)
}

/// What the words of one step gave, before the step's own checks.
#[derive(Default)]
struct Words<'a> {
    positional: Vec<&'a String>,
    dir: Option<PathBuf>,
    output: Option<PathBuf>,
    target: Option<Target>,
    count: Option<TileCount>,
    memory: Option<u64>,
}

/// The options of `step` and its positional words.
fn read_words<'a>(step: &str, args: &'a [String]) -> Result<Words<'a>, CliError> {
    let mut w = Words::default();
    let Words {
        positional,
        dir,
        output,
        target,
        count,
        memory,
    } = &mut w;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| CliError(format!("{name} needs a value")))
        };
        match (step, arg.as_str()) {
            ("plan", "--work") => *dir = Some(PathBuf::from(value(arg)?)),
            ("plan", "--tiles" | "--tile-triangles") => {
                if count.is_some() {
                    return Err(CliError(
                        "give only one of --tiles, --tile-triangles".into(),
                    ));
                }
                let n = positive(arg, value(arg)?)?;
                *count = Some(if arg == "--tiles" {
                    TileCount::Tiles(n)
                } else {
                    TileCount::TrianglesEach(n)
                });
            }
            ("merge", "-o" | "--output") => *output = Some(PathBuf::from(value(arg)?)),
            ("merge", "--memory") => *memory = Some(bytes(arg, value(arg)?)?),
            ("plan" | "merge", "-p" | "--percent") => {
                let p: f64 = number(arg, value(arg)?)?;
                if !(0.0..=100.0).contains(&p) {
                    return Err(CliError(format!(
                        "{arg}: the percentage must be between 0 and 100, got {p}"
                    )));
                }
                set_target(target, Target::RemovePercent(p))?;
            }
            ("plan" | "merge", "--keep-triangles") => {
                let n = number(arg, value(arg)?)?;
                set_target(target, Target::KeepTriangles(n))?;
            }
            (_, s) if s.starts_with('-') && s.len() > 1 => {
                return Err(CliError(format!("tile {step}: unknown option '{s}'")))
            }
            _ => positional.push(arg),
        }
    }
    Ok(w)
}

/// The command of `step` from its words: the right number of positional words, the
/// options it needs.
fn command_of(step: &str, w: Words<'_>) -> Result<TileCommand, CliError> {
    let Words {
        positional,
        dir,
        output,
        target,
        count,
        memory,
    } = w;
    let at_most = |n: usize, what: &str| {
        if positional.len() > n {
            Err(CliError(format!(
                "tile {step}: unexpected argument '{}' (usage: decimate tile {step} {what})",
                positional[n]
            )))
        } else {
            Ok(())
        }
    };
    let first = |what: &str| {
        positional
            .first()
            .map(|s| PathBuf::from(s.as_str()))
            .ok_or_else(|| CliError(format!("tile {step}: no {what} given")))
    };
    Ok(match step {
        "plan" => {
            at_most(1, "IN --work DIR")?;
            TileCommand::Plan {
                input: first("input file")?,
                dir: dir.ok_or_else(|| CliError("tile plan needs --work DIR".into()))?,
                count: count.unwrap_or(TileCount::TrianglesEach(DEFAULT_TILE_TRIANGLES)),
                target: target.ok_or_else(|| {
                    CliError("tile plan needs a target: -p or --keep-triangles".into())
                })?,
            }
        }
        "run" => {
            at_most(2, "DIR [INDEX]")?;
            let index = match positional.get(1) {
                Some(s) => Some(number("INDEX", s)?),
                None => None,
            };
            TileCommand::Run {
                dir: first("work folder")?,
                index,
            }
        }
        "status" => {
            at_most(1, "DIR")?;
            TileCommand::Status {
                dir: first("work folder")?,
            }
        }
        _ => {
            at_most(1, "DIR -o OUT")?;
            TileCommand::Merge {
                dir: first("work folder")?,
                output: output.unwrap_or_else(|| PathBuf::from("out.wrl")),
                target,
                memory,
            }
        }
    })
}

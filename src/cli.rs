//! Command-line parsing: the original program's usage (`algo filename [action]
//! [action-options]`), kept word for word where it can be, plus what ours adds.
//!
//! Hand-written rather than clap-derived because the original's shape — a file, then an
//! optional positional action whose options follow it — is its users' habit and the usage
//! text is part of the product.

use std::path::PathBuf;

use decimate_core::decimate::{Algorithm, ErrorBound, Params, Target};
use decimate_core::mesh::repair::Tolerance;
pub use decimate_core::tile::{TileCount, Tiles, DEFAULT_TILE_TRIANGLES};
use decimate_viewer::app::shot::ShotOptions;
use decimate_viewer::render::draw::DrawOptions;

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

/// The usage text, printed by `-h`/`--help`, on errors and (as the original did) at start.
pub const USAGE: &str = "\
usage: decimate filename [action] [action-options]
  -h, --help            prints this message
  --version             prints the version
  filename              the VRML 1.0 / VRML 2.0 / Open Inventor ASCII file to open
                        (gzipped too; PLY, OBJ, STL, OFF and glTF are also read,
                        the extension or the first bytes pick the format)
  action                gui (DEFAULT) | nogui | shot

action-options for nogui (one target is MANDATORY):
  -o filename           the file to save as; the extension picks the format: .wrl
                        (VRML 2.0), .ply, .obj, .stl, .off, .gltf, .glb (DEFAULT:
                        out.wrl); .obj writes its materials to a .mtl of the same
                        name, .gltf its buffer to a .bin
  -a, --algorithm A     schroeder (DEFAULT: vertex removal, vertices never move) |
                        qem (quadric edge collapse, vertices move)
  -p number             percent of the vertices to remove (100: as far as possible)
  -v number             number of vertices to remove
  --keep-vertices N     stop when N vertices are left
  --keep-triangles N    stop when N triangles are left
  --max-error E[%]      never remove a vertex whose error exceeds E model units
                        (or E percent of the model's bounding-box diagonal)
  --feature-angle DEG   dihedral angle that makes an edge a feature edge (DEFAULT: 30);
                        raised in 15-degree steps when a count target cannot be met
                        otherwise or corners would crowd it (not -p 100, --max-error)
  --keep-features       never raise the feature angle: stop short of the target instead
  --keep-border         never move or remove a vertex on the open border (edges of one
                        triangle): pieces of one mesh decimated apart still fit together
  --no-weld             do not merge coincident vertices before decimating
  --weld-tolerance E[%] also merge vertices closer than E model units (or E percent of
                        the model's bounding-box diagonal) before decimating (DEFAULT: off)
  --progressive FILE    also write the collapses as vertex splits (FILE.pm), to rebuild
                        any level between the result and the input (implies -a qem);
                        with FILE.pm as the input, nogui rebuilds the level the target
                        asks for (never below the base) instead of decimating
  --overwrite           allow -o or --progressive to name an input file
  -q, --quiet           no summary, progress or warnings on stderr, except warnings
                        that say part of the input is not read or of the result not
                        written
  --lenient             read a VRML / Inventor node's unknown fields as a warning (the
                        value skipped) rather than an error

action-options for shot (offscreen render to PNG, no window; --mode and --crease-angle
also set what the viewer draws):
  -o filename           the PNG to write (DEFAULT: shot.png)
  --size WxH            image size (DEFAULT: 800x600)
  --background R,G,B    the viewports' colour, each 0-255, or #rrggbb
  --viewports N         1-4 viewports: the original, then the decimated scene
  --mode LIST           comma-separated: triangles,edges,points,normals,vertex-normals,
                        flat,unlit,untextured,error (DEFAULT: triangles)
  --msaa N              anti-aliasing: 1 (off), 2, 4 or 8 samples per pixel (DEFAULT: 4)
  --crease-angle DEG    smooth shading keeps edges whose faces meet at more than DEG
                        sharp (DEFAULT: the file's creaseAngle, else 45; 180: smooth)
  --labels, --no-labels a caption on each viewport: what it shows, its counts
                        (DEFAULT: on with more than one viewport)
  --measure             add metro's error against the original (mean, max, % of the
                        diagonal) to each decimated viewport's caption
  -p / -v / ...         decimation target, as for nogui; a list such as -p 60,80,90
                        gives each decimated viewport its own (and --viewports 4)

  --tiles auto|N        decimate in N spatial tiles (auto: sized by --memory), as many
                        at once as --memory allows, borders locked, then weld them and
                        decimate the seams again; PLY, STL or OBJ, -p or --keep-triangles
  --memory SIZE         what a tiled run may use, e.g. 2G or 512M (DEFAULT: a
                        quarter of the machine's RAM)

typical usage:           decimate model.wrl
typical usage for nogui: decimate model.wrl nogui -p 100 -o output.wrl

tiled decimation as separate jobs (see docs/cluster.md):
  decimate tile plan IN --work DIR (-p P | --keep-triangles T)
                        [--tiles N | --tile-triangles M]
  decimate tile run DIR [INDEX]   (INDEX DEFAULT: $SLURM_ARRAY_TASK_ID or
                                   $JOB_COMPLETION_INDEX)
  decimate tile status DIR
  decimate tile merge DIR [-o OUT] [-p P | --keep-triangles T] [--memory SIZE]
";

/// Parses the arguments after the program name.
pub fn parse<I, S>(args: I) -> Result<Command, CliError>
where
    I: IntoIterator<Item = S>,
    S: Into<String>,
{
    let args: Vec<String> = args.into_iter().map(Into::into).collect();
    let steps = ["plan", "run", "status", "merge"];
    if args.len() >= 2 && args[0] == "tile" && steps.contains(&args[1].as_str()) {
        return parse_tile(&args[1..]).map(Command::Tile);
    }
    let mut it = args.into_iter();
    let mut tiles: Option<Tiles> = None;
    let mut memory: Option<u64> = None;
    let mut input: Option<PathBuf> = None;
    let mut action: Option<Action> = None;
    let mut output: Option<PathBuf> = None;
    let mut params = Params::default();
    let mut algorithm: Option<Algorithm> = None;
    let mut progressive: Option<PathBuf> = None;
    let mut target: Option<Target> = None;
    // Every target of a list (`-p 60,80,90`): one per decimated viewport of a shot.
    let mut targets: Vec<Target> = Vec::new();
    let mut viewports: Option<u32> = None;
    let mut weld = true;
    let mut weld_tolerance = None;
    let mut overwrite = false;
    let mut quiet = false;
    let mut crease_angle: Option<f32> = None;
    let mut lenient = false;
    let mut shot = ShotOptions::default();

    while let Some(arg) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| CliError(format!("{name} needs a value")))
        };
        match arg.as_str() {
            "-h" | "--help" => return Ok(Command::Help),
            "--version" | "-V" => return Ok(Command::Version),
            "-o" | "--output" => output = Some(PathBuf::from(value(&arg)?)),
            "-p" | "--percent" => {
                let list: Vec<f64> = numbers(&arg, &value(&arg)?)?;
                if let Some(p) = list.iter().find(|p| !(0.0..=100.0).contains(*p)) {
                    return Err(CliError(format!(
                        "{arg}: the percentage must be between 0 and 100, got {p}"
                    )));
                }
                targets = list.into_iter().map(Target::RemovePercent).collect();
                set_target(&mut target, targets[0])?;
            }
            "-v" | "--vertices" => {
                targets = numbers(&arg, &value(&arg)?)?
                    .into_iter()
                    .map(Target::RemoveVertices)
                    .collect();
                set_target(&mut target, targets[0])?;
            }
            "--keep-vertices" => {
                targets = numbers(&arg, &value(&arg)?)?
                    .into_iter()
                    .map(Target::KeepVertices)
                    .collect();
                set_target(&mut target, targets[0])?;
            }
            "--keep-triangles" => {
                targets = numbers(&arg, &value(&arg)?)?
                    .into_iter()
                    .map(Target::KeepTriangles)
                    .collect();
                set_target(&mut target, targets[0])?;
            }
            "--max-error" => params.max_error = Some(error_bound(&value(&arg)?)?),
            "--feature-angle" => {
                let a: f64 = number(&arg, &value(&arg)?)?;
                if !(0.0..=180.0).contains(&a) {
                    return Err(CliError(format!(
                        "--feature-angle: expected degrees between 0 and 180, got {a}"
                    )));
                }
                params.feature_angle_deg = a;
            }
            "-a" | "--algorithm" => {
                algorithm = Some(match value(&arg)?.as_str() {
                    "schroeder" => Algorithm::Schroeder,
                    "qem" => Algorithm::Qem,
                    other => {
                        return Err(CliError(format!(
                            "{arg}: unknown algorithm '{other}' (expected schroeder or qem)"
                        )))
                    }
                })
            }
            "--progressive" => progressive = Some(PathBuf::from(value(&arg)?)),
            "--no-weld" => weld = false,
            "--weld-tolerance" => weld_tolerance = Some(tolerance(&value(&arg)?)?),
            "--keep-features" => params.keep_features = true,
            "--keep-border" => params.keep_border = true,
            "--overwrite" => overwrite = true,
            "-q" | "--quiet" => quiet = true,
            "--lenient" => lenient = true,
            "--size" => {
                let (w, h) = size(&value(&arg)?)?;
                shot.width = w;
                shot.height = h;
            }
            "--background" => shot.background = Some(colour(&arg, &value(&arg)?)?),
            "--viewports" => {
                let n: u32 = number(&arg, &value(&arg)?)?;
                if !(1..=4).contains(&n) {
                    return Err(CliError(format!("--viewports: expected 1 to 4, got {n}")));
                }
                viewports = Some(n);
            }
            "--tiles" => {
                let v = value(&arg)?;
                tiles = Some(if v == "auto" {
                    Tiles::Auto
                } else {
                    Tiles::Count(positive(&arg, &v)?)
                });
            }
            "--memory" => memory = Some(bytes(&arg, &value(&arg)?)?),
            "--crease-angle" => {
                let a: f32 = number(&arg, &value(&arg)?)?;
                if !(0.0..=180.0).contains(&a) {
                    return Err(CliError(format!(
                        "--crease-angle: expected degrees between 0 and 180, got {a}"
                    )));
                }
                crease_angle = Some(a);
            }
            "--labels" => shot.labels = Some(true),
            "--no-labels" => shot.labels = Some(false),
            "--measure" => shot.measure = true,
            "--mode" => shot.modes = draw_modes(&value(&arg)?)?,
            "--msaa" => {
                let n: u32 = number(&arg, &value(&arg)?)?;
                if ![1, 2, 4, 8].contains(&n) {
                    return Err(CliError(format!(
                        "--msaa: expected 1 (off), 2, 4 or 8 samples per pixel, got {n}"
                    )));
                }
                shot.msaa = n;
            }
            s if s.starts_with('-') && s.len() > 1 => {
                return Err(CliError(format!("unknown option '{s}'")))
            }
            s => {
                if input.is_none() {
                    input = Some(PathBuf::from(s));
                } else if action.is_none() {
                    action = Some(match s {
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
                    return Err(CliError(format!("unexpected argument '{s}'")));
                }
            }
        }
    }

    let input = input.ok_or_else(|| CliError("no filename given".into()))?;
    let action = action.unwrap_or(Action::Gui);
    if target.is_none() && params.max_error.is_some() {
        target = Some(Target::ErrorOnly);
    }
    if action == Action::NoGui && target.is_none() {
        return Err(CliError(
            "nogui needs a target: one of -p, -v, --keep-vertices, --keep-triangles, --max-error"
                .into(),
        ));
    }
    params.algorithm = resolve_algorithm(algorithm, progressive.is_some())?;
    let target_given = target.is_some();
    if let Some(t) = target {
        params.target = t;
    }
    let output = output.unwrap_or_else(|| match action {
        Action::Shot => PathBuf::from("shot.png"),
        _ => PathBuf::from("out.wrl"),
    });
    if let Some(pm) = &progressive {
        check_progressive(pm, action, &output)?;
    }
    if tiles.is_some() || memory.is_some() {
        check_tiles(action, &params, progressive.is_some(), tiles.is_some())?;
    }
    if action == Action::NoGui && decimate_core::io::Format::from_path(&output).is_none() {
        return Err(CliError(format!(
            "-o {}: no writer knows this extension (expected .wrl, .vrml, .ply, .obj, .stl, .off, .gltf or .glb)",
            output.display()
        )));
    }
    shot.texture_dir = decimate_core::io::texture_path::folder_of(&input).to_path_buf();
    shot_targets(&mut shot, targets, viewports, action)?;
    check_measure(&shot, action, target_given)?;
    if crease_angle.is_some() && action == Action::NoGui {
        return Err(CliError(
            "--crease-angle is an option of the viewer and shot (shading only)".into(),
        ));
    }
    Ok(Command::Run(Box::new(Args {
        input,
        action,
        output,
        params,
        target_given,
        weld,
        weld_tolerance,
        overwrite,
        progressive,
        quiet,
        crease_angle,
        lenient,
        shot,
        tiles,
        memory,
    })))
}

/// `--measure` belongs to `shot` with a target (something decimated to measure), and
/// shows in the captions.
fn check_measure(shot: &ShotOptions, action: Action, target_given: bool) -> Result<(), CliError> {
    if !shot.measure {
        return Ok(());
    }
    if action != Action::Shot {
        return Err(CliError(
            "--measure is an option of shot (in the viewer, key d measures)".into(),
        ));
    }
    if !target_given {
        return Err(CliError(
            "--measure needs a target (-p, -v, ...): nothing is decimated to measure".into(),
        ));
    }
    if shot.labels == Some(false) {
        return Err(CliError(
            "--measure says the error in the captions: it cannot go with --no-labels".into(),
        ));
    }
    Ok(())
}

/// `--tiles` belongs to nogui with a count target it can share out (`tile::cut::target_of`).
fn check_tiles(
    action: Action,
    params: &Params,
    progressive: bool,
    tiles: bool,
) -> Result<(), CliError> {
    if !tiles {
        return Err(CliError("--memory is an option of --tiles".into()));
    }
    if action != Action::NoGui {
        return Err(CliError("--tiles is an option of nogui".into()));
    }
    if progressive {
        return Err(CliError(
            "--tiles cannot record --progressive vertex splits".into(),
        ));
    }
    if params.max_error.is_some() {
        return Err(CliError("--tiles takes no --max-error".into()));
    }
    match params.target {
        Target::RemovePercent(_) | Target::KeepTriangles(_) => Ok(()),
        _ => Err(CliError(
            "--tiles needs -p or --keep-triangles as its target".into(),
        )),
    }
}

/// Parses the words after `decimate tile`.
fn parse_tile(args: &[String]) -> Result<TileCommand, CliError> {
    let step = args[0].as_str();
    let mut it = args[1..].iter();
    let mut positional: Vec<&String> = Vec::new();
    let mut dir: Option<PathBuf> = None;
    let mut output: Option<PathBuf> = None;
    let mut target: Option<Target> = None;
    let mut count: Option<TileCount> = None;
    let mut memory: Option<u64> = None;
    while let Some(arg) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| CliError(format!("{name} needs a value")))
        };
        match (step, arg.as_str()) {
            ("plan", "--work") => dir = Some(PathBuf::from(value(arg)?)),
            ("plan", "--tiles" | "--tile-triangles") => {
                if count.is_some() {
                    return Err(CliError(
                        "give only one of --tiles, --tile-triangles".into(),
                    ));
                }
                let n = positive(arg, value(arg)?)?;
                count = Some(if arg == "--tiles" {
                    TileCount::Tiles(n)
                } else {
                    TileCount::TrianglesEach(n)
                });
            }
            ("merge", "-o" | "--output") => output = Some(PathBuf::from(value(arg)?)),
            ("merge", "--memory") => memory = Some(bytes(arg, value(arg)?)?),
            ("plan" | "merge", "-p" | "--percent") => {
                let p: f64 = number(arg, value(arg)?)?;
                if !(0.0..=100.0).contains(&p) {
                    return Err(CliError(format!(
                        "{arg}: the percentage must be between 0 and 100, got {p}"
                    )));
                }
                set_target(&mut target, Target::RemovePercent(p))?;
            }
            ("plan" | "merge", "--keep-triangles") => {
                let n = number(arg, value(arg)?)?;
                set_target(&mut target, Target::KeepTriangles(n))?;
            }
            (_, s) if s.starts_with('-') && s.len() > 1 => {
                return Err(CliError(format!("tile {step}: unknown option '{s}'")))
            }
            _ => positional.push(arg),
        }
    }
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

/// A count of at least one.
fn positive(name: &str, s: &str) -> Result<usize, CliError> {
    match number::<usize>(name, s)? {
        0 => Err(CliError(format!("{name}: expected at least 1, got 0"))),
        n => Ok(n),
    }
}

/// A size in bytes, with an optional K, M, G or T suffix (powers of 1024).
fn bytes(name: &str, s: &str) -> Result<u64, CliError> {
    let t = s.trim();
    let (digits, unit) = match t.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => (&t[..i], c.to_ascii_uppercase()),
        _ => (t, 'B'),
    };
    let shift = match unit {
        'B' => 0,
        'K' => 10,
        'M' => 20,
        'G' => 30,
        'T' => 40,
        _ => {
            return Err(CliError(format!(
                "{name}: expected a size such as 2G, got '{s}'"
            )))
        }
    };
    let v: f64 = number(name, digits)?;
    if !(v.is_finite() && v > 0.0) {
        return Err(CliError(format!(
            "{name}: expected a positive size, got '{s}'"
        )));
    }
    Ok((v * f64::from(1u32 << 10).powi(shift / 10)) as u64)
}

/// The algorithm `-a` asked for, or the one `--progressive` implies: only quadric edge
/// collapse has vertex splits to record.
fn resolve_algorithm(asked: Option<Algorithm>, progressive: bool) -> Result<Algorithm, CliError> {
    match (asked, progressive) {
        (Some(Algorithm::Schroeder), true) => Err(CliError(
            "--progressive: vertex removal (-a schroeder) records no vertex splits; use -a qem \
             (or leave -a out)"
                .into(),
        )),
        (_, true) => Ok(Algorithm::Qem),
        (asked, false) => Ok(asked.unwrap_or_default()),
    }
}

/// `--progressive` belongs to nogui and needs a file of its own.
fn check_progressive(
    pm: &std::path::Path,
    action: Action,
    output: &std::path::Path,
) -> Result<(), CliError> {
    if action != Action::NoGui {
        return Err(CliError("--progressive is an option of nogui".into()));
    }
    if pm == output {
        return Err(CliError(format!(
            "--progressive: {} is also the -o file; give them different names",
            pm.display()
        )));
    }
    Ok(())
}

/// A list of targets is one per decimated viewport of a shot: it sets the viewport count
/// when `--viewports` is not given, and must fit the count when it is.
fn shot_targets(
    shot: &mut ShotOptions,
    targets: Vec<Target>,
    viewports: Option<u32>,
    action: Action,
) -> Result<(), CliError> {
    if targets.len() > 1 && action != Action::Shot {
        return Err(CliError(format!(
            "a list of {} targets gives each decimated viewport of a shot its own; {} takes one",
            targets.len(),
            if action == Action::NoGui {
                "nogui"
            } else {
                "the viewer"
            }
        )));
    }
    let decimated = targets.len() as u32;
    if decimated > 3 {
        return Err(CliError(format!(
            "{decimated} targets: at most 3, for the viewports beside the original"
        )));
    }
    shot.viewports = match viewports {
        Some(n) if targets.len() > 1 && decimated != n.saturating_sub(1) => {
            return Err(CliError(format!(
                "--viewports {n}: {decimated} targets need {} viewports (the first shows the \
                 original), one target per decimated viewport",
                decimated + 1
            )))
        }
        Some(n) => n,
        None if targets.len() > 1 => (decimated + 1).min(4),
        None => 1,
    };
    if targets.len() > 1 {
        shot.targets = targets;
    }
    Ok(())
}

fn set_target(slot: &mut Option<Target>, t: Target) -> Result<(), CliError> {
    if slot.is_some() {
        return Err(CliError(
            "give only one of -p, -v, --keep-vertices, --keep-triangles".into(),
        ));
    }
    *slot = Some(t);
    Ok(())
}

fn number<T: std::str::FromStr>(name: &str, s: &str) -> Result<T, CliError> {
    s.trim()
        .parse()
        .map_err(|_| CliError(format!("{name}: expected a number, got '{s}'")))
}

/// `R,G,B` (each 0 to 255) or `#rrggbb`, as RGB from 0 to 1.
fn colour(name: &str, s: &str) -> Result<[f32; 3], CliError> {
    let bad = || {
        CliError(format!(
            "{name}: expected R,G,B (0-255 each) or #rrggbb, got '{s}'"
        ))
    };
    let channels: Vec<u8> = match s.strip_prefix('#') {
        Some(hex) if hex.len() == 6 && hex.is_ascii() => (0..3)
            .map(|i| u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).map_err(|_| bad()))
            .collect::<Result<_, _>>()?,
        Some(_) => return Err(bad()),
        None => numbers::<u8>(name, s).map_err(|_| bad())?,
    };
    match channels[..] {
        [r, g, b] => Ok([r, g, b].map(|c| f32::from(c) / 255.0)),
        _ => Err(bad()),
    }
}

/// A comma-separated list of numbers (`60,80,90`), at least one.
fn numbers<T: std::str::FromStr>(name: &str, s: &str) -> Result<Vec<T>, CliError> {
    s.split(',').map(|item| number(name, item)).collect()
}

fn error_bound(s: &str) -> Result<ErrorBound, CliError> {
    let (digits, percent) = match s.strip_suffix('%') {
        Some(d) => (d, true),
        None => (s, false),
    };
    let e: f64 = number("--max-error", digits)?;
    if !e.is_finite() || e < 0.0 {
        return Err(CliError(format!(
            "--max-error: expected a non-negative number, got '{s}'"
        )));
    }
    Ok(if percent {
        ErrorBound::DiagonalFraction(e / 100.0)
    } else {
        ErrorBound::Absolute(e)
    })
}

fn tolerance(s: &str) -> Result<Tolerance, CliError> {
    let (digits, percent) = match s.strip_suffix('%') {
        Some(d) => (d, true),
        None => (s, false),
    };
    let e: f64 = number("--weld-tolerance", digits)?;
    if !e.is_finite() || e < 0.0 {
        return Err(CliError(format!(
            "--weld-tolerance: expected a non-negative number, got '{s}'"
        )));
    }
    Ok(if percent {
        Tolerance::DiagonalFraction(e / 100.0)
    } else {
        Tolerance::Absolute(e)
    })
}

fn size(s: &str) -> Result<(u32, u32), CliError> {
    let bad = || CliError(format!("--size: expected WxH such as 800x600, got '{s}'"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.parse().map_err(|_| bad())?;
    let h: u32 = h.parse().map_err(|_| bad())?;
    if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
        return Err(CliError(format!(
            "--size: each side must be 1 to 8192 pixels, got '{s}'"
        )));
    }
    Ok((w, h))
}

/// The draw toggles of a `--mode` list (the viewer's toggles, shading words meaning "off").
pub fn draw_modes(s: &str) -> Result<DrawOptions, CliError> {
    let mut m = DrawOptions {
        triangles: false,
        ..DrawOptions::default()
    };
    for word in s.split(',').map(str::trim).filter(|w| !w.is_empty()) {
        match word {
            "triangles" | "solid" => m.triangles = true,
            "edges" => m.edges = true,
            "points" => m.points = true,
            "normals" => m.face_normals = true,
            "vertex-normals" => m.vertex_normals = true,
            "flat" => m.smooth = false,
            "unlit" => m.lighting = false,
            "untextured" => m.textures = false,
            "error" => m.error_map = true,
            other => {
                return Err(CliError(format!(
                    "--mode: unknown mode '{other}' (expected triangles, edges, points, \
                     normals, vertex-normals, flat, unlit, untextured, error)"
                )))
            }
        }
    }
    // Shading words alone still mean "draw the triangles".
    if !(m.edges || m.points) {
        m.triangles = true;
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(args: &[&str]) -> Args {
        match parse(args.iter().copied()) {
            Ok(Command::Run(a)) => *a,
            other => panic!("expected a run, got {other:?}"),
        }
    }

    #[test]
    fn original_typical_usages() {
        let a = run(&["model.wrl"]);
        assert_eq!(a.action, Action::Gui);
        let a = run(&["model.wrl", "nogui", "-p", "100", "-o", "output.wrl"]);
        assert_eq!(a.action, Action::NoGui);
        assert_eq!(a.params.target, Target::RemovePercent(100.0));
        assert_eq!(a.output, PathBuf::from("output.wrl"));
        let a = run(&["model.wrl", "nogui", "-v", "50"]);
        assert_eq!(a.params.target, Target::RemoveVertices(50));
        assert_eq!(a.output, PathBuf::from("out.wrl"));
    }

    #[test]
    fn algorithm_is_schroeder_unless_qem_is_asked() {
        let a = run(&["model.wrl", "nogui", "-p", "90"]);
        assert_eq!(a.params.algorithm, Algorithm::Schroeder);
        let a = run(&["model.wrl", "nogui", "-a", "qem", "-p", "90"]);
        assert_eq!(a.params.algorithm, Algorithm::Qem);
        let a = run(&["model.wrl", "nogui", "--algorithm", "schroeder", "-p", "90"]);
        assert_eq!(a.params.algorithm, Algorithm::Schroeder);
        let e = parse(["model.wrl", "nogui", "-a", "lindstrom", "-p", "9"]);
        assert_eq!(
            e,
            Err(CliError(
                "-a: unknown algorithm 'lindstrom' (expected schroeder or qem)".into()
            ))
        );
        assert!(USAGE.contains("-a, --algorithm A"));
    }

    #[test]
    fn progressive_selects_qem_and_refuses_schroeder() {
        let a = run(&["m.wrl", "nogui", "-p", "90", "--progressive", "m.pm"]);
        assert_eq!(a.progressive, Some(PathBuf::from("m.pm")));
        assert_eq!(a.params.algorithm, Algorithm::Qem);
        assert_eq!(a.output, PathBuf::from("out.wrl"));
        let a = run(&[
            "m.wrl",
            "nogui",
            "-a",
            "qem",
            "--progressive",
            "x",
            "-p",
            "9",
        ]);
        assert_eq!(a.progressive, Some(PathBuf::from("x")));
        assert_eq!(a.params.algorithm, Algorithm::Qem);
        assert_eq!(run(&["m.wrl", "nogui", "-p", "9"]).progressive, None);
        for order in [
            ["-a", "schroeder", "--progressive", "m.pm"],
            ["--progressive", "m.pm", "-a", "schroeder"],
        ] {
            let mut args = vec!["m.wrl", "nogui", "-p", "50"];
            args.extend(order);
            let e = parse(args).unwrap_err();
            assert!(
                e.0.contains("records no vertex splits") && e.0.contains("-a qem"),
                "{e}"
            );
        }
        assert!(USAGE.contains("  --progressive FILE    also write the collapses"));
        assert!(USAGE.contains("(implies -a qem)"));
    }

    #[test]
    fn progressive_needs_nogui_a_value_and_its_own_file() {
        let e = parse(["m.wrl", "nogui", "-p", "9", "--progressive"]).unwrap_err();
        assert!(e.0.contains("--progressive needs a value"), "{e}");
        let e = parse(["m.wrl", "shot", "--progressive", "m.pm"]).unwrap_err();
        assert!(e.0.contains("option of nogui"), "{e}");
        let e = parse(["m.wrl", "--progressive", "m.pm"]).unwrap_err();
        assert!(e.0.contains("option of nogui"), "{e}");
        let e = parse(["m.wrl", "nogui", "-p", "9", "--progressive", "out.wrl"]).unwrap_err();
        assert!(e.0.contains("also the -o file"), "{e}");
        let e = parse([
            "m.wrl",
            "nogui",
            "-p",
            "9",
            "-o",
            "a.pm",
            "--progressive",
            "a.pm",
        ]);
        assert!(e.is_err());
    }

    #[test]
    fn tile_steps_parse_and_a_file_named_tile_still_opens() {
        assert_eq!(
            parse(["tile", "run", "w"]),
            Ok(Command::Tile(TileCommand::Run {
                dir: PathBuf::from("w"),
                index: None
            }))
        );
        assert_eq!(
            parse([
                "tile",
                "plan",
                "in.ply",
                "--work",
                "w",
                "--tile-triangles",
                "5",
                "-p",
                "90"
            ]),
            Ok(Command::Tile(TileCommand::Plan {
                input: PathBuf::from("in.ply"),
                dir: PathBuf::from("w"),
                count: TileCount::TrianglesEach(5),
                target: Target::RemovePercent(90.0),
            }))
        );
        assert_eq!(
            parse(["tile", "merge", "w", "-o", "o.ply", "--memory", "512M"]),
            Ok(Command::Tile(TileCommand::Merge {
                dir: PathBuf::from("w"),
                output: PathBuf::from("o.ply"),
                target: None,
                memory: Some(512 << 20),
            }))
        );
        assert_eq!(run(&["tile"]).input, PathBuf::from("tile"));
        assert_eq!(run(&["tile", "nogui", "-p", "9"]).action, Action::NoGui);
        let a = run(&[
            "m.ply", "nogui", "-p", "9", "--tiles", "auto", "--memory", "1.5G",
        ]);
        assert_eq!((a.tiles, a.memory), (Some(Tiles::Auto), Some(3 << 29)));
        assert_eq!(
            run(&["m.ply", "nogui", "-p", "9", "--tiles", "7"]).tiles,
            Some(Tiles::Count(7))
        );
    }

    #[test]
    fn help_and_version() {
        assert_eq!(parse(["-h"]), Ok(Command::Help));
        assert_eq!(parse(["x.wrl", "--help"]), Ok(Command::Help));
        assert_eq!(parse(["--version"]), Ok(Command::Version));
    }

    #[test]
    fn nogui_without_target_is_an_error() {
        let e = parse(["m.wrl", "nogui"]).unwrap_err();
        assert!(e.0.contains("needs a target"), "{e}");
    }

    #[test]
    fn bad_values_are_named() {
        assert!(parse(["m.wrl", "nogui", "-p", "abc"])
            .unwrap_err()
            .0
            .contains("-p"));
        assert!(parse(["m.wrl", "nogui", "-p", "140"])
            .unwrap_err()
            .0
            .contains("between 0 and 100"));
        assert!(parse(["m.wrl", "nogui", "-p"])
            .unwrap_err()
            .0
            .contains("needs a value"));
        assert!(parse(["m.wrl", "fly"])
            .unwrap_err()
            .0
            .contains("unknown action"));
        assert!(parse(["m.wrl", "nogui", "-p", "5", "-v", "3"])
            .unwrap_err()
            .0
            .contains("only one"));
        assert!(parse(["m.wrl", "--frobnicate"])
            .unwrap_err()
            .0
            .contains("--frobnicate"));
        assert!(parse(Vec::<String>::new())
            .unwrap_err()
            .0
            .contains("no filename"));
    }

    #[test]
    fn error_bounds_and_shot_options() {
        let a = run(&["m.wrl", "nogui", "-p", "90", "--keep-features"]);
        assert!(a.params.keep_features && !a.params.keep_border);
        let a = run(&["m.wrl", "nogui", "-p", "90", "--keep-border"]);
        assert!(a.params.keep_border && !a.params.keep_features);
        let a = run(&["m.wrl", "nogui", "--max-error", "0.5%"]);
        assert_eq!(a.params.target, Target::ErrorOnly);
        assert_eq!(
            a.params.max_error,
            Some(ErrorBound::DiagonalFraction(0.005))
        );
        let a = run(&[
            "m.wrl",
            "shot",
            "--size",
            "640x480",
            "--viewports",
            "4",
            "--mode",
            "edges,flat",
        ]);
        assert_eq!(
            (a.shot.width, a.shot.height, a.shot.viewports),
            (640, 480, 4)
        );
        assert!(a.shot.modes.edges && !a.shot.modes.smooth && !a.shot.modes.triangles);
        assert!(a.shot.modes.lighting && a.shot.modes.textures);
        assert_eq!(run(&["m.wrl", "shot"]).shot.modes, DrawOptions::default());
        assert_eq!(a.output, PathBuf::from("shot.png"));
        assert!(parse(["m.wrl", "shot", "--viewports", "5"]).is_err());
        assert_eq!(a.shot.labels, None);
        let a = run(&["m.wrl", "shot", "--no-labels"]);
        assert_eq!(a.shot.labels, Some(false));
        assert!(!a.shot.measure);
        assert!(
            run(&["m.wrl", "shot", "-p", "60,80", "--measure"])
                .shot
                .measure
        );
        for (args, says) in [
            (
                &["m.wrl", "nogui", "-p", "50", "--measure"][..],
                "an option of shot",
            ),
            (&["m.wrl", "shot", "--measure"][..], "needs a target"),
            (
                &["m.wrl", "shot", "-p", "5", "--measure", "--no-labels"][..],
                "--no-labels",
            ),
        ] {
            let e = parse(args.iter().copied()).map(|_| ()).unwrap_err();
            assert!(e.0.contains(says), "{args:?}: {}", e.0);
        }
        let a = run(&["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "0.1%"]);
        assert_eq!(a.weld_tolerance, Some(Tolerance::DiagonalFraction(0.001)));
        let a = run(&["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "0.25"]);
        assert_eq!(a.weld_tolerance, Some(Tolerance::Absolute(0.25)));
        assert_eq!(run(&["m.wrl", "nogui", "-p", "50"]).weld_tolerance, None);
        assert!(parse(["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "-1"]).is_err());
        assert!(parse(["m.wrl", "nogui", "-p", "50", "--weld-tolerance", "x%"]).is_err());
        assert!(parse(["m.wrl", "shot", "--size", "0x10"]).is_err());
    }

    #[test]
    fn msaa_and_the_error_map_are_options_of_the_viewer_and_shot() {
        assert_eq!(run(&["m.wrl", "shot"]).shot.msaa, 4);
        assert_eq!(run(&["m.wrl", "shot", "--msaa", "1"]).shot.msaa, 1);
        assert_eq!(run(&["m.wrl", "--msaa", "8"]).shot.msaa, 8);
        match parse(["m.wrl", "shot", "--msaa", "3"]) {
            Err(e) => assert!(e.0.contains("--msaa") && e.0.contains('3'), "{}", e.0),
            Ok(_) => panic!("--msaa 3 was accepted"),
        }
        assert!(parse(["m.wrl", "shot", "--msaa", "x"]).is_err());
        let a = run(&["m.wrl", "shot", "--mode", "error"]);
        assert!(a.shot.modes.error_map && a.shot.modes.triangles);
        assert!(!run(&["m.wrl", "shot"]).shot.modes.error_map);
    }

    #[test]
    fn the_crease_angle_is_for_the_viewer_and_shot() {
        assert_eq!(
            run(&["m.wrl", "--crease-angle", "180"]).crease_angle,
            Some(180.0)
        );
        assert_eq!(
            run(&["m.wrl", "shot", "--crease-angle", "60"]).crease_angle,
            Some(60.0)
        );
        assert_eq!(run(&["m.wrl"]).crease_angle, None);
        for (args, says) in [
            (
                &["m.wrl", "--crease-angle", "200"][..],
                "between 0 and 180, got 200",
            ),
            (
                &["m.wrl", "shot", "--crease-angle", "x"],
                "--crease-angle: expected a number",
            ),
            (
                &["m.wrl", "nogui", "-p", "5", "--crease-angle", "60"],
                "viewer and shot",
            ),
        ] {
            let e = parse(args.iter().copied()).unwrap_err();
            assert!(e.0.contains(says), "{args:?}: {e}");
        }
    }

    #[test]
    fn a_list_of_targets_gives_each_decimated_viewport_its_own() {
        let a = run(&[
            "m.wrl",
            "shot",
            "-p",
            "60,80,90",
            "--mode",
            "triangles,edges",
        ]);
        assert_eq!(a.shot.viewports, 4);
        assert_eq!(
            a.shot.targets,
            [60.0, 80.0, 90.0].map(Target::RemovePercent).to_vec()
        );
        assert_eq!(a.params.target, Target::RemovePercent(60.0));
        let a = run(&[
            "m.wrl",
            "shot",
            "--keep-triangles",
            "500,100",
            "--viewports",
            "3",
        ]);
        assert_eq!(a.shot.viewports, 3);
        assert_eq!(
            a.shot.targets,
            [500, 100].map(Target::KeepTriangles).to_vec()
        );
        let a = run(&["m.wrl", "shot", "-p", "60"]);
        assert_eq!((a.shot.viewports, a.shot.targets.len()), (1, 0));
        let white = Some([1.0; 3]);
        assert_eq!(
            run(&["m.wrl", "shot", "--background", "255,255,255"])
                .shot
                .background,
            white
        );
        assert_eq!(
            run(&["m.wrl", "shot", "--background", "#ffffff"])
                .shot
                .background,
            white
        );
        for (args, says) in [
            (
                &["m.wrl", "shot", "-p", "60,80,90", "--viewports", "3"][..],
                "need 4 viewports",
            ),
            (
                &["m.wrl", "shot", "-p", "60,80", "--viewports", "4"][..],
                "2 targets need 3 viewports",
            ),
            (&["m.wrl", "shot", "-p", "10,20,30,40"], "at most 3"),
            (&["m.wrl", "shot", "--background", "1,2"], "expected R,G,B"),
            (
                &["m.wrl", "shot", "--background", "#12345g"],
                "expected R,G,B",
            ),
            (
                &["m.wrl", "shot", "--background", "0,0,256"],
                "expected R,G,B",
            ),
            (
                &["m.wrl", "shot", "-p", "60,180"],
                "between 0 and 100, got 180",
            ),
            (
                &["m.wrl", "shot", "-p", "60,,90"],
                "-p: expected a number, got ''",
            ),
            (&["m.wrl", "nogui", "-p", "60,80"], "nogui takes one"),
            (&["m.wrl", "-v", "6,8"], "the viewer takes one"),
        ] {
            let e = parse(args.iter().copied()).unwrap_err();
            assert!(e.0.contains(says), "{args:?}: {e}");
        }
    }
}

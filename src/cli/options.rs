//! The table of options: each row names its spellings, the usage line it prints and what it
//! does to the command line being parsed. The usage text is printed from this table, so an
//! option cannot be accepted without being shown, nor shown without being accepted.

use std::path::PathBuf;
use std::sync::LazyLock;

use super::values::{
    bytes, colour, draw_modes, error_bound, number, numbers, positive, set_target, size, tolerance,
};
use super::CliError;
use decimate_core::decimate::{Algorithm, Cost, Params, Target};
use decimate_core::mesh::repair::Tolerance;
use decimate_core::tile::Tiles;
use decimate_viewer::app::shot::ShotOptions;

/// Where a row prints in the usage text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Section {
    /// Under the `usage:` line: help, version, the positional words.
    General,
    /// "action-options for nogui".
    NoGui,
    /// "action-options for shot".
    Shot,
    /// The tiled run's options, after a blank line.
    Tiles,
}

/// What an option does to the command line being parsed.
pub(super) enum Apply {
    /// A switch: no value.
    Flag(fn(&mut Pending)),
    /// An option with a value; gets the spelling used (for messages) and the value.
    Value(fn(&mut Pending, &str, &str) -> Result<(), CliError>),
    /// Ends the parse with this answer (`--help`, `--version`).
    Stop(Early),
    /// A usage line only: a positional word or a note, not an option.
    Text,
}

/// The answers that end a parse early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Early {
    Help,
    Version,
}

/// One row of the table.
pub(super) struct OptionSpec {
    /// Every spelling the parser accepts (the first few are shown in `shown`).
    pub names: &'static [&'static str],
    /// The usage line's left column.
    pub shown: Option<&'static str>,
    /// The usage line's right column, one entry a line.
    pub help: &'static [&'static str],
    pub section: Section,
    pub apply: Apply,
}

/// Everything the options set, before the checks that need all of them (`finish`).
#[derive(Debug, Default)]
pub(super) struct Pending {
    pub input: Option<PathBuf>,
    pub action: Option<super::Action>,
    pub output: Option<PathBuf>,
    pub params: Params,
    pub algorithm: Option<Algorithm>,
    pub progressive: Option<PathBuf>,
    pub target: Option<Target>,
    /// Every target of a list (`-p 60,80,90`): one per decimated viewport of a shot.
    pub targets: Vec<Target>,
    pub viewports: Option<u32>,
    pub no_weld: bool,
    pub weld_tolerance: Option<Tolerance>,
    pub overwrite: bool,
    pub quiet: bool,
    pub crease_angle: Option<f32>,
    pub lenient: bool,
    pub shot: ShotOptions,
    pub tiles: Option<Tiles>,
    pub memory: Option<u64>,
    pub threads: Option<usize>,
}

/// The option spelled `name`, if any row accepts it.
pub(super) fn find(name: &str) -> Option<&'static OptionSpec> {
    OPTIONS.iter().find(|o| o.names.contains(&name))
}

/// The usage text, printed by `-h`/`--help`, on errors and by the viewer at start.
pub(super) fn usage() -> &'static str {
    static TEXT: LazyLock<String> = LazyLock::new(usage_text);
    &TEXT
}

fn usage_text() -> String {
    let mut out = String::from("usage: decimate filename [action] [action-options]\n");
    rows(&mut out, Section::General);
    out.push_str("\naction-options for nogui (one target is MANDATORY):\n");
    rows(&mut out, Section::NoGui);
    out.push_str(
        "\naction-options for shot (offscreen render to PNG, no window; --mode and \
         --crease-angle\nalso set what the viewer draws):\n",
    );
    rows(&mut out, Section::Shot);
    out.push('\n');
    rows(&mut out, Section::Tiles);
    out.push_str(TAIL);
    out
}

/// The usage lines of one section, left column 21 wide as the original's.
fn rows(out: &mut String, section: Section) {
    for o in OPTIONS.iter().filter(|o| o.section == section) {
        let Some(shown) = o.shown else { continue };
        for (i, line) in o.help.iter().enumerate() {
            let left = if i == 0 { shown } else { "" };
            out.push_str(&format!("  {left:<21} {line}\n"));
        }
    }
}

const TAIL: &str = "
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

/// A list of targets from `value`: the first is the target, all of them the shot's list.
fn targets(
    p: &mut Pending,
    name: &str,
    value: &str,
    make: fn(f64) -> Target,
) -> Result<(), CliError> {
    let list: Vec<f64> = numbers(name, value)?;
    p.targets = list.into_iter().map(make).collect();
    set_target(&mut p.target, p.targets[0])
}

/// A count list: whole numbers only.
fn count_targets(
    p: &mut Pending,
    name: &str,
    value: &str,
    make: fn(usize) -> Target,
) -> Result<(), CliError> {
    let list: Vec<usize> = numbers(name, value)?;
    p.targets = list.into_iter().map(make).collect();
    set_target(&mut p.target, p.targets[0])
}

fn percent(p: &mut Pending, name: &str, value: &str) -> Result<(), CliError> {
    let list: Vec<f64> = numbers(name, value)?;
    if let Some(bad) = list.iter().find(|v| !(0.0..=100.0).contains(*v)) {
        return Err(CliError(format!(
            "{name}: the percentage must be between 0 and 100, got {bad}"
        )));
    }
    targets(p, name, value, Target::RemovePercent)
}

/// Degrees between 0 and 180.
fn degrees<T>(name: &str, value: &str) -> Result<T, CliError>
where
    T: std::str::FromStr + PartialOrd + From<u8> + std::fmt::Display,
{
    let a: T = number(name, value)?;
    if !(T::from(0)..=T::from(180)).contains(&a) {
        return Err(CliError(format!(
            "{name}: expected degrees between 0 and 180, got {a}"
        )));
    }
    Ok(a)
}

fn algorithm(p: &mut Pending, name: &str, value: &str) -> Result<(), CliError> {
    p.algorithm = Some(match value {
        "schroeder" => Algorithm::Schroeder,
        "qem" => Algorithm::Qem,
        other => {
            return Err(CliError(format!(
                "{name}: unknown algorithm '{other}' (expected schroeder or qem)"
            )))
        }
    });
    Ok(())
}

fn cost(p: &mut Pending, name: &str, value: &str) -> Result<(), CliError> {
    p.params.cost = match value {
        "quadric" => Cost::Quadric,
        "lt" => Cost::LindstromTurk,
        other => {
            return Err(CliError(format!(
                "{name}: unknown cost '{other}' (expected quadric or lt)"
            )))
        }
    };
    Ok(())
}

fn viewports(p: &mut Pending, name: &str, value: &str) -> Result<(), CliError> {
    let n: u32 = number(name, value)?;
    if !(1..=4).contains(&n) {
        return Err(CliError(format!("--viewports: expected 1 to 4, got {n}")));
    }
    p.viewports = Some(n);
    Ok(())
}

fn tiles(p: &mut Pending, name: &str, value: &str) -> Result<(), CliError> {
    p.tiles = Some(if value == "auto" {
        Tiles::Auto
    } else {
        Tiles::Count(positive(name, value)?)
    });
    Ok(())
}

fn msaa(p: &mut Pending, name: &str, value: &str) -> Result<(), CliError> {
    let n: u32 = number(name, value)?;
    if ![1, 2, 4, 8].contains(&n) {
        return Err(CliError(format!(
            "--msaa: expected 1 (off), 2, 4 or 8 samples per pixel, got {n}"
        )));
    }
    p.shot.msaa = n;
    Ok(())
}

fn image_size(p: &mut Pending, _: &str, value: &str) -> Result<(), CliError> {
    (p.shot.width, p.shot.height) = size(value)?;
    Ok(())
}

/// The rows, in usage order.
static OPTIONS: &[OptionSpec] = &[
    OptionSpec {
        names: &["-h", "--help"],
        shown: Some("-h, --help"),
        help: &["prints this message"],
        section: Section::General,
        apply: Apply::Stop(Early::Help),
    },
    OptionSpec {
        names: &["--version", "-V"],
        shown: Some("--version"),
        help: &["prints the version"],
        section: Section::General,
        apply: Apply::Stop(Early::Version),
    },
    OptionSpec {
        names: &[],
        shown: Some("filename"),
        help: &[
            "the VRML 1.0 / VRML 2.0 / Open Inventor ASCII file to open",
            "(gzipped too; PLY, OBJ, STL, OFF and glTF are also read,",
            "the extension or the first bytes pick the format)",
        ],
        section: Section::General,
        apply: Apply::Text,
    },
    OptionSpec {
        names: &[],
        shown: Some("action"),
        help: &["gui (DEFAULT) | nogui | shot"],
        section: Section::General,
        apply: Apply::Text,
    },
    OptionSpec {
        names: &["-o", "--output"],
        shown: Some("-o filename"),
        help: &[
            "the file to save as; the extension picks the format: .wrl",
            "(VRML 2.0), .ply, .obj, .stl, .off, .gltf, .glb (DEFAULT:",
            "out.wrl); .obj writes its materials to a .mtl of the same",
            "name, .gltf its buffer to a .bin",
        ],
        section: Section::NoGui,
        apply: Apply::Value(|p, _, v| {
            p.output = Some(PathBuf::from(v));
            Ok(())
        }),
    },
    OptionSpec {
        names: &["-a", "--algorithm"],
        shown: Some("-a, --algorithm A"),
        help: &[
            "schroeder (DEFAULT: vertex removal, vertices never move) |",
            "qem (quadric edge collapse, vertices move)",
        ],
        section: Section::NoGui,
        apply: Apply::Value(algorithm),
    },
    OptionSpec {
        names: &["--cost"],
        shown: Some("--cost C"),
        help: &["qem: quadric (DEFAULT) | lt (Lindström–Turk: volume and boundary kept)"],
        section: Section::NoGui,
        apply: Apply::Value(cost),
    },
    OptionSpec {
        names: &["-p", "--percent"],
        shown: Some("-p number"),
        help: &["percent of the vertices to remove (100: as far as possible)"],
        section: Section::NoGui,
        apply: Apply::Value(percent),
    },
    OptionSpec {
        names: &["-v", "--vertices"],
        shown: Some("-v number"),
        help: &["number of vertices to remove"],
        section: Section::NoGui,
        apply: Apply::Value(|p, n, v| count_targets(p, n, v, Target::RemoveVertices)),
    },
    OptionSpec {
        names: &["--keep-vertices"],
        shown: Some("--keep-vertices N"),
        help: &["stop when N vertices are left"],
        section: Section::NoGui,
        apply: Apply::Value(|p, n, v| count_targets(p, n, v, Target::KeepVertices)),
    },
    OptionSpec {
        names: &["--keep-triangles"],
        shown: Some("--keep-triangles N"),
        help: &["stop when N triangles are left"],
        section: Section::NoGui,
        apply: Apply::Value(|p, n, v| count_targets(p, n, v, Target::KeepTriangles)),
    },
    OptionSpec {
        names: &["--max-error"],
        shown: Some("--max-error E[%]"),
        help: &[
            "keep the output within E model units of the input (or E percent of",
            "the bounding-box diagonal): metro's Hausdorff distance, the larger of",
            "input->output and output->input, stays at most E (both algorithms)",
        ],
        section: Section::NoGui,
        apply: Apply::Value(|p, _, v| {
            p.params.max_error = Some(error_bound(v)?);
            Ok(())
        }),
    },
    OptionSpec {
        names: &["--feature-angle"],
        shown: Some("--feature-angle DEG"),
        help: &[
            "dihedral angle that makes an edge a feature edge (DEFAULT: 30);",
            "raised in 15-degree steps when a count target cannot be met",
            "otherwise or corners would crowd it (not -p 100, --max-error)",
        ],
        section: Section::NoGui,
        apply: Apply::Value(|p, n, v| {
            p.params.feature_angle_deg = degrees(n, v)?;
            Ok(())
        }),
    },
    OptionSpec {
        names: &["--keep-features"],
        shown: Some("--keep-features"),
        help: &["never raise the feature angle: stop short of the target instead"],
        section: Section::NoGui,
        apply: Apply::Flag(|p| p.params.keep_features = true),
    },
    OptionSpec {
        names: &["--keep-border"],
        shown: Some("--keep-border"),
        help: &[
            "never move or remove a vertex on the open border (edges of one",
            "triangle): pieces of one mesh decimated apart still fit together",
        ],
        section: Section::NoGui,
        apply: Apply::Flag(|p| p.params.keep_border = true),
    },
    OptionSpec {
        names: &["--no-weld"],
        shown: Some("--no-weld"),
        help: &["do not merge coincident vertices before decimating"],
        section: Section::NoGui,
        apply: Apply::Flag(|p| p.no_weld = true),
    },
    OptionSpec {
        names: &["--weld-tolerance"],
        shown: Some("--weld-tolerance E[%]"),
        help: &[
            "also merge vertices closer than E model units (or E percent of",
            "the model's bounding-box diagonal) before decimating (DEFAULT: off)",
        ],
        section: Section::NoGui,
        apply: Apply::Value(|p, _, v| {
            p.weld_tolerance = Some(tolerance(v)?);
            Ok(())
        }),
    },
    OptionSpec {
        names: &["--progressive"],
        shown: Some("--progressive FILE"),
        help: &[
            "also write the collapses as vertex splits (FILE.pm), to rebuild",
            "any level between the result and the input (implies -a qem);",
            "with FILE.pm as the input, nogui rebuilds the level the target",
            "asks for (never below the base) instead of decimating",
        ],
        section: Section::NoGui,
        apply: Apply::Value(|p, _, v| {
            p.progressive = Some(PathBuf::from(v));
            Ok(())
        }),
    },
    OptionSpec {
        names: &["--overwrite"],
        shown: Some("--overwrite"),
        help: &["allow -o or --progressive to name an input file"],
        section: Section::NoGui,
        apply: Apply::Flag(|p| p.overwrite = true),
    },
    OptionSpec {
        names: &["-q", "--quiet"],
        shown: Some("-q, --quiet"),
        help: &[
            "no summary, progress or warnings on stderr, except warnings",
            "that say part of the input is not read or of the result not",
            "written",
        ],
        section: Section::NoGui,
        apply: Apply::Flag(|p| p.quiet = true),
    },
    OptionSpec {
        names: &["--lenient"],
        shown: Some("--lenient"),
        help: &[
            "read a VRML / Inventor node's unknown fields as a warning (the",
            "value skipped) rather than an error",
        ],
        section: Section::NoGui,
        apply: Apply::Flag(|p| p.lenient = true),
    },
    OptionSpec {
        names: &["--threads"],
        shown: Some("--threads N"),
        help: &[
            "decimate on N threads, this one included; 1: no other thread",
            "(DEFAULT: RAYON_NUM_THREADS, else one per core); the result is",
            "the same for every N",
        ],
        section: Section::NoGui,
        apply: Apply::Value(|p, n, v| {
            p.threads = Some(positive(n, v)?);
            Ok(())
        }),
    },
    OptionSpec {
        names: &[],
        shown: Some("-o filename"),
        help: &["the PNG to write (DEFAULT: shot.png)"],
        section: Section::Shot,
        apply: Apply::Text,
    },
    OptionSpec {
        names: &["--size"],
        shown: Some("--size WxH"),
        help: &["image size (DEFAULT: 800x600)"],
        section: Section::Shot,
        apply: Apply::Value(image_size),
    },
    OptionSpec {
        names: &["--background"],
        shown: Some("--background R,G,B"),
        help: &["the viewports' colour, each 0-255, or #rrggbb"],
        section: Section::Shot,
        apply: Apply::Value(|p, n, v| {
            p.shot.background = Some(colour(n, v)?);
            Ok(())
        }),
    },
    OptionSpec {
        names: &["--viewports"],
        shown: Some("--viewports N"),
        help: &["1-4 viewports: the original, then the decimated scene"],
        section: Section::Shot,
        apply: Apply::Value(viewports),
    },
    OptionSpec {
        names: &["--mode"],
        shown: Some("--mode LIST"),
        help: &[
            "comma-separated: triangles,edges,points,normals,vertex-normals,",
            "flat,unlit,untextured,error (DEFAULT: triangles)",
        ],
        section: Section::Shot,
        apply: Apply::Value(|p, _, v| {
            p.shot.modes = draw_modes(v)?;
            Ok(())
        }),
    },
    OptionSpec {
        names: &["--msaa"],
        shown: Some("--msaa N"),
        help: &["anti-aliasing: 1 (off), 2, 4 or 8 samples per pixel (DEFAULT: 4)"],
        section: Section::Shot,
        apply: Apply::Value(msaa),
    },
    OptionSpec {
        names: &["--crease-angle"],
        shown: Some("--crease-angle DEG"),
        help: &[
            "smooth shading keeps edges whose faces meet at more than DEG",
            "sharp (DEFAULT: the file's creaseAngle, else 45; 180: smooth)",
        ],
        section: Section::Shot,
        apply: Apply::Value(|p, n, v| {
            p.crease_angle = Some(degrees(n, v)?);
            Ok(())
        }),
    },
    OptionSpec {
        names: &["--labels"],
        shown: Some("--labels, --no-labels"),
        help: &[
            "a caption on each viewport: what it shows, its counts",
            "(DEFAULT: on with more than one viewport)",
        ],
        section: Section::Shot,
        apply: Apply::Flag(|p| p.shot.labels = Some(true)),
    },
    OptionSpec {
        names: &["--no-labels"],
        shown: None,
        help: &[],
        section: Section::Shot,
        apply: Apply::Flag(|p| p.shot.labels = Some(false)),
    },
    OptionSpec {
        names: &["--measure"],
        shown: Some("--measure"),
        help: &[
            "add metro's error against the original (mean, max, % of the",
            "diagonal) to each decimated viewport's caption",
        ],
        section: Section::Shot,
        apply: Apply::Flag(|p| p.shot.measure = true),
    },
    OptionSpec {
        names: &[],
        shown: Some("-p / -v / ..."),
        help: &[
            "decimation target, as for nogui; a list such as -p 60,80,90",
            "gives each decimated viewport its own (and --viewports 4)",
        ],
        section: Section::Shot,
        apply: Apply::Text,
    },
    OptionSpec {
        names: &["--tiles"],
        shown: Some("--tiles auto|N"),
        help: &[
            "decimate in N spatial tiles (auto: sized by --memory), as many",
            "at once as --memory allows, borders locked, then weld them and",
            "decimate the seams again; PLY, STL, OBJ or OFF, -p or --keep-triangles",
        ],
        section: Section::Tiles,
        apply: Apply::Value(tiles),
    },
    OptionSpec {
        names: &["--memory"],
        shown: Some("--memory SIZE"),
        help: &[
            "what a tiled run may use, e.g. 2G or 512M (DEFAULT: a",
            "quarter of the machine's RAM)",
        ],
        section: Section::Tiles,
        apply: Apply::Value(|p, n, v| {
            p.memory = Some(bytes(n, v)?);
            Ok(())
        }),
    },
];

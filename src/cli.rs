//! Command-line parsing: the original program's usage (`algo filename [action]
//! [action-options]`), kept word for word where it can be, plus what ours adds.
//!
//! Hand-written rather than clap-derived because the original's shape — a file, then an
//! optional positional action whose options follow it — is its users' habit and the usage
//! text is part of the product.

use std::path::PathBuf;

use crate::decimate::{Algorithm, ErrorBound, Params, Target};

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

/// Draw modes a `shot` can ask for (`--mode edges,points,...`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShotModes {
    pub triangles: bool,
    pub edges: bool,
    pub points: bool,
    pub face_normals: bool,
    pub vertex_normals: bool,
    pub flat: bool,
    pub unlit: bool,
    /// Textured models in their material colour instead (`--mode untextured`).
    pub untextured: bool,
}

impl Default for ShotModes {
    fn default() -> Self {
        Self {
            triangles: true,
            edges: false,
            points: false,
            face_normals: false,
            vertex_normals: false,
            flat: false,
            unlit: false,
            untextured: false,
        }
    }
}

/// Options of the `shot` action.
#[derive(Debug, Clone, PartialEq)]
pub struct ShotOptions {
    pub width: u32,
    pub height: u32,
    /// 1–4 viewports: the first shows the original, the others the decimated scene.
    pub viewports: u32,
    pub modes: ShotModes,
    /// Where relative texture names are read from: the input file's folder.
    pub texture_dir: PathBuf,
}

impl Default for ShotOptions {
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            viewports: 1,
            modes: ShotModes::default(),
            texture_dir: PathBuf::from("."),
        }
    }
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
    /// Allow `-o` (and `--progressive`) to name the input file.
    pub overwrite: bool,
    /// `--progressive`: also write the collapses as vertex splits to this file (nogui; the
    /// algorithm is then quadric edge collapse).
    pub progressive: Option<PathBuf>,
    /// No summary or progress on stderr.
    pub quiet: bool,
    pub shot: ShotOptions,
}

/// What the command line asks for.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    Run(Box<Args>),
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
                        otherwise (never for -p 100 or --max-error alone)
  --keep-features       never raise the feature angle: stop short of the target instead
  --keep-border         never move or remove a vertex on the open border (edges of one
                        triangle): pieces of one mesh decimated apart still fit together
  --no-weld             do not merge coincident vertices before decimating
  --progressive FILE    also write the collapses as vertex splits (FILE.pm), to rebuild
                        any level between the result and the input (implies -a qem);
                        with FILE.pm as the input, nogui rebuilds the level the target
                        asks for (never below the base) instead of decimating
  --overwrite           allow -o or --progressive to name an input file
  -q, --quiet           no summary or progress on stderr

action-options for shot (offscreen render to PNG, no window):
  -o filename           the PNG to write (DEFAULT: shot.png)
  --size WxH            image size (DEFAULT: 800x600)
  --viewports N         1-4 viewports: the original, then the decimated scene
  --mode LIST           comma-separated: triangles,edges,points,normals,vertex-normals,
                        flat,unlit,untextured (DEFAULT: triangles)
  -p / -v / ...         decimation target, as for nogui

typical usage:           decimate model.wrl
typical usage for nogui: decimate model.wrl nogui -p 100 -o output.wrl
";

/// Parses the arguments after the program name.
pub fn parse<I, S>(args: I) -> Result<Command, CliError>
where
    I: IntoIterator<Item = S>,
    S: Into<String>,
{
    let mut it = args.into_iter().map(Into::into);
    let mut input: Option<PathBuf> = None;
    let mut action: Option<Action> = None;
    let mut output: Option<PathBuf> = None;
    let mut params = Params::default();
    let mut algorithm: Option<Algorithm> = None;
    let mut progressive: Option<PathBuf> = None;
    let mut target: Option<Target> = None;
    let mut weld = true;
    let mut overwrite = false;
    let mut quiet = false;
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
                let p: f64 = number(&arg, &value(&arg)?)?;
                if !(0.0..=100.0).contains(&p) {
                    return Err(CliError(format!(
                        "{arg}: the percentage must be between 0 and 100, got {p}"
                    )));
                }
                set_target(&mut target, Target::RemovePercent(p))?;
            }
            "-v" | "--vertices" => {
                let n = number(&arg, &value(&arg)?)?;
                set_target(&mut target, Target::RemoveVertices(n))?;
            }
            "--keep-vertices" => {
                let n = number(&arg, &value(&arg)?)?;
                set_target(&mut target, Target::KeepVertices(n))?;
            }
            "--keep-triangles" => {
                let n = number(&arg, &value(&arg)?)?;
                set_target(&mut target, Target::KeepTriangles(n))?;
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
            "--keep-features" => params.keep_features = true,
            "--keep-border" => params.keep_border = true,
            "--overwrite" => overwrite = true,
            "-q" | "--quiet" => quiet = true,
            "--size" => {
                let (w, h) = size(&value(&arg)?)?;
                shot.width = w;
                shot.height = h;
            }
            "--viewports" => {
                let n: u32 = number(&arg, &value(&arg)?)?;
                if !(1..=4).contains(&n) {
                    return Err(CliError(format!("--viewports: expected 1 to 4, got {n}")));
                }
                shot.viewports = n;
            }
            "--mode" => shot.modes = modes(&value(&arg)?)?,
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
    shot.texture_dir = crate::io::texture_path::folder_of(&input).to_path_buf();
    Ok(Command::Run(Box::new(Args {
        input,
        action,
        output,
        params,
        target_given,
        weld,
        overwrite,
        progressive,
        quiet,
        shot,
    })))
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

fn modes(s: &str) -> Result<ShotModes, CliError> {
    let mut m = ShotModes {
        triangles: false,
        ..ShotModes::default()
    };
    for word in s.split(',').map(str::trim).filter(|w| !w.is_empty()) {
        match word {
            "triangles" | "solid" => m.triangles = true,
            "edges" => m.edges = true,
            "points" => m.points = true,
            "normals" => m.face_normals = true,
            "vertex-normals" => m.vertex_normals = true,
            "flat" => m.flat = true,
            "unlit" => m.unlit = true,
            "untextured" => m.untextured = true,
            other => {
                return Err(CliError(format!(
                    "--mode: unknown mode '{other}' (expected triangles, edges, points, \
                     normals, vertex-normals, flat, unlit, untextured)"
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
        assert!(a.shot.modes.edges && a.shot.modes.flat && !a.shot.modes.triangles);
        assert_eq!(a.output, PathBuf::from("shot.png"));
        assert!(parse(["m.wrl", "shot", "--viewports", "5"]).is_err());
        assert!(parse(["m.wrl", "shot", "--size", "0x10"]).is_err());
    }
}

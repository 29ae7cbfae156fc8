//! `metro A B`: the geometric error between two surfaces, after Cignoni, Rocchini and
//! Scopigno, "Metro: measuring error on simplified surfaces", Computer Graphics Forum 17(2),
//! 1998.
//!
//! Owns the command line only: argument parsing, reading both files with the project's readers,
//! and printing `decimate_core::metro`'s report. Exit status: 0 measured, 1 a file could not be read
//! or has nothing to measure, 2 bad usage.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use decimate_core::metro::{self, report, Options, Surface};

const USAGE: &str = "\
usage: metro [options] A B

Measures the distance between the surfaces in files A and B (any format decimate reads):
A->B (samples of A against surface B), B->A, and the Hausdorff distance (the larger max).
Max is over vertex, edge and face samples; mean and RMS are area-weighted. Relative values
are fractions of A's bounding-box diagonal. Also prints each surface's areas, connected
pieces, boundary and non-manifold edges and, for closed surfaces, volumes.

options:
  -n, --samples N   face samples per direction (default: 10 per triangle, at least 10000);
                    edge samples are a tenth of this, and every vertex is sampled too
  -s, --seed S      seed of the sample placement (default 1); same seed, same numbers
      --folds       also count B's triangles folded over A (A the input, B the output): a
                    triangle whose normal turns more than 90° from the part of A it stands
                    for; triangles with no normal are counted apart as degenerate
      --fold-reach R
                    a fold sample inside a thin part of A whose nearest side faces away
                    stands for the other side if that faces like it within (1 + R) times
                    the nearest distance (default 1)
  -j, --threads N   worker threads (default: all cores)
      --json        print JSON instead of a table
  -h, --help        this text
";

struct Args {
    files: Vec<String>,
    options: Options,
    threads: Option<usize>,
    json: bool,
}

fn parse(args: &[String]) -> Result<Option<Args>, String> {
    let mut parsed = Args {
        files: Vec::new(),
        options: Options::default(),
        threads: None,
        json: false,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| format!("{name} needs a value"))
                .cloned()
        };
        match arg.as_str() {
            "-h" | "--help" => return Ok(None),
            "--json" => parsed.json = true,
            "-n" | "--samples" => {
                let v = value(arg)?;
                parsed.options.samples = Some(number(&v, arg)?);
            }
            "-s" | "--seed" => {
                let v = value(arg)?;
                parsed.options.seed = v
                    .parse()
                    .map_err(|_| format!("{arg}: '{v}' is not a whole number"))?;
            }
            "--folds" => parsed.options.folds = true,
            "--fold-reach" => {
                let v = value(arg)?;
                parsed.options.fold_reach = match v.parse::<f64>() {
                    Ok(r) if r.is_finite() && r >= 0.0 => r,
                    _ => return Err(format!("{arg}: '{v}' is not a number of at least 0")),
                };
            }
            "-j" | "--threads" => {
                let v = value(arg)?;
                parsed.threads = Some(number(&v, arg)?);
            }
            s if s.starts_with('-') && s.len() > 1 => return Err(format!("unknown option {s}")),
            _ => parsed.files.push(arg.clone()),
        }
    }
    if parsed.files.len() != 2 {
        return Err(format!("expected two files, got {}", parsed.files.len()));
    }
    Ok(Some(parsed))
}

fn number(v: &str, name: &str) -> Result<usize, String> {
    match v.parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err(format!("{name}: '{v}' is not a positive whole number")),
    }
}

fn read(path: &str) -> Result<Surface, String> {
    let outcome = decimate_core::io::read_scene(Path::new(path)).map_err(|e| e.to_string())?;
    for w in decimate_core::io::warning::grouped(&outcome.warnings) {
        eprintln!("metro: {path}: warning: {w}");
    }
    let surface = Surface::from_scene(&outcome.scene);
    if surface.triangles.is_empty() {
        return Err(format!("{path}: no triangles to measure"));
    }
    Ok(surface)
}

/// The mesh arrays on huge pages (see `decimate_core::alloc`).
#[global_allocator]
static ALLOCATOR: decimate_core::alloc::HugePages = decimate_core::alloc::HugePages;

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let args = match parse(&argv) {
        Ok(Some(a)) => a,
        Ok(None) => {
            print!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("metro: {e}\n\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    if let Some(n) = args.threads {
        // Only fails if a pool already exists, which cannot happen this early.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global();
    }
    let start = Instant::now();
    let (a, b) = rayon::join(|| read(&args.files[0]), || read(&args.files[1]));
    let (a, b) = match (a, b) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("metro: {e}");
            return ExitCode::from(1);
        }
    };
    let t_read = start.elapsed().as_secs_f64();
    let comparison = match metro::compare(&a, &b, &args.options) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("metro: {e}");
            return ExitCode::from(1);
        }
    };
    let names = [args.files[0].as_str(), args.files[1].as_str()];
    if args.json {
        print!("{}", report::json(&comparison, names));
    } else {
        print!("{}", report::table(&comparison, names));
    }
    let t = comparison.timings;
    eprintln!(
        "metro: {:.3} s (read {:.3}, hierarchies {:.3}, A->B {:.3}, B->A {:.3}, folds {:.3}) on {} \
         threads",
        start.elapsed().as_secs_f64(),
        t_read,
        t.bvh,
        t.a_to_b,
        t.b_to_a,
        t.folds,
        rayon::current_num_threads()
    );
    ExitCode::SUCCESS
}

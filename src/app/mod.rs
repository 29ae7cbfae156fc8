//! The viewer side of the program: the `shot` action (offscreen picture) and the interactive
//! viewer, both over `render`. `run` is what `main` calls for the `gui` and `shot` actions.

pub mod controller;
pub mod menu;
pub mod shot;
pub mod viewport;

use std::process::ExitCode;

use crate::cli::{Action, Args};
use crate::mesh::Scene;

/// Runs the `gui` or `shot` action on an already built scene.
pub fn run(scene: Scene, args: &Args) -> ExitCode {
    match args.action {
        Action::Shot => run_shot(&scene, args),
        Action::Gui | Action::NoGui => {
            eprintln!("decimate: the interactive viewer is not built yet; use nogui or shot");
            ExitCode::from(2)
        }
    }
}

fn run_shot(scene: &Scene, args: &Args) -> ExitCode {
    let params = args.target_given.then_some(&args.params);
    let (image, report) = match shot::render(scene, &args.shot, params, Default::default()) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("decimate: cannot render: {e}");
            return ExitCode::FAILURE;
        }
    };
    if let (Some(report), false) = (report, args.quiet) {
        eprint!("{}", crate::batch::summary(&report));
    }
    if let Err(e) = shot::write_png(&image, &args.output) {
        eprintln!("decimate: cannot write {e}");
        return ExitCode::FAILURE;
    }
    if !args.quiet {
        eprintln!("wrote {}", args.output.display());
    }
    ExitCode::SUCCESS
}

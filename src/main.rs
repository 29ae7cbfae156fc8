//! `decimate`: start-up in the original program's six steps — (1) parameter check, (2) parse
//! the scene file, (3) build the models, then for the viewer (4) build the menus, (5) register
//! the callbacks and (6) enter the main loop; `nogui` decimates and writes instead.

use std::process::ExitCode;

use decimate::cli::{self, Action, Command};
use decimate::{batch, tile_command, viewer_start};
use decimate_core::{io, mesh};

/// The mesh arrays on huge pages (see `decimate_core::alloc`).
#[global_allocator]
static ALLOCATOR: decimate_core::alloc::HugePages = decimate_core::alloc::HugePages;

fn main() -> ExitCode {
    decimate_core::alloc::return_large_blocks();
    // (1) Parameter check.
    let args = match cli::parse(std::env::args().skip(1)) {
        Ok(Command::Run(args)) => args,
        Ok(Command::Tile(step)) => return tile_command::run_step(&step),
        Ok(Command::Help) => {
            print!("{}", cli::usage());
            return ExitCode::SUCCESS;
        }
        Ok(Command::Version) => {
            println!("decimate {}", env!("CARGO_PKG_VERSION"));
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("decimate: {e}\n\n{}", cli::usage());
            return ExitCode::from(2);
        }
    };

    // Before anything runs in parallel (the weld below): the pool of `--threads`.
    decimate_core::threads::join_pool_of(args.threads);

    // Tiled: the input is streamed, never read whole.
    if args.tiles.is_some() {
        return tile_command::nogui_tiled(&args);
    }

    // (2) Parse the VRML / Open Inventor file.
    let Some(outcome) = parse_scene(&args) else {
        return ExitCode::FAILURE;
    };

    // (3) Build the models: weld duplicated vertices, fill in what the file lacks.
    let options = mesh::build::BuildOptions {
        weld: args.weld,
        weld_tolerance: args.weld_tolerance,
    };
    let (scene, repairs) = mesh::build::build_scene_with(outcome.scene, &options);
    if !args.quiet {
        if let Some(line) = repairs.summary() {
            eprint!("{line}");
        }
    }

    match args.action {
        Action::NoGui => batch::run(
            scene,
            outcome.progressive,
            &outcome.material_libraries,
            &args,
        ),
        // (4) menus, (5) callbacks, (6) main loop: the viewer.
        Action::Gui | Action::Shot => viewer_start::run(scene, &args),
    }
}

/// Step (2): the scene file read, its warnings printed grouped by kind (`-q` keeps those
/// that say data was lost); `None`, with the reason printed, when it gives no triangle.
fn parse_scene(args: &cli::Args) -> Option<io::ReadOutcome> {
    let options = io::ReadOptions {
        lenient: args.lenient,
    };
    let outcome = match io::read_scene_with(&args.input, options) {
        Ok(outcome) => outcome,
        Err(e) => {
            eprintln!("decimate: {e}");
            return None;
        }
    };
    for w in io::warning::grouped(&outcome.warnings) {
        if !args.quiet || w.loses_data() {
            eprintln!("decimate: warning: {w}");
        }
    }
    if outcome.scene.triangle_count() == 0 {
        eprintln!(
            "decimate: {}: no triangles: the file has no shape this program reads{}",
            args.input.display(),
            if outcome.warnings.is_empty() {
                ""
            } else {
                " (see the warnings above)"
            }
        );
        return None;
    }
    Some(outcome)
}

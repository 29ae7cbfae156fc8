//! Steps (4) to (6) of the original program's start-up for the `gui` action — build the
//! menus, register the callbacks, enter the main loop — and the `shot` action, both handed to
//! `decimate-viewer` with the options the command line parsed.

use std::process::ExitCode;

use crate::cli::{Action, Args};
use decimate_core::mesh::Scene;
use decimate_viewer::app::{controller, glut, menu, shot, viewer};

/// Runs the `gui` or `shot` action on an already built scene.
pub fn run(mut scene: Scene, args: &Args) -> ExitCode {
    decimate_core::threads::join_pool();
    if let Some(degrees) = args.crease_angle {
        for m in &mut scene.models {
            m.crease_angle = Some(degrees.to_radians());
        }
    }
    match args.action {
        Action::Shot => run_shot(&scene, args),
        Action::Gui | Action::NoGui => run_gui(scene, args),
    }
}

/// The viewer: steps (4) to (6) of the original's start-up.
fn run_gui(scene: Scene, args: &Args) -> ExitCode {
    if !args.quiet {
        // One line, not the ~100 of the usage: the window's own help has the keys.
        eprintln!("decimate: h shows the keys, the right mouse button the menu, q quits");
    }
    // (4) Build the popup menu: one list of entries, shared by the popup and the keyboard.
    let entries = menu::menu();
    // (5) Register the callbacks: the viewer answers display, reshape, keyboard, mouse and
    // motion events for the viewports the controller owns.
    let mut controller = controller::ViewportController::new(scene, args.params, 1024, 720);
    controller.input_dir = decimate_core::io::texture_path::folder_of(&args.input).to_path_buf();
    controller.inputs = vec![args.input.clone()];
    controller.set_draw_options(args.shot.modes);
    controller.msaa = args.shot.msaa;
    let mut viewer = viewer::Viewer::new(controller, entries);
    // (6) Hand control to the main loop.
    // ASCII only: a window manager reading the Latin-1 title property shows no mojibake.
    let title = format!("decimate - {}", args.input.display());
    match glut::main_loop(&title, &mut viewer) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("decimate: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run_shot(scene: &Scene, args: &Args) -> ExitCode {
    let params = args.target_given.then_some(&args.params);
    let rendered = shot::render_measured(scene, &args.shot, params, Default::default());
    let (image, report, measured) = match rendered {
        Ok(r) => r,
        Err(e) => {
            eprintln!("decimate: cannot render: {e}");
            return ExitCode::FAILURE;
        }
    };
    if !args.quiet {
        // Each copy's summary, then (when measured) the distance its caption and the
        // heat-map legend show: metro's, not the decimator's own bound in the summary.
        for (report, measured) in report.iter().zip(&measured) {
            eprint!("{}", report.summary());
            match measured {
                Ok(Some(error)) => eprintln!("{}", error.words()),
                Ok(None) => {}
                Err(e) => eprintln!("cannot measure: {e}"),
            }
        }
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

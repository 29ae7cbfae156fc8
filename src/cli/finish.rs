//! From the options to a command: the defaults that depend on the action, and the checks
//! that need several options at once (a target for nogui, options of the wrong action, a
//! list of targets against the viewports).

use std::path::PathBuf;

use super::options::Pending;
use super::{Action, Args, CliError};
use decimate_core::decimate::{Algorithm, Params, Target};
use decimate_viewer::app::shot::ShotOptions;

/// The command line the options make, once every check passes.
pub(super) fn finish(mut p: Pending) -> Result<Args, CliError> {
    let input = p
        .input
        .take()
        .ok_or_else(|| CliError("no filename given".into()))?;
    let action = p.action.unwrap_or(Action::Gui);
    if p.target.is_none() && p.params.max_error.is_some() {
        p.target = Some(Target::ErrorOnly);
    }
    if action == Action::NoGui && p.target.is_none() {
        return Err(CliError(
            "nogui needs a target: one of -p, -v, --keep-vertices, --keep-triangles, --max-error"
                .into(),
        ));
    }
    p.params.algorithm = resolve_algorithm(p.algorithm, p.progressive.is_some())?;
    let target_given = p.target.is_some();
    if let Some(t) = p.target {
        p.params.target = t;
    }
    let output = p.output.take().unwrap_or_else(|| match action {
        Action::Shot => PathBuf::from("shot.png"),
        _ => PathBuf::from("out.wrl"),
    });
    check_action_options(&p, action, &output)?;
    p.shot.texture_dir = decimate_core::io::texture_path::folder_of(&input).to_path_buf();
    let targets = std::mem::take(&mut p.targets);
    shot_targets(&mut p.shot, targets, p.viewports, action)?;
    check_measure(&p.shot, action, target_given)?;
    Ok(Args {
        input,
        action,
        output,
        params: p.params,
        target_given,
        weld: !p.no_weld,
        weld_tolerance: p.weld_tolerance,
        overwrite: p.overwrite,
        progressive: p.progressive,
        quiet: p.quiet,
        crease_angle: p.crease_angle,
        lenient: p.lenient,
        shot: p.shot,
        tiles: p.tiles,
        memory: p.memory,
        threads: p.threads,
    })
}

/// Options given to an action they do not belong to, and a nogui output no writer knows.
fn check_action_options(
    p: &Pending,
    action: Action,
    output: &std::path::Path,
) -> Result<(), CliError> {
    if let Some(pm) = &p.progressive {
        check_progressive(pm, action, output)?;
    }
    if p.tiles.is_some() || p.memory.is_some() {
        check_tiles(
            action,
            &p.params,
            p.progressive.is_some(),
            p.tiles.is_some(),
        )?;
    }
    if action == Action::NoGui && decimate_core::io::Format::from_path(output).is_none() {
        return Err(CliError(format!(
            "-o {}: no writer knows this extension (expected .wrl, .vrml, .ply, .obj, .stl, \
             .off, .gltf or .glb)",
            output.display()
        )));
    }
    if p.crease_angle.is_some() && action == Action::NoGui {
        return Err(CliError(
            "--crease-angle is an option of the viewer and shot (shading only)".into(),
        ));
    }
    Ok(())
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

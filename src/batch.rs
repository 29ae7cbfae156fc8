//! The `nogui` action: decimate the scene to the command line's target, print a summary
//! (and a progress bar on long runs) on stderr, and write the result in the format the
//! output's extension names (VRML 2.0 by default; `io::write_scene`) — never over the input
//! unless `--overwrite` says so. With `--progressive FILE` the collapses are recorded too
//! (`simplify_scene_progressive`) and written to FILE as vertex splits (`io::progressive`).
//! When the input is such a file, nothing is decimated: each model's level that meets the
//! target is rebuilt from the base by its vertex splits (`decimate::levels`), exactly as the
//! recorded decimation left it at that count. Texture names are rebased from the input's
//! folder to the output's before writing (`io::rebase_textures`).

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use crate::cli::Args;
use decimate_core::decimate::levels::levels_for;
use decimate_core::decimate::summary::counts_column;
use decimate_core::decimate::{simplify_scene, simplify_scene_progressive, Report};
use decimate_core::io;
use decimate_core::mesh::progressive::{Lod, ProgressiveScene};
use decimate_core::mesh::Scene;
use decimate_core::progress_bar::Progress;

/// Runs the nogui job on `scene`, or on `recorded` when the input is a progressive mesh; the
/// exit code says whether the output was written. `material_libraries` are the input OBJ's
/// (`mtllib`, relative to its folder): an output's own MTL must not replace one of them.
pub fn run(
    mut scene: Scene,
    recorded: Option<ProgressiveScene>,
    material_libraries: &[String],
    args: &Args,
) -> ExitCode {
    decimate_core::threads::join_pool();
    let input_dir = io::texture_path::folder_of(&args.input);
    let inputs: Vec<PathBuf> = std::iter::once(args.input.clone())
        .chain(material_libraries.iter().map(|l| input_dir.join(l)))
        .collect();
    // The OBJ output's material library is written too (when the scene has materials).
    let mtl = (io::Format::from_path(&args.output) == Some(io::Format::Obj))
        .then(|| io::obj::mtl_path_for(&args.output));
    let outputs = std::iter::once(&args.output)
        .chain(&args.progressive)
        .chain(&mtl);
    for output in outputs {
        if !args.overwrite && inputs.iter().any(|input| same_file(input, output)) {
            eprintln!(
                "decimate: {}: refusing to write over an input file (add --overwrite to allow it)",
                output.display()
            );
            return ExitCode::from(2);
        }
    }
    if let Some(pm) = recorded {
        return rebuild_levels(&pm, args);
    }
    let (report, progressive) = decimate(&mut scene, args);
    if !args.quiet {
        eprint!("{}", report.summary());
    }
    if !write(&mut scene, args) {
        return ExitCode::FAILURE;
    }
    if let (Some(path), Some(pm)) = (&args.progressive, &progressive) {
        if let Err(e) = io::progressive_file::write_progressive(pm, path) {
            eprintln!("decimate: cannot write {e}");
            return ExitCode::FAILURE;
        }
        if !args.quiet {
            let splits: usize = pm.models.iter().map(|m| m.splits.len()).sum();
            let plural = if splits == 1 { "" } else { "s" };
            eprintln!("wrote {} ({splits} vertex split{plural})", path.display());
        }
    }
    ExitCode::SUCCESS
}

/// Writes each model of the progressive mesh `pm` at the level that meets the command line's
/// count target (never below its base).
fn rebuild_levels(pm: &ProgressiveScene, args: &Args) -> ExitCode {
    let input = args.input.display();
    let refuse = |why: String| {
        eprintln!("decimate: {input}: {why}");
        ExitCode::from(2)
    };
    if args.progressive.is_some() {
        return refuse("is already a progressive mesh: --progressive has nothing to record".into());
    }
    let levels = match levels_for(pm, args.params.target) {
        Some(levels) if args.params.max_error.is_none() => levels,
        _ => {
            return refuse(
                "a progressive mesh records no errors: --max-error cannot pick a level; give \
                 -p, -v, --keep-vertices or --keep-triangles"
                    .into(),
            )
        }
    };
    let start = Instant::now();
    let mut models = Vec::with_capacity(pm.models.len());
    let mut s = String::new();
    let (mut vb, mut tb, mut va, mut ta) = (0, 0, 0, 0);
    for (m, &level) in pm.models.iter().zip(&levels) {
        let mut lod = Lod::new(m);
        lod.set_level(level);
        let model = lod.model().clone();
        let (v, t) = (model.positions.len(), model.triangles.len());
        let (full_v, full_t) = (m.full_vertex_count(), m.full_face_count());
        let base = if level == 0 && !m.splits.is_empty() {
            "  (the base: the file holds no coarser level)"
        } else {
            ""
        };
        s += &counts_column(&m.base.name, (full_v, v), (full_t, t));
        s += &format!(" level {level} of {}{base}\n", m.splits.len());
        (vb, tb, va, ta) = (vb + full_v, tb + full_t, va + v, ta + t);
        models.push(model);
    }
    if !args.quiet {
        eprintln!(
            "{s}total: vertices {vb} -> {va}, triangles {tb} -> {ta}; rebuilt by vertex splits \
             in {:.3} s",
            start.elapsed().as_secs_f64()
        );
    }
    if write(&mut Scene { models }, args) {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// Writes `scene` to the output: texture names rebased for its folder, and a warning for
/// whatever its format cannot hold (`io::losses`). False (with the error printed) when the
/// file could not be written.
fn write(scene: &mut Scene, args: &Args) -> bool {
    rebase_textures(scene, args);
    // What the output cannot hold is lost data: said even under `-q`.
    for loss in io::losses::losses_at(scene, &args.output) {
        eprintln!("decimate: warning: {}: {loss}", args.output.display());
    }
    if let Err(e) = io::write_scene(scene, &args.output) {
        eprintln!("decimate: cannot write {e}");
        return false;
    }
    if !args.quiet {
        eprintln!("wrote {}", args.output.display());
    }
    true
}

/// Decimates `scene` to the command line's target, with a progress bar on a terminal;
/// records the progressive mesh when `--progressive` asks for it.
fn decimate(scene: &mut Scene, args: &Args) -> (Report, Option<ProgressiveScene>) {
    let bar = Progress::labelled(
        "decimating",
        false,
        !args.quiet && std::io::stderr().is_terminal(),
    );
    let mut update = |f| bar.set(f);
    let result = if args.progressive.is_some() {
        let (report, pm) = simplify_scene_progressive(scene, &args.params, &mut update);
        (report, Some(pm))
    } else {
        (simplify_scene(scene, &args.params, &mut update), None)
    };
    bar.finish();
    result
}

/// Re-expresses the scene's texture names, read relative to the input's folder, for the
/// output's folder, so that the written file still finds its images.
fn rebase_textures(scene: &mut Scene, args: &Args) {
    use io::texture_path::folder_of;
    io::rebase_textures(scene, folder_of(&args.input), folder_of(&args.output));
}

/// True when both paths name the same existing file.
fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

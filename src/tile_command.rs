//! The `decimate tile ...` steps and `nogui --tiles` as the command line runs them: messages
//! on stderr, exit status 0 on success, 1 when a file is at fault, 2 for a bad request.

use std::io::IsTerminal;
use std::process::ExitCode;

use crate::cli::{Args, TileCommand};
use decimate_core::progress_bar::Progress;
use decimate_core::tile::local::{run_local, work_dir_for};
use decimate_core::tile::schedule::{count_for, default_memory};
use decimate_core::tile::{cut, merge, run, TileError};

fn fail(e: &TileError) -> ExitCode {
    eprintln!("decimate: {e}");
    match e {
        TileError::Request(_) => ExitCode::from(2),
        _ => ExitCode::FAILURE,
    }
}

/// Runs one `decimate tile` step.
pub fn run_step(cmd: &TileCommand) -> ExitCode {
    decimate_core::threads::join_pool();
    match cmd {
        TileCommand::Plan {
            input,
            dir,
            count,
            target,
        } => match cut::plan(input, dir, *count, *target, &mut |s| eprintln!("{s}")) {
            Ok(m) => {
                println!(
                    "{} tiles planned in {} ({} triangles, target {})",
                    m.tiles.len(),
                    dir.display(),
                    m.triangles,
                    m.target_triangles
                );
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e),
        },
        TileCommand::Run { dir, index } => {
            let result = run::tile_index(*index).and_then(|i| Ok((i, run::run_tile(dir, i)?)));
            match result {
                Ok((i, r)) => {
                    println!("tile {i}: triangles {} -> {}", r.before, r.after);
                    ExitCode::SUCCESS
                }
                Err(e) => fail(&e),
            }
        }
        TileCommand::Status { dir } => match run::status(dir) {
            Ok(done) => {
                for (i, d) in done.iter().enumerate() {
                    println!("tile {i}: {}", if *d { "done" } else { "pending" });
                }
                let n = done.iter().filter(|d| **d).count();
                println!("{n} of {} tiles done", done.len());
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e),
        },
        TileCommand::Merge {
            dir,
            output,
            target,
            memory,
        } => match merge::merge(
            dir,
            output,
            *target,
            memory.unwrap_or_else(default_memory),
            &Progress::new(true, false),
            (0.0, 1.0),
        ) {
            Ok(r) => {
                let (before, after) = r.models.iter().fold((0, 0), |(b, a), m| {
                    (b + m.triangles_before, a + m.triangles_after)
                });
                println!(
                    "merged: triangles {before} -> {after}, written to {}",
                    output.display()
                );
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e),
        },
    }
}

/// `decimate IN nogui --tiles ...`: everything in one process, the work folder removed after.
pub fn nogui_tiled(args: &Args) -> ExitCode {
    decimate_core::threads::join_pool();
    if !args.overwrite && same_file(&args.input, &args.output) {
        eprintln!(
            "decimate: {}: refusing to write over an input file (add --overwrite to allow it)",
            args.output.display()
        );
        return ExitCode::from(2);
    }
    let Some(tiles) = args.tiles else {
        return ExitCode::from(2);
    };
    let memory = args.memory.unwrap_or_else(default_memory);
    let dir = work_dir_for(&args.output);
    let start = std::time::Instant::now();
    let progress = Progress::new(!args.quiet, !args.quiet && std::io::stderr().is_terminal());
    let result = run_local(
        &args.input,
        &args.output,
        &dir,
        count_for(tiles, memory),
        args.params.target,
        memory,
        &progress,
    );
    progress.finish();
    // The tiles are scratch: gone whether the run succeeded or not.
    let _ = std::fs::remove_dir_all(&dir);
    match result {
        Ok(r) => {
            if !args.quiet {
                let m = r.models.first();
                eprintln!(
                    "total: triangles {} -> {} in {:.3} s, written to {}",
                    m.map_or(0, |m| m.triangles_before),
                    m.map_or(0, |m| m.triangles_after),
                    start.elapsed().as_secs_f64(),
                    args.output.display()
                );
            }
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e),
    }
}

fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

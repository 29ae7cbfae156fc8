//! Decimating with the `decimate-core` library alone, as a program would.
//!
//! `cargo run -p decimate-core --example simplify` decimates a generated sphere given as
//! arrays; `cargo run -p decimate-core --example simplify -- IN OUT [PERCENT]` decimates the
//! file IN (any format the `decimate` program reads) by quadric edge collapse, removing
//! PERCENT of its vertices (90 by default), and writes OUT in the format its extension names
//! (`.glb`, `.ply`, …).

use std::path::Path;
use std::process::ExitCode;

use decimate_core::api::{simplify, simplify_file, Algorithm, Params, Target};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let percent = args.get(2).map_or(Ok(90.0), |p| p.parse::<f64>());
    let Ok(percent) = percent else {
        eprintln!("simplify: PERCENT must be a number, not {:?}", args[2]);
        return ExitCode::from(2);
    };
    let params = Params {
        target: Target::RemovePercent(percent),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    match args.as_slice() {
        [] => arrays(&params),
        [input, output] | [input, output, _] => {
            match simplify_file(Path::new(input), Path::new(output), &params) {
                Ok(done) => {
                    for w in &done.warnings {
                        eprintln!("simplify: warning: {w}");
                    }
                    let m = &done.report.models;
                    let before: usize = m.iter().map(|m| m.triangles_before).sum();
                    let after: usize = m.iter().map(|m| m.triangles_after).sum();
                    println!("{input}: {before} -> {after} triangles, written to {output}");
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("simplify: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        _ => {
            eprintln!("usage: simplify [IN OUT [PERCENT]]");
            ExitCode::from(2)
        }
    }
}

/// A sphere of `rings × segments` quads as arrays, decimated and checked.
fn arrays(params: &Params) -> ExitCode {
    let (rings, segments) = (40u32, 80u32);
    let mut positions = Vec::new();
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            positions.push([
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ]);
        }
    }
    // Quads between rings (the poles' rings collapse to points: their triangles are skipped).
    let mut indices = Vec::new();
    for r in 1..rings - 1 {
        for s in 0..segments {
            let a = r * segments + s;
            let b = r * segments + (s + 1) % segments;
            let (c, d) = (b + segments, a + segments);
            indices.extend([a, d, c, a, c, b]);
        }
    }
    match simplify(&positions, &indices, params) {
        Ok((mesh, report)) => {
            let m = &report.models[0];
            println!(
                "sphere: {} -> {} vertices, {} -> {} triangles, largest error {:.5}",
                m.vertices_before,
                mesh.positions.len(),
                indices.len() / 3,
                mesh.indices.len() / 3,
                m.max_error
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("simplify: {e}");
            ExitCode::FAILURE
        }
    }
}

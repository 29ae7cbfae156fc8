//! `api-timer FILE KEEP_TRIANGLES`: reads FILE's first model, then times, on its arrays,
//! what `decimate.simplify(..., keep_triangles=K)` does in Rust: `api::model_from_arrays`,
//! the `decimate` program's weld and repair (`mesh::build`), qem decimation, and the copy
//! back to arrays. Prints `seconds vertices triangles` of the call and its result.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use decimate_core::api::{model_from_arrays, simplify_scene, Algorithm, Params, Scene, Target};
use decimate_core::io::read_scene;
use decimate_core::mesh::build::{build_scene_with, BuildOptions};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let (Some(file), Some(keep)) = (args.get(1), args.get(2).and_then(|k| k.parse().ok())) else {
        eprintln!("usage: api-timer FILE KEEP_TRIANGLES");
        return ExitCode::FAILURE;
    };
    let scene = match read_scene(Path::new(file)) {
        Ok(outcome) => outcome.scene,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let Some(model) = scene.models.first() else {
        eprintln!("{file}: no mesh");
        return ExitCode::FAILURE;
    };
    let positions: Vec<[f32; 3]> = model.positions.iter().map(|p| p.to_array()).collect();
    let indices: Vec<u32> = model.triangles.iter().flatten().copied().collect();
    let params = Params {
        target: Target::KeepTriangles(keep),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let start = Instant::now();
    let model = match model_from_arrays(&positions, &indices) {
        Ok(model) => model,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let options = BuildOptions {
        weld: true,
        weld_tolerance: None,
    };
    let (mut scene, _) = build_scene_with(
        Scene {
            models: vec![model],
        },
        &options,
    );
    simplify_scene(&mut scene, &params);
    let (v, t) = scene.models.first().map_or((Vec::new(), Vec::new()), |m| {
        let v: Vec<[f32; 3]> = m.positions.iter().map(|p| p.to_array()).collect();
        (v, m.triangles.clone())
    });
    let seconds = start.elapsed().as_secs_f64();
    println!("{seconds} {} {}", v.len(), t.len());
    ExitCode::SUCCESS
}

//! `gen-models`: writes the report's test models (test001–test008) and large synthetic meshes
//! for benchmarks, from `decimate::mesh::shapes`.
//!
//! ```text
//! gen-models assets DIR                      test001.wrl … test008.wrl into DIR
//! gen-models sphere RINGS SEGMENTS FILE      a bumpy sphere (.ply or .wrl by extension)
//! ```

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use decimate::io;
use decimate::mesh::{shapes, Model, Scene};

fn write(model: Model, path: &Path) -> Result<(), String> {
    let scene = Scene {
        models: vec![model],
    };
    let ply = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ply"));
    let result = if ply {
        io::write_ply(&scene, path)
    } else {
        io::write_vrml2(&scene, path)
    };
    result.map_err(|e| e.to_string())?;
    println!("wrote {}", path.display());
    Ok(())
}

fn run(args: &[String]) -> Result<(), String> {
    let usage = "usage: gen-models assets DIR | gen-models sphere RINGS SEGMENTS FILE";
    match args {
        [cmd, dir] if cmd == "assets" => {
            let dir = PathBuf::from(dir);
            std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            for model in shapes::all() {
                let path = dir.join(format!("{}.wrl", model.name));
                write(model, &path)?;
            }
            Ok(())
        }
        [cmd, rings, segments, file] if cmd == "sphere" => {
            let parse = |s: &str| {
                s.parse::<u32>()
                    .map_err(|_| format!("not a count: '{s}'\n{usage}"))
            };
            write(
                shapes::bumpy_sphere(parse(rings)?, parse(segments)?),
                Path::new(file),
            )
        }
        _ => Err(usage.to_string()),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gen-models: {e}");
            ExitCode::from(2)
        }
    }
}

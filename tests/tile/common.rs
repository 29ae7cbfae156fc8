//! The test mesh and the command runner shared by the tile tests.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use decimate_core::mesh::{shapes, Model, Scene};

/// A closed bumpy sphere of 57 600 triangles written as binary PLY into `dir`.
pub fn sphere_ply(dir: &Path) -> (PathBuf, Model) {
    let model = shapes::bumpy_sphere(121, 240);
    let path = dir.join("sphere.ply");
    let scene = Scene {
        models: vec![model.clone()],
    };
    decimate_core::io::write_ply(&scene, &path).expect("write the test mesh");
    (path, model)
}

/// Runs `decimate` with `args` (and `env`), returning its output.
pub fn decimate(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_decimate"));
    c.args(args)
        .env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("JOB_COMPLETION_INDEX");
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("run decimate")
}

/// As [`decimate`], asserting success.
pub fn ok(args: &[&str], env: &[(&str, &str)]) -> Output {
    let out = decimate(args, env);
    assert!(
        out.status.success(),
        "decimate {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// The single model a PLY file holds, read by the in-memory reader.
pub fn read_model(path: &Path) -> Model {
    let outcome = decimate_core::io::read_scene(path).expect("read the result");
    let mut models = outcome.scene.models;
    assert_eq!(models.len(), 1, "{}", path.display());
    let mut m = models.remove(0);
    decimate_core::mesh::weld::weld(&mut m, 0.0);
    m
}

pub fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// `decimate tile plan INPUT --work WORK --tiles TILES -p 90`, which must succeed.
pub fn plan(input: &Path, work: &Path, tiles: u32) {
    let tiles = tiles.to_string();
    ok(
        &[
            "tile",
            "plan",
            s(input),
            "--work",
            s(work),
            "--tiles",
            &tiles,
            "-p",
            "90",
        ],
        &[],
    );
}

/// `decimate INPUT nogui --tiles TILES -p 90 -o OUT -q`, the one-command run that the tile
/// commands and the job scripts must equal byte for byte; it must succeed.
pub fn one_command(input: &Path, tiles: u32, out: &Path) {
    let tiles = tiles.to_string();
    ok(
        &[
            s(input),
            "nogui",
            "--tiles",
            &tiles,
            "-p",
            "90",
            "-o",
            s(out),
            "-q",
        ],
        &[],
    );
}

/// `bash SCRIPT INPUT WORK OUT --tiles 4 -p 90`: a job script of tools/ on the test mesh.
pub fn job_script(script: &str, input: &Path, work: &Path, out: &Path) -> Command {
    let mut c = Command::new("bash");
    c.args([
        script,
        s(input),
        s(work),
        s(out),
        "--tiles",
        "4",
        "-p",
        "90",
    ]);
    c
}

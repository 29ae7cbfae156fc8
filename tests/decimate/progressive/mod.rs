//! `--progressive FILE.pm` as a user meets it: the binary writes the decimated scene and the
//! progressive file; reading the file back gives a base mesh with exactly the output's
//! counts, levels with exactly base + k vertices and a clean surface, and at the top level the
//! input itself — positions, triangles, colours and texture coordinates bit for bit.
//! Malformed files are refused with a message naming the file and the byte, never a panic.

use std::path::{Path, PathBuf};
use std::process::Output;

use decimate_core::io::progressive_file::{parse_progressive, read_progressive};
use decimate_core::io::{read_scene, write_scene, ReadError};
use decimate_core::mesh::progressive::{Lod, ProgressiveScene};
use decimate_core::mesh::{build::build_scene, measure, shapes, Attribute, Model, Scene};

use crate::support::binary::decimate;

mod command_line;
mod malformed;
mod textures;

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Writes `models` to `dir/in.wrl`.
fn write_input(dir: &Path, models: Vec<Model>) -> PathBuf {
    write_input_as(dir, "in.wrl", models)
}

/// Writes `models` to `dir/name`, in the format its extension names.
fn write_input_as(dir: &Path, name: &str, models: Vec<Model>) -> PathBuf {
    let path = dir.join(name);
    write_scene(&Scene { models }, &path).unwrap_or_else(|e| panic!("write {e}"));
    path
}

/// The scene as the binary sees it: read, then built (welded).
fn as_built(path: &Path) -> Scene {
    let outcome = read_scene(path).unwrap_or_else(|e| panic!("read {e}"));
    build_scene(outcome.scene, true)
}

fn read_pm(path: &Path) -> ProgressiveScene {
    read_progressive(path).unwrap_or_else(|e| panic!("read {e}"))
}

/// Runs `decimate in.wrl nogui -p 90 -o out.wrl --progressive out.pm` on `models`; returns
/// the directory, the input as built, the output as read and the progressive scene.
fn run_progressive(models: Vec<Model>) -> (tempfile::TempDir, Scene, Scene, ProgressiveScene) {
    run_progressive_as("wrl", models)
}

/// As [`run_progressive`], with input and output `in.EXT` and `out.EXT`.
fn run_progressive_as(
    ext: &str,
    models: Vec<Model>,
) -> (tempfile::TempDir, Scene, Scene, ProgressiveScene) {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    let (name, output) = (format!("in.{ext}"), format!("out.{ext}"));
    let input = write_input_as(dir.path(), &name, models);
    let o = decimate(
        dir.path(),
        &[
            &name,
            "nogui",
            "-p",
            "90",
            "-o",
            &output,
            "--progressive",
            "out.pm",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let pm = read_pm(&dir.path().join("out.pm"));
    let splits: usize = pm.models.iter().map(|m| m.splits.len()).sum();
    assert!(
        stderr(&o).contains(&format!("wrote out.pm ({splits} vertex splits)")),
        "{}",
        stderr(&o)
    );
    let out = read_scene(&dir.path().join(output))
        .unwrap_or_else(|e| panic!("read {e}"))
        .scene;
    (dir, as_built(&input), out, pm)
}

/// Base counts equal the output's, and the top level is the input exactly.
fn assert_round_trip(input: &Scene, out: &Scene, pm: &ProgressiveScene) {
    assert_eq!(pm.models.len(), input.models.len());
    assert_eq!(pm.models.len(), out.models.len());
    for ((pm, before), after) in pm.models.iter().zip(&input.models).zip(&out.models) {
        let name = &before.name;
        assert_eq!(pm.base.name, after.name);
        assert_eq!(pm.base.positions.len(), after.positions.len(), "{name}");
        assert_eq!(pm.base.triangles.len(), after.triangles.len(), "{name}");
        assert!(pm.splits.len() * 10 >= before.positions.len() * 8, "{name}");
        let back = pm.original();
        assert_eq!(back.positions, before.positions, "{name}: positions");
        assert_eq!(back.triangles, before.triangles, "{name}: triangles");
        assert_eq!(back.colors, before.colors, "{name}: colours");
        assert_eq!(
            back.texcoords, before.texcoords,
            "{name}: texture coordinates"
        );
        assert_eq!(back.transform, before.transform, "{name}: transform");
    }
}

/// `m` with per-vertex colours: red above y = 0, blue below.
pub fn red_above_blue_below(mut m: Model) -> Model {
    let colours = m
        .positions
        .iter()
        .map(|p| {
            if p.y > 0.0 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 0.0, 1.0]
            }
        })
        .collect();
    m.colors = Some(Attribute::PerVertex(colours));
    m
}

fn one_colour_per_face(mut m: Model) -> Model {
    let f = m.triangles.len();
    let colours = (0..f).map(|t| [t as f32 / f as f32, 0.5, 0.25]).collect();
    m.colors = Some(Attribute::PerFace(colours));
    m
}

#[test]
fn the_top_level_is_the_input_and_the_base_is_the_output() {
    for model in [
        shapes::bumpy_sphere(24, 32),
        shapes::cube(6, 2.0),
        red_above_blue_below(shapes::uv_sphere(16, 24)),
        one_colour_per_face(shapes::cube(5, 1.0)),
    ] {
        let name = model.name.clone();
        let colors = |m: &Model| m.colors.as_ref().map(std::mem::discriminant);
        let binding = colors(&model);
        let (_dir, input, out, pm) = run_progressive(vec![model]);
        assert_eq!(
            colors(&input.models[0]),
            binding,
            "{name}: the input's colours"
        );
        assert_eq!(
            colors(&pm.models[0].base),
            binding,
            "{name}: the base's colours"
        );
        assert_round_trip(&input, &out, &pm);
    }
}

#[test]
fn every_level_has_base_plus_k_vertices_and_a_clean_closed_surface() {
    let (_dir, input, _, pm) = run_progressive(vec![shapes::bumpy_sphere(24, 32)]);
    let pm = &pm.models[0];
    let euler = measure::euler_characteristic(&input.models[0]);
    assert_eq!(euler, 2);
    let (v0, f0) = (pm.base.positions.len(), pm.base.triangles.len());
    let top = pm.splits.len();
    let mut lod = Lod::new(pm);
    let levels = [0, 1, 2, top / 4, top / 2, top - 1, top, top / 3, 0];
    for k in levels {
        lod.set_level(k);
        let m = lod.model();
        assert_eq!(lod.level(), k);
        assert_eq!(m.positions.len(), v0 + k, "level {k}");
        // Closed: every split adds two faces.
        assert_eq!(m.triangles.len(), f0 + 2 * k, "level {k}");
        assert_eq!(measure::degenerate_triangles(m, 1e-9), 0, "level {k}");
        assert_eq!(measure::euler_characteristic(m), euler, "level {k}");
        assert_eq!(measure::boundary_loops(m), 0, "level {k}");
    }
    lod.set_level(top + 100);
    assert_eq!(lod.level(), top);
    assert_eq!(lod.model().positions.len(), input.models[0].positions.len());
}

#[test]
fn two_shapes_in_one_file_keep_two_progressive_models() {
    let mut cube = shapes::cube(6, 1.0);
    cube.transform = glam::Mat4::from_translation(glam::Vec3::new(3.0, 0.0, 0.0));
    let (_dir, input, out, pm) = run_progressive(vec![shapes::bumpy_sphere(16, 24), cube]);
    assert_eq!(pm.models.len(), 2);
    assert_eq!(input.models.len(), 2);
    assert_round_trip(&input, &out, &pm);
    assert_ne!(pm.models[0].base.name, pm.models[1].base.name);
}

/// Writes `bytes` to `dir/name`, reads it back and returns the error's text, which must name
/// the file.
fn refused(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("{e}"));
    match read_progressive(&path) {
        Ok(_) => panic!("{name}: a malformed file was read"),
        Err(e) => {
            let text = e.to_string();
            assert!(
                text.starts_with(&path.display().to_string()),
                "{name}: the message does not name the file: {text}"
            );
            assert!(matches!(e, ReadError::Binary { .. }), "{e:?}");
            text
        }
    }
}

/// Release-mode timings of the `.pm` file of a 1M-triangle sphere kept at 10 %; prints them
/// and asserts no time:
/// `cargo test --release --test decimate progressive:: -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing_of_a_million_triangle_sphere() {
    use decimate_core::decimate::{simplify_scene_progressive, Algorithm, Params, Target};
    use decimate_core::io::progressive_file::write_progressive;
    use std::time::Instant;

    let mut scene = Scene {
        models: vec![shapes::bumpy_sphere(700, 715)],
    };
    let triangles = scene.models[0].triangles.len();
    let params = Params {
        target: Target::RemovePercent(90.0),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    let start = Instant::now();
    let (_, pm) = simplify_scene_progressive(&mut scene, &params, &mut |_| {});
    let decimated = start.elapsed();
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    let path = dir.path().join("sphere.pm");
    let start = Instant::now();
    write_progressive(&pm, &path).unwrap_or_else(|e| panic!("write {e}"));
    let written = start.elapsed();
    let start = Instant::now();
    let back = read_pm(&path);
    let read = start.elapsed();
    assert_eq!(back, pm);
    let start = Instant::now();
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
    let loaded = start.elapsed();
    let start = Instant::now();
    let parsed = parse_progressive(&bytes, &path).unwrap_or_else(|e| panic!("{e}"));
    let parse = start.elapsed();
    let start = Instant::now();
    let valid = parsed.models.iter().all(|m| m.validate().is_ok());
    let validate = start.elapsed();
    assert!(valid);
    eprintln!(
        "read = fs::read {loaded:.2?} + parse {parse:.2?} (of which validate {validate:.2?})"
    );
    let size = std::fs::metadata(&path).map_or(0, |m| m.len());
    eprintln!(
        "{triangles} triangles, {} splits: decimate {decimated:.2?}, write {written:.2?}, \
         read {read:.2?}, {size} bytes ({:.1} MiB)",
        pm.models[0].splits.len(),
        size as f64 / (1 << 20) as f64
    );
}

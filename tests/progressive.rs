//! `--progressive FILE.pm` as a user meets it: the binary writes the decimated scene and the
//! progressive file; reading the file back gives a base mesh with exactly the output's
//! counts, levels with exactly base + k vertices and a clean surface, and at the top level the
//! input itself — positions, triangles, colours and texture coordinates bit for bit.
//! Malformed files are refused with a message naming the file and the byte, never a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use decimate::io::progressive_file::{parse_progressive, read_progressive, MAGIC};
use decimate::io::{read_scene, write_scene, ReadError};
use decimate::mesh::progressive::{Lod, ProgressiveScene, VertexSplit};
use decimate::mesh::{build::build_scene, measure, shapes, Attribute, Model, Scene};

fn decimate(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("run decimate: {e}"))
}

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

fn red_above_blue_below(mut m: Model) -> Model {
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

/// A grid of `n` × `n` squares over the unit square (each cut in two) at height `z(x, y)`,
/// textured by (x, y) and cut by a seam down x = 0.5: the squares right of it map to a
/// second island, shifted by 2 in u, so the seam's points are there once per side.
fn textured_grid(n: u32, z: impl Fn(f32, f32) -> f32) -> Model {
    textured_grid_in(n, z, |i, _| u32::from(2 * i >= n))
}

/// As [`textured_grid`], the square `(i, j)` in texture island `island(i, j)`.
fn textured_grid_in(
    n: u32,
    z: impl Fn(f32, f32) -> f32,
    island: impl Fn(u32, u32) -> u32,
) -> Model {
    let (mut positions, mut texcoords, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    let mut ids = std::collections::HashMap::new();
    let at = |i: u32| i as f32 / n as f32;
    for j in 0..n {
        for i in 0..n {
            let island = island(i, j);
            let mut id = |i: u32, j: u32| {
                *ids.entry((i, j, island)).or_insert_with(|| {
                    let (x, y) = (at(i), at(j));
                    positions.push(glam::Vec3::new(x, y, z(x, y)));
                    texcoords.push([x + 2.0 * island as f32, y]);
                    positions.len() as u32 - 1
                })
            };
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Model {
        name: "grid".into(),
        positions,
        triangles,
        texcoords: Some(texcoords),
        ..Model::default()
    }
}

/// `(position, texture coordinates)` of each vertex of an OBJ the binary wrote, which must
/// give one `vt` per vertex and number each face corner's `vt` as its vertex.
fn obj_vertices(path: &Path) -> Vec<([f32; 3], [f32; 2])> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}"));
    let (mut v, mut vt) = (Vec::new(), Vec::new());
    let numbers = |rest: &str| -> Vec<f32> {
        rest.split_whitespace()
            .map(|x| x.parse().unwrap_or_else(|e| panic!("{x}: {e}")))
            .collect()
    };
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("v ") {
            let p = numbers(rest);
            v.push([p[0], p[1], p[2]]);
        } else if let Some(rest) = line.strip_prefix("vt ") {
            let t = numbers(rest);
            vt.push([t[0], t[1]]);
        } else if let Some(rest) = line.strip_prefix("f ") {
            for corner in rest.split_whitespace() {
                let (a, b) = corner.split_once('/').unwrap_or((corner, ""));
                assert_eq!(a, b, "the corner {corner} has its vertex's vt");
            }
        }
    }
    assert_eq!(vt.len(), v.len(), "one vt per vertex");
    v.into_iter().zip(vt).collect()
}

#[test]
fn texture_coordinates_come_back_exactly_and_rebuilt_levels_keep_the_mapping() {
    let models = vec![
        textured_grid(40, |_, _| 0.0),
        textured_grid(24, |x, y| 0.2 * (3.0 * x).sin() * (2.0 * y).cos()),
    ];
    let (dir, input, out, pm) = run_progressive_as("obj", models);
    for (m, name) in input.models.iter().zip(["flat", "curved"]) {
        assert!(m.texcoords.is_some(), "{name}: the input is textured");
    }
    for (m, name) in pm.models.iter().zip(["flat", "curved"]) {
        assert!(m.base.texcoords.is_some(), "{name}: the base is textured");
    }
    // The top level is the input, its coordinates bit for bit.
    assert_round_trip(&input, &out, &pm);
    // A level rebuilt from the file: the flat grid's coordinates are still its positions'
    // (x, y) on its island.
    let o = decimate(
        dir.path(),
        &["out.pm", "nogui", "-p", "50", "-o", "p50.obj"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let vertices = obj_vertices(&dir.path().join("p50.obj"));
    // Half of each model's vertices, or one fewer where that level would split only one
    // side of a texture seam.
    let half: Vec<usize> = pm
        .models
        .iter()
        .map(|m| {
            let (base, full) = (m.base.positions.len(), m.full_vertex_count());
            base + m.whole_level(full - (full as f64 / 2.0).round() as usize - base)
        })
        .collect();
    assert_eq!(vertices.len(), half[0] + half[1]);
    for (p, uv) in &vertices[..half[0]] {
        let shift = if uv[0] > 1.5 { 2.0 } else { 0.0 };
        let off = (uv[0] - shift - p[0]).abs().max((uv[1] - p[1]).abs());
        assert!(off < 1e-5, "{p:?} maps to {uv:?}");
    }
}

#[test]
fn collapses_into_a_seam_junction_come_back_exactly() {
    // Four islands meet at the grid's centre: a junction of four sides, pinned, which takes
    // its neighbours in where it stands (with a seam vertex, both sides at once). Those
    // collapses are recorded like any other, and refined away like any other.
    let n = 40;
    let z = |x: f32, y: f32| 0.2 * (3.0 * x).sin() * (2.0 * y).cos();
    let quarters = textured_grid_in(n, z, |i, j| {
        u32::from(2 * i >= n) + 2 * u32::from(2 * j >= n)
    });
    let (_dir, input, out, pm) = run_progressive_as("obj", vec![quarters]);
    assert_round_trip(&input, &out, &pm);
    let centre = glam::Vec3::new(0.5, 0.5, z(0.5, 0.5));
    let copies = |m: &Model| m.positions.iter().filter(|&&p| p == centre).count();
    assert_eq!(copies(&input.models[0]), 4, "the input's junction");
    assert_eq!(
        copies(&out.models[0]),
        4,
        "the junction stays, once per island"
    );
}

#[test]
fn a_file_cut_in_its_texture_coordinates_is_refused() {
    let (dir, _, _, pm) = run_progressive_as("obj", vec![textured_grid(12, |_, _| 0.0)]);
    let b = std::fs::read(dir.path().join("out.pm")).unwrap_or_else(|e| panic!("{e}"));
    let m = &pm.models[0];
    // The attribute byte: texture coordinates (bit 3) only.
    let flags = 16 + 4 + m.base.name.len() + 64 + 12 + 5 + 1;
    assert_eq!(b[flags], 8);
    // The base's coordinates come after its positions: a cut there leaves too few bytes.
    let (v, f) = (m.base.positions.len(), m.base.triangles.len());
    let positions = flags + 1 + 8;
    let text = refused(dir.path(), "base.pm", &b[..positions + 12 * v + 4]);
    assert!(text.contains("truncated"), "{text}");
    // The last split's, read after all the others: the cut is named there.
    let split = |s: &VertexSplit| 4 + 36 + 24 + 4 + 4 * s.renamed.len() + 1 + 12 * s.added.len();
    let earlier = &m.splits[..m.splits.len() - 1];
    let last = positions + 20 * v + 12 * f + 4 + earlier.iter().map(split).sum::<usize>();
    let text = refused(dir.path(), "split.pm", &b[..last + 40 + 12]);
    assert!(
        text.contains(&format!(
            "split {}: the file ends before a texture coordinate",
            earlier.len()
        )),
        "{text}"
    );
}

#[test]
fn schroeder_with_progressive_is_a_usage_error_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    write_input(dir.path(), vec![shapes::cube(4, 1.0)]);
    let o = decimate(
        dir.path(),
        &[
            "in.wrl",
            "nogui",
            "-p",
            "50",
            "-a",
            "schroeder",
            "--progressive",
            "x.pm",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("-a qem"), "{}", stderr(&o));
    assert!(!dir.path().join("x.pm").exists());
    assert!(!dir.path().join("out.wrl").exists());
}

#[test]
fn progressive_over_the_input_is_refused_unless_overwrite() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    let input = write_input(dir.path(), vec![shapes::cube(4, 1.0)]);
    let before = std::fs::read(&input).unwrap_or_else(|e| panic!("{e}"));
    let args = ["in.wrl", "nogui", "-p", "50", "--progressive", "in.wrl"];
    let o = decimate(dir.path(), &args);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("refusing to write over an input file"));
    assert_eq!(std::fs::read(&input).ok(), Some(before));
    assert!(!dir.path().join("out.wrl").exists());
    let o = decimate(dir.path(), &[&args[..], &["--overwrite"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(read_progressive(&input).is_ok());
}

#[test]
fn an_unwritable_progressive_file_is_named_with_exit_1() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    write_input(dir.path(), vec![shapes::cube(4, 1.0)]);
    let o = decimate(
        dir.path(),
        &[
            "in.wrl",
            "nogui",
            "-p",
            "50",
            "--progressive",
            "no/such/x.pm",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("no/such/x.pm"), "{}", stderr(&o));
}

// ---------------------------------------------------------------------------------------
// Malformed files

/// A valid progressive file of a small cube, no attributes; its bytes.
fn small_pm(dir: &Path) -> Vec<u8> {
    write_input(dir, vec![shapes::cube(3, 1.0)]);
    let o = decimate(
        dir,
        &[
            "in.wrl",
            "nogui",
            "-p",
            "90",
            "-q",
            "--progressive",
            "ok.pm",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "-q prints nothing: {}", stderr(&o));
    std::fs::read(dir.join("ok.pm")).unwrap_or_else(|e| panic!("{e}"))
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

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// Byte offset of the first split's `keep` field in a one-model file without attributes.
fn first_split_offset(b: &[u8]) -> (usize, u32) {
    let name_len = u32_at(b, 16) as usize;
    let counts = 16 + 4 + name_len + 64 + 12 + 5 + 1 + 1;
    let (v, f) = (u32_at(b, counts) as usize, u32_at(b, counts + 4) as usize);
    (counts + 8 + 12 * v + 12 * f + 4, v as u32)
}

#[test]
fn truncated_files_are_refused_at_every_cut() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    let b = small_pm(dir.path());
    assert!(read_progressive(&dir.path().join("ok.pm")).is_ok());
    for cut in [
        0,
        4,
        8,
        11,
        12,
        16,
        40,
        b.len() / 3,
        b.len() / 2,
        b.len() - 1,
    ] {
        let text = refused(dir.path(), "cut.pm", &b[..cut]);
        if cut == 0 {
            assert!(text.contains("empty"), "{text}");
        } else if cut < 8 {
            assert!(text.contains("byte 0: not a progressive mesh"), "{text}");
        } else {
            assert!(
                text.contains("the file ends before") || text.contains("truncated"),
                "{cut}: {text}"
            );
        }
    }
    let text = refused(dir.path(), "long.pm", &[&b[..], &[0]].concat());
    assert!(text.contains("1 byte after the last model"), "{text}");
}

#[test]
fn wrong_magic_version_index_count_or_number_is_named_with_its_byte() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    let b = small_pm(dir.path());
    assert_eq!(&b[..8], &MAGIC);

    let mut bad = b.clone();
    bad[0] ^= 0x20;
    let text = refused(dir.path(), "magic.pm", &bad);
    assert!(
        text.ends_with(
            "byte 0: not a progressive mesh: the file does not start with \"DECIMPM\\0\""
        ),
        "{text}"
    );

    let mut bad = b.clone();
    bad[8..12].copy_from_slice(&2u32.to_le_bytes());
    let text = refused(dir.path(), "version.pm", &bad);
    assert!(
        text.contains("byte 8: format version 2 is not supported"),
        "{text}"
    );

    let (at, v) = first_split_offset(&b);
    assert!(u32_at(&b, at) < v, "the offset computed is a split's keep");
    let mut bad = b.clone();
    bad[at..at + 4].copy_from_slice(&v.to_le_bytes());
    let text = refused(dir.path(), "index.pm", &bad);
    assert!(
        text.contains(&format!(
            "byte {at}: model 0: split 0: the vertex that splits {v} is out of range (expected below {v})"
        )),
        "{text}"
    );

    // An absurd base vertex count: refused before anything is allocated for it.
    let name_len = u32_at(&b, 16) as usize;
    let vertex_count = 16 + 4 + name_len + 64 + 12 + 5 + 1 + 1;
    let mut bad = b.clone();
    bad[vertex_count..vertex_count + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let text = refused(dir.path(), "count.pm", &bad);
    assert!(
        text.contains(&format!(
            "byte {vertex_count}: model 0: the base vertex count is 4294967295, but"
        )),
        "{text}"
    );

    // A NaN position.
    let first_position = vertex_count + 8;
    let mut bad = b.clone();
    bad[first_position..first_position + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let text = refused(dir.path(), "nan.pm", &bad);
    assert!(
        text.contains(&format!(
            "byte {first_position}: model 0: a position is not a finite number"
        )),
        "{text}"
    );

    let text = refused(dir.path(), "empty.pm", &[]);
    assert!(text.contains("byte 0: the file is empty"), "{text}");
}

/// Release-mode timings of the `.pm` file of a 1M-triangle sphere kept at 10 %; prints them
/// and asserts no time: `cargo test --release --test progressive -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing_of_a_million_triangle_sphere() {
    use decimate::decimate::{decimate_scene_progressive, Algorithm, Params, Target};
    use decimate::io::progressive_file::write_progressive;
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
    let (_, pm) = decimate_scene_progressive(&mut scene, &params, &mut |_| {});
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

#[test]
fn a_progressive_file_as_input_rebuilds_the_level_a_count_asks_for() {
    let models = vec![shapes::bumpy_sphere(30, 60), shapes::cube(6, 2.0)];
    let (dir, input, out, pm) = run_progressive(models);
    let run = |args: &[&str]| decimate(dir.path(), &[&["out.pm", "nogui"], args].concat());
    let full: Vec<usize> = input.models.iter().map(|m| m.positions.len()).collect();
    // At -p 90 the level is the recorded base: the decimated output, exactly.
    let o = run(&["-p", "90", "-o", "again.wrl"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let again = read_scene(&dir.path().join("again.wrl")).map(|r| r.scene);
    assert_eq!(again.ok().as_ref(), Some(&out));
    // -p 0 is the input; -p 50 removes exactly half of each model's vertices (rounded), and
    // each level keeps every invariant of the surface.
    for (p, name) in [(0.0, "p0.wrl"), (50.0, "p50.wrl")] {
        let o = run(&["-p", &p.to_string(), "-o", name]);
        assert!(o.status.success(), "{}", stderr(&o));
        let level = as_built(&dir.path().join(name));
        for ((m, before), n) in level.models.iter().zip(&input.models).zip(&full) {
            let removed = (p / 100.0 * *n as f64).round() as usize;
            assert_eq!(m.positions.len(), n - removed, "{} at {p} %", before.name);
            let broken = measure::invariant_violations(before, m);
            assert!(broken.is_empty(), "{} at {p} %: {broken:?}", before.name);
            if p == 0.0 {
                // The input's positions, bit for bit (in the progressive numbering).
                let bits = |m: &Model| {
                    let mut b: Vec<[u32; 3]> = m
                        .positions
                        .iter()
                        .map(|p| p.to_array().map(f32::to_bits))
                        .collect();
                    b.sort_unstable();
                    b
                };
                assert_eq!(bits(m), bits(before), "{}", before.name);
            }
        }
        assert!(
            stderr(&o).contains("rebuilt by vertex splits"),
            "{}",
            stderr(&o)
        );
    }
    // Past the base: the base, and the summary says so.
    let o = run(&["-p", "99", "-o", "p99.wrl"]);
    assert!(
        stderr(&o).contains("the file holds no coarser level"),
        "{}",
        stderr(&o)
    );
    let p99 = read_scene(&dir.path().join("p99.wrl")).map(|r| r.scene);
    assert_eq!(p99.ok().as_ref(), Some(&out));
    // An error bound cannot pick a level, and recording again is refused: nothing written.
    for args in [
        &["--max-error", "0.01", "-o", "e.wrl"][..],
        &["-p", "50", "-o", "e.wrl", "--progressive", "again.pm"][..],
    ] {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("out.pm"), "{}", stderr(&o));
        assert!(!dir.path().join("e.wrl").exists(), "{args:?}");
    }
    let levels = pm.models.iter().map(|m| m.splits.len()).sum::<usize>();
    assert!(levels > 0);
}

//! The `decimate` binary as a user runs it: the original's usage, outputs that our reader
//! parses back with the expected counts, errors that name the file and line with a non-zero
//! exit and no output left behind, and the input never overwritten unless asked.

use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use decimate_core::io::read_scene;
use decimate_core::mesh::measure;

use crate::support::binary::decimate;

fn asset(name: &str) -> String {
    let p: PathBuf = [env!("CARGO_MANIFEST_DIR"), "assets", name]
        .iter()
        .collect();
    p.to_string_lossy().into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// (vertices, triangles) of each model in a file, as our reader sees it.
fn counts(path: &Path) -> Vec<(usize, usize)> {
    let scene = read_scene(path).expect("output parses").scene;
    scene
        .models
        .iter()
        .map(|m| (m.positions.len(), m.triangles.len()))
        .collect()
}

#[test]
fn full_decimation_of_the_report_models_through_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    for (name, expected) in [
        ("test001.wrl", (4, 4)),
        ("test002.wrl", (8, 12)),
        ("test003.wrl", (4, 2)),
        ("test004.wrl", (8, 12)),
    ] {
        let o = decimate(
            dir.path(),
            &[&asset(name), "nogui", "-p", "100", "-o", "full.wrl"],
        );
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("fully decimated"),
            "{name}: {}",
            stderr(&o)
        );
        assert_eq!(
            counts(&dir.path().join("full.wrl")),
            vec![expected],
            "{name}"
        );
    }
}

#[test]
fn default_output_is_out_wrl_and_percentages_are_exact() {
    let dir = tempfile::tempdir().unwrap();
    let o = decimate(dir.path(), &[&asset("test004.wrl"), "nogui", "-p", "90"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = dir.path().join("out.wrl");
    assert_eq!(counts(&out)[0].0, 60);
    let scene = read_scene(&out).unwrap().scene;
    assert!((measure::volume(&scene.models[0]) - 1000.0).abs() < 1e-3);
    let summary = stderr(&o);
    assert!(summary.contains("602 -> 60"), "{summary}");
    assert!(summary.contains("vertices/s"), "{summary}");

    let o = decimate(
        dir.path(),
        &[&asset("test004.wrl"), "nogui", "-v", "102", "-o", "v.wrl"],
    );
    assert!(o.status.success());
    assert_eq!(counts(&dir.path().join("v.wrl"))[0].0, 500);
    let o = decimate(
        dir.path(),
        &[
            &asset("test004.wrl"),
            "nogui",
            "--keep-triangles",
            "500",
            "-o",
            "t.wrl",
        ],
    );
    assert!(o.status.success());
    let t = counts(&dir.path().join("t.wrl"))[0].1;
    assert!((498..=500).contains(&t), "{t} triangles");
}

#[test]
fn max_error_bounds_the_removal() {
    let dir = tempfile::tempdir().unwrap();
    // The dome is curved everywhere: a tight bound keeps far more than a loose one.
    let run = |bound: &str, out: &str| {
        let o = decimate(
            dir.path(),
            &[
                &asset("test006.wrl"),
                "nogui",
                "--max-error",
                bound,
                "-o",
                out,
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        counts(&dir.path().join(out))[0].0
    };
    let tight = run("0.01%", "tight.wrl");
    let loose = run("1%", "loose.wrl");
    assert!(
        tight > loose && loose > 4 && tight < 2402,
        "tight {tight}, loose {loose}"
    );
    // Planar regions cost nothing: a zero bound still flattens the plane to its corners.
    let o = decimate(
        dir.path(),
        &[
            &asset("test003.wrl"),
            "nogui",
            "--max-error",
            "0",
            "-o",
            "z.wrl",
        ],
    );
    assert!(o.status.success());
    assert_eq!(counts(&dir.path().join("z.wrl")), vec![(4, 2)]);
}

#[test]
fn every_model_of_a_scene_is_decimated_and_tiny_ones_dropped() {
    let dir = tempfile::tempdir().unwrap();
    // A 3x3-vertex flat grid and a triangle with its edge midpoints (6 vertices): the
    // midpoints go, leaving 3 vertices, so that model is dropped as the original did.
    let scene = "#VRML V2.0 utf8
DEF grid Shape { geometry IndexedFaceSet {
  coord Coordinate { point [ 0 0 0, 1 0 0, 2 0 0, 0 1 0, 1 1 0, 2 1 0, 0 2 0, 1 2 0, 2 2 0 ] }
  coordIndex [ 0 1 4 3 -1, 1 2 5 4 -1, 3 4 7 6 -1, 4 5 8 7 -1 ] } }
Transform { translation 5 0 0 children [
  DEF tri Shape { geometry IndexedFaceSet {
    coord Coordinate { point [ 0 0 0, 2 0 0, 1 2 0, 1 0 0, 1.5 1 0, 0.5 1 0 ] }
    coordIndex [ 0 3 5 -1, 3 1 4 -1, 5 4 2 -1, 3 4 5 -1 ] } } ] }
";
    std::fs::write(dir.path().join("two.wrl"), scene).unwrap();
    let o = decimate(
        dir.path(),
        &["two.wrl", "nogui", "-p", "100", "-o", "two-out.wrl"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = stderr(&o);
    assert!(summary.contains("dropped"), "{summary}");
    assert_eq!(counts(&dir.path().join("two-out.wrl")), vec![(4, 2)]);
}

#[test]
fn gzipped_input_is_read() {
    use std::io::Write;
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read(asset("test002.wrl")).unwrap();
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(&text).unwrap();
    std::fs::write(dir.path().join("cube.wrl.gz"), gz.finish().unwrap()).unwrap();
    let o = decimate(dir.path(), &["cube.wrl.gz", "nogui", "-p", "100"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(counts(&dir.path().join("out.wrl")), vec![(8, 12)]);
}

#[test]
fn the_input_is_never_overwritten_unless_asked() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("m.wrl");
    std::fs::copy(asset("test004.wrl"), &input).unwrap();
    let before = std::fs::read(&input).unwrap();
    let o = decimate(dir.path(), &["m.wrl", "nogui", "-p", "50", "-o", "m.wrl"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--overwrite"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&input).unwrap(), before);
    let o = decimate(
        dir.path(),
        &["m.wrl", "nogui", "-p", "50", "-o", "m.wrl", "--overwrite"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(counts(&input)[0].0, 301);
}

#[test]
fn an_output_through_a_link_or_into_a_pipe_lands_where_it_points() {
    let dir = tempfile::tempdir().unwrap();
    // A link: the file it names gets the model, the link stays a link, and a link to the
    // input counts as the input.
    std::fs::create_dir(dir.path().join("real")).unwrap();
    std::os::unix::fs::symlink("real/m.ply", dir.path().join("link.ply")).unwrap();
    let args = [
        asset("test006.wrl"),
        "nogui".into(),
        "-p".into(),
        "30".into(),
    ];
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = decimate(dir.path(), &[&args[..], &["-o", "link.ply"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let link = std::fs::symlink_metadata(dir.path().join("link.ply")).unwrap();
    assert!(link.file_type().is_symlink());
    assert_eq!(counts(&dir.path().join("real/m.ply")), vec![(1681, 3358)]);
    let input = dir.path().join("m.wrl");
    std::fs::copy(asset("test006.wrl"), &input).unwrap();
    std::os::unix::fs::symlink("m.wrl", dir.path().join("same.wrl")).unwrap();
    let o = decimate(
        dir.path(),
        &["m.wrl", "nogui", "-p", "30", "-o", "same.wrl"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(&input).unwrap(),
        std::fs::read(asset("test006.wrl")).unwrap()
    );
    // A named pipe (as `-o /dev/stdout` would be): written into, not replaced by a file.
    let fifo = dir.path().join("pipe.off");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo))
    };
    let o = decimate(dir.path(), &[&args[..], &["-o", "pipe.off"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    // Asked before waiting on the reader: had the pipe been replaced, it would wait forever.
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(kind.is_fifo(), "the pipe was replaced by a file");
    let bytes = reader.join().unwrap().unwrap();
    let scene = decimate_core::io::parse_bytes(bytes, &fifo).unwrap().scene;
    let piped: Vec<_> = scene
        .models
        .iter()
        .map(|m| (m.positions.len(), m.triangles.len()))
        .collect();
    assert_eq!(piped, vec![(1681, 3358)]);
}

#[test]
fn bad_files_fail_with_file_and_line_and_leave_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("index.wrl", "#VRML V1.0 ascii\nSeparator {\n Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n IndexedFaceSet { coordIndex [ 0, 1, 7, -1 ] }\n}\n", "index.wrl:4"),
        ("braces.wrl", "#VRML V2.0 utf8\nShape {\n geometry IndexedFaceSet {\n", "braces.wrl:"),
        ("binary.iv", "#Inventor V2.1 binary\n\0\0\0", "binary Inventor"),
        ("nan.wrl", "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n coord Coordinate { point [ 0 0 0, nan 1 0, 0 1 0 ] }\n coordIndex [ 0 1 2 -1 ] } }\n", "nan.wrl:3"),
        ("text.wrl", "hello, world\n", "text.wrl"),
    ];
    for (name, text, expected) in cases {
        std::fs::write(dir.path().join(name), text).unwrap();
        let o = decimate(dir.path(), &[name, "nogui", "-p", "50", "-o", "never.wrl"]);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", stderr(&o));
        assert!(stderr(&o).contains(expected), "{name}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{name}");
        assert!(!dir.path().join("never.wrl").exists(), "{name}");
    }
    let o = decimate(dir.path(), &["missing.wrl", "nogui", "-p", "50"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("missing.wrl"));
}

#[test]
fn the_readme_commands_use_only_options_the_usage_lists() {
    // A user copies the README's typical commands and reads `--help` for the rest: every
    // option those commands use must be one the binary's usage lists.
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
        .expect("README.md");
    assert!(readme.contains("`decimate --help` prints every option"));
    let block = readme
        .split("## Typical commands")
        .nth(1)
        .and_then(|rest| rest.split("```").nth(1))
        .expect("a fenced block under '## Typical commands'");
    let dir = tempfile::tempdir().unwrap();
    let decimate_help =
        String::from_utf8_lossy(&decimate(dir.path(), &["--help"]).stdout).into_owned();
    let metro = Command::new(env!("CARGO_BIN_EXE_metro"))
        .arg("--help")
        .output()
        .expect("run metro");
    let metro_help = String::from_utf8_lossy(&metro.stdout).into_owned();
    let (mut commands, mut options) = (0, 0);
    for line in block.lines() {
        let mut words = line.split('#').next().unwrap_or("").split_whitespace();
        let help = match words.next() {
            Some("decimate") => &decimate_help,
            Some("metro") => &metro_help,
            _ => continue,
        };
        commands += 1;
        for option in words.filter(|w| w.starts_with('-')) {
            let listed = help
                .split(|c: char| c.is_whitespace() || c == ',')
                .any(|w| w == option);
            assert!(listed, "README: '{line}': {option} is not in the usage");
            options += 1;
        }
    }
    assert!(
        commands >= 10 && options >= 20,
        "{commands} commands, {options} options"
    );
}

#[test]
fn usage_help_and_bad_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let o = decimate(dir.path(), &["--help"]);
    assert!(o.status.success());
    let help = String::from_utf8_lossy(&o.stdout);
    assert!(help.contains("decimate filename [action] [action-options]"));
    assert!(help.contains("nogui -p 100 -o output.wrl"));
    let o = decimate(dir.path(), &["--version"]);
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("decimate "));
    for args in [
        vec![],
        vec!["m.wrl", "nogui"],
        vec!["m.wrl", "nogui", "-p", "abc"],
        vec!["m.wrl", "explode"],
    ] {
        let o = decimate(dir.path(), &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains("usage:"), "{args:?}");
    }
}

/// The viewer on a machine with no display: a non-zero exit and a message that says which
/// display it tried, not a panic. A display name that no server has stands in for a
/// headless machine whatever the test runs under.
#[test]
fn gui_without_a_display_names_the_display_it_tried() {
    let dir = std::env::temp_dir().join(format!("decimate-cli-nodisplay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let out = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args([asset("test004.wrl").as_str(), "gui"])
        .current_dir(&dir)
        .env("DISPLAY", ":9999")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run decimate");
    let _ = std::fs::remove_dir_all(&dir);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "stderr: {err}");
    assert!(
        err.contains("cannot open the X11 display (DISPLAY=:9999)"),
        "stderr: {err}"
    );
    assert!(!err.contains("panicked"), "stderr: {err}");
}

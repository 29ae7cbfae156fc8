//! `--progressive` on the command line: the usage errors that write nothing, an unwritable
//! file, and a `.pm` file as input rebuilding the level a count asks for.

use std::process::Output;

use decimate_core::io::progressive_file::read_progressive;
use decimate_core::io::read_scene;
use decimate_core::mesh::{measure, shapes, Model};
use tempfile::TempDir;

use super::{as_built, decimate, run_progressive, stderr, write_input};

/// Runs `decimate in.wrl nogui -p 50 ARGS` in a fresh folder holding a small cube as
/// `in.wrl`; the folder and what the command did.
fn on_a_cube(args: &[&str]) -> (TempDir, Output) {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("temporary directory: {e}"));
    write_input(dir.path(), vec![shapes::cube(4, 1.0)]);
    let o = decimate(
        dir.path(),
        &[&["in.wrl", "nogui", "-p", "50"], args].concat(),
    );
    (dir, o)
}

#[test]
fn schroeder_with_progressive_is_a_usage_error_and_writes_nothing() {
    let (dir, o) = on_a_cube(&["-a", "schroeder", "--progressive", "x.pm"]);
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
    let (_dir, o) = on_a_cube(&["--progressive", "no/such/x.pm"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("no/such/x.pm"), "{}", stderr(&o));
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

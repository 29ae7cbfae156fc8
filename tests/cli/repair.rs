//! Damaged input as a user brings it: repaired before decimation, with every repair counted
//! on stderr.

use decimate_core::io::read_scene;
use decimate_core::mesh::measure;

use crate::support::binary::decimate;

/// An octahedron (six corners at the unit axes) as an OFF file with two faces turned
/// inside out, one face twice, a face with a repeated corner, one with collinear corners,
/// an unused vertex (which the reader never keeps: faces are built corner by corner; the
/// collinear face's middle corner is what goes unused) and two copies of the +z corner 1e-4 apart (one for the upper faces
/// facing -x, one for the rest).
const DAMAGED_OCTAHEDRON: &str = "OFF
9 12 0
1 0 0
-1 0 0
0 1 0
0 -1 0
0 0 1
0 0 -1
0.5 0 0
5 5 5
0.0001 0 1
3 0 2 4
3 1 2 8
3 1 3 8
3 3 0 4
3 2 0 5
3 1 2 5
3 3 5 1
3 0 3 5
3 0 2 4
3 0 0 5
3 0 6 1
3 0 3 5
";

#[test]
fn damaged_input_is_repaired_and_every_repair_counted() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("oct.off"), DAMAGED_OCTAHEDRON).unwrap();
    let out = decimate(
        dir.path(),
        &[
            "oct.off",
            "nogui",
            "-p",
            "0",
            "-o",
            "out.off",
            "--weld-tolerance",
            "0.01%",
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let line = err.lines().find(|l| l.starts_with("repaired input:"));
    assert_eq!(
        line,
        Some(
            "repaired input: 1 vertex welded within the tolerance, 2 triangles with no area \
             removed, 2 duplicate triangles removed, 2 triangles flipped to face like their \
             neighbours, 1 unused vertex removed"
        ),
        "{err}"
    );
    let scene = read_scene(&dir.path().join("out.off")).unwrap().scene;
    let m = &scene.models[0];
    assert_eq!((m.positions.len(), m.triangles.len()), (6, 8));
    assert!(
        (measure::volume(m) - 4.0 / 3.0).abs() < 1e-4,
        "{}",
        measure::volume(m)
    );
    assert_eq!(measure::boundary_loops(m), 0);
}

#[test]
fn without_a_tolerance_near_duplicates_stay_apart_and_nothing_is_said_of_welding() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("oct.off"), DAMAGED_OCTAHEDRON).unwrap();
    let out = decimate(
        dir.path(),
        &["oct.off", "nogui", "-p", "0", "-o", "out.off"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("welded"), "{err}");
    let scene = read_scene(&dir.path().join("out.off")).unwrap().scene;
    let m = &scene.models[0];
    // The +z corner's two copies stay apart: two open borders where they meet.
    assert_eq!((m.positions.len(), m.triangles.len()), (7, 8));
}

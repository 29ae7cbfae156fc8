//! Our VRML 2.0 output is read by an independent reader — VTK's `vtkVRMLImporter` (Debian's
//! `python3-vtk9`) — with the shapes and triangles we wrote: the report's models decimated
//! by the binary, and a two-shape coloured scene with a transform.
//!
//! Needs `/usr/bin/python3` with VTK. CI installs it (`.ci/run`, `tools/setup`); without it
//! the test fails when `CI` is set and is skipped with a notice otherwise.

use std::path::Path;
use std::process::Command;

const CHECK: &str = r#"
import sys, vtk
vtk.vtkObject.GlobalWarningDisplayOff()
imp = vtk.vtkVRMLImporter()
imp.SetFileName(sys.argv[1])
imp.Update()
actors = imp.GetRenderer().GetActors()
actors.InitTraversal()
for _ in range(actors.GetNumberOfItems()):
    pd = actors.GetNextActor().GetMapper().GetInput()
    tris = vtk.vtkTriangleFilter()
    tris.SetInputData(pd)
    tris.Update()
    print(tris.GetOutput().GetNumberOfPolys())
"#;

fn vtk_available() -> bool {
    Command::new("/usr/bin/python3")
        .args(["-c", "import vtk"])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Triangle counts of each shape VTK reads from `file`, sorted.
fn vtk_triangles(file: &Path) -> Vec<usize> {
    let o = Command::new("/usr/bin/python3")
        .args(["-c", CHECK])
        .arg(file)
        .output()
        .expect("run python3");
    assert!(
        o.status.success(),
        "VTK failed on {}: {}",
        file.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    let mut counts: Vec<usize> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| l.trim().parse().ok())
        .collect();
    counts.sort_unstable();
    counts
}

/// Triangle counts of each model our reader sees, sorted.
fn our_triangles(file: &Path) -> Vec<usize> {
    let scene = decimate::io::read_scene(file).expect("our reader").scene;
    let mut counts: Vec<usize> = scene.models.iter().map(|m| m.triangles.len()).collect();
    counts.sort_unstable();
    counts
}

#[test]
fn vtk_reads_what_we_write() {
    if !vtk_available() {
        assert!(
            std::env::var_os("CI").is_none(),
            "VTK for Python is missing: apt-get install python3-vtk9"
        );
        eprintln!("skipped: VTK for Python is missing (apt-get install python3-vtk9)");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let scene = "#VRML V2.0 utf8
DEF red Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }
  geometry IndexedFaceSet {
    coord Coordinate { point [ 0 0 0, 1 0 0, 2 0 0, 0 1 0, 1 1 0, 2 1 0, 0 2 0, 1 2 0, 2 2 0 ] }
    color Color { color [ 1 0 0, 0 1 0, 0 0 1, 1 1 0 ] } colorPerVertex FALSE
    coordIndex [ 0 1 4 3 -1, 1 2 5 4 -1, 3 4 7 6 -1, 4 5 8 7 -1 ] } }
Transform { translation 5 0 0 rotation 0 0 1 0.5 scale 2 2 2 children [
  DEF cube Shape { geometry Box { size 1 1 1 } } ] }
";
    std::fs::write(dir.path().join("scene.wrl"), scene).unwrap();
    let mut inputs: Vec<_> = (1..=6)
        .map(|i| assets.join(format!("test00{i}.wrl")))
        .collect();
    inputs.push(dir.path().join("scene.wrl"));
    for (i, input) in inputs.iter().enumerate() {
        let out = dir.path().join(format!("out{i}.wrl"));
        let o = Command::new(env!("CARGO_BIN_EXE_decimate"))
            .arg(input)
            .args(["nogui", "-p", "50", "-q", "-o"])
            .arg(&out)
            .output()
            .expect("run decimate");
        assert!(
            o.status.success(),
            "{}: {}",
            input.display(),
            String::from_utf8_lossy(&o.stderr)
        );
        let ours = our_triangles(&out);
        assert!(!ours.is_empty(), "{}", input.display());
        assert_eq!(
            vtk_triangles(&out),
            ours,
            "{}: VTK disagrees",
            input.display()
        );
    }
}

//! Our VRML 2.0 output is read by an independent reader — VTK's `vtkVRMLImporter` (Debian's
//! `python3-vtk9`) — with the shapes and triangles we wrote: the report's models decimated
//! by the binary, a two-shape coloured scene with a transform, and texture coordinates (a
//! seamed grid, a textured sphere) as we wrote them.
//!
//! Needs `/usr/bin/python3` with VTK. CI installs it (`.ci/run`, `tools/setup --test`); without it
//! the test fails when `CI` is set and is skipped with a notice otherwise.

use std::path::Path;
use std::process::Command;

/// A Python program that imports the VRML file named by its argument with VTK and runs
/// `per_shape` (indented, with the shape's polygon data in `pd`) for every shape.
fn vtk_script(per_shape: &str) -> String {
    format!("{IMPORT}{per_shape}")
}

const IMPORT: &str = r#"
import sys, vtk
vtk.vtkObject.GlobalWarningDisplayOff()
imp = vtk.vtkVRMLImporter()
imp.SetFileName(sys.argv[1])
imp.Update()
actors = imp.GetRenderer().GetActors()
actors.InitTraversal()
for _ in range(actors.GetNumberOfItems()):
    pd = actors.GetNextActor().GetMapper().GetInput()
"#;

const CHECK: &str = r#"    tris = vtk.vtkTriangleFilter()
    tris.SetInputData(pd)
    tris.Update()
    print(tris.GetOutput().GetNumberOfPolys())
"#;

/// True when VTK for Python is there; without it a test fails under CI and is skipped
/// with a notice otherwise.
fn vtk_available() -> bool {
    let there = Command::new("/usr/bin/python3")
        .args(["-c", "import vtk"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !there {
        assert!(
            std::env::var_os("CI").is_none(),
            "VTK for Python is missing: apt-get install python3-vtk9"
        );
        eprintln!("skipped: VTK for Python is missing (apt-get install python3-vtk9)");
    }
    there
}

/// What the VTK program running `per_shape` prints for `file`; fails when VTK fails.
fn run_vtk(per_shape: &str, file: &Path) -> String {
    let o = Command::new("/usr/bin/python3")
        .arg("-c")
        .arg(vtk_script(per_shape))
        .arg(file)
        .output()
        .expect("run python3");
    assert!(
        o.status.success(),
        "VTK failed on {}: {}",
        file.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Runs `decimate INPUT nogui ARGS -q -o OUT`, which must succeed.
fn decimate_to(input: &Path, args: &[&str], out: &Path) {
    let o = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .arg(input)
        .arg("nogui")
        .args(args)
        .args(["-q", "-o"])
        .arg(out)
        .output()
        .expect("run decimate");
    assert!(
        o.status.success(),
        "{}: {}",
        input.display(),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Triangle counts of each shape VTK reads from `file`, sorted.
fn vtk_triangles(file: &Path) -> Vec<usize> {
    let mut counts: Vec<usize> = run_vtk(CHECK, file)
        .lines()
        .filter_map(|l| l.trim().parse().ok())
        .collect();
    counts.sort_unstable();
    counts
}

/// Triangle counts of each model our reader sees, sorted.
fn our_triangles(file: &Path) -> Vec<usize> {
    let scene = decimate_core::io::read_scene(file)
        .expect("our reader")
        .scene;
    let mut counts: Vec<usize> = scene.models.iter().map(|m| m.triangles.len()).collect();
    counts.sort_unstable();
    counts
}

#[test]
fn vtk_reads_what_we_write() {
    if !vtk_available() {
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
        decimate_to(input, &["-p", "50"], &out);
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

const TCOORDS: &str = r#"    tc = pd.GetPointData().GetTCoords()
    print(pd.GetNumberOfPoints(), tc.GetNumberOfTuples() if tc else 0)
    for i in range(pd.GetNumberOfPoints()):
        x, y, _ = pd.GetPoint(i)
        u, v = tc.GetTuple2(i) if tc else (float("nan"), float("nan"))
        print(x, y, u, v)
"#;

/// What VTK reads of the one shape in `file`: its counts of points and of texture coordinate
/// pairs, and each point's (x, y, u, v).
fn vtk_texture_coordinates(file: &Path) -> (Vec<usize>, Vec<[f64; 4]>) {
    let text = run_vtk(TCOORDS, file);
    let mut lines = text.lines();
    let counts = lines
        .next()
        .expect("one shape")
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    let points = lines
        .map(|line| {
            let [x, y, u, v] = line
                .split_whitespace()
                .map(|w| w.parse::<f64>().unwrap())
                .collect::<Vec<_>>()[..]
            else {
                panic!("{line}")
            };
            [x, y, u, v]
        })
        .collect();
    (counts, points)
}

#[test]
fn vtk_reads_our_texture_coordinates() {
    if !vtk_available() {
        return;
    }
    // A flat 4 × 4 grid, u = x and v = y, with a seam at x = 0.5: the right half's
    // coordinates are shifted by 2 in u, so its points there have two pairs.
    let mut points = String::new();
    let mut uvs = String::new();
    let (mut faces, mut uv_faces) = (String::new(), String::new());
    for j in 0..=4 {
        for i in 0..=4 {
            points += &format!("{} {} 0, ", i as f32 / 4.0, j as f32 / 4.0);
        }
    }
    for shift in [0.0, 2.0] {
        for j in 0..=4 {
            for i in 0..=4 {
                uvs += &format!("{} {}, ", i as f32 / 4.0 + shift, j as f32 / 4.0);
            }
        }
    }
    for j in 0..4 {
        for i in 0..4 {
            let q = [j * 5 + i, j * 5 + i + 1, j * 5 + i + 6, j * 5 + i + 5];
            let s = if i >= 2 { 25 } else { 0 };
            faces += &format!("{} {} {} {} -1, ", q[0], q[1], q[2], q[3]);
            uv_faces += &format!("{} {} {} {} -1, ", q[0] + s, q[1] + s, q[2] + s, q[3] + s);
        }
    }
    let scene = format!(
        "#VRML V2.0 utf8\nShape {{ appearance Appearance {{ texture ImageTexture {{ url \"grid.png\" repeatS FALSE }} }}\n\
         geometry IndexedFaceSet {{ coord Coordinate {{ point [ {points} ] }} coordIndex [ {faces} ]\n\
         texCoord TextureCoordinate {{ point [ {uvs} ] }} texCoordIndex [ {uv_faces} ] }} }}\n"
    );
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("grid.wrl");
    std::fs::write(&input, scene).unwrap();
    for algorithm in ["schroeder", "qem"] {
        let out = dir.path().join(format!("{algorithm}.wrl"));
        decimate_to(&input, &["-a", algorithm, "-p", "40"], &out);
        // The clamped texture is written as such, and VTK reads past it.
        let written = std::fs::read_to_string(&out).unwrap();
        assert!(written.contains("repeatS FALSE"), "{algorithm}");
        let (counts, points) = vtk_texture_coordinates(&out);
        let ours = decimate_core::io::read_scene(&out).unwrap().scene;
        // 30 vertices (25 points, 5 of them twice) less 40 %.
        assert_eq!(ours.models[0].positions.len(), 18, "{algorithm}");
        assert_eq!(
            counts,
            [18, 18],
            "{algorithm}: VTK's points and coordinate pairs"
        );
        for [x, y, u, v] in points {
            let shift = if u > 1.5 { 2.0 } else { 0.0 };
            assert!(
                (u - shift - x).abs() < 1e-5 && (v - y).abs() < 1e-5,
                "{algorithm}: VTK maps ({x}, {y}) to ({u}, {v})"
            );
        }
    }
}

#[test]
fn vtk_reads_the_coordinates_of_a_textured_sphere_we_decimated() {
    if !vtk_available() {
        return;
    }
    // A VRML 2.0 Sphere under a texture makes its own coordinates (v from the bottom pole
    // to the top); vertex removal keeps the kept points' coordinates as they were.
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("sphere.wrl");
    std::fs::write(
        &input,
        "#VRML V2.0 utf8\nShape { appearance Appearance { texture ImageTexture { url \"c.png\" } }\n\
         geometry Sphere { radius 2 } }\n",
    )
    .unwrap();
    let out = dir.path().join("out.wrl");
    decimate_to(&input, &["-a", "schroeder", "-p", "50"], &out);
    let (counts, points) = vtk_texture_coordinates(&out);
    let ours = decimate_core::io::read_scene(&out).unwrap().scene;
    let n = ours.models[0].positions.len();
    assert!(n < 238, "decimated: {n} vertices");
    assert_eq!(counts, [n, n], "VTK's points and coordinate pairs");
    for [_, y, u, v] in points {
        let expected = 1.0 - (y / 2.0).clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
        assert!(
            (0.0..=1.0).contains(&u) && (v - expected).abs() < 1e-4,
            "VTK maps a point at height {y} to ({u}, {v})"
        );
    }
}

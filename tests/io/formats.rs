//! OBJ, STL and OFF: hand-written files for the tricky syntax, round trips through our
//! writers, malformed inputs failing with file and line (or record), the binary writing each
//! format by the `-o` extension, and VTK reading our OBJ and STL output.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::support::texture::textured_corners;

use decimate_core::io::{parse_bytes, read_scene, write_scene, ReadError, ReadOutcome};
use decimate_core::mesh::build::build_scene;
use decimate_core::mesh::{Attribute, Scene};
use glam::Vec3;

fn read(name: &str, src: &[u8]) -> ReadOutcome {
    parse_bytes(src.to_vec(), Path::new(name)).unwrap_or_else(|e| panic!("{e}"))
}

fn area(scene: &Scene) -> f32 {
    let mut a = 0.0;
    for m in &scene.models {
        for t in &m.triangles {
            let [p, q, r] = t.map(|i| m.positions[i as usize]);
            a += (q - p).cross(r - p).length() / 2.0;
        }
    }
    a
}

/// Triangle normals' sum (world): orientation survives a round trip when this does.
fn normal_sum(scene: &Scene) -> Vec3 {
    let mut n = Vec3::ZERO;
    for m in &scene.models {
        let w: Vec<Vec3> = m
            .positions
            .iter()
            .map(|&p| m.transform.transform_point3(p))
            .collect();
        for t in &m.triangles {
            let [p, q, r] = t.map(|i| w[i as usize]);
            n += (q - p).cross(r - p);
        }
    }
    n
}

#[test]
fn obj_negative_indices_normals_groups_and_skipped_statements() {
    let src = b"# a quad, a coloured triangle, an empty group
mtllib scene.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vn 0 0 1
vt 0 0
g first
usemtl red
usemtl blue
f -4//1 -3//1 -2//1 -1//1
g nothing here
o second
v 0 0 1 1 0 0
v 1 0 1 0 1 0
v 0 1 1 0 0 1
s 1
l 1 2
f 5/1/1 6/1 \\
  7
";
    let out = read("t.obj", src);
    let s = &out.scene;
    let names: Vec<&str> = s.models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["first", "second"]);
    assert_eq!(s.models[0].triangles.len(), 2);
    assert_eq!(s.models[1].triangles.len(), 1);
    assert_eq!(s.models[1].positions[0], Vec3::new(0.0, 0.0, 1.0));
    let Some(Attribute::PerVertex(c)) = &s.models[1].colors else {
        panic!("no per-vertex colours: {:?}", s.models[1].colors)
    };
    assert_eq!(c, &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    // One warning per kind: s, l; and one for the second model, whose third corner has no
    // texture coordinate (so it has none). Materials are read, not skipped: the last
    // `usemtl` before a face counts and carries over `o`; the library is handed back.
    assert_eq!(out.warnings.len(), 3, "{:?}", out.warnings);
    assert!(out.warnings[2]
        .message
        .starts_with("second: some face corners have texture"));
    assert_eq!(s.models[1].texcoords, None);
    assert!(!out.warnings.iter().any(|w| w.message.contains("mtl")));
    let materials: Vec<Option<&str>> = s.models.iter().map(|m| m.material.as_deref()).collect();
    assert_eq!(materials, [Some("blue"), Some("blue")]);
    assert_eq!(out.material_libraries, ["scene.mtl"]);
    // Counter-clockwise seen from +z.
    assert!(normal_sum(s).z > 0.0);
}

const L_SHAPE: [[f32; 2]; 6] = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]];

#[test]
fn concave_polygons_keep_their_area_in_obj_and_off() {
    let mut obj = String::new();
    let mut off = String::from("OFF\n6 1 0\n");
    for [x, y] in L_SHAPE {
        obj += &format!("v {x} {y} 0\n");
        off += &format!("{x} {y} 0\n");
    }
    obj += "f 1 2 3 4 5 6\n";
    off += "6 0 1 2 3 4 5\n";
    for (name, src) in [("l.obj", obj), ("l.off", off)] {
        let s = read(name, src.as_bytes()).scene;
        assert_eq!(s.triangle_count(), 4, "{name}");
        assert!((area(&s) - 3.0).abs() < 1e-6, "{name}: area {}", area(&s));
        assert!(normal_sum(&s).z > 0.0, "{name}");
    }
}

#[test]
fn ascii_stl_with_two_solids_gives_two_models() {
    let src = b"solid first part
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 1 0 0
      vertex 0 1 0
    endloop
  endfacet
  facet normal 0 0 1
    outer loop
      vertex 1 0 0
      vertex 1 1 0
      vertex 0 1 0
    endloop
  endfacet
endsolid first part
SOLID second
 FACET NORMAL 0 0 1 OUTER LOOP VERTEX 5 5 5 VERTEX 6 5 5 VERTEX 5 6 5 ENDLOOP ENDFACET
ENDSOLID second
";
    let s = read("two.stl", src).scene;
    let names: Vec<&str> = s.models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["first part", "second"]);
    assert_eq!(s.models[0].triangles.len(), 2);
    assert_eq!(s.models[0].positions.len(), 6, "per-facet vertices");
    let s = build_scene(s, true);
    assert_eq!(s.models[0].positions.len(), 4, "welded");
    assert_eq!(s.models[1].positions.len(), 3);
    // Sniffed without the extension too.
    assert_eq!(read("two", src).scene.models.len(), 2);
}

/// A binary STL of `tris`, with `header` at the start of its 80 header bytes.
fn binary_stl(header: &[u8], tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = vec![b' '; 80];
    b[..header.len()].copy_from_slice(header);
    b.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        b.extend([0f32; 3].iter().flat_map(|v| v.to_le_bytes()));
        b.extend(t.iter().flatten().flat_map(|v| v.to_le_bytes()));
        b.extend([0u8; 2]);
    }
    b
}

const TETRA: [[[f32; 3]; 3]; 4] = [
    [[0., 0., 0.], [0., 1., 0.], [1., 0., 0.]],
    [[0., 0., 0.], [1., 0., 0.], [0., 0., 1.]],
    [[0., 0., 0.], [0., 0., 1.], [0., 1., 0.]],
    [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
];

#[test]
fn binary_stl_whose_header_starts_with_solid() {
    let bytes = binary_stl(b"solid tetra exported by some CAD tool", &TETRA);
    for name in ["tetra.stl", "tetra.bin"] {
        let s = read(name, &bytes).scene;
        assert_eq!(s.models.len(), 1);
        assert_eq!(s.models[0].name, "tetra exported by some CAD tool");
        assert_eq!(s.triangle_count(), 4);
        let s = build_scene(s, true);
        assert_eq!(s.vertex_count(), 4);
        // A closed, outward-facing tetrahedron: volume 1/6.
        let m = &s.models[0];
        let vol: f32 = m
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                a.dot(b.cross(c)) / 6.0
            })
            .sum();
        assert!((vol - 1.0 / 6.0).abs() < 1e-6, "volume {vol}");
    }
}

#[test]
fn coff_vertex_colours_and_off_face_colours() {
    let src = b"COFF
# integer colours are 0..255, float ones 0..1
4 2 5
0 0 0 255 0 0 255
1 0 0 0 255 0 255
1 1 0 0 0 1.0 1.0
0 1 0 0.5 0.5 0.5 1
3 0 1 2
3 0 2 3
";
    let s = read("c.off", src).scene;
    let Some(Attribute::PerVertex(c)) = &s.models[0].colors else {
        panic!("{:?}", s.models[0].colors)
    };
    assert_eq!(
        c,
        &[[1., 0., 0.], [0., 1., 0.], [0., 0., 1.], [0.5, 0.5, 0.5]]
    );
    let src = b"NOFF 4 1 0
0 0 0  0 0 1
1 0 0  0 0 1
1 1 0  0 0 1
0 1 0  0 0 1
4 0 1 2 3  0 0 255
";
    let s = read("n.off", src).scene;
    assert_eq!(s.triangle_count(), 2);
    assert_eq!(
        s.models[0].colors,
        Some(Attribute::PerFace(vec![[0., 0., 1.]; 2]))
    );
}

#[test]
fn off_texture_coordinates_are_read_and_round_trip_exactly() {
    // ST with colours and with normals: s t come last on the line.
    let src = b"STCOFF
4 2 0
0 0 0  255 0 0 255  0.125 0.25
1 0 0  0 255 0 255  0.333333343 0.5
1 1 0  0 0 255 255  0.1 1e-7
0 1 0  9 9 9 255  -0 2
3 0 1 2
3 0 2 3
";
    let out = read("st.off", src);
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    let m = &out.scene.models[0];
    assert_eq!(
        m.texcoords.as_deref(),
        Some(&[[0.125, 0.25], [1.0 / 3.0, 0.5], [0.1, 1e-7], [-0.0, 2.0]][..])
    );
    assert!(matches!(m.colors, Some(Attribute::PerVertex(_))));
    let s = read(
        "n.off",
        b"STNOFF 3 1 0\n0 0 0 0 0 1 0.5 0.5\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0 1\n3 0 1 2\n",
    )
    .scene;
    assert_eq!(
        s.models[0].texcoords.as_deref(),
        Some(&[[0.5, 0.5], [1.0, 0.0], [0.0, 1.0]][..])
    );

    // Written back: STCOFF with the colour before s t, and the same corners exactly.
    let mut text = Vec::new();
    decimate_core::io::off::write_off_to(&mut text, &out.scene).unwrap();
    assert!(
        text.starts_with(b"STCOFF\n"),
        "{}",
        String::from_utf8_lossy(&text)
    );
    let back = read("back.off", &text);
    assert_eq!(textured_corners(&back.scene), textured_corners(&out.scene));
    assert_eq!(back.scene.models[0].colors, m.colors);

    // Without colours: STOFF; a seam (point 0 twice, other coordinates) stays cut.
    let mut model = out.scene.models[0].clone();
    model.colors = None;
    model.positions.push(model.positions[0]);
    model.texcoords.as_mut().unwrap().push([7.5, 1.0 / 3.0]);
    model.triangles[1][0] = 4;
    let scene = Scene {
        models: vec![model],
    };
    let mut text = Vec::new();
    decimate_core::io::off::write_off_to(&mut text, &scene).unwrap();
    assert!(
        text.starts_with(b"STOFF\n"),
        "{}",
        String::from_utf8_lossy(&text)
    );
    let back = read("seam.off", &text);
    assert_eq!(back.scene.vertex_count(), 5);
    assert_eq!(textured_corners(&back.scene), textured_corners(&scene));
}

/// Two coloured shapes, one translated and one mirrored.
const SCENE: &str = "#VRML V2.0 utf8
DEF A Transform { translation 0 0 5 children [ Shape { geometry IndexedFaceSet {
  coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0, 2 0 0, 2 1 0 ] }
  color Color { color [ 1 0 0, 0 1 0, 0 0 1, 1 1 0, 0.25 0.5 0.75, 0 0 0 ] }
  coordIndex [ 0 1 2 3 -1 1 4 5 2 -1 ] } } ] }
DEF B Transform { scale -1 1 1 children [ Shape { geometry IndexedFaceSet {
  coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 0 0 1 ] }
  color Color { color [ 1 1 1, 1 0 1, 0 1 1, 0.5 0.5 0.5 ] }
  coordIndex [ 0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3 -1 ] } } ] }
";

fn world_bounds(s: &Scene) -> (Vec3, Vec3) {
    let mut lo = Vec3::splat(f32::MAX);
    let mut hi = Vec3::splat(f32::MIN);
    for m in &s.models {
        for &p in &m.positions {
            let p = m.transform.transform_point3(p);
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (lo, hi)
}

#[test]
fn each_format_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let original = build_scene(
        parse_bytes(SCENE.as_bytes().to_vec(), Path::new("s.wrl"))
            .unwrap()
            .scene,
        true,
    );
    assert_eq!(original.models.len(), 2);
    for ext in ["obj", "stl", "off", "ply", "wrl"] {
        let path = dir.path().join(format!("out.{ext}"));
        write_scene(&original, &path).unwrap();
        let back = build_scene(read_scene(&path).unwrap().scene, true);
        assert_eq!(back.triangle_count(), 8, "{ext}");
        assert_eq!(back.vertex_count(), 10, "{ext}");
        assert_eq!(world_bounds(&back), world_bounds(&original), "{ext}");
        let n = normal_sum(&back);
        assert!(
            (n - normal_sum(&original)).length() < 1e-5,
            "{ext}: orientation {n}"
        );
        if matches!(ext, "obj" | "wrl") {
            let per_model: Vec<usize> = back.models.iter().map(|m| m.triangles.len()).collect();
            assert_eq!(per_model, [4, 4], "{ext}");
        } else {
            assert_eq!(back.models.len(), 1, "{ext}: one file, models concatenated");
        }
        // Colours survive where the format has them, exactly (shortest round-trip floats).
        let colors = |s: &Scene| -> Vec<[u32; 3]> {
            let mut v: Vec<[u32; 3]> = s
                .models
                .iter()
                .flat_map(|m| match &m.colors {
                    Some(Attribute::PerVertex(c)) => c.clone(),
                    _ => Vec::new(),
                })
                .map(|c| c.map(f32::to_bits))
                .collect();
            v.sort_unstable();
            v
        };
        match ext {
            "obj" | "off" | "wrl" => assert_eq!(colors(&back), colors(&original), "{ext}"),
            "stl" => assert!(back.models[0].colors.is_none()),
            _ => {}
        }
    }
}

fn fails(name: &str, src: &[u8]) -> ReadError {
    match parse_bytes(src.to_vec(), Path::new(name)) {
        Ok(o) => panic!("{name} was read: {} triangles", o.scene.triangle_count()),
        Err(e) => e,
    }
}

#[test]
fn malformed_files_fail_with_file_and_line() {
    let cases: &[(&str, &[u8], &str)] = &[
        ("a.obj", b"v 0 0 0\nv 1 0 0\nf 1 2 3\n", "a.obj:3: vertex index 3 is out of range"),
        ("a.obj", b"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 -4\n", "a.obj:4: vertex index -4 is out of range: 3 vertices are defined above this line"),
        ("a.obj", b"v 0 0 0\nf 0 1 1\n", "a.obj:2: vertex index 0 is invalid"),
        ("a.obj", b"# x\nv 0 0 nan\n", "a.obj:2: a vertex's z is not a finite number"),
        ("a.obj", b"v 1 2\n", "a.obj:1: missing a vertex's z"),
        ("a.obj", b"v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 two 3\n", "a.obj:4: expected a vertex index, found 'two'"),
        ("a.obj", b"v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//2 2//1 3//1\n", "a.obj:5: normal index 2 is out of range"),
        ("a.obj", b"v 0 0 0\n", "a.obj:1: the OBJ file has no faces"),
        ("a.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n", "a.off:4: unexpected end of file after 2 of 3 vertices"),
        ("a.off", b"OFF\n99999999999 1 0\n", "a.off:2: the file declares 99999999999 vertices, more than its 20 bytes"),
        ("a.off", b"OFF\n0 0 0\n", "a.off:2: the file declares 0 vertices and 0 faces"),
        ("a.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "a.off:6: face 0: vertex index '7' is not in 0..3"),
        ("a.off", b"OFF\n3 1 0\n0 0 zz\n1 0 0\n0 1 0\n3 0 1 2\n", "a.off:3: expected a number for a vertex's z, found 'zz'"),
        ("a.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n5 0 1 2\n", "a.off:6: expected 'n i1 … in' for face 0"),
        ("a.off", b"4OFF\n", "a.off:1: '4OFF' (4-D or n-D OFF) is not supported"),
        ("a.off", b"STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1\n0 1 0 0 1\n3 0 1 2\n", "a.off:4: expected texture coordinates 's t' at the end of an STOFF vertex line, found 4 values"),
        ("a.off", b"STCOFF\n3 1 0\n0 0 0 1 0 0 1 0 0\n1 0 0 1 0 0 1 1 y\n", "a.off:4: expected a number for a texture coordinate, found 'y'"),
        ("a.stl", b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n", "a.stl:3: a facet has 2 vertices"),
        ("a.stl", b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 x\n", "a.stl:5: expected a number for a vertex's z, found 'x'"),
        ("a.stl", b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "a.stl:4: unexpected end of file inside a facet"),
        ("a.stl", b"solid a\nendsolid a\n", "a.stl:2: the STL file has no facets"),
    ];
    for (name, src, want) in cases {
        let e = fails(name, src);
        assert!(matches!(e, ReadError::Syntax { .. }), "{e:?}");
        assert!(e.to_string().starts_with(want), "got  {e}\nwant {want}");
    }
}

#[test]
fn broken_binary_stl_names_the_record() {
    let mut short = binary_stl(b"part", &TETRA);
    short.truncate(84 + 50 * 2 + 20);
    let e = fails("short.stl", &short);
    assert!(
        e.to_string()
            .starts_with("short.stl: record 3: the binary STL is truncated"),
        "{e}"
    );
    let mut nan = binary_stl(b"part", &TETRA);
    nan[84 + 50 + 12 + 4..84 + 50 + 12 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = fails("nan.stl", &nan);
    assert_eq!(
        e.to_string(),
        "nan.stl: record 2: a vertex coordinate is not finite (NaN)"
    );
    let mut long = binary_stl(b"part", &TETRA);
    long.extend([0u8; 7]);
    let e = fails("long.stl", &long);
    assert!(
        e.to_string()
            .starts_with("long.stl:1: the binary STL has 7 bytes after"),
        "{e}"
    );
    let e = fails("none.stl", &binary_stl(b"part", &[]));
    assert!(e.to_string().contains("no triangles"), "{e}");
    // A huge count in a small file is refused before anything is allocated.
    let mut huge = binary_stl(b"part", &TETRA);
    huge[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(matches!(
        fails("huge.stl", &huge),
        ReadError::Record { record: 5, .. }
    ));
}

#[test]
fn every_prefix_of_every_fixture_reads_or_fails_cleanly() {
    let fixtures: Vec<(&str, Vec<u8>)> = vec![
        ("p.obj", b"v 0 0 0 1 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\ng x\nf -1 -2 -3\n".to_vec()),
        ("p.off", b"COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2 1 1 1\n".to_vec()),
        ("t.off", b"STCOFF\n3 1 0\n0 0 0 1 0 0 0.5 0.5\n1 0 0 0 1 0 1 0\n0 1 0 0 0 1 0 1\n3 0 1 2\n".to_vec()),
        ("p.stl", b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n".to_vec()),
        ("q.stl", binary_stl(b"solid q", &TETRA)),
    ];
    for (name, src) in fixtures {
        read(name, &src);
        for cut in 0..src.len() {
            // Ok or Err both fine: no panic, and errors name the file.
            if let Err(e) = parse_bytes(src[..cut].to_vec(), Path::new(name)) {
                assert!(e.to_string().starts_with(name), "{e}");
            }
        }
    }
}

fn decimate_to(dir: &Path, out: &str) -> PathBuf {
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/test004.wrl");
    let o = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .current_dir(dir)
        .arg(&input)
        .args(["nogui", "-p", "90", "-q", "-o", out])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    dir.join(out)
}

#[test]
fn the_binary_writes_the_format_the_extension_names() {
    let dir = tempfile::tempdir().unwrap();
    for (out, magic) in [
        ("out.obj", &b"# written by decimate"[..]),
        ("out.stl", &b"binary STL written by decimate"[..]),
        ("out.off", &b"OFF\n"[..]),
        ("out.ply", &b"ply\n"[..]),
        ("out.wrl", &b"#VRML V2.0 utf8"[..]),
        ("out.vrml", &b"#VRML V2.0 utf8"[..]),
    ] {
        let path = decimate_to(dir.path(), out);
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(magic), "{out}");
        let scene = read_scene(&path).unwrap().scene;
        // STL repeats every vertex per facet; the others share them.
        if out.ends_with(".stl") {
            assert_eq!(scene.vertex_count(), 3 * scene.triangle_count());
            assert_eq!(bytes.len(), 84 + 50 * scene.triangle_count());
        } else {
            assert_eq!(scene.vertex_count(), 60, "{out}");
        }
        assert_eq!(build_scene(scene, true).vertex_count(), 60, "{out}");
    }
}

const VTK_CHECK: &str = r#"
import sys, vtk
vtk.vtkObject.GlobalWarningDisplayOff()
r = vtk.vtkOBJReader() if sys.argv[1].endswith(".obj") else vtk.vtkSTLReader()
r.SetFileName(sys.argv[1])
r.Update()
o = r.GetOutput()
print(o.GetNumberOfPoints(), o.GetNumberOfPolys())
"#;

#[test]
fn vtk_reads_our_obj_and_stl() {
    if !Command::new("/usr/bin/python3")
        .args(["-c", "import vtk"])
        .output()
        .is_ok_and(|o| o.status.success())
    {
        assert!(
            std::env::var_os("CI").is_none(),
            "VTK for Python is missing: apt-get install python3-vtk9"
        );
        eprintln!("skipped: VTK for Python is missing (apt-get install python3-vtk9)");
        return;
    }
    // VTK has no OFF reader; our OFF output is checked by our reader only.
    let dir = tempfile::tempdir().unwrap();
    for out in ["out.obj", "out.stl"] {
        let path = decimate_to(dir.path(), out);
        let ours = read_scene(&path).unwrap().scene.triangle_count();
        let o = Command::new("/usr/bin/python3")
            .args(["-c", VTK_CHECK])
            .arg(&path)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8_lossy(&o.stdout);
        let counts: Vec<usize> = text
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect();
        // vtkSTLReader merges coincident points, like our welding.
        assert_eq!(counts, [60, ours], "{out}: VTK says {text}");
    }
}

//! Reading hand-written VRML 1.0, Open Inventor and VRML 2.0 scenes: counts, transforms,
//! instancing, Switch, triangulation, orientation, bindings, gzip.

use decimate_core::io::{parse_str, read_scene};
use decimate_core::mesh::{Attribute, Model, Scene};
use glam::Vec3;

fn parse(src: &str) -> Scene {
    match parse_str(src, "test.wrl") {
        Ok(o) => o.scene,
        Err(e) => panic!("parse failed: {e}"),
    }
}

fn world(m: &Model, i: usize) -> Vec3 {
    m.transform.transform_point3(m.positions[i])
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

/// Position of the local vertex at `p` (positions are compacted, so look it up).
fn index_of(m: &Model, p: Vec3) -> usize {
    m.positions
        .iter()
        .position(|&q| close(p, q))
        .unwrap_or_else(|| panic!("{p} not among {:?}", m.positions))
}

fn tri_normal(m: &Model, t: [u32; 3]) -> Vec3 {
    let [a, b, c] = t.map(|i| m.positions[i as usize]);
    (b - a).cross(c - a)
}

/// Signed volume of a closed mesh; positive when its triangles face outwards.
fn volume(m: &Model) -> f32 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

const CUBE_V1: &str = "#VRML V1.0 ascii
Separator {
  Coordinate3 { point [ -1 -1 -1, 1 -1 -1, -1 1 -1, 1 1 -1, -1 -1 1, 1 -1 1, -1 1 1, 1 1 1 ] }
  IndexedFaceSet { coordIndex [ 4 5 7 6 -1, 0 2 3 1 -1, 1 3 7 5 -1, 0 4 6 2 -1, 2 6 7 3 -1, 0 1 5 4 -1 ] }
}";

#[test]
fn vrml1_indexed_face_set_cube_gives_8_vertices_12_outward_triangles() {
    let s = parse(CUBE_V1);
    assert_eq!(s.models.len(), 1);
    assert_eq!(s.vertex_count(), 8);
    assert_eq!(s.triangle_count(), 12);
    assert!((volume(&s.models[0]) - 8.0).abs() < 1e-4);
}

#[test]
fn only_referenced_vertices_are_kept() {
    let s = parse(
        "#VRML V1.0 ascii
Separator {
  Coordinate3 { point [ 9 9 9, 0 0 0, 8 8 8, 1 0 0, 0 1 0, 7 7 7 ] }
  IndexedFaceSet { coordIndex [ 1, 3, 4, -1 ] }
}",
    );
    let m = &s.models[0];
    assert_eq!(m.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
}

#[test]
fn translation_rotation_scale_accumulate_in_order() {
    let s = parse(
        "#VRML V1.0 ascii
Separator {
  Translation { translation 1 2 3 }
  Rotation { rotation 0 0 1 1.5707963 }
  Scale { scaleFactor 2 2 2 }
  Coordinate3 { point [ 1 0 0, 0 1 0, 0 0 1 ] }
  IndexedFaceSet { coordIndex [ 0 1 2 -1 ] }
}",
    );
    let m = &s.models[0];
    // Local points stay local; the transform carries the scene graph.
    assert_eq!(m.positions[0], Vec3::X);
    assert!(
        close(world(m, 0), Vec3::new(1.0, 4.0, 3.0)),
        "{}",
        world(m, 0)
    );
}

#[test]
fn separator_scopes_state_and_group_does_not() {
    let s = parse(
        "#VRML V1.0 ascii
Separator {
  Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }
  Separator { Translation { translation 5 0 0 } }
  IndexedFaceSet { coordIndex [ 0 1 2 ] }
  Group { Translation { translation 0 7 0 } }
  IndexedFaceSet { coordIndex [ 0 1 2 ] }
}",
    );
    assert_eq!(s.models.len(), 2);
    assert!(close(world(&s.models[0], 1), Vec3::X));
    assert!(close(world(&s.models[1], 1), Vec3::new(1.0, 7.0, 0.0)));
}

#[test]
fn transform_separator_restores_only_the_transform() {
    let s = parse(
        "#VRML V1.0 ascii
Separator {
  TransformSeparator { Translation { translation 5 0 0 } Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] } }
  IndexedFaceSet { coordIndex [ 0 1 2 ] }
}",
    );
    assert_eq!(s.models.len(), 1);
    assert!(close(world(&s.models[0], 0), Vec3::ZERO));
}

#[test]
fn vrml1_transform_uses_center_and_scale_orientation() {
    let s = parse(
        "#VRML V1.0 ascii
Separator {
  Transform { translation 1 0 0 rotation 0 0 1 1.5707963 scaleFactor 2 1 1 center 1 0 0 }
  Coordinate3 { point [ 2 0 0, 0 0 0, 0 0 1 ] }
  IndexedFaceSet { coordIndex [ 0 1 2 ] }
}",
    );
    let m = &s.models[0];
    let p = world(m, index_of(m, Vec3::new(2.0, 0.0, 0.0)));
    assert!(close(p, Vec3::new(2.0, 2.0, 0.0)), "{p}");
}

#[test]
fn matrix_transform_is_row_major_with_translation_in_the_last_row() {
    let s = parse(
        "#VRML V1.0 ascii
Separator {
  MatrixTransform { matrix 0 1 0 0  -1 0 0 0  0 0 1 0  10 20 30 1 }
  Coordinate3 { point [ 1 0 0, 0 0 0, 0 0 1 ] }
  IndexedFaceSet { coordIndex [ 0 1 2 ] }
}",
    );
    let m = &s.models[0];
    // Row vectors: x maps to the first row (0 1 0), then the translation is added.
    assert!(
        close(world(m, 0), Vec3::new(10.0, 21.0, 30.0)),
        "{}",
        world(m, 0)
    );
    assert!(close(world(m, 1), Vec3::new(10.0, 20.0, 30.0)));
}

#[test]
fn def_use_instancing_gives_two_models() {
    let s = parse(
        "#VRML V1.0 ascii
Separator {
  DEF Tri Separator {
    Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }
    DEF Face IndexedFaceSet { coordIndex [ 0 1 2 ] }
  }
  Translation { translation 10 0 0 }
  USE Tri
}",
    );
    assert_eq!(s.models.len(), 2);
    assert_eq!(s.models[0].name, "Face");
    assert!(close(world(&s.models[1], 1), Vec3::new(11.0, 0.0, 0.0)));
    assert_eq!(s.models[0].positions, s.models[1].positions);
}

fn switch_scene(which: &str) -> Scene {
    parse(&format!(
        "#VRML V1.0 ascii
Separator {{
  Coordinate3 {{ point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] }}
  Switch {{ {which}
    IndexedFaceSet {{ coordIndex [ 0 1 2 ] }}
    IndexedFaceSet {{ coordIndex [ 0 1 2 3 ] }}
    IndexedFaceSet {{ coordIndex [ 0 2 3 ] }}
  }}
}}"
    ))
}

#[test]
fn switch_which_child_picks_one_all_or_none() {
    let s = switch_scene("whichChild 1");
    assert_eq!(s.models.len(), 1);
    assert_eq!(s.triangle_count(), 2);
    assert_eq!(switch_scene("whichChild -3").models.len(), 3);
    assert_eq!(switch_scene("").models.len(), 0);
    assert_eq!(switch_scene("whichChild 7").models.len(), 0);
}

#[test]
fn concave_l_shape_is_cut_into_four_ccw_triangles_of_its_area() {
    let s = read_scene(std::path::Path::new("tests/data/l_shape_v1.wrl"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    let m = &s.models[0];
    assert_eq!(m.positions.len(), 6);
    assert_eq!(m.triangles.len(), 4);
    let mut area = 0.0;
    for &t in &m.triangles {
        let n = tri_normal(m, t);
        assert!(n.z > 0.0, "triangle {t:?} is clockwise");
        area += n.z / 2.0;
    }
    assert!((area - 3.0).abs() < 1e-5, "area {area}");
}

#[test]
fn clockwise_faces_are_flipped_to_counter_clockwise() {
    // Seen from +z this triangle is clockwise; the file says so.
    let v1 = parse(
        "#VRML V1.0 ascii
Separator {
  ShapeHints { vertexOrdering CLOCKWISE shapeType SOLID creaseAngle 0.5 }
  Coordinate3 { point [ 0 0 0, 0 1 0, 1 0 0 ] }
  IndexedFaceSet { coordIndex [ 0 1 2 -1 ] }
}",
    );
    let m = &v1.models[0];
    assert!(tri_normal(m, m.triangles[0]).z > 0.0);
    assert!(m.solid);
    assert_eq!(m.crease_angle, Some(0.5));
    let v2 = parse(
        "#VRML V2.0 utf8
Shape { geometry IndexedFaceSet {
  coord Coordinate { point [ 0 0 0, 0 1 0, 1 0 0 ] }
  coordIndex [ 0 1 2 -1 ] ccw FALSE } }",
    );
    let m = &v2.models[0];
    assert!(tri_normal(m, m.triangles[0]).z > 0.0);
    assert!(m.solid, "VRML 2.0 solid defaults to TRUE");
}

#[test]
fn vrml1_material_bindings_per_face_per_face_indexed_per_vertex_indexed() {
    let base = |binding: &str, extra: &str| {
        parse(&format!(
            "#VRML V1.0 ascii
Separator {{
  Material {{ diffuseColor [ 1 0 0, 0 1 0, 0 0 1 ] }}
  MaterialBinding {{ value {binding} }}
  Coordinate3 {{ point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0, 2 0 0, 2 1 0 ] }}
  IndexedFaceSet {{ coordIndex [ 0 1 2 3 -1, 1 4 5 2 -1 ] {extra} }}
}}"
        ))
        .models
        .remove(0)
    };
    let (r, g, b) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    // Each quad's colour goes to both of its triangles.
    assert_eq!(
        base("PER_FACE", "").colors,
        Some(Attribute::PerFace(vec![r, r, g, g]))
    );
    assert_eq!(
        base("PER_FACE_INDEXED", "materialIndex [ 2, 0 ]").colors,
        Some(Attribute::PerFace(vec![b, b, r, r]))
    );
    // Per corner: a point given two colours (1 and 2: red or green in the first face, blue
    // in the second) becomes two vertices, one per colour, the two sides of a colour seam.
    let m = base(
        "PER_VERTEX_INDEXED",
        "materialIndex [ 0 0 1 1 -1, 2 2 2 2 -1 ]",
    );
    let Some(Attribute::PerVertex(c)) = &m.colors else {
        panic!("{:?}", m.colors)
    };
    assert_eq!(c.len(), 8);
    let colours_at = |p: Vec3| {
        let mut at: Vec<[f32; 3]> = (0..m.positions.len())
            .filter(|&v| m.positions[v] == p)
            .map(|v| c[v])
            .collect();
        at.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        at
    };
    assert_eq!(colours_at(Vec3::X), vec![b, r]);
    assert_eq!(colours_at(Vec3::new(1.0, 1.0, 0.0)), vec![b, g]);
    assert_eq!(colours_at(Vec3::new(2.0, 1.0, 0.0)), vec![b]);
    // Each face's triangles use its own copies.
    for (t, want) in m
        .triangles
        .iter()
        .zip([[r, r, g], [r, g, g], [b; 3], [b; 3]])
    {
        let mut got = t.map(|v| c[v as usize]);
        let mut want = want;
        got.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        want.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        assert_eq!(got, want, "triangle {t:?}");
    }
    // OVERALL: no colour array, the first diffuse colour.
    let m = base("OVERALL", "");
    assert_eq!(m.colors, None);
    assert_eq!(m.diffuse, r);
}

#[test]
fn vrml2_shape_with_per_face_colours_and_transform() {
    let s = read_scene(std::path::Path::new("tests/data/colored_v2.wrl"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    assert_eq!(s.models.len(), 1);
    let m = &s.models[0];
    assert_eq!(m.name, "Panel");
    assert_eq!(m.positions.len(), 6);
    assert_eq!(m.triangles.len(), 4);
    assert_eq!(m.diffuse, [0.2, 0.4, 0.6]);
    assert!(!m.solid);
    let (r, b) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    assert_eq!(m.colors, Some(Attribute::PerFace(vec![r, r, b, b])));
    assert!(close(world(m, 1), Vec3::new(1.0, 0.0, 5.0)));
}

#[test]
fn vrml2_per_vertex_colours_normals_and_nested_transforms() {
    let s = parse(
        "#VRML V2.0 utf8
Transform { scale 2 2 2 children Transform { translation 1 0 0 children [
  Shape { geometry IndexedFaceSet {
    coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }
    coordIndex [ 0 1 2 -1 ]
    color Color { color [ 1 0 0, 0 1 0, 0 0 1 ] }
    colorIndex [ 2 1 0 -1 ]
    normal Normal { vector [ 0 0 1 ] }
    normalIndex [ 0 0 0 -1 ]
  } }
] } }",
    );
    let m = &s.models[0];
    assert!(close(world(m, 0), Vec3::new(2.0, 0.0, 0.0)));
    assert_eq!(
        m.colors,
        Some(Attribute::PerVertex(vec![
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0]
        ]))
    );
    assert_eq!(m.normals, Some(Attribute::PerVertex(vec![Vec3::Z; 3])));
}

#[test]
fn vrml2_def_use_switch_and_skipped_statements() {
    let o = parse_str(
        "#VRML V2.0 utf8
PROTO Thing [ field SFFloat size 1 ] { Group { } }
EXTERNPROTO Other [ field SFInt32 n ] \"other.wrl#Other\"
DEF T Transform { children [ DEF S Shape { geometry IndexedFaceSet {
  coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] } coordIndex [ 0 1 2 ] } } ] }
Transform { translation 0 0 3 children USE S }
Switch { whichChoice 1 choice [ USE S, Shape { geometry Box { size 2 4 6 } } ] }
Thing { size 2 }
DEF Timer TimeSensor { }
ROUTE Timer.fraction_changed TO T.set_scale
Inline { url \"x.wrl\" }
Viewpoint { position 0 0 10 description \"home\" }
",
        "t.wrl",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let s = &o.scene;
    assert_eq!(s.models.len(), 3);
    assert!(close(world(&s.models[1], 0), Vec3::new(0.0, 0.0, 3.0)));
    let boxm = &s.models[2];
    assert_eq!((boxm.positions.len(), boxm.triangles.len()), (8, 12));
    assert!((volume(boxm) - 48.0).abs() < 1e-3);
    let w: Vec<String> = o.warnings.iter().map(|w| w.to_string()).collect();
    let w = w.join("\n");
    for needle in ["PROTO", "EXTERNPROTO", "ROUTE", "Inline", "'Thing'"] {
        assert!(w.contains(needle), "no warning about {needle}: {w}");
    }
    assert!(!w.contains("Viewpoint"), "{w}");
}

#[test]
fn strips_face_sets_and_quad_meshes_triangulate_with_one_orientation() {
    let s = parse(
        "#Inventor V2.1 ascii
Separator {
  Coordinate3 { point [ 0 0 0, 0 1 0, 1 0 0, 1 1 0, 2 0 0, 2 1 0, 3 0 0, 3 1 0, 4 0 0 ] }
  IndexedTriangleStripSet { coordIndex [ 1 0 3 2 5 -1 ] }
  TriangleStripSet { startIndex 1 numVertices [ 4 ] }
  FaceSet { numVertices [ 3, 4 ] }
  Coordinate3 { point [ 0 0 0, 1 0 0, 2 0 0, 0 1 0, 1 1 0, 2 1.5 0, 0 2 0, 1 2 0, 2 2 0 ] }
  QuadMesh { verticesPerRow 3 verticesPerColumn 3 }
}",
    );
    let counts: Vec<(usize, usize)> = s
        .models
        .iter()
        .map(|m| (m.positions.len(), m.triangles.len()))
        .collect();
    // ITSS over 1 0 3 2 5 (3 triangles), TSS of 4 vertices (2), FaceSet 3+4 corners (1+2),
    // QuadMesh 3x3 (8).
    assert_eq!(counts, vec![(5, 3), (4, 2), (7, 3), (9, 8)]);
    for m in &s.models[..2] {
        for &t in &m.triangles {
            assert!(
                tri_normal(m, t).z > 0.0,
                "{} has a flipped strip triangle",
                m.name
            );
        }
    }
    let q = &s.models[3];
    let first = tri_normal(q, q.triangles[0]);
    assert!(q
        .triangles
        .iter()
        .all(|&t| tri_normal(q, t).dot(first) >= 0.0));
}

#[test]
fn inventor_vertex_property_packed_colours_and_skipped_extras() {
    let o = parse_str(
        "#Inventor V2.1 ascii
Separator {
  Info { string \"made by hand { with braces }\" }
  Label { label \"x\" }
  PerspectiveCamera { position 0 0 5 }
  DirectionalLight { }
  ComplexityEnvironment { }
  DrawStyle { style LINES }
  Texture2 { filename \"\" }
  LightModel { model BASE_COLOR }
  Material { ambientColor 0.2 0.2 0.2 ~ diffuseColor 0.5 0.5 0.5 }
  Frobnicator { fields [ SFFloat a ] a 1 }
  Frobnicator { fields [ SFFloat a ] a 2 }
  DEF +0 IndexedFaceSet {
    vertexProperty VertexProperty {
      vertex [ 0 0 0, 1 0 0, 0 1 0 ]
      orderedRGBA [ 0xff0000ff, 0x00ff00ff, 0x0000ffff ]
      materialBinding PER_VERTEX_INDEXED
    }
    coordIndex [ 0, 1, 2, -1 ]
  }
  USE +0
}",
        "t.iv",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(o.scene.models.len(), 2);
    let m = &o.scene.models[0];
    assert_eq!(m.diffuse, [1.0, 0.0, 0.0]);
    assert_eq!(
        m.colors,
        Some(Attribute::PerVertex(vec![
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0]
        ]))
    );
    assert_eq!(o.warnings.len(), 1, "{:?}", o.warnings);
    assert!(o.warnings[0].message.contains("Frobnicator"));
}

#[test]
fn inventor_cube_and_unbracketed_single_values() {
    let s = parse(
        "#Inventor V1.0 ascii
Separator { Cube { width 2 height 4 depth 6 } Coordinate3 { point 1 2 3 } }",
    );
    assert_eq!(s.models.len(), 1);
    assert!((volume(&s.models[0]) - 48.0).abs() < 1e-3);
}

#[test]
fn gzipped_files_are_read() {
    use std::io::Write;
    let dir = std::env::temp_dir().join(format!("decimate-io-gz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cube.wrl.gz");
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(CUBE_V1.as_bytes()).unwrap();
    std::fs::write(&path, gz.finish().unwrap()).unwrap();
    let s = read_scene(&path).unwrap_or_else(|e| panic!("{e}")).scene;
    assert_eq!((s.vertex_count(), s.triangle_count()), (8, 12));
    std::fs::remove_dir_all(&dir).ok();
}

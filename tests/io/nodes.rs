//! Every geometry node of VRML 1.0, Inventor and VRML 2.0 on generated scenes: the round
//! primitives with each combination of parts (triangle counts and bounds against closed-form
//! values, closed and outward when whole), `Complexity`, `File` inclusion, `Array` and
//! `MultipleCopy` expansion; and the files that used to read silently wrong, now refused with
//! the file, the line and the reason.

use std::collections::HashMap;
use std::f32::consts::{PI, TAU};

use decimate_core::io::{
    parse_str, read_scene, read_scene_with, ReadOptions, Warning, WarningKind,
};
use decimate_core::mesh::{Model, Scene};
use glam::Vec3;

use crate::support::binary::decimate;

/// The warnings' sentences.
fn messages(warnings: &[Warning]) -> Vec<&str> {
    warnings.iter().map(|w| w.message.as_str()).collect()
}

fn read(src: &str) -> Scene {
    parse_str(src, "t.iv")
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

fn fail(src: &str, name: &str) -> String {
    match parse_str(src, name) {
        Ok(o) => panic!("expected an error, read {} models", o.scene.models.len()),
        Err(e) => e.to_string(),
    }
}

fn world(m: &Model) -> Vec<Vec3> {
    m.positions
        .iter()
        .map(|&p| m.transform.transform_point3(p))
        .collect()
}

fn bounds(m: &Model) -> (Vec3, Vec3) {
    world(m).iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

fn near(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-4
}

fn signed_volume(m: &Model) -> f32 {
    let p = world(m);
    m.triangles
        .iter()
        .map(|t| p[t[0] as usize].dot(p[t[1] as usize].cross(p[t[2] as usize])) / 6.0)
        .sum()
}

/// Closed and consistently oriented: each directed edge once, its reverse once.
fn closed(m: &Model) -> bool {
    let mut edges = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

/// No triangle of zero area.
fn no_degenerate(m: &Model) -> bool {
    let p = world(m);
    m.triangles.iter().all(|t| {
        let (a, b, c) = (p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]);
        (b - a).cross(c - a).length() > 1e-6
    })
}

/// The extent of a ring of `n` vertices at angles `2 pi j / n` from -z towards -x:
/// (min x, max x, min z, max z) for radius 1.
fn ring_extent(n: u32) -> (f32, f32, f32, f32) {
    let a = |j: u32| TAU * j as f32 / n as f32;
    let xs: Vec<f32> = (0..n).map(|j| -a(j).sin()).collect();
    let zs: Vec<f32> = (0..n).map(|j| -a(j).cos()).collect();
    let min = |v: &[f32]| v.iter().copied().fold(f32::MAX, f32::min);
    let max = |v: &[f32]| v.iter().copied().fold(f32::MIN, f32::max);
    (min(&xs), max(&xs), min(&zs), max(&zs))
}

const PART_MASKS: [(&str, bool, bool, bool); 7] = [
    ("SIDES", true, false, false),
    ("TOP", false, true, false),
    ("BOTTOM", false, false, true),
    ("(SIDES | TOP)", true, true, false),
    ("(SIDES | BOTTOM)", true, false, true),
    ("(TOP | BOTTOM)", false, true, true),
    ("ALL", true, true, true),
];

#[test]
fn inventor_cylinders_with_each_parts_mask() {
    // Default complexity 0.5: Coin's 40 x 0.5 = 20 slices.
    let n = 20;
    for (mask, side, top, bottom) in PART_MASKS {
        let s = read(&format!(
            "#Inventor V2.1 ascii\nCylinder {{ parts {mask} radius 2 height 6 }}"
        ));
        let m = &s.models[0];
        let want = if side { 2 * n } else { 0 }
            + if top { n - 2 } else { 0 }
            + if bottom { n - 2 } else { 0 };
        assert_eq!(m.triangles.len(), want as usize, "{mask}");
        let (lo, hi) = bounds(m);
        let y_lo = if side || bottom { -3.0 } else { 3.0 };
        let y_hi = if side || top { 3.0 } else { -3.0 };
        let (x0, x1, z0, z1) = ring_extent(n);
        assert!(
            near(lo, Vec3::new(2.0 * x0, y_lo, 2.0 * z0)),
            "{mask}: {lo}"
        );
        assert!(
            near(hi, Vec3::new(2.0 * x1, y_hi, 2.0 * z1)),
            "{mask}: {hi}"
        );
        assert!(no_degenerate(m), "{mask}");
        assert_eq!(closed(m), side && top && bottom, "{mask}");
        if side && top && bottom {
            let v = signed_volume(m);
            let exact = 0.5 * n as f32 * (TAU / n as f32).sin() * 4.0 * 6.0;
            assert!((v - exact).abs() < 1e-3 * exact, "{v} vs {exact}");
        }
    }
}

#[test]
fn vrml1_cones_with_each_parts_mask() {
    let n = 20;
    for (mask, side, _, bottom) in PART_MASKS {
        let src = format!(
            "#VRML V1.0 ascii\nSeparator {{ Cone {{ parts {mask} bottomRadius 1 height 4 }} }}"
        );
        let s = read(&src);
        let want = if side { n } else { 0 } + if bottom { n - 2 } else { 0 };
        if want == 0 {
            // A cone has no top: TOP alone draws nothing, and says so.
            let o = parse_str(&src, "t.wrl").unwrap();
            assert!(o.scene.models.is_empty(), "{mask}");
            assert_eq!(
                messages(&o.warnings),
                ["line 2: 'Cone' of zero size or with no parts skipped"]
            );
            continue;
        }
        let m = &s.models[0];
        assert_eq!(m.triangles.len(), want as usize, "{mask}");
        let (lo, hi) = bounds(m);
        let (x0, x1, z0, z1) = ring_extent(n);
        let y_hi = if side { 2.0 } else { -2.0 };
        assert!(near(lo, Vec3::new(x0, -2.0, z0)), "{mask}: {lo}");
        assert!(near(hi, Vec3::new(x1, y_hi, z1)), "{mask}: {hi}");
        assert!(no_degenerate(m));
        assert_eq!(closed(m), side && bottom, "{mask}");
        if side && bottom {
            let v = signed_volume(m);
            let exact = 0.5 * n as f32 * (TAU / n as f32).sin() * 4.0 / 3.0;
            assert!((v - exact).abs() < 1e-3 * exact, "{v} vs {exact}");
        }
    }
}

#[test]
fn spheres_are_closed_outward_with_coin_counts_at_each_complexity() {
    // (Complexity value, stacks, slices): Coin's 30 x value, at least 3 stacks, 4 slices.
    for (value, stacks, slices) in [(0.5f32, 15u32, 15u32), (1.0, 30, 30), (0.0, 3, 4)] {
        let s = read(&format!(
            "#Inventor V2.1 ascii\nSeparator {{ Complexity {{ value {value} }} Sphere {{ radius 3 }} }}"
        ));
        let m = &s.models[0];
        assert_eq!(
            m.triangles.len() as u32,
            2 * slices * (stacks - 2),
            "{value}"
        );
        assert!(closed(m) && no_degenerate(m), "{value}");
        assert!(m.solid);
        let (lo, hi) = bounds(m);
        assert!((lo.y + 3.0).abs() < 1e-5 && (hi.y - 3.0).abs() < 1e-5);
        // The widest ring, at the equator when the stack count is odd.
        let widest = (1..stacks - 1)
            .map(|i| (PI * i as f32 / (stacks - 1) as f32).sin())
            .fold(0.0f32, f32::max);
        let (x0, x1, z0, z1) = ring_extent(slices);
        assert!(
            near(lo, Vec3::new(3.0 * widest * x0, -3.0, 3.0 * widest * z0)),
            "{lo}"
        );
        assert!(
            near(hi, Vec3::new(3.0 * widest * x1, 3.0, 3.0 * widest * z1)),
            "{hi}"
        );
        let v = signed_volume(m);
        assert!(v > 0.0 && v < 4.0 / 3.0 * PI * 27.0, "{v}");
    }
}

#[test]
fn complexity_is_scoped_by_separators_and_sets_slices() {
    let s = read(
        "#Inventor V2.1 ascii
Separator {
  Separator { Complexity { value 1 } Cylinder { } }
  Cylinder { }
  Complexity { type BOUNDING_BOX value 0.1 }
  Cone { }
}",
    );
    let counts: Vec<usize> = s.models.iter().map(|m| m.triangles.len()).collect();
    assert_eq!(counts, [80 + 38 + 38, 40 + 18 + 18, 20 + 18]);
}

#[test]
fn vrml2_primitives_with_their_part_booleans() {
    let s = parse_str(
        "#VRML V2.0 utf8
Shape { geometry Sphere { radius 2 } }
Transform { translation 10 0 0 children Shape { geometry Cylinder { side FALSE height 1 } } }
Shape { geometry Cylinder { top FALSE bottom FALSE } }
Shape { geometry Cone { bottom FALSE } }
Shape { geometry Cone { } }",
        "t.wrl",
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .scene;
    let counts: Vec<usize> = s.models.iter().map(|m| m.triangles.len()).collect();
    assert_eq!(counts, [390, 36, 40, 20, 38]);
    let (lo, hi) = bounds(&s.models[1]);
    assert!((lo.y + 0.5).abs() < 1e-6 && (hi.y - 0.5).abs() < 1e-6);
    assert!((lo.x - 9.0).abs() < 1e-5 && (hi.x - 11.0).abs() < 1e-5);
    for i in [0, 4] {
        assert!(closed(&s.models[i]) && signed_volume(&s.models[i]) > 0.0);
    }
    assert!(!closed(&s.models[2]) && !s.models[2].solid);
}

#[test]
fn vrml2_elevation_grid_faces_up_with_colours_per_quad() {
    let s = parse_str(
        "#VRML V2.0 utf8
Shape { geometry ElevationGrid {
  xDimension 3 zDimension 2 xSpacing 2 zSpacing 5
  height [ 0 1 2, 0 1 2 ]
  colorPerVertex FALSE color Color { color [ 1 0 0, 0 0 1 ] }
} }
Shape { geometry ElevationGrid { xDimension 1 zDimension 4 height [ 0 0 0 0 ] } }",
        "t.wrl",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.scene.models.len(), 1);
    assert_eq!(
        messages(&s.warnings),
        ["line 7: 'ElevationGrid' with fewer than 2 x 2 points skipped"]
    );
    assert_eq!(s.warnings[0].line, Some(7));
    let m = &s.scene.models[0];
    assert_eq!((m.positions.len(), m.triangles.len()), (6, 4));
    let (lo, hi) = bounds(m);
    assert!(near(lo, Vec3::ZERO) && near(hi, Vec3::new(4.0, 2.0, 5.0)));
    let p = world(m);
    let mut area = 0.0;
    for t in &m.triangles {
        let n = (p[t[1] as usize] - p[t[0] as usize]).cross(p[t[2] as usize] - p[t[0] as usize]);
        assert!(n.y > 0.0, "every quad faces +y");
        area += n.length() / 2.0;
    }
    // Two slopes of 2 x 5 rising by 1: each sqrt(4 + 1) x 5.
    assert!((area - 2.0 * 5.0 * 5f32.sqrt()).abs() < 1e-4, "{area}");
    let colours = match &m.colors {
        Some(decimate_core::mesh::Attribute::PerFace(c)) => c.clone(),
        other => panic!("{other:?}"),
    };
    assert_eq!(
        colours,
        [
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 1.0]
        ]
    );
    let e = fail(
        "#VRML V2.0 utf8\nShape { geometry ElevationGrid {\n xDimension 3 zDimension 3\n height [ 0 0 0 ] } }",
        "g.wrl",
    );
    assert!(
        e.starts_with("g.wrl:4: ElevationGrid of 3 x 3 points needs 9 heights, found 3"),
        "{e}"
    );
}

#[test]
fn vrml2_extrusions_are_closed_outward_sweeps() {
    let s = parse_str(
        "#VRML V2.0 utf8
Shape { geometry Extrusion { } }
Shape { geometry Extrusion { spine [ 0 0 0, 0 2 0, 2 2 0 ] scale 0.25 0.25 } }
Shape { geometry Extrusion {
  spine [ 0 0 0, 4 0 0, 4 0 4, 0 0 4, 0 0 0 ] scale 0.5 0.5 } }
Shape { geometry Extrusion { beginCap FALSE endCap FALSE } }",
        "t.wrl",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let m = &s.scene.models;
    assert_eq!(m.len(), 4);
    // The default: the square swept one unit up, a closed box of 2 x 1 x 2.
    assert_eq!((m[0].positions.len(), m[0].triangles.len()), (8, 12));
    let (lo, hi) = bounds(&m[0]);
    assert!(near(lo, Vec3::new(-1.0, 0.0, -1.0)) && near(hi, Vec3::new(1.0, 1.0, 1.0)));
    assert!(closed(&m[0]) && (signed_volume(&m[0]) - 4.0).abs() < 1e-4);
    // A bent spine: two square tubes of 0.5 x 0.5 meeting at the corner, closed by caps.
    assert_eq!((m[1].positions.len(), m[1].triangles.len()), (12, 16 + 4));
    assert!(closed(&m[1]) && no_degenerate(&m[1]) && signed_volume(&m[1]) > 0.0);
    // A closed spine: a square ring with no caps, closed all the same.
    assert_eq!((m[2].positions.len(), m[2].triangles.len()), (16, 32));
    assert!(closed(&m[2]) && no_degenerate(&m[2]) && signed_volume(&m[2]) > 0.0);
    // No caps: an open tube.
    assert_eq!(m[3].triangles.len(), 8);
    assert!(!closed(&m[3]));
}

#[test]
fn inventor_1_indexed_triangle_mesh_and_shape_hints() {
    let s = parse_str(
        "#Inventor V1.0 ascii
Separator {
  ShapeHints { hints (SOLID | ORDERED | CONVEX) }
  Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0, 0 2 0, 1 2 0 ] }
  IndexedTriangleMesh { coordIndex [ 0, 1, 2, 3, 4, 5, -1 ] }
}",
        "t.iv",
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .scene;
    let m = &s.models[0];
    assert_eq!(m.triangles.len(), 4);
    // Inventor 1.0's ShapeHints: SOLID and ORDERED make a solid, counter-clockwise shape.
    assert!(m.solid);
    let p = world(m);
    for t in &m.triangles {
        let n = (p[t[1] as usize] - p[t[0] as usize]).cross(p[t[2] as usize] - p[t[0] as usize]);
        assert!(n.z > 0.0, "every strip triangle faces +z");
    }
}

#[test]
fn file_nodes_include_other_files_relative_to_the_including_one() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("parts")).unwrap();
    std::fs::write(
        dir.path().join("parts/wheel.iv"),
        "#Inventor V2.1 ascii\nSeparator { File { name \"hub.iv\" } Cylinder { } }",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("parts/hub.iv"),
        "#Inventor V2.1 ascii\nCube { }",
    )
    .unwrap();
    let main = dir.path().join("car.iv");
    std::fs::write(
        &main,
        "#Inventor V2.1 ascii\nSeparator {\n Translation { translation 5 0 0 }\n File { name \"parts/wheel.iv\" }\n}",
    )
    .unwrap();
    let s = read_scene(&main).unwrap_or_else(|e| panic!("{e}")).scene;
    let counts: Vec<usize> = s.models.iter().map(|m| m.triangles.len()).collect();
    assert_eq!(counts, [12, 76]);
    let (lo, hi) = bounds(&s.models[0]);
    assert!(near(lo, Vec3::new(4.0, -1.0, -1.0)) && near(hi, Vec3::new(6.0, 1.0, 1.0)));

    // A file that includes itself through another is refused, naming the File node's line.
    std::fs::write(
        dir.path().join("parts/hub.iv"),
        "#Inventor V2.1 ascii\nSeparator {\n File { name \"wheel.iv\" }\n}",
    )
    .unwrap();
    let e = read_scene(&main).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}:4: in included file", main.display())),
        "{e}"
    );
    assert!(e.contains("includes itself"), "{e}");
    // A path from the root is outside the model's folder: refused before it is opened.
    std::fs::write(
        dir.path().join("dev.iv"),
        "#Inventor V2.1 ascii\nFile { name \"/dev/zero\" }",
    )
    .unwrap();
    let e = read_scene(&dir.path().join("dev.iv"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(":2: 'File' name '/dev/zero' is outside the model's folder"),
        "{e}"
    );
    // A missing file is named.
    std::fs::remove_file(dir.path().join("parts/wheel.iv")).unwrap();
    let e = read_scene(&main).unwrap_err().to_string();
    assert!(
        e.contains(":4: cannot read included file") && e.contains("wheel.iv"),
        "{e}"
    );
}

#[test]
fn array_and_multiple_copy_make_their_copies() {
    let s = read(
        "#Inventor V2.1 ascii
Array { numElements1 3 separation1 4 0 0 numElements2 2 separation2 0 5 0 origin CENTER
  Cube { }
}
MultipleCopy { matrix [ 1 0 0 0  0 1 0 0  0 0 1 0  0 0 20 1,
                        2 0 0 0  0 2 0 0  0 0 2 0  0 0 30 1 ]
  Sphere { }
}",
    );
    assert_eq!(s.models.len(), 8);
    let centres: Vec<Vec3> = s
        .models
        .iter()
        .map(|m| {
            let (lo, hi) = bounds(m);
            (lo + hi) * 0.5
        })
        .collect();
    let mut want = Vec::new();
    for y in [-2.5, 2.5] {
        for x in [-4.0, 0.0, 4.0] {
            want.push(Vec3::new(x, y, 0.0));
        }
    }
    for (c, w) in centres.iter().zip(&want) {
        assert!(near(*c, *w), "{c} vs {w}");
    }
    // A sphere's ring starts at -z: its lowest z is the centre's minus the radius.
    let (lo, hi) = bounds(&s.models[7]);
    assert!((hi.y - lo.y - 4.0).abs() < 1e-4, "{lo} {hi}");
    assert!((lo.z - 28.0).abs() < 1e-4, "{lo}");
    let (lo, hi) = bounds(&s.models[6]);
    assert!(
        (hi.y - lo.y - 2.0).abs() < 1e-4 && (lo.z - 19.0).abs() < 1e-4,
        "{lo}"
    );
}

#[test]
fn node_kits_are_walked_for_their_parts_in_the_kits_order() {
    let s = read(
        "#Inventor V2.1 ascii
Separator {
  DEF Body SeparatorKit {
    appearance AppearanceKit { material Material { diffuseColor 1 0 0 } }
    transform Transform { translation 10 0 0 }
    childList NodeKitListPart {
      containerTypeName \"Separator\"
      childTypeNames [ \"ShapeKit\" ]
      containerNode Separator {
        ShapeKit {
          transform Transform { translation 0 5 0 }
          localTransform Transform { scaleFactor 3 3 3 }
          shape Sphere { }
          childList NodeKitListPart { containerNode Separator { ShapeKit { shape Cube { } } } }
        }
      }
    }
  }
  Cube { }
}",
    );
    assert_eq!(s.models.len(), 3);
    let counts: Vec<usize> = s.models.iter().map(|m| m.triangles.len()).collect();
    assert_eq!(counts, [390, 12, 12]);
    // The sphere: both kits' transforms, then its own local scale.
    let (lo, hi) = bounds(&s.models[0]);
    assert!(
        (lo.y - 2.0).abs() < 1e-4 && (hi.y - 8.0).abs() < 1e-4,
        "{lo} {hi}"
    );
    // The kit's child: the kits' transforms, not the sibling shape's local scale.
    let (lo, hi) = bounds(&s.models[1]);
    assert!(near(lo, Vec3::new(9.0, 4.0, -1.0)) && near(hi, Vec3::new(11.0, 6.0, 1.0)));
    assert_eq!(s.models[1].diffuse, [1.0, 0.0, 0.0]);
    // Nothing leaks out of the kit.
    let (lo, hi) = bounds(&s.models[2]);
    assert!(near(lo, Vec3::splat(-1.0)) && near(hi, Vec3::ONE));
    assert_eq!(s.models[2].diffuse, [0.8, 0.8, 0.8]);
}

#[test]
fn a_switch_choosing_minus_two_inherits_the_enclosing_choice() {
    let s = read(
        "#Inventor V2.1 ascii
Switch { whichChild 1
  Cube { }
  Separator { Switch { whichChild -2 Sphere { } Cone { } } }
}",
    );
    let counts: Vec<usize> = s.models.iter().map(|m| m.triangles.len()).collect();
    assert_eq!(counts, [38]);
}

#[test]
fn text_and_nurbs_are_skipped_with_one_warning_each_that_counts_them() {
    let o = parse_str(
        "#Inventor V2.1 ascii
Separator { Text3 { string \"a\" } Cube { } Text3 { string \"b\" } NurbsSurface { }
  Text3 { string \"c\" } }",
        "t.iv",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(o.scene.models.len(), 1);
    assert_eq!(o.warnings.len(), 2, "{:?}", o.warnings);
    assert!(
        o.warnings[0]
            .message
            .starts_with("3 'Text3' shape(s) skipped, the first at line 2"),
        "{:?}",
        o.warnings
    );
    // Typed: the kind, where the first one is, and how many.
    let w = &o.warnings[0];
    assert_eq!(
        (w.kind, w.line, w.count),
        (WarningKind::SkippedNode, Some(2), 3)
    );
    assert!(w.loses_data());
    assert!(o.warnings[1]
        .message
        .starts_with("1 'NurbsSurface' shape(s) skipped"));
}

#[test]
fn an_error_inside_a_used_node_names_the_use_and_the_def_lines() {
    let e = fail(
        "#Inventor V2.1 ascii
Separator {
  Switch { whichChild -1
    DEF Bad IndexedFaceSet { coordIndex [ 0, 1, 9, -1 ] }
  }
  Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }
  USE Bad
}",
        "use.iv",
    );
    assert!(
        e.starts_with("use.iv:7: in 'USE Bad' (DEF Bad at line 4): line 4: index 9"),
        "{e}"
    );
    let e = fail(
        "#VRML V2.0 utf8
Switch { choice DEF F IndexedFaceSet { coord Coordinate { point [ 0 0 0 ] } coordIndex [ 0 0 4 ] } }
Shape {
  geometry USE F
}",
        "use.wrl",
    );
    assert!(
        e.starts_with("use.wrl:4: in 'USE F' (DEF F at line 2): line 2: index 4"),
        "{e}"
    );
}

#[test]
fn an_unknown_field_is_an_error_naming_it_or_a_warning_when_lenient() {
    let src = "#Inventor V2.1 ascii\nSeparator {\n Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n IndexedFaceSet {\n  coordIndexx [ 0, 1, 2, -1 ]\n }\n}";
    let e = fail(src, "typo.iv");
    assert!(
        e.starts_with(
            "typo.iv:5: 'IndexedFaceSet' has no field 'coordIndexx' (its fields: coordIndex,"
        ),
        "{e}"
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("typo.iv");
    std::fs::write(&path, src).unwrap();
    let o = read_scene_with(&path, ReadOptions { lenient: true }).unwrap();
    assert!(o.scene.models.is_empty());
    assert!(
        o.warnings[0].message.contains("no field 'coordIndexx'"),
        "{:?}",
        o.warnings
    );
    let e = fail(
        "#VRML V2.0 utf8\nShape { geometry Box { sise 1 2 3 } }",
        "typo.wrl",
    );
    assert!(
        e.starts_with("typo.wrl:2: 'Box' has no field 'sise'"),
        "{e}"
    );
}

#[test]
fn control_bytes_carriage_returns_and_wrong_headers() {
    let e = fail(
        "#Inventor V2.1 ascii\nSeparator {\n Cu\0be { }\n}",
        "nul.iv",
    );
    assert!(
        e.starts_with("nul.iv:3: control byte 0x00 outside a string"),
        "{e}"
    );
    // Lines ended by a carriage return alone: read, and errors counted in those lines.
    let s = read("#Inventor V2.1 ascii\rSeparator {\r Cube { }\r}\r");
    assert_eq!(s.models[0].triangles.len(), 12);
    let e = fail(
        "#Inventor V2.1 ascii\rSeparator {\r Cube { width x }\r}\r",
        "cr.iv",
    );
    assert!(
        e.starts_with("cr.iv:3: expected a number for 'width'"),
        "{e}"
    );
    // A VRML 2.0 header over an Inventor body.
    let e = fail("#VRML V2.0 utf8\nSeparator {\n Cube { }\n}", "header.wrl");
    assert!(
        e.starts_with(
            "header.wrl:2: no node of this file is a VRML 2.0 node (the first is 'Separator')"
        ),
        "{e}"
    );
}

#[test]
fn the_binary_refuses_unknown_outputs_and_empty_results_and_keeps_loss_warnings_under_q() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("cube.iv"),
        "#Inventor V2.1 ascii\nSeparator { Cube { } Text3 { string \"x\" } }",
    )
    .unwrap();
    let o = decimate(
        dir.path(),
        &["cube.iv", "nogui", "-p", "50", "-o", "out.xyz"],
    );
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("-o out.xyz: no writer knows this extension"),
        "{err}"
    );
    assert!(!dir.path().join("out.xyz").exists());

    let o = decimate(
        dir.path(),
        &["cube.iv", "nogui", "-p", "0", "-q", "-o", "out.wrl"],
    );
    assert_eq!(o.status.code(), Some(0));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("warning: 1 'Text3' shape(s) skipped"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");

    std::fs::write(
        dir.path().join("text.iv"),
        "#Inventor V2.1 ascii\nSeparator { Text3 { string \"x\" } }",
    )
    .unwrap();
    let o = decimate(
        dir.path(),
        &["text.iv", "nogui", "-p", "50", "-q", "-o", "t.wrl"],
    );
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("text.iv: no triangles"), "{err}");
    assert!(!dir.path().join("t.wrl").exists());
}

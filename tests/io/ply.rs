//! PLY input: ASCII and binary big-endian files with quads, colours and extra properties;
//! texture coordinates as Blender, MeshLab and others write them, and through our writer.

use decimate_core::io::ply::write_ply_to;
use decimate_core::io::{parse_bytes, ReadError, ReadOutcome};
use decimate_core::mesh::{Attribute, Model, Scene};
use glam::Vec3;
use std::path::Path;

use crate::support::texture::textured_corners;

#[test]
fn ascii_ply_with_a_quad_and_colours() {
    let src = "ply
format ascii 1.0
comment a unit square and a triangle
element vertex 5
property float x
property float y
property float z
property float confidence
property uchar red
property uchar green
property uchar blue
element face 2
property list uchar int vertex_indices
property uchar flags
end_header
0 0 0 1 255 0 0
1 0 0 1 0 255 0
1 1 0 1 0 0 255
0 1 0 1 255 255 255
2 0.5 0 1 0 0 0
4 0 1 2 3 7
3 1 4 2 0
";
    let s = parse_bytes(src.as_bytes().to_vec(), Path::new("sq.ply"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    assert_eq!(s.vertex_count(), 5);
    assert_eq!(s.triangle_count(), 3);
    let Some(Attribute::PerVertex(c)) = &s.models[0].colors else {
        panic!()
    };
    assert_eq!(c[2], [0.0, 0.0, 1.0]);
}

#[test]
fn binary_big_endian_ply_with_double_coordinates() {
    let mut b = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list uchar uint vertex_index\nend_header\n".to_vec();
    for v in [0.0f64, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        b.extend(v.to_be_bytes());
    }
    b.push(3);
    for i in [0u32, 1, 2] {
        b.extend(i.to_be_bytes());
    }
    let s = parse_bytes(b.clone(), Path::new("t.ply"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    assert_eq!(s.models[0].triangles, vec![[0, 1, 2]]);
    assert_eq!(s.models[0].positions[1], glam::Vec3::X);
    // Truncated: an error, not a panic.
    b.truncate(b.len() - 3);
    let e = parse_bytes(b, Path::new("t.ply")).unwrap_err();
    assert!(matches!(e, ReadError::Syntax { .. }));
    assert!(e.to_string().contains("end of file"), "{e}");
}

#[test]
fn ply_index_out_of_range_is_an_error() {
    let src = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 1 2\n";
    let e = parse_bytes(src.as_bytes().to_vec(), Path::new("bad.ply")).unwrap_err();
    assert!(e.to_string().starts_with("bad.ply:7:"), "{e}");
    assert!(e.to_string().contains("out of range"), "{e}");
}

/// Found by `tests/fuzz/`: an infinite colour read, then made a progressive mesh
/// that did not read back. A vertex's colour and normal must be finite, as its position is
/// (texture coordinates that are not are skipped with a warning, see below).
#[test]
fn a_non_finite_colour_or_normal_names_its_line() {
    let header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                  property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
                  property float nx\nproperty float ny\nproperty float nz\nproperty float s\n\
                  property float t\nelement face 1\nproperty list uchar int vertex_indices\n\
                  end_header\n";
    let good = "0 0 0 1 2 3 0 0 1 0 0\n1 0 0 1 2 3 0 0 1 1 0\n";
    for (last, what) in [
        (
            "0 1 0 1 1e39 3 0 0 1 0 1",
            "vertex 2's green is not a finite number (inf)",
        ),
        (
            "0 1 0 1 2 3 0 nan 1 0 1",
            "vertex 2's ny is not a finite number (NaN)",
        ),
    ] {
        let src = format!("{header}{good}{last}\n3 0 1 2\n");
        let e = parse_bytes(src.into_bytes(), Path::new("bad.ply")).unwrap_err();
        assert_eq!(e.to_string(), format!("bad.ply:20: {what}"));
    }
}
#[test]
fn ascii_ply_indices_read_the_same_in_any_number_form() {
    // Plain digits take a fast path; leading zeros, a decimal point, an exponent and a plus
    // sign still name the same integers, and a fraction or a minus sign is still an error.
    let square = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                  property float z\nelement face 2\nproperty list uchar int vertex_indices\n\
                  end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    let s = read(
        "forms.ply",
        format!("{square}3 0 1 2\n3.0 000 2e0 +3\n").as_bytes(),
    )
    .scene;
    assert_eq!(s.models[0].triangles, vec![[0, 1, 2], [0, 2, 3]]);
    for bad in ["2.5", "-2", "4294967296"] {
        let src = format!("{square}3 0 1 2\n3 0 3 {bad}\n");
        let e = parse_bytes(src.into_bytes(), Path::new("bad.ply")).unwrap_err();
        assert!(e.to_string().contains("non-negative integer"), "{bad}: {e}");
    }
}

fn read(name: &str, src: &[u8]) -> ReadOutcome {
    parse_bytes(src.to_vec(), Path::new(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// A coloured quad textured with awkward floats and cut by a seam: vertex 4 is vertex 0's
/// point on the other side, with other coordinates.
fn textured_model() -> Model {
    let p = [
        Vec3::new(0.1, 0.2, 0.3),
        Vec3::new(1.0 / 3.0, 0.0, 1e-7),
        Vec3::new(12345.678, 0.5, -2.25),
        Vec3::new(-1.0, 3.0e10, 0.7),
    ];
    Model {
        name: "textured".into(),
        positions: vec![p[0], p[1], p[2], p[3], p[0]],
        triangles: vec![[0, 1, 2], [4, 2, 3]],
        colors: Some(Attribute::PerVertex(vec![[1.0, 0.0, 0.0]; 5])),
        texcoords: Some(vec![
            [0.1, 1.0 / 3.0],
            [-0.0, 1e-7],
            [12345.678, 0.5],
            [-2.25, 1e30],
            [2.1, 1.0 / 7.0],
        ]),
        ..Model::default()
    }
}

#[test]
fn textured_binary_ply_round_trips_exactly_with_its_colours() {
    let scene = Scene {
        models: vec![textured_model()],
    };
    let mut bytes = Vec::new();
    write_ply_to(&mut bytes, &scene).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    assert!(
        text.contains("property uchar blue\nproperty float s\nproperty float t\nelement face"),
        "{text}"
    );
    let back = read("t.ply", &bytes);
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    let m = &back.scene.models[0];
    assert_eq!(m.positions.len(), 5, "the seam stays cut");
    assert_eq!(textured_corners(&back.scene), textured_corners(&scene));
    assert_eq!(
        m.colors,
        Some(Attribute::PerVertex(vec![[1.0, 0.0, 0.0]; 5]))
    );
    // Every prefix reads or fails cleanly.
    for cut in 0..bytes.len() {
        if let Err(e) = parse_bytes(bytes[..cut].to_vec(), Path::new("t.ply")) {
            assert!(e.to_string().starts_with("t.ply"), "{e}");
        }
    }
}

#[test]
fn blender_ascii_ply_texture_coordinates_read_and_round_trip() {
    // Blender's layout: x y z nx ny nz s t, then colours.
    let src = "ply
format ascii 1.0
comment Created by Blender
element vertex 4
property float x
property float y
property float z
property float nx
property float ny
property float nz
property float s
property float t
property uchar red
property uchar green
property uchar blue
property uchar alpha
element face 1
property list uchar uint vertex_indices
end_header
0 0 0 0 0 1 0.125 0.25 255 0 0 255
1 0 0 0 0 1 0.333333343 0.5 0 255 0 255
1 1 0 0 0 1 0.1 0.7 0 0 255 255
0 1 0 0 0 1 1e-7 -0.0 9 9 9 255
4 0 1 2 3
";
    let back = read("blender.ply", src.as_bytes());
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    let m = &back.scene.models[0];
    assert_eq!(
        m.texcoords.as_deref(),
        Some(&[[0.125, 0.25], [1.0 / 3.0, 0.5], [0.1, 0.7], [1e-7, -0.0]][..])
    );
    // Read (ASCII) -> write (binary) -> read keeps them bit for bit.
    let mut bytes = Vec::new();
    write_ply_to(&mut bytes, &back.scene).unwrap();
    let again = read("again.ply", &bytes);
    assert_eq!(
        textured_corners(&again.scene),
        textured_corners(&back.scene)
    );
}

#[test]
fn meshlab_and_other_texture_coordinate_names_and_types() {
    // MeshLab (VCG): texture_u texture_v, here as doubles in a big-endian file.
    let mut b = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty double texture_u\nproperty double texture_v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    for v in [
        [0.0, 0.0, 0.0, 0.25, 0.75],
        [1.0, 0.0, 0.0, 0.5, 0.125],
        [0.0, 1.0, 0.0, 1.0 / 3.0, 2.0],
    ] {
        for x in &v[..3] {
            b.extend((*x as f32).to_be_bytes());
        }
        for x in &v[3..] {
            b.extend(f64::to_be_bytes(*x));
        }
    }
    b.push(3);
    for i in [0i32, 1, 2] {
        b.extend(i.to_be_bytes());
    }
    let m = &read("vcg.ply", &b).scene.models[0];
    assert_eq!(
        m.texcoords.as_deref(),
        Some(&[[0.25, 0.75], [0.5, 0.125], [1.0 / 3.0, 2.0]][..])
    );
    // u v as ushorts, little-endian, after an extra property.
    let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty ushort u\nproperty uchar quality\nproperty ushort v\nelement face 1\nproperty list uchar uchar vertex_indices\nend_header\n".to_vec();
    for (i, p) in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .enumerate()
    {
        for x in p {
            b.extend(x.to_le_bytes());
        }
        b.extend((i as u16 * 1000).to_le_bytes());
        b.push(7);
        b.extend(65535u16.to_le_bytes());
    }
    b.extend([3, 0, 1, 2]);
    let m = &read("uv.ply", &b).scene.models[0];
    assert_eq!(
        m.texcoords.as_deref(),
        Some(&[[0.0, 65535.0], [1000.0, 65535.0], [2000.0, 65535.0]][..])
    );
    // texture_s texture_t, ASCII.
    let src = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float texture_s\nproperty float texture_t\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 1\n1 0 0 1 1\n0 1 0 0 0\n3 0 1 2\n";
    let m = &read("st.ply", src.as_bytes()).scene.models[0];
    assert_eq!(
        m.texcoords.as_deref(),
        Some(&[[0.0, 1.0], [1.0, 1.0], [0.0, 0.0]][..])
    );
}

#[test]
fn meshlab_per_corner_texcoords_split_the_seam() {
    // Two triangles over a square; they agree on the shared corner 2 but not on corner 0.
    let src = "ply
format ascii 1.0
comment VCGLIB generated
element vertex 4
property float x
property float y
property float z
element face 2
property list uchar int vertex_indices
property list uchar float texcoord
property int texnumber
end_header
0 0 0
1 0 0
1 1 0
0 1 0
3 0 1 2 6 0 0 1 0 1 1 0
3 0 2 3 6 5 5 1 1 0 1 0
";
    let out = read("wedge.ply", src.as_bytes());
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    let m = &out.scene.models[0];
    assert_eq!(m.positions.len(), 5, "point 0 is split, point 2 shared");
    let t = m.texcoords.as_ref().unwrap();
    let corners: Vec<[f32; 2]> = m
        .triangles
        .iter()
        .flatten()
        .map(|&i| t[i as usize])
        .collect();
    assert_eq!(
        corners,
        [[0., 0.], [1., 0.], [1., 1.], [5., 5.], [1., 1.], [0., 1.]]
    );
}

#[test]
fn broken_texture_coordinates_are_skipped_with_a_warning() {
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    let tri = "element face 1\nproperty list uchar int vertex_indices\n";
    let cases = [
        // Half a pair.
        (
            format!("{head}property float s\n{tri}end_header\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n"),
            "has 's' but no 't'",
        ),
        (
            format!("{head}property float texture_v\n{tri}end_header\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n"),
            "has 'texture_v' but no 'texture_u'",
        ),
        // Not finite.
        (
            format!("{head}property float u\nproperty float v\n{tri}end_header\n0 0 0 1 nan\n1 0 0 1 1\n0 1 0 1 1\n3 0 1 2\n"),
            "not a finite pair",
        ),
        // A per-corner list of the wrong length.
        (
            format!("{head}{tri}property list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 4 0 0 1 0\n"),
            "face 0 has 4 'texcoord' values for 3 corners",
        ),
    ];
    for (src, want) in cases {
        let out = read("bad.ply", src.as_bytes());
        assert_eq!(out.scene.triangle_count(), 1);
        assert_eq!(out.scene.models[0].texcoords, None, "{want}");
        assert_eq!(out.warnings.len(), 1, "{:?}", out.warnings);
        assert!(out.warnings[0].message.contains(want), "{:?}", out.warnings);
    }
    // A texture coordinate that is not a number is an error on its line.
    let src = format!("{head}property float s\nproperty float t\n{tri}end_header\n0 0 0 0 0\n1 0 0 x 0\n0 1 0 0 0\n3 0 1 2\n");
    let e = parse_bytes(src.into_bytes(), Path::new("x.ply")).unwrap_err();
    assert!(e.to_string().starts_with("x.ply:13:"), "{e}");
}

#[test]
fn meshlab_texture_file_comment_names_the_image_both_ways() {
    // MeshLab's header names the image in a comment; the name may hold spaces.
    let src = "ply
format ascii 1.0
comment VCGLIB generated
comment TextureFile scan texture 01.png
comment TextureFile second.png
element vertex 3
property float x
property float y
property float z
property float texture_u
property float texture_v
element face 1
property list uchar int vertex_indices
end_header
0 0 0 0 0
1 0 0 1 0
0 1 0 0 1
3 0 1 2
";
    let back = read("meshlab.ply", src.as_bytes());
    let m = &back.scene.models[0];
    assert_eq!(m.texture.as_deref(), Some("scan texture 01.png"));
    let mut bytes = Vec::new();
    write_ply_to(&mut bytes, &back.scene).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    assert!(
        text.contains("\ncomment TextureFile scan texture 01.png\n"),
        "{text}"
    );
    let again = read("again.ply", &bytes);
    assert_eq!(
        again.scene.models[0].texture.as_deref(),
        Some("scan texture 01.png")
    );
    // Without texture coordinates the image is meaningless: not kept, not written.
    let plain = src
        .replace("property float texture_u\nproperty float texture_v\n", "")
        .replace(" 0 0\n", "\n")
        .replace(" 1 0\n", "\n")
        .replace(" 0 1\n", "\n");
    let back = read("plain.ply", plain.as_bytes());
    assert_eq!(back.scene.models[0].texture, None);
    // Two models mapping different images: a PLY cannot say which is which, so none.
    let mut two = again.scene.clone();
    let mut other = two.models[0].clone();
    other.texture = Some("other.png".into());
    two.models.push(other);
    let mut bytes = Vec::new();
    write_ply_to(&mut bytes, &two).unwrap();
    assert!(!String::from_utf8_lossy(&bytes).contains("TextureFile"));
}

//! PLY input: ASCII and binary big-endian files with quads, colours and extra properties.

use decimate::io::{parse_bytes, ReadError};
use decimate::mesh::Attribute;
use std::path::Path;

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

//! The seamed grid in the other formats that carry texture coordinates: VRML 2.0 and
//! Inventor face sets (with their image and bindings) and a PLY with per-vertex pairs.

use std::collections::HashMap;
use std::process::Command;

use super::{check_layout, check_seam, distinct_positions, run, seam_vertices, Obj};
use crate::support::shapes::Grid;

/// The flat grid of [`grid_obj`] (`n` × `n` squares, the seam at x = 0.5, the right island
/// shifted by 2 in u) as one VRML 2.0 or Inventor face set with per-corner texture indices
/// and a texture image.
fn grid_scene(n: usize, inventor: bool) -> String {
    let at = |i: usize| i as f32 / n as f32;
    let (mut points, mut uvs, mut faces, mut uv_faces) =
        (String::new(), String::new(), String::new(), String::new());
    let grid = Grid::square(n);
    for (i, j) in grid.points() {
        points += &format!("{} {} 0, ", at(i), at(j));
    }
    for island in 0..2 {
        for (i, j) in grid.points() {
            uvs += &format!("{} {}, ", at(i) + 2.0 * island as f32, at(j));
        }
    }
    for (i, _, quad) in grid.squares() {
        let shift = usize::from(i >= n / 2) * grid.point_count();
        faces += &format!("{} {} {} {} -1, ", quad[0], quad[1], quad[2], quad[3]);
        uv_faces += &format!(
            "{} {} {} {} -1, ",
            quad[0] + shift,
            quad[1] + shift,
            quad[2] + shift,
            quad[3] + shift
        );
    }
    if inventor {
        format!(
            "#Inventor V2.1 ascii\nSeparator {{\n Texture2 {{ filename \"maps/grid.png\" }}\n \
             Coordinate3 {{ point [ {points} ] }}\n TextureCoordinate2 {{ point [ {uvs} ] }}\n \
             IndexedFaceSet {{ coordIndex [ {faces} ] textureCoordIndex [ {uv_faces} ] }}\n}}\n"
        )
    } else {
        format!(
            "#VRML V2.0 utf8\nShape {{\n appearance Appearance {{ texture ImageTexture \
             {{ url [ \"maps/grid.png\" \"http://example.org/grid.png\" ] }} }}\n \
             geometry IndexedFaceSet {{\n  coord Coordinate {{ point [ {points} ] }}\n  \
             coordIndex [ {faces} ]\n  texCoord TextureCoordinate {{ point [ {uvs} ] }}\n  \
             texCoordIndex [ {uv_faces} ]\n }}\n}}\n"
        )
    }
}

#[test]
fn vrml_and_inventor_textures_come_out_in_vrml_with_their_image() {
    let n = 16;
    for (kind, inventor) in [("vrml", false), ("inventor", true)] {
        for algorithm in ["schroeder", "qem"] {
            let dir = std::env::temp_dir().join(format!(
                "decimate-texcoords-{kind}-{algorithm}-{}",
                std::process::id()
            ));
            std::fs::create_dir_all(&dir).unwrap();
            let input = dir.join(if inventor { "in.iv" } else { "in.wrl" });
            let output = dir.join("out.wrl");
            std::fs::write(&input, grid_scene(n, inventor)).unwrap();
            let run = Command::new(env!("CARGO_BIN_EXE_decimate"))
                .arg(&input)
                .args(["nogui", "-a", algorithm, "--keep-vertices", "100", "-o"])
                .arg(&output)
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&run.stderr);
            assert!(run.status.success(), "{kind} {algorithm}: {stderr}");
            assert!(!stderr.contains("warning"), "{kind} {algorithm}: {stderr}");
            let scene = decimate_core::io::read_scene(&output).unwrap().scene;
            std::fs::remove_dir_all(&dir).ok();
            let [m] = scene.models.as_slice() else {
                panic!("{kind} {algorithm}: one model expected")
            };
            let points = (m.positions.iter())
                .map(|p| p.to_array().map(|c| (c + 0.0).to_bits()))
                .collect::<std::collections::HashSet<_>>();
            assert_eq!(points.len(), 100, "{kind} {algorithm}");
            assert_eq!(
                m.texture.as_deref(),
                Some("maps/grid.png"),
                "{kind} {algorithm}"
            );
            let t = m.texcoords.as_ref().expect("texture coordinates written");
            assert_eq!(t.len(), m.positions.len());
            for (p, uv) in m.positions.iter().zip(t) {
                let shift = if uv[0] > 1.5 { 2.0 } else { 0.0 };
                assert!(
                    (uv[0] - shift - p.x).abs() < 1e-5 && (uv[1] - p.y).abs() < 1e-5,
                    "{kind} {algorithm}: vertex at {p} maps to {uv:?}"
                );
            }
            for tri in &m.triangles {
                let islands = tri.map(|v| t[v as usize][0] > 1.5);
                assert!(
                    islands.iter().all(|&i| i == islands[0]),
                    "{kind} {algorithm}"
                );
            }
            let vertices = m
                .positions
                .iter()
                .map(|p| p.to_array())
                .zip(t.iter().copied());
            check_seam(vertices, n, &format!("{kind} {algorithm}"));
        }
    }
}

#[test]
fn inventor_texture_bindings_pick_pairs_by_index_or_in_corner_order() {
    // Two triangles over four points; the second lists its corners in another order.
    let shape = |binding: &str, index: &str| {
        format!(
            "#Inventor V2.1 ascii\nSeparator {{\n Coordinate3 {{ point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] }}\n \
             TextureCoordinate2 {{ point [ 0 0, 0.1 0, 0.2 0, 0.3 0, 0.4 0, 0.5 0 ] }}\n {binding}\n \
             IndexedFaceSet {{ coordIndex [ 0, 1, 2, -1, 2, 3, 0, -1 ] {index} }}\n}}\n"
        )
    };
    let read = |text: String| {
        let scene = decimate_core::io::parse_str(&text, "t.iv").unwrap().scene;
        let m = &scene.models[0];
        // Each corner's u, triangle by triangle.
        let t = m.texcoords.as_ref().expect("texture coordinates");
        m.triangles
            .iter()
            .flat_map(|tri| tri.map(|v| t[v as usize][0]))
            .collect::<Vec<f32>>()
    };
    // Default (PER_VERTEX_INDEXED) without an index: as the coordinates.
    assert_eq!(read(shape("", "")), [0.0, 0.1, 0.2, 0.2, 0.3, 0.0]);
    // With textureCoordIndex.
    assert_eq!(
        read(shape("", "textureCoordIndex [ 5, 4, 3, -1, 2, 1, 0, -1 ]")),
        [0.5, 0.4, 0.3, 0.2, 0.1, 0.0]
    );
    // PER_VERTEX: the pairs in corner order, whatever coordIndex says; the seam this makes
    // at points 0 and 2 splits them.
    let per_vertex = shape("TextureCoordinateBinding { value PER_VERTEX }", "");
    assert_eq!(read(per_vertex.clone()), [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]);
    let scene = decimate_core::io::parse_str(&per_vertex, "t.iv")
        .unwrap()
        .scene;
    assert_eq!(scene.models[0].positions.len(), 6);
}

/// `grid_obj`'s flat grid as an ASCII PLY with MeshLab's per-vertex `texture_u texture_v`:
/// the points on the seam are there twice, once per island.
fn grid_ply(n: usize) -> String {
    let at = |i: usize| i as f32 / n as f32;
    let mut vertices = String::new();
    let mut id: HashMap<(usize, usize, usize), usize> = HashMap::new();
    for j in 0..=n {
        for i in 0..=n {
            for island in 0..2 {
                if (island == 0 && i <= n / 2) || (island == 1 && i >= n / 2) {
                    id.insert((island, i, j), id.len());
                    let (x, y) = (at(i), at(j));
                    vertices += &format!("{x} {y} 0 {} {y}\n", x + 2.0 * island as f32);
                }
            }
        }
    }
    let mut faces = String::new();
    for j in 0..n {
        for i in 0..n {
            let island = usize::from(i >= n / 2);
            let v = |i, j| id[&(island, i, j)];
            let [a, b, c, d] = [v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)];
            faces += &format!("4 {a} {b} {c} {d}\n");
        }
    }
    format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nproperty float texture_u\nproperty float texture_v\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n{vertices}{faces}",
        id.len(),
        n * n
    )
}

/// Our binary PLY output, checked against the exact layout the writer promises (x y z s t
/// floats per vertex, triangles as uchar 3 + three ints), as an `Obj` whose pairs are
/// numbered as the vertices.
fn read_our_ply(bytes: &[u8]) -> Obj {
    let end = b"end_header\n";
    let split = bytes
        .windows(end.len())
        .position(|w| w == end)
        .expect("a header")
        + end.len();
    let header = std::str::from_utf8(&bytes[..split]).expect("an ASCII header");
    let count = |el: &str| -> usize {
        let line = header.lines().find(|l| l.starts_with(el)).expect(el);
        line[el.len()..].trim().parse().expect("a count")
    };
    let (nv, nf) = (count("element vertex "), count("element face "));
    assert_eq!(
        header,
        format!(
            "ply\nformat binary_little_endian 1.0\ncomment written by decimate\n\
             element vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n\
             property float s\nproperty float t\nelement face {nf}\n\
             property list uchar int vertex_indices\nend_header\n"
        )
    );
    let body = &bytes[split..];
    assert_eq!(body.len(), nv * 20 + nf * 13, "one s t pair per vertex");
    let f = |k: usize| f32::from_le_bytes(body[k..k + 4].try_into().unwrap());
    let mut obj = Obj {
        positions: Vec::new(),
        texcoords: Vec::new(),
        triangles: Vec::new(),
    };
    for v in 0..nv {
        let k = v * 20;
        obj.positions.push([f(k), f(k + 4), f(k + 8)]);
        obj.texcoords.push([f(k + 12), f(k + 16)]);
    }
    for t in 0..nf {
        let k = nv * 20 + t * 13;
        assert_eq!(body[k], 3);
        let i = |c: usize| {
            u32::from_le_bytes(body[k + 1 + 4 * c..k + 5 + 4 * c].try_into().unwrap()) as usize
        };
        obj.triangles.push([0, 1, 2].map(|c| (i(c), i(c))));
    }
    obj
}

#[test]
fn a_textured_ply_comes_out_of_qem_with_a_pair_per_vertex() {
    let n = 32;
    let out = read_our_ply(&run(
        "ply-qem",
        "ply",
        &grid_ply(n),
        &["-a", "qem", "--keep-vertices", "300"],
    ));
    assert_eq!(distinct_positions(&out.positions), 300);
    check_layout(&out);
    for (p, uv) in out.positions.iter().zip(&out.texcoords) {
        let shift = if uv[0] > 1.5 { 2.0 } else { 0.0 };
        assert!(
            (uv[0] - shift - p[0]).abs() < 1e-5 && (uv[1] - p[1]).abs() < 1e-5,
            "vertex at {p:?} maps to {uv:?}"
        );
    }
    let [a, b] = seam_vertices(&out);
    assert!(a == b && a < n + 1, "the seam's sides: {a} and {b} points");
}

//! Texture coordinates through a progressive mesh: back bit for bit at the top level, kept
//! mapped on a level rebuilt from the file, seam junctions restored, and a file cut in them
//! refused.

use std::path::Path;

use decimate_core::mesh::progressive::VertexSplit;
use decimate_core::mesh::Model;

use super::{assert_round_trip, decimate, refused, run_progressive_as, stderr};

/// A grid of `n` × `n` squares over the unit square (each cut in two) at height `z(x, y)`,
/// textured by (x, y) and cut by a seam down x = 0.5: the squares right of it map to a
/// second island, shifted by 2 in u, so the seam's points are there once per side.
fn textured_grid(n: u32, z: impl Fn(f32, f32) -> f32) -> Model {
    textured_grid_in(n, z, |i, _| u32::from(2 * i >= n))
}

/// As [`textured_grid`], the square `(i, j)` in texture island `island(i, j)`.
fn textured_grid_in(
    n: u32,
    z: impl Fn(f32, f32) -> f32,
    island: impl Fn(u32, u32) -> u32,
) -> Model {
    let (mut positions, mut texcoords, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    let mut ids = std::collections::HashMap::new();
    let at = |i: u32| i as f32 / n as f32;
    for j in 0..n {
        for i in 0..n {
            let island = island(i, j);
            let mut id = |i: u32, j: u32| {
                *ids.entry((i, j, island)).or_insert_with(|| {
                    let (x, y) = (at(i), at(j));
                    positions.push(glam::Vec3::new(x, y, z(x, y)));
                    texcoords.push([x + 2.0 * island as f32, y]);
                    positions.len() as u32 - 1
                })
            };
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Model {
        name: "grid".into(),
        positions,
        triangles,
        texcoords: Some(texcoords),
        ..Model::default()
    }
}

/// `(position, texture coordinates)` of each vertex of an OBJ the binary wrote, which must
/// give one `vt` per vertex and number each face corner's `vt` as its vertex.
fn obj_vertices(path: &Path) -> Vec<([f32; 3], [f32; 2])> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}"));
    let (mut v, mut vt) = (Vec::new(), Vec::new());
    let numbers = |rest: &str| -> Vec<f32> {
        rest.split_whitespace()
            .map(|x| x.parse().unwrap_or_else(|e| panic!("{x}: {e}")))
            .collect()
    };
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("v ") {
            let p = numbers(rest);
            v.push([p[0], p[1], p[2]]);
        } else if let Some(rest) = line.strip_prefix("vt ") {
            let t = numbers(rest);
            vt.push([t[0], t[1]]);
        } else if let Some(rest) = line.strip_prefix("f ") {
            for corner in rest.split_whitespace() {
                let (a, b) = corner.split_once('/').unwrap_or((corner, ""));
                assert_eq!(a, b, "the corner {corner} has its vertex's vt");
            }
        }
    }
    assert_eq!(vt.len(), v.len(), "one vt per vertex");
    v.into_iter().zip(vt).collect()
}

#[test]
fn texture_coordinates_come_back_exactly_and_rebuilt_levels_keep_the_mapping() {
    let models = vec![
        textured_grid(40, |_, _| 0.0),
        textured_grid(24, |x, y| 0.2 * (3.0 * x).sin() * (2.0 * y).cos()),
    ];
    let (dir, input, out, pm) = run_progressive_as("obj", models);
    for (m, name) in input.models.iter().zip(["flat", "curved"]) {
        assert!(m.texcoords.is_some(), "{name}: the input is textured");
    }
    for (m, name) in pm.models.iter().zip(["flat", "curved"]) {
        assert!(m.base.texcoords.is_some(), "{name}: the base is textured");
    }
    // The top level is the input, its coordinates bit for bit.
    assert_round_trip(&input, &out, &pm);
    // A level rebuilt from the file: the flat grid's coordinates are still its positions'
    // (x, y) on its island.
    let o = decimate(
        dir.path(),
        &["out.pm", "nogui", "-p", "50", "-o", "p50.obj"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let vertices = obj_vertices(&dir.path().join("p50.obj"));
    // Half of each model's vertices, or one fewer where that level would split only one
    // side of a texture seam.
    let half: Vec<usize> = pm
        .models
        .iter()
        .map(|m| {
            let (base, full) = (m.base.positions.len(), m.full_vertex_count());
            base + m.whole_level(full - (full as f64 / 2.0).round() as usize - base)
        })
        .collect();
    assert_eq!(vertices.len(), half[0] + half[1]);
    for (p, uv) in &vertices[..half[0]] {
        let shift = if uv[0] > 1.5 { 2.0 } else { 0.0 };
        let off = (uv[0] - shift - p[0]).abs().max((uv[1] - p[1]).abs());
        assert!(off < 1e-5, "{p:?} maps to {uv:?}");
    }
}

#[test]
fn collapses_into_a_seam_junction_come_back_exactly() {
    // Four islands meet at the grid's centre: a junction of four sides, pinned, which takes
    // its neighbours in where it stands (with a seam vertex, both sides at once). Those
    // collapses are recorded like any other, and refined away like any other.
    let n = 40;
    let z = |x: f32, y: f32| 0.2 * (3.0 * x).sin() * (2.0 * y).cos();
    let quarters = textured_grid_in(n, z, |i, j| {
        u32::from(2 * i >= n) + 2 * u32::from(2 * j >= n)
    });
    let (_dir, input, out, pm) = run_progressive_as("obj", vec![quarters]);
    assert_round_trip(&input, &out, &pm);
    let centre = glam::Vec3::new(0.5, 0.5, z(0.5, 0.5));
    let copies = |m: &Model| m.positions.iter().filter(|&&p| p == centre).count();
    assert_eq!(copies(&input.models[0]), 4, "the input's junction");
    assert_eq!(
        copies(&out.models[0]),
        4,
        "the junction stays, once per island"
    );
}

#[test]
fn a_file_cut_in_its_texture_coordinates_is_refused() {
    let (dir, _, _, pm) = run_progressive_as("obj", vec![textured_grid(12, |_, _| 0.0)]);
    let b = std::fs::read(dir.path().join("out.pm")).unwrap_or_else(|e| panic!("{e}"));
    let m = &pm.models[0];
    // The attribute byte: texture coordinates (bit 3) only.
    let flags = 16 + 4 + m.base.name.len() + 64 + 12 + 5 + 1;
    assert_eq!(b[flags], 8);
    // The base's coordinates come after its positions: a cut there leaves too few bytes.
    let (v, f) = (m.base.positions.len(), m.base.triangles.len());
    let positions = flags + 1 + 8;
    let text = refused(dir.path(), "base.pm", &b[..positions + 12 * v + 4]);
    assert!(text.contains("truncated"), "{text}");
    // The last split's, read after all the others: the cut is named there.
    let split = |s: &VertexSplit| 4 + 36 + 24 + 4 + 4 * s.renamed.len() + 1 + 12 * s.added.len();
    let earlier = &m.splits[..m.splits.len() - 1];
    let last = positions + 20 * v + 12 * f + 4 + earlier.iter().map(split).sum::<usize>();
    let text = refused(dir.path(), "split.pm", &b[..last + 40 + 12]);
    assert!(
        text.contains(&format!(
            "split {}: the file ends before a texture coordinate",
            earlier.len()
        )),
        "{text}"
    );
}

//! Per-face colour borders as seams. A model coloured per face (an OFF with face colours, a
//! VRML `colorPerVertex FALSE`) has a border wherever two neighbouring faces differ. For the
//! decimation that border is an attribute discontinuity like a colour seam (`mesh::seams`):
//! [`split`] gives each point one vertex per face colour around it, as a file with
//! per-vertex colours would, so both algorithms keep the border a shared, sharp line and
//! simplify it only as a whole; [`merge`] turns the result back into per-face colours over
//! one vertex per point.

use std::collections::HashMap;

use super::seams::position_key;
use super::{Attribute, Model};

/// Gives `model` one vertex per point and face colour, with per-vertex colours, when it is
/// coloured per face in regions: two or more colours, borders that add at most a quarter
/// of its vertices or 64 (colours that change from face to face, a gradient, are no border to
/// keep), and no two used vertices at one point with the same texture coordinates (an
/// unwelded model keeps its own duplicates). True when it did: the model must then go
/// through [`merge`] after decimation.
pub fn split(model: &mut Model) -> bool {
    let Some(Attribute::PerFace(face_colors)) = &model.colors else {
        return false;
    };
    if face_colors.len() != model.triangles.len()
        || face_colors.iter().all(|c| c == &face_colors[0])
        || has_coincident_vertices(model)
    {
        return false;
    }
    let n = model.positions.len();
    let Some(split) = split_corners(model, face_colors, (n / 4).max(64)) else {
        return false;
    };
    model.triangles = split.triangles;
    append_copies(model, &split.originals);
    model.colors = Some(Attribute::PerVertex(split.colors));
    true
}

/// A model's corners split by face colour.
struct Split {
    /// The triangles over the old vertices and the new copies.
    triangles: Vec<[u32; 3]>,
    /// The vertex each copy copies, in the copies' order.
    originals: Vec<u32>,
    /// Every vertex's colour, copies included.
    colors: Vec<[f32; 3]>,
}

/// The corners split so that each vertex keeps its first face's colour and a further
/// colour gets a new vertex; `None` when more than `most` would be added.
fn split_corners(model: &Model, face_colors: &[[f32; 3]], most: usize) -> Option<Split> {
    let n = model.positions.len();
    let mut colors: Vec<Option<[f32; 3]>> = vec![None; n];
    let mut copies: HashMap<(u32, [u32; 3]), u32> = HashMap::new();
    let mut added: Vec<u32> = Vec::new();
    let mut triangles = model.triangles.clone();
    for (t, colour) in triangles.iter_mut().zip(face_colors) {
        for v in t.iter_mut() {
            match colors[*v as usize] {
                None => colors[*v as usize] = Some(*colour),
                Some(c) if c == *colour => {}
                Some(_) => {
                    let next = (n + added.len()) as u32;
                    let copy = *copies.entry((*v, colour.map(f32::to_bits))).or_insert(next);
                    if copy == next {
                        if added.len() == most {
                            return None;
                        }
                        added.push(*v);
                        colors.push(Some(*colour));
                    }
                    *v = copy;
                }
            }
        }
    }
    let colors = colors.iter().map(|c| c.unwrap_or([1.0; 3])).collect();
    Some(Split {
        triangles,
        originals: added,
        colors,
    })
}

/// Undoes [`split`] on the decimated `model`: each triangle takes its first corner's
/// colour, and the vertices at one point with the same texture coordinates become one.
pub fn merge(model: &mut Model) {
    let Some(Attribute::PerVertex(vertex_colors)) = &model.colors else {
        return;
    };
    let face_colors: Vec<[f32; 3]> = (model.triangles.iter())
        .map(|t| vertex_colors[t[0] as usize])
        .collect();
    let mut first_at: HashMap<([u32; 3], [u32; 2]), u32> = HashMap::new();
    let keys: Vec<_> = (0..model.positions.len()).map(|v| key(model, v)).collect();
    let mut rename: Vec<u32> = Vec::with_capacity(keys.len());
    for (v, k) in keys.into_iter().enumerate() {
        rename.push(*first_at.entry(k).or_insert(v as u32));
    }
    for t in &mut model.triangles {
        *t = t.map(|v| rename[v as usize]);
    }
    model.colors = Some(Attribute::PerFace(face_colors));
    super::repair::drop_unused_vertices(model);
}

/// Where vertex `v` stands and its texture coordinates, as bits.
fn key(model: &Model, v: usize) -> ([u32; 3], [u32; 2]) {
    let uv = (model.texcoords.as_ref())
        .and_then(|t| t.get(v))
        .map_or([0; 2], |t| t.map(f32::to_bits));
    (position_key(model.positions[v]), uv)
}

/// True when two used vertices of `model` stand at one point with the same texture
/// coordinates.
fn has_coincident_vertices(model: &Model) -> bool {
    let mut used = vec![false; model.positions.len()];
    model
        .triangles
        .iter()
        .flatten()
        .for_each(|&v| used[v as usize] = true);
    let mut seen = std::collections::HashSet::new();
    (0..model.positions.len())
        .filter(|&v| used[v])
        .any(|v| !seen.insert(key(model, v)))
}

/// Appends a copy of each vertex in `originals` with its position and per-vertex
/// attributes (colours excepted: [`split`] sets them).
fn append_copies(model: &mut Model, originals: &[u32]) {
    let n = model.positions.len();
    for &v in originals {
        model.positions.push(model.positions[v as usize]);
    }
    if let Some(Attribute::PerVertex(normals)) = &mut model.normals {
        if normals.len() == n {
            originals
                .iter()
                .for_each(|&v| normals.push(normals[v as usize]));
        }
    }
    if let Some(texcoords) = &mut model.texcoords {
        if texcoords.len() == n {
            originals
                .iter()
                .for_each(|&v| texcoords.push(texcoords[v as usize]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Two unit squares side by side (x in [0, 2]), two triangles each, red on the left and
    /// blue on the right: the shared edge's two points get a copy each.
    fn two_squares() -> Model {
        Model {
            positions: (0..6)
                .map(|i| Vec3::new((i % 3) as f32, (i / 3) as f32, 0.0))
                .collect(),
            triangles: vec![[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]],
            colors: Some(Attribute::PerFace(vec![
                [1.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.0, 0.0, 1.0],
            ])),
            ..Model::default()
        }
    }

    #[test]
    fn a_colour_border_gets_one_vertex_per_side_and_merges_back_as_it_was() {
        let mut m = two_squares();
        let before = m.clone();
        assert!(split(&mut m));
        assert_eq!(m.positions.len(), 8);
        let Some(Attribute::PerVertex(c)) = &m.colors else {
            panic!("per-vertex colours expected")
        };
        for (t, want) in m
            .triangles
            .iter()
            .zip(before.colors.as_ref().unwrap().values())
        {
            assert!(t.iter().all(|&v| c[v as usize] == *want), "{t:?}");
        }
        merge(&mut m);
        assert_eq!(m, before);
    }

    #[test]
    fn colours_that_change_from_face_to_face_are_no_border_to_keep() {
        // A 20 × 20 grid of squares (441 vertices) with a colour per triangle: a border
        // everywhere would add more than a quarter of the vertices.
        let n = 20u32;
        let mut m = Model {
            positions: (0..(n + 1) * (n + 1))
                .map(|i| Vec3::new((i % (n + 1)) as f32, (i / (n + 1)) as f32, 0.0))
                .collect(),
            ..Model::default()
        };
        for i in 0..n {
            for j in 0..n {
                let v = |di: u32, dj: u32| (j + dj) * (n + 1) + i + di;
                m.triangles.push([v(0, 0), v(1, 0), v(1, 1)]);
                m.triangles.push([v(0, 0), v(1, 1), v(0, 1)]);
            }
        }
        let shades = (0..m.triangles.len())
            .map(|k| [k as f32 / 800.0; 3])
            .collect();
        m.colors = Some(Attribute::PerFace(shades));
        let before = m.clone();
        assert!(!split(&mut m));
        assert_eq!(m, before);
    }

    #[test]
    fn one_colour_or_an_unwelded_model_is_left_alone() {
        let mut m = two_squares();
        m.colors = Some(Attribute::PerFace(vec![[0.5; 3]; 4]));
        assert!(!split(&mut m));
        let mut m = two_squares();
        m.positions.push(m.positions[1]);
        m.triangles[2][0] = 6;
        assert!(!split(&mut m));
        assert_eq!(m.positions.len(), 7);
    }
}

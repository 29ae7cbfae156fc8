//! `MeshData`: the CPU side of what the GPU draws for one model — interleaved vertices,
//! triangle, edge and point index lists, and the face / vertex normal line segments — built
//! from a `Model` once per decimation, with no Vulkan in sight (so it is unit-tested).
//! Only the vertices and triangles are always built; the line and point lists are
//! [`Layers`] built when a draw mode needs them: they are most of the bytes, and a slider move
//! should not wait for lists nobody draws (docs/design.md#viewer-upload).
//!
//! Vertices are shared between triangles (indexed drawing), except where a corner needs its
//! own: with per-face colours, and at creases — a vertex whose faces differ by more than the
//! crease angle (the file's `creaseAngle`, else `DEFAULT_CREASE_DEG`) gets one normal per
//! corner, averaged over the faces within the crease angle of that corner's face, so smooth
//! shading keeps a cube's edges sharp. Flat shading needs no duplication: the fragment
//! shader derives the face normal from screen-space derivatives.

use glam::Vec3;
use rayon::prelude::*;

use decimate_core::mesh::{Attribute, Model};

/// Vertices or faces per parallel task: each takes well under a microsecond.
const PER_TASK: usize = 4096;

/// Crease angle for smooth shading when the file gives none.
pub const DEFAULT_CREASE_DEG: f32 = 45.0;

/// One vertex as the vertex shader reads it (locations 0 to 4).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    /// RGBA, 8 bits per channel (`R8G8B8A8_UNORM`).
    pub color: [u8; 4],
    /// Where a geomorph starts this vertex: the shader draws `mix(morph_from, position, t)`
    /// for the push constant `t` (1 when nothing morphs). Equal to `position` by default.
    pub morph_from: [f32; 3],
    /// Texture coordinates as the file gave them (origin at the image's bottom left); 0
    /// without any.
    pub uv: [f32; 2],
}

/// The optional parts of [`MeshData`]: which line and point lists are built.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Layers {
    pub edges: bool,
    pub points: bool,
    pub face_normals: bool,
    pub vertex_normals: bool,
}

impl Layers {
    /// Every list: what any draw mode may need.
    pub const ALL: Self = Self {
        edges: true,
        points: true,
        face_normals: true,
        vertex_normals: true,
    };

    /// True when every list in `other` is in `self`.
    pub fn contains(self, other: Self) -> bool {
        (self.edges || !other.edges)
            && (self.points || !other.points)
            && (self.face_normals || !other.face_normals)
            && (self.vertex_normals || !other.vertex_normals)
    }

    /// The lists in either.
    pub fn union(self, other: Self) -> Self {
        Self {
            edges: self.edges || other.edges,
            points: self.points || other.points,
            face_normals: self.face_normals || other.face_normals,
            vertex_normals: self.vertex_normals || other.vertex_normals,
        }
    }
}

/// What the GPU needs to draw one model: vertices and triangles, and the lists of `layers`
/// (those not asked for are empty).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshData {
    pub vertices: Vec<Vertex>,
    /// Three indices per triangle, counter-clockwise.
    pub triangles: Vec<u32>,
    /// Two indices per unique edge.
    pub edges: Vec<u32>,
    /// One index per vertex used by a triangle.
    pub points: Vec<u32>,
    /// Two vertices per segment: triangle centroid → centroid + normal × length.
    pub face_normals: Vec<Vertex>,
    /// Two vertices per segment: vertex → vertex + normal × length.
    pub vertex_normals: Vec<Vertex>,
}

impl MeshData {
    /// Builds every list of the draw data for `model`; normal segments are `normal_length`
    /// long (model units).
    pub fn from_model(model: &Model, normal_length: f32) -> Self {
        Self::build(model, normal_length, None, Layers::ALL)
    }

    /// As [`Self::from_model`], with only the lists of `layers`, and the geomorph start of
    /// every model vertex (`morph_from`, indexed like `model.positions`; ignored unless it
    /// has one entry per position). Normal segments do not morph.
    pub fn build(
        model: &Model,
        normal_length: f32,
        morph_from: Option<&[Vec3]>,
        layers: Layers,
    ) -> Self {
        let morph_from = morph_from.filter(|m| m.len() == model.positions.len());
        let incident = VertexFaces::new(model, model.positions.len());
        // Normals and creases are taken on the welded surface: the copies of a vertex split
        // at a texture seam share their faces, so a seam is no crease.
        let weld = welded_ids(model);
        let welded_incident = weld
            .as_ref()
            .map(|w| VertexFaces::welded(model, w, model.positions.len()));
        let welded = Welded {
            incident: welded_incident.as_ref().unwrap_or(&incident),
            id: weld.as_deref(),
        };
        let (face, normals) = surface_normals(model, &welded);
        let creases = Creases::new(model, &welded, &face);
        let corners = Corners {
            model,
            normals: &normals,
            creases: &creases,
            face_colors: match &model.colors {
                Some(Attribute::PerFace(c)) if c.len() == model.triangles.len() => Some(c),
                _ => None,
            },
            vertex_colors: match &model.colors {
                Some(Attribute::PerVertex(c)) if c.len() == model.positions.len() => Some(c),
                _ => None,
            },
            texcoords: (model.texcoords.as_deref()).filter(|t| t.len() == model.positions.len()),
            morph_from,
        };
        let (mut data, render_index) = corners.triangles();
        if layers.points {
            data.points = render_index
                .iter()
                .copied()
                .filter(|&i| i != u32::MAX)
                .collect();
        }
        // The line lists are independent of each other: built side by side.
        let ((edges, face_normals), vertex_normals) = rayon::join(
            || {
                rayon::join(
                    || {
                        when(layers.edges, || {
                            unique_edges(model, &incident, &render_index)
                        })
                    },
                    || {
                        when(layers.face_normals, || {
                            face_normal_segments(model, normal_length)
                        })
                    },
                )
            },
            || {
                when(layers.vertex_normals, || {
                    vertex_normal_segments(model, &normals, &render_index, normal_length)
                })
            },
        );
        data.edges = edges;
        data.face_normals = face_normals;
        data.vertex_normals = vertex_normals;
        data
    }
}

/// The face normals (empty when the file gave per-vertex normals: neither the vertex normals
/// nor the crease test then needs them) and the vertex normals of `model`.
fn surface_normals(model: &Model, welded: &Welded<'_>) -> (Vec<Vec3>, Vec<Vec3>) {
    let file_normals = match &model.normals {
        Some(Attribute::PerVertex(n)) if n.len() == model.positions.len() => Some(n),
        _ => None,
    };
    let face = if file_normals.is_some() {
        Vec::new()
    } else {
        face_normals(model)
    };
    let normals = match file_normals {
        Some(n) => n.par_iter().map(|v| v.normalize_or_zero()).collect(),
        None => welded.spread(gathered_normals(&face, welded.incident)),
    };
    (face, normals)
}

/// What a triangle corner's render vertex is made of.
struct Corners<'a> {
    model: &'a Model,
    normals: &'a [Vec3],
    creases: &'a Creases<'a>,
    face_colors: Option<&'a Vec<[f32; 3]>>,
    vertex_colors: Option<&'a Vec<[f32; 3]>>,
    texcoords: Option<&'a [[f32; 2]]>,
    morph_from: Option<&'a [Vec3]>,
}

impl Corners<'_> {
    /// The render vertices and the triangle list; and for each model vertex the render
    /// vertex that stands for it in point lists (its first, when corners have their own;
    /// `u32::MAX` when no triangle uses it).
    fn triangles(&self) -> (MeshData, Vec<u32>) {
        let model = self.model;
        let mut data = MeshData {
            vertices: Vec::with_capacity(model.positions.len()),
            triangles: Vec::with_capacity(3 * model.triangles.len()),
            ..MeshData::default()
        };
        let mut render_index = vec![u32::MAX; model.positions.len()];
        // The render vertex shared by every corner of `v` that needs no vertex of its own.
        let mut shared = vec![u32::MAX; model.positions.len()];
        for (t, tri) in model.triangles.iter().enumerate() {
            for &v in tri {
                let vi = v as usize;
                let own_corner = self.face_colors.is_some() || self.creases.is_creased(vi);
                let index = if !own_corner && shared[vi] != u32::MAX {
                    shared[vi]
                } else {
                    let index = data.vertices.len() as u32;
                    data.vertices.push(self.vertex(t, vi));
                    if !own_corner {
                        shared[vi] = index;
                    }
                    index
                };
                data.triangles.push(index);
                if render_index[vi] == u32::MAX {
                    render_index[vi] = index;
                }
            }
        }
        (data, render_index)
    }

    /// The render vertex of model vertex `vi` as a corner of triangle `t`.
    fn vertex(&self, t: usize, vi: usize) -> Vertex {
        let model = self.model;
        let normal = if self.creases.is_creased(vi) {
            self.creases.corner_normal(t, vi)
        } else {
            self.normals[vi]
        };
        let color_of_vertex = || to_rgba8(self.vertex_colors.map_or(model.diffuse, |c| c[vi]));
        Vertex {
            position: model.positions[vi].to_array(),
            normal: normal.to_array(),
            color: self
                .face_colors
                .map_or_else(color_of_vertex, |c| to_rgba8(c[t])),
            morph_from: (self.morph_from.map_or(model.positions[vi], |m| m[vi])).to_array(),
            uv: self.texcoords.map_or([0.0; 2], |t| t[vi]),
        }
    }
}

/// `build()` when `on`, else nothing.
fn when<T>(on: bool, build: impl FnOnce() -> Vec<T>) -> Vec<T> {
    if on {
        build()
    } else {
        Vec::new()
    }
}

/// Which vertices sit on a crease, and the faces around each vertex to average corner
/// normals over. None creased when the file gave per-vertex normals (they are used as they
/// are).
struct Creases<'a> {
    /// Face normals (twice the area, out of the counter-clockwise side).
    face: &'a [Vec3],
    welded: &'a Welded<'a>,
    creased: Vec<bool>,
    cos_crease: f32,
}

impl<'a> Creases<'a> {
    /// `face`: the model's face normals (twice the area), empty when the file gave
    /// per-vertex normals (then nothing is creased).
    fn new(model: &Model, welded: &'a Welded<'a>, face: &'a [Vec3]) -> Self {
        let crease = model
            .crease_angle
            .unwrap_or(DEFAULT_CREASE_DEG.to_radians());
        let mut c = Self {
            face,
            welded,
            creased: Vec::new(),
            cos_crease: crease.cos(),
        };
        c.creased = if face.is_empty() {
            vec![false; model.positions.len()]
        } else {
            (0..model.positions.len())
                .into_par_iter()
                .with_min_len(PER_TASK)
                .map(|v| {
                    let around = c.around(v);
                    around.iter().enumerate().any(|(i, &f)| {
                        around[i + 1..]
                            .iter()
                            .any(|&g| !c.within(f as usize, g as usize))
                    })
                })
                .collect()
        };
        c
    }

    fn around(&self, v: usize) -> &[u32] {
        self.welded.around(v)
    }

    /// True when faces `f` and `g` meet at no more than the crease angle.
    fn within(&self, f: usize, g: usize) -> bool {
        let (a, b) = (self.face[f], self.face[g]);
        a.dot(b) >= self.cos_crease * a.length() * b.length()
    }

    fn is_creased(&self, v: usize) -> bool {
        self.creased[v]
    }

    /// The normal of vertex `v` in face `t`: the area-weighted average over the faces around
    /// `v` within the crease angle of `t`.
    fn corner_normal(&self, t: usize, v: usize) -> Vec3 {
        self.around(v)
            .iter()
            .filter(|&&g| self.within(t, g as usize))
            .map(|&g| self.face[g as usize])
            .sum::<Vec3>()
            .normalize_or_zero()
    }
}

/// Two render indices per unique edge (undirected; a repeated corner's edge counts too),
/// each at its first appearance in triangle order. An edge is new in triangle `t` when no
/// earlier triangle has both its ends (in a triangle every two corners are joined) and no
/// earlier side of `t` is the same edge.
fn unique_edges(model: &Model, incident: &VertexFaces, render_index: &[u32]) -> Vec<u32> {
    let has_edge = |tri: &[u32; 3], a: u32, b: u32| {
        if a == b {
            tri.iter().filter(|&&v| v == a).count() >= 2
        } else {
            tri.contains(&a) && tri.contains(&b)
        }
    };
    let mut edges = Vec::with_capacity(model.triangles.len() * 3);
    for (t, tri) in model.triangles.iter().enumerate() {
        let sides = [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])];
        for (i, &(a, b)) in sides.iter().enumerate() {
            let same = |&(x, y): &(u32, u32)| (x.min(y), x.max(y)) == (a.min(b), a.max(b));
            if sides[..i].iter().any(same) {
                continue;
            }
            let earlier = incident
                .around(a as usize)
                .iter()
                .take_while(|&&f| (f as usize) < t)
                .any(|&f| has_edge(&model.triangles[f as usize], a, b));
            if !earlier {
                edges.push(render_index[a as usize]);
                edges.push(render_index[b as usize]);
            }
        }
    }
    edges
}

/// Each triangle's normal, a segment from its centroid.
fn face_normal_segments(model: &Model, normal_length: f32) -> Vec<Vertex> {
    let mut out = Vec::with_capacity(model.triangles.len() * 2);
    for tri in &model.triangles {
        let [a, b, c] = tri.map(|v| model.positions[v as usize]);
        let centre = (a + b + c) / 3.0;
        let normal = (b - a).cross(c - a).normalize_or_zero();
        push_segment(&mut out, centre, normal * normal_length);
    }
    out
}

/// Each used vertex's normal, a segment from the vertex.
fn vertex_normal_segments(
    model: &Model,
    normals: &[Vec3],
    render_index: &[u32],
    normal_length: f32,
) -> Vec<Vertex> {
    let mut out = Vec::new();
    for (v, &i) in render_index.iter().enumerate() {
        if i != u32::MAX {
            push_segment(&mut out, model.positions[v], normals[v] * normal_length);
        }
    }
    out
}

/// The model's vertices welded by position: `id[v]` is the first vertex at `v`'s position
/// (`None` when no two share one), and `incident` lists the faces around each such first
/// vertex.
struct Welded<'a> {
    incident: &'a VertexFaces,
    id: Option<&'a [u32]>,
}

impl Welded<'_> {
    /// The faces around `v` and every other copy of its position.
    fn around(&self, v: usize) -> &[u32] {
        self.incident.around(self.id.map_or(v, |id| id[v] as usize))
    }

    /// Per-vertex values computed for the first copies, given to every copy.
    fn spread(&self, first: Vec<Vec3>) -> Vec<Vec3> {
        match self.id {
            Some(id) => id.iter().map(|&w| first[w as usize]).collect(),
            None => first,
        }
    }
}

/// For each vertex the first vertex at the same position, or `None` when all positions
/// differ (no copies to weld). Only a textured model has copies: the scene builder welds
/// every other coincident vertex.
fn welded_ids(model: &Model) -> Option<Vec<u32>> {
    model.texcoords.as_ref()?;
    let mut first = std::collections::HashMap::with_capacity(model.positions.len());
    let id: Vec<u32> = (model.positions.iter().enumerate())
        .map(|(v, p)| {
            *first
                .entry(p.to_array().map(f32::to_bits))
                .or_insert(v as u32)
        })
        .collect();
    (first.len() < model.positions.len()).then_some(id)
}

/// Vertex → incident faces, ascending (a face with a repeated corner is listed once per
/// corner): shared by the crease test and the edge list.
struct VertexFaces {
    /// `faces[offsets[v]..offsets[v + 1]]` are the faces around `v`.
    offsets: Vec<u32>,
    faces: Vec<u32>,
}

impl VertexFaces {
    /// A counting sort of the corners by vertex.
    fn new(model: &Model, vertex_count: usize) -> Self {
        let mut offsets = vec![0u32; vertex_count + 1];
        for tri in &model.triangles {
            for &v in tri {
                offsets[v as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            offsets[v + 1] += offsets[v];
        }
        let mut fill = offsets.clone();
        let mut faces = vec![0; model.triangles.len() * 3];
        for (t, tri) in model.triangles.iter().enumerate() {
            for &v in tri {
                faces[fill[v as usize] as usize] = t as u32;
                fill[v as usize] += 1;
            }
        }
        Self { offsets, faces }
    }

    /// As [`Self::new`] with every corner counted at its welded vertex `weld[v]`.
    fn welded(model: &Model, weld: &[u32], vertex_count: usize) -> Self {
        let welded = Model {
            triangles: (model.triangles.iter())
                .map(|t| t.map(|v| weld[v as usize]))
                .collect(),
            ..Model::default()
        };
        Self::new(&welded, vertex_count)
    }

    fn around(&self, v: usize) -> &[u32] {
        &self.faces[self.offsets[v] as usize..self.offsets[v + 1] as usize]
    }

    fn vertex_count(&self) -> usize {
        self.offsets.len() - 1
    }
}

fn push_segment(out: &mut Vec<Vertex>, from: Vec3, along: Vec3) {
    for p in [from, from + along] {
        out.push(Vertex {
            position: p.to_array(),
            normal: along.normalize_or_zero().to_array(),
            color: [255; 4],
            morph_from: p.to_array(),
            uv: [0.0; 2],
        });
    }
}

fn to_rgba8(c: [f32; 3]) -> [u8; 4] {
    let q = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    [q(c[0]), q(c[1]), q(c[2]), 255]
}

/// Each triangle's normal, twice its area long, out of its counter-clockwise side.
fn face_normals(model: &Model) -> Vec<Vec3> {
    model
        .triangles
        .par_iter()
        .with_min_len(PER_TASK)
        .map(|tri| {
            let [a, b, c] = tri.map(|v| model.positions[v as usize]);
            (b - a).cross(c - a)
        })
        .collect()
}

/// Per-vertex normals when the file gave none: the area-weighted average of the adjacent
/// triangles' normals (the original computed them the same way), summed in face order.
fn gathered_normals(face: &[Vec3], incident: &VertexFaces) -> Vec<Vec3> {
    (0..incident.vertex_count())
        .into_par_iter()
        .with_min_len(PER_TASK)
        .map(|v| {
            incident
                .around(v)
                .iter()
                .map(|&f| face[f as usize])
                .fold(Vec3::ZERO, |sum, n| sum + n)
                .normalize_or_zero()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_texture_seam_is_no_crease() {
        // A sphere whose vertices on one meridian are split in two, as a texture seam splits
        // them: each copy shades as the unsplit vertex does, not from its side's faces only.
        let whole = decimate_core::mesh::shapes::uv_sphere(12, 24);
        let mut split = whole.clone();
        let bottom = whole.positions.len() as u32 - 1;
        // Texture coordinates are what splits vertices at a seam; their values do not matter.
        split.texcoords = Some(vec![[0.0; 2]; whole.positions.len()]);
        let meridian = |v: u32, s: u32| v != 0 && v != bottom && (v - 1) % 24 == s;
        let mut copy = std::collections::HashMap::new();
        for v in (0..bottom).filter(|&v| meridian(v, 0)) {
            copy.insert(v, split.positions.len() as u32);
            split.positions.push(whole.positions[v as usize]);
            if let Some(t) = &mut split.texcoords {
                t.push([1.0, 0.0]);
            }
        }
        for t in &mut split.triangles {
            if t.iter().any(|&v| meridian(v, 23)) {
                for v in t.iter_mut() {
                    *v = copy.get(v).copied().unwrap_or(*v);
                }
            }
        }
        let expected: std::collections::HashMap<_, _> = MeshData::from_model(&whole, 0.1)
            .vertices
            .iter()
            .map(|v| (v.position.map(f32::to_bits), Vec3::from(v.normal)))
            .collect();
        let d = MeshData::from_model(&split, 0.1);
        assert_eq!(
            d.vertices.len(),
            split.positions.len(),
            "no corner of its own"
        );
        for v in &d.vertices {
            let want = expected[&v.position.map(f32::to_bits)];
            assert!(
                Vec3::from(v.normal).angle_between(want) < 1e-3,
                "at {:?}: {:?}, unsplit {want:?}",
                v.position,
                v.normal
            );
        }
    }

    #[test]
    fn smooth_shading_keeps_a_cubes_edges_sharp_and_a_spheres_round() {
        // Every corner of the 2x2 cube shades with its own face's normal.
        let cube = decimate_core::mesh::shapes::test002();
        let d = MeshData::from_model(&cube, 0.1);
        for (t, tri) in d.triangles.chunks(3).enumerate() {
            let [a, b, c] = cube.triangles[t].map(|v| cube.positions[v as usize]);
            let face = (b - a).cross(c - a).normalize();
            for &i in tri {
                let n = Vec3::from(d.vertices[i as usize].normal);
                assert!(n.dot(face) > 0.9999, "triangle {t}: {n} vs {face}");
            }
        }
        // A smooth sphere (the bumps are steep only at the poles) keeps its vertices shared.
        let sphere = decimate_core::mesh::shapes::bumpy_sphere(24, 48);
        let d = MeshData::from_model(&sphere, 0.1);
        assert!(d.vertices.len() < sphere.positions.len() * 11 / 10);
    }

    /// Two triangles sharing the diagonal of the unit square in the z = 0 plane:
    /// ```text
    /// 3---2
    /// | / |
    /// 0---1
    /// ```
    fn square() -> Model {
        Model {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
                Vec3::new(9.0, 9.0, 9.0), // unused: no point, no normal
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..Model::default()
        }
    }

    #[test]
    fn shared_vertices_unique_edges_used_points() {
        let d = MeshData::from_model(&square(), 0.5);
        assert_eq!(d.vertices.len(), 4, "the unused vertex is not uploaded");
        assert_eq!(d.triangles, vec![0, 1, 2, 0, 2, 3]);
        assert_eq!(d.edges.len(), 2 * 5, "4 sides + 1 diagonal, each once");
        assert_eq!(d.points, vec![0, 1, 2, 3]);
        assert_eq!(d.face_normals.len(), 4);
        assert_eq!(d.vertex_normals.len(), 8);
    }

    #[test]
    fn every_edge_once_in_first_appearance_order_even_with_repeated_corners() {
        let mut model = decimate_core::mesh::shapes::uv_sphere(6, 8);
        // Corners repeated, a triangle given twice and one reversed: edges still once each.
        model.triangles.push([0, 0, 1]);
        model.triangles.push([2, 3, 3]);
        model.triangles.push([4, 4, 4]);
        let first = model.triangles[0];
        model.triangles.push(first);
        model.triangles.push([first[2], first[1], first[0]]);
        let identity: Vec<u32> = (0..model.positions.len() as u32).collect();
        let mut seen = std::collections::HashSet::new();
        let mut expected = Vec::new();
        for tri in &model.triangles {
            for (a, b) in [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])] {
                if seen.insert((a.min(b), a.max(b))) {
                    expected.extend([a, b]);
                }
            }
        }
        let incident = VertexFaces::new(&model, model.positions.len());
        assert_eq!(unique_edges(&model, &incident, &identity), expected);
    }

    #[test]
    fn counter_clockwise_gives_plus_z_normals() {
        let d = MeshData::from_model(&square(), 0.5);
        for v in &d.vertices[..4] {
            assert_eq!(v.normal, [0.0, 0.0, 1.0]);
        }
        let tip = d.face_normals[1].position;
        assert!(
            (tip[2] - 0.5).abs() < 1e-6,
            "segment points out of the front face: {tip:?}"
        );
    }

    #[test]
    fn per_face_colours_split_corners() {
        let mut m = square();
        m.colors = Some(Attribute::PerFace(vec![[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]));
        let d = MeshData::from_model(&m, 0.5);
        assert_eq!(d.vertices.len(), 6);
        assert_eq!(d.vertices[0].color, [255, 0, 0, 255]);
        assert_eq!(d.vertices[5].color, [0, 0, 255, 255]);
        assert_eq!(d.edges.len(), 2 * 5);
        assert_eq!(d.points.len(), 4);
    }

    #[test]
    fn texture_coordinates_follow_their_vertex_onto_split_corners() {
        let mut m = square();
        let uv: Vec<[f32; 2]> = (0..m.positions.len())
            .map(|i| [i as f32 * 0.25, 1.0 - i as f32 * 0.25])
            .collect();
        m.texcoords = Some(uv.clone());
        // Per-face colours give every corner its own vertex: each keeps its coordinates.
        m.colors = Some(Attribute::PerFace(vec![[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]));
        let d = MeshData::from_model(&m, 0.5);
        assert_eq!(d.vertices.len(), 6);
        let corners = m.triangles.iter().flatten();
        for (&index, &v) in d.triangles.iter().zip(corners) {
            assert_eq!(d.vertices[index as usize].uv, uv[v as usize]);
        }
        // Coordinates that do not match the positions are ignored, not misread.
        m.texcoords = Some(vec![[0.5; 2]]);
        let d = MeshData::from_model(&m, 0.5);
        assert!(d.vertices.iter().all(|v| v.uv == [0.0; 2]));
    }

    #[test]
    fn diffuse_colour_when_file_has_none() {
        let d = MeshData::from_model(&square(), 0.5);
        assert_eq!(d.vertices[0].color, [204, 204, 204, 255]);
    }

    #[test]
    fn only_the_lists_asked_for_are_built_and_the_rest_is_the_same() {
        let sphere = decimate_core::mesh::shapes::bumpy_sphere(24, 48);
        let all = MeshData::from_model(&sphere, 0.1);
        let filled = MeshData::build(&sphere, 0.1, None, Layers::default());
        assert_eq!(filled.vertices, all.vertices);
        assert_eq!(filled.triangles, all.triangles);
        assert!(filled.edges.is_empty() && filled.points.is_empty());
        assert!(filled.face_normals.is_empty() && filled.vertex_normals.is_empty());
        assert!(!all.edges.is_empty() && !all.face_normals.is_empty());
        let edges = Layers {
            edges: true,
            ..Layers::default()
        };
        let d = MeshData::build(&sphere, 0.1, None, edges);
        assert_eq!(d.edges, all.edges);
        assert!(d.points.is_empty());
        assert!(Layers::ALL.contains(edges) && !edges.contains(Layers::ALL));
        assert!(edges.contains(Layers::default()));
        assert_eq!(edges.union(Layers::ALL), Layers::ALL);
    }

    #[test]
    fn vertex_normals_are_the_area_weighted_sums_in_face_order() {
        // Reference: scatter every face's normal onto its corners, in face order.
        let model = decimate_core::mesh::shapes::bumpy_sphere(12, 20);
        let mut sums = vec![Vec3::ZERO; model.positions.len()];
        for tri in &model.triangles {
            let [a, b, c] = tri.map(|v| model.positions[v as usize]);
            for &v in tri {
                sums[v as usize] += (b - a).cross(c - a);
            }
        }
        let expected: Vec<Vec3> = sums.into_iter().map(Vec3::normalize_or_zero).collect();
        let incident = VertexFaces::new(&model, model.positions.len());
        assert_eq!(gathered_normals(&face_normals(&model), &incident), expected);
    }
}

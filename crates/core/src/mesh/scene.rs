//! `Scene` and `Model`: what a file holds once parsed, as flat arrays.
//!
//! A model is one shape of the file: positions in its local frame, triangles as index triples
//! (counter-clockwise seen from outside), a world transform accumulated from the scene graph,
//! and optional colours and normals bound per vertex or per face. Every algorithm and the
//! viewer work on these arrays; nothing here knows about file syntax. A file with a node
//! hierarchy (glTF) also leaves its `NodeTree`, shared by its models through `Instance`, so
//! that a writer of the same kind can write the hierarchy back.

use std::sync::Arc;

use glam::{DMat4, DQuat, DVec3, Mat4, Vec3};

/// A per-vertex or per-face attribute array (colours, normals).
#[derive(Debug, Clone, PartialEq)]
pub enum Attribute<T> {
    /// One value per vertex, indexed like `Model::positions`.
    PerVertex(Vec<T>),
    /// One value per triangle, indexed like `Model::triangles`.
    PerFace(Vec<T>),
}

impl<T> Attribute<T> {
    /// The values, whatever they are bound to.
    pub fn values(&self) -> &[T] {
        match self {
            Self::PerVertex(v) | Self::PerFace(v) => v,
        }
    }

    /// Keeps the values of the listed old vertices (or old faces), in that order: the
    /// compaction step after welding or decimation.
    pub fn select(&self, vertices: &[u32], faces: &[u32]) -> Self
    where
        T: Copy,
    {
        match self {
            Self::PerVertex(v) => {
                Self::PerVertex(vertices.iter().map(|&i| v[i as usize]).collect())
            }
            Self::PerFace(v) => Self::PerFace(faces.iter().map(|&i| v[i as usize]).collect()),
        }
    }
}

/// One triangle mesh of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// Name from the file (`DEF` name or the shape's position in the file), for summaries.
    pub name: String,
    /// Local-to-world transform accumulated through the scene graph.
    pub transform: Mat4,
    /// Where the model's frame stands in the file's coordinates, in full precision: a point's
    /// file coordinates are `origin + transform * position`. Zero unless the file's
    /// coordinates are far from zero (georeferenced scans, GIS, BIM), where f32 positions
    /// relative to it keep the precision that f32 file coordinates would lose.
    pub origin: DVec3,
    /// Vertex positions in the model's local frame.
    pub positions: Vec<Vec3>,
    /// Triangles, counter-clockwise when seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// RGB colours in 0..=1, if the file gave any.
    pub colors: Option<Attribute<[f32; 3]>>,
    /// Normals from the file, if any; `mesh::normals` computes them when absent.
    pub normals: Option<Attribute<Vec3>>,
    /// Texture coordinates (u, v), one per vertex, if the file gave any. A vertex where the
    /// texture has a seam is split into one vertex per side (same position, different
    /// coordinates), so the model is cut along its seams; decimation pins such vertices.
    pub texcoords: Option<Vec<[f32; 2]>>,
    /// The image the texture coordinates map, as the file named it (a URL or a path
    /// relative to the file's folder: VRML 2.0's `ImageTexture`, Inventor's `Texture2`, an
    /// OBJ's `map_Kd`); `io::rebase_textures` re-expresses it for another folder.
    pub texture: Option<String>,
    /// Whether the texture repeats along u and along v beyond 0..=1 (VRML 2.0's
    /// `repeatS`/`repeatT`, Inventor's `wrapS`/`wrapT`, an MTL's `-clamp`); where it does
    /// not, coordinates outside take the image's edge texels. Both true unless a file says.
    pub texture_repeat: [bool; 2],
    /// The material's name as the file gave it (OBJ `usemtl`), if any: what an OBJ output
    /// names its `newmtl` after.
    pub material: Option<String>,
    /// Diffuse colour of the shape's material (used when there are no per-vertex/face colours).
    pub diffuse: [f32; 3],
    /// Crease angle in radians from the file (ShapeHints / IndexedFaceSet), if given.
    pub crease_angle: Option<f32>,
    /// True when the file says the shape is a closed solid (back faces may be culled).
    pub solid: bool,
    /// The node and mesh primitive this model instances, when its file has a node tree.
    pub instance: Option<Instance>,
}

impl Default for Model {
    fn default() -> Self {
        Self {
            name: String::new(),
            transform: Mat4::IDENTITY,
            origin: DVec3::ZERO,
            positions: Vec::new(),
            triangles: Vec::new(),
            colors: None,
            normals: None,
            texcoords: None,
            texture: None,
            texture_repeat: [true; 2],
            material: None,
            diffuse: Self::DEFAULT_DIFFUSE,
            crease_angle: None,
            solid: false,
            instance: None,
        }
    }
}

impl Model {
    /// The diffuse colour of a shape whose file gives no material (VRML's default).
    pub const DEFAULT_DIFFUSE: [f32; 3] = [0.8, 0.8, 0.8];

    /// Whether coincident vertices may be the sides of a seam: the model has per-vertex
    /// attributes that the weld keeps apart (texture coordinates, per-vertex colours).
    pub fn has_seam_attributes(&self) -> bool {
        self.texcoords.is_some() || matches!(self.colors, Some(Attribute::PerVertex(_)))
    }

    /// Number of vertices that at least one triangle uses.
    pub fn used_vertex_count(&self) -> usize {
        let mut used = vec![false; self.positions.len()];
        for t in &self.triangles {
            for &v in t {
                used[v as usize] = true;
            }
        }
        used.iter().filter(|&&u| u).count()
    }

    /// Axis-aligned bounds of the positions in the local frame, `None` when empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }
}

/// Everything read from one file: its models, in file order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scene {
    /// The models, in file order.
    pub models: Vec<Model>,
}

impl Scene {
    /// Total vertices over all models.
    pub fn vertex_count(&self) -> usize {
        self.models.iter().map(|m| m.positions.len()).sum()
    }

    /// Total triangles over all models.
    pub fn triangle_count(&self) -> usize {
        self.models.iter().map(|m| m.triangles.len()).sum()
    }
}

/// Where a model stands in its file's node tree: the node that places it and which
/// primitive of that node's mesh it is. Models with the same tree, mesh and primitive are
/// instances of one mesh: decimated once (`decimate::simplify_scene`), written once.
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    /// The node tree the instance belongs to.
    pub tree: Arc<NodeTree>,
    /// Index into `tree.nodes`.
    pub node: usize,
    /// The primitive's index in the node's mesh.
    pub primitive: usize,
    /// True when the mesh cannot be decimated faithfully (skinned, morph targets): it is
    /// left as read, and the writer copies the source's primitive through unchanged.
    pub copied: bool,
}

impl Instance {
    /// The key instances of one mesh primitive share: the tree, mesh and primitive.
    pub fn mesh_key(&self) -> (*const NodeTree, Option<usize>, usize) {
        let mesh = self.tree.nodes.get(self.node).and_then(|n| n.mesh);
        (Arc::as_ptr(&self.tree), mesh, self.primitive)
    }
}

/// A file's node hierarchy as read: every node at its index in the file, the scene's
/// roots, and what a writer of the source's format copies through unchanged.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NodeTree {
    /// All nodes; parents refer to children by index.
    pub nodes: Vec<Node>,
    /// The displayed scene's root nodes.
    pub roots: Vec<usize>,
    /// Opaque to all but the writer of the source's format: for glTF, the skins, morph
    /// targets and animations as a JSON fragment and the bytes its accessors read.
    pub copied: Option<CopiedThrough>,
}

/// One node of a `NodeTree`.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// The node's name in the file, if it has one.
    pub name: Option<String>,
    /// The transform relative to the parent, in the form the file gave it.
    pub local: LocalTransform,
    /// Indices into the tree's nodes.
    pub children: Vec<usize>,
    /// The file's mesh this node places, by its index in the file.
    pub mesh: Option<usize>,
}

/// A node's transform relative to its parent, as a matrix or as translation, rotation and
/// scale (glTF 2.0 § 3.5.3): a writer writes back the form that was read. In f64, as the
/// file's numbers are: georeferenced files put far translations here (see `io::origin`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LocalTransform {
    /// A 4 × 4 matrix.
    Matrix(DMat4),
    /// Translation, rotation and scale, applied scale first.
    Trs {
        /// The translation.
        translation: DVec3,
        /// The rotation, a unit quaternion.
        rotation: DQuat,
        /// The scale along each axis.
        scale: DVec3,
    },
}

impl LocalTransform {
    /// The transform as a matrix.
    pub fn matrix(&self) -> DMat4 {
        match *self {
            Self::Matrix(m) => m,
            Self::Trs {
                translation,
                rotation,
                scale,
            } => DMat4::from_scale_rotation_translation(scale, rotation, translation),
        }
    }
}

/// Source data a writer copies through verbatim: a description (`json`) and the bytes it
/// indexes (`data`); see the writer of `format` for their layout.
#[derive(Debug, Clone, PartialEq)]
pub struct CopiedThrough {
    /// The format whose writer reads this (`"gltf"`).
    pub format: &'static str,
    /// The source's JSON, with the meshes this program replaces marked.
    pub json: String,
    /// The binary data the JSON indexes.
    pub data: Vec<u8>,
}

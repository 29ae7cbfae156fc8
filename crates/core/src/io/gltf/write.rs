//! Writing a `Scene` as glTF 2.0: `.glb` (one file, images embedded) or `.gltf` (JSON, with
//! its binary buffer in a `.bin` and its images beside it).
//!
//! Models read from a glTF file are written in its node tree (`mesh::NodeTree`): every node
//! at its index, with its name, local transform (matrix or TRS, as read) and children, and
//! one mesh per source mesh, its primitives the node's models, shared by every node that
//! places the same (decimated once, see `decimate::simplify_scene`). Skinned and morphed
//! meshes, points and lines primitives, skins, animations, cameras, lights and `extras` are
//! copied through from the source (`copy_through`), and a source material's factors and
//! texture-free extensions join the material written for its model. Other
//! models get one root node each, placed by the model's transform; models with the same
//! geometry and material share one glTF mesh. Each model is one triangle primitive:
//! POSITION, NORMAL (per-vertex normals, unit length; per-face normals are left out, which
//! glTF draws flat anyway), TEXCOORD_0 (v flipped back to glTF's top-down images) and
//! COLOR_0; a model with per-face colours is written with one vertex per triangle corner.
//! Materials carry the diffuse colour as the base colour factor (not metallic, fully
//! rough), the texture as the base colour texture (PNG or JPEG images only; another
//! image's texture is left out, named by `image_losses`) and `doubleSided` for a shape that
//! is not `solid`. Every file goes through `replace_file` (a temporary file,
//! then a rename).

use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};
use std::hash::{Hash, Hasher};
use std::io::Write;
use std::path::{Path, PathBuf};

use glam::Mat4;
use serde_json::{json, Map, Value};

use super::copy_through::Spliced;
use crate::io::{data_uri, texture_path, WriteError};
use crate::mesh::{Attribute, LocalTransform, Model, NodeTree, Scene};

/// glTF's numbers for component types and buffer view targets (glTF 2.0 § 5.1, § 5.11).
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// Sampler wrapping modes (glTF 2.0 § 5.26).
const REPEAT: u32 = 10497;
const CLAMP_TO_EDGE: u32 = 33071;

/// Writes `scene` to `path` as binary glTF when its extension is `.glb`, else as JSON glTF
/// with `NAME.bin` (and any embedded images) beside it. Texture names are read relative to
/// `path`'s folder (see `io::rebase_textures`).
pub fn write_gltf(scene: &Scene, path: &Path) -> Result<(), WriteError> {
    let binary = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    let folder = texture_path::folder_of(path).to_path_buf();
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    let mut b = Builder {
        binary,
        folder: folder.clone(),
        stem: stem.clone(),
        ..Builder::default()
    };
    let (tree, placed, flat) = placement(scene);
    if let Some(tree) = tree {
        b.tree(tree, &placed);
    }
    for m in flat {
        b.model(m);
    }
    let too_big = |what: &str| WriteError {
        file: path.to_path_buf(),
        source: std::io::Error::other(format!(
            "the scene's {what} is larger than a glTF file can hold (4 GiB)"
        )),
    };
    if b.bin.len() > u32::MAX as usize - 4096 {
        return Err(too_big("binary buffer"));
    }
    // A `.gltf`'s images from `data:` URIs are written beside it first.
    for (name, bytes) in &b.files {
        crate::io::write_atomically(&folder.join(name), |w| w.write_all(bytes))?;
    }
    let bin_name = format!("{stem}.bin");
    let json = b.document(&bin_name);
    if binary {
        let json = serde_json::to_vec(&json).map_err(|e| WriteError {
            file: path.to_path_buf(),
            source: std::io::Error::other(e),
        })?;
        if json.len() + b.bin.len() > u32::MAX as usize - 64 {
            return Err(too_big("JSON and binary buffer"));
        }
        crate::io::write_atomically(path, |w| write_glb(w, &json, &b.bin))
    } else {
        if !b.bin.is_empty() {
            crate::io::write_atomically(&folder.join(&bin_name), |w| w.write_all(&b.bin))?;
        }
        crate::io::write_atomically(path, |w| {
            serde_json::to_writer_pretty(&mut *w, &json).map_err(std::io::Error::other)?;
            w.write_all(b"\n")
        })
    }
}

/// The GLB container (glTF 2.0 § 4.4): a 12-byte header, the JSON chunk padded with spaces
/// and the BIN chunk padded with zeros, each to four bytes.
fn write_glb(w: &mut impl Write, json: &[u8], bin: &[u8]) -> std::io::Result<()> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let mut total = 12 + 8 + json_len;
    if !bin.is_empty() {
        total += 8 + bin_len;
    }
    let u32_of = |n: usize| u32::try_from(n).map_err(std::io::Error::other);
    w.write_all(b"glTF")?;
    w.write_all(&2u32.to_le_bytes())?;
    w.write_all(&u32_of(total)?.to_le_bytes())?;
    w.write_all(&u32_of(json_len)?.to_le_bytes())?;
    w.write_all(b"JSON")?;
    w.write_all(json)?;
    w.write_all(&b"   "[..pad(json.len())])?;
    if !bin.is_empty() {
        w.write_all(&u32_of(bin_len)?.to_le_bytes())?;
        w.write_all(b"BIN\0")?;
        w.write_all(bin)?;
        w.write_all(&[0u8; 3][..pad(bin.len())])?;
    }
    w.flush()
}

/// The document being built: the binary buffer and every JSON array that indexes into it.
#[derive(Default)]
struct Builder<'s> {
    binary: bool,
    folder: PathBuf,
    stem: String,
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    materials: Vec<Value>,
    textures: Vec<Value>,
    images: Vec<Value>,
    samplers: Vec<Value>,
    nodes: Vec<Value>,
    /// The scene's root nodes.
    roots: Vec<usize>,
    skins: Vec<Value>,
    animations: Vec<Value>,
    extensions_required: Vec<String>,
    cameras: Vec<Value>,
    lights: Vec<Value>,
    /// The source asset's and scene's fields carried (`copyright`, `name`, `extras`).
    asset: Map<String, Value>,
    scene: Map<String, Value>,
    /// Files to write beside a `.gltf` (images that came as `data:` URIs): name, bytes.
    files: Vec<(String, Vec<u8>)>,
    /// Image index by texture name (`None`: the image cannot be written).
    image_of: HashMap<String, Option<usize>>,
    material_of: HashMap<String, usize>,
    sampler_of: HashMap<[bool; 2], usize>,
    /// Meshes written, by a hash of geometry, material and winding: equal models share one.
    mesh_of: HashMap<u64, Vec<(usize, &'s Model)>>,
    /// Meshes written for a source mesh: the mesh and the models and materials it holds.
    /// Keyed by the source mesh and a hash of the parts (`geometry_hash`).
    source_mesh_of: HashMap<(usize, u64), Vec<(usize, Parts<'s>)>>,
}

/// A written mesh's models, one per primitive, each with its material's index.
type Parts<'s> = Vec<(&'s Model, usize)>;

/// A tree's models: by node, then by primitive of the node's mesh.
type Placed<'s> = BTreeMap<usize, BTreeMap<usize, &'s Model>>;

/// The tree models of `scene` share (that of its first model with one), each tree node's
/// models by primitive, and the models written flat (no tree, or another tree).
fn placement(scene: &Scene) -> (Option<&NodeTree>, Placed<'_>, Vec<&Model>) {
    let tree = scene
        .models
        .iter()
        .find_map(|m| m.instance.as_ref())
        .map(|i| &i.tree);
    let mut placed = Placed::new();
    let mut flat = Vec::new();
    for m in &scene.models {
        match (&m.instance, tree) {
            (Some(i), Some(tree))
                if std::sync::Arc::ptr_eq(&i.tree, tree) && i.node < tree.nodes.len() =>
            {
                // A node reached by two paths places the same geometry twice: written once.
                // Another geometry in the same place (a model split after reading) goes flat.
                let slot = placed.entry(i.node).or_default().entry(i.primitive);
                match slot {
                    std::collections::btree_map::Entry::Vacant(e) => {
                        e.insert(m);
                    }
                    std::collections::btree_map::Entry::Occupied(e) => {
                        if !same_geometry(e.get(), m) {
                            flat.push(m);
                        }
                    }
                }
            }
            _ => flat.push(m),
        }
    }
    (tree.map(|t| &**t), placed, flat)
}

impl<'s> Builder<'s> {
    fn document(&self, bin_name: &str) -> Value {
        let mut asset = self.asset.clone();
        asset.insert("version".into(), json!("2.0"));
        asset.insert("generator".into(), json!("decimate"));
        let mut scene = self.scene.clone();
        scene.insert("nodes".into(), json!(self.roots));
        let mut doc = json!({ "asset": asset, "scene": 0, "scenes": [scene] });
        // Every extension written: the copied accessors', the lights', the materials'.
        let mut used: std::collections::BTreeSet<String> =
            self.extensions_required.iter().cloned().collect();
        if !self.lights.is_empty() {
            used.insert("KHR_lights_punctual".into());
            doc["extensions"] = json!({ "KHR_lights_punctual": { "lights": self.lights } });
        }
        for m in &self.materials {
            used.extend(
                m["extensions"]
                    .as_object()
                    .into_iter()
                    .flat_map(|e| e.keys().cloned()),
            );
        }
        if !used.is_empty() {
            doc["extensionsUsed"] = json!(used);
        }
        if !self.extensions_required.is_empty() {
            doc["extensionsRequired"] = json!(self.extensions_required);
        }
        let mut set = |key: &str, list: &[Value]| {
            if !list.is_empty() {
                doc[key] = Value::Array(list.to_vec());
            }
        };
        set("nodes", &self.nodes);
        set("cameras", &self.cameras);
        set("meshes", &self.meshes);
        set("materials", &self.materials);
        set("textures", &self.textures);
        set("images", &self.images);
        set("samplers", &self.samplers);
        set("skins", &self.skins);
        set("animations", &self.animations);
        set("accessors", &self.accessors);
        set("bufferViews", &self.views);
        if !self.bin.is_empty() {
            let mut buffer = json!({ "byteLength": self.bin.len() });
            if !self.binary {
                buffer["uri"] = Value::String(uri_of(bin_name));
            }
            doc["buffers"] = json!([buffer]);
        }
        doc
    }

    /// Appends `bytes` to the buffer as one view (4-byte aligned) and returns its index.
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    /// A float attribute accessor of `N` components per element; `bounds` adds min and max.
    fn floats<const N: usize>(&mut self, values: &[[f32; N]], bounds: bool) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flat_map(|v| v.iter().flat_map(|c| c.to_le_bytes()))
            .collect();
        let view = self.view(&bytes, Some(ARRAY_BUFFER));
        let kind = ["SCALAR", "VEC2", "VEC3", "VEC4"][N - 1];
        let mut a = json!({ "bufferView": view, "componentType": FLOAT, "count": values.len(), "type": kind });
        if bounds {
            let mut lo = [f32::INFINITY; N];
            let mut hi = [f32::NEG_INFINITY; N];
            for v in values {
                for k in 0..N {
                    lo[k] = lo[k].min(v[k]);
                    hi[k] = hi[k].max(v[k]);
                }
            }
            a["min"] = json!(lo.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
            a["max"] = json!(hi.iter().map(|&x| f64::from(x)).collect::<Vec<_>>());
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// The triangles as an index accessor. A model's winding is glTF's as it stands: under
    /// a mirroring transform both turn clockwise in the world (glTF 2.0 § 3.7.2.1).
    fn indices(&mut self, triangles: &[[u32; 3]]) -> usize {
        let mut bytes = Vec::with_capacity(triangles.len() * 12);
        for t in triangles {
            for &i in t {
                bytes.extend_from_slice(&i.to_le_bytes());
            }
        }
        let view = self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_INT,
            "count": triangles.len() * 3, "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// One node for `m`, and its mesh unless an equal one was written already.
    fn model(&mut self, m: &'s Model) {
        if m.positions.is_empty() || m.triangles.is_empty() {
            return;
        }
        let material = self.material(m, None);
        let key = geometry_hash(m, material);
        let shared = self
            .mesh_of
            .get(&key)
            .and_then(|list| list.iter().find(|(_, o)| same_geometry(o, m)))
            .map(|&(mesh, _)| mesh);
        let mesh = match shared {
            Some(mesh) => mesh,
            None => {
                let mesh = self.mesh(m, material);
                self.mesh_of.entry(key).or_default().push((mesh, m));
                mesh
            }
        };
        let mut node = json!({ "mesh": mesh });
        if !m.name.is_empty() {
            node["name"] = json!(m.name);
        }
        if m.transform != Mat4::IDENTITY {
            node["matrix"] = json!(m.transform.to_cols_array().map(f64::from));
        }
        if m.origin != glam::DVec3::ZERO {
            // A far model's origin goes in a parent node's translation, which JSON holds in
            // full; the accessor keeps the f32 positions relative to it (as exporters do).
            self.nodes.push(node);
            node = json!({
                "translation": m.origin.to_array(),
                "children": [self.nodes.len() - 1],
            });
        }
        self.roots.push(self.nodes.len());
        self.nodes.push(node);
    }

    /// The node tree at the source's indices, each node's mesh made of its `placed` models
    /// (by primitive); then what the source copies through: skins and animations.
    fn tree(&mut self, tree: &'s NodeTree, placed: &Placed<'s>) {
        let spliced = tree
            .copied
            .as_ref()
            .and_then(|c| Spliced::new(c, &mut self.accessors, &mut self.views, &mut self.bin));
        for (i, node) in tree.nodes.iter().enumerate() {
            let mut out = json!({});
            if let Some(name) = &node.name {
                out["name"] = json!(name);
            }
            match node.local {
                LocalTransform::Matrix(m) if m != glam::DMat4::IDENTITY => {
                    out["matrix"] = json!(m.to_cols_array());
                }
                LocalTransform::Matrix(_) => {}
                LocalTransform::Trs {
                    translation,
                    rotation,
                    scale,
                } => {
                    if translation != glam::DVec3::ZERO {
                        out["translation"] = json!(translation.to_array());
                    }
                    if rotation != glam::DQuat::IDENTITY {
                        out["rotation"] = json!(rotation.to_array());
                    }
                    if scale != glam::DVec3::ONE {
                        out["scale"] = json!(scale.to_array());
                    }
                }
            }
            if !node.children.is_empty() {
                out["children"] = json!(node.children);
            }
            let empty = BTreeMap::new();
            let models = placed.get(&i).unwrap_or(&empty);
            let mesh = node
                .mesh
                .and_then(|source| self.source_mesh(source, i, models, spliced.as_ref()));
            if let Some(mesh) = mesh {
                out["mesh"] = json!(mesh);
            }
            // A skin and morph weights only beside the mesh they apply to.
            let fields = spliced.as_ref().and_then(|s| s.node_fields(i));
            for (key, v) in fields.into_iter().flatten() {
                if mesh.is_some() || !matches!(key.as_str(), "skin" | "weights") {
                    out[key.as_str()] = v.clone();
                }
            }
            self.nodes.push(out);
        }
        self.roots.extend(tree.roots.iter().copied());
        if let Some(s) = spliced {
            self.skins = s.skins();
            self.animations = s.animations();
            self.extensions_required = s.extensions_required();
            self.cameras = s.cameras();
            self.lights = s.lights();
            self.asset = s.asset();
            self.scene = s.scene();
        }
    }

    /// The mesh for source mesh `source` placed by node `node` with `models` (by
    /// primitive) and the source's points and lines: the one written for another node when
    /// it holds the same, else a new one, copied through when the source's is. `None` when
    /// nothing is left to write.
    fn source_mesh(
        &mut self,
        source: usize,
        node: usize,
        models: &BTreeMap<usize, &'s Model>,
        spliced: Option<&Spliced>,
    ) -> Option<usize> {
        let parts: Vec<(usize, &'s Model)> = models
            .iter()
            .filter(|(_, m)| !m.positions.is_empty() && !m.triangles.is_empty())
            .map(|(&p, &m)| (p, m))
            .collect();
        let lines = match spliced {
            Some(s) if s.places_lines(node) => s.lines(source),
            _ => Vec::new(),
        };
        if parts.is_empty() && lines.is_empty() {
            return None;
        }
        let with_materials: Parts<'s> = parts
            .iter()
            .map(|&(p, m)| {
                let from = spliced.and_then(|s| s.source_material(source, p));
                (m, self.material(m, from))
            })
            .collect();
        let key = parts_key(source, &with_materials);
        if let Some(mesh) = self.held_mesh(key, &with_materials) {
            return Some(mesh);
        }
        let mut mesh = self.mesh_json(source, &parts, &with_materials, spliced);
        if let Some(s) = spliced {
            self.add_lines(&mut mesh, &parts, lines, s);
            for (key, v) in s.mesh_fields(source) {
                mesh[key.as_str()] = v;
            }
        }
        self.meshes.push(mesh);
        let index = self.meshes.len() - 1;
        self.source_mesh_of
            .entry(key)
            .or_default()
            .push((index, with_materials));
        Some(index)
    }

    /// The mesh written before for the same source and the same models, if any.
    fn held_mesh(&self, key: (usize, u64), with_materials: &Parts<'s>) -> Option<usize> {
        let same = |a: &[(&Model, usize)], b: &[(&Model, usize)]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|((x, i), (y, j))| i == j && same_geometry(x, y))
        };
        let list = self.source_mesh_of.get(&key)?;
        let (mesh, _) = list.iter().find(|(_, held)| same(held, with_materials))?;
        Some(*mesh)
    }

    /// A new mesh's JSON for `parts` (by source primitive): the source's primitives copied
    /// through when every model is a copied one, else primitives written from the models.
    fn mesh_json(
        &mut self,
        source: usize,
        parts: &[(usize, &'s Model)],
        with_materials: &Parts<'s>,
        spliced: Option<&Spliced>,
    ) -> Value {
        let copied = parts
            .iter()
            .all(|(_, m)| m.instance.as_ref().is_some_and(|i| i.copied));
        let verbatim = spliced
            .filter(|_| copied && !parts.is_empty())
            .and_then(|s| s.mesh(source));
        match verbatim {
            Some(mut mesh) => {
                // The source's primitives that were read, each with its model's material.
                let prims = mesh["primitives"].as_array().cloned().unwrap_or_default();
                let kept: Vec<Value> = parts
                    .iter()
                    .zip(with_materials)
                    .filter_map(|(&(p, _), &(_, material))| {
                        let mut prim = prims.get(p)?.clone();
                        prim["material"] = json!(material);
                        Some(prim)
                    })
                    .collect();
                mesh["primitives"] = json!(kept);
                mesh
            }
            None => {
                let prims: Vec<Value> = with_materials
                    .iter()
                    .map(|&(m, material)| self.primitive(m, material))
                    .collect();
                json!({ "primitives": prims })
            }
        }
    }

    /// Puts the source's points and lines primitives `lines` into `mesh` at their places
    /// among the triangle primitives of `parts` (by source index), with their materials.
    fn add_lines(
        &mut self,
        mesh: &mut Value,
        parts: &[(usize, &Model)],
        lines: Vec<(usize, Value)>,
        spliced: &Spliced,
    ) {
        if lines.is_empty() {
            return;
        }
        let triangles = mesh["primitives"].as_array().cloned().unwrap_or_default();
        let mut all: Vec<(usize, Value)> = parts.iter().map(|&(p, _)| p).zip(triangles).collect();
        for (p, mut prim) in lines {
            let source = prim.get("material").and_then(Value::as_u64);
            match source.and_then(|k| spliced.material(k as usize)) {
                Some(material) => prim["material"] = json!(self.add_material(material.clone())),
                None => {
                    if let Some(o) = prim.as_object_mut() {
                        o.remove("material");
                    }
                }
            }
            all.push((p, prim));
        }
        all.sort_by_key(|(p, _)| *p);
        mesh["primitives"] = Value::Array(all.into_iter().map(|(_, prim)| prim).collect());
    }

    /// Writes `m`'s vertex arrays and triangles as a one-primitive mesh.
    fn mesh(&mut self, m: &Model, material: usize) -> usize {
        let mut mesh = json!({ "primitives": [self.primitive(m, material)] });
        if !m.name.is_empty() {
            mesh["name"] = json!(m.name);
        }
        self.meshes.push(mesh);
        self.meshes.len() - 1
    }

    /// `m`'s vertex arrays and triangles as a triangle primitive.
    fn primitive(&mut self, m: &Model, material: usize) -> Value {
        let m = one_vertex_per_corner_if_face_colored(m);
        let positions: Vec<[f32; 3]> = m.positions.iter().map(|p| p.to_array()).collect();
        let mut attributes = json!({ "POSITION": self.floats(&positions, true) });
        if let Some(normals) = unit_normals(&m) {
            attributes["NORMAL"] = json!(self.floats(&normals, false));
        }
        if let Some(uv) = m
            .texcoords
            .as_ref()
            .filter(|t| t.len() == m.positions.len())
        {
            let uv: Vec<[f32; 2]> = uv.iter().map(|&[u, v]| [u, 1.0 - v]).collect();
            attributes["TEXCOORD_0"] = json!(self.floats(&uv, false));
        }
        if let Some(Attribute::PerVertex(c)) = &m.colors {
            if c.len() == m.positions.len() {
                let c: Vec<[f32; 3]> = c.iter().map(|c| c.map(|x| x.clamp(0.0, 1.0))).collect();
                attributes["COLOR_0"] = json!(self.floats(&c, false));
            }
        }
        let indices = self.indices(&m.triangles);
        json!({ "attributes": attributes, "indices": indices, "material": material })
    }

    /// The material for `m` (diffuse colour, texture, wrapping, sidedness), shared by every
    /// model that has the same; with what `source` (the glTF material read, without
    /// textures) says beside them: its factors, alpha, `extras` and extensions.
    fn material(&mut self, m: &Model, source: Option<&Value>) -> usize {
        let textured = m.texcoords.is_some();
        let image = match (&m.texture, textured) {
            (Some(name), true) => self.image(name),
            _ => None,
        };
        let [r, g, b] = m.diffuse.map(|c| f64::from(c.clamp(0.0, 1.0)));
        let mut pbr = json!({
            "baseColorFactor": [r, g, b, 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": 1.0,
        });
        if let Some(image) = image {
            let sampler = self.sampler(m.texture_repeat);
            let texture = json!({ "source": image, "sampler": sampler });
            let index = match self.textures.iter().position(|t| *t == texture) {
                Some(i) => i,
                None => {
                    self.textures.push(texture);
                    self.textures.len() - 1
                }
            };
            pbr["baseColorTexture"] = json!({ "index": index });
        }
        let mut material = json!({ "pbrMetallicRoughness": pbr, "doubleSided": !m.solid });
        if let Some(name) = &m.material {
            material["name"] = json!(name);
        }
        if let Some(source) = source {
            carry_material_fields(&mut material, source);
        }
        self.add_material(material)
    }

    /// `material`'s index, written once however many primitives use it.
    fn add_material(&mut self, material: Value) -> usize {
        let key = material.to_string();
        if let Some(&i) = self.material_of.get(&key) {
            return i;
        }
        self.materials.push(material);
        self.material_of.insert(key, self.materials.len() - 1);
        self.materials.len() - 1
    }

    fn sampler(&mut self, repeat: [bool; 2]) -> usize {
        if let Some(&i) = self.sampler_of.get(&repeat) {
            return i;
        }
        let wrap = |r: bool| if r { REPEAT } else { CLAMP_TO_EDGE };
        self.samplers
            .push(json!({ "wrapS": wrap(repeat[0]), "wrapT": wrap(repeat[1]) }));
        self.sampler_of.insert(repeat, self.samplers.len() - 1);
        self.samplers.len() - 1
    }

    /// The image a texture name points at, written once: embedded in a `.glb`; beside a
    /// `.gltf` (by its name when it is a file, as a new file when it is a `data:` URI).
    /// `None` when it cannot be read or is not PNG or JPEG.
    fn image(&mut self, name: &str) -> Option<usize> {
        if let Some(&i) = self.image_of.get(name) {
            return i;
        }
        let i = self.new_image(name);
        self.image_of.insert(name.to_string(), i);
        i
    }

    fn new_image(&mut self, name: &str) -> Option<usize> {
        let (bytes, media_type, embedded) = load_image(name, &self.folder).ok()?;
        let image = if self.binary {
            let view = self.view(&bytes, None);
            json!({ "bufferView": view, "mimeType": media_type })
        } else if embedded {
            let ext = if media_type == "image/png" {
                "png"
            } else {
                "jpg"
            };
            let file = format!("{}_image{}.{ext}", self.stem, self.images.len());
            let uri = uri_of(&file);
            self.files.push((file, bytes));
            json!({ "uri": uri })
        } else {
            json!({ "uri": uri_of(&name.replace('\\', "/")) })
        };
        self.images.push(image);
        Some(self.images.len() - 1)
    }
}

/// The fields of a source glTF material beyond a model's (factors, alpha, `extras`,
/// texture-free extensions), onto `material`: an emissive strength keeps its emissive
/// factor, a metal stays metallic.
fn carry_material_fields(material: &mut Value, source: &Value) {
    for key in [
        "emissiveFactor",
        "alphaMode",
        "alphaCutoff",
        "extras",
        "extensions",
    ] {
        if let Some(v) = source.get(key) {
            material[key] = v.clone();
        }
    }
    let pbr = &source["pbrMetallicRoughness"];
    // Written as floats, as the writer's own factors are.
    for key in ["metallicFactor", "roughnessFactor"] {
        if let Some(v) = pbr.get(key).and_then(Value::as_f64) {
            material["pbrMetallicRoughness"][key] = json!(v);
        }
    }
    if let Some(alpha) = pbr["baseColorFactor"].get(3).and_then(Value::as_f64) {
        material["pbrMetallicRoughness"]["baseColorFactor"][3] = json!(alpha);
    }
}

/// The bytes and media type of the image a texture name points at from `folder`, and
/// whether it came embedded (`data:` URI); why not, when it cannot be written.
fn load_image(name: &str, folder: &Path) -> Result<(Vec<u8>, &'static str, bool), String> {
    let (bytes, embedded) = match data_uri::parse(name) {
        Some(d) => (d?.bytes, true),
        None => {
            let file = image_file(name, folder).ok_or("it is not a file glTF can embed")?;
            let bytes = crate::io::file_limits::read_regular(&file)
                .map_err(|e| format!("{}: {e}", file.display()))?;
            (bytes, false)
        }
    };
    let media_type = data_uri::image_media_type(&bytes).ok_or("it is not a PNG or JPEG image")?;
    Ok((bytes, media_type, embedded))
}

/// One warning for each texture image a glTF file written at `path` leaves out (it cannot
/// be read, or is not PNG or JPEG), naming the image and why.
pub fn image_losses(scene: &Scene, path: &Path) -> Vec<String> {
    let folder = texture_path::folder_of(path);
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for m in &scene.models {
        let Some(name) = m.texture.as_deref().filter(|_| m.texcoords.is_some()) else {
            continue;
        };
        if !seen.insert(name) {
            continue;
        }
        if let Err(why) = load_image(name, folder) {
            let shown = match data_uri::is_data_uri(name) {
                true => "an embedded image".to_string(),
                false => format!("'{name}'"),
            };
            out.push(format!(
                "the texture image {shown} of {} is left out of the glTF file: {why}",
                m.name
            ));
        }
    }
    out
}

/// The file a (non-`data:`) texture name points at from `folder`; `None` for other URLs.
fn image_file(name: &str, folder: &Path) -> Option<PathBuf> {
    if let Some(rest) = name.strip_prefix("file://") {
        return Some(PathBuf::from(
            rest.strip_prefix("localhost").unwrap_or(rest),
        ));
    }
    if texture_path::has_url_scheme(name) {
        return None;
    }
    Some(folder.join(name.replace('\\', "/")))
}

/// A relative file name as a URI: bytes other than unreserved characters and `/` are
/// percent-encoded (RFC 3986), so spaces and `#` survive.
fn uri_of(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    for b in name.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_' | b'~' | b'/') {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// `m`'s per-vertex normals scaled to unit length, as glTF requires; `None` when it has
/// none per vertex or one cannot be (zero or not finite).
fn unit_normals(m: &Model) -> Option<Vec<[f32; 3]>> {
    let Some(Attribute::PerVertex(n)) = &m.normals else {
        return None;
    };
    if n.len() != m.positions.len() {
        return None;
    }
    n.iter()
        .map(|v| v.try_normalize().map(|u| u.to_array()))
        .collect()
}

/// `m` with one vertex per triangle corner when its colours are per face (glTF colours
/// are per vertex); `m` itself otherwise.
fn one_vertex_per_corner_if_face_colored(m: &Model) -> Cow<'_, Model> {
    let Some(Attribute::PerFace(colors)) = &m.colors else {
        return Cow::Borrowed(m);
    };
    let corners: Vec<u32> = m.triangles.iter().flatten().copied().collect();
    fn pick<T: Copy>(corners: &[u32], v: &[T]) -> Vec<T> {
        corners.iter().map(|&c| v[c as usize]).collect()
    }
    let normals = match &m.normals {
        Some(Attribute::PerVertex(n)) if n.len() == m.positions.len() => {
            Some(Attribute::PerVertex(pick(&corners, n)))
        }
        _ => None,
    };
    let per_corner = m
        .triangles
        .iter()
        .enumerate()
        .flat_map(|(t, _)| [colors.get(t).copied().unwrap_or(m.diffuse); 3])
        .collect();
    Cow::Owned(Model {
        positions: pick(&corners, &m.positions),
        triangles: (0..m.triangles.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect(),
        normals,
        texcoords: m
            .texcoords
            .as_ref()
            .filter(|t| t.len() == m.positions.len())
            .map(|t| pick(&corners, t)),
        colors: Some(Attribute::PerVertex(per_corner)),
        name: m.name.clone(),
        texture: m.texture.clone(),
        material: m.material.clone(),
        instance: m.instance.clone(),
        ..*m
    })
}

/// A hash of what makes two models' glTF meshes the same (a sample of their arrays: equal
/// hashes are compared in full by `same_geometry`).
fn geometry_hash(m: &Model, material: usize) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    (material, m.positions.len(), m.triangles.len()).hash(&mut h);
    for p in m.positions.iter().take(64) {
        p.to_array().map(f32::to_bits).hash(&mut h);
    }
    m.triangles.iter().take(64).for_each(|t| t.hash(&mut h));
    h.finish()
}

fn same_geometry(a: &Model, b: &Model) -> bool {
    a.positions == b.positions
        && a.triangles == b.triangles
        && a.normals == b.normals
        && a.texcoords == b.texcoords
        && a.colors == b.colors
}

/// The key meshes written for a source are held under: the source and a hash of the
/// models' geometry and materials.
fn parts_key(source: usize, with_materials: &Parts<'_>) -> (usize, u64) {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for &(m, material) in with_materials {
        geometry_hash(m, material).hash(&mut h);
    }
    (source, h.finish())
}

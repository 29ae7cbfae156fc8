//! What a glTF file holds that a `Scene` does not, carried from reader to writer unchanged:
//! skinned meshes and meshes with morph targets (every accessor of their primitives,
//! JOINTS/WEIGHTS and targets included), points and lines primitives with their accessors,
//! the skins with their inverse bind matrices, the animations, the cameras, the
//! `KHR_lights_punctual` lights, the nodes' `skin`, `weights`, `camera`, light and `extras`,
//! and the names and `extras` of the asset, scene, meshes and materials. Node indices are
//! kept as read (the writer writes the node tree at the same indices), so joints, cameras
//! and animation targets need no renumbering; accessors and buffer views are renumbered
//! into a fragment with its own bytes, and shifted again where the writer splices it in.
//!
//! The fragment (`CopiedThrough::json`): `{ "accessors", "bufferViews" (buffer 0: the
//! fragment's bytes), "meshes": { "MESH": mesh without materials }, "primitives": { "MESH":
//! { "PRIMITIVE": points or lines primitive } }, "mesh_fields": { "MESH": { "name", "extras",
//! "materials": [source material per primitive] } }, "materials": { "MATERIAL": material
//! without textures }, "skins", "animations", "cameras", "lights", "nodes": { "NODE": {
//! "skin", "weights", "camera", "extras", "extensions" } }, "lined_nodes", "asset", "scene",
//! "extensionsRequired", "carries" }`.
//!
//! Extensions: `KHR_lights_punctual` is carried; a material's extensions are carried when
//! they name no texture (their factors stand alone; a texture would need its image carried
//! too); every other extension the file uses is named in a warning, and left out.

use crate::io::warning::{Warning, WarningKind};
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

use serde_json::{json, Map, Value};

use super::accessor::Buffers;
use crate::mesh::CopiedThrough;

/// The `CopiedThrough::format` of a glTF fragment.
pub const FORMAT: &str = "glTF";

/// glTF's primitive modes a `Scene` cannot hold (glTF 2.0 § 5.24.4): POINTS, LINES,
/// LINE_LOOP and LINE_STRIP.
const POINTS_AND_LINES: [u64; 4] = [0, 1, 2, 3];

/// The extensions a glTF output carries or decodes whatever they hold.
const CARRIED_EXTENSIONS: [&str; 2] = ["KHR_lights_punctual", "KHR_mesh_quantization"];

/// The fragment `gather` makes, and the warnings for what it leaves out.
pub struct Gathered {
    pub copied: Option<CopiedThrough>,
    pub warnings: Vec<Warning>,
}

/// The fragment for `meshes` (by index in `root`, copied whole), the points and lines
/// primitives of the meshes `scene` places, and everything else of `root` a `Scene` does
/// not hold (see the module's doc); `copied` is `None` when there is nothing to carry.
pub fn gather(
    root: &Value,
    scene: Option<usize>,
    buffers: &Buffers,
    meshes: &BTreeSet<usize>,
) -> Result<Gathered, String> {
    let list = |key: &str| root[key].as_array().map(Vec::as_slice).unwrap_or(&[]);
    let mut g = Gatherer {
        root,
        buffers,
        accessors: Vec::new(),
        views: Vec::new(),
        data: Vec::new(),
        accessor_of: HashMap::new(),
        view_of: HashMap::new(),
    };
    let mut extras = false;
    let (out_meshes, morphed) = copied_meshes(list("meshes"), meshes, &mut g)?;
    // Points and lines, of the meshes the scene's nodes place.
    let (placing, lined_meshes) = lined(root, scene);
    let (primitives, lined_materials) =
        lined_primitives(list("meshes"), &lined_meshes, &mut g, &mut extras)?;
    let lined_nodes = placed_by(placing, &lined_meshes);
    let mesh_fields = mesh_fields(list("meshes"), &mut extras);
    let mut uses = ExtensionUses::default();
    let (materials, mut warnings) =
        materials(list("materials"), &lined_materials, &mut uses, &mut extras);
    let (out_skins, out_animations) = skins_and_animations(root, &mut g)?;
    let nodes = node_fields(list("nodes"), &mut extras);
    let (cameras, lights) = cameras_and_lights(root);
    let asset = pick(&root["asset"], &["copyright", "extras"]);
    let scene_fields = match scene {
        Some(s) => pick(&list("scenes")[s], &["name", "extras"]),
        None => Map::new(),
    };
    extras |= asset.contains_key("extras") || scene_fields.contains_key("extras");
    let carries: Vec<&str> = [
        ("skins", !out_skins.is_empty()),
        ("morph targets", morphed),
        ("animations", !out_animations.is_empty()),
        ("cameras", !cameras.is_empty()),
        ("lights", !lights.is_empty()),
        ("points and lines primitives", !lined_nodes.is_empty()),
        ("extras", extras),
    ]
    .into_iter()
    .filter_map(|(kind, has)| has.then_some(kind))
    .collect();
    warnings.extend(lost_extensions(&uses, list("extensionsUsed")));
    let required = list("extensionsRequired")
        .iter()
        .filter(|e| e.as_str() == Some("KHR_mesh_quantization"))
        .cloned()
        .collect();
    let pieces = Pieces {
        meshes: out_meshes,
        primitives,
        mesh_fields,
        materials,
        skins: out_skins,
        animations: out_animations,
        cameras,
        lights,
        nodes,
        lined_nodes,
        asset,
        scene: scene_fields,
        required,
        carries,
    };
    Ok(Gathered {
        copied: pieces.into_copied(g),
        warnings,
    })
}

/// The nodes (of `placing`, node and mesh pairs) that place one of `meshes`.
fn placed_by(placing: Vec<(usize, usize)>, meshes: &BTreeSet<usize>) -> Vec<usize> {
    placing
        .into_iter()
        .filter(|(_, m)| meshes.contains(m))
        .map(|(n, _)| n)
        .collect()
}

/// What the fragment holds, gathered piece by piece.
struct Pieces<'a> {
    meshes: Map<String, Value>,
    primitives: Map<String, Value>,
    mesh_fields: Map<String, Value>,
    materials: Map<String, Value>,
    skins: Vec<Value>,
    animations: Vec<Value>,
    cameras: Vec<Value>,
    lights: Vec<Value>,
    nodes: BTreeMap<String, Value>,
    lined_nodes: Vec<usize>,
    asset: Map<String, Value>,
    scene: Map<String, Value>,
    required: Vec<Value>,
    carries: Vec<&'a str>,
}

impl Pieces<'_> {
    /// The fragment with the accessors, views and data `g` gathered; `None` when the file
    /// has nothing a `Scene` does not hold.
    fn into_copied(self, g: Gatherer<'_>) -> Option<CopiedThrough> {
        let anything = !(self.meshes.is_empty()
            && self.carries.is_empty()
            && self.mesh_fields.is_empty()
            && self.materials.is_empty()
            && self.nodes.is_empty()
            && self.asset.is_empty()
            && self.scene.is_empty());
        if !anything {
            return None;
        }
        let fragment = json!({
            "accessors": g.accessors,
            "bufferViews": g.views,
            "meshes": self.meshes,
            "primitives": self.primitives,
            "mesh_fields": self.mesh_fields,
            "materials": self.materials,
            "skins": self.skins,
            "animations": self.animations,
            "cameras": self.cameras,
            "lights": self.lights,
            "nodes": self.nodes,
            "lined_nodes": self.lined_nodes,
            "asset": self.asset,
            "scene": self.scene,
            "extensionsRequired": self.required,
            "carries": self.carries,
        });
        Some(CopiedThrough {
            format: FORMAT,
            json: fragment.to_string(),
            data: g.data,
        })
    }
}

/// The skins and animations, their accessors remapped.
fn skins_and_animations(
    root: &Value,
    g: &mut Gatherer<'_>,
) -> Result<(Vec<Value>, Vec<Value>), String> {
    let list = |key: &str| root[key].as_array().map(Vec::as_slice).unwrap_or(&[]);
    let mut out_skins = list("skins").to_vec();
    for skin in &mut out_skins {
        g.remap_field(skin, "inverseBindMatrices")?;
    }
    let mut out_animations = list("animations").to_vec();
    for animation in &mut out_animations {
        for sampler in animation["samplers"].as_array_mut().into_iter().flatten() {
            g.remap_field(sampler, "input")?;
            g.remap_field(sampler, "output")?;
        }
    }
    Ok((out_skins, out_animations))
}

/// The cameras and `KHR_lights_punctual` lights, without extensions.
fn cameras_and_lights(root: &Value) -> (Vec<Value>, Vec<Value>) {
    let cameras = root["cameras"].as_array().map(Vec::as_slice).unwrap_or(&[]);
    let cameras: Vec<Value> = cameras.iter().map(without_extensions).collect();
    let lights: Vec<Value> = root
        .pointer("/extensions/KHR_lights_punctual/lights")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .map(without_extensions)
        .collect();
    (cameras, lights)
}

/// A warning naming the extensions the file uses that the output leaves out.
fn lost_extensions(uses: &ExtensionUses, used: &[Value]) -> Option<Warning> {
    let lost = uses.lost(used);
    (!lost.is_empty()).then(|| {
        Warning::new(
            WarningKind::SkippedAttribute,
            format!(
                "glTF extensions left out of the output: {}",
                lost.join(", ")
            ),
        )
    })
}

/// The meshes copied through whole (skinned or morphed), without their materials and
/// extensions, their accessors remapped; and whether any has morph targets.
fn copied_meshes(
    all: &[Value],
    meshes: &BTreeSet<usize>,
    g: &mut Gatherer<'_>,
) -> Result<(Map<String, Value>, bool), String> {
    let mut out_meshes = Map::new();
    let mut morphed = false;
    for &m in meshes {
        let mut mesh = all
            .get(m)
            .cloned()
            .ok_or_else(|| format!("mesh {m} is missing"))?;
        // Extensions are left out (named in a warning): the output does not declare them.
        if let Some(o) = mesh.as_object_mut() {
            o.remove("extensions");
        }
        for p in mesh["primitives"].as_array_mut().into_iter().flatten() {
            if let Some(p) = p.as_object_mut() {
                p.remove("material");
                p.remove("extensions");
            }
            morphed |= p.get("targets").is_some();
            g.primitive(p)?;
        }
        out_meshes.insert(m.to_string(), mesh);
    }
    Ok((out_meshes, morphed))
}

/// The points and lines primitives of `lined_meshes`, by mesh and index, their accessors
/// remapped; and the materials they use.
fn lined_primitives(
    all: &[Value],
    lined_meshes: &BTreeSet<usize>,
    g: &mut Gatherer<'_>,
    extras: &mut bool,
) -> Result<(Map<String, Value>, BTreeSet<u64>), String> {
    let mut primitives = Map::new();
    let mut lined_materials = BTreeSet::new();
    for &m in lined_meshes {
        let mut carried = Map::new();
        for (i, p) in all[m]["primitives"]
            .as_array()
            .into_iter()
            .flatten()
            .enumerate()
        {
            if !is_points_or_lines(p) {
                continue;
            }
            let mut p = p.clone();
            if let Some(o) = p.as_object_mut() {
                o.remove("extensions");
            }
            g.primitive(&mut p)?;
            lined_materials.extend(p.get("material").and_then(Value::as_u64));
            *extras |= p.get("extras").is_some();
            carried.insert(i.to_string(), p);
        }
        primitives.insert(m.to_string(), Value::Object(carried));
    }
    Ok((primitives, lined_materials))
}

/// Every mesh's name, extras and its primitives' materials, by mesh.
fn mesh_fields(all: &[Value], extras: &mut bool) -> Map<String, Value> {
    let mut mesh_fields = Map::new();
    for (m, mesh) in all.iter().enumerate() {
        let mut fields = pick(mesh, &["name", "extras"]);
        *extras |= fields.contains_key("extras");
        let materials: Vec<Value> = mesh["primitives"]
            .as_array()
            .into_iter()
            .flatten()
            .map(|p| p.get("material").cloned().unwrap_or(Value::Null))
            .collect();
        if materials.iter().any(|v| !v.is_null()) {
            fields.insert("materials".into(), json!(materials));
        }
        if !fields.is_empty() {
            mesh_fields.insert(m.to_string(), Value::Object(fields));
        }
    }
    mesh_fields
}

/// Every material without its textures (said in a warning when points and lines
/// primitives used them), by index.
fn materials(
    all: &[Value],
    lined_materials: &BTreeSet<u64>,
    uses: &mut ExtensionUses,
    extras: &mut bool,
) -> (Map<String, Value>, Vec<Warning>) {
    let mut warnings = Vec::new();
    let mut materials = Map::new();
    for (k, material) in all.iter().enumerate() {
        let (kept, lost_texture) = without_textures(material, uses);
        if lost_texture && lined_materials.contains(&(k as u64)) {
            warnings.push(Warning::new(
            WarningKind::SkippedAttribute,
            format!(
                "material {k}'s textures are left out of its points and lines primitives (copied through without them)"
            ),
        ));
        }
        *extras |= kept.get("extras").is_some();
        materials.insert(k.to_string(), kept);
    }
    (materials, warnings)
}

/// The node fields a `Scene` does not hold (skin, weights, camera, extras, light), by node.
fn node_fields(all: &[Value], extras: &mut bool) -> BTreeMap<String, Value> {
    let mut nodes = BTreeMap::new();
    for (i, node) in all.iter().enumerate() {
        let mut fields = pick(node, &["skin", "weights", "camera", "extras"]);
        *extras |= fields.contains_key("extras");
        if let Some(light) = node.pointer("/extensions/KHR_lights_punctual") {
            fields.insert("extensions".into(), json!({ "KHR_lights_punctual": light }));
        }
        if !fields.is_empty() {
            nodes.insert(i.to_string(), Value::Object(fields));
        }
    }
    nodes
}

/// What of a source a glTF fragment carries that other formats leave out ("skins",
/// "cameras", ...), in the order a warning names them.
pub fn carried_kinds(copied: &CopiedThrough) -> Vec<String> {
    if copied.format != FORMAT {
        return Vec::new();
    }
    let fragment: Value = serde_json::from_str(&copied.json).unwrap_or_default();
    fragment["carries"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|k| k.as_str().map(str::to_string))
        .collect()
}

fn is_points_or_lines(p: &Value) -> bool {
    p.get("mode")
        .and_then(Value::as_u64)
        .is_some_and(|m| POINTS_AND_LINES.contains(&m))
}

/// The nodes reachable from `scene`'s roots with the mesh each places, and those meshes
/// that hold points or lines.
fn lined(root: &Value, scene: Option<usize>) -> (Vec<(usize, usize)>, BTreeSet<usize>) {
    let nodes = root["nodes"].as_array().map(Vec::as_slice).unwrap_or(&[]);
    let mut seen = vec![false; nodes.len()];
    let mut stack: Vec<usize> = scene
        .and_then(|s| root["scenes"][s]["nodes"].as_array())
        .into_iter()
        .flatten()
        .filter_map(|n| n.as_u64().map(|n| n as usize))
        .collect();
    let mut placing = Vec::new();
    while let Some(n) = stack.pop() {
        if n >= nodes.len() || std::mem::replace(&mut seen[n], true) {
            continue;
        }
        if let Some(m) = nodes[n]["mesh"].as_u64() {
            placing.push((n, m as usize));
        }
        stack.extend(
            nodes[n]["children"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|c| c.as_u64().map(|c| c as usize)),
        );
    }
    placing.sort_unstable();
    let meshes = root["meshes"].as_array().map(Vec::as_slice).unwrap_or(&[]);
    let lined = placing
        .iter()
        .map(|&(_, m)| m)
        .filter(|&m| {
            meshes.get(m).is_some_and(|mesh| {
                mesh["primitives"]
                    .as_array()
                    .is_some_and(|ps| ps.iter().any(is_points_or_lines))
            })
        })
        .collect();
    (placing, lined)
}

/// The fields `keys` of `object` that it has.
fn pick(object: &Value, keys: &[&str]) -> Map<String, Value> {
    keys.iter()
        .filter_map(|&k| Some((k.to_string(), object.get(k)?.clone())))
        .collect()
}

/// `v` without its `extensions` (a camera's or light's: none is carried).
fn without_extensions(v: &Value) -> Value {
    let mut v = v.clone();
    if let Some(o) = v.as_object_mut() {
        o.remove("extensions");
    }
    v
}

/// Which extensions were carried where met, and which were left out somewhere.
#[derive(Default)]
struct ExtensionUses {
    carried: BTreeSet<String>,
    dropped: BTreeSet<String>,
}

impl ExtensionUses {
    /// The extensions of `used` (the file's `extensionsUsed`) the output does not carry
    /// everywhere they were.
    fn lost(&self, used: &[Value]) -> Vec<String> {
        used.iter()
            .filter_map(Value::as_str)
            .filter(|e| {
                !CARRIED_EXTENSIONS.contains(e)
                    && (self.dropped.contains(*e) || !self.carried.contains(*e))
            })
            .map(str::to_string)
            .collect()
    }
}

/// True when `v` holds a texture reference anywhere (a member named `...Texture`, as core
/// glTF and the KHR_materials extensions name them).
fn names_texture(v: &Value) -> bool {
    match v {
        Value::Object(o) => o
            .iter()
            .any(|(k, v)| k.ends_with("Texture") || names_texture(v)),
        Value::Array(a) => a.iter().any(names_texture),
        _ => false,
    }
}

/// `material` without its textures, and its extensions that name none; and whether a core
/// texture was removed. The extensions met are tallied in `uses`.
fn without_textures(material: &Value, uses: &mut ExtensionUses) -> (Value, bool) {
    let mut m = material.clone();
    let mut lost_texture = false;
    let Some(o) = m.as_object_mut() else {
        return (m, false);
    };
    let mut strip = |o: &mut Map<String, Value>| {
        let before = o.len();
        o.retain(|k, _| !k.ends_with("Texture"));
        lost_texture |= o.len() != before;
    };
    strip(o);
    if let Some(pbr) = o
        .get_mut("pbrMetallicRoughness")
        .and_then(Value::as_object_mut)
    {
        strip(pbr);
        // Extensions below the material's own are not carried (nor tallied as carried).
        pbr.remove("extensions");
    }
    if let Some(ext) = o.get_mut("extensions").and_then(Value::as_object_mut) {
        ext.retain(|name, v| {
            let keep = !names_texture(v);
            match keep {
                true => uses.carried.insert(name.clone()),
                false => uses.dropped.insert(name.clone()),
            };
            keep
        });
        if ext.is_empty() {
            o.remove("extensions");
        }
    }
    (m, lost_texture)
}

/// Copies accessors and their buffer views (once each) into the fragment.
struct Gatherer<'a> {
    root: &'a Value,
    buffers: &'a Buffers,
    accessors: Vec<Value>,
    views: Vec<Value>,
    data: Vec<u8>,
    accessor_of: HashMap<u64, usize>,
    view_of: HashMap<u64, usize>,
}

impl Gatherer<'_> {
    /// A primitive's attributes, indices and morph targets, renumbered.
    fn primitive(&mut self, p: &mut Value) -> Result<(), String> {
        self.remap_map(&mut p["attributes"])?;
        self.remap_field(p, "indices")?;
        for target in p
            .get_mut("targets")
            .and_then(Value::as_array_mut)
            .into_iter()
            .flatten()
        {
            self.remap_map(target)?;
        }
        Ok(())
    }

    /// Every value of a `{ "NAME": accessor }` map, renumbered.
    fn remap_map(&mut self, map: &mut Value) -> Result<(), String> {
        for v in map.as_object_mut().into_iter().flat_map(|m| m.values_mut()) {
            *v = json!(self.accessor(v)?);
        }
        Ok(())
    }

    /// `object[key]`, an accessor index when present, renumbered.
    fn remap_field(&mut self, object: &mut Value, key: &str) -> Result<(), String> {
        if let Some(v) = object.get_mut(key) {
            *v = json!(self.accessor(v)?);
        }
        Ok(())
    }

    fn accessor(&mut self, index: &Value) -> Result<usize, String> {
        let i = index
            .as_u64()
            .ok_or_else(|| format!("{index} is not an accessor index"))?;
        if let Some(&k) = self.accessor_of.get(&i) {
            return Ok(k);
        }
        let mut a = self.root["accessors"]
            .get(i as usize)
            .cloned()
            .ok_or_else(|| format!("accessor {i} is missing"))?;
        self.remap_view(&mut a)?;
        if let Some(sparse) = a.get_mut("sparse") {
            self.remap_view(&mut sparse["indices"])?;
            self.remap_view(&mut sparse["values"])?;
        }
        self.accessors.push(a);
        self.accessor_of.insert(i, self.accessors.len() - 1);
        Ok(self.accessors.len() - 1)
    }

    /// `object["bufferView"]`, when present, copied into the fragment's bytes.
    fn remap_view(&mut self, object: &mut Value) -> Result<(), String> {
        let Some(v) = object.get("bufferView").and_then(Value::as_u64) else {
            return Ok(());
        };
        if let Some(&k) = self.view_of.get(&v) {
            object["bufferView"] = json!(k);
            return Ok(());
        }
        let view = &self.root["bufferViews"][v as usize];
        let field = |key: &str| view.get(key).and_then(Value::as_u64).unwrap_or(0) as usize;
        let (buffer, offset, length) = (field("buffer"), field("byteOffset"), field("byteLength"));
        let bytes = self
            .buffers
            .0
            .get(buffer)
            .and_then(|b| b.get(offset..offset.checked_add(length)?))
            .ok_or_else(|| format!("bufferView {v} runs past the end of buffer {buffer}"))?;
        // The view keeps its offset modulo 4: an accessor's own offset within it may rely
        // on it for its components' alignment (glTF 2.0 § 3.6.2.4).
        while self.data.len() % 4 != offset % 4 {
            self.data.push(0);
        }
        let mut copy = json!({ "buffer": 0, "byteOffset": self.data.len(), "byteLength": length });
        for key in ["byteStride", "target"] {
            if let Some(x) = view.get(key) {
                copy[key] = x.clone();
            }
        }
        self.data.extend_from_slice(bytes);
        self.views.push(copy);
        self.view_of.insert(v, self.views.len() - 1);
        object["bufferView"] = json!(self.views.len() - 1);
        Ok(())
    }
}

/// A fragment spliced into a document being written: its accessors and views appended at
/// `accessor_base` and `view_base`, its bytes at `byte_base` of the writer's buffer.
pub struct Spliced {
    fragment: Value,
    accessor_base: usize,
    /// The nodes that place points or lines (`lined_nodes`), looked up once per node.
    lined_nodes: HashSet<u64>,
}

impl Spliced {
    /// Appends the fragment's accessors, views and bytes to the writer's lists and buffer.
    pub fn new(
        copied: &CopiedThrough,
        accessors: &mut Vec<Value>,
        views: &mut Vec<Value>,
        bin: &mut Vec<u8>,
    ) -> Option<Self> {
        if copied.format != FORMAT {
            return None;
        }
        let fragment: Value = serde_json::from_str(&copied.json).ok()?;
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let (view_base, byte_base) = (views.len(), bin.len());
        bin.extend_from_slice(&copied.data);
        for v in fragment["bufferViews"].as_array().into_iter().flatten() {
            let mut v = v.clone();
            v["byteOffset"] = json!(v["byteOffset"].as_u64().unwrap_or(0) as usize + byte_base);
            views.push(v);
        }
        let accessor_base = accessors.len();
        let shift_view = |o: &mut Value| {
            if let Some(k) = o.get("bufferView").and_then(Value::as_u64) {
                o["bufferView"] = json!(k as usize + view_base);
            }
        };
        for a in fragment["accessors"].as_array().into_iter().flatten() {
            let mut a = a.clone();
            shift_view(&mut a);
            if let Some(sparse) = a.get_mut("sparse") {
                shift_view(&mut sparse["indices"]);
                shift_view(&mut sparse["values"]);
            }
            accessors.push(a);
        }
        let lined_nodes = fragment["lined_nodes"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(Value::as_u64)
            .collect();
        Some(Self {
            fragment,
            accessor_base,
            lined_nodes,
        })
    }

    fn shift(&self, v: &mut Value) {
        if let Some(k) = v.as_u64() {
            *v = json!(k as usize + self.accessor_base);
        }
    }

    fn shift_map(&self, map: &mut Value) {
        for v in map.as_object_mut().into_iter().flat_map(|m| m.values_mut()) {
            self.shift(v);
        }
    }

    /// A primitive's accessors renumbered.
    fn shift_primitive(&self, p: &mut Value) {
        self.shift_map(&mut p["attributes"]);
        if let Some(i) = p.get_mut("indices") {
            self.shift(i);
        }
        for t in p
            .get_mut("targets")
            .and_then(Value::as_array_mut)
            .into_iter()
            .flatten()
        {
            self.shift_map(t);
        }
    }

    /// The source's mesh `mesh`, when it is copied through: its primitives, accessors
    /// renumbered, without materials.
    pub fn mesh(&self, mesh: usize) -> Option<Value> {
        let mut mesh = self.fragment["meshes"].get(mesh.to_string())?.clone();
        for p in mesh["primitives"].as_array_mut().into_iter().flatten() {
            self.shift_primitive(p);
        }
        Some(mesh)
    }

    /// The points and lines primitives of source mesh `mesh`, by their index in it, their
    /// accessors renumbered; `material` still names the source's material.
    pub fn lines(&self, mesh: usize) -> Vec<(usize, Value)> {
        let Some(list) = self.fragment["primitives"]
            .get(mesh.to_string())
            .and_then(Value::as_object)
        else {
            return Vec::new();
        };
        let mut out: Vec<(usize, Value)> = list
            .iter()
            .filter_map(|(p, prim)| {
                let mut prim = prim.clone();
                self.shift_primitive(&mut prim);
                Some((p.parse().ok()?, prim))
            })
            .collect();
        out.sort_by_key(|(p, _)| *p);
        out
    }

    /// True when node `node` is reached from the scene and its mesh holds points or lines.
    pub fn places_lines(&self, node: usize) -> bool {
        self.lined_nodes.contains(&(node as u64))
    }

    /// Source material `k` without its textures (for points and lines).
    pub fn material(&self, k: usize) -> Option<&Value> {
        self.fragment["materials"].get(k.to_string())
    }

    /// The source material of primitive `p` of mesh `mesh`, without its textures.
    pub fn source_material(&self, mesh: usize, p: usize) -> Option<&Value> {
        let k = self.fragment["mesh_fields"]
            .get(mesh.to_string())
            .and_then(|f| f["materials"].get(p))
            .and_then(Value::as_u64)?;
        self.material(k as usize)
    }

    /// Source mesh `mesh`'s `name` and `extras`.
    pub fn mesh_fields(&self, mesh: usize) -> Map<String, Value> {
        match self.fragment["mesh_fields"].get(mesh.to_string()) {
            Some(f) => pick(f, &["name", "extras"]),
            None => Map::new(),
        }
    }

    /// The source's cameras, at their indices (nodes name them so).
    pub fn cameras(&self) -> Vec<Value> {
        self.list("cameras")
    }

    /// The source's `KHR_lights_punctual` lights, at their indices.
    pub fn lights(&self) -> Vec<Value> {
        self.list("lights")
    }

    /// The source asset's `copyright` and `extras`.
    pub fn asset(&self) -> Map<String, Value> {
        pick(&self.fragment["asset"], &["copyright", "extras"])
    }

    /// The source scene's `name` and `extras`.
    pub fn scene(&self) -> Map<String, Value> {
        pick(&self.fragment["scene"], &["name", "extras"])
    }

    fn list(&self, key: &str) -> Vec<Value> {
        self.fragment[key].as_array().cloned().unwrap_or_default()
    }

    /// Every skin, in the source's order (nodes name them by index).
    pub fn skins(&self) -> Vec<Value> {
        let mut skins = self.fragment["skins"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        for s in &mut skins {
            if let Some(i) = s.get_mut("inverseBindMatrices") {
                self.shift(i);
            }
        }
        skins
    }

    /// Every animation, its samplers' accessors renumbered.
    pub fn animations(&self) -> Vec<Value> {
        let mut list = self.fragment["animations"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        for a in &mut list {
            for s in a["samplers"].as_array_mut().into_iter().flatten() {
                for key in ["input", "output"] {
                    if let Some(i) = s.get_mut(key) {
                        self.shift(i);
                    }
                }
            }
        }
        list
    }

    /// Node `node`'s `skin`, `weights`, `camera`, `extras` and light, as read.
    pub fn node_fields(&self, node: usize) -> Option<&Map<String, Value>> {
        self.fragment["nodes"].get(node.to_string())?.as_object()
    }

    /// The extensions the copied accessors need (`KHR_mesh_quantization`).
    pub fn extensions_required(&self) -> Vec<String> {
        self.fragment["extensionsRequired"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|e| e.as_str().map(str::to_string))
            .collect()
    }
}

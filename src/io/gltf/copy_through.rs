//! What a glTF file holds that cannot be decimated faithfully, carried from reader to writer
//! unchanged: skinned meshes and meshes with morph targets (every accessor of their
//! primitives, JOINTS/WEIGHTS and targets included), the skins with their inverse bind
//! matrices, the animations, and the nodes' `skin` and `weights`. Node indices are kept as
//! read (the writer writes the node tree at the same indices), so joints and animation
//! targets need no renumbering; accessors and buffer views are renumbered into a fragment
//! with its own bytes, and shifted again where the writer splices it in.
//!
//! The fragment (`CopiedThrough::json`): `{ "accessors", "bufferViews" (buffer 0: the
//! fragment's bytes), "meshes": { "MESH": mesh without materials }, "skins", "animations",
//! "nodes": { "NODE": { "skin", "weights" } }, "extensionsRequired" }`.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use serde_json::{json, Map, Value};

use super::accessor::Buffers;
use crate::mesh::CopiedThrough;

/// The `CopiedThrough::format` of a glTF fragment.
pub const FORMAT: &str = "glTF";

/// The fragment for `meshes` (by index in `root`) and every skin and animation of `root`;
/// `None` when there is nothing to carry.
pub fn gather(
    root: &Value,
    buffers: &Buffers,
    meshes: &BTreeSet<usize>,
) -> Result<Option<CopiedThrough>, String> {
    let list = |key: &str| root[key].as_array().map(Vec::as_slice).unwrap_or(&[]);
    let (skins, animations) = (list("skins"), list("animations"));
    if meshes.is_empty() && skins.is_empty() && animations.is_empty() {
        return Ok(None);
    }
    let mut g = Gatherer {
        root,
        buffers,
        accessors: Vec::new(),
        views: Vec::new(),
        data: Vec::new(),
        accessor_of: HashMap::new(),
        view_of: HashMap::new(),
    };
    let mut out_meshes = Map::new();
    for &m in meshes {
        let mut mesh = list("meshes")
            .get(m)
            .cloned()
            .ok_or_else(|| format!("mesh {m} is missing"))?;
        for p in mesh["primitives"].as_array_mut().into_iter().flatten() {
            if let Some(p) = p.as_object_mut() {
                p.remove("material");
            }
            g.remap_map(&mut p["attributes"])?;
            g.remap_field(p, "indices")?;
            for target in p
                .get_mut("targets")
                .and_then(Value::as_array_mut)
                .into_iter()
                .flatten()
            {
                g.remap_map(target)?;
            }
        }
        out_meshes.insert(m.to_string(), mesh);
    }
    let mut out_skins = skins.to_vec();
    for skin in &mut out_skins {
        g.remap_field(skin, "inverseBindMatrices")?;
    }
    let mut out_animations = animations.to_vec();
    for animation in &mut out_animations {
        for sampler in animation["samplers"].as_array_mut().into_iter().flatten() {
            g.remap_field(sampler, "input")?;
            g.remap_field(sampler, "output")?;
        }
    }
    let mut nodes = BTreeMap::new();
    for (i, node) in list("nodes").iter().enumerate() {
        let mut extra = Map::new();
        for key in ["skin", "weights"] {
            if let Some(v) = node.get(key) {
                extra.insert(key.to_string(), v.clone());
            }
        }
        if !extra.is_empty() {
            nodes.insert(i.to_string(), Value::Object(extra));
        }
    }
    let required: Vec<&Value> = list("extensionsRequired")
        .iter()
        .filter(|e| e.as_str() == Some("KHR_mesh_quantization"))
        .collect();
    let fragment = json!({
        "accessors": g.accessors,
        "bufferViews": g.views,
        "meshes": out_meshes,
        "skins": out_skins,
        "animations": out_animations,
        "nodes": nodes,
        "extensionsRequired": required,
    });
    Ok(Some(CopiedThrough {
        format: FORMAT,
        json: fragment.to_string(),
        data: g.data,
    }))
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
        Some(Self {
            fragment,
            accessor_base,
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

    /// The source's mesh `mesh`, when it is copied through: its primitives, accessors
    /// renumbered, without materials.
    pub fn mesh(&self, mesh: usize) -> Option<Value> {
        let mut mesh = self.fragment["meshes"].get(mesh.to_string())?.clone();
        for p in mesh["primitives"].as_array_mut().into_iter().flatten() {
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
        Some(mesh)
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

    /// Node `node`'s `skin` and `weights`, as read.
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

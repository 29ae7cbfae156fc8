//! Reading `.gltf` and `.glb` into a `Scene`: the default scene's nodes are walked from
//! their roots, each node's matrix or TRS composed onto its parent's, and every triangle
//! primitive of a node's mesh becomes one model placed by the node's world transform
//! (decoded once per primitive, however many nodes use its mesh).
//!
//! Kept: POSITION, NORMAL, TEXCOORD_0 (v flipped: glTF's images start at the top, a
//! model's texture coordinates at the bottom), COLOR_0 (RGB of RGB or RGBA), the base
//! colour factor and texture (PNG or JPEG, beside the file or embedded: an embedded image
//! becomes a `data:` URI, see `io::data_uri`), the sampler's wrapping and the double-sided
//! flag. The node tree is kept (`mesh::NodeTree`, every model's `Instance`) for the glTF
//! writer. Skinned meshes and meshes with morph targets are read in their rest pose, marked
//! to be left undecimated, and carried with their skins and the animations to a glTF output
//! (`copy_through`); one warning names each. Points and lines primitives cannot be held by
//! a `Scene`: their positions and indices are checked, and they are carried to a glTF
//! output unchanged (`copy_through`, with cameras, lights and `extras`); one warning names
//! them.

use crate::io::warning::{Warning, WarningKind};
use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

use glam::{DMat4, DVec3, Mat4, Vec3};
use gltf::mesh::Mode;
use gltf::Semantic;

use super::accessor::{check_attribute, read_floats, read_floats_prefix, read_indices, Buffers};
use super::exact::{self, Exact};
use crate::io::{data_uri, file_limits, origin, texture_path, ReadError, ReadOutcome, MAX_MODELS};
use crate::mesh::{Attribute, Instance, LocalTransform, Model, Node, NodeTree, Scene};

/// Most node visits one file may take (a node listed as the child of several parents is
/// visited once per path; a file could otherwise multiply its nodes exponentially).
const MAX_NODE_VISITS: usize = MAX_MODELS;

/// Reads a glTF 2.0 file (JSON or binary) held in `bytes`; `path` names it in messages and
/// is the folder external buffers and images are read from.
///
/// A file with a `CESIUM_RTC` centre keeps no node tree (the tree has no place for it):
/// a glTF output writes its models flat, each under a node at its origin.
pub fn read_gltf(bytes: &[u8], path: &Path) -> Result<ReadOutcome, ReadError> {
    let fail = |message: String| ReadError::Unsupported {
        file: path.to_path_buf(),
        message,
    };
    let gltf = parse_document(bytes, path)?;
    validate(&gltf.document).map_err(fail)?;
    check_hierarchy(&gltf.document).map_err(fail)?;
    let folder = texture_path::folder_of(path);
    check_image_uris(&gltf.document, folder).map_err(fail)?;
    let buffers = load_buffers(&gltf, folder).map_err(fail)?;
    let document = &gltf.document;
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next());
    let copied = copied_meshes(document);
    let root = raw_json(bytes).map_err(fail)?;
    let exact = Exact::of(&root);
    let (tree, carried_warnings) = match &scene {
        Some(scene) if exact.rtc == DMat4::IDENTITY => {
            let (tree, w) = node_tree(&root, document, scene, &buffers, &copied).map_err(fail)?;
            (Some(Arc::new(tree)), w)
        }
        _ => (None, Vec::new()),
    };
    let mut reader = Reader {
        buffers: &buffers,
        tree,
        copied: &copied,
        primitives: HashMap::new(),
        models: Vec::new(),
        warnings: Vec::new(),
        warned: HashSet::new(),
        lines: Vec::new(),
        triangles: 0,
        visits: 0,
        quantized: document
            .extensions_used()
            .any(|e| e == "KHR_mesh_quantization"),
        exact,
        origin: None,
        // The file and the buffer files it loads (a GLB's own chunk counted once).
        max_triangles: file_limits::max_instanced_triangles(
            (bytes.len() + buffers.total_len())
                .saturating_sub(gltf.blob.as_ref().map_or(0, Vec::len)),
        ),
    };
    match scene {
        Some(scene) => {
            for node in scene.nodes() {
                reader.node(&node).map_err(fail)?;
            }
        }
        // No scene: every mesh once, where it stands.
        None => {
            let at = (Mat4::IDENTITY, reader.exact.rtc);
            for mesh in document.meshes() {
                reader.mesh(&mesh, at, None).map_err(fail)?;
            }
        }
    }
    let carried = reader.tree.is_some();
    let Reader {
        models,
        mut warnings,
        lines,
        ..
    } = reader;
    if let Some(w) = lines_warning(&lines, carried) {
        warnings.push(w);
    }
    warnings.extend(carried_warnings);
    copied_warnings(document, &copied, &mut warnings);
    Ok(ReadOutcome {
        scene: Scene { models },
        warnings,
        progressive: None,
        material_libraries: Vec::new(),
    })
}

/// Checks a GLB container (glTF 2.0, 4.4): version 2, a total length equal to the file's,
/// a JSON chunk first, then at most a BIN chunk, each inside the file; the error gives the
/// byte offset of the field at fault.
fn check_glb(bytes: &[u8]) -> Result<(), (usize, String)> {
    let word = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err((
            0,
            format!(
                "the 12-byte GLB header is cut short ({} bytes)",
                bytes.len()
            ),
        ));
    };
    if version != 2 {
        return Err((4, format!("GLB version {version}: only version 2 is read")));
    }
    if length != bytes.len() {
        return Err((
            8,
            format!(
                "the GLB header says {length} bytes, the file has {}",
                bytes.len()
            ),
        ));
    }
    let mut at = 12;
    let mut chunk = 0;
    while at < bytes.len() {
        let (Some(len), Some(kind)) = (word(at), word(at + 4)) else {
            return Err((at, "a GLB chunk header is cut short".to_string()));
        };
        // The first chunk is the JSON; later ones are BIN or of types readers ignore.
        if chunk == 0 && kind != 0x4E4F_534A {
            return Err((
                at + 4,
                "the first GLB chunk is not the JSON chunk".to_string(),
            ));
        }
        let end = at + 8 + len;
        if end > bytes.len() || !len.is_multiple_of(4) {
            return Err((
                at,
                format!(
                    "GLB chunk {chunk} says {len} bytes: not a multiple of 4 or past the end \
                     of the file ({} bytes)",
                    bytes.len()
                ),
            ));
        }
        at = end;
        chunk += 1;
    }
    if chunk == 0 {
        return Err((12, "the GLB file has no JSON chunk".to_string()));
    }
    Ok(())
}

/// The file's JSON (or GLB container, its header checked) parsed, not yet validated.
fn parse_document(bytes: &[u8], path: &Path) -> Result<gltf::Gltf, ReadError> {
    if super::is_glb(bytes) {
        check_glb(bytes).map_err(|(offset, message)| ReadError::Binary {
            file: path.to_path_buf(),
            offset,
            message,
        })?;
    }
    let fail = |message: String| ReadError::Unsupported {
        file: path.to_path_buf(),
        message,
    };
    gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| match e {
        gltf::Error::Deserialize(j) => ReadError::Syntax {
            file: path.to_path_buf(),
            line: j.line().max(1),
            message: format!("not valid glTF JSON: {j}"),
        },
        e => fail(describe(&e)),
    })
}

/// One warning for all the points and lines primitives met (`lines`): copied through to a
/// glTF output when the scene keeps its tree (`carried`), left out otherwise.
fn lines_warning(lines: &[String], carried: bool) -> Option<Warning> {
    if lines.is_empty() {
        return None;
    }
    let shown: Vec<&str> = lines.iter().take(3).map(String::as_str).collect();
    let more = match lines.len() {
        n if n > 3 => format!(" and {} more", n - 3),
        _ => String::new(),
    };
    let fate = match carried {
        true => "are copied through unchanged to a glTF output, not decimated nor shown",
        false => "are left out: the scene holds triangles",
    };
    let kind = match carried {
        true => WarningKind::Note,
        false => WarningKind::SkippedNode,
    };
    Some(
        Warning::new(
            kind,
            format!(
                "points and lines primitives {fate} ({}{more})",
                shown.join(", ")
            ),
        )
        .times(lines.len()),
    )
}

/// A note for each mesh copied through (skinned or morphed), and one for animations.
fn copied_warnings(
    document: &gltf::Document,
    copied: &BTreeMap<usize, &'static str>,
    warnings: &mut Vec<Warning>,
) {
    for mesh in document.meshes() {
        let (m, name) = (mesh.index(), mesh.name().unwrap_or(""));
        let Some(why) = copied.get(&m) else {
            continue;
        };
        warnings.push(Warning::new(
            WarningKind::Note,
            format!(
                "mesh {m} '{name}' {why}: copied through unchanged to a glTF output, not decimated (shown {})",
                match *why {
                    SKINNED => "in its rest pose",
                    _ => "in its base shape",
                }
            ),
        ));
    }
    if document.animations().count() > 0 {
        warnings.push(Warning::new(
            WarningKind::Note,
            "glTF animations are shown at rest; a glTF output carries them unchanged",
        ));
    }
}

/// The gltf crate's checks (every index in range, required fields present), less two it
/// makes that the reader does not need: POSITION's `min` and `max` (exporters often leave
/// them out; the reader computes bounds itself) and `KHR_mesh_quantization` (its integer
/// attributes are decoded by `accessor`).
fn validate(document: &gltf::Document) -> Result<(), String> {
    use gltf::json::validation::{Error, Validate};
    let root = document.as_json();
    let version = &root.asset.version;
    if !version.starts_with("2.") {
        return Err(format!(
            "asset.version: '{version}' is not 2.x: only glTF 2.0 files are read"
        ));
    }
    // gltf-json 1.4 looks up POSITION's accessor unchecked: check the indices first.
    let n = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(i) = primitive.attributes.values().find(|i| i.value() >= n) {
                return Err(format!(
                    "mesh {m} primitive {p} names accessor {}, but there are {n}",
                    i.value()
                ));
            }
        }
    }
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, error| {
        let path = path();
        let shown = path.to_string();
        let bounds = shown.ends_with(".min") || shown.ends_with(".max");
        let quantization =
            matches!(error, Error::Unsupported) && shown.contains("\"KHR_mesh_quantization\"");
        if !bounds && !quantization {
            errors.push((path, error));
        }
    });
    match errors.is_empty() {
        true => Ok(()),
        false => Err(describe(&gltf::Error::Validation(errors))),
    }
}

/// Refuses an image that is neither a URI nor a bufferView, or a bufferView without the
/// `mimeType` the spec requires with it: the gltf crate's `Image::source` panics on both.
fn check_image_sources(document: &gltf::Document) -> Result<(), String> {
    for (i, image) in document.as_json().images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (Some(_), None, _) | (None, Some(_), Some(_)) => {}
            (None, Some(_), None) => {
                return Err(format!("images[{i}]: a bufferView image needs a mimeType"))
            }
            _ => return Err(format!("images[{i}]: give either a uri or a bufferView")),
        }
    }
    Ok(())
}

/// Refuses image URIs that name files outside the model's folder (a path from the root,
/// `..` above it, a `file:` URI): the viewer and a glTF output would read them. `data:` URIs
/// and other URLs are never read as files.
fn check_image_uris(document: &gltf::Document, folder: &Path) -> Result<(), String> {
    check_image_sources(document)?;
    for image in document.images() {
        let gltf::image::Source::Uri { uri, .. } = image.source() else {
            continue;
        };
        let file_uri = uri
            .get(..5)
            .is_some_and(|s| s.eq_ignore_ascii_case("file:"));
        if texture_path::has_url_scheme(uri) && !file_uri {
            continue;
        }
        let name = String::from_utf8_lossy(&data_uri::percent_decode(uri)).into_owned();
        file_limits::resolve_reference(folder, &name)
            .map_err(|e| format!("images[{}].uri: {e}", image.index()))?;
    }
    Ok(())
}

/// Refuses a node hierarchy that is not a set of trees (glTF 2.0, 3.5.3): a node that is
/// the child of two nodes (or listed twice by one), or a node that is its own ancestor. A
/// node graph that shares children could expand exponentially (2^24 instances from 24
/// levels); a cycle never ends.
fn check_hierarchy(document: &gltf::Document) -> Result<(), String> {
    const NONE: usize = usize::MAX;
    let mut parent = vec![NONE; document.nodes().count()];
    for node in document.nodes() {
        for child in node.children() {
            let c = child.index();
            if parent[c] != NONE {
                return Err(format!(
                    "nodes[{c}] is a child of nodes[{}] and of nodes[{}]: a glTF node has one \
                     parent at most",
                    parent[c],
                    node.index()
                ));
            }
            parent[c] = node.index();
        }
    }
    // Up each node's parents until a node already done: one on the path means a cycle.
    let (todo, on_path, done) = (0u8, 1u8, 2u8);
    let mut state = vec![todo; parent.len()];
    let mut path = Vec::new();
    for start in 0..parent.len() {
        let mut v = start;
        while v != NONE && state[v] == todo {
            state[v] = on_path;
            path.push(v);
            v = parent[v];
        }
        if v != NONE && state[v] == on_path {
            return Err(format!(
                "nodes[{v}] is its own ancestor: the node hierarchy has a cycle"
            ));
        }
        for p in path.drain(..) {
            state[p] = done;
        }
    }
    Ok(())
}

/// A gltf crate error said for a user: validation errors list what is wrong and where.
fn describe(e: &gltf::Error) -> String {
    match e {
        gltf::Error::Validation(list) => {
            let shown: Vec<String> = list
                .iter()
                .take(5)
                .map(|(path, err)| format!("{path}: {err}"))
                .collect();
            let more = match list.len() {
                n if n > 5 => format!(" (and {} more)", n - 5),
                _ => String::new(),
            };
            format!("not a valid glTF 2.0 file: {}{more}", shown.join("; "))
        }
        gltf::Error::Binary(b) => format!("not a valid binary glTF (.glb) file: {b}"),
        e => format!("not a valid glTF 2.0 file: {e}"),
    }
}

/// Every buffer's bytes: the GLB's BIN chunk, a `data:` URI or a file beside `folder`.
fn load_buffers(gltf: &gltf::Gltf, folder: &Path) -> Result<Buffers, String> {
    let mut out = Vec::new();
    for buffer in gltf.document.buffers() {
        let i = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => gltf.blob.clone().ok_or_else(|| {
                format!("buffer {i} is the GLB's binary chunk, but there is none")
            })?,
            gltf::buffer::Source::Uri(uri) => match data_uri::parse(uri) {
                Some(d) => d.map_err(|e| format!("buffer {i}: {e}"))?.bytes,
                None => {
                    let name = String::from_utf8_lossy(&data_uri::percent_decode(uri)).into_owned();
                    let file = file_limits::resolve_reference(folder, &name)
                        .map_err(|e| format!("buffers[{i}].uri: {e}"))?;
                    file_limits::read_regular(&file)
                        .map_err(|e| format!("buffers[{i}].uri: {}: {e}", file.display()))?
                }
            },
        };
        if data.len() < buffer.length() {
            return Err(format!(
                "buffer {i} holds {} bytes, but the file says {}",
                data.len(),
                buffer.length()
            ));
        }
        out.push(data);
    }
    Ok(Buffers(out))
}

/// What the walk carries: the decoded primitives by (mesh, primitive), the models so far.
struct Reader<'b> {
    buffers: &'b Buffers,
    /// The file's node tree, shared by every model a node places.
    tree: Option<Arc<NodeTree>>,
    /// The meshes copied through (skinned or morphed), by index.
    copied: &'b BTreeMap<usize, &'static str>,
    primitives: HashMap<(usize, usize), Option<Model>>,
    models: Vec<Model>,
    warnings: Vec<Warning>,
    /// The kinds of warning given (one each), the points and lines primitives met (said
    /// in one warning), and the triangles placed so far.
    warned: HashSet<&'static str>,
    lines: Vec<String>,
    triangles: usize,
    /// Nodes visited so far, and the most triangles the scene may expand to.
    visits: usize,
    max_triangles: usize,
    /// The file uses `KHR_mesh_quantization`: attributes may be integers.
    quantized: bool,
    /// The nodes' transforms in f64, and the origin of the models they place far from zero
    /// (picked at the first one, shared by the others).
    exact: Exact,
    origin: Option<DVec3>,
}

impl Reader<'_> {
    /// A texture or attribute left out, said once per `key`.
    fn warn_once(&mut self, key: &'static str, message: String) {
        if self.warned.insert(key) {
            self.warnings
                .push(Warning::new(WarningKind::SkippedAttribute, message));
        }
    }

    /// Places `root` and every node below it, depth first in file order: a node's mesh,
    /// then its children's. Iterative, so a hierarchy 100,000 deep takes no stack; the
    /// hierarchy is a set of trees (`check_hierarchy`), so each node is met once.
    fn node(&mut self, root: &gltf::Node<'_>) -> Result<(), String> {
        let mut stack = vec![(root.clone(), Mat4::IDENTITY, self.exact.rtc)];
        while let Some((node, parent, parent_exact)) = stack.pop() {
            self.visits += 1;
            if self.visits > MAX_NODE_VISITS {
                return Err(format!(
                    "the scenes place more than {MAX_NODE_VISITS} nodes (roots listed by several scenes?)"
                ));
            }
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            if !world.is_finite() {
                return Err(format!("node {}'s transform is not finite", node.index()));
            }
            let exact = parent_exact * self.exact.local(node.index());
            if let Some(mesh) = node.mesh() {
                self.mesh(&mesh, (world, exact), Some(&node))?;
            }
            let first = stack.len();
            stack.extend(node.children().map(|c| (c, world, exact)));
            stack[first..].reverse();
        }
        Ok(())
    }

    /// Places every triangle primitive of `mesh` at `world` (f32, and f64 with CESIUM_RTC's
    /// centre), as one model each; one placed far from zero gets the scene's origin and a
    /// transform relative to it.
    fn mesh(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        (world, exact): (Mat4, DMat4),
        node: Option<&gltf::Node<'_>>,
    ) -> Result<(), String> {
        let (world, origin) = match origin::place(&exact, None, &mut self.origin) {
            Some(placed) => (placed.transform, placed.origin),
            None => (world, DVec3::ZERO),
        };
        let node_name = node.and_then(|n| n.name());
        let several = mesh.primitives().len() > 1;
        for primitive in mesh.primitives() {
            let key = (mesh.index(), primitive.index());
            if !self.primitives.contains_key(&key) {
                let decoded = self.primitive(mesh, &primitive).map_err(|e| {
                    format!("mesh {} primitive {}: {e}", mesh.index(), primitive.index())
                })?;
                self.primitives.insert(key, decoded);
            }
            let Some(Some(local)) = self.primitives.get(&key) else {
                continue;
            };
            self.triangles += local.triangles.len();
            if self.models.len() >= MAX_MODELS || self.triangles > self.max_triangles {
                return Err(format!(
                    "the scene expands to more than {MAX_MODELS} models or {} triangles \
                     (meshes used by many nodes?); {}",
                    self.max_triangles,
                    file_limits::EXPANSION_HINT
                ));
            }
            let base = node_name
                .or(mesh.name())
                .filter(|n| !n.trim().is_empty())
                .map(str::to_string)
                .unwrap_or_else(|| format!("mesh{}", mesh.index()));
            let name = match several {
                true => format!("{base}.{}", primitive.index()),
                false => base,
            };
            let instance = match (&self.tree, node) {
                (Some(tree), Some(node)) => Some(Instance {
                    tree: tree.clone(),
                    node: node.index(),
                    primitive: primitive.index(),
                    copied: self.copied.contains_key(&mesh.index()),
                }),
                _ => None,
            };
            let model = Model {
                name,
                transform: world,
                origin,
                instance,
                ..local.clone()
            };
            // No winding change under a mirroring node: glTF's "clockwise when the
            // determinant is negative" is what counter-clockwise local triangles become in
            // the world, as a model's are (see `io::outward_triangles`).
            self.models.push(model);
        }
        Ok(())
    }

    /// Decodes one primitive into a model in its own frame; `None` (with a warning) for
    /// what a `Scene` cannot hold.
    fn primitive(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        p: &gltf::Primitive<'_>,
    ) -> Result<Option<Model>, String> {
        let mode = p.mode();
        let Some(pos) = p.get(&Semantic::Positions) else {
            return Err("the primitive has no POSITION attribute".into());
        };
        let path = |what: &str| {
            format!(
                "meshes[{}].primitives[{}].attributes.{what}",
                mesh.index(),
                p.index()
            )
        };
        check_attribute(&pos, "POSITION", self.quantized, &path("POSITION"))?;
        for (semantic, a) in p.attributes() {
            let name = semantic.to_string();
            check_attribute(&a, &name, self.quantized, &path(&name))?;
        }
        let positions: Vec<Vec3> = read_floats::<3>(&pos, self.buffers)?
            .into_iter()
            .map(Vec3::from)
            .collect();
        if let Some(k) = positions.iter().position(|v| !v.is_finite()) {
            return Err(format!("POSITION {k} is not a finite number"));
        }
        let n = positions.len();
        let corners = read_corners(p, n, self.buffers)?;
        // Points and lines, checked above, go to a glTF output as they are (`copy_through`).
        if let Some(kind) = points_or_lines(mode) {
            self.lines.push(format!(
                "mesh {} primitive {} {kind}",
                mesh.index(),
                p.index()
            ));
            return Ok(None);
        }
        let triangles = assemble(mode, &corners);
        let mut model = Model {
            positions,
            triangles,
            ..Model::default()
        };
        read_attributes(p, self.buffers, &mut model)?;
        self.material(&p.material(), &mut model);
        if !model.diffuse.iter().all(|c| c.is_finite()) {
            return Err("the material's baseColorFactor is not finite".into());
        }
        Ok(Some(model))
    }

    /// The base colour, its texture and the double-sided flag of `m`, onto `model`.
    fn material(&mut self, m: &gltf::Material<'_>, model: &mut Model) {
        let pbr = m.pbr_metallic_roughness();
        let [r, g, b, _] = pbr.base_color_factor();
        model.diffuse = [r, g, b];
        model.solid = !m.double_sided();
        model.material = m.name().map(str::to_string);
        let Some(info) = pbr.base_color_texture() else {
            return;
        };
        if info.tex_coord() != 0 {
            self.warn_once(
                "texcoord",
                format!(
                    "base colour textures on TEXCOORD_{} are left out (TEXCOORD_0 is read)",
                    info.tex_coord()
                ),
            );
            return;
        }
        let texture = info.texture();
        let sampler = texture.sampler();
        let repeats =
            |w: gltf::texture::WrappingMode| w != gltf::texture::WrappingMode::ClampToEdge;
        model.texture_repeat = [repeats(sampler.wrap_s()), repeats(sampler.wrap_t())];
        model.texture = match texture.source().source() {
            gltf::image::Source::Uri { uri, .. } => Some(match data_uri::is_data_uri(uri) {
                true => uri.to_string(),
                false => String::from_utf8_lossy(&data_uri::percent_decode(uri)).into_owned(),
            }),
            gltf::image::Source::View { view, mime_type } => {
                let bytes =
                    self.buffers.0.get(view.buffer().index()).and_then(|b| {
                        b.get(view.offset()..view.offset().checked_add(view.length())?)
                    });
                match bytes {
                    Some(bytes) => Some(data_uri::encode(mime_type, bytes)),
                    None => {
                        self.warn_once(
                            "image-view",
                            format!("image {}'s bufferView runs past its buffer: the texture is left out", texture.source().index()),
                        );
                        None
                    }
                }
            }
        };
    }
}

/// glTF's name of a points or lines mode; `None` for triangles.
fn points_or_lines(mode: Mode) -> Option<&'static str> {
    match mode {
        Mode::Points => Some("POINTS"),
        Mode::Lines => Some("LINES"),
        Mode::LineLoop => Some("LINE_LOOP"),
        Mode::LineStrip => Some("LINE_STRIP"),
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => None,
    }
}

/// Why a mesh is copied through: said in its warning.
const SKINNED: &str = "is skinned";
const MORPHED: &str = "has morph targets";

/// The meshes that cannot be decimated faithfully, by index: those a skinned node places and
/// those with morph targets.
fn copied_meshes(document: &gltf::Document) -> BTreeMap<usize, &'static str> {
    let mut out = BTreeMap::new();
    for mesh in document.meshes() {
        if mesh.primitives().any(|p| p.morph_targets().len() > 0) {
            out.insert(mesh.index(), MORPHED);
        }
    }
    for node in document.nodes() {
        if let (Some(mesh), Some(_)) = (node.mesh(), node.skin()) {
            out.insert(mesh.index(), SKINNED);
        }
    }
    out
}

/// Every node of the file at its index (name, local transform as given, children, mesh),
/// A primitive's corners: its indices, each checked against the `n` vertices, or the
/// vertices in order.
fn read_corners(p: &gltf::Primitive<'_>, n: usize, buffers: &Buffers) -> Result<Vec<u32>, String> {
    let Some(a) = p.indices() else {
        return Ok((0..n as u32).collect());
    };
    let idx = read_indices(&a, buffers)?;
    if let Some((k, &i)) = idx.iter().enumerate().find(|(_, &i)| i as usize >= n) {
        return Err(format!(
            "index {k} is {i}, but there are {n} vertices (accessor {})",
            a.index()
        ));
    }
    Ok(idx)
}

/// A primitive's normals, first texture coordinates and first colours, one per vertex of
/// `model`, all finite.
fn read_attributes(
    p: &gltf::Primitive<'_>,
    buffers: &Buffers,
    model: &mut Model,
) -> Result<(), String> {
    let n = model.positions.len();
    let same_count = |what: &str, len: usize| {
        if len == n {
            Ok(())
        } else {
            Err(format!("{what} has {len} values for {n} vertices"))
        }
    };
    if let Some(a) = p.get(&Semantic::Normals) {
        let normals = read_floats::<3>(&a, buffers)?;
        same_count("NORMAL", normals.len())?;
        all_finite("NORMAL", &normals)?;
        model.normals = Some(Attribute::PerVertex(
            normals.into_iter().map(Vec3::from).collect(),
        ));
    }
    if let Some(a) = p.get(&Semantic::TexCoords(0)) {
        let uv = read_floats::<2>(&a, buffers)?;
        same_count("TEXCOORD_0", uv.len())?;
        all_finite("TEXCOORD_0", &uv)?;
        model.texcoords = Some(uv.into_iter().map(|[u, v]| [u, 1.0 - v]).collect());
    }
    if let Some(a) = p.get(&Semantic::Colors(0)) {
        let c = read_floats_prefix::<3>(&a, buffers)?;
        same_count("COLOR_0", c.len())?;
        all_finite("COLOR_0", &c)?;
        let c = c
            .into_iter()
            .map(|c| c.map(|x| x.clamp(0.0, 1.0)))
            .collect();
        model.colors = Some(Attribute::PerVertex(c));
    }
    Ok(())
}

/// `scene`'s roots, and the copy-through fragment (the `copied` meshes and all else a
/// `Scene` does not hold, read from the file's JSON `root`); the warnings for what even a
/// glTF output leaves out.
fn node_tree(
    root: &serde_json::Value,
    document: &gltf::Document,
    scene: &gltf::Scene<'_>,
    buffers: &Buffers,
    copied: &BTreeMap<usize, &'static str>,
) -> Result<(NodeTree, Vec<Warning>), String> {
    let json_nodes = root.get("nodes").and_then(serde_json::Value::as_array);
    let nodes = document
        .nodes()
        .map(|n| Node {
            name: n.name().map(str::to_string),
            // From the JSON, in f64: the gltf crate's transform is f32.
            local: json_nodes.and_then(|j| j.get(n.index())).map_or(
                LocalTransform::Matrix(DMat4::IDENTITY),
                exact::local_transform,
            ),
            children: n.children().map(|c| c.index()).collect(),
            mesh: n.mesh().map(|m| m.index()),
        })
        .collect();
    let meshes: BTreeSet<usize> = copied.keys().copied().collect();
    let gathered = super::copy_through::gather(root, Some(scene.index()), buffers, &meshes)?;
    let tree = NodeTree {
        nodes,
        roots: scene.nodes().map(|n| n.index()).collect(),
        copied: gathered.copied,
    };
    Ok((tree, gathered.warnings))
}

/// The file's JSON as read, with every field the gltf crate's types leave out (unknown
/// extensions, `extras` of every kind) for `copy_through`.
fn raw_json(bytes: &[u8]) -> Result<serde_json::Value, String> {
    let json = match super::is_glb(bytes) {
        true => {
            gltf::binary::Glb::from_slice(bytes)
                .map_err(|e| describe(&e))?
                .json
        }
        false => std::borrow::Cow::Borrowed(bytes),
    };
    serde_json::from_slice(&json).map_err(|e| format!("not valid glTF JSON: {e}"))
}

/// An error naming the first value of `what` that is not a finite number, if any.
fn all_finite<const N: usize>(what: &str, values: &[[f32; N]]) -> Result<(), String> {
    match values.iter().position(|v| !v.iter().all(|x| x.is_finite())) {
        Some(k) => Err(format!("{what} {k} is not a finite number")),
        None => Ok(()),
    }
}

/// The triangles of a primitive's corners: listed in threes, as a strip or as a fan (glTF
/// 2.0 § 3.7.2.1). Triangles that repeat a vertex (a strip's restarts) are left out of
/// strips and fans, where they carry no surface.
fn assemble(mode: Mode, c: &[u32]) -> Vec<[u32; 3]> {
    let keep = |t: &[u32; 3]| t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
    match mode {
        Mode::TriangleStrip => (0..c.len().saturating_sub(2))
            .map(|i| match i % 2 {
                0 => [c[i], c[i + 1], c[i + 2]],
                _ => [c[i], c[i + 2], c[i + 1]],
            })
            .filter(keep)
            .collect(),
        Mode::TriangleFan => (1..c.len().saturating_sub(1))
            .map(|i| [c[i], c[i + 1], c[0]])
            .filter(keep)
            .collect(),
        _ => c.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_alternate_their_winding_and_fans_turn_around_the_first_corner() {
        // 0---2---4
        //  \ / \ /
        //   1---3
        assert_eq!(
            assemble(Mode::TriangleStrip, &[0, 1, 2, 3, 4]),
            vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            assemble(Mode::TriangleFan, &[0, 1, 2, 3]),
            vec![[1, 2, 0], [2, 3, 0]]
        );
        assert_eq!(
            assemble(Mode::TriangleStrip, &[0, 1, 1, 2]),
            Vec::<[u32; 3]>::new()
        );
        assert_eq!(assemble(Mode::Triangles, &[0, 1, 2, 3]), vec![[0, 1, 2]]);
    }
}

//! VRML 1.0 and Open Inventor ASCII semantics: a traversal state machine over the parsed
//! node tree.
//!
//! Properties (coordinates, normals, materials, bindings, shape hints, complexity, the
//! transform) accumulate in a state that `Separator` saves and restores; `Group`, `File` and
//! `Switch` let it leak as the specification says (a Switch's choice of -2 inherits the
//! enclosing one's), `TransformSeparator` saves the transform only; `Array` and
//! `MultipleCopy` repeat their children, node kits walk their parts in catalog order. Every
//! shape node (IndexedFaceSet, IndexedTriangleStripSet, IndexedTriangleMesh, FaceSet,
//! TriangleStripSet, QuadMesh, Cube, Sphere, Cone, Cylinder) becomes one `Model` with the
//! state's world transform. Inventor 2.1 `vertexProperty` fields override the state for their
//! shape. Under a `Texture2`, Cube, Sphere, Cone and Cylinder make their own texture
//! coordinates (see `primitives`), other shapes without coordinates get the default mapping
//! (see `default_texcoords`); `Texture2Transform`s accumulate and transform every shape's.
//! `MatrixTransform` follows the row-vector convention: the matrix is written row by row
//! with the translation in the last row. An error inside a `USE`d node names the USE's line
//! and the DEF's.

use crate::io::warning::{Warning, WarningKind};
use std::borrow::Cow;
use std::rc::Rc;

use glam::{Affine2, DMat4, DVec3, Mat4, Quat, Vec3};

use super::bindings::{
    explicit, resolve, split_polygons, strips_to_triangles, texcoords_per_vertex, Binding, Geo,
};
use super::default_texcoords;
use super::far;
use super::lexer::{PResult, ParseError};
use super::parse::{is_kit, used_at, Node, Value, USE_KIND};
use super::primitives::{self, Parts};
use super::texture_transform;
use super::Ctx;
use crate::io::shape_to_model::{Bind, ShapeSpec, TexCoords};
use crate::mesh::Model;

const DEFAULT_DIFFUSE: [f32; 3] = [0.8, 0.8, 0.8];

#[derive(Clone)]
struct State {
    transform: Mat4,
    /// `transform` composed in f64, for far scenes (see `far`).
    exact: DMat4,
    coords: Option<Rc<Node>>,
    normals: Option<Rc<Node>>,
    texcoords: Option<Rc<Node>>,
    /// `Texture2`'s file name.
    texture: Option<String>,
    /// `Texture2`'s `wrapS`, `wrapT`: true for REPEAT (the default), false for CLAMP.
    texture_repeat: [bool; 2],
    /// The `Texture2Transform`s met so far, composed (the last applied first).
    texture_transform: Affine2,
    material: Option<Rc<Node>>,
    material_binding: Binding,
    normal_binding: Binding,
    texcoord_binding: Binding,
    ccw: bool,
    solid: bool,
    crease_angle: Option<f32>,
    /// `Complexity`'s value as the primitives use it (0..=1).
    complexity: f32,
    /// The choice of the last Switch traversed, for a Switch below whose `whichChild` is -2.
    switch_choice: i32,
}

impl Default for State {
    fn default() -> Self {
        Self {
            transform: Mat4::IDENTITY,
            exact: DMat4::IDENTITY,
            coords: None,
            normals: None,
            texcoords: None,
            texture: None,
            texture_repeat: [true; 2],
            texture_transform: Affine2::IDENTITY,
            material: None,
            material_binding: Binding::Overall,
            normal_binding: Binding::Default,
            texcoord_binding: Binding::Default,
            ccw: true,
            solid: false,
            crease_angle: None,
            complexity: primitives::DEFAULT_COMPLEXITY,
            switch_choice: -1,
        }
    }
}

/// Rotation from an SFRotation (axis x y z, angle in radians); a zero axis is no rotation.
pub fn rotation(v: Option<&[f32]>) -> Quat {
    match v {
        Some(&[x, y, z, angle, ..]) => {
            let axis = Vec3::new(x, y, z).normalize_or_zero();
            if axis == Vec3::ZERO {
                Quat::IDENTITY
            } else {
                Quat::from_axis_angle(axis, angle)
            }
        }
        _ => Quat::IDENTITY,
    }
}

/// An SFVec3f, or `default` when absent or short.
pub fn vec3(v: Option<&[f32]>, default: Vec3) -> Vec3 {
    match v {
        Some(&[x, y, z, ..]) => Vec3::new(x, y, z),
        _ => default,
    }
}

/// The VRML transform `T * C * R * SR * S * -SR * -C`.
pub fn compose(t: Vec3, r: Quat, s: Vec3, so: Quat, c: Vec3) -> Mat4 {
    Mat4::from_translation(t + c)
        * Mat4::from_quat(r)
        * Mat4::from_quat(so)
        * Mat4::from_scale(s)
        * Mat4::from_quat(so.inverse())
        * Mat4::from_translation(-c)
}

/// Traverses the top-level nodes (an implicit root Separator) into models.
pub fn read(roots: &[Rc<Node>], warnings: &mut Vec<Warning>, nodes: usize) -> PResult<Vec<Model>> {
    let mut ctx = Ctx::new(warnings, nodes);
    let mut state = State::default();
    for n in roots {
        traverse(n, &mut state, &mut ctx)?;
    }
    Ok(ctx.models)
}

fn traverse(node: &Rc<Node>, state: &mut State, ctx: &mut Ctx<'_>) -> PResult<()> {
    if node.skipped {
        return Ok(());
    }
    ctx.budget.visit(node.line)?;
    if node.kind == USE_KIND {
        let target = node.target();
        let name = node.def.as_deref().unwrap_or_default();
        return traverse(target, state, ctx).map_err(|e| used_at(e, node.line, name, target.line));
    }
    if apply_transform(node, state)? || apply_property(node, state)? {
        return Ok(());
    }
    match node.kind.as_str() {
        "Separator" | "Selection" | "Annotation" | "WWWAnchor" => {
            let mut inner = state.clone();
            for c in &node.children {
                traverse(c, &mut inner, ctx)?;
            }
        }
        "Array" => {
            for offset in array_offsets(node)? {
                let exact = DMat4::from_translation(offset.as_dvec3());
                copy(node, state, (Mat4::from_translation(offset), exact), ctx)?;
            }
        }
        "MultipleCopy" => multiple_copy(node, state, ctx)?,
        "TransformSeparator" => {
            let saved = (state.transform, state.exact);
            for c in &node.children {
                traverse(c, state, ctx)?;
            }
            (state.transform, state.exact) = saved;
        }
        // A File node's children are the included file's nodes (see `include`).
        "Group" | "File" => {
            for c in &node.children {
                traverse(c, state, ctx)?;
            }
        }
        "Switch" | "Blinker" => switch(node, state, ctx)?,
        "LOD" | "LevelOfDetail" => {
            // The most detailed level.
            if let Some(c) = node.children.first() {
                traverse(c, state, ctx)?;
            }
        }
        "IndexedFaceSet"
        | "IndexedTriangleStripSet"
        | "IndexedTriangleMesh"
        | "FaceSet"
        | "TriangleStripSet"
        | "QuadMesh"
        | "Cube" => shape(node, state, ctx)?,
        "Sphere" | "Cone" | "Cylinder" => primitive(node, state, ctx)?,
        k if is_kit(k) => kit(node, state, ctx)?,
        _ => {}
    }
    Ok(())
}

/// A MultipleCopy: its children once per matrix of `matrix`.
fn multiple_copy(node: &Rc<Node>, state: &mut State, ctx: &mut Ctx<'_>) -> PResult<()> {
    let m = node.floats("matrix").unwrap_or(&[]);
    if !m.len().is_multiple_of(16) {
        return Err(ParseError::new(
            node.line_of("matrix"),
            format!(
                "expected 16 numbers per matrix in 'matrix', found {}",
                m.len()
            ),
        ));
    }
    let exact = node.exact("matrix").unwrap_or_default();
    for (one, exact) in m.chunks_exact(16).zip(exact.chunks_exact(16)) {
        let m = (Mat4::from_cols_slice(one), DMat4::from_cols_slice(exact));
        copy(node, state, m, ctx)?;
    }
    Ok(())
}

/// A Switch or Blinker: -1 none, -2 the enclosing switch's choice, -3 all; the choice is
/// inherited by switches below (Inventor's switch element).
fn switch(node: &Rc<Node>, state: &mut State, ctx: &mut Ctx<'_>) -> PResult<()> {
    let default = if node.kind == "Blinker" { 0 } else { -1 };
    let mut which = node.int("whichChild").unwrap_or(default);
    if which == -2 {
        which = state.switch_choice;
    }
    state.switch_choice = which;
    if which == -3 {
        for c in &node.children {
            traverse(c, state, ctx)?;
        }
    } else if which >= 0 {
        if let Some(c) = node.children.get(which as usize) {
            traverse(c, state, ctx)?;
        }
    }
    Ok(())
}

/// Applies a transformation node (Transform, Translation, Rotation, Scale, RotationXYZ,
/// MatrixTransform, ResetTransform) to the state; false when `node` is none of them.
fn apply_transform(node: &Node, state: &mut State) -> PResult<bool> {
    let applied = apply_f32_transform(node, state)?;
    if applied {
        apply_exact_transform(node, state);
    }
    Ok(applied)
}

/// [`apply_transform`] in f64, on `state.exact` (`node` is a transformation node checked by
/// [`apply_f32_transform`]).
fn apply_exact_transform(node: &Node, state: &mut State) {
    let m = match node.kind.as_str() {
        "Transform" => far::compose(
            far::dvec3(node, "translation", DVec3::ZERO),
            far::rotation(node.floats("rotation")),
            far::scale(node.floats("scaleFactor"), DVec3::ONE),
            far::rotation(node.floats("scaleOrientation")),
            far::dvec3(node, "center", DVec3::ZERO),
        ),
        "Translation" => DMat4::from_translation(far::dvec3(node, "translation", DVec3::ZERO)),
        "Rotation" | "Rotor" | "Pendulum" => {
            DMat4::from_quat(far::rotation(node.floats("rotation")))
        }
        "Scale" => DMat4::from_scale(far::scale(node.floats("scaleFactor"), DVec3::ONE)),
        "MatrixTransform" => match node.exact("matrix") {
            Some(m) if m.len() == 16 => DMat4::from_cols_slice(&m),
            _ => DMat4::IDENTITY,
        },
        "ResetTransform" => {
            if node
                .word("whatToReset")
                .unwrap_or("TRANSFORM")
                .contains("TRANSFORM")
            {
                state.exact = DMat4::IDENTITY;
            }
            DMat4::IDENTITY
        }
        // RotationXYZ.
        _ => {
            let angle = node.float("angle").unwrap_or(0.0);
            let axis = match node.word("axis").unwrap_or("X") {
                "Y" => DVec3::Y,
                "Z" => DVec3::Z,
                _ => DVec3::X,
            };
            DMat4::from_axis_angle(axis, angle.into())
        }
    };
    state.exact *= m;
}

/// [`apply_transform`] on the f32 world transform.
fn apply_f32_transform(node: &Node, state: &mut State) -> PResult<bool> {
    match node.kind.as_str() {
        "Transform" => {
            let m = compose(
                vec3(node.floats("translation"), Vec3::ZERO),
                rotation(node.floats("rotation")),
                vec3(node.floats("scaleFactor"), Vec3::ONE),
                rotation(node.floats("scaleOrientation")),
                vec3(node.floats("center"), Vec3::ZERO),
            );
            state.transform *= m;
        }
        "Translation" => {
            state.transform *= Mat4::from_translation(vec3(node.floats("translation"), Vec3::ZERO));
        }
        "Rotation" | "Rotor" | "Pendulum" => {
            state.transform *= Mat4::from_quat(rotation(node.floats("rotation")));
        }
        "Scale" => {
            state.transform *= Mat4::from_scale(vec3(node.floats("scaleFactor"), Vec3::ONE));
        }
        "RotationXYZ" => {
            let angle = node.float("angle").unwrap_or(0.0);
            let axis = match node.word("axis").unwrap_or("X") {
                "Y" => Vec3::Y,
                "Z" => Vec3::Z,
                _ => Vec3::X,
            };
            state.transform *= Mat4::from_axis_angle(axis, angle);
        }
        "MatrixTransform" => {
            if let Some(m) = node.floats("matrix") {
                let arr: [f32; 16] = match m.try_into() {
                    Ok(a) => a,
                    Err(_) => {
                        return Err(ParseError::new(
                            node.line_of("matrix"),
                            format!("expected 16 numbers in 'matrix', found {}", m.len()),
                        ))
                    }
                };
                // Row-major with row vectors = column-major with column vectors.
                state.transform *= Mat4::from_cols_array(&arr);
            }
        }
        "ResetTransform" => {
            let what = node.word("whatToReset").unwrap_or("TRANSFORM");
            if what.contains("TRANSFORM") {
                state.transform = Mat4::IDENTITY;
            }
        }
        _ => return Ok(false),
    }
    Ok(true)
}

/// Sets the property a property node (coordinates, normals, texture, material, bindings,
/// shape hints, complexity) gives the shapes after it; false when `node` is none of them.
fn apply_property(node: &Rc<Node>, state: &mut State) -> PResult<bool> {
    match node.kind.as_str() {
        "Coordinate3" => state.coords = Some(node.clone()),
        "Normal" => state.normals = Some(node.clone()),
        "TextureCoordinate2" => state.texcoords = Some(node.clone()),
        // An empty file name turns texturing off.
        "Texture2" => {
            state.texture = node
                .strings("filename")
                .first()
                .filter(|f| !f.is_empty())
                .cloned();
            state.texture_repeat = [wrap(node, "wrapS")?, wrap(node, "wrapT")?];
        }
        "Texture2Transform" => state.texture_transform *= texture_transform::inventor(node),
        "Material" | "BaseColor" => state.material = Some(node.clone()),
        "MaterialBinding" => state.material_binding = binding(node)?,
        "NormalBinding" => state.normal_binding = binding(node)?,
        "TextureCoordinateBinding" => state.texcoord_binding = binding(node)?,
        "ShapeHints" => {
            let ordering = node.word("vertexOrdering").unwrap_or("UNKNOWN_ORDERING");
            state.ccw = ordering != "CLOCKWISE";
            state.solid = ordering != "UNKNOWN_ORDERING" && node.word("shapeType") == Some("SOLID");
            // Inventor 1.0: `hints (SOLID | ORDERED | CONVEX)`, ORDERED meaning counter-clockwise.
            if let Some(hints) = node.word("hints") {
                let has = |h: &str| hints.split('|').any(|w| w.trim() == h);
                state.ccw = true;
                state.solid = has("SOLID") && has("ORDERED");
            }
            if let Some(a) = node.float("creaseAngle") {
                state.crease_angle = Some(a);
            }
        }
        "Complexity" => state.complexity = complexity(node)?,
        _ => return Ok(false),
    }
    Ok(true)
}

/// The property parts of Inventor's node kits, in the order their catalogs traverse them
/// (SeparatorKit, AppearanceKit, ShapeKit); `localTransform` and `shape` follow in a scope
/// of their own, then `childList`.
const KIT_PROPERTY_PARTS: [&str; 25] = [
    "callbackList",
    "pickStyle",
    "appearance",
    "lightModel",
    "environment",
    "drawStyle",
    "material",
    "complexity",
    "texture2",
    "font",
    "units",
    "transform",
    "texture2Transform",
    "materialBinding",
    "normalBinding",
    "textureCoordinateBinding",
    "shapeHints",
    "coordinate3",
    "coordinate4",
    "normal",
    "textureCoordinate2",
    "textureCoordinateFunction",
    "profileCoordinate2",
    "profileCoordinate3",
    "profileList",
];

/// A node kit: its property parts, then its shape under `localTransform`, then `childList`
/// (a `NodeKitListPart`, whose `containerNode` holds the children), then any other part (a
/// dragger's) in a scope of its own. Kits separate their state, except the appearance kit
/// and the list part, whose properties are meant for what follows them.
fn kit(node: &Rc<Node>, state: &mut State, ctx: &mut Ctx<'_>) -> PResult<()> {
    let separate = !matches!(node.kind.as_str(), "AppearanceKit" | "NodeKitListPart");
    let mut own;
    let st = if separate {
        own = state.clone();
        &mut own
    } else {
        state
    };
    for part in KIT_PROPERTY_PARTS {
        if let Some(p) = node.node_or_use(part) {
            traverse(p, st, ctx)?;
        }
    }
    let mut shape_state = st.clone();
    for part in ["localTransform", "shape"] {
        if let Some(p) = node.node_or_use(part) {
            traverse(p, &mut shape_state, ctx)?;
        }
    }
    for part in ["childList", "containerNode"] {
        if let Some(p) = node.node_or_use(part) {
            traverse(p, st, ctx)?;
        }
    }
    let walked = |name: &str| {
        KIT_PROPERTY_PARTS.contains(&name)
            || matches!(
                name,
                "localTransform" | "shape" | "childList" | "containerNode"
            )
    };
    for f in node.fields.iter().filter(|f| !walked(&f.name)) {
        if let Value::Node(Some(p)) = &f.value {
            let mut inner = st.clone();
            traverse(p, &mut inner, ctx)?;
        }
    }
    Ok(())
}

/// One copy of an Array's or MultipleCopy's children, each copy a separator placed by `m`.
fn copy(node: &Rc<Node>, state: &State, m: (Mat4, DMat4), ctx: &mut Ctx<'_>) -> PResult<()> {
    ctx.budget.copy(node.line)?;
    let mut inner = state.clone();
    inner.transform *= m.0;
    inner.exact *= m.1;
    for c in &node.children {
        traverse(c, &mut inner, ctx)?;
    }
    Ok(())
}

/// The translations of an Array's copies: `numElements1..3` along `separation1..3`, from
/// the origin (FIRST), centred on it (CENTER) or ending at it (LAST).
fn array_offsets(node: &Node) -> PResult<Vec<Vec3>> {
    let axes = [Vec3::X, Vec3::Y, Vec3::Z];
    let mut counts = [1u64; 3];
    let mut seps = [Vec3::ZERO; 3];
    for k in 0..3 {
        let count = node.int(&format!("numElements{}", k + 1)).unwrap_or(1);
        counts[k] = count.max(0) as u64;
        seps[k] = vec3(node.floats(&format!("separation{}", k + 1)), axes[k]);
    }
    let total = counts.iter().product::<u64>();
    if total > super::MAX_MODELS as u64 {
        return Err(ParseError::new(
            node.line,
            format!("Array of {total} copies: more than {}", super::MAX_MODELS),
        ));
    }
    let shift = match node.word("origin").unwrap_or("FIRST") {
        "FIRST" => 0.0,
        "CENTER" => 0.5,
        "LAST" => 1.0,
        w => {
            return Err(ParseError::new(
                node.line_of("origin"),
                format!("expected FIRST, CENTER or LAST in Array's origin, found '{w}'"),
            ))
        }
    };
    let start: Vec3 = (0..3)
        .map(|k| -seps[k] * shift * counts[k].saturating_sub(1) as f32)
        .sum();
    let mut out = Vec::with_capacity(total as usize);
    for k in 0..counts[2] {
        for j in 0..counts[1] {
            for i in 0..counts[0] {
                out.push(start + seps[0] * i as f32 + seps[1] * j as f32 + seps[2] * k as f32);
            }
        }
    }
    Ok(out)
}

/// The complexity the primitives use after a `Complexity` node: its value for
/// OBJECT_SPACE and, lacking a camera and a viewport, for SCREEN_SPACE too; Coin's default
/// for BOUNDING_BOX (see docs/design.md#primitives).
fn complexity(node: &Node) -> PResult<f32> {
    let value = node
        .float("value")
        .unwrap_or(primitives::DEFAULT_COMPLEXITY);
    match node.word("type") {
        None | Some("OBJECT_SPACE" | "SCREEN_SPACE") => Ok(value.clamp(0.0, 1.0)),
        Some("BOUNDING_BOX") => Ok(primitives::DEFAULT_COMPLEXITY),
        Some(w) => Err(ParseError::new(
            node.line_of("type"),
            format!("expected OBJECT_SPACE, SCREEN_SPACE or BOUNDING_BOX in Complexity's type, found '{w}'"),
        )),
    }
}

/// `Texture2`'s wrap `field`: true for REPEAT (also when absent), false for CLAMP.
fn wrap(node: &Node, field: &str) -> PResult<bool> {
    match node.word(field) {
        None | Some("REPEAT") => Ok(true),
        Some("CLAMP") => Ok(false),
        Some(w) => Err(ParseError::new(
            node.line_of(field),
            format!("expected REPEAT or CLAMP in Texture2's {field}, found '{w}'"),
        )),
    }
}

fn binding(node: &Node) -> PResult<Binding> {
    let w = node.word("value").unwrap_or("DEFAULT");
    Binding::parse(w).ok_or_else(|| {
        ParseError::new(
            node.line_of("value"),
            format!(
                "expected a binding such as PER_VERTEX_INDEXED in '{}', found '{w}'",
                node.kind
            ),
        )
    })
}

fn diffuse_values(material: Option<&Rc<Node>>) -> &[f32] {
    let v = material.and_then(|m| match m.kind.as_str() {
        "BaseColor" => m.floats("rgb"),
        _ => m.floats("diffuseColor"),
    });
    match v {
        Some(v) if v.len() >= 3 => v,
        _ => &DEFAULT_DIFFUSE,
    }
}

/// Unpacks Inventor packed colours 0xRRGGBBAA into flat RGB floats.
fn unpack_rgba(packed: &[i32]) -> Vec<f32> {
    let mut out = Vec::with_capacity(packed.len() * 3);
    for &p in packed {
        let p = p as u32;
        out.extend([(p >> 24) & 0xff, (p >> 16) & 0xff, (p >> 8) & 0xff].map(|c| c as f32 / 255.0));
    }
    out
}

/// The values of the shape's `vertexProperty` field `own` when it has some, else those of
/// the traversal state's node in `field` (Coordinate3, Normal, TextureCoordinate2).
fn property_or<'a>(
    vp: Option<&'a Rc<Node>>,
    own: &str,
    state_node: &'a Option<Rc<Node>>,
    field: &str,
) -> &'a [f32] {
    match vp.and_then(|v| v.floats(own)).filter(|v| !v.is_empty()) {
        Some(v) => v,
        None => state_node
            .as_ref()
            .and_then(|n| n.floats(field))
            .unwrap_or(&[]),
    }
}

/// The f64 points of the shape's coordinates (those [`property_or`] picks), when one of
/// them is far from zero.
fn far_points<'a>(node: &'a Node, state: &'a State) -> Option<&'a [f64]> {
    let vp = node
        .node("vertexProperty")
        .filter(|v| !v.skipped && v.kind == "VertexProperty");
    match vp
        .and_then(|v| v.floats("vertex"))
        .filter(|v| !v.is_empty())
    {
        Some(_) => vp.and_then(|v| v.far("vertex")),
        None => state.coords.as_ref().and_then(|n| n.far("point")),
    }
}

/// A shape's vertex data: its `vertexProperty` values where it has them, else the
/// traversal state's nodes (a Cube makes its own corners).
struct Props<'a> {
    coords: Cow<'a, [f32]>,
    normals: &'a [f32],
    materials: Cow<'a, [f32]>,
    material_binding: Binding,
    normal_binding: Binding,
    texcoords: Cow<'a, [f32]>,
}

fn props<'a>(node: &'a Node, state: &'a State) -> Props<'a> {
    let vp = node
        .node("vertexProperty")
        .filter(|v| !v.skipped && v.kind == "VertexProperty");
    let cube = node.kind == "Cube";
    let textured_cube = cube && state.texture.is_some();
    let coords = if cube {
        let half = Vec3::new(
            node.float("width").unwrap_or(2.0),
            node.float("height").unwrap_or(2.0),
            node.float("depth").unwrap_or(2.0),
        ) * 0.5;
        Cow::Owned(primitives::box_coords(half, textured_cube))
    } else {
        Cow::Borrowed(property_or(vp, "vertex", &state.coords, "point"))
    };
    // A Cube makes its own texture coordinates, as the specification defines them.
    let texcoords = if textured_cube {
        Cow::Owned(primitives::box_texcoords())
    } else {
        Cow::Borrowed(property_or(vp, "texCoord", &state.texcoords, "point"))
    };
    let rgba = vp
        .and_then(|v| v.ints("orderedRGBA"))
        .filter(|v| !v.is_empty());
    let (materials, material_binding) = match rgba {
        Some(rgba) => (
            Cow::Owned(unpack_rgba(rgba)),
            vp.and_then(|v| v.word("materialBinding"))
                .and_then(Binding::parse)
                .unwrap_or(Binding::Overall),
        ),
        None => (
            Cow::Borrowed(diffuse_values(state.material.as_ref())),
            state.material_binding,
        ),
    };
    Props {
        coords,
        normals: property_or(vp, "normal", &state.normals, "vector"),
        materials,
        material_binding,
        normal_binding: vp
            .and_then(|v| v.word("normalBinding"))
            .and_then(Binding::parse)
            .unwrap_or(state.normal_binding),
        texcoords,
    }
}

/// The shape's polygons over `npoints` coordinates, and the field that indexed them; a
/// textured Cube's faces have corners of their own.
fn geometry(node: &Node, npoints: usize, textured: bool) -> PResult<(Geo, &'static str)> {
    match node.kind.as_str() {
        "IndexedFaceSet" => {
            let raw = node.ints("coordIndex").unwrap_or(&[]);
            let (c, e, p) = split_polygons(raw, node.line_of("coordIndex"), "coordIndex")?;
            Ok((Geo::faces(c, e, p), "coordIndex"))
        }
        "IndexedTriangleStripSet" | "IndexedTriangleMesh" => {
            let raw = node.ints("coordIndex").unwrap_or(&[]);
            let (c, e, p) = split_polygons(raw, node.line_of("coordIndex"), "coordIndex")?;
            let s = strips_to_triangles(&c, &e);
            let ntri = s.ends.len() as u32;
            let geo = Geo {
                seq_no: s.source.clone(),
                raw_pos: s.source.iter().map(|&k| p[k as usize] as u32).collect(),
                corners: s.corners,
                ends: s.ends,
                face_no: (0..ntri).collect(),
                part_no: s.part,
            };
            Ok((geo, "coordIndex"))
        }
        "FaceSet" | "TriangleStripSet" => counted(node, npoints),
        "QuadMesh" => quad_mesh(node, npoints),
        _ => Ok((cube_geo(textured), "Cube")),
    }
}

/// FaceSet and TriangleStripSet: runs of `numVertices` consecutive coordinates from
/// `startIndex` (-1 meaning "all remaining").
fn counted(node: &Node, npoints: usize) -> PResult<(Geo, &'static str)> {
    let start = node.int("startIndex").unwrap_or(0).max(0) as u64;
    let counts = node.ints("numVertices").unwrap_or(&[]);
    let line = node.line_of("numVertices");
    let mut corners = Vec::new();
    let mut ends = Vec::new();
    let mut next = start;
    for &n in counts {
        let n = match n {
            -1 => (npoints as u64).saturating_sub(next),
            n if n < 0 => {
                return Err(ParseError::new(
                    line,
                    format!("negative count {n} in 'numVertices'"),
                ))
            }
            n => n as u64,
        };
        if next + n > npoints as u64 {
            return Err(ParseError::new(
                line,
                format!(
                    "'numVertices' asks for vertices up to {} but the coordinates have {npoints} points",
                    next + n
                ),
            ));
        }
        corners.extend(next as u32..(next + n) as u32);
        ends.push(corners.len() as u32);
        next += n;
    }
    if node.kind == "FaceSet" {
        let faces = (0..ends.len() as u32).collect();
        return Ok((Geo::non_indexed(corners, ends, faces), "numVertices"));
    }
    let s = strips_to_triangles(&corners, &ends);
    let ntri = s.ends.len() as u32;
    let seq: Vec<u32> = s.source.iter().map(|&k| corners[k as usize]).collect();
    let geo = Geo {
        raw_pos: seq.clone(),
        seq_no: seq,
        corners: s.corners,
        ends: s.ends,
        face_no: (0..ntri).collect(),
        part_no: s.part,
    };
    Ok((geo, "numVertices"))
}

/// A QuadMesh: `verticesPerColumn` rows of `verticesPerRow` coordinates from `startIndex`;
/// each row of quads is a part.
fn quad_mesh(node: &Node, npoints: usize) -> PResult<(Geo, &'static str)> {
    let start = node.int("startIndex").unwrap_or(0).max(0) as u64;
    let rows = node.int("verticesPerColumn").unwrap_or(1).max(0) as u64;
    let cols = node.int("verticesPerRow").unwrap_or(1).max(0) as u64;
    if start + rows * cols > npoints as u64 {
        return Err(ParseError::new(
            node.line_of("verticesPerColumn"),
            format!(
                "QuadMesh of {rows} x {cols} vertices from {start} needs more than the {npoints} points given"
            ),
        ));
    }
    let (start, rows, cols) = (start as u32, rows as u32, cols as u32);
    let mut corners = Vec::new();
    let mut ends = Vec::new();
    let mut part = Vec::new();
    let at = |r: u32, c: u32| start + r * cols + c;
    for r in 0..rows.saturating_sub(1) {
        for c in 0..cols.saturating_sub(1) {
            corners.extend([at(r, c), at(r + 1, c), at(r + 1, c + 1), at(r, c + 1)]);
            ends.push(corners.len() as u32);
            part.push(r);
        }
    }
    Ok((Geo::non_indexed(corners, ends, part), "verticesPerColumn"))
}

/// A Cube's six quads over `primitives::box_coords`, counter-clockwise seen from outside;
/// PER_FACE and PER_PART bind one value per side.
fn cube_geo(textured: bool) -> Geo {
    let corners = primitives::box_quads(textured);
    Geo {
        seq_no: (0..24).collect(),
        raw_pos: (0..24).collect(),
        ends: (1..=6).map(|i| i * 4).collect(),
        corners,
        face_no: (0..6).collect(),
        part_no: (0..6).collect(),
    }
}

/// Colours, normals and texture coordinates of a shape bound over `geo`.
fn attributes<'a>(
    node: &Node,
    state: &State,
    props: &'a Props<'_>,
    geo: &Geo,
) -> (Bind<'a>, Bind<'a>, Option<TexCoords<'a>>) {
    let indexed = matches!(
        node.kind.as_str(),
        "IndexedFaceSet" | "IndexedTriangleStripSet" | "IndexedTriangleMesh"
    );
    let index = |field: &str| if indexed { node.ints(field) } else { None };
    // Non-indexed shapes have no index lists: an *_INDEXED binding means the plain one.
    let plain = |b: Binding| match (indexed, b) {
        (false, Binding::PerPartIndexed) => Binding::PerPart,
        (false, Binding::PerFaceIndexed) => Binding::PerFace,
        (false, Binding::PerVertexIndexed) => Binding::PerVertex,
        _ => b,
    };
    if node.kind == "Cube" {
        let colors = match plain(props.material_binding) {
            b @ (Binding::PerFace | Binding::PerPart) => resolve(b, &props.materials, None, geo),
            _ => Bind::None,
        };
        let texcoords = state
            .texture
            .as_ref()
            .and_then(|_| texcoords_per_vertex(&props.texcoords, None, geo, true));
        return (colors, Bind::None, texcoords);
    }
    let colors = resolve(
        plain(props.material_binding),
        &props.materials,
        index("materialIndex"),
        geo,
    );
    let normal_binding = match props.normal_binding {
        // Indexed shapes default to per-vertex-indexed normals, others to per-vertex.
        Binding::Default if indexed => Binding::PerVertexIndexed,
        Binding::Default => Binding::PerVertex,
        b => b,
    };
    let normal_index = index("normalIndex").filter(|i| explicit(Some(i)).is_some());
    let normals = resolve(plain(normal_binding), props.normals, normal_index, geo);
    // Per vertex, the only binding there is: PER_VERTEX takes the pairs in corner order,
    // PER_VERTEX_INDEXED (the default) through textureCoordIndex or else coordIndex.
    let by_index = indexed && state.texcoord_binding != Binding::PerVertex;
    let texcoord_index = if by_index {
        node.ints("textureCoordIndex")
    } else {
        None
    };
    let texcoords = texcoords_per_vertex(&props.texcoords, texcoord_index, geo, by_index);
    (colors, normals, texcoords)
}

fn shape(node: &Rc<Node>, state: &State, ctx: &mut Ctx<'_>) -> PResult<()> {
    let props = props(node, state);
    let textured = state.texture.is_some();
    let (geo, index_field) = geometry(node, props.coords.len() / 3, textured)?;
    let (colors, normals, texcoords) = attributes(node, state, &props, &geo);
    let cube = node.kind == "Cube";
    let m = &props.materials;
    let spec = ShapeSpec {
        name: shape_name(node, ctx),
        transform: state.transform,
        coords: &props.coords,
        corners: geo.corners,
        ends: geo.ends,
        colors,
        normals,
        texcoords,
        ccw: state.ccw || cube,
        solid: state.solid || cube,
        crease_angle: state.crease_angle,
        diffuse: [m[0], m[1], m[2]],
        line: if cube {
            node.line
        } else {
            node.line_of(index_field)
        },
        index_field,
    };
    let far = (!cube).then(|| far_points(node, state)).flatten();
    finish(spec, state, far, node.line, ctx)
}

/// The DEF name of a shape node, or its kind and number.
fn shape_name(node: &Node, ctx: &Ctx<'_>) -> String {
    node.def
        .clone()
        .unwrap_or_else(|| format!("{}_{}", node.kind, ctx.models.len() + 1))
}

/// Builds the model (relative to the scene's origin where it is far), gives it the state's texture (with the default coordinates where the
/// shape has none) and keeps it unless it is empty.
fn finish(
    spec: ShapeSpec<'_>,
    state: &State,
    far_points: Option<&[f64]>,
    line: usize,
    ctx: &mut Ctx<'_>,
) -> PResult<()> {
    let mut model = far::build_placed(spec, &state.exact, far_points, ctx)?;
    if state.texture.is_some() && model.texcoords.is_none() {
        default_texcoords::bounding_box(&mut model);
    }
    texture_transform::apply(&mut model, state.texture_transform);
    model.texture = state.texture.clone();
    if model.texture.is_some() {
        // Wrapping means nothing without an image: left at the default, as `.pm` files keep it.
        model.texture_repeat = state.texture_repeat;
    }
    if model.triangles.is_empty() {
        return Ok(());
    }
    ctx.budget.spend(model.triangles.len(), line)?;
    ctx.models.push(model);
    Ok(())
}

/// A size field of a primitive: its absolute value (Coin accepts negative sizes), or the
/// default when absent.
fn size(node: &Node, field: &str, default: f32) -> f32 {
    node.float(field).map_or(default, f32::abs)
}

/// Says that a primitive (or VRML 2.0 ElevationGrid) that makes no triangles (a zero size,
/// no parts, fewer than 2 x 2 points) was skipped.
pub fn skip_empty(node: &Node, ctx: &mut Ctx<'_>) {
    let why = match node.kind.as_str() {
        "ElevationGrid" => "with fewer than 2 x 2 points",
        "Extrusion" => "with fewer than 2 spine or cross-section points",
        _ => "of zero size or with no parts",
    };
    ctx.warnings.push(
        Warning::new(
            WarningKind::SkippedNode,
            format!("line {}: '{}' {why} skipped", node.line, node.kind),
        )
        .at(node.line),
    );
}

/// `Sphere`, `Cone` or `Cylinder`, tessellated at the state's complexity.
fn primitive(node: &Rc<Node>, state: &State, ctx: &mut Ctx<'_>) -> PResult<()> {
    let parts = match node.word("parts") {
        None => Parts::ALL,
        Some(w) => Parts::from_mask(w).ok_or_else(|| {
            ParseError::new(
                node.line_of("parts"),
                format!(
                    "expected SIDES, TOP, BOTTOM or ALL in {}'s parts, found '{w}'",
                    node.kind
                ),
            )
        })?,
    };
    let c = state.complexity;
    let textured = state.texture.is_some();
    let t = match node.kind.as_str() {
        "Sphere" => primitives::sphere(size(node, "radius", 1.0), c, textured),
        "Cylinder" => primitives::cylinder(
            size(node, "radius", 1.0),
            size(node, "height", 2.0),
            c,
            parts,
            textured,
        ),
        _ => primitives::cone(
            size(node, "bottomRadius", 1.0),
            size(node, "height", 2.0),
            c,
            parts,
            textured,
        ),
    };
    if t.triangles.is_empty() {
        skip_empty(node, ctx);
        return Ok(());
    }
    let geo = t.to_geo();
    let colors = match state.material_binding {
        Binding::PerPart | Binding::PerPartIndexed => resolve(
            Binding::PerPart,
            diffuse_values(state.material.as_ref()),
            None,
            &geo,
        ),
        _ => Bind::None,
    };
    let d = diffuse_values(state.material.as_ref());
    let spec = primitives::shape_spec(
        shape_name(node, ctx),
        state.transform,
        &t,
        geo,
        colors,
        [d[0], d[1], d[2]],
        node.line,
    );
    finish(spec, state, None, node.line, ctx)
}

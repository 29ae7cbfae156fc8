//! VRML 1.0 and Open Inventor ASCII semantics: a traversal state machine over the parsed
//! node tree.
//!
//! Properties (coordinates, normals, materials, bindings, shape hints, the transform)
//! accumulate in a state that `Separator` saves and restores; `Group` and `Switch` let it leak
//! as the specification says, `TransformSeparator` saves the transform only. Every shape node
//! (IndexedFaceSet, IndexedTriangleStripSet, FaceSet, TriangleStripSet, QuadMesh, Cube)
//! becomes one `Model` with the state's world transform. Inventor 2.1 `vertexProperty` fields
//! override the state for their shape. `MatrixTransform` follows the row-vector convention:
//! the matrix is written row by row with the translation in the last row.

use std::rc::Rc;

use glam::{Mat4, Quat, Vec3};

use super::bindings::{
    explicit, resolve, split_polygons, strips_to_triangles, texcoords_per_vertex, Binding, Geo,
};
use super::lexer::{PResult, ParseError};
use super::parse::Node;
use super::Ctx;
use crate::io::shape_to_model::{build, Bind, ShapeSpec};
use crate::mesh::Model;

const DEFAULT_DIFFUSE: [f32; 3] = [0.8, 0.8, 0.8];

#[derive(Clone)]
struct State {
    transform: Mat4,
    coords: Option<Rc<Node>>,
    normals: Option<Rc<Node>>,
    texcoords: Option<Rc<Node>>,
    /// `Texture2`'s file name.
    texture: Option<String>,
    /// `Texture2`'s `wrapS`, `wrapT`: true for REPEAT (the default), false for CLAMP.
    texture_repeat: [bool; 2],
    material: Option<Rc<Node>>,
    material_binding: Binding,
    normal_binding: Binding,
    texcoord_binding: Binding,
    ccw: bool,
    solid: bool,
    crease_angle: Option<f32>,
}

impl Default for State {
    fn default() -> Self {
        Self {
            transform: Mat4::IDENTITY,
            coords: None,
            normals: None,
            texcoords: None,
            texture: None,
            texture_repeat: [true; 2],
            material: None,
            material_binding: Binding::Overall,
            normal_binding: Binding::Default,
            texcoord_binding: Binding::Default,
            ccw: true,
            solid: false,
            crease_angle: None,
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
pub fn read(roots: &[Rc<Node>], warnings: &mut Vec<String>) -> PResult<Vec<Model>> {
    let mut ctx = Ctx::new(warnings);
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
    match node.kind.as_str() {
        "Separator" | "Selection" | "Annotation" | "WWWAnchor" | "Array" | "MultipleCopy" => {
            if matches!(node.kind.as_str(), "Array" | "MultipleCopy") {
                ctx.budget.warn_once(
                    ctx.warnings,
                    &node.kind,
                    format!(
                        "line {}: {} copies are not expanded; its children are read once",
                        node.line, node.kind
                    ),
                );
            }
            let mut inner = state.clone();
            for c in &node.children {
                traverse(c, &mut inner, ctx)?;
            }
        }
        "TransformSeparator" => {
            let saved = state.transform;
            for c in &node.children {
                traverse(c, state, ctx)?;
            }
            state.transform = saved;
        }
        "Group" => {
            for c in &node.children {
                traverse(c, state, ctx)?;
            }
        }
        "Switch" | "Blinker" => {
            // -1 none, -2 inherit (nothing to inherit from here: none), -3 all.
            let which =
                node.int("whichChild")
                    .unwrap_or(if node.kind == "Blinker" { 0 } else { -1 });
            if which == -3 {
                for c in &node.children {
                    traverse(c, state, ctx)?;
                }
            } else if which >= 0 {
                if let Some(c) = node.children.get(which as usize) {
                    traverse(c, state, ctx)?;
                }
            }
        }
        "LOD" | "LevelOfDetail" => {
            // The most detailed level.
            if let Some(c) = node.children.first() {
                traverse(c, state, ctx)?;
            }
        }
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
        "Material" | "BaseColor" => state.material = Some(node.clone()),
        "MaterialBinding" => state.material_binding = binding(node)?,
        "NormalBinding" => state.normal_binding = binding(node)?,
        "TextureCoordinateBinding" => state.texcoord_binding = binding(node)?,
        "ShapeHints" => {
            let ordering = node.word("vertexOrdering").unwrap_or("UNKNOWN_ORDERING");
            state.ccw = ordering != "CLOCKWISE";
            state.solid = ordering != "UNKNOWN_ORDERING" && node.word("shapeType") == Some("SOLID");
            if let Some(a) = node.float("creaseAngle") {
                state.crease_angle = Some(a);
            }
        }
        "IndexedFaceSet"
        | "IndexedTriangleStripSet"
        | "FaceSet"
        | "TriangleStripSet"
        | "QuadMesh"
        | "Cube" => shape(node, state, ctx)?,
        _ => {}
    }
    Ok(())
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

fn shape(node: &Rc<Node>, state: &State, ctx: &mut Ctx<'_>) -> PResult<()> {
    let kind = node.kind.as_str();
    let vp = node
        .node("vertexProperty")
        .filter(|v| !v.skipped && v.kind == "VertexProperty");
    let packed;
    let cube;
    let cube_half;
    // Coordinates: the vertexProperty's, else the state's.
    let coords: &[f32] = if kind == "Cube" {
        cube_half = Vec3::new(
            node.float("width").unwrap_or(2.0),
            node.float("height").unwrap_or(2.0),
            node.float("depth").unwrap_or(2.0),
        ) * 0.5;
        cube = box_corners(cube_half);
        &cube
    } else {
        property_or(vp, "vertex", &state.coords, "point")
    };
    let normal_values = property_or(vp, "normal", &state.normals, "vector");
    let (material_values, material_binding): (&[f32], Binding) = match vp
        .and_then(|v| v.ints("orderedRGBA"))
        .filter(|v| !v.is_empty())
    {
        Some(rgba) => {
            packed = unpack_rgba(rgba);
            let b = vp
                .and_then(|v| v.word("materialBinding"))
                .and_then(Binding::parse)
                .unwrap_or(Binding::Overall);
            (&packed, b)
        }
        None => (
            diffuse_values(state.material.as_ref()),
            state.material_binding,
        ),
    };
    let texcoord_values = property_or(vp, "texCoord", &state.texcoords, "point");
    let normal_binding = vp
        .and_then(|v| v.word("normalBinding"))
        .and_then(Binding::parse)
        .unwrap_or(state.normal_binding);
    let diffuse = [material_values[0], material_values[1], material_values[2]];

    let line = node.line;
    let start = node.int("startIndex").unwrap_or(0).max(0) as u32;
    let indexed = matches!(kind, "IndexedFaceSet" | "IndexedTriangleStripSet");
    let (geo, index_field) = match kind {
        "IndexedFaceSet" => {
            let raw = node.ints("coordIndex").unwrap_or(&[]);
            let (c, e, p) = split_polygons(raw, node.line_of("coordIndex"), "coordIndex")?;
            (Geo::faces(c, e, p), "coordIndex")
        }
        "IndexedTriangleStripSet" => {
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
            (geo, "coordIndex")
        }
        "FaceSet" | "TriangleStripSet" => {
            let counts = node.ints("numVertices").unwrap_or(&[]);
            let mut corners = Vec::new();
            let mut ends = Vec::new();
            let mut next = start as u64;
            for &n in counts {
                // Inventor's -1 means "all remaining vertices".
                let n = if n == -1 {
                    (coords.len() as u64 / 3).saturating_sub(next)
                } else if n < 0 {
                    return Err(ParseError::new(
                        node.line_of("numVertices"),
                        format!("negative count {n} in 'numVertices'"),
                    ));
                } else {
                    n as u64
                };
                if next + n > coords.len() as u64 / 3 {
                    return Err(ParseError::new(
                        node.line_of("numVertices"),
                        format!(
                            "'numVertices' asks for vertices up to {} but the coordinates have {} points",
                            next + n,
                            coords.len() / 3
                        ),
                    ));
                }
                corners.extend(next as u32..(next + n) as u32);
                ends.push(corners.len() as u32);
                next += n;
            }
            if kind == "FaceSet" {
                let nf = ends.len() as u32;
                let geo = Geo {
                    seq_no: corners.clone(),
                    raw_pos: corners.clone(),
                    corners,
                    ends,
                    face_no: (0..nf).collect(),
                    part_no: (0..nf).collect(),
                };
                (geo, "numVertices")
            } else {
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
                (geo, "numVertices")
            }
        }
        "QuadMesh" => {
            let rows = node.int("verticesPerColumn").unwrap_or(1).max(0) as u64;
            let cols = node.int("verticesPerRow").unwrap_or(1).max(0) as u64;
            if start as u64 + rows * cols > coords.len() as u64 / 3 {
                return Err(ParseError::new(
                    node.line_of("verticesPerColumn"),
                    format!(
                        "QuadMesh of {rows} x {cols} vertices from {start} needs more than the {} points given",
                        coords.len() / 3
                    ),
                ));
            }
            let (rows, cols) = (rows as u32, cols as u32);
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
            let nf = ends.len() as u32;
            let geo = Geo {
                seq_no: corners.clone(),
                raw_pos: corners.clone(),
                corners,
                ends,
                face_no: (0..nf).collect(),
                part_no: part,
            };
            (geo, "verticesPerColumn")
        }
        _ => {
            // Cube: six quads, counter-clockwise seen from outside; PER_FACE/PER_PART is per side.
            let faces: [[u32; 4]; 6] = [
                [4, 5, 7, 6],
                [0, 2, 3, 1],
                [1, 3, 7, 5],
                [0, 4, 6, 2],
                [2, 6, 7, 3],
                [0, 1, 5, 4],
            ];
            let corners: Vec<u32> = faces.iter().flatten().copied().collect();
            let geo = Geo {
                seq_no: (0..24).collect(),
                raw_pos: (0..24).collect(),
                ends: (1..=6).map(|i| i * 4).collect(),
                corners,
                face_no: (0..6).collect(),
                part_no: (0..6).collect(),
            };
            (geo, "Cube")
        }
    };
    let (mat_index, norm_index) = if indexed {
        (node.ints("materialIndex"), node.ints("normalIndex"))
    } else {
        (None, None)
    };
    // Non-indexed shapes have no index lists: an *_INDEXED binding means the plain one.
    let plain = |b: Binding| match (indexed, b) {
        (false, Binding::PerPartIndexed) => Binding::PerPart,
        (false, Binding::PerFaceIndexed) => Binding::PerFace,
        (false, Binding::PerVertexIndexed) => Binding::PerVertex,
        _ => b,
    };
    let colors = if kind == "Cube"
        && !matches!(
            material_binding,
            Binding::PerFace | Binding::PerPart | Binding::PerFaceIndexed | Binding::PerPartIndexed
        ) {
        Bind::None
    } else {
        resolve(plain(material_binding), material_values, mat_index, &geo)
    };
    let normal_binding = match normal_binding {
        // Indexed shapes default to per-vertex-indexed normals, others to per-vertex.
        Binding::Default if indexed => Binding::PerVertexIndexed,
        Binding::Default => Binding::PerVertex,
        b => b,
    };
    let normals = if kind == "Cube" {
        Bind::None
    } else {
        resolve(
            plain(normal_binding),
            normal_values,
            norm_index.filter(|i| explicit(Some(i)).is_some()),
            &geo,
        )
    };
    // Per vertex, the only binding there is: PER_VERTEX takes the pairs in corner order,
    // PER_VERTEX_INDEXED (the default) through textureCoordIndex or else coordIndex.
    let texcoords = if kind == "Cube" {
        None
    } else {
        let by_index = indexed && state.texcoord_binding != Binding::PerVertex;
        let index = if by_index {
            node.ints("textureCoordIndex")
        } else {
            None
        };
        texcoords_per_vertex(texcoord_values, index, &geo, by_index)
    };
    let name = node
        .def
        .clone()
        .unwrap_or_else(|| format!("{kind}_{}", ctx.models.len() + 1));
    let spec = ShapeSpec {
        name,
        transform: state.transform,
        coords,
        corners: geo.corners,
        ends: geo.ends,
        colors,
        normals,
        texcoords,
        ccw: state.ccw || kind == "Cube",
        solid: state.solid || kind == "Cube",
        crease_angle: state.crease_angle,
        diffuse,
        line: if kind == "Cube" {
            line
        } else {
            node.line_of(index_field)
        },
        index_field,
    };
    let mut model = build(spec, ctx.warnings)?;
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

/// The eight corners of a centred box, flat x y z; corner `i` has +x when bit 0 is set, +y
/// for bit 1, +z for bit 2.
pub fn box_corners(half: Vec3) -> Vec<f32> {
    (0..8)
        .flat_map(|i| {
            [
                if i & 1 != 0 { half.x } else { -half.x },
                if i & 2 != 0 { half.y } else { -half.y },
                if i & 4 != 0 { half.z } else { -half.z },
            ]
        })
        .collect()
}

//! VRML 2.0 semantics: a walk over the tree of `Transform { children }`, `Group`, `Switch`,
//! `LOD` and `Shape` nodes.
//!
//! Each `Shape` whose geometry is an `IndexedFaceSet` (or a `Box`) becomes one `Model` with the
//! accumulated world transform, the material's diffuse colour, and the face set's colours
//! and normals (`colorPerVertex` / `normalPerVertex`, with or without index lists).

use std::rc::Rc;

use glam::{Mat4, Vec3};

use super::bindings::{explicit, resolve, split_polygons, texcoords_per_vertex, Binding, Geo};
use super::lexer::PResult;
use super::parse::Node;
use super::vrml1::{box_corners, compose, rotation, vec3};
use super::Ctx;
use crate::io::shape_to_model::{build, Bind, ShapeSpec};
use crate::mesh::Model;

/// Walks the top-level nodes into models.
pub fn read(roots: &[Rc<Node>], warnings: &mut Vec<String>) -> PResult<Vec<Model>> {
    let mut ctx = Ctx::new(warnings);
    for n in roots {
        traverse(n, Mat4::IDENTITY, &mut ctx)?;
    }
    Ok(ctx.models)
}

fn traverse(node: &Rc<Node>, transform: Mat4, ctx: &mut Ctx<'_>) -> PResult<()> {
    if node.skipped {
        return Ok(());
    }
    match node.kind.as_str() {
        "Transform" => {
            let m = transform
                * compose(
                    vec3(node.floats("translation"), Vec3::ZERO),
                    rotation(node.floats("rotation")),
                    vec3(node.floats("scale"), Vec3::ONE),
                    rotation(node.floats("scaleOrientation")),
                    vec3(node.floats("center"), Vec3::ZERO),
                );
            for c in node.nodes("children") {
                traverse(c, m, ctx)?;
            }
        }
        "Group" | "Collision" | "Anchor" | "Billboard" => {
            for c in node.nodes("children") {
                traverse(c, transform, ctx)?;
            }
        }
        "Switch" => {
            let which = node.int("whichChoice").unwrap_or(-1);
            if which >= 0 {
                if let Some(c) = node.nodes("choice").get(which as usize) {
                    traverse(c, transform, ctx)?;
                }
            }
        }
        "LOD" => {
            if let Some(c) = node.nodes("level").first() {
                traverse(c, transform, ctx)?;
            }
        }
        "Shape" => shape(node, transform, ctx)?,
        _ => {}
    }
    Ok(())
}

fn shape(node: &Rc<Node>, transform: Mat4, ctx: &mut Ctx<'_>) -> PResult<()> {
    let Some(geometry) = node.node("geometry").filter(|g| !g.skipped) else {
        return Ok(());
    };
    let diffuse = node
        .node("appearance")
        .and_then(|a| a.node("material"))
        .and_then(|m| m.floats("diffuseColor"))
        .and_then(|d| d.get(0..3))
        .map_or([0.8; 3], |d| [d[0], d[1], d[2]]);
    let name = geometry
        .def
        .clone()
        .or_else(|| node.def.clone())
        .unwrap_or_else(|| format!("{}_{}", geometry.kind, ctx.models.len() + 1));
    let image = node
        .node("appearance")
        .and_then(|a| a.node("texture"))
        .filter(|t| t.kind == "ImageTexture");
    let texture = image.and_then(|t| t.strings("url").first().cloned());
    let texture_repeat =
        ["repeatS", "repeatT"].map(|field| image.and_then(|t| t.boolean(field)).unwrap_or(true));
    let boxed;
    let spec = match geometry.kind.as_str() {
        "IndexedFaceSet" => {
            let coords = geometry
                .node("coord")
                .and_then(|c| c.floats("point"))
                .unwrap_or(&[]);
            let raw = geometry.ints("coordIndex").unwrap_or(&[]);
            let line = geometry.line_of("coordIndex");
            let (c, e, p) = split_polygons(raw, line, "coordIndex")?;
            let geo = Geo::faces(c, e, p);
            let per_vertex = |name: &str| geometry.boolean(name).unwrap_or(true);
            let binding = |index: Option<&[i32]>, per_vertex: bool| match (
                per_vertex,
                explicit(index).is_some(),
            ) {
                (true, _) => Binding::PerVertexIndexed,
                (false, true) => Binding::PerFaceIndexed,
                (false, false) => Binding::PerFace,
            };
            let color_values = geometry
                .node("color")
                .and_then(|c| c.floats("color"))
                .unwrap_or(&[]);
            let normal_values = geometry
                .node("normal")
                .and_then(|n| n.floats("vector"))
                .unwrap_or(&[]);
            let ci = geometry.ints("colorIndex");
            let ni = geometry.ints("normalIndex");
            let colors = resolve(
                binding(ci, per_vertex("colorPerVertex")),
                color_values,
                ci,
                &geo,
            );
            let normals = resolve(
                binding(ni, per_vertex("normalPerVertex")),
                normal_values,
                ni,
                &geo,
            );
            let texcoord_values = geometry
                .node("texCoord")
                .and_then(|t| t.floats("point"))
                .unwrap_or(&[]);
            let texcoords =
                texcoords_per_vertex(texcoord_values, geometry.ints("texCoordIndex"), &geo, true);
            ShapeSpec {
                name,
                transform,
                coords,
                corners: geo.corners,
                ends: geo.ends,
                colors,
                normals,
                texcoords,
                ccw: geometry.boolean("ccw").unwrap_or(true),
                solid: geometry.boolean("solid").unwrap_or(true),
                crease_angle: geometry.float("creaseAngle"),
                diffuse,
                line,
                index_field: "coordIndex",
            }
        }
        "Box" => {
            boxed = box_corners(vec3(geometry.floats("size"), Vec3::splat(2.0)) * 0.5);
            let faces: [u32; 24] = [
                4, 5, 7, 6, 0, 2, 3, 1, 1, 3, 7, 5, 0, 4, 6, 2, 2, 6, 7, 3, 0, 1, 5, 4,
            ];
            ShapeSpec {
                name,
                transform,
                coords: &boxed,
                corners: faces.to_vec(),
                ends: (1..=6).map(|i| i * 4).collect(),
                colors: Bind::None,
                normals: Bind::None,
                texcoords: None,
                ccw: true,
                solid: true,
                crease_angle: None,
                diffuse,
                line: geometry.line,
                index_field: "Box",
            }
        }
        other => {
            ctx.budget.warn_once(
                ctx.warnings,
                other,
                format!(
                    "line {}: geometry '{other}' is not converted to triangles; skipped",
                    geometry.line
                ),
            );
            return Ok(());
        }
    };
    let mut model = build(spec, ctx.warnings)?;
    model.texture = texture;
    if model.texture.is_some() {
        // Wrapping means nothing without an image: left at the default, as `.pm` files keep it.
        model.texture_repeat = texture_repeat;
    }
    if model.triangles.is_empty() {
        return Ok(());
    }
    ctx.budget.spend(model.triangles.len(), node.line)?;
    ctx.models.push(model);
    Ok(())
}

//! VRML 2.0 semantics: a walk over the tree of `Transform { children }`, `Group`, `Switch`,
//! `LOD` and `Shape` nodes.
//!
//! Each `Shape` whose geometry is an `IndexedFaceSet`, an `ElevationGrid`, a `Box` or a
//! `Sphere`, `Cone` or `Cylinder` (see `primitives`) becomes one `Model` with the accumulated
//! world transform, the material's diffuse colour, and the geometry's colours and normals
//! (`colorPerVertex` / `normalPerVertex`, with or without index lists). Under an
//! `ImageTexture`, `Box`, the round primitives and `Extrusion` make the texture coordinates
//! the specification defines, and an IndexedFaceSet or ElevationGrid without `texCoord` gets
//! its default mapping (see `default_texcoords`); an `Appearance`'s `TextureTransform`
//! transforms any shape's. An error inside a `USE`d node names the USE's line and the DEF's.

use std::rc::Rc;

use glam::{DVec3, Mat4, Vec3};

use super::bindings::{explicit, resolve, split_polygons, texcoords_per_vertex, Binding, Geo};
use super::default_texcoords;
use super::extrusion;
use super::far;
use super::lexer::{PResult, ParseError};
use super::parse::{used_at, Node, USE_KIND};
use super::primitives::{self, Parts, Tessellation};
use super::texture_transform;
use super::vrml1::{compose, rotation, skip_empty, vec3};
use super::Ctx;
use crate::io::shape_to_model::{Bind, ShapeSpec, TexCoords};
use crate::io::warning::Warning;
use crate::mesh::Model;

/// Walks the top-level nodes into models.
pub fn read(roots: &[Rc<Node>], warnings: &mut Vec<Warning>, nodes: usize) -> PResult<Vec<Model>> {
    let mut ctx = Ctx::new(warnings, nodes);
    for n in roots {
        traverse(n, Mat4::IDENTITY, &mut ctx)?;
    }
    Ok(ctx.models)
}

fn traverse(node: &Rc<Node>, transform: Mat4, ctx: &mut Ctx<'_>) -> PResult<()> {
    if node.skipped {
        return Ok(());
    }
    ctx.budget.visit(node.line)?;
    if node.kind == USE_KIND {
        return through_use(node, |target| traverse(target, transform, ctx));
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
            let saved = ctx.exact;
            ctx.exact = saved
                * far::compose(
                    far::dvec3(node, "translation", DVec3::ZERO),
                    far::rotation(node.floats("rotation")),
                    far::scale(node.floats("scale"), DVec3::ONE),
                    far::rotation(node.floats("scaleOrientation")),
                    far::dvec3(node, "center", DVec3::ZERO),
                );
            for c in node.nodes("children") {
                traverse(c, m, ctx)?;
            }
            ctx.exact = saved;
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

/// Runs `walk` on the node a `USE` names; an error inside names the USE and the DEF lines.
fn through_use(used: &Rc<Node>, walk: impl FnOnce(&Rc<Node>) -> PResult<()>) -> PResult<()> {
    let target = used.target();
    let name = used.def.as_deref().unwrap_or_default();
    walk(target).map_err(|e| used_at(e, used.line, name, target.line))
}

fn shape(node: &Rc<Node>, transform: Mat4, ctx: &mut Ctx<'_>) -> PResult<()> {
    match node.node_or_use("geometry") {
        Some(g) if g.kind == USE_KIND => through_use(g, |_| shape_geometry(node, transform, ctx)),
        _ => shape_geometry(node, transform, ctx),
    }
}

fn shape_geometry(node: &Rc<Node>, transform: Mat4, ctx: &mut Ctx<'_>) -> PResult<()> {
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
    // Primitives get the texture coordinates their specifications define only under a texture.
    let textured = texture.is_some();
    let texture_repeat =
        ["repeatS", "repeatT"].map(|field| image.and_then(|t| t.boolean(field)).unwrap_or(true));
    let look = Look {
        name,
        transform,
        diffuse,
        textured,
    };
    let Some(mut model) = geometry_model(geometry, look, ctx)? else {
        return Ok(());
    };
    if textured && model.texcoords.is_none() {
        match geometry.kind.as_str() {
            "IndexedFaceSet" => default_texcoords::bounding_box(&mut model),
            "ElevationGrid" => default_texcoords::elevation_grid(&mut model),
            // Every other geometry makes its own.
            _ => {}
        }
    }
    if let Some(t) = node
        .node("appearance")
        .and_then(|a| a.node("textureTransform"))
        .filter(|t| t.kind == "TextureTransform")
    {
        texture_transform::apply(&mut model, texture_transform::vrml2(t));
    }
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

/// What a Shape gives its geometry's model: name, placement, colour, and whether it has a
/// texture (primitives then make their texture coordinates).
struct Look {
    name: String,
    transform: Mat4,
    diffuse: [f32; 3],
    textured: bool,
}

/// The model of a Shape's `geometry` node; `None` when it is empty or of a kind not
/// converted to triangles (said in a warning).
fn geometry_model(geometry: &Rc<Node>, look: Look, ctx: &mut Ctx<'_>) -> PResult<Option<Model>> {
    let Look {
        name,
        transform,
        diffuse,
        textured,
    } = look;
    let spec = match geometry.kind.as_str() {
        "IndexedFaceSet" => indexed_face_set(geometry, name, transform, diffuse)?,
        "Box" => return box_model(geometry, name, transform, diffuse, textured, ctx).map(Some),
        "ElevationGrid" => {
            let (points, geo) = elevation_grid(geometry)?;
            if geo.ends.is_empty() {
                skip_empty(geometry, ctx);
                return Ok(None);
            }
            let far = far_grid_points(geometry);
            let spec = grid_spec(geometry, name, transform, diffuse, &points, geo);
            return place(spec, far.as_deref(), ctx).map(Some);
        }
        "Extrusion" => {
            return extrusion_model(geometry, name, transform, diffuse, textured, ctx);
        }
        "Sphere" | "Cone" | "Cylinder" => {
            let tess = primitive(geometry, textured);
            if tess.triangles.is_empty() {
                skip_empty(geometry, ctx);
                return Ok(None);
            }
            let spec = primitives::shape_spec(
                name,
                transform,
                &tess,
                tess.to_geo(),
                Bind::None,
                diffuse,
                geometry.line,
            );
            return place(spec, None, ctx).map(Some);
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
            return Ok(None);
        }
    };
    let far = geometry.node("coord").and_then(|c| c.far("point"));
    place(spec, far, ctx).map(Some)
}

/// Builds a shape's model at the walk's f64 transform (see `far`).
fn place(spec: ShapeSpec<'_>, far_points: Option<&[f64]>, ctx: &mut Ctx<'_>) -> PResult<Model> {
    let exact = ctx.exact;
    far::build_placed(spec, &exact, far_points, ctx)
}

/// A Box: six quads, with the specification's texture coordinates under a texture.
fn box_model(
    geometry: &Rc<Node>,
    name: String,
    transform: Mat4,
    diffuse: [f32; 3],
    textured: bool,
    ctx: &mut Ctx<'_>,
) -> PResult<Model> {
    let half = vec3(geometry.floats("size"), Vec3::splat(2.0)) * 0.5;
    let boxed = primitives::box_coords(half, textured);
    let made_uv = if textured {
        primitives::box_texcoords()
    } else {
        Vec::new()
    };
    let corners = primitives::box_quads(textured);
    let spec = ShapeSpec {
        name,
        transform,
        coords: &boxed,
        texcoords: textured.then(|| TexCoords {
            values: &made_uv,
            index: corners.clone(),
        }),
        corners,
        ends: (1..=6).map(|i| i * 4).collect(),
        colors: Bind::None,
        normals: Bind::None,
        ccw: true,
        solid: true,
        crease_angle: None,
        diffuse,
        line: geometry.line,
        index_field: "Box",
    };
    place(spec, None, ctx)
}

/// An Extrusion swept along its spine; `None` when it sweeps nothing.
fn extrusion_model(
    geometry: &Rc<Node>,
    name: String,
    transform: Mat4,
    diffuse: [f32; 3],
    textured: bool,
    ctx: &mut Ctx<'_>,
) -> PResult<Option<Model>> {
    let swept = extrusion::extrude(geometry, textured)?;
    if swept.ends.is_empty() {
        skip_empty(geometry, ctx);
        return Ok(None);
    }
    let spec = ShapeSpec {
        name,
        transform,
        coords: &swept.points,
        corners: swept.corners,
        ends: swept.ends,
        colors: Bind::None,
        normals: Bind::None,
        texcoords: textured.then(|| TexCoords {
            values: &swept.texcoords,
            index: swept.texcoord_index,
        }),
        ccw: geometry.boolean("ccw").unwrap_or(true),
        solid: geometry.boolean("solid").unwrap_or(true),
        crease_angle: geometry.float("creaseAngle"),
        diffuse,
        line: geometry.line,
        index_field: "spine",
    };
    place(spec, swept.far_points.as_deref(), ctx).map(Some)
}

/// A `Sphere`, `Cone` or `Cylinder` at Coin's default complexity, with the parts its
/// `side`, `top` and `bottom` fields keep (negative sizes taken as positive, as Coin does),
/// with texture coordinates when `textured`.
fn primitive(g: &Node, textured: bool) -> Tessellation {
    let size = |field: &str, default: f32| g.float(field).map_or(default, f32::abs);
    let on = |field: &str| g.boolean(field).unwrap_or(true);
    let parts = Parts {
        side: on("side"),
        top: on("top"),
        bottom: on("bottom"),
    };
    let c = primitives::DEFAULT_COMPLEXITY;
    match g.kind.as_str() {
        "Sphere" => primitives::sphere(size("radius", 1.0), c, textured),
        "Cylinder" => {
            primitives::cylinder(size("radius", 1.0), size("height", 2.0), c, parts, textured)
        }
        _ => primitives::cone(
            size("bottomRadius", 1.0),
            size("height", 2.0),
            c,
            parts,
            textured,
        ),
    }
}

/// An IndexedFaceSet's polygons with their colours, normals and texture coordinates
/// (`colorPerVertex` / `normalPerVertex`, with or without index lists).
fn indexed_face_set(
    g: &Node,
    name: String,
    transform: Mat4,
    diffuse: [f32; 3],
) -> PResult<ShapeSpec<'_>> {
    let coords = g
        .node("coord")
        .and_then(|c| c.floats("point"))
        .unwrap_or(&[]);
    let raw = g.ints("coordIndex").unwrap_or(&[]);
    let line = g.line_of("coordIndex");
    let (c, e, p) = split_polygons(raw, line, "coordIndex")?;
    let geo = Geo::faces(c, e, p);
    let per_vertex = |name: &str| g.boolean(name).unwrap_or(true);
    let binding =
        |index: Option<&[i32]>, per_vertex: bool| match (per_vertex, explicit(index).is_some()) {
            (true, _) => Binding::PerVertexIndexed,
            (false, true) => Binding::PerFaceIndexed,
            (false, false) => Binding::PerFace,
        };
    let color_values = g
        .node("color")
        .and_then(|c| c.floats("color"))
        .unwrap_or(&[]);
    let normal_values = g
        .node("normal")
        .and_then(|n| n.floats("vector"))
        .unwrap_or(&[]);
    let ci = g.ints("colorIndex");
    let ni = g.ints("normalIndex");
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
    let texcoord_values = g
        .node("texCoord")
        .and_then(|t| t.floats("point"))
        .unwrap_or(&[]);
    let texcoords = texcoords_per_vertex(texcoord_values, g.ints("texCoordIndex"), &geo, true);
    Ok(ShapeSpec {
        name,
        transform,
        coords,
        corners: geo.corners,
        ends: geo.ends,
        colors,
        normals,
        texcoords,
        ccw: g.boolean("ccw").unwrap_or(true),
        solid: g.boolean("solid").unwrap_or(true),
        crease_angle: g.float("creaseAngle"),
        diffuse,
        line,
        index_field: "coordIndex",
    })
}

/// An ElevationGrid's points (`xDimension` by `zDimension`, `xSpacing` and `zSpacing`
/// apart, at `height`) and its quads, counter-clockwise seen from +y; each quad is a face.
fn elevation_grid(g: &Node) -> PResult<(Vec<f32>, Geo)> {
    let nx = g.int("xDimension").unwrap_or(0).max(0) as u64;
    let nz = g.int("zDimension").unwrap_or(0).max(0) as u64;
    let heights = g.floats("height").unwrap_or(&[]);
    if nx * nz > heights.len() as u64 {
        return Err(ParseError::new(
            g.line_of("height"),
            format!(
                "ElevationGrid of {nx} x {nz} points needs {} heights, found {}",
                nx * nz,
                heights.len()
            ),
        ));
    }
    let (nx, nz) = (nx as u32, nz as u32);
    let (dx, dz) = grid_spacing(g);
    let mut points = Vec::with_capacity(heights.len() * 3);
    for j in 0..nz {
        for i in 0..nx {
            let h = heights[(j * nx + i) as usize];
            points.extend([i as f32 * dx, h, j as f32 * dz]);
        }
    }
    let at = |i: u32, j: u32| j * nx + i;
    let mut corners = Vec::new();
    for j in 0..nz.saturating_sub(1) {
        for i in 0..nx.saturating_sub(1) {
            corners.extend([at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)]);
        }
    }
    let n = (corners.len() / 4) as u32;
    let ends = (1..=n).map(|k| k * 4).collect();
    let pos = (0..corners.len()).collect();
    Ok((points, Geo::faces(corners, ends, pos)))
}

/// An ElevationGrid's `xSpacing` and `zSpacing`.
fn grid_spacing(g: &Node) -> (f32, f32) {
    let spacing = |field| g.float(field).unwrap_or(1.0);
    (spacing("xSpacing"), spacing("zSpacing"))
}

/// An ElevationGrid's points in f64 (flat x y z, as `elevation_grid` makes them) when its
/// heights are far from zero (see `io::origin`); `None` otherwise. The grid's x and z are
/// f32 products, exact in f64, so the points differ from the f32 ones in height only.
fn far_grid_points(g: &Node) -> Option<Vec<f64>> {
    let heights = g.far("height")?;
    let nx = g.int("xDimension").unwrap_or(0).max(0) as usize;
    let (dx, dz) = grid_spacing(g);
    let points = heights
        .iter()
        .take(nx * g.int("zDimension").unwrap_or(0).max(0) as usize)
        .enumerate()
        .flat_map(|(k, &h)| {
            let (i, j) = (k % nx, k / nx);
            [f64::from(i as f32 * dx), h, f64::from(j as f32 * dz)]
        })
        .collect();
    Some(points)
}

/// The shape of an ElevationGrid over `points`: colours and normals per point or per quad
/// (`colorPerVertex`, `normalPerVertex`), texture coordinates per point.
fn grid_spec<'a>(
    g: &'a Node,
    name: String,
    transform: Mat4,
    diffuse: [f32; 3],
    points: &'a [f32],
    geo: Geo,
) -> ShapeSpec<'a> {
    let values =
        |node: &str, field: &str| g.node(node).and_then(|n| n.floats(field)).unwrap_or(&[]);
    let binding = |field: &str| match g.boolean(field).unwrap_or(true) {
        true => Binding::PerVertexIndexed,
        false => Binding::PerFace,
    };
    let colors = resolve(
        binding("colorPerVertex"),
        values("color", "color"),
        None,
        &geo,
    );
    let normals = resolve(
        binding("normalPerVertex"),
        values("normal", "vector"),
        None,
        &geo,
    );
    let texcoords = texcoords_per_vertex(values("texCoord", "point"), None, &geo, true);
    ShapeSpec {
        name,
        transform,
        coords: points,
        corners: geo.corners,
        ends: geo.ends,
        colors,
        normals,
        texcoords,
        ccw: g.boolean("ccw").unwrap_or(true),
        solid: g.boolean("solid").unwrap_or(true),
        crease_angle: g.float("creaseAngle"),
        diffuse,
        line: g.line_of("height"),
        index_field: "height",
    }
}

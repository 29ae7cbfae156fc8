//! `GpuMesh` and `GpuScene`: a scene's `MeshData` uploaded into device-local buffers, once per
//! decimation (never per frame) and again only when a draw mode needs a list that was left
//! out (`Layers`), with the world transform of each model, its texture's binding (images are
//! uploaded once, by `Textures`) and the scene's world-space bounds for framing the camera.

use std::sync::Arc;

use ash::vk;
use glam::{Mat4, Vec3};

use super::buffer::{Buffer, Uploader};
use super::camera::Bounds;
use super::commands::Commands;
use super::context::Context;
use super::error::{RenderError, Result};
use super::mesh_data::{Layers, MeshData};
use super::texture::{Binding, Textures};
use decimate_core::mesh::{Model, Scene};

/// Normal segments are this fraction of the scene's bounding-box diagonal.
const NORMAL_LENGTH: f32 = 0.03;

/// One model's buffers.
pub struct GpuMesh {
    pub transform: Mat4,
    /// The model's texture (the white stand-in when it has none), and the stand-in, bound
    /// when textures are off.
    pub texture: vk::DescriptorSet,
    pub plain: vk::DescriptorSet,
    /// True when `texture` is the model's own image.
    pub textured: bool,
    pub vertices: Buffer,
    pub triangles: Buffer,
    pub triangle_indices: u32,
    pub edges: Buffer,
    pub edge_indices: u32,
    pub points: Buffer,
    pub point_count: u32,
    pub face_normals: Buffer,
    pub face_normal_vertices: u32,
    pub vertex_normals: Buffer,
    pub vertex_normal_vertices: u32,
}

/// Every model of a scene, ready to draw.
pub struct GpuScene {
    pub meshes: Vec<GpuMesh>,
    /// World-space bounds; a unit box around the origin for an empty scene.
    pub bounds: Bounds,
    pub vertex_count: usize,
    pub triangle_count: usize,
    /// The optional lists uploaded: a draw mode whose list is missing draws nothing.
    pub layers: Layers,
}

impl GpuScene {
    /// Uploads `scene` with the lists of `layers`; the returned buffers are ready when this
    /// returns.
    pub fn upload(
        context: &Arc<Context>,
        commands: &Commands,
        textures: &mut Textures,
        scene: &Scene,
        layers: Layers,
    ) -> Result<Self> {
        Self::upload_morphing(context, commands, textures, scene, None, layers)
    }

    /// As [`Self::upload`], with each model's geomorph start positions (`morph_from[i]` for
    /// model `i`, indexed like its positions): drawn with a morph factor below 1, vertices
    /// glide from there.
    pub fn upload_morphing(
        context: &Arc<Context>,
        commands: &Commands,
        textures: &mut Textures,
        scene: &Scene,
        morph_from: Option<&[Vec<Vec3>]>,
        layers: Layers,
    ) -> Result<Self> {
        let bounds = scene_bounds(scene);
        let normal_length = (bounds.max - bounds.min).length() * NORMAL_LENGTH;
        let mut uploader = Uploader::new(context, commands)?;
        let mut meshes = Vec::with_capacity(scene.models.len());
        for (i, model) in scene.models.iter().enumerate() {
            // Normal segments are drawn in the model's frame: scale their length back.
            let scale = model
                .transform
                .to_scale_rotation_translation()
                .0
                .max_element();
            let length = normal_length / if scale > 0.0 { scale } else { 1.0 };
            let from = morph_from.and_then(|m| m.get(i)).map(Vec::as_slice);
            let data = MeshData::build(model, length, from, layers);
            let has_coordinates = model.texcoords.is_some();
            let texture = model.texture.as_deref().filter(|_| has_coordinates);
            let binding = textures.binding(&mut uploader, texture, model.texture_repeat)?;
            let plain = textures.white(&mut uploader)?;
            meshes.push(upload_mesh(&mut uploader, model, &data, binding, plain)?);
        }
        uploader.finish()?;
        Ok(Self {
            meshes,
            bounds,
            vertex_count: scene.models.iter().map(Model::used_vertex_count).sum(),
            triangle_count: scene.triangle_count(),
            layers,
        })
    }
}

/// Uploads one model's lists; it draws with `texture`, or with `plain` when textures are off.
fn upload_mesh(
    up: &mut Uploader<'_>,
    model: &Model,
    data: &MeshData,
    texture: Binding,
    plain: vk::DescriptorSet,
) -> Result<GpuMesh> {
    let count = |n: usize, what: &str| {
        u32::try_from(n).map_err(|_| {
            RenderError::TooLarge(format!("{}: too many {what} to draw ({n})", model.name))
        })
    };
    let vertex = vk::BufferUsageFlags::VERTEX_BUFFER;
    let index = vk::BufferUsageFlags::INDEX_BUFFER;
    Ok(GpuMesh {
        transform: model.transform,
        texture: texture.set,
        plain,
        textured: texture.textured,
        vertices: up.upload("vertices", vertex, &data.vertices)?,
        triangles: up.upload("triangles", index, &data.triangles)?,
        triangle_indices: count(data.triangles.len(), "triangles")?,
        edges: up.upload("edges", index, &data.edges)?,
        edge_indices: count(data.edges.len(), "edges")?,
        points: up.upload("points", index, &data.points)?,
        point_count: count(data.points.len(), "points")?,
        face_normals: up.upload("face normals", vertex, &data.face_normals)?,
        face_normal_vertices: count(data.face_normals.len(), "face normals")?,
        vertex_normals: up.upload("vertex normals", vertex, &data.vertex_normals)?,
        vertex_normal_vertices: count(data.vertex_normals.len(), "vertex normals")?,
    })
}

/// World-space bounds of every model's positions (transforms applied to the box corners).
pub fn scene_bounds(scene: &Scene) -> Bounds {
    let mut all: Option<Bounds> = None;
    for model in &scene.models {
        let Some((lo, hi)) = model.bounds() else {
            continue;
        };
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            let p = model.transform.transform_point3(corner);
            let b = Bounds { min: p, max: p };
            all = Some(all.map_or(b, |a| a.union(b)));
        }
    }
    all.unwrap_or(Bounds {
        min: Vec3::splat(-1.0),
        max: Vec3::splat(1.0),
    })
}

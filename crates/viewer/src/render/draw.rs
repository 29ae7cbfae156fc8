//! Recording the draws of a frame: for each viewport, set its rectangle and camera, then draw
//! every model in each enabled mode (filled, edges, points, normals), grouped by pipeline.
//! Shared by the offscreen target and the window's swapchain.

use ash::vk;

use super::attachments::Attachments;
use super::camera::Camera;
use super::gpu_mesh::{GpuMesh, GpuScene};
use super::mesh_data::Layers;
use super::pipeline::{DrawMode, Pipelines, PushConstants};
use super::tiles::Rect;

/// Background of every viewport.
pub const BACKGROUND: [f32; 4] = [0.16, 0.18, 0.22, 1.0];
/// Colour between tiles.
pub const SEPARATOR: [f32; 4] = [0.05, 0.05, 0.06, 1.0];
/// Frame drawn around the current viewport in the interactive viewer.
pub const HIGHLIGHT: [f32; 4] = [0.95, 0.75, 0.2, 1.0];

/// What a viewport draws: the original's toggles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DrawOptions {
    pub triangles: bool,
    pub edges: bool,
    pub points: bool,
    pub face_normals: bool,
    pub vertex_normals: bool,
    pub lighting: bool,
    pub smooth: bool,
    /// Textured models drawn textured (else in their material colour).
    pub textures: bool,
    /// Decimated models coloured by their distance to the original (the error heat-map; the
    /// front end supplies the coloured copy, the original is drawn in neutral grey).
    pub error_map: bool,
}

impl Default for DrawOptions {
    fn default() -> Self {
        Self {
            triangles: true,
            edges: false,
            points: false,
            face_normals: false,
            vertex_normals: false,
            lighting: true,
            smooth: true,
            textures: true,
            error_map: false,
        }
    }
}

impl DrawOptions {
    /// The optional lists these options draw.
    pub fn layers(&self) -> Layers {
        Layers {
            edges: self.edges,
            points: self.points,
            face_normals: self.face_normals,
            vertex_normals: self.vertex_normals,
        }
    }

    /// The pipelines to run, in drawing order.
    pub fn modes(&self) -> Vec<DrawMode> {
        let mut modes = Vec::new();
        if self.triangles {
            modes.push(match (self.lighting, self.smooth) {
                (false, _) => DrawMode::FilledUnlit,
                (true, true) => DrawMode::FilledSmooth,
                (true, false) => DrawMode::FilledFlat,
            });
        }
        if self.edges {
            modes.push(if self.triangles {
                DrawMode::EdgesOverSurface
            } else {
                DrawMode::EdgesAlone
            });
        }
        if self.points {
            modes.push(DrawMode::Points);
        }
        if self.face_normals {
            modes.push(DrawMode::FaceNormals);
        }
        if self.vertex_normals {
            modes.push(DrawMode::VertexNormals);
        }
        modes
    }
}

/// One viewport of a frame.
pub struct ViewportDraw<'a> {
    pub rect: Rect,
    pub scene: &'a GpuScene,
    pub camera: &'a Camera,
    pub options: DrawOptions,
    /// Geomorph factor, 0 (at the vertices' `morph_from`) to 1 (at their positions).
    pub morph: f32,
}

/// Records the draws of `views` into `cmd`, inside an active dynamic rendering pass.
///
/// # Safety
/// `cmd` must be recording inside `vkCmdBeginRendering` with attachments of the pipelines'
/// formats, and every buffer of the scenes must stay alive until the commands have executed.
pub unsafe fn record(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    pipelines: &Pipelines,
    views: &[ViewportDraw<'_>],
) {
    for view in views {
        let r = view.rect;
        if r.width == 0 || r.height == 0 {
            continue;
        }
        let viewport = vk::Viewport {
            x: r.x as f32,
            y: r.y as f32,
            width: r.width as f32,
            height: r.height as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        };
        let scissor = vk::Rect2D {
            offset: vk::Offset2D {
                x: r.x as i32,
                y: r.y as i32,
            },
            extent: vk::Extent2D {
                width: r.width,
                height: r.height,
            },
        };
        // SAFETY (for the block): the caller guarantees `cmd` is recording inside rendering.
        unsafe {
            device.cmd_set_viewport(cmd, 0, &[viewport]);
            device.cmd_set_scissor(cmd, 0, &[scissor]);
        }
        let view_matrix = view.camera.view();
        let clip_from_view = view.camera.projection(r.aspect());
        for mode in view.options.modes() {
            // SAFETY: as above; the pipeline was created for this rendering's formats.
            unsafe {
                device.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::GRAPHICS, pipelines.get(mode))
            };
            for mesh in &view.scene.meshes {
                let view_from_model = view_matrix * mesh.transform;
                let textured = view.options.textures && mesh.textured;
                let push = PushConstants::new(
                    clip_from_view * view_from_model,
                    view_from_model,
                    view.morph,
                    textured,
                );
                let set = if textured { mesh.texture } else { mesh.plain };
                // SAFETY: `PushConstants` is plain `repr(C)` floats, exactly the layout's range.
                unsafe {
                    let bytes = std::slice::from_raw_parts(
                        std::ptr::from_ref(&push).cast::<u8>(),
                        size_of::<PushConstants>(),
                    );
                    device.cmd_push_constants(
                        cmd,
                        pipelines.layout,
                        vk::ShaderStageFlags::VERTEX,
                        0,
                        bytes,
                    );
                    device.cmd_bind_descriptor_sets(
                        cmd,
                        vk::PipelineBindPoint::GRAPHICS,
                        pipelines.layout,
                        0,
                        &[set],
                        &[],
                    );
                    draw_mesh(device, cmd, mesh, mode);
                }
            }
        }
    }
}

/// # Safety
/// As for [`record`], with the pipeline of `mode` bound.
unsafe fn draw_mesh(device: &ash::Device, cmd: vk::CommandBuffer, mesh: &GpuMesh, mode: DrawMode) {
    let indexed = |index: &super::buffer::Buffer, count: u32| {
        if count == 0 {
            return;
        }
        // SAFETY: the caller guarantees a recording command buffer and live buffers.
        unsafe {
            device.cmd_bind_vertex_buffers(cmd, 0, &[mesh.vertices.handle], &[0]);
            device.cmd_bind_index_buffer(cmd, index.handle, 0, vk::IndexType::UINT32);
            device.cmd_draw_indexed(cmd, count, 1, 0, 0, 0);
        }
    };
    let lines = |vertices: &super::buffer::Buffer, count: u32| {
        if count == 0 {
            return;
        }
        // SAFETY: as above.
        unsafe {
            device.cmd_bind_vertex_buffers(cmd, 0, &[vertices.handle], &[0]);
            device.cmd_draw(cmd, count, 1, 0, 0);
        }
    };
    match mode {
        DrawMode::FilledSmooth | DrawMode::FilledFlat | DrawMode::FilledUnlit => {
            indexed(&mesh.triangles, mesh.triangle_indices)
        }
        DrawMode::EdgesOverSurface | DrawMode::EdgesAlone => {
            indexed(&mesh.edges, mesh.edge_indices)
        }
        DrawMode::Points => indexed(&mesh.points, mesh.point_count),
        DrawMode::FaceNormals => lines(&mesh.face_normals, mesh.face_normal_vertices),
        DrawMode::VertexNormals => lines(&mesh.vertex_normals, mesh.vertex_normal_vertices),
    }
}

/// Begins dynamic rendering into `target` for the viewports `rects`: the pass's own clear
/// gives the separator colour between them (or the background, when one viewport fills the
/// picture), then each viewport is cleared to the background and the `highlighted` one's
/// border to the highlight colour. Every full-size clear costs a pass over every sample, so
/// none is made twice.
///
/// # Safety
/// `cmd` must be recording outside rendering; the views must be in attachment layouts.
pub unsafe fn begin_tiles(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    target: Attachments,
    extent: vk::Extent2D,
    rects: &[Rect],
    highlighted: Option<usize>,
    background: [f32; 4],
) {
    let whole = Rect {
        x: 0,
        y: 0,
        width: extent.width,
        height: extent.height,
    };
    let one_full_tile = rects == [whole] && highlighted.is_none();
    let load = if one_full_tile { background } else { SEPARATOR };
    // SAFETY: guaranteed by the caller; the pass begun here is the one the tiles clear.
    unsafe {
        begin_rendering(device, cmd, target, extent, load);
        if !one_full_tile {
            clear_tiles(device, cmd, rects, highlighted, background);
        }
    }
}

/// Clears each viewport to `background` (and the `highlighted` one's border to the
/// highlight colour).
///
/// # Safety
/// `cmd` must be recording inside `vkCmdBeginRendering` with colour attachment 0 covering
/// every rectangle.
unsafe fn clear_tiles(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    rects: &[Rect],
    highlighted: Option<usize>,
    background: [f32; 4],
) {
    let clear = |rect: vk::Rect2D, color: [f32; 4]| {
        if rect.extent.width == 0 || rect.extent.height == 0 {
            return;
        }
        let attachments = [vk::ClearAttachment {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            color_attachment: 0,
            clear_value: vk::ClearValue {
                color: vk::ClearColorValue { float32: color },
            },
        }];
        let rects = [vk::ClearRect {
            rect,
            base_array_layer: 0,
            layer_count: 1,
        }];
        // SAFETY: the caller guarantees an active rendering pass covering `rect`.
        unsafe { device.cmd_clear_attachments(cmd, &attachments, &rects) };
    };
    let to_vk = |r: Rect, inset: u32| vk::Rect2D {
        offset: vk::Offset2D {
            x: (r.x + inset) as i32,
            y: (r.y + inset) as i32,
        },
        extent: vk::Extent2D {
            width: r.width.saturating_sub(2 * inset),
            height: r.height.saturating_sub(2 * inset),
        },
    };
    for (i, &r) in rects.iter().enumerate() {
        if highlighted == Some(i) {
            clear(to_vk(r, 0), HIGHLIGHT);
            clear(to_vk(r, 2), background);
        } else {
            clear(to_vk(r, 0), background);
        }
    }
}

/// Begins dynamic rendering into `target` (colour cleared to `clear`, depth to 1).
///
/// # Safety
/// `cmd` must be recording outside rendering; the views must be in attachment layouts.
pub unsafe fn begin_rendering(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    target: Attachments,
    extent: vk::Extent2D,
    clear: [f32; 4],
) {
    let color = vk::RenderingAttachmentInfo::default()
        .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
        .load_op(vk::AttachmentLoadOp::CLEAR)
        .clear_value(vk::ClearValue {
            color: vk::ClearColorValue { float32: clear },
        });
    let color = match target.multisampled {
        // The samples are only needed until they are averaged into the picture.
        Some(samples) => color
            .image_view(samples)
            .store_op(vk::AttachmentStoreOp::DONT_CARE)
            .resolve_mode(vk::ResolveModeFlags::AVERAGE)
            .resolve_image_view(target.color)
            .resolve_image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL),
        None => color
            .image_view(target.color)
            .store_op(vk::AttachmentStoreOp::STORE),
    };
    let color_attachments = [color];
    let depth = target.depth;
    let depth_attachment = vk::RenderingAttachmentInfo::default()
        .image_view(depth)
        .image_layout(vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL)
        .load_op(vk::AttachmentLoadOp::CLEAR)
        .store_op(vk::AttachmentStoreOp::DONT_CARE)
        .clear_value(vk::ClearValue {
            depth_stencil: vk::ClearDepthStencilValue {
                depth: 1.0,
                stencil: 0,
            },
        });
    let info = vk::RenderingInfo::default()
        .render_area(vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent,
        })
        .layer_count(1)
        .color_attachments(&color_attachments)
        .depth_attachment(&depth_attachment);
    // SAFETY: guaranteed by the caller.
    unsafe { device.cmd_begin_rendering(cmd, &info) };
}

/// Begins a colour-only pass that keeps what was drawn (for the UI).
///
/// # Safety
/// `cmd` must be recording outside rendering, `view` in the colour-attachment layout.
pub unsafe fn begin_overlay(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    view: vk::ImageView,
    extent: vk::Extent2D,
) {
    let color = [vk::RenderingAttachmentInfo::default()
        .image_view(view)
        .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
        .load_op(vk::AttachmentLoadOp::LOAD)
        .store_op(vk::AttachmentStoreOp::STORE)];
    let info = vk::RenderingInfo::default()
        .render_area(vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent,
        })
        .layer_count(1)
        .color_attachments(&color);
    // SAFETY: guaranteed by the caller.
    unsafe { device.cmd_begin_rendering(cmd, &info) };
}

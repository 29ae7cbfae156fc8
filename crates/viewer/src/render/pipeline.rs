//! `Pipelines`: one graphics pipeline per draw mode (filled lit smooth / lit flat / unlit,
//! edges, points, face normals, vertex normals) over one vertex layout, one push-constant
//! layout and one descriptor set (the model's texture, `render::texture`), for a given colour format (dynamic rendering, no render pass). Each mode is the
//! same two shaders with different specialization constants and topology. Every pipeline
//! draws with one sample count (multisample anti-aliasing), changed by [`Pipelines::set_samples`].

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::Result;
use super::image::DEPTH_FORMAT;
use super::mesh_data::Vertex;
use super::shader::{ShaderModule, MESH_FRAG, MESH_VERT};

/// What one pipeline draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DrawMode {
    /// Triangles lit with interpolated vertex normals.
    FilledSmooth,
    /// Triangles lit with their face normal.
    FilledFlat,
    /// Triangles in their colour, no lighting.
    FilledUnlit,
    /// Unique edges over filled triangles (dark).
    EdgesOverSurface,
    /// Unique edges alone (light).
    EdgesAlone,
    /// Vertices as points.
    Points,
    /// Face-normal segments.
    FaceNormals,
    /// Vertex-normal segments.
    VertexNormals,
}

impl DrawMode {
    pub const ALL: [Self; 8] = [
        Self::FilledSmooth,
        Self::FilledFlat,
        Self::FilledUnlit,
        Self::EdgesOverSurface,
        Self::EdgesAlone,
        Self::Points,
        Self::FaceNormals,
        Self::VertexNormals,
    ];

    fn topology(self) -> vk::PrimitiveTopology {
        match self {
            Self::FilledSmooth | Self::FilledFlat | Self::FilledUnlit => {
                vk::PrimitiveTopology::TRIANGLE_LIST
            }
            Self::Points => vk::PrimitiveTopology::POINT_LIST,
            _ => vk::PrimitiveTopology::LINE_LIST,
        }
    }

    /// Shading (fragment shader `SHADING`) and constant colour.
    fn shading(self) -> (i32, [f32; 3]) {
        match self {
            Self::FilledSmooth => (0, [0.0; 3]),
            Self::FilledFlat => (1, [0.0; 3]),
            Self::FilledUnlit => (2, [0.0; 3]),
            Self::EdgesOverSurface => (3, [0.05, 0.05, 0.08]),
            Self::EdgesAlone => (3, [0.85, 0.88, 0.95]),
            Self::Points => (3, [1.0, 0.65, 0.1]),
            Self::FaceNormals => (3, [0.2, 0.8, 1.0]),
            Self::VertexNormals => (3, [1.0, 0.35, 0.7]),
        }
    }

    /// Fraction of the depth range overlays are pulled towards the eye.
    fn depth_nudge(self) -> f32 {
        match self {
            Self::FilledSmooth | Self::FilledFlat | Self::FilledUnlit => 0.0,
            Self::Points => 4e-4,
            _ => 2e-4,
        }
    }
}

/// Per-draw constants: 128 bytes, the minimum every device guarantees.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct PushConstants {
    pub clip_from_model: [f32; 16],
    /// The top three rows of the (affine) view-from-model matrix: GLSL's `mat3x4`, so that
    /// the geomorph factor fits in lavapipe's 128 bytes of push constants.
    pub view_rows: [f32; 12],
    /// Geomorph factor: vertices are drawn at `mix(morph_from, position, morph)`.
    pub morph: f32,
    /// 1 when the bound texture replaces the vertex colour, 0 when it is the white stand-in.
    pub textured: f32,
    pub _pad: [f32; 2],
}

impl PushConstants {
    pub fn new(
        clip_from_model: glam::Mat4,
        view_from_model: glam::Mat4,
        morph: f32,
        textured: bool,
    ) -> Self {
        let t = view_from_model.transpose();
        let mut view_rows = [0.0; 12];
        view_rows[0..4].copy_from_slice(&t.x_axis.to_array());
        view_rows[4..8].copy_from_slice(&t.y_axis.to_array());
        view_rows[8..12].copy_from_slice(&t.z_axis.to_array());
        Self {
            clip_from_model: clip_from_model.to_cols_array(),
            view_rows,
            morph,
            textured: f32::from(u8::from(textured)),
            _pad: [0.0; 2],
        }
    }
}

/// Filled triangles' depth bias: (constant in depth-buffer units, times the depth slope), the
/// usual polygon offset of a wireframe over its surface.
const FILL_DEPTH_BIAS: (f32, f32) = (1.0, 1.5);

/// Point size asked for; clamped to the device's range (1 px without `largePoints`).
pub const POINT_SIZE: f32 = 5.0;

/// The pipelines of every draw mode and their shared layout.
pub struct Pipelines {
    context: Arc<Context>,
    pub layout: vk::PipelineLayout,
    /// Set 0: binding 0, the model's texture (a combined image sampler, fragment stage).
    pub texture_layout: vk::DescriptorSetLayout,
    pipelines: Vec<(DrawMode, vk::Pipeline)>,
    pub color_format: vk::Format,
    /// Samples per pixel of the targets these pipelines draw into.
    pub samples: vk::SampleCountFlags,
}

/// Samples per pixel asked for by default: 4× anti-aliasing, which every desktop GPU and
/// lavapipe offer (docs/design.md#msaa).
pub const DEFAULT_MSAA: u32 = 4;

impl Pipelines {
    /// Single-sampled pipelines (no anti-aliasing) drawing into `color_format`.
    pub fn new(context: &Arc<Context>, color_format: vk::Format) -> Result<Self> {
        Self::with_samples(context, color_format, 1)
    }

    /// Pipelines drawing with the most samples per pixel, at most `msaa`, that the device
    /// offers (1: no anti-aliasing); their targets need [`Self::samples`] samples.
    pub fn with_samples(
        context: &Arc<Context>,
        color_format: vk::Format,
        msaa: u32,
    ) -> Result<Self> {
        let device = &context.device;
        let ranges = [vk::PushConstantRange::default()
            .stage_flags(vk::ShaderStageFlags::VERTEX)
            .size(size_of::<PushConstants>() as u32)];
        let bindings = [vk::DescriptorSetLayoutBinding::default()
            .binding(0)
            .descriptor_type(vk::DescriptorType::COMBINED_IMAGE_SAMPLER)
            .descriptor_count(1)
            .stage_flags(vk::ShaderStageFlags::FRAGMENT)];
        let set_info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
        // SAFETY: valid create info on a live device.
        let texture_layout = unsafe { device.create_descriptor_set_layout(&set_info, None)? };
        let set_layouts = [texture_layout];
        let layout_info = vk::PipelineLayoutCreateInfo::default()
            .set_layouts(&set_layouts)
            .push_constant_ranges(&ranges);
        // SAFETY: valid create info on a live device.
        let layout = match unsafe { device.create_pipeline_layout(&layout_info, None) } {
            Ok(layout) => layout,
            Err(e) => {
                // SAFETY: the set layout was just created and nothing uses it.
                unsafe { device.destroy_descriptor_set_layout(texture_layout, None) };
                return Err(e.into());
            }
        };
        let mut this = Self {
            context: context.clone(),
            layout,
            texture_layout,
            pipelines: Vec::new(),
            color_format,
            samples: context.capabilities.samples(msaa),
        };
        if !context.capabilities.large_points {
            eprintln!(
                "decimate: {} has no largePoints: points are drawn 1 pixel wide",
                context.device_name
            );
        }
        this.create_all()?;
        Ok(this)
    }

    /// Makes the pipelines again for at most `msaa` samples per pixel (the layouts, and so the
    /// textures' descriptor sets, stay); nothing is done when the count is unchanged. The
    /// caller waits for the GPU first.
    pub fn set_samples(&mut self, msaa: u32) -> Result<()> {
        let samples = self.context.capabilities.samples(msaa);
        if samples == self.samples {
            return Ok(());
        }
        self.destroy_pipelines();
        self.samples = samples;
        self.create_all()
    }

    fn create_all(&mut self) -> Result<()> {
        let vert = ShaderModule::new(&self.context, MESH_VERT)?;
        let frag = ShaderModule::new(&self.context, MESH_FRAG)?;
        for mode in DrawMode::ALL {
            let pipeline = self.create(mode, &vert, &frag)?;
            self.pipelines.push((mode, pipeline));
        }
        Ok(())
    }

    fn destroy_pipelines(&mut self) {
        for (_, p) in self.pipelines.drain(..) {
            // SAFETY: the caller waited for the GPU, so no command buffer uses the pipeline.
            unsafe { self.context.device.destroy_pipeline(p, None) };
        }
    }

    /// The pipeline of `mode`.
    pub fn get(&self, mode: DrawMode) -> vk::Pipeline {
        self.pipelines
            .iter()
            .find(|(m, _)| *m == mode)
            .map_or(vk::Pipeline::null(), |(_, p)| *p)
    }

    fn create(
        &self,
        mode: DrawMode,
        vert: &ShaderModule,
        frag: &ShaderModule,
    ) -> Result<vk::Pipeline> {
        let data = specialization_data(mode, self.context.capabilities.point_size(POINT_SIZE));
        let entries = SPECIALIZATION_ENTRIES.map(|id| {
            vk::SpecializationMapEntry::default()
                .constant_id(id)
                .offset(id * 4)
                .size(4)
        });
        let specialization = vk::SpecializationInfo::default()
            .map_entries(&entries)
            .data(&data);
        let stage = |stage, module: &ShaderModule| {
            vk::PipelineShaderStageCreateInfo::default()
                .stage(stage)
                .module(module.handle)
                .name(c"main")
                .specialization_info(&specialization)
        };
        let stages = [
            stage(vk::ShaderStageFlags::VERTEX, vert),
            stage(vk::ShaderStageFlags::FRAGMENT, frag),
        ];
        let bindings = [vk::VertexInputBindingDescription::default()
            .binding(0)
            .stride(size_of::<Vertex>() as u32)
            .input_rate(vk::VertexInputRate::VERTEX)];
        let attributes = vertex_attributes();
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(&bindings)
            .vertex_attribute_descriptions(&attributes);
        let input_assembly =
            vk::PipelineInputAssemblyStateCreateInfo::default().topology(mode.topology());
        let viewport = vk::PipelineViewportStateCreateInfo::default()
            .viewport_count(1)
            .scissor_count(1);
        let rasterization = rasterization(mode);
        let multisample =
            vk::PipelineMultisampleStateCreateInfo::default().rasterization_samples(self.samples);
        let depth = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(true)
            .depth_write_enable(true)
            .depth_compare_op(vk::CompareOp::LESS_OR_EQUAL);
        let blend_attachments = [vk::PipelineColorBlendAttachmentState::default()
            .color_write_mask(vk::ColorComponentFlags::RGBA)];
        let blend =
            vk::PipelineColorBlendStateCreateInfo::default().attachments(&blend_attachments);
        let dynamic_states = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
        let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic_states);
        let color_formats = [self.color_format];
        let mut rendering = vk::PipelineRenderingCreateInfo::default()
            .color_attachment_formats(&color_formats)
            .depth_attachment_format(DEPTH_FORMAT);
        let info = vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&input_assembly)
            .viewport_state(&viewport)
            .rasterization_state(&rasterization)
            .multisample_state(&multisample)
            .depth_stencil_state(&depth)
            .color_blend_state(&blend)
            .dynamic_state(&dynamic)
            .layout(self.layout)
            .push_next(&mut rendering);
        // SAFETY: every state struct and the specialization data outlive the call; the layout
        // and shader modules are alive.
        let pipelines = unsafe {
            self.context
                .device
                .create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
        };
        self.first_or_destroy(pipelines)
    }

    /// The one pipeline of a batch of one, or the batch's error (with whatever it made
    /// destroyed).
    fn first_or_destroy(
        &self,
        pipelines: std::result::Result<Vec<vk::Pipeline>, (Vec<vk::Pipeline>, vk::Result)>,
    ) -> Result<vk::Pipeline> {
        match pipelines {
            Ok(p) => Ok(p[0]),
            Err((created, e)) => {
                for p in created {
                    // SAFETY: pipelines returned by a failed batch are not in use.
                    unsafe { self.context.device.destroy_pipeline(p, None) };
                }
                Err(e.into())
            }
        }
    }
}

/// The ids of the shaders' specialization constants, 4 bytes each.
const SPECIALIZATION_ENTRIES: [u32; 7] = [0, 1, 2, 3, 4, 5, 6];

/// The shaders' specialization constants for `mode`, ids 0..=6 in the order the shaders
/// declare them: depth nudge, point size, shading, colour (3), round points.
fn specialization_data(mode: DrawMode, point_size: f32) -> Vec<u8> {
    let (shading, colour) = mode.shading();
    let mut data = Vec::with_capacity(28);
    data.extend_from_slice(&mode.depth_nudge().to_ne_bytes());
    data.extend_from_slice(&point_size.to_ne_bytes());
    data.extend_from_slice(&shading.to_ne_bytes());
    for c in colour {
        data.extend_from_slice(&c.to_ne_bytes());
    }
    let round_points = vk::Bool32::from(mode == DrawMode::Points && point_size > 2.0);
    data.extend_from_slice(&round_points.to_ne_bytes());
    data
}

/// `Vertex`'s fields as the vertex shader reads them: position, normal, colour (RGBA8),
/// morph origin, texture coordinates.
fn vertex_attributes() -> [vk::VertexInputAttributeDescription; 5] {
    let attribute = |location: u32, format: vk::Format, offset: u32| {
        vk::VertexInputAttributeDescription::default()
            .location(location)
            .format(format)
            .offset(offset)
    };
    [
        attribute(0, vk::Format::R32G32B32_SFLOAT, 0),
        attribute(1, vk::Format::R32G32B32_SFLOAT, 12),
        attribute(2, vk::Format::R8G8B8A8_UNORM, 24),
        attribute(3, vk::Format::R32G32B32_SFLOAT, 28),
        attribute(4, vk::Format::R32G32_SFLOAT, 40),
    ]
}

/// Two-sided: open meshes show their back faces, lit by the flipped normal. Filled
/// triangles are pushed back by their depth slope (polygon offset), so edges and points
/// drawn over a surface seen at a grazing angle are not dashed by it.
fn rasterization(mode: DrawMode) -> vk::PipelineRasterizationStateCreateInfo<'static> {
    let filled = mode.topology() == vk::PrimitiveTopology::TRIANGLE_LIST;
    vk::PipelineRasterizationStateCreateInfo::default()
        .polygon_mode(vk::PolygonMode::FILL)
        .cull_mode(vk::CullModeFlags::NONE)
        .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
        .depth_bias_enable(filled)
        .depth_bias_constant_factor(FILL_DEPTH_BIAS.0)
        .depth_bias_slope_factor(FILL_DEPTH_BIAS.1)
        .line_width(1.0)
}

impl Drop for Pipelines {
    fn drop(&mut self) {
        // Owners wait for the GPU before dropping; pipelines go before their layout.
        self.destroy_pipelines();
        // SAFETY: as above; nothing uses the layouts any more.
        unsafe {
            self.context
                .device
                .destroy_pipeline_layout(self.layout, None);
            self.context
                .device
                .destroy_descriptor_set_layout(self.texture_layout, None);
        }
    }
}

//! `OffscreenTarget`: a colour + depth target with no window (multisampled and resolved into
//! the colour image when anti-aliased), rendered with the same pipelines and draw code as the
//! viewer and read back to RGBA8 rows — the `shot` action, the
//! golden-image tests and the frame-time benchmark.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::attachments::DrawImages;
use super::buffer::Buffer;
use super::commands::Commands;
use super::context::Context;
use super::draw::{self, ViewportDraw};
use super::error::{RenderError, Result};
use super::image::{self, Image, Transition};
use super::pipeline::Pipelines;
pub use decimate_core::mesh::rgba_image::RgbaImage;

/// Colour format of offscreen images (8-bit RGBA, written to PNG as is).
pub const OFFSCREEN_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

/// An offscreen colour and depth target with its readback buffer.
pub struct OffscreenTarget {
    context: Arc<Context>,
    color: Image,
    /// Depth and, when anti-aliased, the multisampled colour image.
    images: DrawImages,
    readback: Buffer,
    pub extent: vk::Extent2D,
    /// What the viewports are cleared to (`draw::BACKGROUND` unless set).
    pub background: [f32; 4],
}

impl OffscreenTarget {
    /// A single-sampled target, for single-sampled pipelines ([`Pipelines::new`]).
    pub fn new(context: &Arc<Context>, width: u32, height: u32) -> Result<Self> {
        Self::with_samples(context, width, height, vk::SampleCountFlags::TYPE_1)
    }

    /// A target drawn with `samples` samples per pixel: those of the pipelines that draw
    /// into it ([`Pipelines::samples`]).
    pub fn with_samples(
        context: &Arc<Context>,
        width: u32,
        height: u32,
        samples: vk::SampleCountFlags,
    ) -> Result<Self> {
        let extent = vk::Extent2D { width, height };
        let bytes = u64::from(width) * u64::from(height) * 4;
        if width == 0 || height == 0 || bytes > 1 << 30 {
            return Err(RenderError::TooLarge(format!(
                "image size {width}x{height} is not drawable"
            )));
        }
        let color = Image::new(
            context,
            "offscreen colour",
            OFFSCREEN_FORMAT,
            extent,
            vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC,
        )?;
        let images = DrawImages::new(context, "offscreen", OFFSCREEN_FORMAT, extent, samples)?;
        let readback = Buffer::new(
            context,
            "readback",
            bytes,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuToCpu,
        )?;
        Ok(Self {
            context: context.clone(),
            color,
            images,
            readback,
            extent,
            background: draw::BACKGROUND,
        })
    }

    /// Draws `views` (tiles cleared first, none highlighted) and waits for the GPU. With
    /// `read_back` the picture is copied out and returned.
    pub fn render(
        &self,
        commands: &Commands,
        pipelines: &Pipelines,
        views: &[ViewportDraw<'_>],
        read_back: bool,
    ) -> Result<Option<RgbaImage>> {
        self.render_with_overlay(commands, pipelines, views, read_back, None)
    }

    /// As [`Self::render`], then `overlay` records into a colour-only pass over the picture
    /// (of [`OFFSCREEN_FORMAT`], no depth): captions drawn over the viewports.
    pub fn render_with_overlay(
        &self,
        commands: &Commands,
        pipelines: &Pipelines,
        views: &[ViewportDraw<'_>],
        read_back: bool,
        overlay: Option<&mut dyn FnMut(vk::CommandBuffer) -> Result<()>>,
    ) -> Result<Option<RgbaImage>> {
        if pipelines.samples != self.images.samples {
            return Err(RenderError::SampleCount(format!(
                "pipelines of {} samples per pixel cannot draw into a target of {}",
                pipelines.samples.as_raw(),
                self.images.samples.as_raw()
            )));
        }
        let device = &self.context.device;
        let cmd = commands.begin()?;
        let rects: Vec<_> = views.iter().map(|v| v.rect).collect();
        // SAFETY: `cmd` is recording; the images, the pipelines and the scenes' buffers stay
        // alive until `submit_and_wait` returns.
        unsafe {
            image::transition(
                device,
                cmd,
                self.color.handle,
                OFFSCREEN_FORMAT,
                image::TO_COLOR_ATTACHMENT,
            );
            self.images.to_attachments(device, cmd);
            let target = self.images.attachments(self.color.view);
            draw::begin_tiles(
                device,
                cmd,
                target,
                self.extent,
                &rects,
                None,
                self.background,
            );
            draw::record(device, cmd, pipelines, views);
            device.cmd_end_rendering(cmd);
        }
        if let Some(overlay) = overlay {
            // SAFETY: `cmd` is recording outside rendering, the colour image in the
            // colour-attachment layout; the pass opened here is closed right after.
            unsafe { draw::begin_overlay(device, cmd, self.color.view, self.extent) };
            let recorded = overlay(cmd);
            // SAFETY: as above; the pass must end even when the overlay failed.
            unsafe { device.cmd_end_rendering(cmd) };
            recorded?;
        }
        if read_back {
            // SAFETY: `cmd` is recording outside rendering, after the colour image was drawn.
            unsafe { self.record_readback(cmd) };
        }
        commands.submit_and_wait()?;
        if !read_back {
            return Ok(None);
        }
        Ok(Some(RgbaImage {
            width: self.extent.width,
            height: self.extent.height,
            pixels: self.readback.mapped()?.to_vec(),
        }))
    }

    /// # Safety
    /// `cmd` must be recording, after the colour image was drawn, outside rendering.
    unsafe fn record_readback(&self, cmd: vk::CommandBuffer) {
        let device = &self.context.device;
        let to_transfer = Transition {
            old: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            new: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            src_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
            src_access: vk::AccessFlags2::COLOR_ATTACHMENT_WRITE,
            dst_stage: vk::PipelineStageFlags2::COPY,
            dst_access: vk::AccessFlags2::TRANSFER_READ,
        };
        let region = [vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: vk::ImageAspectFlags::COLOR,
                mip_level: 0,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(vk::Extent3D {
                width: self.extent.width,
                height: self.extent.height,
                depth: 1,
            })];
        let to_host = [vk::MemoryBarrier2::default()
            .src_stage_mask(vk::PipelineStageFlags2::COPY)
            .src_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
            .dst_stage_mask(vk::PipelineStageFlags2::HOST)
            .dst_access_mask(vk::AccessFlags2::HOST_READ)];
        // SAFETY: guaranteed by the caller; the buffer holds width × height × 4 bytes.
        unsafe {
            image::transition(
                device,
                cmd,
                self.color.handle,
                OFFSCREEN_FORMAT,
                to_transfer,
            );
            device.cmd_copy_image_to_buffer(
                cmd,
                self.color.handle,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                self.readback.handle,
                &region,
            );
            device.cmd_pipeline_barrier2(
                cmd,
                &vk::DependencyInfo::default().memory_barriers(&to_host),
            );
        }
    }
}

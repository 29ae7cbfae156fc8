//! `Image`: a 2D `vk::Image` with one view and its gpu-allocator memory (a colour or depth
//! attachment, or a sampled texture with its mip levels), freed in `Drop`.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::Allocation;
use gpu_allocator::MemoryLocation;

use super::context::Context;
use super::error::Result;

/// Depth format used by every target: supported for attachments by every Vulkan 1.3 device
/// the renderer accepts in practice (lavapipe, Mesa, NVIDIA, AMD).
pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;

/// An image, its view and its memory.
pub struct Image {
    context: Arc<Context>,
    pub handle: vk::Image,
    pub view: vk::ImageView,
    pub format: vk::Format,
    pub extent: vk::Extent2D,
    allocation: Option<Allocation>,
}

impl Image {
    /// A device-local 2D image of `format` for `usage`; the aspect follows from the format.
    pub fn new(
        context: &Arc<Context>,
        name: &str,
        format: vk::Format,
        extent: vk::Extent2D,
        usage: vk::ImageUsageFlags,
    ) -> Result<Self> {
        Self::with_levels(context, name, format, extent, usage, 1)
    }

    /// A device-local attachment of `samples` samples per pixel (a multisampled colour or
    /// depth target, resolved or discarded at the end of the pass).
    pub fn multisampled(
        context: &Arc<Context>,
        name: &str,
        format: vk::Format,
        extent: vk::Extent2D,
        usage: vk::ImageUsageFlags,
        samples: vk::SampleCountFlags,
    ) -> Result<Self> {
        Self::create(context, name, format, extent, usage, 1, samples)
    }

    /// As [`Self::new`], with `levels` mip levels (at least one), all in its view.
    pub fn with_levels(
        context: &Arc<Context>,
        name: &str,
        format: vk::Format,
        extent: vk::Extent2D,
        usage: vk::ImageUsageFlags,
        levels: u32,
    ) -> Result<Self> {
        Self::create(
            context,
            name,
            format,
            extent,
            usage,
            levels,
            vk::SampleCountFlags::TYPE_1,
        )
    }

    fn create(
        context: &Arc<Context>,
        name: &str,
        format: vk::Format,
        extent: vk::Extent2D,
        usage: vk::ImageUsageFlags,
        levels: u32,
        samples: vk::SampleCountFlags,
    ) -> Result<Self> {
        let device = &context.device;
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(format)
            .extent(vk::Extent3D {
                width: extent.width.max(1),
                height: extent.height.max(1),
                depth: 1,
            })
            .mip_levels(levels.max(1))
            .array_layers(1)
            .samples(samples)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: valid create info on a live device.
        let handle = unsafe { device.create_image(&info, None)? };
        let mut image = Self {
            context: context.clone(),
            handle,
            view: vk::ImageView::null(),
            format,
            extent,
            allocation: None,
        };
        // SAFETY: `handle` was just created on this device.
        let requirements = unsafe { device.get_image_memory_requirements(handle) };
        let allocation = context.allocate(name, requirements, MemoryLocation::GpuOnly, false)?;
        // SAFETY: the allocation satisfies the image's requirements and is bound only here.
        let bound =
            unsafe { device.bind_image_memory(handle, allocation.memory(), allocation.offset()) };
        image.allocation = Some(allocation);
        bound?;
        let view_info = vk::ImageViewCreateInfo::default()
            .image(handle)
            .view_type(vk::ImageViewType::TYPE_2D)
            .format(format)
            .subresource_range(subresource_range(format));
        // SAFETY: the image is bound to memory and the view matches its format.
        image.view = unsafe { device.create_image_view(&view_info, None)? };
        Ok(image)
    }
}

/// The whole image (every mip level), with the aspect its format implies.
pub fn subresource_range(format: vk::Format) -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange::default()
        .aspect_mask(aspect(format))
        .level_count(vk::REMAINING_MIP_LEVELS)
        .layer_count(1)
}

/// Depth aspect for depth formats, colour otherwise.
pub fn aspect(format: vk::Format) -> vk::ImageAspectFlags {
    match format {
        vk::Format::D32_SFLOAT | vk::Format::D16_UNORM => vk::ImageAspectFlags::DEPTH,
        _ => vk::ImageAspectFlags::COLOR,
    }
}

impl Drop for Image {
    fn drop(&mut self) {
        // SAFETY: owners wait for the GPU before dropping attachments; the view goes before the
        // image and the image before its memory. Destroying a null view is a no-op.
        unsafe {
            self.context.device.destroy_image_view(self.view, None);
            self.context.device.destroy_image(self.handle, None);
        }
        if let Some(allocation) = self.allocation.take() {
            self.context.free(allocation);
        }
    }
}

/// One layout transition of a whole image, with the stages and accesses it orders.
#[derive(Debug, Clone, Copy)]
pub struct Transition {
    pub old: vk::ImageLayout,
    pub new: vk::ImageLayout,
    pub src_stage: vk::PipelineStageFlags2,
    pub src_access: vk::AccessFlags2,
    pub dst_stage: vk::PipelineStageFlags2,
    pub dst_access: vk::AccessFlags2,
}

/// Records `t` for `image` (of `format`) into `cmd`.
///
/// # Safety
/// `cmd` must be recording and `image` alive until the commands have executed.
pub unsafe fn transition(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    image: vk::Image,
    format: vk::Format,
    t: Transition,
) {
    let barrier = [vk::ImageMemoryBarrier2::default()
        .image(image)
        .subresource_range(subresource_range(format))
        .old_layout(t.old)
        .new_layout(t.new)
        .src_stage_mask(t.src_stage)
        .src_access_mask(t.src_access)
        .dst_stage_mask(t.dst_stage)
        .dst_access_mask(t.dst_access)];
    let dependency = vk::DependencyInfo::default().image_memory_barriers(&barrier);
    // SAFETY: guaranteed by the caller.
    unsafe { device.cmd_pipeline_barrier2(cmd, &dependency) };
}

/// Colour attachment from "anything, contents discarded" to drawable.
pub const TO_COLOR_ATTACHMENT: Transition = Transition {
    old: vk::ImageLayout::UNDEFINED,
    new: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
    src_access: vk::AccessFlags2::NONE,
    dst_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
    dst_access: vk::AccessFlags2::COLOR_ATTACHMENT_WRITE,
};

/// Depth attachment from "contents discarded" to drawable.
pub const TO_DEPTH_ATTACHMENT: Transition = Transition {
    old: vk::ImageLayout::UNDEFINED,
    new: vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::LATE_FRAGMENT_TESTS,
    src_access: vk::AccessFlags2::DEPTH_STENCIL_ATTACHMENT_WRITE,
    dst_stage: vk::PipelineStageFlags2::EARLY_FRAGMENT_TESTS,
    dst_access: vk::AccessFlags2::from_raw(
        vk::AccessFlags2::DEPTH_STENCIL_ATTACHMENT_WRITE.as_raw()
            | vk::AccessFlags2::DEPTH_STENCIL_ATTACHMENT_READ.as_raw(),
    ),
};

/// A texture from freshly written by a copy to sampled by fragment shaders.
pub const COPIED_TO_SAMPLED: Transition = Transition {
    old: vk::ImageLayout::TRANSFER_DST_OPTIMAL,
    new: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::COPY,
    src_access: vk::AccessFlags2::TRANSFER_WRITE,
    dst_stage: vk::PipelineStageFlags2::FRAGMENT_SHADER,
    dst_access: vk::AccessFlags2::SHADER_SAMPLED_READ,
};

/// A new image (contents undefined) to the destination of a copy.
pub const TO_COPY_DESTINATION: Transition = Transition {
    old: vk::ImageLayout::UNDEFINED,
    new: vk::ImageLayout::TRANSFER_DST_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::NONE,
    src_access: vk::AccessFlags2::NONE,
    dst_stage: vk::PipelineStageFlags2::COPY,
    dst_access: vk::AccessFlags2::TRANSFER_WRITE,
};

//! `Buffer`: a `vk::Buffer` with its gpu-allocator memory, freed in `Drop`. Mesh buffers are
//! host-visible (on lavapipe and integrated GPUs all memory is) and filled once at upload.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::Allocation;
use gpu_allocator::MemoryLocation;

use super::context::Context;
use super::error::{RenderError, Result};

/// A buffer and its memory.
pub struct Buffer {
    context: Arc<Context>,
    pub handle: vk::Buffer,
    pub size: vk::DeviceSize,
    allocation: Option<Allocation>,
}

impl Buffer {
    /// Creates a buffer of `size` bytes in `location`.
    pub fn new(
        context: &Arc<Context>,
        name: &str,
        size: vk::DeviceSize,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Self> {
        let device = &context.device;
        let info = vk::BufferCreateInfo::default()
            .size(size.max(4))
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: valid create info on a live device.
        let handle = unsafe { device.create_buffer(&info, None)? };
        // From here on `buffer` owns `handle`, so an early return frees it.
        let mut buffer = Self {
            context: context.clone(),
            handle,
            size,
            allocation: None,
        };
        // SAFETY: `handle` was just created on this device.
        let requirements = unsafe { device.get_buffer_memory_requirements(handle) };
        let allocation = context.allocate(name, requirements, location, true)?;
        // SAFETY: the allocation satisfies the buffer's requirements and is not bound elsewhere.
        let bound =
            unsafe { device.bind_buffer_memory(handle, allocation.memory(), allocation.offset()) };
        buffer.allocation = Some(allocation);
        bound?;
        Ok(buffer)
    }

    /// A host-visible buffer holding `data`.
    pub fn with_data<T: Copy>(
        context: &Arc<Context>,
        name: &str,
        usage: vk::BufferUsageFlags,
        data: &[T],
    ) -> Result<Self> {
        let bytes = size_of_val(data);
        let mut buffer = Self::new(context, name, bytes as u64, usage, MemoryLocation::CpuToGpu)?;
        let target = buffer.mapped_mut()?;
        // SAFETY: `T: Copy` is plain data; the mapping is at least `bytes` long and does not
        // overlap `data`.
        unsafe {
            std::ptr::copy_nonoverlapping(data.as_ptr().cast::<u8>(), target.as_mut_ptr(), bytes);
        }
        Ok(buffer)
    }

    /// The mapped bytes of a host-visible buffer.
    pub fn mapped(&self) -> Result<&[u8]> {
        self.allocation
            .as_ref()
            .and_then(Allocation::mapped_slice)
            .ok_or_else(|| RenderError::TooLarge("buffer is not host-visible".into()))
    }

    /// The mapped bytes of a host-visible buffer, writable.
    pub fn mapped_mut(&mut self) -> Result<&mut [u8]> {
        self.allocation
            .as_mut()
            .and_then(Allocation::mapped_slice_mut)
            .ok_or_else(|| RenderError::TooLarge("buffer is not host-visible".into()))
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        // SAFETY: callers wait for the GPU to finish with the buffer before dropping it (frames
        // are fenced); the buffer is destroyed before its memory is returned.
        unsafe { self.context.device.destroy_buffer(self.handle, None) };
        if let Some(allocation) = self.allocation.take() {
            self.context.free(allocation);
        }
    }
}

/// Batches uploads into device-local buffers: each `upload` stages its data, `finish` copies
/// them all in one submission and frees the staging buffers.
pub struct Uploader<'a> {
    context: &'a Arc<Context>,
    commands: &'a super::commands::Commands,
    cmd: vk::CommandBuffer,
    staging: Vec<Buffer>,
}

impl<'a> Uploader<'a> {
    pub fn new(context: &'a Arc<Context>, commands: &'a super::commands::Commands) -> Result<Self> {
        let cmd = commands.begin()?;
        Ok(Self {
            context,
            commands,
            cmd,
            staging: Vec::new(),
        })
    }

    /// A device-local buffer that will hold `data` once `finish` returns.
    pub fn upload<T: Copy>(
        &mut self,
        name: &str,
        usage: vk::BufferUsageFlags,
        data: &[T],
    ) -> Result<Buffer> {
        let staging =
            Buffer::with_data(self.context, name, vk::BufferUsageFlags::TRANSFER_SRC, data)?;
        let buffer = Buffer::new(
            self.context,
            name,
            staging.size,
            usage | vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuOnly,
        )?;
        if staging.size > 0 {
            let region = [vk::BufferCopy::default().size(staging.size)];
            // SAFETY: both buffers are alive until `finish` has waited for the copy, and both
            // are at least `size` bytes long.
            unsafe {
                self.context.device.cmd_copy_buffer(
                    self.cmd,
                    staging.handle,
                    buffer.handle,
                    &region,
                )
            };
        }
        self.staging.push(staging);
        Ok(buffer)
    }

    /// A device-local sampled image of `format` that will hold `levels` (8-bit RGBA; the
    /// full-size image first, then each mip level at half the size of the one before, as
    /// Vulkan sizes them) once `finish` returns, in `SHADER_READ_ONLY_OPTIMAL` layout.
    pub fn upload_image(
        &mut self,
        name: &str,
        format: vk::Format,
        levels: &[decimate_core::mesh::rgba_image::RgbaImage],
    ) -> Result<super::image::Image> {
        use super::image::{transition, Image, COPIED_TO_SAMPLED, TO_COPY_DESTINATION};
        let Some(base) = levels.first() else {
            return Err(RenderError::BadLevels(format!("image {name:?}: no levels")));
        };
        check_levels(name, levels)?;
        let (bytes, regions) = packed_levels(levels);
        let staging = Buffer::with_data(
            self.context,
            name,
            vk::BufferUsageFlags::TRANSFER_SRC,
            &bytes,
        )?;
        let extent = vk::Extent2D {
            width: base.width,
            height: base.height,
        };
        let usage = vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST;
        let target = Image::with_levels(
            self.context,
            name,
            format,
            extent,
            usage,
            regions.len() as u32,
        )?;
        let device = &self.context.device;
        // SAFETY: the command buffer is recording; the staging buffer holds every level's
        // width × height RGBA texels at its region's offset and lives until `finish` has
        // waited; each level's extent is the image's at that level (both checked above); the
        // image is alive and owned by the caller, who keeps it until then.
        unsafe {
            transition(device, self.cmd, target.handle, format, TO_COPY_DESTINATION);
            device.cmd_copy_buffer_to_image(
                self.cmd,
                staging.handle,
                target.handle,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &regions,
            );
            transition(device, self.cmd, target.handle, format, COPIED_TO_SAMPLED);
        }
        self.staging.push(staging);
        Ok(target)
    }

    /// Runs every copy and waits for them; the buffers are then ready to draw from.
    pub fn finish(self) -> Result<()> {
        let barrier = [vk::MemoryBarrier2::default()
            .src_stage_mask(vk::PipelineStageFlags2::COPY)
            .src_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
            .dst_stage_mask(vk::PipelineStageFlags2::VERTEX_INPUT)
            .dst_access_mask(
                vk::AccessFlags2::VERTEX_ATTRIBUTE_READ | vk::AccessFlags2::INDEX_READ,
            )];
        let dependency = vk::DependencyInfo::default().memory_barriers(&barrier);
        // SAFETY: the command buffer is recording (begun in `new`).
        unsafe {
            self.context
                .device
                .cmd_pipeline_barrier2(self.cmd, &dependency)
        };
        self.commands.submit_and_wait()
    }
}
/// Checks that `levels` is a mip chain: level `i` is the base halved `i` times (at least
/// 1), with width × height RGBA texels.
fn check_levels(name: &str, levels: &[decimate_core::mesh::rgba_image::RgbaImage]) -> Result<()> {
    let Some(base) = levels.first() else {
        return Err(RenderError::BadLevels(format!("image {name:?}: no levels")));
    };
    for (i, level) in levels.iter().enumerate() {
        let side = |full: u32| full.checked_shr(i as u32).unwrap_or(0).max(1);
        let (w, h) = (side(base.width), side(base.height));
        if (level.width, level.height) != (w, h)
            || level.pixels.len() != w as usize * h as usize * 4
        {
            return Err(RenderError::BadLevels(format!(
                "image {name:?}: level {i} is {} × {} ({} bytes), not {w} × {h} RGBA",
                level.width,
                level.height,
                level.pixels.len()
            )));
        }
    }
    Ok(())
}

/// Every level's texels one after the other, and the copy region of each.
fn packed_levels(
    levels: &[decimate_core::mesh::rgba_image::RgbaImage],
) -> (Vec<u8>, Vec<vk::BufferImageCopy>) {
    let mut bytes = Vec::with_capacity(levels.iter().map(|l| l.pixels.len()).sum());
    let mut regions = Vec::with_capacity(levels.len());
    for (level, image) in levels.iter().enumerate() {
        regions.push(
            vk::BufferImageCopy::default()
                // RGBA8 texels: every offset is a multiple of the texel size, 4.
                .buffer_offset(bytes.len() as vk::DeviceSize)
                .image_subresource(
                    vk::ImageSubresourceLayers::default()
                        .aspect_mask(vk::ImageAspectFlags::COLOR)
                        .mip_level(level as u32)
                        .layer_count(1),
                )
                .image_extent(vk::Extent3D {
                    width: image.width,
                    height: image.height,
                    depth: 1,
                }),
        );
        bytes.extend_from_slice(&image.pixels);
    }
    (bytes, regions)
}

//! `Commands`: a command pool with one primary command buffer and a fence, for work that is
//! recorded, submitted and waited for (offscreen frames, staging uploads). Freed in `Drop`.

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::Result;

/// A reusable one-at-a-time command buffer.
pub struct Commands {
    context: Arc<Context>,
    pool: vk::CommandPool,
    pub buffer: vk::CommandBuffer,
    fence: vk::Fence,
}

impl Commands {
    pub fn new(context: &Arc<Context>) -> Result<Self> {
        let device = &context.device;
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(context.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        // SAFETY: valid create info on a live device.
        let pool = unsafe { device.create_command_pool(&pool_info, None)? };
        let mut this = Self {
            context: context.clone(),
            pool,
            buffer: vk::CommandBuffer::null(),
            fence: vk::Fence::null(),
        };
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        // SAFETY: the pool was just created on this device.
        this.buffer = unsafe { device.allocate_command_buffers(&alloc)? }[0];
        // SAFETY: valid create info on a live device.
        this.fence = unsafe { device.create_fence(&vk::FenceCreateInfo::default(), None)? };
        Ok(this)
    }

    /// The pool, for libraries that record their own one-time commands (egui uploads).
    pub fn pool(&self) -> vk::CommandPool {
        self.pool
    }

    /// Ends recording, for a buffer submitted elsewhere (the swapchain's frame submission).
    pub fn end(&self) -> Result<()> {
        // SAFETY: the buffer is recording (begun by `begin`).
        unsafe { self.context.device.end_command_buffer(self.buffer)? };
        Ok(())
    }

    /// Resets the buffer and starts recording a one-time submission.
    pub fn begin(&self) -> Result<vk::CommandBuffer> {
        let device = &self.context.device;
        let info = vk::CommandBufferBeginInfo::default()
            .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
        // SAFETY: the previous submission (if any) was waited for in `submit_and_wait`.
        unsafe {
            device.reset_command_buffer(self.buffer, vk::CommandBufferResetFlags::empty())?;
            device.begin_command_buffer(self.buffer, &info)?;
        }
        Ok(self.buffer)
    }

    /// Ends recording, submits, and blocks until the GPU has executed it.
    pub fn submit_and_wait(&self) -> Result<()> {
        let device = &self.context.device;
        let buffers = [self.buffer];
        let submit = vk::SubmitInfo::default().command_buffers(&buffers);
        // SAFETY: the buffer is in the recording state (begun by `begin`); the fence is
        // unsignalled (reset after every wait) and owned by us.
        unsafe {
            device.end_command_buffer(self.buffer)?;
            device.queue_submit(self.context.queue, &[submit], self.fence)?;
            device.wait_for_fences(&[self.fence], true, u64::MAX)?;
            device.reset_fences(&[self.fence])?;
        }
        Ok(())
    }
}

impl Drop for Commands {
    fn drop(&mut self) {
        // SAFETY: `submit_and_wait` always waits, so nothing recorded here is still executing;
        // freeing the pool frees its command buffer.
        unsafe {
            self.context.device.destroy_fence(self.fence, None);
            self.context.device.destroy_command_pool(self.pool, None);
        }
    }
}

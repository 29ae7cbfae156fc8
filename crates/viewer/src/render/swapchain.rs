//! `Swapchain`: the window's surface, its swapchain images and views, a depth buffer of the
//! same size (and a multisampled colour image when anti-aliased, beside single-sampled
//! images for the frames drawn while the view moves), and the semaphores and fence of the
//! one frame in flight. Recreated on resize;
//! everything freed in `Drop` (views and swapchain before the surface).

use std::sync::Arc;

use ash::vk;
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};

use super::attachments::DrawImages;
use super::context::Context;
use super::error::{RenderError, Result};

/// A window's presentable images.
pub struct Swapchain {
    context: Arc<Context>,
    surface_loader: ash::khr::surface::Instance,
    swapchain_loader: ash::khr::swapchain::Device,
    surface: vk::SurfaceKHR,
    handle: vk::SwapchainKHR,
    pub images: Vec<vk::Image>,
    views: Vec<vk::ImageView>,
    /// Depth and multisampled colour, made again with the swapchain.
    pub draw_images: Option<DrawImages>,
    /// With multisampling, a single-sampled depth buffer too: the frames drawn while the
    /// view moves (docs/design.md#msaa), kept so that switching costs nothing.
    pub moving_images: Option<DrawImages>,
    /// Samples per pixel the viewports are drawn with.
    pub samples: vk::SampleCountFlags,
    pub format: vk::Format,
    pub extent: vk::Extent2D,
    image_available: vk::Semaphore,
    /// One per swapchain image: presentation waits on the one of the image it shows.
    render_finished: Vec<vk::Semaphore>,
    pub in_flight: vk::Fence,
    /// The images can be copied into (a kept picture drawn back, `picture_cache`).
    pub restorable: bool,
}

/// The image acquired for a frame.
pub struct Frame {
    pub index: u32,
    pub image: vk::Image,
    pub view: vk::ImageView,
}

impl Swapchain {
    /// Creates the surface of `window` and a swapchain of `width` × `height`, drawn with
    /// `samples` samples per pixel.
    pub fn new(
        context: &Arc<Context>,
        window: &(impl HasDisplayHandle + HasWindowHandle),
        (width, height): (u32, u32),
        samples: vk::SampleCountFlags,
    ) -> Result<Self> {
        let display = window
            .display_handle()
            .map_err(|e| RenderError::Window(e.to_string()))?;
        let window_handle = window
            .window_handle()
            .map_err(|e| RenderError::Window(e.to_string()))?;
        // SAFETY: the handles come from a live window that outlives the swapchain (the viewer
        // drops the swapchain before the window).
        let surface = unsafe {
            ash_window::create_surface(
                &context.entry,
                &context.instance,
                display.as_raw(),
                window_handle.as_raw(),
                None,
            )?
        };
        let surface_loader = ash::khr::surface::Instance::new(&context.entry, &context.instance);
        let swapchain_loader = ash::khr::swapchain::Device::new(&context.instance, &context.device);
        let mut this = Self {
            context: context.clone(),
            surface_loader,
            swapchain_loader,
            surface,
            handle: vk::SwapchainKHR::null(),
            images: Vec::new(),
            views: Vec::new(),
            draw_images: None,
            moving_images: None,
            samples,
            format: vk::Format::B8G8R8A8_UNORM,
            extent: vk::Extent2D { width, height },
            image_available: vk::Semaphore::null(),
            render_finished: Vec::new(),
            in_flight: vk::Fence::null(),
            restorable: false,
        };
        // SAFETY: plain queries and creations on live objects.
        unsafe {
            let supported = this.surface_loader.get_physical_device_surface_support(
                context.physical_device,
                context.queue_family,
                surface,
            )?;
            if !supported {
                return Err(RenderError::Window(format!(
                    "{} cannot present to this window",
                    context.device_name
                )));
            }
            let device = &context.device;
            this.image_available =
                device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None)?;
            this.in_flight = device.create_fence(
                &vk::FenceCreateInfo::default().flags(vk::FenceCreateFlags::SIGNALED),
                None,
            )?;
        }
        this.recreate(width, height)?;
        Ok(this)
    }

    /// (Re)creates the swapchain, its views and the depth buffer for a new window size.
    pub fn recreate(&mut self, width: u32, height: u32) -> Result<()> {
        self.context.wait_idle()?;
        let physical = self.context.physical_device;
        // SAFETY: plain queries on a live surface.
        let (caps, formats) = unsafe {
            (
                self.surface_loader
                    .get_physical_device_surface_capabilities(physical, self.surface)?,
                self.surface_loader
                    .get_physical_device_surface_formats(physical, self.surface)?,
            )
        };
        let format = pick_format(&formats)?;
        let extent = pick_extent(&caps, width, height);
        let mut count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            count = count.min(caps.max_image_count);
        }
        // A copy destination too where the surface allows: a kept picture of the viewports
        // is copied back into it (`picture_cache`).
        let restorable = caps
            .supported_usage_flags
            .contains(vk::ImageUsageFlags::TRANSFER_DST);
        let mut usage = vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC;
        if restorable {
            usage |= vk::ImageUsageFlags::TRANSFER_DST;
        }
        self.restorable = restorable;
        let old = self.handle;
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(self.surface)
            .min_image_count(count)
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(usage)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(vk::CompositeAlphaFlagsKHR::OPAQUE)
            .present_mode(vk::PresentModeKHR::FIFO)
            .clipped(true)
            .old_swapchain(old);
        self.destroy_views();
        // SAFETY: the device is idle, so the old swapchain's images are not in use; it is
        // retired here and destroyed right after the new one exists.
        unsafe {
            self.handle = self.swapchain_loader.create_swapchain(&info, None)?;
            if old != vk::SwapchainKHR::null() {
                self.swapchain_loader.destroy_swapchain(old, None);
            }
            self.images = self.swapchain_loader.get_swapchain_images(self.handle)?;
        }
        self.format = format.format;
        self.extent = extent;
        self.create_views(format.format)?;
        self.draw_images = Some(DrawImages::new(
            &self.context,
            "window",
            format.format,
            extent,
            self.samples,
        )?);
        self.moving_images = self.single_images()?;
        Ok(())
    }

    /// A view and a render-finished semaphore for each swapchain image.
    fn create_views(&mut self, format: vk::Format) -> Result<()> {
        for &image in &self.images {
            let view_info = vk::ImageViewCreateInfo::default()
                .image(image)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(format)
                .subresource_range(super::image::subresource_range(format));
            // SAFETY: the image belongs to the live swapchain.
            let view = unsafe { self.context.device.create_image_view(&view_info, None)? };
            self.views.push(view);
            // SAFETY: valid create info on a live device.
            let semaphore = unsafe {
                self.context
                    .device
                    .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)?
            };
            self.render_finished.push(semaphore);
        }
        Ok(())
    }

    /// The single-sampled images drawn with while the view moves; none when the window
    /// draws single-sampled anyway.
    fn single_images(&self) -> Result<Option<DrawImages>> {
        if self.samples == vk::SampleCountFlags::TYPE_1 {
            return Ok(None);
        }
        let one = vk::SampleCountFlags::TYPE_1;
        DrawImages::new(
            &self.context,
            "window (moving)",
            self.format,
            self.extent,
            one,
        )
        .map(Some)
    }

    /// The images to draw this frame with: the single-sampled ones when `moving` (if there
    /// are any), else those of [`Self::samples`].
    pub fn images(&self, moving: bool) -> Option<&DrawImages> {
        match (&self.moving_images, moving) {
            (Some(images), true) => Some(images),
            _ => self.draw_images.as_ref(),
        }
    }

    /// Draws with `samples` samples per pixel from now on (the depth and multisampled images
    /// are made again; the caller's pipelines must match).
    pub fn set_samples(&mut self, samples: vk::SampleCountFlags) -> Result<()> {
        if samples == self.samples && self.draw_images.is_some() {
            return Ok(());
        }
        self.context.wait_idle()?;
        self.draw_images = None;
        self.moving_images = None;
        self.samples = samples;
        self.draw_images = Some(DrawImages::new(
            &self.context,
            "window",
            self.format,
            self.extent,
            samples,
        )?);
        self.moving_images = self.single_images()?;
        Ok(())
    }

    /// Waits for the previous frame, then acquires the next image; `None` when the swapchain
    /// is out of date (the caller recreates it).
    pub fn acquire(&self) -> Result<Option<Frame>> {
        let device = &self.context.device;
        // SAFETY: the fence and semaphore are ours; waiting on the fence before reusing the
        // command buffer and the semaphore keeps one frame in flight.
        unsafe {
            device.wait_for_fences(&[self.in_flight], true, u64::MAX)?;
            match self.swapchain_loader.acquire_next_image(
                self.handle,
                u64::MAX,
                self.image_available,
                vk::Fence::null(),
            ) {
                Ok((index, _suboptimal)) => {
                    device.reset_fences(&[self.in_flight])?;
                    Ok(Some(Frame {
                        index,
                        image: self.images[index as usize],
                        view: self.views[index as usize],
                    }))
                }
                Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(None),
                Err(e) => Err(e.into()),
            }
        }
    }

    /// Submits `cmd` for `frame` and presents it; `false` when the swapchain must be recreated.
    pub fn submit_and_present(&self, cmd: vk::CommandBuffer, frame: &Frame) -> Result<bool> {
        let wait = [vk::SemaphoreSubmitInfo::default()
            .semaphore(self.image_available)
            .stage_mask(vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT)];
        let signal_semaphore = self.render_finished[frame.index as usize];
        let signal = [vk::SemaphoreSubmitInfo::default()
            .semaphore(signal_semaphore)
            .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        let buffers = [vk::CommandBufferSubmitInfo::default().command_buffer(cmd)];
        let submit = vk::SubmitInfo2::default()
            .wait_semaphore_infos(&wait)
            .command_buffer_infos(&buffers)
            .signal_semaphore_infos(&signal);
        let swapchains = [self.handle];
        let indices = [frame.index];
        let waits = [signal_semaphore];
        let present = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: `cmd` is fully recorded; the fence was reset in `acquire`.
        unsafe {
            self.context
                .device
                .queue_submit2(self.context.queue, &[submit], self.in_flight)?;
            match self
                .swapchain_loader
                .queue_present(self.context.queue, &present)
            {
                Ok(false) => Ok(true),
                Ok(true) | Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(false),
                Err(e) => Err(e.into()),
            }
        }
    }

    fn destroy_views(&mut self) {
        // SAFETY: callers wait for the device to be idle first.
        unsafe {
            for view in self.views.drain(..) {
                self.context.device.destroy_image_view(view, None);
            }
            for s in self.render_finished.drain(..) {
                self.context.device.destroy_semaphore(s, None);
            }
        }
        self.draw_images = None;
        self.moving_images = None;
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        let _ = self.context.wait_idle();
        self.destroy_views();
        // SAFETY: the device is idle; views went first, then the swapchain, then the surface.
        unsafe {
            self.context
                .device
                .destroy_semaphore(self.image_available, None);
            self.context.device.destroy_fence(self.in_flight, None);
            if self.handle != vk::SwapchainKHR::null() {
                self.swapchain_loader.destroy_swapchain(self.handle, None);
            }
            self.surface_loader.destroy_surface(self.surface, None);
        }
    }
}
/// UNORM like the offscreen target, so the window and `shot` show the same colours; else
/// whatever the surface offers first.
fn pick_format(formats: &[vk::SurfaceFormatKHR]) -> Result<vk::SurfaceFormatKHR> {
    formats
        .iter()
        .find(|f| f.format == vk::Format::B8G8R8A8_UNORM || f.format == vk::Format::R8G8B8A8_UNORM)
        .or_else(|| formats.first())
        .copied()
        .ok_or_else(|| RenderError::Window("the surface offers no format".into()))
}

/// The surface's own extent, or the window's `width` × `height` within its limits.
fn pick_extent(caps: &vk::SurfaceCapabilitiesKHR, width: u32, height: u32) -> vk::Extent2D {
    if caps.current_extent.width != u32::MAX {
        return caps.current_extent;
    }
    vk::Extent2D {
        width: width.clamp(caps.min_image_extent.width, caps.max_image_extent.width),
        height: height.clamp(caps.min_image_extent.height, caps.max_image_extent.height),
    }
}

//! `PictureCache`: the window's viewports as last drawn (before the UI went on top), kept
//! in an image of the swapchain's format with the key of what they showed. While a job
//! runs, a frame whose viewports would look the same copies this picture back and draws
//! only the UI over it, instead of drawing every triangle again
//! (docs/design.md#viewer-jobs).

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::Result;
use super::image::{self, Image, Transition};

/// The kept picture and the key it was drawn for (`K`: whatever decides the viewports'
/// look — cameras, scenes, sizes, draw modes).
pub struct PictureCache<K> {
    image: Option<Image>,
    key: Option<K>,
}

impl<K> Default for PictureCache<K> {
    fn default() -> Self {
        Self {
            image: None,
            key: None,
        }
    }
}

/// A colour attachment just drawn, to the source of a copy.
const DRAWN_TO_COPY_SOURCE: Transition = Transition {
    old: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
    new: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
    src_access: vk::AccessFlags2::COLOR_ATTACHMENT_WRITE,
    dst_stage: vk::PipelineStageFlags2::COPY,
    dst_access: vk::AccessFlags2::TRANSFER_READ,
};

/// The copy's source back to a colour attachment the UI is drawn on (contents kept).
const COPY_SOURCE_TO_DRAWN: Transition = Transition {
    old: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
    new: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::COPY,
    src_access: vk::AccessFlags2::NONE,
    dst_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
    dst_access: vk::AccessFlags2::from_raw(
        vk::AccessFlags2::COLOR_ATTACHMENT_WRITE.as_raw()
            | vk::AccessFlags2::COLOR_ATTACHMENT_READ.as_raw(),
    ),
};

/// A copy's destination, just written, to a colour attachment the UI is drawn on.
const COPIED_TO_DRAWN: Transition = Transition {
    old: vk::ImageLayout::TRANSFER_DST_OPTIMAL,
    new: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::COPY,
    src_access: vk::AccessFlags2::TRANSFER_WRITE,
    dst_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
    dst_access: vk::AccessFlags2::from_raw(
        vk::AccessFlags2::COLOR_ATTACHMENT_WRITE.as_raw()
            | vk::AccessFlags2::COLOR_ATTACHMENT_READ.as_raw(),
    ),
};

/// The kept picture, any earlier copy done, to the destination of the next one.
const KEPT_TO_COPY_DESTINATION: Transition = Transition {
    old: vk::ImageLayout::UNDEFINED,
    new: vk::ImageLayout::TRANSFER_DST_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::COPY,
    src_access: vk::AccessFlags2::TRANSFER_READ,
    dst_stage: vk::PipelineStageFlags2::COPY,
    dst_access: vk::AccessFlags2::TRANSFER_WRITE,
};

/// The kept picture, just written, to the source of later copies.
const KEPT_TO_COPY_SOURCE: Transition = Transition {
    old: vk::ImageLayout::TRANSFER_DST_OPTIMAL,
    new: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
    src_stage: vk::PipelineStageFlags2::COPY,
    src_access: vk::AccessFlags2::TRANSFER_WRITE,
    dst_stage: vk::PipelineStageFlags2::COPY,
    dst_access: vk::AccessFlags2::TRANSFER_READ,
};

impl<K: PartialEq> PictureCache<K> {
    /// Whether the picture kept was drawn for `key` (and can stand for a new drawing).
    pub fn holds(&self, key: &K) -> bool {
        self.image.is_some() && self.key.as_ref() == Some(key)
    }

    /// Records a copy of `source` (a colour attachment of `format` and `extent`, just drawn;
    /// left a colour attachment with its contents) into the kept picture, for `key`.
    ///
    /// # Safety
    /// `cmd` must be recording outside a rendering pass, `source` alive until the commands
    /// have executed, and no earlier frame's commands may still use the kept picture when
    /// its size or format changes (the swapchain waits for the device when it is made again).
    pub unsafe fn capture(
        &mut self,
        context: &Arc<Context>,
        cmd: vk::CommandBuffer,
        source: vk::Image,
        format: vk::Format,
        extent: vk::Extent2D,
        key: K,
    ) -> Result<()> {
        self.key = None;
        if (self.image.as_ref()).is_none_or(|i| i.extent != extent || i.format != format) {
            self.image = None;
            let usage = vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
            self.image = Some(Image::new(context, "kept picture", format, extent, usage)?);
        }
        let Some(kept) = &self.image else {
            return Ok(());
        };
        let device = &context.device;
        // SAFETY: guaranteed by the caller; the kept picture lives in `self`.
        unsafe {
            image::transition(device, cmd, source, format, DRAWN_TO_COPY_SOURCE);
            image::transition(device, cmd, kept.handle, format, KEPT_TO_COPY_DESTINATION);
            copy(device, cmd, source, kept.handle, extent);
            image::transition(device, cmd, kept.handle, format, KEPT_TO_COPY_SOURCE);
            image::transition(device, cmd, source, format, COPY_SOURCE_TO_DRAWN);
        }
        self.key = Some(key);
        Ok(())
    }

    /// Records the copy of the kept picture into `target` (of the kept picture's format and
    /// extent; its contents discarded), left a colour attachment the UI can be drawn on.
    /// False, recording nothing, when no picture is kept.
    ///
    /// # Safety
    /// `cmd` must be recording outside a rendering pass and `target` alive until the
    /// commands have executed.
    pub unsafe fn restore(
        &self,
        device: &ash::Device,
        cmd: vk::CommandBuffer,
        target: vk::Image,
    ) -> bool {
        let Some(kept) = &self.image else {
            return false;
        };
        // SAFETY: guaranteed by the caller; the kept picture lives in `self`.
        unsafe {
            image::transition(device, cmd, target, kept.format, image::TO_COPY_DESTINATION);
            copy(device, cmd, kept.handle, target, kept.extent);
            image::transition(device, cmd, target, kept.format, COPIED_TO_DRAWN);
        }
        true
    }
}

/// Records a copy of the whole colour image `from` (transfer source) to `to` (transfer
/// destination), both `extent`.
///
/// # Safety
/// As [`PictureCache::restore`], for both images.
unsafe fn copy(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    from: vk::Image,
    to: vk::Image,
    extent: vk::Extent2D,
) {
    let layers = vk::ImageSubresourceLayers::default()
        .aspect_mask(vk::ImageAspectFlags::COLOR)
        .layer_count(1);
    let region = [vk::ImageCopy::default()
        .src_subresource(layers)
        .dst_subresource(layers)
        .extent(vk::Extent3D {
            width: extent.width,
            height: extent.height,
            depth: 1,
        })];
    // SAFETY: guaranteed by the caller.
    unsafe {
        device.cmd_copy_image(
            cmd,
            from,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            to,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            &region,
        );
    }
}

//! `DrawImages`: what a target needs beside the image its picture ends in — the depth buffer
//! and, with multisample anti-aliasing, the multisampled colour image the viewports are drawn
//! into and resolved from — for the offscreen target and the window alike.

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::Result;
use super::image::{self, Image, DEPTH_FORMAT};

/// The views a frame's viewports are drawn with: the colour view the picture ends in, and
/// with multisampling the multisampled view drawn into and averaged into `color` at the end
/// of the pass; `depth` has the drawing view's sample count.
#[derive(Debug, Clone, Copy)]
pub struct Attachments {
    pub color: vk::ImageView,
    pub multisampled: Option<vk::ImageView>,
    pub depth: vk::ImageView,
}

/// A target's depth buffer and multisampled colour image (none at one sample per pixel).
pub struct DrawImages {
    pub depth: Image,
    pub multisampled: Option<Image>,
    pub samples: vk::SampleCountFlags,
}

impl DrawImages {
    /// Images of `extent` for drawing with `samples` samples per pixel into a picture of
    /// `color_format`.
    pub fn new(
        context: &Arc<Context>,
        name: &str,
        color_format: vk::Format,
        extent: vk::Extent2D,
        samples: vk::SampleCountFlags,
    ) -> Result<Self> {
        let depth = Image::multisampled(
            context,
            &format!("{name} depth"),
            DEPTH_FORMAT,
            extent,
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT,
            samples,
        )?;
        let multisampled = if samples == vk::SampleCountFlags::TYPE_1 {
            None
        } else {
            Some(Image::multisampled(
                context,
                &format!("{name} samples"),
                color_format,
                extent,
                vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSIENT_ATTACHMENT,
                samples,
            )?)
        };
        Ok(Self {
            depth,
            multisampled,
            samples,
        })
    }

    /// The views to draw with when the picture ends in `color`.
    pub fn attachments(&self, color: vk::ImageView) -> Attachments {
        Attachments {
            color,
            multisampled: self.multisampled.as_ref().map(|i| i.view),
            depth: self.depth.view,
        }
    }

    /// Records the transitions of the depth buffer and the multisampled image (contents
    /// discarded) to their attachment layouts.
    ///
    /// # Safety
    /// `cmd` must be recording outside rendering; the images stay alive until it has run.
    pub unsafe fn to_attachments(&self, device: &ash::Device, cmd: vk::CommandBuffer) {
        // SAFETY: guaranteed by the caller.
        unsafe {
            image::transition(
                device,
                cmd,
                self.depth.handle,
                DEPTH_FORMAT,
                image::TO_DEPTH_ATTACHMENT,
            );
            if let Some(samples) = &self.multisampled {
                image::transition(
                    device,
                    cmd,
                    samples.handle,
                    samples.format,
                    image::TO_COLOR_ATTACHMENT,
                );
            }
        }
    }
}

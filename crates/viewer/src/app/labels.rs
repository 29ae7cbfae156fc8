//! Viewport captions: what each viewport shows — "original" or its target, with vertices,
//! triangles and the algorithm — painted with egui at the viewport's bottom-right corner (`overlay` lays out the rest).
//! The same words and painter serve the window and `shot`, where a headless egui context
//! ([`HeadlessCaptions`]) paints them into the offscreen picture.

use std::sync::Arc;

use ash::vk;
use egui_ash_renderer::allocator::GpuAllocator;
use egui_ash_renderer::{DynamicRendering, Options, RenderMode, Renderer};

use crate::render::commands::Commands;
use crate::render::context::Context;
use crate::render::offscreen::OFFSCREEN_FORMAT;
use crate::render::tiles::Rect;
use crate::render::RenderError;
use decimate_core::decimate::{Algorithm, ErrorBound, Target};

/// Caption text size in points.
const TEXT_SIZE: f32 = 12.0;
/// The smallest caption text, in points, however narrow the viewport.
const MIN_TEXT_SIZE: f32 = 7.0;
/// Gap between a caption and its viewport's edges, in points.
const MARGIN: f32 = 6.0;

/// What a decimated viewport was asked for, in words.
pub fn target_words(target: Target, max_error: Option<ErrorBound>) -> String {
    let mut words = match target {
        Target::RemovePercent(p) if p >= 100.0 => "as far as possible".to_string(),
        Target::RemovePercent(p) => format!("{p} % removed"),
        Target::RemoveVertices(n) => format!("{n} vertices removed"),
        Target::KeepVertices(n) => format!("to {n} vertices"),
        Target::KeepTriangles(n) => format!("to {n} triangles"),
        Target::ErrorOnly => "within the error bound".to_string(),
    };
    match max_error {
        Some(ErrorBound::Absolute(e)) => words.push_str(&format!(", error ≤ {e}")),
        Some(ErrorBound::DiagonalFraction(f)) => {
            words.push_str(&format!(", error ≤ {} % of the diagonal", f * 100.0));
        }
        None => {}
    }
    words
}

/// The algorithm's short name, as `-a` spells it.
pub fn algorithm_name(algorithm: Algorithm) -> &'static str {
    match algorithm {
        Algorithm::Schroeder => "schroeder",
        Algorithm::Qem => "qem",
    }
}

/// A caption: what the viewport shows on the first line, its counts on the second.
pub fn caption(what: &str, vertices: usize, triangles: usize) -> String {
    format!("{what}\n{}", counts(vertices, triangles))
}

/// "871,414 vertices, 1,742,128 triangles": counts as captions and the status line show them.
pub fn counts(vertices: usize, triangles: usize) -> String {
    format!(
        "{} vertices, {} triangles",
        grouped(vertices),
        grouped(triangles)
    )
}

/// `n` with its digits in groups of three ("1,742,128"), as the vertex field accepts them.
pub fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Paints `captions` (a viewport rectangle in pixels and its text) on the viewports' layer,
/// under every window and menu, at the context's pixels per point.
pub fn paint(ctx: &egui::Context, captions: &[(Rect, String)]) {
    let painter = ctx.layer_painter(super::text_layout::base_layer());
    paint_on(&painter, captions, ctx.pixels_per_point());
}

/// Paints `captions` with `painter`, each at its viewport's bottom-right corner, clipped to
/// it; rectangles in pixels, `pixels_per_point` of them to a point.
pub fn paint_on(painter: &egui::Painter, captions: &[(Rect, String)], pixels_per_point: f32) {
    for (rect, text) in captions {
        let tile = super::text_layout::points(rect, pixels_per_point);
        let layout = |size: f32| {
            painter.layout_no_wrap(
                text.clone(),
                egui::FontId::proportional(size),
                egui::Color32::from_gray(235),
            )
        };
        // A narrow tile gets smaller text, so the caption fits beside the model.
        let mut galley = layout(TEXT_SIZE);
        let room = tile.width() - 2.0 * MARGIN;
        if galley.size().x > room {
            galley = layout((TEXT_SIZE * room / galley.size().x).max(MIN_TEXT_SIZE));
        }
        let top_left = tile.max - galley.size() - egui::vec2(MARGIN, MARGIN);
        let frame = egui::Rect::from_min_size(top_left, galley.size()).expand(3.0);
        let painter = painter.with_clip_rect(tile);
        painter.rect_filled(frame, 3.0, egui::Color32::from_black_alpha(160));
        painter.galley(top_left, galley, egui::Color32::WHITE);
    }
}

/// An egui context with no window and its Vulkan renderer, for captions in a `shot`.
pub struct HeadlessCaptions {
    // Field order is drop order: the renderer before anything it was made with.
    renderer: Renderer<GpuAllocator>,
    primitives: Vec<egui::ClippedPrimitive>,
    extent: vk::Extent2D,
    pixels_per_point: f32,
}

impl HeadlessCaptions {
    /// Lays out `captions` over a picture of `extent` (one pixel per point) and uploads the
    /// font atlas they use.
    pub fn new(
        context: &Arc<Context>,
        commands: &Commands,
        extent: vk::Extent2D,
        captions: &[(Rect, String)],
    ) -> Result<Self, RenderError> {
        Self::with_painter(context, commands, extent, &|ctx| paint(ctx, captions))
    }

    /// As [`Self::new`], with whatever `paint_all` paints (captions, a legend) over a picture
    /// of `extent`, its text as large as `text_layout::text_scale` says.
    pub fn with_painter(
        context: &Arc<Context>,
        commands: &Commands,
        extent: vk::Extent2D,
        paint_all: &dyn Fn(&egui::Context),
    ) -> Result<Self, RenderError> {
        let overlay = |e: egui_ash_renderer::RendererError| RenderError::Overlay(e.to_string());
        let mut renderer = Renderer::with_gpu_allocator(
            context.allocator().clone(),
            context.device.clone(),
            RenderMode::DynamicRendering(DynamicRendering {
                color_attachment_format: OFFSCREEN_FORMAT,
                depth_attachment_format: None,
                stencil_attachment_format: None,
            }),
            Options {
                in_flight_frames: 1,
                ..Options::default()
            },
        )
        .map_err(overlay)?;
        let ctx = egui::Context::default();
        let ppp = super::text_layout::text_scale(extent.width, extent.height);
        let size = egui::vec2(extent.width as f32, extent.height as f32) / ppp;
        let mut input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, size)),
            ..egui::RawInput::default()
        };
        if let Some(root) = input.viewports.get_mut(&egui::ViewportId::ROOT) {
            root.native_pixels_per_point = Some(ppp);
        }
        let output = ctx.run_ui(input, |ui| paint_all(ui.ctx()));
        let mut textures = output.textures_delta;
        let uploads = std::mem::take(&mut textures.set);
        // Nothing to free: the context ends with the shot.
        textures.clear();
        for (id, deltas) in uploads {
            for delta in &deltas {
                renderer
                    .set_texture(context.queue, commands.pool(), id, delta)
                    .map_err(overlay)?;
            }
        }
        let primitives = ctx.tessellate(output.shapes, output.pixels_per_point);
        Ok(Self {
            renderer,
            primitives,
            extent,
            pixels_per_point: output.pixels_per_point,
        })
    }

    /// Records the captions into `cmd`, inside a colour-only pass over the picture.
    pub fn record(&mut self, cmd: vk::CommandBuffer) -> Result<(), RenderError> {
        self.renderer
            .cmd_draw(cmd, self.extent, self.pixels_per_point, &self.primitives)
            .map_err(|e| RenderError::Overlay(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_read_as_the_command_line_asked() {
        assert_eq!(
            target_words(Target::RemovePercent(60.0), None),
            "60 % removed"
        );
        assert_eq!(
            target_words(Target::RemovePercent(100.0), None),
            "as far as possible"
        );
        assert_eq!(
            target_words(Target::KeepTriangles(500), None),
            "to 500 triangles"
        );
        assert_eq!(
            target_words(Target::ErrorOnly, Some(ErrorBound::DiagonalFraction(0.005))),
            "within the error bound, error ≤ 0.5 % of the diagonal"
        );
        assert_eq!(
            caption("original", 602, 1200),
            "original\n602 vertices, 1,200 triangles"
        );
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(1_742_128), "1,742,128");
        assert_eq!(grouped(871_414), "871,414");
    }
}

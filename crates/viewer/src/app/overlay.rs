//! What the window and `shot` paint over the viewports, laid out so that nothing covers
//! what it should not: the status line in a strip of its own at the bottom (the viewports
//! tile the area above it), each viewport's caption inside it, the heat-map legend inside
//! each heat-mapped viewport, and the help overlay above all of them. Text grows with the
//! picture (`text_scale`), so it stays readable on a large window or shot.

pub use super::text_layout::{base_layer, points, text_scale};
use crate::render::tiles::Rect;

use super::error_map::{self, Legend};
use super::labels;

/// Height of the status strip, in points.
pub const STATUS_POINTS: f32 = 22.0;

/// The status strip's height in pixels at `pixels_per_point`, at most a third of `height`.
pub fn status_strip(height: u32, pixels_per_point: f32) -> u32 {
    ((STATUS_POINTS * pixels_per_point).ceil() as u32).min(height / 3)
}

/// What is painted over the viewports. Rectangles are in pixels.
#[derive(Default)]
pub struct Overlay<'a> {
    /// Each viewport's rectangle and caption.
    pub captions: &'a [(Rect, String)],
    /// The heat-map legend and the viewports it is painted in.
    pub legend: Option<(Legend, &'a [Rect])>,
    /// The status line and its strip's height in pixels.
    pub status: Option<(&'a str, u32)>,
    /// The help text, shown over everything else.
    pub help: Option<&'a str>,
}

/// Paints `overlay` with `ctx` (captions, legends and status on the base layer, help above).
pub fn paint(ctx: &egui::Context, overlay: &Overlay<'_>) {
    let ppp = ctx.pixels_per_point();
    let painter = ctx.layer_painter(base_layer());
    labels::paint_on(&painter, overlay.captions, ppp);
    if let Some((legend, rects)) = &overlay.legend {
        for rect in rects.iter() {
            error_map::paint_legend(&painter, legend, points(rect, ppp));
        }
    }
    if let Some((status, strip)) = overlay.status {
        paint_status(&painter, ctx.content_rect(), status, strip as f32 / ppp);
    }
    if let Some(text) = overlay.help {
        let layer = egui::LayerId::new(egui::Order::Foreground, egui::Id::new("help"));
        paint_help(&ctx.layer_painter(layer), ctx.content_rect(), text);
    }
}

/// The help text in a dark box at the top-right corner of `screen`, over everything
/// painted before it (painted directly: an egui window would be invisible in the one frame
/// a `shot` lays out).
fn paint_help(painter: &egui::Painter, screen: egui::Rect, text: &str) {
    let galley = painter.layout_no_wrap(
        text.to_string(),
        egui::FontId::monospace(12.0),
        egui::Color32::from_gray(230),
    );
    let margin = 8.0;
    let size = galley.size() + egui::vec2(2.0 * margin, 2.0 * margin);
    let frame = egui::Rect::from_min_size(
        egui::pos2(screen.max.x - 6.0 - size.x, screen.min.y + 6.0),
        size,
    );
    painter.rect_filled(frame, 4.0, egui::Color32::from_rgb(27, 27, 30));
    painter.rect_stroke(
        frame,
        4.0,
        egui::Stroke::new(1.0, egui::Color32::from_gray(90)),
        egui::StrokeKind::Inside,
    );
    painter.galley(
        frame.min + egui::vec2(margin, margin),
        galley,
        egui::Color32::WHITE,
    );
}

/// The status line on a dark strip `height` points high along the bottom of `screen`,
/// cut at the strip's right end when it is longer than the window.
fn paint_status(painter: &egui::Painter, screen: egui::Rect, status: &str, height: f32) {
    let strip =
        egui::Rect::from_min_max(egui::pos2(screen.min.x, screen.max.y - height), screen.max);
    let painter = painter.with_clip_rect(strip);
    painter.rect_filled(strip, 0.0, egui::Color32::from_rgb(24, 24, 28));
    let galley = painter.layout_no_wrap(
        status.to_string(),
        egui::FontId::proportional(13.0),
        egui::Color32::from_gray(230),
    );
    let top = strip.center().y - galley.size().y / 2.0;
    painter.galley(
        egui::pos2(strip.min.x + 6.0, top),
        galley,
        egui::Color32::WHITE,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_grows_with_large_pictures_only() {
        assert_eq!(text_scale(1024, 720), 1.0);
        assert_eq!(text_scale(400, 300), 1.0);
        assert!((text_scale(1600, 1200) - 1200.0 / 720.0).abs() < 1e-6);
        assert_eq!(text_scale(10_000, 10_000), 3.0);
        assert_eq!(status_strip(720, 1.0), 22);
        assert_eq!(status_strip(30, 1.0), 10);
    }
}

//! Where viewport text goes and how large it is: the layer captions are painted on, the
//! text scale for a picture's size, a tile's rectangle in egui's points. Shared by the
//! captions (`labels`) and everything else painted over the viewports (`overlay`).

use crate::render::tiles::Rect;

/// The shared layer of everything painted on the viewports (captions, legends, status):
/// under every window, menu and dialog egui draws.
pub fn base_layer() -> egui::LayerId {
    egui::LayerId::new(egui::Order::Background, egui::Id::new("viewport text"))
}

/// How much larger than at 720 pixels text is drawn on a `width` × `height` picture: 1 up
/// to 720 pixels on the shorter side, proportionally above (at most 3).
pub fn text_scale(width: u32, height: u32) -> f32 {
    (width.min(height) as f32 / 720.0).clamp(1.0, 3.0)
}

/// `rect` (pixels) in points.
pub fn points(rect: &Rect, pixels_per_point: f32) -> egui::Rect {
    egui::Rect::from_min_size(
        egui::pos2(rect.x as f32, rect.y as f32) / pixels_per_point,
        egui::vec2(rect.width as f32, rect.height as f32) / pixels_per_point,
    )
}

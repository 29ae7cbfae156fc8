//! The error heat-map draw mode (`E`, `--mode error`): decimated viewports coloured by their
//! distance to the original (`metro::field::error_field`, interpolated between vertices), the
//! original drawn in a neutral grey, and a colour-ramp legend in model units and percent of
//! the bounding-box diagonal, painted with egui in the window and in `shot`.

use std::borrow::Cow;

use crate::mesh::{Attribute, Scene};
use crate::metro::field::{error_field, ErrorField};

use super::viewport::Viewport;

/// The colour ramp, cold to hot: blue, cyan, green, yellow, red (equal steps), the order
/// MeshLab's quality mapping and most heat-maps use.
const RAMP: [[f32; 3]; 5] = [
    [0.15, 0.30, 0.95],
    [0.10, 0.80, 0.90],
    [0.20, 0.80, 0.20],
    [0.95, 0.85, 0.10],
    [0.90, 0.10, 0.10],
];

/// The original's colour in the heat-map mode: grey, so that no ramp colour appears on it.
pub const NEUTRAL: [f32; 3] = [0.62, 0.62, 0.62];

/// Legend bar size in points, and its gap from the picture's edges.
const BAR: (f32, f32) = (150.0, 10.0);
const MARGIN: f32 = 8.0;

/// The colour of `t` in 0..=1 on the ramp (clamped).
pub fn ramp(t: f32) -> [f32; 3] {
    let x = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        1.0
    } * (RAMP.len() - 1) as f32;
    let i = (x.floor() as usize).min(RAMP.len() - 2);
    let f = x - i as f32;
    let (a, b) = (RAMP[i], RAMP[i + 1]);
    [0, 1, 2].map(|c| a[c] * (1.0 - f) + b[c] * f)
}

/// What the ramp spans: 0 to `max` model units, `max` being `diagonal` × a percentage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Legend {
    pub max: f64,
    pub diagonal: f64,
}

impl Legend {
    /// The legend for `fields` drawn together (one scale for every viewport).
    pub fn spanning<'a>(fields: impl IntoIterator<Item = &'a ErrorField>) -> Self {
        let mut legend = Self {
            max: 0.0,
            diagonal: 0.0,
        };
        for f in fields {
            legend.max = legend.max.max(f.max);
            legend.diagonal = legend.diagonal.max(f.diagonal);
        }
        legend
    }

    /// Where `distance` falls on the ramp (0: none; a scene without error is all cold).
    pub fn position(&self, distance: f64) -> f32 {
        if self.max > 0.0 {
            (distance / self.max) as f32
        } else {
            0.0
        }
    }

    /// `distance` as the legend writes it: model units, and percent of the diagonal.
    pub fn words(&self, distance: f64) -> String {
        let percent = if self.diagonal > 0.0 {
            distance / self.diagonal * 100.0
        } else {
            0.0
        };
        format!("{} ({percent:.2} %)", significant(distance))
    }
}

/// `x` with three significant digits, without an exponent for everyday sizes.
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return "0".into();
    }
    let digits = (2 - x.abs().log10().floor() as i32).clamp(0, 9) as usize;
    format!("{x:.digits$}")
}

/// A copy of `decimated` coloured by `field` on `legend`'s scale: per-vertex colours, no
/// texture (the lighting still shows the shape).
pub fn heat_scene(decimated: &Scene, field: &ErrorField, legend: &Legend) -> Scene {
    let mut scene = decimated.clone();
    for (model, distances) in scene.models.iter_mut().zip(&field.distances) {
        let colours = (0..model.positions.len())
            .map(|v| ramp(legend.position(distances.get(v).copied().map_or(0.0, f64::from))))
            .collect();
        model.colors = Some(Attribute::PerVertex(colours));
        model.texture = None;
    }
    scene
}

/// A copy of `scene` in the neutral grey: what the original looks like beside heat-maps.
pub fn neutral_scene(scene: &Scene) -> Scene {
    let mut scene = scene.clone();
    for model in &mut scene.models {
        model.colors = None;
        model.texture = None;
        model.diffuse = NEUTRAL;
    }
    scene
}

/// How the window draws a viewport's scene: in its own colours, in the heat-map mode's grey
/// (it shows the original), or heat-mapped on a legend of this maximum (its `f64` bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Look {
    Own,
    Neutral,
    Heat(u64),
}

/// The window's error fields, one per heat-mapped viewport, computed once per scene it shows
/// (viewport id and generation).
#[derive(Debug, Default)]
pub struct FieldCache {
    fields: Vec<(u64, u64, ErrorField)>,
}

/// True when `vp` shows a decimation of its original (not the original itself).
fn decimated(vp: &Viewport) -> bool {
    vp.last.is_some() || vp.lod().is_some()
}

impl FieldCache {
    /// Measures the heat-mapped viewports whose scene changed and forgets the others; the
    /// legend they share, if any viewport is heat-mapped.
    pub fn update(&mut self, viewports: &[Viewport]) -> Option<Legend> {
        let mapped = |vp: &&Viewport| vp.options.error_map && decimated(vp);
        self.fields.retain(|(id, generation, _)| {
            (viewports.iter().filter(mapped)).any(|v| v.id == *id && v.generation == *generation)
        });
        for vp in viewports.iter().filter(mapped) {
            if !self.fields.iter().any(|(id, _, _)| *id == vp.id) {
                let field = error_field(vp.original(), vp.scene());
                self.fields.push((vp.id, vp.generation, field));
            }
        }
        let any = viewports.iter().any(|vp| vp.options.error_map);
        any.then(|| Legend::spanning(self.fields.iter().map(|(_, _, f)| f)))
    }

    /// How `vp` is drawn, with `legend` from [`Self::update`].
    pub fn look(&self, vp: &Viewport, legend: Option<&Legend>) -> Look {
        match (vp.options.error_map, legend) {
            (true, Some(legend)) if decimated(vp) => Look::Heat(legend.max.to_bits()),
            (true, _) => Look::Neutral,
            (false, _) => Look::Own,
        }
    }

    /// The scene to upload for `vp` drawn with `look`.
    pub fn scene<'a>(&self, vp: &'a Viewport, look: Look) -> Cow<'a, Scene> {
        let field = self.fields.iter().find(|(id, _, _)| *id == vp.id);
        match (look, field) {
            (Look::Heat(bits), Some((_, _, field))) => {
                let legend = Legend {
                    max: f64::from_bits(bits),
                    diagonal: field.diagonal,
                };
                Cow::Owned(heat_scene(vp.scene(), field, &legend))
            }
            (Look::Neutral, _) | (Look::Heat(_), None) => Cow::Owned(neutral_scene(vp.scene())),
            (Look::Own, _) => Cow::Borrowed(vp.scene()),
        }
    }
}

/// Paints `legend` at the top right of `screen` (points): a title, the ramp as a bar, and
/// its ends and middle in model units and percent of the diagonal.
pub fn paint_legend(ctx: &egui::Context, legend: &Legend, screen: egui::Rect) {
    let layer = egui::LayerId::new(egui::Order::Middle, egui::Id::new("error legend"));
    let painter = ctx.layer_painter(layer);
    let font = egui::FontId::proportional(11.0);
    let text = egui::Color32::from_gray(235);
    let title = painter.layout_no_wrap("distance to the original".into(), font.clone(), text);
    let zero = painter.layout_no_wrap("0".into(), font.clone(), text);
    let top = painter.layout_no_wrap(legend.words(legend.max), font.clone(), text);
    let line = title.size().y;
    let width = BAR
        .0
        .max(title.size().x)
        .max(zero.size().x + top.size().x + 12.0);
    let height = line + 4.0 + BAR.1 + 4.0 + line;
    let frame = egui::Rect::from_min_size(
        egui::pos2(screen.max.x - MARGIN - width, screen.min.y + MARGIN),
        egui::vec2(width, height),
    );
    painter.rect_filled(frame.expand(4.0), 3.0, egui::Color32::from_black_alpha(170));
    painter.galley(frame.min, title, text);
    let bar = egui::Rect::from_min_size(
        egui::pos2(frame.min.x, frame.min.y + line + 4.0),
        egui::vec2(width, BAR.1),
    );
    let mut mesh = egui::Mesh::default();
    let steps = 32;
    for i in 0..=steps {
        let t = i as f32 / steps as f32;
        let [r, g, b] = ramp(t).map(|c| (c * 255.0).round() as u8);
        let colour = egui::Color32::from_rgb(r, g, b);
        let x = bar.min.x + t * bar.width();
        mesh.colored_vertex(egui::pos2(x, bar.min.y), colour);
        mesh.colored_vertex(egui::pos2(x, bar.max.y), colour);
        if i > 0 {
            let k = 2 * i;
            mesh.add_triangle(k - 2, k - 1, k);
            mesh.add_triangle(k - 1, k + 1, k);
        }
    }
    painter.add(egui::Shape::mesh(mesh));
    // 0 under the bar's left end, the maximum under its right end.
    let below = bar.max.y + 4.0;
    painter.galley(egui::pos2(bar.min.x, below), zero, text);
    painter.galley(egui::pos2(bar.max.x - top.size().x, below), top, text);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_runs_from_blue_to_red() {
        assert_eq!(ramp(0.0), RAMP[0]);
        assert_eq!(ramp(1.0), RAMP[4]);
        assert_eq!(ramp(7.0), RAMP[4]);
        assert_eq!(ramp(-1.0), RAMP[0]);
        assert_eq!(ramp(0.5), RAMP[2]);
        let mid = ramp(0.125);
        assert!(mid[2] > mid[0], "an eighth is still cold: {mid:?}");
    }

    #[test]
    fn legend_words_give_units_and_percent() {
        let legend = Legend {
            max: 0.0123,
            diagonal: 2.0,
        };
        assert_eq!(legend.words(0.0123), "0.0123 (0.61 %)");
        assert_eq!(significant(12.345), "12.3");
        assert_eq!(significant(0.0), "0");
        assert_eq!(legend.position(0.0123), 1.0);
    }
}

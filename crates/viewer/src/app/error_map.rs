//! The error heat-map draw mode (`E`, `--mode error`): decimated viewports coloured by their
//! distance to the original (`metro::field::error_field`, interpolated between vertices), the
//! original drawn in a neutral grey, and a colour-ramp legend in model units and percent of
//! the bounding-box diagonal, painted with egui in the window and in `shot`.

use std::borrow::Cow;

use decimate_core::mesh::{Attribute, Scene};
use decimate_core::metro::field::ErrorField;

use super::jobs;
use super::viewport::Viewport;
use super::worker::{Job, Poll};

/// The colour ramp, small to large: viridis (dark purple, blue, teal, green, yellow) in nine
/// equal steps — perceptually uniform, readable in grey and by colour-blind eyes.
const RAMP: [[f32; 3]; 9] = [
    [0.267, 0.004, 0.329],
    [0.278, 0.173, 0.478],
    [0.2314, 0.3176, 0.5451],
    [0.173, 0.443, 0.557],
    [0.129, 0.565, 0.553],
    [0.153, 0.678, 0.506],
    [0.361, 0.784, 0.388],
    [0.667, 0.863, 0.196],
    [0.992, 0.906, 0.145],
];

/// The original's colour in the heat-map mode: grey, so that no ramp colour appears on it.
pub const NEUTRAL: [f32; 3] = [0.62, 0.62, 0.62];

/// Legend bar size in points, and its gap from the viewport's edges.
const BAR: (f32, f32) = (170.0, 10.0);
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

/// Share of the distances below the ramp's hot end: the largest distances are usually a few
/// vertices (a spike, a border), and a ramp ending at them would paint everything else in one
/// cold colour (docs/design.md#error-map).
pub const RAMP_PERCENTILE: f64 = 0.99;

/// What the ramp spans: 0 to `top` model units (the hot end: that far or farther), `max`
/// being the largest distance to the input (metro's, as `d` and `--measure` say it), and
/// `diagonal` the original's bounding-box diagonal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Legend {
    pub top: f64,
    pub max: f64,
    pub diagonal: f64,
}

impl Legend {
    /// The legend for `fields` drawn together (one scale for every viewport): the ramp ends
    /// at the [`RAMP_PERCENTILE`] of their distances (at the largest, if that is 0).
    pub fn spanning<'a>(fields: impl IntoIterator<Item = &'a ErrorField>) -> Self {
        let mut legend = Self {
            top: 0.0,
            max: 0.0,
            diagonal: 0.0,
        };
        let mut all: Vec<f32> = Vec::new();
        for f in fields {
            legend.max = legend.max.max(f.max);
            legend.diagonal = legend.diagonal.max(f.diagonal);
            all.extend(f.distances.iter().flatten().copied());
        }
        if !all.is_empty() {
            let k = ((all.len() - 1) as f64 * RAMP_PERCENTILE).round() as usize;
            let (_, &mut nth, _) = all.select_nth_unstable_by(k, f32::total_cmp);
            legend.top = f64::from(nth);
        }
        if legend.top <= 0.0 {
            legend.top = legend.max;
        }
        legend
    }

    /// This legend with `max` as its largest distance (metro's maximum, measured apart from
    /// the field's vertex distances); the ramp keeps its hot end, at most `max`.
    pub fn with_max(self, max: f64) -> Self {
        Self {
            top: if max > 0.0 {
                self.top.min(max)
            } else {
                self.top
            },
            max,
            ..self
        }
    }

    /// Where `distance` falls on the ramp (0: none; a scene without error is all cold).
    pub fn position(&self, distance: f64) -> f32 {
        if self.top > 0.0 {
            (distance / self.top) as f32
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

/// A tick's value: three significant digits at most, no trailing zeros ("0.05", "0.1").
fn tick_words(x: f64) -> String {
    let words = significant(x);
    if words.contains('.') {
        words
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    } else {
        words
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
/// (it shows the original), or heat-mapped on a ramp ending at this distance (its `f64` bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Look {
    Own,
    Neutral,
    Heat(u64),
}

/// A heat-mapped viewport's error field and metro's maximum distance (the legend's `max`).
type Measured = (ErrorField, f64);

/// The window's error fields, one per heat-mapped viewport, measured once per scene it shows
/// (viewport id and generation) by a worker job, one at a time: a frame never waits for
/// one, and a viewport is drawn in the neutral grey until its field arrives.
#[derive(Default)]
pub struct FieldCache {
    /// Viewport id, generation, field, and metro's maximum distance (the legend's `max`).
    fields: Vec<(u64, u64, ErrorField, f64)>,
    /// The field being measured: viewport id, generation, job.
    pending: Option<(u64, u64, Job<Measured>)>,
    /// The scene whose measurement was cancelled or failed: not measured again until it
    /// changes (or `E` is pressed again).
    stopped: Option<(u64, u64)>,
}

/// True when `vp` shows a decimation of its original (not the original itself).
fn decimated(vp: &Viewport) -> bool {
    vp.last.is_some() || vp.lod().is_some()
}

/// True when `vp` is heat-mapped and shows a decimation: it needs a field.
fn mapped(vp: &&Viewport) -> bool {
    vp.options.error_map && decimated(vp)
}

impl FieldCache {
    /// Forgets the fields no viewport shows any more, takes the field measured if its job
    /// ended, and — when the view is `resting` (no geomorph playing, no camera move) —
    /// starts measuring the next heat-mapped viewport that lacks one. Never waits. The
    /// legend the fields share, once one has arrived.
    pub fn update(&mut self, viewports: &[Viewport], resting: bool) -> Option<Legend> {
        let wanted = |id: u64, generation: u64| {
            (viewports.iter().filter(mapped)).any(|v| v.id == id && v.generation == generation)
        };
        self.fields
            .retain(|(id, generation, _, _)| wanted(*id, *generation));
        if self
            .stopped
            .is_some_and(|(id, generation)| !wanted(id, generation))
        {
            self.stopped = None;
        }
        if let Some((id, generation, job)) = &self.pending {
            let (id, generation) = (*id, *generation);
            if !wanted(id, generation) {
                // The scene it measures is gone (a new level, E off): its result is of no use.
                job.cancel();
                self.pending = None;
            } else {
                match job.poll() {
                    Poll::Running => {}
                    Poll::Done((field, max)) => {
                        self.fields.push((id, generation, field, max));
                        self.pending = None;
                    }
                    Poll::Failed(e) => {
                        eprintln!("decimate: {e}");
                        self.stopped = Some((id, generation));
                        self.pending = None;
                    }
                    Poll::Cancelled => self.pending = None,
                }
            }
        }
        if self.pending.is_none() && resting {
            let next = viewports.iter().enumerate().find(|(_, vp)| {
                mapped(vp)
                    && !self.fields.iter().any(|(id, _, _, _)| *id == vp.id)
                    && self.stopped != Some((vp.id, vp.generation))
            });
            if let Some((n, vp)) = next {
                let what = format!("viewport {}: measuring the heat-map", n + 1);
                let job = jobs::field(what, vp.original().clone(), vp.scene().clone());
                self.pending = Some((vp.id, vp.generation, job));
            }
        }
        let any = viewports.iter().any(|vp| vp.options.error_map);
        (any && !self.fields.is_empty()).then(|| {
            let legend = Legend::spanning(self.fields.iter().map(|(_, _, f, _)| f));
            legend.with_max(self.fields.iter().map(|f| f.3).fold(0.0, f64::max))
        })
    }

    /// The status line's words while a field is measured.
    pub fn status(&self) -> Option<String> {
        self.pending.as_ref().map(|(_, _, job)| job.status())
    }

    /// Whether a field is being measured.
    pub fn busy(&self) -> bool {
        self.pending.is_some()
    }

    /// `Esc` while a field is measured: stops it (its viewport stays grey until its scene
    /// changes or `E` is pressed again); the status line's words, `None` when none ran.
    pub fn cancel(&mut self) -> Option<String> {
        let (id, generation, job) = self.pending.take()?;
        job.cancel();
        self.stopped = Some((id, generation));
        Some(format!("cancelled: {}", job.what))
    }

    /// How `vp` is drawn, with `legend` from [`Self::update`]: heat-mapped once its field
    /// has arrived, grey until then.
    pub fn look(&self, vp: &Viewport, legend: Option<&Legend>) -> Look {
        let has_field = self.fields.iter().any(|(id, _, _, _)| *id == vp.id);
        match (vp.options.error_map, legend) {
            (true, Some(legend)) if decimated(vp) && has_field => Look::Heat(legend.top.to_bits()),
            (true, _) => Look::Neutral,
            (false, _) => Look::Own,
        }
    }

    /// The scene to upload for `vp` drawn with `look` on `legend`.
    pub fn scene<'a>(
        &self,
        vp: &'a Viewport,
        look: Look,
        legend: Option<&Legend>,
    ) -> Cow<'a, Scene> {
        let field = self.fields.iter().find(|(id, _, _, _)| *id == vp.id);
        match (look, field, legend) {
            (Look::Heat(_), Some((_, _, field, _)), Some(legend)) => {
                Cow::Owned(heat_scene(vp.scene(), field, legend))
            }
            (Look::Neutral | Look::Heat(_), _, _) => Cow::Owned(neutral_scene(vp.scene())),
            (Look::Own, _, _) => Cow::Borrowed(vp.scene()),
        }
    }
}

/// Tick values for a scale from 0 to `top`: 0 and multiples of the largest 1, 2, 2.5 or 5
/// × 10^k step that still gives three ticks (so three or four in all).
pub fn ticks(top: f64) -> Vec<f64> {
    if !(top > 0.0 && top.is_finite()) {
        return vec![0.0];
    }
    let mut power = 10f64.powf((top / 2.0).log10().floor());
    let mut step = power;
    for _ in 0..2 {
        for m in [1.0, 2.0, 2.5, 5.0] {
            if m * power <= top / 2.0 {
                step = m * power;
            }
        }
        power *= 10.0;
    }
    let count = (top / step + 1e-9).floor() as usize;
    (0..=count).map(|i| i as f64 * step).collect()
}

/// Paints `legend` at the top-right corner of `viewport` (a heat-mapped viewport, in points,
/// clipped to it): the units, the ramp with three or four ticks in model units, and the
/// hot end and largest distance in model units and percent of the diagonal.
pub fn paint_legend(painter: &egui::Painter, legend: &Legend, viewport: egui::Rect) {
    let painter = painter.with_clip_rect(viewport);
    let font = egui::FontId::proportional(11.0);
    let text = egui::Color32::from_gray(235);
    let lay = |s: String| painter.layout_no_wrap(s, font.clone(), text);
    let title = lay("distance to the input: model units (% of bbox diagonal)".into());
    let end = if legend.top < legend.max { "≥ " } else { "" };
    let summary = lay(format!(
        "top {end}{}, max {}",
        legend.words(legend.top),
        legend.words(legend.max)
    ));
    let line = title.size().y;
    let width = BAR.0.max(title.size().x).max(summary.size().x);
    let height = line + 4.0 + BAR.1 + 2.0 + line + 2.0 + line;
    let frame = egui::Rect::from_min_size(
        egui::pos2(viewport.max.x - MARGIN - width, viewport.min.y + MARGIN),
        egui::vec2(width, height),
    );
    painter.rect_filled(frame.expand(4.0), 3.0, egui::Color32::from_black_alpha(170));
    painter.galley(frame.min, title, text);
    let bar = egui::Rect::from_min_size(
        egui::pos2(frame.min.x, frame.min.y + line + 4.0),
        egui::vec2(width, BAR.1),
    );
    painter.add(egui::Shape::mesh(ramp_mesh(bar)));
    let tick_y = bar.max.y + 2.0;
    for value in ticks(legend.top) {
        let x = bar.min.x + legend.position(value).clamp(0.0, 1.0) * bar.width();
        painter.line_segment(
            [egui::pos2(x, bar.min.y), egui::pos2(x, bar.max.y + 2.0)],
            egui::Stroke::new(1.0, text),
        );
        let label = lay(tick_words(value));
        let left = (x - label.size().x / 2.0).clamp(bar.min.x, bar.max.x - label.size().x);
        painter.galley(egui::pos2(left, tick_y), label, text);
    }
    painter.galley(egui::pos2(frame.min.x, tick_y + line + 2.0), summary, text);
}

/// The ramp as a horizontal strip filling `bar`, cold on the left.
fn ramp_mesh(bar: egui::Rect) -> egui::Mesh {
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
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_runs_from_dark_purple_to_yellow_getting_lighter() {
        assert_eq!(ramp(0.0), RAMP[0]);
        assert_eq!(ramp(1.0), RAMP[8]);
        assert_eq!(ramp(7.0), RAMP[8]);
        assert_eq!(ramp(-1.0), RAMP[0]);
        assert_eq!(ramp(0.5), RAMP[4]);
        // Perceptual: lightness rises all the way (a rainbow's does not).
        let luma = |c: [f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        for i in 1..=64 {
            let (a, b) = (ramp((i - 1) as f32 / 64.0), ramp(i as f32 / 64.0));
            assert!(luma(b) > luma(a), "lightness falls at {i}/64");
        }
    }

    #[test]
    fn three_or_four_round_ticks_from_zero() {
        assert_eq!(ticks(1.0), vec![0.0, 0.5, 1.0]);
        assert_eq!(ticks(0.0123).len(), 3);
        for top in [0.0007, 0.0123, 0.458, 0.582, 1.0, 3.7, 99.0, 1234.5] {
            let t = ticks(top);
            assert!((3..=5).contains(&t.len()), "{top}: {t:?}");
            assert_eq!(t[0], 0.0);
            assert!(
                *t.last().unwrap_or(&f64::MAX) <= top * (1.0 + 1e-9),
                "{top}: {t:?}"
            );
        }
        assert_eq!(ticks(0.0), vec![0.0]);
        assert_eq!(tick_words(0.05), "0.05");
        assert_eq!(tick_words(0.1), "0.1");
        assert_eq!(tick_words(250.0), "250");
    }

    #[test]
    fn legend_words_give_units_and_percent() {
        let legend = Legend {
            top: 0.0123,
            max: 0.02,
            diagonal: 2.0,
        };
        assert_eq!(legend.words(0.0123), "0.0123 (0.61 %)");
        assert_eq!(significant(12.345), "12.3");
        assert_eq!(significant(0.0), "0");
        assert_eq!(legend.position(0.0123), 1.0);
    }

    #[test]
    fn the_ramp_ends_at_the_99th_percentile_unless_that_is_zero() {
        let field = |distances: Vec<f32>| ErrorField {
            max: distances.iter().copied().fold(0.0, f32::max).into(),
            distances: vec![distances],
            diagonal: 1.0,
        };
        // 1000 distances 0.001 … 1.0: the hot end at the 990th.
        let spread = field((1..=1000).map(|i| i as f32 / 1000.0).collect());
        let legend = Legend::spanning([&spread]);
        assert!((legend.top - 0.990).abs() < 1e-6, "{}", legend.top);
        assert!((legend.max - 1.0).abs() < 1e-6);
        // One vertex moved among 100 unmoved: the ramp ends at it.
        let mut one = vec![0.0; 100];
        one[7] = 0.5;
        let legend = Legend::spanning([&field(one)]);
        assert_eq!(legend.top, 0.5);
    }

    /// A wavy 21×21 grid (441 vertices), so that a decimation moves the surface.
    fn waves() -> Scene {
        let m = decimate_core::mesh::shapes::height_grid(20, |i, j| {
            (i as f32 * 0.7).sin() * (j as f32 * 0.5).cos()
        });
        Scene { models: vec![m] }
    }

    /// A controller with viewport 1 decimated by key `9` and then heat-mapped by `E`.
    fn heat_mapped() -> super::super::controller::ViewportController {
        use super::super::controller::ViewportController;
        use super::super::menu::{action_for_key, Key};
        use decimate_core::decimate::Params;
        let mut c = ViewportController::new(waves(), Params::default(), 800, 600);
        for k in ['9', 'E'] {
            let action = action_for_key(Key::Char(k)).unwrap_or_else(|| panic!("{k} unbound"));
            c.dispatch(action);
            c.wait();
        }
        assert!(decimated(c.current_viewport()) && c.current_viewport().options.error_map);
        c
    }

    /// Frames (updates at rest) until the legend shows, at most 30 s.
    fn frames_until_legend(fields: &mut FieldCache, viewports: &[Viewport]) -> Legend {
        let start = std::time::Instant::now();
        loop {
            if let Some(legend) = fields.update(viewports, true) {
                return legend;
            }
            assert!(
                start.elapsed() < std::time::Duration::from_secs(30),
                "the field never arrived"
            );
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
    }

    #[test]
    fn pressing_e_starts_a_job_and_the_field_arrives_with_the_legend() {
        let c = heat_mapped();
        let vp = c.current_viewport();
        let mut fields = FieldCache::default();
        // The frame E is pressed in: it starts the measurement and draws grey, no legend.
        assert_eq!(fields.update(c.viewports(), true), None);
        assert!(fields.busy(), "the field is measured by a job");
        let status = fields.status().unwrap_or_default();
        assert!(
            status.starts_with("viewport 1: measuring the heat-map [")
                && status.ends_with("Esc cancels"),
            "{status}"
        );
        assert_eq!(fields.look(vp, None), Look::Neutral);
        let legend = frames_until_legend(&mut fields, c.viewports());
        assert!(!fields.busy() && fields.status().is_none());
        assert!(legend.max > 0.0 && legend.top > 0.0, "{legend:?}");
        assert_eq!(
            fields.look(vp, Some(&legend)),
            Look::Heat(legend.top.to_bits())
        );
        // The original beside it stays grey; nothing is measured again for the same level.
        assert_eq!(fields.update(c.viewports(), true), Some(legend));
        assert!(!fields.busy());
        let heat = fields.scene(vp, fields.look(vp, Some(&legend)), Some(&legend));
        assert!(matches!(
            heat.models[0].colors,
            Some(Attribute::PerVertex(ref c)) if c.len() == vp.scene().models[0].positions.len()
        ));
    }

    #[test]
    fn d_the_legend_and_shots_measure_say_one_max_distance_to_the_input() {
        use super::super::level_error::LevelError;
        use super::super::menu::{action_for_key, Key};
        let mut c = heat_mapped();
        let mut fields = FieldCache::default();
        fields.update(c.viewports(), true);
        let legend = frames_until_legend(&mut fields, c.viewports());
        if let Some(d) = action_for_key(Key::Char('d')) {
            c.dispatch(d);
        }
        c.wait();
        c.poll();
        let vp = c.current_viewport();
        let d = vp.error().copied();
        let d = d.unwrap_or_else(|| panic!("d measured nothing: {}", c.message));
        // shot --measure's caption and summary, and shot's legend, for the same level.
        let level = vp.scene().clone();
        let measured = LevelError::measure(vp.original(), &level);
        let measured = measured.unwrap_or_else(|e| panic!("{e}"));
        let (_, _, shot_legend) = super::super::shot::heat_mapped(
            vp.original(),
            vec![level],
            true,
            &[Ok(Some(measured))],
        );
        assert!(d.max > 0.0, "{d:?}");
        assert_eq!(legend.max, d.max, "window legend against d");
        assert_eq!(measured.max, d.max, "--measure against d");
        assert_eq!(
            shot_legend.map(|l| l.max),
            Some(d.max),
            "shot's legend against d"
        );
        assert!(legend.top <= legend.max, "{legend:?}");
    }

    #[test]
    fn no_field_is_measured_while_the_view_moves_and_esc_stops_one() {
        let c = heat_mapped();
        let mut fields = FieldCache::default();
        assert_eq!(fields.update(c.viewports(), false), None);
        assert!(!fields.busy(), "a geomorph or a drag plays: no job yet");
        fields.update(c.viewports(), true);
        assert!(fields.busy());
        let said = fields.cancel().unwrap_or_default();
        assert_eq!(said, "cancelled: viewport 1: measuring the heat-map");
        assert!(
            fields.cancel().is_none(),
            "nothing left to cancel: Esc quits"
        );
        assert_eq!(fields.update(c.viewports(), true), None);
        assert!(
            !fields.busy(),
            "a cancelled level is not measured again by itself"
        );
        // E off and on again asks for it.
        let mut off = c.viewports().to_vec();
        off[0].options.error_map = false;
        assert_eq!(fields.update(&off, true), None);
        fields.update(c.viewports(), true);
        assert!(fields.busy());
        frames_until_legend(&mut fields, c.viewports());
    }
}

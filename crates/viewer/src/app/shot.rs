//! The `shot` action: render the scene offscreen — no window, no display — with exactly the
//! viewer's renderer, viewports tiled as in the viewer (the first shows the original scene,
//! the others the decimated one, each with its own target when `-p 60,80,90` lists several),
//! captioned (with `--measure`, each decimated viewport's metro error too), and write a PNG
//! through a temporary file and a rename.

use std::path::{Path, PathBuf};

use crate::render::camera::Camera;
use crate::render::commands::Commands;
use crate::render::context::{Context, DevicePreference};
use crate::render::draw::DrawOptions;
use crate::render::draw::ViewportDraw;
use crate::render::gpu_mesh::GpuScene;
use crate::render::offscreen::{OffscreenTarget, RgbaImage, OFFSCREEN_FORMAT};
use crate::render::pipeline::Pipelines;
use crate::render::texture::Textures;
use crate::render::tiles::tiles;
use crate::render::RenderError;
use decimate_core::decimate::{simplify_scene, Params, Report, Target};
use decimate_core::io::texture_image;
use decimate_core::mesh::Scene;

use super::counts::Counts;
use super::error_map::{self, Legend};
use super::labels::{self, HeadlessCaptions};
use super::level_error::LevelError;
use super::overlay::{self, Overlay};

/// What can go wrong taking a shot.
/// Options of the `shot` action.
#[derive(Debug, Clone, PartialEq)]
pub struct ShotOptions {
    pub width: u32,
    pub height: u32,
    /// 1–4 viewports: the first shows the original, the others the decimated scene.
    pub viewports: u32,
    /// What each viewport draws (`--mode`).
    pub modes: DrawOptions,
    /// Captions on the viewports (`--labels` / `--no-labels`); by default with more than one.
    pub labels: Option<bool>,
    /// Each decimated viewport's caption says its metro error against the original
    /// (`--measure`; turns the captions on).
    pub measure: bool,
    /// One target per decimated viewport (`-p 60,80,90`); empty when one target was given.
    pub targets: Vec<Target>,
    /// Where relative texture names are read from: the input file's folder.
    pub texture_dir: PathBuf,
    /// Samples per pixel for anti-aliasing (`--msaa`; 1: off), as many as the device offers.
    pub msaa: u32,
    /// A status line in the window's strip below the viewports, as the viewer shows it.
    pub status: Option<String>,
    /// The viewer's help overlay over the picture.
    pub help: bool,
    /// The viewports' background colour, RGB from 0 to 1 (`--background`); the viewer's own
    /// when `None`.
    pub background: Option<[f32; 3]>,
}

impl Default for ShotOptions {
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            viewports: 1,
            modes: DrawOptions::default(),
            labels: None,
            measure: false,
            targets: Vec::new(),
            texture_dir: PathBuf::from("."),
            msaa: crate::render::pipeline::DEFAULT_MSAA,
            status: None,
            help: false,
            background: None,
        }
    }
}

#[derive(Debug, thiserror::Error)]
pub enum ShotError {
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error("{file}: {source}")]
    Write {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{file}: PNG encoding failed: {source}")]
    Encode {
        file: PathBuf,
        #[source]
        source: png::EncodingError,
    },
}

/// What viewport `i` of `count` shows: `None` for the original, else the parameters of its
/// decimation. Viewport 1 shows the original and the others the decimated scene, each with
/// its own target from `targets` (the last one repeated) or `params`' own; a single viewport
/// with a target shows the decimated scene (otherwise the target would be ignored).
pub fn viewport_params(
    count: usize,
    params: Option<&Params>,
    targets: &[Target],
) -> Vec<Option<Params>> {
    (0..count)
        .map(|i| {
            let params = params?;
            if count > 1 && i == 0 {
                return None;
            }
            let target = targets.get(i.saturating_sub(1)).or(targets.last());
            Some(Params {
                target: target.copied().unwrap_or(params.target),
                ..*params
            })
        })
        .collect()
}

/// A decimated copy of the scene on the GPU, with its report and caption.
struct Decimated {
    params: Params,
    gpu: GpuScene,
    report: Report,
    caption: String,
}

/// The decimated copies to draw, in the heat-map's colours when `heat` (the legend spans
/// every copy), with the original to draw beside them (neutral grey in the heat-map mode).
/// The legend's largest distance is metro's (`measured`, one per copy), as the captions say.
pub(crate) fn heat_mapped(
    scene: &Scene,
    copies: Vec<Scene>,
    heat: bool,
    measured: &[Measured],
) -> (Option<Scene>, Vec<Scene>, Option<Legend>) {
    if !heat {
        return (None, copies, None);
    }
    let fields: Vec<_> = (copies.iter())
        .map(|copy| decimate_core::metro::field::error_field(scene, copy))
        .collect();
    let mut legend = Legend::spanning(&fields);
    let maxes = measured.iter().filter_map(|m| m.as_ref().ok()?.as_ref());
    if let Some(max) = maxes.map(|e| e.max).reduce(f64::max) {
        legend = legend.with_max(max);
    }
    let coloured = (copies.iter().zip(&fields))
        .map(|(copy, field)| error_map::heat_scene(copy, field, &legend))
        .collect();
    (
        Some(error_map::neutral_scene(scene)),
        coloured,
        Some(legend),
    )
}

/// A decimated copy's metro error against the original, when measured (`--measure` or the
/// heat-map): `Ok(None)` when not asked for, `Err` saying why it could not be measured.
pub type Measured = Result<Option<LevelError>, String>;

/// A picture of `scene` and, when `params` is given, of its decimated copies (see
/// [`viewport_params`]); their reports in viewport order. Every viewport uses the same camera,
/// framed on the original. Captions (`labels`, by default with more than one viewport) say
/// what each viewport shows.
pub fn render(
    scene: &Scene,
    options: &ShotOptions,
    params: Option<&Params>,
    device: DevicePreference,
) -> Result<(RgbaImage, Vec<Report>), RenderError> {
    let (image, reports, _) = render_measured(scene, options, params, device)?;
    Ok((image, reports))
}

/// [`render`], with each decimated copy's metro error too (see [`Measured`]), in the order
/// of the reports: the figure its caption and the legend show.
pub fn render_measured(
    scene: &Scene,
    options: &ShotOptions,
    params: Option<&Params>,
    device: DevicePreference,
) -> Result<(RgbaImage, Vec<Report>, Vec<Measured>), RenderError> {
    let context = Context::new(&[], false, device)?;
    let commands = Commands::new(&context)?;
    let (pipelines, target) = offscreen(&context, options)?;
    let draw = options.modes;
    let mut textures = Textures::new(
        &context,
        pipelines.texture_layout,
        texture_image::reader(&options.texture_dir),
    )?;
    let (rects, strip) = layout(options);
    let shown = viewport_params(rects.len(), params, &options.targets);
    let made = decimate_each(scene, &shown);
    let measured = measure_each(scene, &made, options.measure || draw.error_map);
    let copies = made.iter().map(|(_, copy, _)| copy.clone()).collect();
    let (neutral, drawn, legend) = heat_mapped(scene, copies, draw.error_map, &measured);
    let uploader = Uploader {
        context: &context,
        commands: &commands,
        layers: draw.layers(),
    };
    let original = uploader.one(&mut textures, neutral.as_ref().unwrap_or(scene))?;
    let captioned = captioned(made, &measured, options.measure);
    let decimated = uploader.decimated(&mut textures, captioned, &drawn)?;
    let camera = Camera::framing(original.bounds);
    let shots = Shots {
        original: (&original, caption_of_original(scene)),
        decimated: &decimated,
        camera: &camera,
        options: draw,
    };
    let (views, captions) = shots.views(&rects, &shown);
    let labelled = options.labels.unwrap_or(rects.len() > 1 || options.measure);
    let heat: Vec<_> = (rects.iter().zip(&shown))
        .filter(|(_, p)| p.is_some())
        .map(|(r, _)| *r)
        .collect();
    let help = options.help.then(super::menu::key_help);
    let painted = Overlay {
        captions: if labelled { &captions } else { &[] },
        legend: legend.map(|l| (l, heat.as_slice())),
        status: (options.status.as_deref()).map(|s| (s, strip)),
        help: help.as_deref(),
    };
    let painting = labelled || legend.is_some() || strip > 0 || help.is_some();
    let overlay = painting.then_some(&painted);
    let image = draw_and_read(&context, &commands, &pipelines, &target, &views, overlay)?;
    let reports = decimated.into_iter().map(|d| d.report).collect();
    Ok((image, reports, measured))
}

/// The original's caption: its counts.
fn caption_of_original(scene: &Scene) -> String {
    let counts = Counts::of(scene);
    labels::caption("original", counts.vertices, counts.triangles)
}

/// What a shot's viewports draw from: the original (with its caption), the decimated
/// copies, one camera and the draw modes.
struct Shots<'a> {
    original: (&'a GpuScene, String),
    decimated: &'a [Decimated],
    camera: &'a Camera,
    options: DrawOptions,
}

impl<'a> Shots<'a> {
    /// Each viewport's draw and caption: the copy its params made, or the original.
    fn views(
        &self,
        rects: &[crate::render::tiles::Rect],
        shown: &[Option<Params>],
    ) -> (
        Vec<ViewportDraw<'a>>,
        Vec<(crate::render::tiles::Rect, String)>,
    ) {
        (rects.iter().zip(shown))
            .map(|(&rect, p)| {
                let d = p.and_then(|p| self.decimated.iter().find(|d| d.params == p));
                let view = ViewportDraw {
                    rect,
                    scene: d.map_or(self.original.0, |d| &d.gpu),
                    camera: self.camera,
                    options: self.options,
                    morph: 1.0,
                };
                let caption = d.map_or(&self.original.1, |d| &d.caption).clone();
                (view, (rect, caption))
            })
            .unzip()
    }
}

/// Each decimated copy in `made` measured against `scene` when `wanted` (see [`Measured`]).
fn measure_each(scene: &Scene, made: &[(Params, Scene, Report)], wanted: bool) -> Vec<Measured> {
    (made.iter())
        .map(|(_, copy, _)| match wanted {
            true => LevelError::measure(scene, copy).map(Some),
            false => Ok(None),
        })
        .collect()
}

/// Each copy's params, caption (with its `measured` line when `measure`) and report.
fn captioned(
    made: Vec<(Params, Scene, Report)>,
    measured: &[Measured],
    measure: bool,
) -> Vec<(Params, String, Report)> {
    (made.into_iter().zip(measured))
        .map(|((params, copy, report), m)| {
            let caption = caption_of(&copy, &params, measure.then_some(m));
            (params, caption, report)
        })
        .collect()
}

/// The pipelines and the picture `options` ask for (size, samples, background).
fn offscreen(
    context: &std::sync::Arc<Context>,
    options: &ShotOptions,
) -> Result<(Pipelines, OffscreenTarget), RenderError> {
    let pipelines = Pipelines::with_samples(context, OFFSCREEN_FORMAT, options.msaa)?;
    let mut target =
        OffscreenTarget::with_samples(context, options.width, options.height, pipelines.samples)?;
    if let Some([r, g, b]) = options.background {
        target.background = [r, g, b, 1.0];
    }
    Ok((pipelines, target))
}

/// What uploads a shot's scenes.
struct Uploader<'a> {
    context: &'a std::sync::Arc<Context>,
    commands: &'a Commands,
    layers: crate::render::mesh_data::Layers,
}

impl Uploader<'_> {
    /// One scene on the GPU.
    fn one(&self, textures: &mut Textures, scene: &Scene) -> Result<GpuScene, RenderError> {
        GpuScene::upload(self.context, self.commands, textures, scene, self.layers)
    }

    /// The decimated copies on the GPU, each drawn as `drawn` says (its heat-mapped version,
    /// or itself), with its params, caption and report.
    fn decimated(
        &self,
        textures: &mut Textures,
        made: Vec<(Params, String, Report)>,
        drawn: &[Scene],
    ) -> Result<Vec<Decimated>, RenderError> {
        let mut decimated = Vec::with_capacity(made.len());
        for ((params, caption, report), shown_copy) in made.into_iter().zip(drawn) {
            let gpu = self.one(textures, shown_copy)?;
            decimated.push(Decimated {
                params,
                gpu,
                report,
                caption,
            });
        }
        Ok(decimated)
    }
}

/// The viewports' rectangles, tiled over what the status strip (when there is a status
/// line) leaves, and the strip's height.
fn layout(options: &ShotOptions) -> (Vec<crate::render::tiles::Rect>, u32) {
    let ppp = overlay::text_scale(options.width, options.height);
    let strip = (options.status.as_ref()).map_or(0, |_| overlay::status_strip(options.height, ppp));
    let rects = tiles(
        options.viewports as usize,
        options.width,
        options.height - strip,
    );
    (rects, strip)
}

/// `scene` decimated once for each distinct parameter set of `shown`, with the reports.
fn decimate_each(scene: &Scene, shown: &[Option<Params>]) -> Vec<(Params, Scene, Report)> {
    let mut made: Vec<(Params, Scene, Report)> = Vec::new();
    for p in shown.iter().flatten() {
        if made.iter().any(|(q, _, _)| q == p) {
            continue;
        }
        let mut copy = scene.clone();
        let report = simplify_scene(&mut copy, p, &mut |_| {});
        made.push((*p, copy, report));
    }
    made
}

/// Draws `views` into `target`, with `painted` over them when given, and reads it back.
fn draw_and_read(
    context: &std::sync::Arc<Context>,
    commands: &Commands,
    pipelines: &Pipelines,
    target: &OffscreenTarget,
    views: &[ViewportDraw<'_>],
    painted: Option<&Overlay<'_>>,
) -> Result<RgbaImage, RenderError> {
    let image = match painted {
        Some(painted) => {
            let paint = |ctx: &egui::Context| overlay::paint(ctx, painted);
            let mut overlay =
                HeadlessCaptions::with_painter(context, commands, target.extent, &paint)?;
            let mut record = |cmd| overlay.record(cmd);
            target.render_with_overlay(commands, pipelines, views, true, Some(&mut record))?
        }
        None => target.render(commands, pipelines, views, true)?,
    };
    image.ok_or_else(|| RenderError::TooLarge("no picture was read back".into()))
}

/// The caption of `level`, `original` decimated with `params`: its target and algorithm,
/// its counts, and with `measure` its metro error against `original`.
pub fn decimated_caption(
    original: &Scene,
    level: &Scene,
    params: &Params,
    measure: bool,
) -> String {
    let measured = measure.then(|| LevelError::measure(original, level).map(Some));
    caption_of(level, params, measured.as_ref())
}

/// The caption of `level` made with `params`, with `measured`'s line when given.
fn caption_of(level: &Scene, params: &Params, measured: Option<&Measured>) -> String {
    let what = format!(
        "{} ({})",
        labels::target_words(params.target, params.max_error),
        labels::algorithm_name(params.algorithm)
    );
    let counts = Counts::of(level);
    let mut caption = labels::caption(&what, counts.vertices, counts.triangles);
    match measured {
        Some(Ok(Some(error))) => caption.push_str(&format!("\n{}", error.words())),
        Some(Err(e)) => caption.push_str(&format!("\ncannot measure: {e}")),
        Some(Ok(None)) | None => {}
    }
    caption
}

/// Writes `image` as an RGBA PNG through [`decimate_core::io::replace::replace_file`]: a temporary
/// file renamed over `path`, so a crash never leaves half a file under the real name.
pub fn write_png(image: &RgbaImage, path: &Path) -> Result<(), ShotError> {
    // The encoder's own error is kept aside: `replace_file` passes on I/O errors only.
    let mut encoding = None;
    let written = decimate_core::io::replace::replace_file(path, |out| {
        let mut encoder = png::Encoder::new(out, image.width, image.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let result = encoder.write_header().and_then(|mut writer| {
            writer.write_image_data(&image.pixels)?;
            writer.finish()
        });
        result.map_err(|e| {
            let message = e.to_string();
            encoding = Some(e);
            std::io::Error::other(message)
        })
    });
    match (written, encoding) {
        (Ok(()), _) => Ok(()),
        (Err(_), Some(source)) => Err(ShotError::Encode {
            file: path.to_path_buf(),
            source,
        }),
        (Err(source), None) => Err(ShotError::Write {
            file: path.to_path_buf(),
            source,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use decimate_core::mesh::shapes;

    #[test]
    fn a_measured_caption_says_the_levels_metro_error() {
        let original = Scene {
            models: vec![shapes::test006()],
        };
        let params = Params {
            target: Target::RemovePercent(90.0),
            ..Params::default()
        };
        let mut level = original.clone();
        simplify_scene(&mut level, &params, &mut |_| {});
        let caption = decimated_caption(&original, &level, &params, true);
        let lines: Vec<&str> = caption.lines().collect();
        let kept = level.models[0].used_vertex_count();
        assert_eq!(lines[0], "90 % removed (schroeder)");
        assert_eq!(
            lines[1],
            format!("{kept} vertices, {} triangles", level.triangle_count())
        );
        let error = LevelError::measure(&original, &level).unwrap_or_else(|e| panic!("{e}"));
        assert!(error.max > 0.0, "{error:?}");
        assert_eq!(lines[2], error.words());
        assert_eq!(lines.len(), 3);
        let unmeasured = decimated_caption(&original, &level, &params, false);
        assert_eq!(unmeasured, lines[..2].join("\n"));
    }
}

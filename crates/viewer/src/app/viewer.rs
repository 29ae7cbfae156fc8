//! `Viewer`: the interactive viewer's callbacks. It owns the `ViewportController` (what is
//! shown) and the GPU side (context, swapchain, pipelines, one `GpuScene` per viewport,
//! uploaded again only when that viewport's scene changes), and turns window events into
//! `Action`s through the same menu data as the popup.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use ash::vk;
use glam::Vec2;
use winit::window::Window;

use crate::render::camera::Camera;
use crate::render::camera::Navigation;
use crate::render::commands::Commands;
use crate::render::context::{Context, DevicePreference};
use crate::render::draw::DrawOptions;
use crate::render::draw::{self, ViewportDraw};
use crate::render::gpu_mesh::GpuScene;
use crate::render::image::{self, Transition};
use crate::render::offscreen::{OffscreenTarget, OFFSCREEN_FORMAT};
use crate::render::picture_cache::PictureCache;
use crate::render::pipeline::Pipelines;
use crate::render::swapchain::{Frame, Swapchain};
use crate::render::texture::Textures;
use crate::render::tiles::Rect;
use crate::render::RenderError;
use decimate_core::io::texture_image;

use super::app_error::AppError;
use super::controller::{Effect, ViewportController};
use super::error_map::{FieldCache, Legend, Look};
use super::file_dialog::{DialogOutcome, FileDialog};
use super::glut::{Button, Callbacks, Flow, Special};
use super::labels::HeadlessCaptions;
use super::menu::{action_for_key, key_help, Key, MenuEntry};
use super::overlay::{self, Overlay};
use super::panel::{ViewportPanel, BELOW_LOD_SLIDER};
use super::save::{save_path, SavePath};
use super::settle::Settle;
use super::shot::write_png;
use super::ui::{LodSlider, UiLayer, UiResult, UiState, VertexField};

/// GPU objects of the window; field order is drop order (UI and meshes before the context).
struct Gpu {
    ui: UiLayer,
    /// Each viewport's scene: its id, generation and look (own colours or heat-mapped).
    scenes: Vec<(u64, (u64, Look), GpuScene)>,
    /// The viewports as last drawn at rest, drawn back while a job runs.
    picture: PictureCache<SceneKey>,
    /// Uploaded once per name, shared by every viewport's scenes; dropped before the
    /// pipelines, whose set layout its sets were made with.
    textures: Textures,
    pipelines: Pipelines,
    /// With multisampling, single-sampled pipelines too, for the frames drawn while the view
    /// moves (docs/design.md#msaa); kept so that switching costs nothing.
    moving_pipelines: Option<Pipelines>,
    frame_commands: Commands,
    upload_commands: Commands,
    swapchain: Swapchain,
    context: Arc<Context>,
}

/// The viewer: controller + GPU + pointer state.
pub struct Viewer {
    pub controller: ViewportController,
    menu: Vec<MenuEntry>,
    gpu: Option<Gpu>,
    size: (u32, u32),
    resized: bool,
    pointer: (f64, f64),
    dragging: bool,
    /// The middle button (or Shift + left) is down: moves pan.
    panning: bool,
    popup_at: Option<egui::Pos2>,
    popup_just_opened: bool,
    field: Option<VertexField>,
    /// The Open… or Save as… dialog, while it is shown.
    dialog: Option<FileDialog>,
    help_text: String,
    /// The last message of the status line and when it expires.
    message: Option<(String, Instant)>,
    /// The heat-mapped viewports' error fields and the legend they share.
    fields: FieldCache,
    legend: Option<Legend>,
    /// Whether the view moves: the frames then are single-sampled.
    settle: Settle,
    /// The last frame was drawn single-sampled though multisampling is on: a sharp one is
    /// due when the view rests.
    drawn_moving: bool,
    /// The window's scale factor (physical pixels per logical one).
    scale_factor: f32,
    /// How long the last frame took to draw, and when it ended.
    last_frame: Duration,
    last_drawn: Instant,
    /// The last frame drew the kept picture instead of the viewports.
    drawn_kept: bool,
}

/// One viewport's id, scene uploaded (generation and look), rectangle, camera, draw modes
/// and geomorph factor (as bits).
type ViewKey = (u64, Option<(u64, Look)>, Rect, Camera, DrawOptions, u32);

/// What decides how the viewports look: a kept picture drawn for the same key can stand
/// for drawing them again.
#[derive(PartialEq)]
struct SceneKey {
    views: Vec<ViewKey>,
    highlight: Option<usize>,
    single: bool,
    samples: vk::SampleCountFlags,
}

/// Where F2 saves the window's picture.
const PICTURE: &str = "window.png";

/// How long a message stays in the status line.
const MESSAGE_LIFETIME: Duration = Duration::from_secs(6);

/// While a job runs, a frame this often at most (and on input): the progress bar moves four
/// times a second and the job's end is seen; see docs/design.md#viewer-jobs.
const JOB_FRAME_INTERVAL: Duration = Duration::from_millis(250);

/// While a job runs, the next progress frame waits this many times as long as the last
/// frame took (a large model drawn in software takes a core for long): drawing takes at
/// most about one part in six of the time, and the job keeps the cores.
const JOB_FRAME_SHARE: u32 = 5;

/// With `DECIMATE_TRACE` set, the viewer prints each key it handles and each frame drawn
/// while a job runs to stderr, with the milliseconds since it started: how the window test
/// sees that the window keeps answering.
fn trace(what: std::fmt::Arguments<'_>) {
    static START: std::sync::OnceLock<Option<Instant>> = std::sync::OnceLock::new();
    let start = START.get_or_init(|| std::env::var_os("DECIMATE_TRACE").map(|_| Instant::now()));
    if let Some(start) = start {
        eprintln!("decimate: trace {} ms: {what}", start.elapsed().as_millis());
    }
}

impl Viewer {
    /// (4) The menus are built by the caller and handed in; nothing touches the GPU until the
    /// window exists.
    pub fn new(controller: ViewportController, menu: Vec<MenuEntry>) -> Self {
        Self {
            controller,
            menu,
            gpu: None,
            size: (1, 1),
            resized: false,
            pointer: (0.0, 0.0),
            dragging: false,
            panning: false,
            popup_at: None,
            popup_just_opened: false,
            field: None,
            dialog: None,
            help_text: key_help(),
            message: None,
            fields: FieldCache::default(),
            legend: None,
            settle: Settle::default(),
            drawn_moving: false,
            scale_factor: 1.0,
            last_frame: Duration::ZERO,
            last_drawn: Instant::now(),
            drawn_kept: false,
        }
    }

    fn run_effect(&mut self, effect: Effect) -> Flow {
        match effect {
            Effect::None => Flow::Continue,
            Effect::AskVertexCount => {
                self.field = Some(VertexField {
                    hint: format!(
                        "0 to {} vertices (0: as far as possible)",
                        self.controller.original_vertices()
                    ),
                    ..VertexField::default()
                });
                Flow::Continue
            }
            Effect::SavePicture => {
                let message = match self.save_picture() {
                    Ok(message) => message,
                    Err(e) => format!("cannot save the picture: {e}"),
                };
                eprintln!("decimate: {message}");
                self.controller.message = message;
                Flow::Continue
            }
            Effect::Dialog(kind) => {
                let (folder, name) = self.controller.dialog_start(kind);
                self.dialog = Some(FileDialog::new(kind, &folder, &name));
                self.popup_at = None;
                Flow::Continue
            }
            Effect::Quit => Flow::Quit,
        }
    }

    /// Takes the job's result if it has ended (and says so); true then.
    fn poll_job(&mut self) -> bool {
        let ended = self.controller.poll();
        if ended {
            eprintln!("decimate: {}", self.controller.message);
        }
        ended
    }

    /// Esc: closes the popup or the field; else stops the job running (the viewport keeps
    /// what it showed) or the heat-map's measurement; else closes the help. Never quits.
    fn escape(&mut self) {
        if self.popup_at.take().is_some() || self.field.take().is_some() {
            return;
        }
        if self.dialog.take().is_some() {
            return;
        }
        if self.controller.cancel_job() {
            eprintln!("decimate: {}", self.controller.message);
        } else if let Some(message) = self.fields.cancel() {
            eprintln!("decimate: {message}");
            self.controller.message = message;
        } else {
            self.controller.help = false;
        }
    }

    /// A key while the quit question is shown: q or y quits, n or Esc stays, others wait.
    fn answer_quit(&mut self, key: Key) -> Flow {
        match key {
            Key::Char('q' | 'y' | 'Y') => Flow::Quit,
            Key::Char('n' | 'N') | Key::Escape => {
                self.controller.confirm_quit = false;
                self.controller.message = "not quitting".into();
                Flow::Continue
            }
            _ => Flow::Continue,
        }
    }

    /// A new scene was opened: its textures are read from its own folder, and nothing of
    /// the old one stays on the GPU.
    fn reload_textures(&mut self) -> Result<(), AppError> {
        let Some(gpu) = self.gpu.as_mut() else {
            return Ok(());
        };
        gpu.context.wait_idle()?;
        gpu.scenes.clear();
        gpu.textures = Textures::new(
            &gpu.context,
            gpu.pipelines.texture_layout,
            texture_image::reader(&self.controller.input_dir),
        )?;
        Ok(())
    }

    /// F2: what the window shows — viewports, captions, legends and the status line —
    /// rendered again offscreen and written to `window.png` (never over an input; through a
    /// temporary file).
    fn save_picture(&mut self) -> Result<String, AppError> {
        let status = self.status();
        let strip = self.controller.status_strip;
        let Some(gpu) = self.gpu.as_mut() else {
            return Ok("no window to picture yet".into());
        };
        let wanted = PathBuf::from(PICTURE);
        let Some(target) = save_path(&wanted, &self.controller.inputs) else {
            return Ok(format!(
                "cannot save: {PICTURE} and its alternatives are inputs"
            ));
        };
        let extent = gpu.swapchain.extent;
        gpu.context.wait_idle()?;
        // The window's pipelines draw in the swapchain's format; the picture is RGBA.
        let msaa = gpu.pipelines.samples.as_raw();
        let pipelines = Pipelines::with_samples(&gpu.context, OFFSCREEN_FORMAT, msaa)?;
        let offscreen = OffscreenTarget::with_samples(
            &gpu.context,
            extent.width,
            extent.height,
            pipelines.samples,
        )?;
        let views = viewport_draws(&gpu.scenes, &self.controller, extent, Instant::now());
        let rects = self.controller.rects_for(extent.width, extent.height);
        let captions: Vec<_> = (rects.iter().copied())
            .zip(self.controller.viewports().iter().map(|vp| vp.caption()))
            .collect();
        let commands = &gpu.upload_commands;
        let heat = heat_mapped_rects(&self.controller, &self.fields, self.legend.as_ref(), &rects);
        let legend = self.legend.map(|l| (l, heat.as_slice()));
        let paint = |ctx: &egui::Context| {
            let captions = Overlay {
                captions: &captions,
                legend,
                status: Some((&status, strip)),
                ..Overlay::default()
            };
            overlay::paint(ctx, &captions);
        };
        let mut overlay = HeadlessCaptions::with_painter(&gpu.context, commands, extent, &paint)?;
        let mut record = |cmd| overlay.record(cmd);
        let image = offscreen
            .render_with_overlay(commands, &pipelines, &views, true, Some(&mut record))?
            .ok_or_else(|| RenderError::TooLarge("no picture was read back".into()))?;
        let path = target.path();
        Ok(match write_png(&image, path) {
            Ok(()) if matches!(target, SavePath::Numbered(_)) => {
                format!(
                    "saved the window as {} (kept the earlier ones)",
                    path.display()
                )
            }
            Ok(()) if matches!(target, SavePath::Instead(_)) => format!(
                "{PICTURE} is an input file, not written over: saved the window as {}",
                path.display()
            ),
            Ok(()) => format!("saved the window as {}", path.display()),
            Err(e) => format!("cannot save the picture: {e}"),
        })
    }

    /// The status line, one line: the last message while it is fresh, else the current
    /// viewport's state.
    fn status(&mut self) -> String {
        // Messages age while a job's progress is shown too: an expired one must not keep
        // asking for frames (`due`).
        let now = Instant::now();
        let message = std::mem::take(&mut self.controller.message);
        if !message.is_empty() {
            self.message = Some((message, now + MESSAGE_LIFETIME));
        }
        if self
            .message
            .as_ref()
            .is_some_and(|(_, until)| *until <= now)
        {
            self.message = None;
        }
        if let Some(job) = self
            .controller
            .job_status()
            .or_else(|| self.fields.status())
        {
            return job;
        }
        if let Some((message, _)) = &self.message {
            return message.clone();
        }
        let vp = self.controller.current_viewport();
        format!(
            "viewport {}/{}: {}",
            self.controller.current() + 1,
            self.controller.viewports().len(),
            vp.status()
        )
    }

    /// Uploads the scenes whose generation changed, or whose draw modes now need a list that
    /// was left out (then with the lists it had too, so toggling a mode back and forth
    /// uploads once), and forgets removed viewports.
    fn sync_scenes(
        gpu: &mut Gpu,
        controller: &ViewportController,
        fields: &FieldCache,
        legend: Option<&Legend>,
    ) -> Result<(), AppError> {
        let viewports = controller.viewports();
        gpu.scenes
            .retain(|(id, _, _)| viewports.iter().any(|v| v.id == *id));
        for vp in viewports {
            let needed = vp.options.layers();
            let key = (vp.generation, fields.look(vp, legend));
            let uploaded = gpu
                .scenes
                .iter()
                .find(|(id, k, _)| *id == vp.id && *k == key)
                .map(|(_, _, scene)| scene.layers);
            if uploaded.is_none_or(|layers| !layers.contains(needed)) {
                gpu.context.wait_idle()?;
                let morph_from = vp.lod().and_then(|l| l.morph_from());
                let scene = GpuScene::upload_morphing(
                    &gpu.context,
                    &gpu.upload_commands,
                    &mut gpu.textures,
                    &fields.scene(vp, key.1, legend),
                    morph_from,
                    uploaded.map_or(needed, |layers| layers.union(needed)),
                )?;
                gpu.scenes.retain(|(id, _, _)| *id != vp.id);
                gpu.scenes.push((vp.id, key, scene));
            }
        }
        Ok(())
    }

    /// One frame: advance geomorphs, bring the GPU copies up to date, lay out the UI, draw
    /// and present, then act on what the UI reported. `Flow::Quit` when a menu entry quits.
    fn draw_frame(&mut self, window: &Window) -> Result<Flow, AppError> {
        // Geomorphs advance with the clock; while one runs, frames keep coming.
        let now = Instant::now();
        self.poll_job();
        let morphing = self.controller.tick(now);
        let moving = (self.settle).moving(self.dragging || self.panning || morphing, now);
        let Some(gpu) = self.gpu.as_mut() else {
            return Ok(Flow::Continue);
        };
        if self.resized {
            gpu.swapchain.recreate(self.size.0, self.size.1)?;
            self.resized = false;
        }
        if gpu.context.capabilities.samples(self.controller.msaa) != gpu.pipelines.samples {
            gpu.context.wait_idle()?;
            gpu.pipelines.set_samples(self.controller.msaa)?;
            gpu.swapchain.set_samples(gpu.pipelines.samples)?;
            gpu.moving_pipelines =
                single_sampled(&gpu.context, &gpu.pipelines, gpu.swapchain.format)?;
        }
        // The heat-map's error fields: a job measures them for the level at rest.
        self.legend = self.fields.update(self.controller.viewports(), !moving);
        Self::sync_scenes(gpu, &self.controller, &self.fields, self.legend.as_ref())?;
        let ui_result = self.run_ui(window)?;
        if !self.present(now, moving)? {
            // The swapchain no longer fits the window: made again next frame.
            self.resized = true;
            window.request_redraw();
        }
        self.popup_just_opened = false;
        let job = self
            .controller
            .job_status()
            .or_else(|| self.fields.status());
        let job = job.as_deref().unwrap_or("no job");
        let samples = match (&self.gpu, self.drawn_moving) {
            (Some(gpu), false) => gpu.pipelines.samples.as_raw(),
            _ => 1,
        };
        self.last_frame = now.elapsed();
        self.last_drawn = Instant::now();
        let kept = if self.drawn_kept {
            ", kept picture"
        } else {
            ""
        };
        trace(format_args!(
            "frame in {} ms, {job}, {samples}x samples{kept}",
            self.last_frame.as_millis()
        ));
        // egui asks for a frame after any input it saw; while a job runs that is honoured
        // only when something of egui's is open (popup, field, question) and may animate.
        let ui_open = self.popup_at.is_some()
            || self.field.is_some()
            || self.dialog.is_some()
            || self.controller.confirm_quit;
        if (ui_result.repaint && (ui_open || !self.busy())) || morphing {
            window.request_redraw();
        }
        Ok(self.apply_ui(ui_result, window))
    }

    /// Lays out this frame's UI: status strip, captions, legends, level-of-detail slider,
    /// help, popup, field, quit question.
    fn run_ui(&mut self, window: &Window) -> Result<UiResult, AppError> {
        let status = self.status();
        let help = self.controller.help.then_some(self.help_text.as_str());
        let confirm = (self.controller.confirm_quit).then(|| {
            let unsaved = self.controller.unsaved().len();
            format!("{unsaved} decimated viewport(s) not saved (F3 saves one).")
        });
        let rects = self.controller.rects();
        let captions: Vec<_> = (rects.iter().copied())
            .zip(self.controller.viewports().iter().map(|vp| vp.caption()))
            .collect();
        let heat = heat_mapped_rects(&self.controller, &self.fields, self.legend.as_ref(), &rects);
        let Some(gpu) = self.gpu.as_mut() else {
            return Ok(UiResult::default());
        };
        let ppp = gpu.ui.pixels_per_point();
        let lods = lod_sliders(&self.controller, &rects, ppp);
        let panels = viewport_panels(&self.controller, &rects, ppp);
        gpu.ui.run(
            window,
            &gpu.context,
            &gpu.upload_commands,
            UiState {
                menu: &self.menu,
                checked: &|a| self.controller.checked(a),
                popup_at: self.popup_at.map(|p| egui::pos2(p.x / ppp, p.y / ppp)),
                popup_just_opened: self.popup_just_opened,
                field: self.field.as_mut(),
                overlay: Overlay {
                    captions: &captions,
                    legend: self.legend.map(|l| (l, heat.as_slice())),
                    status: Some((&status, self.controller.status_strip)),
                    help,
                },
                lods: &lods,
                confirm: confirm.as_deref(),
                dialog: self.dialog.as_mut(),
                panels: &panels,
            },
        )
    }

    /// Draws the viewports and the UI into the next swapchain image and presents it; false
    /// when the swapchain is out of date (nothing was drawn or not shown).
    fn present(&mut self, now: Instant, moving: bool) -> Result<bool, AppError> {
        let busy = self.busy();
        let Some(gpu) = self.gpu.as_mut() else {
            return Ok(true);
        };
        // Single-sampled while the view moves, when multisampling is on.
        let single =
            moving && gpu.moving_pipelines.is_some() && gpu.swapchain.moving_images.is_some();
        self.drawn_moving = single;
        let Some(frame) = gpu.swapchain.acquire()? else {
            return Ok(false);
        };
        let extent = gpu.swapchain.extent;
        let views = viewport_draws(&gpu.scenes, &self.controller, extent, now);
        let highlight = (views.len() > 1).then_some(self.controller.current());
        let key = SceneKey {
            views: scene_keys(&gpu.scenes, &self.controller, extent, now),
            highlight,
            single,
            samples: gpu.pipelines.samples,
        };
        let cmd = gpu.frame_commands.begin()?;
        let device = &gpu.context.device;
        // While a job runs the viewports change only with the camera or the job's end: the
        // picture kept of them is drawn back instead of every triangle (a large model drawn
        // in software takes seconds, taken from the job).
        // SAFETY: `cmd` is recording, outside any pass; the swapchain image stays alive until
        // the frame's fence is waited for.
        self.drawn_kept = busy
            && gpu.swapchain.restorable
            && gpu.picture.holds(&key)
            && unsafe { gpu.picture.restore(device, cmd, frame.image) };
        if !self.drawn_kept {
            record_viewports(gpu, cmd, &frame, &views, highlight, single)?;
            drop(views);
            if gpu.swapchain.restorable && !single {
                // SAFETY: as above; the kept picture is remade only after a resize, which
                // waited for the device.
                unsafe {
                    (gpu.picture).capture(
                        &gpu.context,
                        cmd,
                        frame.image,
                        gpu.swapchain.format,
                        extent,
                        key,
                    )?;
                }
            }
        }
        // SAFETY: `cmd` is recording outside a pass; the image is a colour attachment now.
        unsafe { draw::begin_overlay(&gpu.context.device, cmd, frame.view, extent) };
        gpu.ui.draw(cmd, extent)?;
        let to_present = Transition {
            old: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            new: vk::ImageLayout::PRESENT_SRC_KHR,
            src_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
            src_access: vk::AccessFlags2::COLOR_ATTACHMENT_WRITE,
            dst_stage: vk::PipelineStageFlags2::BOTTOM_OF_PIPE,
            dst_access: vk::AccessFlags2::NONE,
        };
        let device = &gpu.context.device;
        // SAFETY: `cmd` is recording inside the overlay pass `record_viewports` opened; the
        // swapchain image stays alive until the frame's fence is waited for.
        unsafe {
            device.cmd_end_rendering(cmd);
            image::transition(device, cmd, frame.image, gpu.swapchain.format, to_present);
        }
        gpu.frame_commands.end()?;
        let presented = gpu.swapchain.submit_and_present(cmd, &frame)?;
        gpu.ui.end_frame()?;
        Ok(presented)
    }

    /// Acts on what the user did in the UI this frame: slider, popup, field, menu entry.
    fn apply_ui(&mut self, ui_result: UiResult, window: &Window) -> Flow {
        let mut flow = Flow::Continue;
        let acted = ui_result.lod_vertices.is_some()
            || ui_result.close_popup
            || ui_result.close_field
            || ui_result.vertex_count.is_some()
            || ui_result.action.is_some()
            || ui_result.quit_answer.is_some()
            || ui_result.dialog.is_some()
            || ui_result.panel_action.is_some();
        if let Some((viewport, n)) = ui_result.lod_vertices {
            self.settle.moved(Instant::now());
            self.controller.select(viewport);
            self.controller.set_lod_vertices(n, Instant::now());
        }
        if ui_result.close_popup || ui_result.action.is_some() {
            self.popup_at = None;
        }
        if ui_result.close_field {
            self.field = None;
        }
        if let Some(text) = ui_result.vertex_count {
            match self.controller.submit_vertex_count(&text) {
                Ok(()) => self.field = None,
                Err(e) => {
                    if let Some(field) = &mut self.field {
                        field.error = Some(e);
                    }
                }
            }
        }
        if let Some((viewport, action)) = ui_result.panel_action {
            trace(format_args!(
                "panel of viewport {}: {action:?}",
                viewport + 1
            ));
            self.controller.select(viewport);
            let effect = self.controller.dispatch(action);
            flow = self.run_effect(effect);
        }
        if let Some(action) = ui_result.action {
            let effect = self.controller.dispatch(action);
            flow = self.run_effect(effect);
        }
        if let Some(news) = self.dialog.as_mut().and_then(FileDialog::take_news) {
            eprintln!("decimate: {news}");
            self.controller.message = news;
        }
        match ui_result.dialog {
            Some(DialogOutcome::Open(path)) => {
                self.dialog = None;
                self.open_file(window, path);
            }
            Some(DialogOutcome::Save(path)) => {
                self.dialog = None;
                self.controller.save_as(&path);
            }
            Some(DialogOutcome::Cancel) => self.dialog = None,
            None => {}
        }
        match ui_result.quit_answer {
            Some(true) => flow = Flow::Quit,
            Some(false) => self.controller.confirm_quit = false,
            None => {}
        }
        if acted {
            window.request_redraw();
        }
        flow
    }
}

impl Viewer {
    /// A decimation, progressive mesh, measurement or heat-map field is being computed.
    fn busy(&self) -> bool {
        self.controller.busy() || self.fields.busy()
    }

    /// When the sharp frame is due once the view rests, after single-sampled ones (a button
    /// held still waits for its release, which draws a frame).
    fn rest_at(&self) -> Option<Instant> {
        let held = self.dragging || self.panning;
        (self.settle.rests_at()).filter(|_| self.drawn_moving && !held)
    }
}

/// The level-of-detail slider of each viewport that has it on, at its top-left corner
/// (`rects` in pixels, `ppp` of them to a point).
fn lod_sliders(controller: &ViewportController, rects: &[Rect], ppp: f32) -> Vec<LodSlider> {
    (rects.iter().zip(controller.viewports()).enumerate())
        .filter_map(|(i, (rect, vp))| {
            let lod = vp.lod()?;
            Some(LodSlider {
                viewport: i,
                corner: overlay::points(rect, ppp).min,
                range: lod.range(),
                at: lod.target(),
            })
        })
        .collect()
}

/// Each viewport's panel, at its top-left corner (below its level-of-detail slider when
/// that is shown; `rects` in pixels, `ppp` of them to a point).
fn viewport_panels(
    controller: &ViewportController,
    rects: &[Rect],
    ppp: f32,
) -> Vec<ViewportPanel> {
    (rects.iter().zip(controller.viewports()).enumerate())
        .map(|(i, (rect, vp))| {
            let lod = vp.lod().is_some();
            let below = if lod { BELOW_LOD_SLIDER } else { 0.0 };
            ViewportPanel {
                viewport: i,
                id: vp.id,
                corner: overlay::points(rect, ppp).min + egui::vec2(0.0, below),
                qem: vp.params.algorithm == decimate_core::decimate::Algorithm::Qem,
                keep_border: vp.params.keep_border,
                lod,
            }
        })
        .collect()
}

/// The rectangles of the viewports drawn heat-mapped (their legend goes in each).
fn heat_mapped_rects(
    controller: &ViewportController,
    fields: &FieldCache,
    legend: Option<&Legend>,
    rects: &[Rect],
) -> Vec<Rect> {
    (rects.iter().zip(controller.viewports()))
        .filter(|(_, vp)| matches!(fields.look(vp, legend), Look::Heat(_)))
        .map(|(r, _)| *r)
        .collect()
}

/// What each viewport draws this frame, for the viewports whose scene is on the GPU.
fn viewport_draws<'a>(
    scenes: &'a [(u64, (u64, Look), GpuScene)],
    controller: &'a ViewportController,
    extent: vk::Extent2D,
    now: Instant,
) -> Vec<ViewportDraw<'a>> {
    controller
        .rects_for(extent.width, extent.height)
        .into_iter()
        .zip(controller.viewports())
        .filter_map(|(rect, vp)| {
            let (_, _, scene) = scenes.iter().find(|(id, _, _)| *id == vp.id)?;
            Some(ViewportDraw {
                rect,
                scene,
                camera: &vp.camera,
                options: vp.options,
                morph: vp.lod().map_or(1.0, |l| l.morph_factor(now)),
            })
        })
        .collect()
}

/// Each viewport's [`ViewKey`] this frame.
fn scene_keys(
    scenes: &[(u64, (u64, Look), GpuScene)],
    controller: &ViewportController,
    extent: vk::Extent2D,
    now: Instant,
) -> Vec<ViewKey> {
    let rects = controller.rects_for(extent.width, extent.height);
    (rects.into_iter().zip(controller.viewports()))
        .map(|(rect, vp)| {
            let look = (scenes.iter().find(|(id, _, _)| *id == vp.id)).map(|(_, k, _)| *k);
            let morph = vp.lod().map_or(1.0, |l| l.morph_factor(now));
            (
                vp.id,
                look,
                rect,
                vp.camera.clone(),
                vp.options,
                morph.to_bits(),
            )
        })
        .collect()
}

/// Records the viewports' pass into `cmd` (tiles, highlight of the current one, models),
/// single-sampled when `single`; the image is left a colour attachment.
fn record_viewports(
    gpu: &Gpu,
    cmd: vk::CommandBuffer,
    frame: &Frame,
    views: &[ViewportDraw<'_>],
    highlight: Option<usize>,
    single: bool,
) -> Result<(), AppError> {
    let device = &gpu.context.device;
    let (format, extent) = (gpu.swapchain.format, gpu.swapchain.extent);
    let pipelines = match (&gpu.moving_pipelines, single) {
        (Some(pipelines), true) => pipelines,
        _ => &gpu.pipelines,
    };
    let images = gpu
        .swapchain
        .images(single)
        .ok_or_else(|| RenderError::Window("the swapchain has no depth buffer".into()))?;
    let rects: Vec<_> = views.iter().map(|v| v.rect).collect();
    // SAFETY: `cmd` is recording; the swapchain image, depth buffer, pipelines and scenes
    // stay alive until the frame's fence is waited for (next `acquire` or device idle).
    unsafe {
        image::transition(device, cmd, frame.image, format, image::TO_COLOR_ATTACHMENT);
        images.to_attachments(device, cmd);
        let attachments = images.attachments(frame.view);
        draw::begin_tiles(
            device,
            cmd,
            attachments,
            extent,
            &rects,
            highlight,
            draw::BACKGROUND,
        );
        draw::record(device, cmd, pipelines, views);
        device.cmd_end_rendering(cmd);
    }
    Ok(())
}

impl Callbacks for Viewer {
    fn create(&mut self, window: &Arc<Window>) -> Result<(), AppError> {
        use raw_window_handle::HasDisplayHandle;
        let display = window
            .display_handle()
            .map_err(|e| AppError::Window(e.to_string()))?;
        let extensions = ash_window::enumerate_required_extensions(display.as_raw())
            .map_err(|e| AppError::Window(format!("no Vulkan surface support: {e}")))?;
        let context = Context::new(extensions, true, DevicePreference::Fastest)?;
        let size = window.inner_size();
        self.scale_factor = window.scale_factor() as f32;
        let samples = context.capabilities.samples(self.controller.msaa);
        let swapchain = Swapchain::new(
            &context,
            window.as_ref(),
            (size.width, size.height),
            samples,
        )?;
        let pipelines = Pipelines::with_samples(&context, swapchain.format, samples.as_raw())?;
        let textures = Textures::new(
            &context,
            pipelines.texture_layout,
            texture_image::reader(&self.controller.input_dir),
        )?;
        let moving_pipelines = single_sampled(&context, &pipelines, swapchain.format)?;
        let ui = UiLayer::new(&context, window, swapchain.format)?;
        eprintln!("decimate: drawing with {}", context.device_name);
        self.gpu = Some(Gpu {
            ui,
            scenes: Vec::new(),
            picture: PictureCache::default(),
            textures,
            pipelines,
            moving_pipelines,
            frame_commands: Commands::new(&context)?,
            upload_commands: Commands::new(&context)?,
            swapchain,
            context,
        });
        Ok(())
    }

    fn display(&mut self, window: &Window) -> Result<Flow, AppError> {
        self.draw_frame(window)
    }

    fn reshape(&mut self, width: u32, height: u32) {
        self.size = (width.max(1), height.max(1));
        let ppp = self.scale_factor * overlay::text_scale(self.size.0, self.size.1);
        self.controller.status_strip = overlay::status_strip(self.size.1, ppp);
        self.controller.resize(self.size.0, self.size.1);
        self.resized = true;
    }

    fn keyboard(&mut self, key: Key) -> Flow {
        trace(format_args!("key {key:?}"));
        // A key acts on the latest state: a job that has ended is taken first (F3 then saves
        // its result, not what the last frame showed).
        self.poll_job();
        if self.controller.confirm_quit {
            return self.answer_quit(key);
        }
        if key == Key::Escape {
            self.escape();
            return Flow::Continue;
        }
        if self.dialog.is_some() {
            // The dialog's name field takes the keys.
            return Flow::Continue;
        }
        // W / S walk in eye control; elsewhere they keep their menu meaning.
        let eye = self.controller.current_viewport().camera.navigation == Navigation::Eye;
        match key {
            Key::Char('w') if eye => {
                self.settle.moved(Instant::now());
                self.controller.walk(0.1, 0.0);
                return Flow::Continue;
            }
            Key::Char('S') if eye => {
                self.settle.moved(Instant::now());
                self.controller.walk(-0.1, 0.0);
                return Flow::Continue;
            }
            _ => {}
        }
        match action_for_key(key) {
            Some(action) => {
                let effect = self.controller.dispatch(action);
                self.run_effect(effect)
            }
            None => Flow::Continue,
        }
    }

    fn close_requested(&mut self) -> Flow {
        let effect = self.controller.quit();
        self.run_effect(effect)
    }

    fn special(&mut self, key: Special) {
        let (forward, right) = match key {
            Special::Up => (0.1, 0.0),
            Special::Down => (-0.1, 0.0),
            Special::Left => (0.0, -0.1),
            Special::Right => (0.0, 0.1),
        };
        self.settle.moved(Instant::now());
        self.controller.walk(forward, right);
    }

    fn mouse(&mut self, button: Button, pressed: bool, x: f64, y: f64) -> Flow {
        match (button, pressed) {
            (Button::Right, true) => {
                self.controller.pointer_at(x, y);
                self.popup_at = Some(egui::pos2(x as f32, y as f32));
                self.popup_just_opened = true;
                if let Some(next) = self.controller.next_save() {
                    let name = next.file_name().unwrap_or_default().to_string_lossy();
                    super::menu::name_next_save(&mut self.menu, &name);
                }
            }
            (Button::Left, true) => {
                self.popup_at = None;
                self.controller.pointer_at(x, y);
                self.dragging = true;
            }
            (Button::Left, false) => self.dragging = false,
            (Button::Middle, true) => {
                self.popup_at = None;
                self.controller.pointer_at(x, y);
                self.panning = true;
            }
            (Button::Middle, false) => self.panning = false,
            _ => {}
        }
        Flow::Continue
    }

    fn motion(&mut self, x: f64, y: f64) {
        let delta = Vec2::new((x - self.pointer.0) as f32, (y - self.pointer.1) as f32);
        self.pointer = (x, y);
        if self.dragging {
            self.settle.moved(Instant::now());
            self.controller.drag(delta);
        } else if self.panning {
            self.settle.moved(Instant::now());
            self.controller.pan(delta);
        } else if self.popup_at.is_none() {
            self.controller.pointer_at(x, y);
        }
    }

    fn wheel(&mut self, steps: f32) {
        self.settle.moved(Instant::now());
        self.controller.wheel(steps);
    }

    fn filter(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        let Some(gpu) = self.gpu.as_mut() else {
            return false;
        };
        let consumed = gpu.ui.on_event(window, event);
        // While the popup or the field is open, egui owns the pointer and keyboard it uses.
        let ui_open = self.popup_at.is_some() || self.field.is_some() || self.dialog.is_some();
        consumed && (ui_open || gpu.ui.wants_pointer())
    }

    fn dropped(&mut self, window: &Window, path: PathBuf) {
        self.open_file(window, path);
    }

    fn wake_at(&self) -> Option<Instant> {
        let message = self.message.as_ref().map(|(_, until)| *until);
        // While a job runs the loop wakes this often to see whether it ended; `due` says
        // whether a frame is drawn.
        let job = self.busy().then(|| Instant::now() + JOB_FRAME_INTERVAL);
        message.into_iter().chain(job).chain(self.rest_at()).min()
    }

    fn due(&mut self) -> bool {
        let now = Instant::now();
        let message_ends = self
            .message
            .as_ref()
            .is_some_and(|(_, until)| *until <= now);
        if !self.busy() || message_ends || self.rest_at().is_some_and(|at| at <= now) {
            return true;
        }
        // The job's end is drawn at once; its progress with frames apart by at least
        // JOB_FRAME_SHARE times the time one takes.
        let wait = JOB_FRAME_INTERVAL.max(self.last_frame * JOB_FRAME_SHARE);
        self.poll_job() || self.last_drawn + wait <= now
    }

    fn destroy(&mut self) {
        if let Some(gpu) = &self.gpu {
            let _ = gpu.context.wait_idle();
        }
        self.gpu = None;
    }
}

/// Single-sampled pipelines beside `pipelines` when those multisample (for the frames drawn
/// while the view moves); none when they draw single-sampled already.
fn single_sampled(
    context: &Arc<Context>,
    pipelines: &Pipelines,
    format: vk::Format,
) -> Result<Option<Pipelines>, AppError> {
    if pipelines.samples == vk::SampleCountFlags::TYPE_1 {
        return Ok(None);
    }
    Ok(Some(Pipelines::with_samples(context, format, 1)?))
}

impl Viewer {
    /// Shows the model in `path` instead (a file dropped on the window or chosen in Open…);
    /// a file that cannot be read leaves the model shown, and the status line says why.
    fn open_file(&mut self, window: &Window, path: PathBuf) {
        match decimate_core::io::read_scene(&path) {
            Ok(outcome) => {
                let scene = decimate_core::mesh::build::build_scene(outcome.scene, true);
                self.controller.open(scene, &path);
                self.field = None;
                self.popup_at = None;
                window.set_title(&format!("decimate - {}", path.display()));
                if let Err(e) = self.reload_textures() {
                    self.controller.message = format!("{}: textures: {e}", path.display());
                }
            }
            Err(e) => self.controller.message = format!("cannot open {e}"),
        }
        eprintln!("decimate: {}", self.controller.message);
    }
}

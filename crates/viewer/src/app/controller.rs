//! `ViewportController`: owns the 1–4 viewports tiled over the window, knows the current one
//! (the one under the mouse, or chosen with Tab) and dispatches `Action`s — decimate events go
//! to the current viewport only, as in the original. Decimations, progressive meshes and
//! error measurements run as a worker job (`jobs`), one at a time; the window polls it each
//! frame and `Esc` cancels it. GPU-free, so it is unit-tested.

use std::path::PathBuf;
use std::sync::Arc;

use glam::Vec2;

use crate::render::camera::Navigation;
use crate::render::draw::DrawOptions;
use crate::render::tiles::{tiles, Rect};
use decimate_core::decimate::{Algorithm, Params};
use decimate_core::mesh::Scene;

use super::counts::Counts;
use super::jobs::{self, Done, Running, Task};
use super::menu::{Action, DecimateEvent, DecimateKind};
use super::save::{save_path, SavePath};
use super::viewport::Viewport;
use super::worker::Poll;

/// At most this many viewports, as in the original.
pub const MAX_VIEWPORTS: usize = 4;

/// What the window must do after an action.
#[derive(Debug, Clone, PartialEq)]
pub enum Effect {
    None,
    /// Open the vertex-count text field.
    AskVertexCount,
    /// Save a picture of the viewports (the window draws it).
    SavePicture,
    /// Show the Open… or Save as… dialog (the window draws it).
    Dialog(super::file_dialog::DialogKind),
    Quit,
}

/// The viewports of the window and the current one.
pub struct ViewportController {
    original: Arc<Scene>,
    /// The original's counts (welded vertices).
    original_counts: Counts,
    params: Params,
    viewports: Vec<Viewport>,
    next_id: u64,
    current: usize,
    width: u32,
    height: u32,
    pub help: bool,
    /// Every viewport shows the current one's camera (`c`).
    pub linked: bool,
    /// What a new viewport draws (the command line's `--mode`).
    draw_options: DrawOptions,
    /// Where F3 saves (`out.wrl` in the working directory), unless that is an input.
    pub save_path: PathBuf,
    /// The files the scene was read from: no save ever writes over one of them.
    pub inputs: Vec<PathBuf>,
    /// The folder the scene was read from: its relative texture names are relative to it,
    /// and F3 re-expresses them for `save_path`'s folder.
    pub input_dir: PathBuf,
    /// The last thing that happened, for the status line.
    pub message: String,
    /// The decimation, progressive mesh or measurement running, if any.
    job: Option<Running>,
    /// Samples per pixel asked for (`--msaa`, `M`): 1 is no anti-aliasing.
    pub msaa: u32,
    /// Each viewport's id and the generation F3 last saved of it.
    saved: Vec<(u64, u64)>,
    /// Quitting was asked for with decimated viewports unsaved: the window shows the
    /// question until it is answered (quit again, or Esc / n to stay).
    pub confirm_quit: bool,
    /// Pixels at the bottom of the window kept for the status line, below the viewports.
    pub status_strip: u32,
}

impl ViewportController {
    pub fn new(original: Scene, params: Params, width: u32, height: u32) -> Self {
        let original = Arc::new(original);
        let counts = Counts::of(&original);
        Self {
            viewports: vec![Viewport::new(0, original.clone(), counts, params)],
            next_id: 1,
            original,
            original_counts: counts,
            params,
            current: 0,
            width,
            height,
            help: false,
            linked: false,
            draw_options: DrawOptions::default(),
            save_path: PathBuf::from("out.wrl"),
            inputs: Vec::new(),
            input_dir: PathBuf::from("."),
            message: String::new(),
            job: None,
            msaa: crate::render::pipeline::DEFAULT_MSAA,
            saved: Vec::new(),
            confirm_quit: false,
            status_strip: 0,
        }
    }

    /// The viewports (numbered from 1) that show a decimated scene F3 has not saved.
    pub fn unsaved(&self) -> Vec<usize> {
        let original = self.original_counts.vertices;
        (self.viewports.iter().enumerate())
            .filter(|(_, vp)| vp.vertex_count() < original)
            .filter(|(_, vp)| !self.saved.contains(&(vp.id, vp.generation)))
            .map(|(i, _)| i + 1)
            .collect()
    }

    /// `q`, the menu's Quit or the window's close button: quits when nothing decimated is
    /// unsaved or the question was asked already; else asks it (`confirm_quit`).
    pub fn quit(&mut self) -> Effect {
        let unsaved = self.unsaved();
        if unsaved.is_empty() || self.confirm_quit {
            return Effect::Quit;
        }
        self.confirm_quit = true;
        self.message = format!(
            "{} not saved: q or y quits, n or Esc stays (F3 saves)",
            viewport_list(&unsaved)
        );
        eprintln!("decimate: {}", self.message);
        Effect::None
    }

    /// Every viewport, and each one added later, draws with `options` (`--mode`).
    pub fn set_draw_options(&mut self, options: DrawOptions) {
        self.draw_options = options;
        for vp in &mut self.viewports {
            vp.options = options;
        }
    }

    /// Shows `scene`, read from `path`, instead: one viewport of it, the cameras framed on it;
    /// the algorithm, border and link settings stay.
    pub fn open(&mut self, scene: Scene, path: &std::path::Path) {
        self.drop_job();
        let original = Arc::new(scene);
        self.original_counts = Counts::of(&original);
        let mut first = Viewport::new(
            self.next_id,
            original.clone(),
            self.original_counts,
            self.params,
        );
        first.options = self.draw_options;
        self.viewports = vec![first];
        self.next_id += 1;
        self.original = original;
        self.current = 0;
        self.inputs = vec![path.to_path_buf()];
        self.input_dir = decimate_core::io::texture_path::folder_of(path).to_path_buf();
        let vp = self.current_viewport();
        self.message = format!(
            "opened {}: {} vertices, {} triangles",
            path.display(),
            vp.vertex_count(),
            vp.triangle_count()
        );
    }

    pub fn viewports(&self) -> &[Viewport] {
        &self.viewports
    }

    pub fn current(&self) -> usize {
        self.current
    }

    pub fn current_viewport(&self) -> &Viewport {
        &self.viewports[self.current]
    }

    fn current_mut(&mut self) -> &mut Viewport {
        &mut self.viewports[self.current]
    }

    /// Window size in pixels (the reshape callback).
    pub fn resize(&mut self, width: u32, height: u32) {
        self.width = width;
        self.height = height;
    }

    /// The viewports' rectangles in the window.
    pub fn rects(&self) -> Vec<Rect> {
        self.rects_for(self.width, self.height)
    }

    /// The viewports' rectangles in a window of `width` × `height` (the swapchain's
    /// extent): tiled over what the status strip leaves at the bottom.
    pub fn rects_for(&self, width: u32, height: u32) -> Vec<Rect> {
        let strip = self.status_strip.min(height.saturating_sub(1));
        tiles(self.viewports.len(), width, height - strip)
    }

    /// The mouse moved to `(x, y)`: the viewport under it becomes current.
    pub fn pointer_at(&mut self, x: f64, y: f64) {
        if let Some(i) = self.rects().iter().position(|r| r.contains(x, y)) {
            self.current = i;
        }
    }

    /// A decimate event for the current viewport only, run as a job.
    pub fn decimate(&mut self, event: DecimateEvent) {
        self.start(Task::Decimate(event), String::new());
    }

    /// What a finished decimation asked and shows now (the same counts as the status line):
    /// it took `seconds`, and `fully` decimated the scene.
    fn decimated_words(vp: &Viewport, event: DecimateEvent, seconds: f64, fully: bool) -> String {
        let asked = match event.kind {
            DecimateKind::Percentage => format!("removed {:.0} %", event.amount),
            DecimateKind::Number => format!("asked to remove {:.0} vertices", event.amount),
        };
        format!(
            "{asked}: {} vertices, {} triangles left in {seconds:.3} s{}",
            vp.vertex_count(),
            vp.triangle_count(),
            if fully { " — fully decimated" } else { "" }
        )
    }

    /// The current viewport's algorithm or border setting changed: its last decimation, if
    /// it shows one, is made again with the new settings, so that they can be compared
    /// side by side with another viewport's.
    fn settings_changed(&mut self) {
        let i = self.current;
        let settings = self.current_viewport().settings();
        match self.current_viewport().last_event() {
            Some(event) => self.start(Task::Decimate(event), format!("{settings}; ")),
            None => {
                self.message = format!("viewport {}: {settings} from the next decimation", i + 1)
            }
        }
    }

    /// Starts `task` for the current viewport, cancelling the job running (the latest
    /// request wins); `prefix` goes before the result in the status line.
    fn start(&mut self, task: Task, prefix: String) {
        self.drop_job();
        let n = self.current + 1;
        let vp = self.current_viewport();
        let original = vp.original().clone();
        let job = match task {
            Task::Decimate(event) => {
                let params = vp.params_for(event);
                let what = format!(
                    "viewport {n}: decimating ({})",
                    super::labels::target_words(params.target, params.max_error)
                );
                jobs::decimate(what, original, params)
            }
            Task::Lod => {
                let what = format!("viewport {n}: building the level of detail");
                jobs::lod(what, original, vp.params)
            }
            Task::Measure { .. } => {
                let what = format!("viewport {n}: measuring the error (metro)");
                jobs::measure(what, original, vp.scene().clone())
            }
        };
        self.job = Some(Running {
            viewport: vp.id,
            task,
            prefix,
            job,
        });
    }

    /// The running job's line for the status line: what, a progress bar, how to stop it.
    pub fn job_status(&self) -> Option<String> {
        self.job.as_ref().map(|r| r.job.status())
    }

    /// Whether a job is running.
    pub fn busy(&self) -> bool {
        self.job.is_some()
    }

    /// Takes the running job's result when it has ended, without waiting; true when the
    /// job ended (the viewports or the message changed).
    pub fn poll(&mut self) -> bool {
        let Some(running) = &self.job else {
            return false;
        };
        match running.job.poll() {
            Poll::Running => false,
            poll => {
                self.end_job(poll);
                true
            }
        }
    }

    /// Waits for the running job and takes its result (tests: what a user sees once the
    /// bar is full).
    pub fn wait(&mut self) {
        if let Some(running) = &self.job {
            let poll = running.job.wait();
            self.end_job(poll);
        }
    }

    /// `Esc` while a job runs: stops it, the viewport showing what it showed. False when
    /// no job was running.
    pub fn cancel_job(&mut self) -> bool {
        let Some(running) = self.job.take() else {
            return false;
        };
        running.job.cancel();
        let n = self.viewport_number(running.viewport);
        let shows = n.map_or(String::new(), |n| {
            let vp = &self.viewports[n - 1];
            format!(
                "; viewport {n} still shows {} vertices, {} triangles",
                vp.vertex_count(),
                vp.triangle_count()
            )
        });
        self.message = format!("cancelled: {}{shows}", running.job.what);
        true
    }

    /// Forgets the running job (a new one replaces it, or the scene it reads is closed).
    fn drop_job(&mut self) {
        if let Some(running) = self.job.take() {
            running.job.cancel();
        }
    }

    /// Viewport `id`'s number (1-based), if it is still open.
    fn viewport_number(&self, id: u64) -> Option<usize> {
        self.viewports
            .iter()
            .position(|v| v.id == id)
            .map(|i| i + 1)
    }

    /// Hands an ended job's result to its viewport, and says what happened.
    fn end_job(&mut self, poll: Poll<Done>) {
        let Some(running) = self.job.take() else {
            return;
        };
        let Some(n) = self.viewport_number(running.viewport) else {
            return;
        };
        let vp = &mut self.viewports[n - 1];
        let done = match poll {
            Poll::Done(done) => done,
            Poll::Running => return,
            Poll::Cancelled => {
                self.message = format!("cancelled: {}", running.job.what);
                return;
            }
            Poll::Failed(e) => {
                self.message = e;
                return;
            }
        };
        let said = match (running.task, done) {
            (
                Task::Decimate(event),
                Done::Decimated {
                    scene,
                    report,
                    counts,
                },
            ) => {
                let (seconds, fully) = (report.seconds, report.fully_decimated());
                vp.show_decimated(event, scene, report, counts);
                let words = Self::decimated_words(vp, event, seconds, fully);
                format!("{}{words}", running.prefix)
            }
            (Task::Lod, Done::Lod(lod)) => {
                let (lo, hi) = lod.range();
                let seconds = lod.build_seconds;
                vp.show_lod(*lod);
                format!("level of detail {lo} to {hi} vertices, built in {seconds:.3} s")
            }
            (Task::Measure { generation }, Done::Measured(Ok(error))) => {
                if vp.set_error(generation, error) {
                    error.words()
                } else {
                    "the scene changed while it was measured: measure again (d)".into()
                }
            }
            (Task::Measure { .. }, Done::Measured(Err(e))) => format!("cannot measure: {e}"),
            _ => "a job ended with the result of another".into(),
        };
        self.message = format!("viewport {n}: {said}");
    }

    /// Vertices of the original scene (used by some triangle).
    pub fn original_vertices(&self) -> usize {
        (self.original.models.iter())
            .map(decimate_core::mesh::Model::used_vertex_count)
            .sum()
    }

    /// "Decimate to N vertices": 0 is key `0` (remove 100 %: as far as possible, features
    /// kept), any other count a NUMBER event for the difference from the original.
    pub fn decimate_to(&mut self, vertices: usize) {
        let original = self.original_vertices();
        let event = if vertices == 0 {
            DecimateEvent {
                amount: 100.0,
                kind: DecimateKind::Percentage,
            }
        } else if let Some(remove) = original.checked_sub(vertices) {
            DecimateEvent {
                amount: remove as f64,
                kind: DecimateKind::Number,
            }
        } else {
            self.message = format!("{vertices} vertices is more than the original's {original}");
            return;
        };
        self.decimate(event);
    }

    /// The vertex-count field was submitted with `text`: decimates to that count, or says
    /// why the text is no count of this scene (the field stays open with the message).
    pub fn submit_vertex_count(&mut self, text: &str) -> Result<(), String> {
        let n = parse_vertex_count(text, self.original_vertices())?;
        self.decimate_to(n);
        Ok(())
    }

    /// The level-of-detail slider of the current viewport moved to `vertices`.
    pub fn set_lod_vertices(&mut self, vertices: usize, now: std::time::Instant) {
        self.current_mut().set_lod_vertices(vertices, now);
    }

    /// Viewport `index` (from 0) becomes the current one, when there is one.
    pub fn select(&mut self, index: usize) {
        if index < self.viewports.len() {
            self.current = index;
        }
    }

    /// Advances every viewport's geomorph; true while one runs.
    pub fn tick(&mut self, now: std::time::Instant) -> bool {
        let mut running = false;
        for vp in &mut self.viewports {
            running |= vp.tick(now);
        }
        running
    }

    /// Left-drag by `delta` pixels in the current viewport.
    pub fn drag(&mut self, delta: Vec2) {
        self.current_mut().camera.drag(delta);
        self.follow_current_camera();
    }

    /// Middle-drag (or Shift + left-drag) by `delta` pixels in the current viewport: pans.
    pub fn pan(&mut self, delta: Vec2) {
        let Some(rect) = self.rects().get(self.current).copied() else {
            return;
        };
        let (height, aspect) = (rect.height as f32, rect.aspect());
        self.current_mut().camera.pan(delta, height, aspect);
        self.follow_current_camera();
    }

    /// Wheel steps in the current viewport.
    pub fn wheel(&mut self, steps: f32) {
        self.current_mut().camera.wheel(steps);
        self.follow_current_camera();
    }

    /// Arrow / W S keys: walk in eye control.
    pub fn walk(&mut self, forward: f32, right: f32) {
        self.current_mut().camera.walk(forward, right);
        self.follow_current_camera();
    }

    /// With linked cameras, every viewport takes the current one's camera.
    fn follow_current_camera(&mut self) {
        if self.linked {
            let camera = self.current_viewport().camera.clone();
            for vp in &mut self.viewports {
                vp.camera = camera.clone();
            }
        }
    }

    /// Runs `action`; returns what the window must do about it.
    pub fn dispatch(&mut self, action: Action) -> Effect {
        match action {
            Action::Decimate(event) => self.decimate(event),
            Action::AskVertexCount => return Effect::AskVertexCount,
            Action::ToggleLod => self.toggle_lod(),
            Action::MeasureError => {
                let generation = self.current_viewport().generation;
                self.start(Task::Measure { generation }, String::new());
            }
            Action::ToggleAlgorithm => {
                let params = &mut self.current_mut().params;
                params.algorithm = match params.algorithm {
                    Algorithm::Schroeder => Algorithm::Qem,
                    Algorithm::Qem => Algorithm::Schroeder,
                };
                self.settings_changed();
            }
            Action::ToggleKeepBorder => {
                self.current_mut().params.keep_border ^= true;
                self.settings_changed();
            }
            Action::ToggleMsaa => self.toggle_msaa(),
            Action::CreaseAngle(delta) => self.change_crease(delta),
            Action::ToggleNavigation => {
                let camera = &mut self.current_mut().camera;
                let next = match camera.navigation {
                    Navigation::Model => Navigation::Eye,
                    Navigation::Eye => Navigation::Model,
                };
                camera.set_navigation(next);
                self.follow_current_camera();
            }
            Action::ResetView => {
                self.current_mut().camera.reset();
                self.follow_current_camera();
            }
            Action::ToggleLinkedCameras => self.toggle_linked(),
            Action::AddViewport => self.add_viewport(),
            Action::RemoveViewport => self.remove_viewport(),
            Action::NextViewport => self.current = (self.current + 1) % self.viewports.len(),
            Action::ToggleHelp => self.help ^= true,
            Action::Save => self.save(),
            Action::SavePicture => return Effect::SavePicture,
            Action::Open => return Effect::Dialog(super::file_dialog::DialogKind::Open),
            Action::SaveAs => return Effect::Dialog(super::file_dialog::DialogKind::SaveAs),
            Action::Quit => return self.quit(),
            toggle => self.toggle_draw_option(toggle),
        }
        Effect::None
    }

    /// The draw toggles of the current viewport (triangles, edges, … texture, heat-map).
    fn toggle_draw_option(&mut self, action: Action) {
        let options = &mut self.viewports[self.current].options;
        match action {
            Action::ToggleTriangles => options.triangles ^= true,
            Action::ToggleEdges => options.edges ^= true,
            Action::TogglePoints => options.points ^= true,
            Action::ToggleFaceNormals => options.face_normals ^= true,
            Action::ToggleVertexNormals => options.vertex_normals ^= true,
            Action::ToggleLighting => options.lighting ^= true,
            Action::ToggleSmooth => options.smooth ^= true,
            Action::ToggleErrorMap => options.error_map ^= true,
            Action::ToggleTexture => {
                options.textures ^= true;
                let textured = (self.original.models.iter())
                    .any(|m| m.texture.is_some() && m.texcoords.is_some());
                if !textured {
                    self.message = "this model has no texture: T changes nothing".into();
                }
            }
            _ => {}
        }
    }

    /// `L`: the level-of-detail slider off (the level shown stays), or on (a job builds it).
    fn toggle_lod(&mut self) {
        let i = self.current;
        if self.current_mut().lod_off() {
            self.message = format!("viewport {}: level-of-detail slider off", i + 1);
        } else {
            self.start(Task::Lod, String::new());
        }
    }

    /// `M`: multisampling on (as many samples as asked, where the device has them) or off.
    fn toggle_msaa(&mut self) {
        self.msaa = if self.msaa > 1 {
            1
        } else {
            crate::render::pipeline::DEFAULT_MSAA
        };
        self.message = if self.msaa > 1 {
            format!(
                "anti-aliasing on ({}× MSAA where the device has it)",
                self.msaa
            )
        } else {
            "anti-aliasing off".into()
        };
    }

    /// `[` / `]`: the current viewport's crease angle by `delta` degrees.
    fn change_crease(&mut self, delta: i16) {
        let n = self.current + 1;
        self.message = match self.current_mut().change_crease(f32::from(delta)) {
            Some(d) => format!("viewport {n}: crease angle {d:.0}° (180: fully smooth)"),
            None => format!(
                "viewport {n}: the level-of-detail slider keeps the original's crease angle"
            ),
        };
    }

    /// `c`: every viewport follows the current one's camera, or each keeps its own.
    fn toggle_linked(&mut self) {
        self.linked ^= true;
        self.follow_current_camera();
        self.message = if self.linked {
            format!("cameras linked to viewport {}'s", self.current + 1)
        } else {
            "each viewport has its own camera".into()
        };
    }

    /// `a`: a viewport of the original, made current, up to [`MAX_VIEWPORTS`].
    fn add_viewport(&mut self) {
        if self.viewports.len() >= MAX_VIEWPORTS {
            self.message = format!("at most {MAX_VIEWPORTS} viewports");
            return;
        }
        let id = self.next_id;
        self.next_id += 1;
        let mut vp = Viewport::new(id, self.original.clone(), self.original_counts, self.params);
        vp.options = self.draw_options;
        self.viewports.push(vp);
        self.current = self.viewports.len() - 1;
        if self.linked {
            // A new viewport joins the others' shared camera.
            self.viewports[self.current].camera = self.viewports[0].camera.clone();
        }
    }

    /// `x`: the current viewport goes (its job with it); the last one stays.
    fn remove_viewport(&mut self) {
        if self.viewports.len() <= 1 {
            self.message = "the last viewport stays".into();
            return;
        }
        let gone = self.viewports.remove(self.current);
        // Its job, if it has one, works for nobody now.
        if self.job.as_ref().is_some_and(|r| r.viewport == gone.id) {
            self.drop_job();
        }
        self.current = self.current.min(self.viewports.len() - 1);
    }

    /// Whether the toggle `action` is on for the current viewport (the popup's check marks);
    /// `None` when `action` is no toggle.
    pub fn checked(&self, action: Action) -> Option<bool> {
        let vp = self.current_viewport();
        let o = &vp.options;
        Some(match action {
            Action::ToggleTriangles => o.triangles,
            Action::ToggleEdges => o.edges,
            Action::TogglePoints => o.points,
            Action::ToggleFaceNormals => o.face_normals,
            Action::ToggleVertexNormals => o.vertex_normals,
            Action::ToggleLighting => o.lighting,
            Action::ToggleSmooth => o.smooth,
            Action::ToggleTexture => o.textures,
            Action::ToggleErrorMap => o.error_map,
            Action::ToggleMsaa => self.msaa > 1,
            Action::ToggleLod => vp.lod().is_some(),
            Action::ToggleKeepBorder => vp.params.keep_border,
            Action::ToggleAlgorithm => vp.params.algorithm == Algorithm::Qem,
            Action::ToggleLinkedCameras => self.linked,
            Action::ToggleHelp => self.help,
            _ => return None,
        })
    }

    /// The file F3 writes next: `save_path`, or its first free numbered sibling.
    pub fn next_save(&self) -> Option<PathBuf> {
        save_path(&self.save_path, &self.inputs).map(|p| p.path().to_path_buf())
    }

    /// F3: the current viewport's scene as VRML 2.0, its texture names rebased for the
    /// folder it is saved in; written through a temporary file and a rename, and never over
    /// an input file (then to `out-1.wrl`…, said in the message).
    fn save(&mut self) {
        self.current_mut().settle();
        let n = self.current + 1;
        let Some(target) = save_path(&self.save_path, &self.inputs) else {
            self.message = format!(
                "cannot save: {} and its numbered alternatives are all input files",
                self.save_path.display()
            );
            eprintln!("decimate: {}", self.message);
            return;
        };
        let path = target.path();
        let id_generation = (
            self.current_viewport().id,
            self.current_viewport().generation,
        );
        let to_dir = decimate_core::io::texture_path::folder_of(path);
        let scene =
            decimate_core::io::rebased(self.current_viewport().scene(), &self.input_dir, to_dir);
        self.message = match (decimate_core::io::write_vrml2(&scene, path), &target) {
            (Ok(()), SavePath::AsAsked(_)) => format!("saved viewport {n} as {}", path.display()),
            (Ok(()), SavePath::Instead(_)) => format!(
                "{} is the input file, not written over: saved viewport {n} as {}",
                self.save_path.display(),
                path.display()
            ),
            (Ok(()), SavePath::Numbered(_)) => {
                format!(
                    "saved viewport {n} as {} (kept the earlier saves)",
                    path.display()
                )
            }
            (Err(e), _) => format!("cannot save: {e}"),
        };
        if !self.message.starts_with("cannot") {
            self.saved.retain(|(id, _)| *id != id_generation.0);
            self.saved.push(id_generation);
        }
        eprintln!("decimate: {}", self.message);
    }
}

impl ViewportController {
    /// Save as…: the current viewport's scene written to `path` in the format its extension
    /// names, texture names rebased for its folder, through a temporary file; never over an
    /// input file. The dialog asked before a file that exists is replaced.
    pub fn save_as(&mut self, path: &std::path::Path) {
        self.current_mut().settle();
        let n = self.current + 1;
        let is_input =
            |p: &std::path::Path| (self.inputs.iter()).any(|i| i == p || same_file(i, p));
        if is_input(path) {
            self.message = format!("{} is an input file: not written over", path.display());
            eprintln!("decimate: {}", self.message);
            return;
        }
        let id = self.current_viewport().id;
        let generation = self.current_viewport().generation;
        let to_dir = decimate_core::io::texture_path::folder_of(path);
        let scene =
            decimate_core::io::rebased(self.current_viewport().scene(), &self.input_dir, to_dir);
        self.message = match decimate_core::io::write_scene(&scene, path) {
            Ok(()) => {
                self.saved.retain(|(saved, _)| *saved != id);
                self.saved.push((id, generation));
                format!("saved viewport {n} as {}", path.display())
            }
            Err(e) => format!("cannot save: {e}"),
        };
        eprintln!("decimate: {}", self.message);
    }

    /// The folder Save as… and Open… start in, and the name Save as… suggests.
    pub fn dialog_start(&self, kind: super::file_dialog::DialogKind) -> (PathBuf, String) {
        match kind {
            super::file_dialog::DialogKind::Open => (self.input_dir.clone(), String::new()),
            super::file_dialog::DialogKind::SaveAs => {
                let folder = decimate_core::io::texture_path::folder_of(&self.save_path);
                let name = self.save_path.file_name().unwrap_or_default();
                (folder.to_path_buf(), name.to_string_lossy().into_owned())
            }
        }
    }
}

/// Whether `a` and `b` name the same file (both exist and resolve to one path).
fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
}

/// "viewport 2" or "viewports 1, 3", for the quit question.
fn viewport_list(numbers: &[usize]) -> String {
    let list: Vec<String> = numbers.iter().map(usize::to_string).collect();
    match numbers.len() {
        1 => format!("viewport {}", list[0]),
        _ => format!("viewports {}", list.join(", ")),
    }
}

/// A vertex count typed into the field: a whole number from 0 to `original` (digit groups may
/// be separated by `,` or `_`).
pub fn parse_vertex_count(text: &str, original: usize) -> Result<usize, String> {
    let range = format!("type a whole number from 0 to {original} (0: as far as possible)");
    let digits: String = text
        .trim()
        .chars()
        .filter(|c| !matches!(c, ',' | '_'))
        .collect();
    if digits.is_empty() {
        return Err(format!("no number: {range}"));
    }
    let n: usize = match digits.parse() {
        Ok(n) => n,
        Err(_) if digits.bytes().all(|b| b.is_ascii_digit()) => usize::MAX,
        Err(_) => return Err(format!("'{}' is not a vertex count: {range}", text.trim())),
    };
    if n > original {
        return Err(format!(
            "{} is more than the original's {original} vertices: {range}",
            text.trim()
        ));
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::menu::{action_for_key, Key};
    use decimate_core::mesh::{shapes, Model};
    use glam::Vec3;

    /// A 10×10 grid plane (121 vertices, 200 triangles): test003.
    fn plane() -> Scene {
        Scene {
            models: vec![shapes::test003()],
        }
    }

    fn controller() -> ViewportController {
        ViewportController::new(plane(), Params::default(), 800, 600)
    }

    /// Presses `k` and waits for the job it started, if any, to end.
    fn key(c: &mut ViewportController, k: Key) -> Effect {
        let action = action_for_key(k).unwrap_or_else(|| panic!("{k:?} is not bound"));
        let effect = c.dispatch(action);
        c.wait();
        effect
    }

    #[test]
    fn toggles_reach_the_current_viewport_only() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        assert_eq!(c.current(), 1);
        type Get = fn(&DrawOptions) -> bool;
        let toggles: [(char, Get); 7] = [
            ('t', |o| o.triangles),
            ('e', |o| o.edges),
            ('p', |o| o.points),
            ('n', |o| o.face_normals),
            ('N', |o| o.vertex_normals),
            ('l', |o| o.lighting),
            ('s', |o| o.smooth),
        ];
        for (k, get) in toggles {
            let before = get(&c.viewports()[1].options);
            key(&mut c, Key::Char(k));
            assert_eq!(get(&c.viewports()[1].options), !before, "key {k}");
            assert_eq!(get(&c.viewports()[0].options), before, "key {k} leaked");
        }
    }

    #[test]
    fn panning_slides_the_current_viewport_only_and_reset_undoes_it() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        // Two viewports side by side in 800 × 600: the pointer over the right one.
        c.pointer_at(600.0, 300.0);
        assert_eq!(c.current(), 1);
        let framed = c.viewports()[1].camera.clone();
        c.pan(Vec2::new(40.0, -25.0));
        assert_ne!(c.viewports()[1].camera, framed, "the right viewport pans");
        assert_eq!(c.viewports()[0].camera, framed, "the left one stays");
        key(&mut c, Key::Char('r'));
        assert_eq!(c.viewports()[1].camera, framed);
    }

    #[test]
    fn linked_cameras_follow_the_current_viewport() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        c.pointer_at(600.0, 300.0);
        c.drag(Vec2::new(30.0, 10.0));
        assert_ne!(c.viewports()[0].camera, c.viewports()[1].camera);
        // c: the others take the current one's camera, and follow it from then on.
        key(&mut c, Key::Char('c'));
        assert_eq!(c.viewports()[0].camera, c.viewports()[1].camera);
        c.pointer_at(100.0, 300.0);
        assert_eq!(c.current(), 0);
        c.drag(Vec2::new(-50.0, 20.0));
        c.wheel(2.0);
        c.pan(Vec2::new(15.0, 5.0));
        assert_eq!(c.viewports()[0].camera, c.viewports()[1].camera);
        key(&mut c, Key::Char('a'));
        assert_eq!(c.viewports()[2].camera, c.viewports()[0].camera);
        // c again: each its own.
        key(&mut c, Key::Char('c'));
        c.drag(Vec2::new(40.0, 0.0));
        assert_ne!(c.viewports()[2].camera, c.viewports()[0].camera);
        assert_eq!(c.viewports()[0].camera, c.viewports()[1].camera);
    }

    #[test]
    fn brackets_change_the_crease_angle_of_the_current_viewport() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        key(&mut c, Key::Char(']'));
        assert!(c.message.contains("crease angle 60°"), "{}", c.message);
        assert_eq!(c.current_viewport().generation, 1, "uploaded again");
        for _ in 0..10 {
            key(&mut c, Key::Char(']'));
        }
        assert!(c.message.contains("crease angle 180°"), "{}", c.message);
        let crease =
            |c: &ViewportController, i: usize| c.viewports()[i].scene().models[0].crease_angle;
        assert_eq!(crease(&c, 1), Some(std::f32::consts::PI));
        assert_eq!(crease(&c, 0), None, "the other viewport keeps its own");
        // A decimation keeps it; [ goes back down.
        key(&mut c, Key::Char('5'));
        assert_eq!(crease(&c, 1), Some(std::f32::consts::PI));
        key(&mut c, Key::Char('['));
        assert!(c.message.contains("crease angle 165°"), "{}", c.message);
    }

    #[test]
    fn the_menu_checks_the_toggles_that_are_on() {
        let mut c = controller();
        assert_eq!(c.checked(Action::ToggleTriangles), Some(true));
        assert_eq!(c.checked(Action::ToggleEdges), Some(false));
        key(&mut c, Key::Char('e'));
        key(&mut c, Key::Char('c'));
        assert_eq!(c.checked(Action::ToggleEdges), Some(true));
        assert_eq!(c.checked(Action::ToggleLinkedCameras), Some(true));
        assert_eq!(c.checked(Action::ResetView), None, "no toggle");
        // Every toggle of the menu has a state to show.
        for a in crate::app::menu::actions(&crate::app::menu::menu()) {
            let name = format!("{a:?}");
            assert_eq!(
                c.checked(a).is_some(),
                name.starts_with("Toggle") && name != "ToggleNavigation",
                "{name}"
            );
        }
    }

    #[test]
    fn a_dropped_file_replaces_the_viewports_and_becomes_the_input() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        key(&mut c, Key::Char('5'));
        let cube = Scene {
            models: vec![shapes::test004()],
        };
        let dir = std::env::temp_dir().join(format!("decimate-drop-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join("out.wrl");
        decimate_core::io::write_vrml2(&cube, &path).unwrap_or_else(|e| panic!("{e}"));
        let before = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
        c.open(cube, &path);
        assert_eq!(c.viewports().len(), 1);
        assert_eq!(c.current_viewport().vertex_count(), 602);
        assert!(
            c.message.contains("602 vertices, 1200 triangles"),
            "{}",
            c.message
        );
        assert_eq!(c.original_vertices(), 602);
        // F3 now keeps the dropped file too.
        c.save_path = path.clone();
        key(&mut c, Key::F3);
        assert_eq!(
            std::fs::read(&path).unwrap_or_else(|e| panic!("{e}")),
            before
        );
        assert!(dir.join("out-1.wrl").exists());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_command_lines_modes_reach_every_viewport() {
        let mut c = controller();
        // What `--mode edges,flat` parses to.
        let modes = DrawOptions {
            triangles: false,
            edges: true,
            smooth: false,
            ..DrawOptions::default()
        };
        c.set_draw_options(modes);
        key(&mut c, Key::Char('a'));
        for vp in c.viewports() {
            assert_eq!(vp.options, modes);
        }
        assert!(!modes.triangles && modes.edges && !modes.smooth);
    }

    #[test]
    fn decimate_events_reach_the_current_viewport_only() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        key(&mut c, Key::Char('5'));
        assert_eq!(c.viewports()[0].vertex_count(), 121);
        assert_eq!(c.viewports()[0].generation, 0);
        assert_eq!(c.viewports()[1].generation, 1);
        assert!(c.viewports()[1].last.is_some());
        assert!(c.message.contains("viewport 2"), "{}", c.message);
    }

    #[test]
    fn a_running_decimation_leaves_the_viewport_as_it_was_until_esc_cancels_it() {
        let sphere = shapes::bumpy_sphere(200, 400);
        let n = sphere.used_vertex_count();
        let scene = Scene {
            models: vec![sphere],
        };
        let mut c = ViewportController::new(scene, Params::default(), 800, 600);
        // Not waited for: the window keeps drawing the original meanwhile.
        c.dispatch(Action::Decimate(DecimateEvent {
            amount: 90.0,
            kind: DecimateKind::Percentage,
        }));
        assert!(c.busy());
        let status = c.job_status().unwrap_or_default();
        assert!(
            status.starts_with("viewport 1: decimating (90 % removed) [")
                && status.ends_with("Esc cancels"),
            "{status}"
        );
        assert_eq!(c.current_viewport().vertex_count(), n);
        assert_eq!(c.current_viewport().generation, 0);
        assert!(c.cancel_job());
        assert!(!c.busy() && c.job_status().is_none());
        assert!(
            c.message.starts_with("cancelled: viewport 1: decimating")
                && c.message.ends_with(&format!(
                    "viewport 1 still shows {n} vertices, 159200 triangles"
                )),
            "{}",
            c.message
        );
        std::thread::sleep(std::time::Duration::from_millis(200));
        assert!(!c.poll(), "a cancelled job is forgotten");
        assert_eq!(c.current_viewport().vertex_count(), n);
        assert_eq!(c.current_viewport().generation, 0);
        assert!(!c.cancel_job(), "nothing left to cancel: Esc quits");
    }

    #[test]
    fn removing_a_viewport_stops_its_job() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        c.dispatch(action_for_key(Key::Char('9')).unwrap_or(Action::Quit));
        assert!(c.busy());
        key(&mut c, Key::Char('x'));
        assert!(!c.busy(), "a job for a viewport that is gone still runs");
        assert_eq!(c.viewports().len(), 1);
        assert_eq!(c.current_viewport().vertex_count(), 121);
    }

    #[test]
    fn the_latest_decimate_event_wins() {
        let mut c = controller();
        c.dispatch(action_for_key(Key::Char('9')).unwrap_or(Action::Quit));
        key(&mut c, Key::Char('1'));
        assert_eq!(c.current_viewport().vertex_count(), 121 - 12);
        assert!(
            c.message.starts_with("viewport 1: removed 10 %"),
            "{}",
            c.message
        );
        assert_eq!(
            c.current_viewport().generation,
            1,
            "the 90 % result never showed"
        );
    }

    #[test]
    fn d_measures_the_level_shown_and_its_caption_says_it() {
        let scene = Scene {
            models: vec![shapes::bumpy_sphere(12, 24)],
        };
        let mut c = ViewportController::new(scene, Params::default(), 800, 600);
        key(&mut c, Key::Char('d'));
        let caption = c.current_viewport().caption();
        assert!(
            caption.ends_with(
                "max distance to the input: 0 model units (0.00 % of the diagonal), mean 0"
            ),
            "the original against itself: {caption}"
        );
        key(&mut c, Key::Char('8'));
        assert!(
            !c.current_viewport().caption().contains("distance"),
            "a new level, not measured"
        );
        key(&mut c, Key::Char('d'));
        let error = c.current_viewport().error().copied();
        let error = error.unwrap_or_else(|| panic!("not measured: {}", c.message));
        assert!(
            error.max > 0.0 && error.mean > 0.0 && error.mean < error.max,
            "{error:?}"
        );
        assert!(error.max < 0.2 * error.diagonal, "{error:?}");
        let caption = c.current_viewport().caption();
        assert_eq!(caption.lines().last(), Some(error.words().as_str()));
        assert_eq!(c.message, format!("viewport 1: {}", error.words()));
        // Shading does not change the level: the error stays.
        key(&mut c, Key::Char(']'));
        assert!(c.current_viewport().error().is_some());
    }

    #[test]
    fn captions_count_a_texture_seams_copies_once() {
        // Two quads side by side, cut between them by a texture seam: 8 vertices, 6 points.
        let mut m = Model::default();
        for x in [0.0, 1.0, 1.0, 2.0] {
            for y in [0.0, 1.0] {
                m.positions.push(Vec3::new(x, y, 0.0));
            }
        }
        m.triangles = vec![[0, 2, 3], [0, 3, 1], [4, 6, 7], [4, 7, 5]];
        m.texcoords = Some(vec![[0.0, 0.0]; 8]);
        let c = ViewportController::new(Scene { models: vec![m] }, Params::default(), 800, 600);
        let vp = c.current_viewport();
        assert_eq!(vp.caption(), "original\n6 vertices, 4 triangles");
        assert!(
            vp.status().starts_with("6 vertices, 4 triangles"),
            "{}",
            vp.status()
        );
    }

    #[test]
    fn decimation_always_starts_from_the_original() {
        let mut c = controller();
        key(&mut c, Key::Char('9'));
        let after_90 = c.current_viewport().vertex_count();
        key(&mut c, Key::Char('1'));
        let after_10 = c.current_viewport().vertex_count();
        assert!(
            after_10 >= after_90,
            "10 % after 90 % must go back up: {after_10} < {after_90}"
        );
        assert_eq!(c.current_viewport().original().vertex_count(), 121);
    }

    /// Every vertex position of the current viewport's scene, as bits.
    fn positions(c: &ViewportController) -> Vec<[u32; 3]> {
        let scene = c.current_viewport().scene();
        let points = scene.models.iter().flat_map(|m| &m.positions);
        points.map(|p| p.to_array().map(f32::to_bits)).collect()
    }

    #[test]
    fn two_viewports_compare_the_algorithms_on_the_same_target() {
        let sphere = shapes::bumpy_sphere(12, 24);
        let original: Vec<[u32; 3]> = (sphere.positions.iter())
            .map(|p| p.to_array().map(f32::to_bits))
            .collect();
        let n = sphere.used_vertex_count();
        let scene = Scene {
            models: vec![sphere],
        };
        let mut c = ViewportController::new(scene, Params::default(), 800, 600);
        key(&mut c, Key::Char('a'));
        key(&mut c, Key::Char('8'));
        // Viewport 2, vertex removal (the command line's default): original points only.
        let kept = c.current_viewport().vertex_count();
        assert_eq!(kept, n - (0.8 * n as f64).round() as usize);
        assert!(positions(&c).iter().all(|p| original.contains(p)));
        assert!(c
            .current_viewport()
            .status()
            .contains("decimated by schroeder"));
        // A switch makes the same decimation again by quadric edge collapse: the same
        // count, vertices moved.
        key(&mut c, Key::Char('A'));
        assert!(
            c.message
                .starts_with("viewport 2: quadric edge collapse, border free; removed 80 %"),
            "{}",
            c.message
        );
        assert_eq!(c.current_viewport().vertex_count(), kept);
        assert!(positions(&c).iter().any(|p| !original.contains(p)));
        assert!(c.current_viewport().status().contains("decimated by qem"));
        // Viewport 1 was not decimated: the switch holds for its next decimation.
        key(&mut c, Key::Tab);
        key(&mut c, Key::Char('A'));
        assert_eq!(
            c.message,
            "viewport 1: quadric edge collapse, border free from the next decimation"
        );
        assert_eq!(c.current_viewport().vertex_count(), n);
        key(&mut c, Key::Char('8'));
        assert_eq!(c.current_viewport().vertex_count(), kept);
        // The level-of-detail slider shows its own levels: a switch then waits too.
        key(&mut c, Key::Char('L'));
        key(&mut c, Key::Char('A'));
        assert_eq!(
            c.message,
            "viewport 1: vertex removal, border free from the next decimation"
        );
        assert!(!c.current_viewport().status().contains("decimated by"));
    }

    #[test]
    fn keeping_the_border_holds_the_plane_outline() {
        let mut c = controller();
        key(&mut c, Key::Char('0'));
        // As far as possible, the plane goes down to its four corners (test003)…
        assert_eq!(c.current_viewport().vertex_count(), 4);
        // …or, its border kept, to the 40 points of its outline, decimated again at once.
        key(&mut c, Key::Char('b'));
        assert!(
            c.message.contains("border kept; removed 100 %"),
            "{}",
            c.message
        );
        assert_eq!(c.current_viewport().vertex_count(), 40);
        let outline = |p: &[u32; 3]| {
            let [x, y, _] = p.map(f32::from_bits);
            x == 0.0 || x == 10.0 || y == 0.0 || y == 10.0
        };
        assert!(positions(&c).iter().all(outline));
        key(&mut c, Key::Char('b'));
        assert_eq!(c.current_viewport().vertex_count(), 4);
    }

    #[test]
    fn viewports_add_up_to_four_and_the_last_one_stays() {
        let mut c = controller();
        for _ in 0..5 {
            key(&mut c, Key::Char('a'));
        }
        assert_eq!(c.viewports().len(), 4);
        assert_eq!(c.rects().len(), 4);
        for _ in 0..5 {
            key(&mut c, Key::Char('x'));
        }
        assert_eq!(c.viewports().len(), 1);
        assert_eq!(c.current(), 0);
    }

    #[test]
    fn tab_cycles_and_the_mouse_picks_the_viewport_under_it() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        key(&mut c, Key::Tab);
        assert_eq!(c.current(), 0);
        key(&mut c, Key::Tab);
        assert_eq!(c.current(), 1);
        c.pointer_at(10.0, 300.0);
        assert_eq!(c.current(), 0);
        c.pointer_at(790.0, 300.0);
        assert_eq!(c.current(), 1);
    }

    #[test]
    fn navigation_help_reset_quit_and_text_field() {
        let mut c = controller();
        key(&mut c, Key::Char('m'));
        assert_eq!(c.current_viewport().camera.navigation, Navigation::Eye);
        key(&mut c, Key::Char('m'));
        assert_eq!(c.current_viewport().camera.navigation, Navigation::Model);
        let framed = c.current_viewport().camera.clone();
        c.drag(Vec2::new(30.0, 5.0));
        assert_ne!(c.current_viewport().camera, framed);
        key(&mut c, Key::Char('r'));
        assert_eq!(c.current_viewport().camera, framed);
        key(&mut c, Key::Char('h'));
        assert!(c.help);
        // T on a model with no texture says so, rather than doing nothing visible.
        key(&mut c, Key::Char('T'));
        assert!(c.message.contains("no texture"), "{}", c.message);
        // The algorithm entry shows its state: checked for quadric edge collapse.
        let qem = c.current_viewport().params.algorithm == Algorithm::Qem;
        assert_eq!(c.checked(Action::ToggleAlgorithm), Some(qem));
        key(&mut c, Key::Char('A'));
        assert_eq!(c.checked(Action::ToggleAlgorithm), Some(!qem));
        assert_eq!(key(&mut c, Key::Char('v')), Effect::AskVertexCount);
        // Esc is no key of the controller: the window closes overlays and cancels with it.
        assert_eq!(action_for_key(Key::Escape), None);
        assert_eq!(key(&mut c, Key::Char('q')), Effect::Quit);
    }

    #[test]
    fn quitting_asks_while_a_decimated_viewport_is_unsaved() {
        let mut c = controller();
        key(&mut c, Key::Char('9'));
        c.wait();
        assert_eq!(c.unsaved(), vec![1]);
        // The first q asks; the second (the answer) quits.
        assert_eq!(key(&mut c, Key::Char('q')), Effect::None);
        assert!(c.confirm_quit, "q quit with viewport 1 unsaved");
        assert!(c.message.contains("viewport 1 not saved"), "{}", c.message);
        assert_eq!(key(&mut c, Key::Char('q')), Effect::Quit);
        // Once saved, q quits at once.
        c.confirm_quit = false;
        let dir = std::env::temp_dir().join(format!("decimate-quit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        c.save_path = dir.join("saved.wrl");
        key(&mut c, Key::F3);
        assert_eq!(c.unsaved(), Vec::<usize>::new(), "{}", c.message);
        assert_eq!(key(&mut c, Key::Char('q')), Effect::Quit);
        // An added viewport shows the original: nothing to lose.
        key(&mut c, Key::Char('a'));
        assert_eq!(c.unsaved(), Vec::<usize>::new());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn decimate_to_n_vertices_reaches_n_and_says_the_counts_shown() {
        let mut c = controller();
        assert_eq!(c.submit_vertex_count(" 60\n"), Ok(()));
        c.wait();
        assert_eq!(c.current_viewport().vertex_count(), 60);
        let triangles = c.current_viewport().triangle_count();
        assert!(
            c.message
                .contains(&format!(": 60 vertices, {triangles} triangles left")),
            "{}",
            c.message
        );
        assert_eq!(c.current_viewport().generation, 1);
        // All of them: nothing removed, the original shown.
        assert_eq!(c.submit_vertex_count("121"), Ok(()));
        c.wait();
        assert_eq!(c.current_viewport().vertex_count(), 121);
    }

    #[test]
    fn the_vertex_field_refuses_what_is_no_count_of_the_scene() {
        let mut c = controller();
        for (text, says) in [
            ("abc", "'abc' is not a vertex count"),
            ("-5", "'-5' is not a vertex count"),
            ("12.5", "'12.5' is not a vertex count"),
            ("", "no number"),
            ("99999", "99999 is more than the original's 121 vertices"),
            ("99999999999999999999999", "is more than the original's 121"),
        ] {
            let e = c.submit_vertex_count(text).unwrap_err();
            assert!(e.contains(says), "{text:?}: {e}");
            assert!(e.contains("from 0 to 121"), "{text:?}: {e}");
        }
        assert_eq!(c.current_viewport().generation, 0, "nothing was decimated");
        assert_eq!(parse_vertex_count("1,000", 5000), Ok(1000));
    }

    #[test]
    fn zero_vertices_is_key_zero() {
        let cube = Scene {
            models: vec![shapes::test004()],
        };
        let mut by_key = ViewportController::new(cube.clone(), Params::default(), 800, 600);
        key(&mut by_key, Key::Char('0'));
        let mut by_field = ViewportController::new(cube, Params::default(), 800, 600);
        assert_eq!(by_field.submit_vertex_count("0"), Ok(()));
        by_field.wait();
        for c in [&by_key, &by_field] {
            let vp = c.current_viewport();
            // The cube's eight corners are features: "as far as possible" keeps them.
            assert_eq!((vp.vertex_count(), vp.triangle_count()), (8, 12));
            assert!(
                c.message.contains("8 vertices, 12 triangles left"),
                "{}",
                c.message
            );
        }
    }

    #[test]
    fn the_lod_slider_reaches_the_current_viewport_only_and_saves_what_it_shows() {
        let mut c = controller();
        key(&mut c, Key::Char('a'));
        key(&mut c, Key::Char('L'));
        let (lo, hi) = c
            .current_viewport()
            .lod()
            .map(|l| l.range())
            .unwrap_or_default();
        assert_eq!(hi, 121);
        assert_eq!(
            lo, 4,
            "a plane's progressive mesh goes down to its four corners"
        );
        assert!(c.viewports()[0].lod().is_none());
        let t0 = std::time::Instant::now();
        c.set_lod_vertices(30, t0);
        assert!(c.tick(t0), "a geomorph runs");
        assert!(!c.tick(t0 + crate::app::lod::GEOMORPH));
        assert_eq!(c.current_viewport().vertex_count(), 30);
        // F3 in the middle of a coarsening morph saves the level it goes to, not the fine
        // mesh with its collapsing triangles.
        let dir = std::env::temp_dir().join(format!("decimate-lod-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        c.save_path = dir.join("out.wrl");
        c.set_lod_vertices(10, t0);
        key(&mut c, Key::F3);
        let saved = decimate_core::io::read_scene(&c.save_path).unwrap_or_else(|e| panic!("{e}"));
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(saved.scene.models[0].used_vertex_count(), 10);
        assert_eq!(
            decimate_core::mesh::measure::degenerate_triangles(&saved.scene.models[0], 1e-9),
            0
        );
        c.set_lod_vertices(30, t0);
        c.tick(t0 + crate::app::lod::GEOMORPH);
        assert_eq!(c.viewports()[0].vertex_count(), 121);
        // Off: the level shown stays, and a decimate event starts from the original again.
        key(&mut c, Key::Char('L'));
        assert!(c.current_viewport().lod().is_none());
        assert_eq!(c.current_viewport().vertex_count(), 30);
        key(&mut c, Key::Char('L'));
        key(&mut c, Key::Char('5'));
        assert!(c.current_viewport().lod().is_none());
        assert_eq!(c.current_viewport().vertex_count(), 60);
    }

    #[test]
    fn f3_saves_the_current_viewport() {
        let dir = std::env::temp_dir().join(format!("decimate-f3-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let _ = std::fs::remove_file(dir.join("out.wrl"));
        let _ = std::fs::remove_file(dir.join("out-1.wrl"));
        let mut c = controller();
        c.save_path = dir.join("out.wrl");
        assert_eq!(c.next_save(), Some(dir.join("out.wrl")));
        key(&mut c, Key::Char('9'));
        key(&mut c, Key::F3);
        let saved = decimate_core::io::read_scene(&c.save_path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            saved.scene.models[0].used_vertex_count(),
            c.current_viewport().vertex_count()
        );
        // What the menu's Save entry names next: the numbered sibling, not the save just made.
        assert_eq!(c.next_save(), Some(dir.join("out-1.wrl")));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn f3_never_writes_over_the_input_file() {
        let dir = std::env::temp_dir().join(format!("decimate-f3-in-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let input = dir.join("out.wrl");
        decimate_core::io::write_vrml2(&plane(), &input).unwrap_or_else(|e| panic!("{e}"));
        let before = std::fs::read(&input).unwrap_or_else(|e| panic!("{e}"));
        let mut c = controller();
        c.save_path = input.clone();
        c.inputs = vec![input.clone()];
        key(&mut c, Key::Char('5'));
        key(&mut c, Key::F3);
        assert_eq!(
            std::fs::read(&input).unwrap_or_else(|e| panic!("{e}")),
            before,
            "the input changed"
        );
        let instead = dir.join("out-1.wrl");
        assert!(c.message.contains("out-1.wrl"), "{}", c.message);
        assert!(c.message.contains("input"), "{}", c.message);
        let saved = decimate_core::io::read_scene(&instead).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(saved.scene.models[0].used_vertex_count(), 60);
        // No temporary file is left beside them.
        let names = std::fs::read_dir(&dir).map_or(0, |d| d.count());
        assert_eq!(names, 2);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn f3_points_the_texture_at_the_image_read_beside_the_input() {
        let dir = std::env::temp_dir().join(format!("decimate-f3-tex-{}", std::process::id()));
        let (input_dir, out_dir) = (dir.join("scan"), dir.join("saved"));
        for d in [&input_dir, &out_dir] {
            std::fs::create_dir_all(d).unwrap_or_else(|e| panic!("{e}"));
        }
        let mut scene = plane();
        let m = &mut scene.models[0];
        m.texcoords = Some(
            m.positions
                .iter()
                .map(|p| [p.x / 10.0, p.y / 10.0])
                .collect(),
        );
        m.texture = Some("maps/skin.jpg".into());
        let mut c = ViewportController::new(scene, Params::default(), 800, 600);
        c.input_dir = input_dir;
        c.save_path = out_dir.join("out.wrl");
        key(&mut c, Key::F3);
        // Read as text: a reader keeps references inside the model's folder, so it would
        // drop this one (io::file_limits); what matters is where the file points.
        let saved = std::fs::read_to_string(&c.save_path).unwrap_or_else(|e| panic!("{e}"));
        assert!(saved.contains("\"../scan/maps/skin.jpg\""), "{saved}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

//! `Viewer`: the interactive viewer's callbacks. It owns the `ViewportController` (what is
//! shown) and the GPU side (context, swapchain, pipelines, one `GpuScene` per viewport,
//! uploaded again only when that viewport's scene changes), and turns window events into
//! `Action`s through the same menu data as the popup.

use std::sync::Arc;
use std::time::Instant;

use ash::vk;
use glam::Vec2;
use winit::window::Window;

use crate::io::texture_image;
use crate::render::camera::Navigation;
use crate::render::commands::Commands;
use crate::render::context::{Context, DevicePreference};
use crate::render::draw::{self, ViewportDraw, BACKGROUND};
use crate::render::gpu_mesh::GpuScene;
use crate::render::image::{self, Transition, DEPTH_FORMAT};
use crate::render::pipeline::Pipelines;
use crate::render::swapchain::Swapchain;
use crate::render::texture::Textures;

use super::controller::{Effect, ViewportController};
use super::glut::{Button, Callbacks, Flow, Special};
use super::menu::{action_for_key, key_help, Key, MenuEntry};
use super::ui::{UiLayer, UiState};

/// GPU objects of the window; field order is drop order (UI and meshes before the context).
struct Gpu {
    ui: UiLayer,
    scenes: Vec<(u64, u64, GpuScene)>,
    /// Uploaded once per name, shared by every viewport's scenes; dropped before the
    /// pipelines, whose set layout its sets were made with.
    textures: Textures,
    pipelines: Pipelines,
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
    field: Option<String>,
    help_text: String,
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
            help_text: key_help(),
        }
    }

    fn run_effect(&mut self, effect: Effect) -> Flow {
        match effect {
            Effect::None => Flow::Continue,
            Effect::AskVertexCount => {
                self.field = Some(String::new());
                Flow::Continue
            }
            Effect::Quit => Flow::Quit,
        }
    }

    fn status(&self) -> String {
        let vp = self.controller.current_viewport();
        let mut s = format!(
            "viewport {}/{}: {}",
            self.controller.current() + 1,
            self.controller.viewports().len(),
            vp.status()
        );
        if !self.controller.message.is_empty() {
            s.push('\n');
            s.push_str(&self.controller.message);
        }
        s
    }

    /// Uploads the scenes whose generation changed, or whose draw modes now need a list that
    /// was left out (then with the lists it had too, so toggling a mode back and forth
    /// uploads once), and forgets removed viewports.
    fn sync_scenes(gpu: &mut Gpu, controller: &ViewportController) -> Result<(), String> {
        let viewports = controller.viewports();
        gpu.scenes
            .retain(|(id, _, _)| viewports.iter().any(|v| v.id == *id));
        for vp in viewports {
            let needed = vp.options.layers();
            let uploaded = gpu
                .scenes
                .iter()
                .find(|(id, generation, _)| *id == vp.id && *generation == vp.generation)
                .map(|(_, _, scene)| scene.layers);
            if uploaded.is_none_or(|layers| !layers.contains(needed)) {
                gpu.context.wait_idle().map_err(|e| e.to_string())?;
                let morph_from = vp.lod().and_then(|l| l.morph_from());
                let scene = GpuScene::upload_morphing(
                    &gpu.context,
                    &gpu.upload_commands,
                    &mut gpu.textures,
                    vp.scene(),
                    morph_from,
                    uploaded.map_or(needed, |layers| layers.union(needed)),
                )
                .map_err(|e| format!("cannot upload the scene: {e}"))?;
                gpu.scenes.retain(|(id, _, _)| *id != vp.id);
                gpu.scenes.push((vp.id, vp.generation, scene));
            }
        }
        Ok(())
    }

    fn draw_frame(&mut self, window: &Window) -> Result<(), String> {
        // Geomorphs advance with the clock; while one runs, frames keep coming.
        let now = Instant::now();
        let morphing = self.controller.tick(now);
        let status = self.status();
        let lod = self.controller.current_viewport().lod().map(|l| {
            let (lo, hi) = l.range();
            (lo, hi, l.target())
        });
        let help = self.controller.help.then_some(self.help_text.as_str());
        let Some(gpu) = self.gpu.as_mut() else {
            return Ok(());
        };
        if self.resized {
            gpu.swapchain
                .recreate(self.size.0, self.size.1)
                .map_err(|e| e.to_string())?;
            self.resized = false;
        }
        Self::sync_scenes(gpu, &self.controller)?;
        let scale = window.scale_factor() as f32;
        let ui_result = gpu.ui.run(
            window,
            &gpu.context,
            &gpu.upload_commands,
            UiState {
                menu: &self.menu,
                popup_at: self.popup_at.map(|p| egui::pos2(p.x / scale, p.y / scale)),
                popup_just_opened: self.popup_just_opened,
                field: self.field.as_mut(),
                status: &status,
                help,
                lod,
            },
        )?;

        let Some(frame) = gpu.swapchain.acquire().map_err(|e| e.to_string())? else {
            self.resized = true;
            window.request_redraw();
            return Ok(());
        };
        let extent = gpu.swapchain.extent;
        let views: Vec<_> = self
            .controller
            .rects_for(extent.width, extent.height)
            .into_iter()
            .zip(self.controller.viewports())
            .filter_map(|(rect, vp)| {
                let (_, _, scene) = gpu.scenes.iter().find(|(id, _, _)| *id == vp.id)?;
                Some(ViewportDraw {
                    rect,
                    scene,
                    camera: &vp.camera,
                    options: vp.options,
                    morph: vp.lod().map_or(1.0, |l| l.morph_factor(now)),
                })
            })
            .collect();
        let rects: Vec<_> = views.iter().map(|v| v.rect).collect();
        let highlight = (rects.len() > 1).then_some(self.controller.current());
        let device = &gpu.context.device;
        let format = gpu.swapchain.format;
        let depth = gpu
            .swapchain
            .depth
            .as_ref()
            .ok_or("the swapchain has no depth buffer")?;
        let cmd = gpu.frame_commands.begin().map_err(|e| e.to_string())?;
        // SAFETY: `cmd` is recording; the swapchain image, depth buffer, pipelines and scenes
        // stay alive until the frame's fence is waited for (next `acquire` or device idle).
        unsafe {
            image::transition(device, cmd, frame.image, format, image::TO_COLOR_ATTACHMENT);
            image::transition(
                device,
                cmd,
                depth.handle,
                DEPTH_FORMAT,
                image::TO_DEPTH_ATTACHMENT,
            );
            draw::begin_rendering(device, cmd, frame.view, depth.view, extent, BACKGROUND);
            draw::clear_tiles(device, cmd, extent, &rects, highlight);
            draw::record(device, cmd, &gpu.pipelines, &views);
            device.cmd_end_rendering(cmd);
            begin_overlay(device, cmd, frame.view, extent);
        }
        gpu.ui.draw(cmd, extent)?;
        let to_present = Transition {
            old: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            new: vk::ImageLayout::PRESENT_SRC_KHR,
            src_stage: vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
            src_access: vk::AccessFlags2::COLOR_ATTACHMENT_WRITE,
            dst_stage: vk::PipelineStageFlags2::BOTTOM_OF_PIPE,
            dst_access: vk::AccessFlags2::NONE,
        };
        // SAFETY: as above; the overlay pass is still open and ends here.
        unsafe {
            device.cmd_end_rendering(cmd);
            image::transition(device, cmd, frame.image, format, to_present);
        }
        gpu.frame_commands.end().map_err(|e| e.to_string())?;
        let presented = gpu
            .swapchain
            .submit_and_present(cmd, &frame)
            .map_err(|e| e.to_string())?;
        if !presented {
            self.resized = true;
            window.request_redraw();
        }
        gpu.ui.end_frame()?;
        self.popup_just_opened = false;
        if ui_result.repaint || morphing {
            window.request_redraw();
        }
        if let Some(n) = ui_result.lod_vertices {
            self.controller.set_lod_vertices(n, Instant::now());
            window.request_redraw();
        }

        if ui_result.close_popup || ui_result.action.is_some() {
            self.popup_at = None;
            window.request_redraw();
        }
        if ui_result.close_field {
            self.field = None;
            window.request_redraw();
        }
        if let Some(n) = ui_result.decimate_to {
            self.controller.decimate_to(n);
            window.request_redraw();
        }
        if let Some(action) = ui_result.action {
            let effect = self.controller.dispatch(action);
            if self.run_effect(effect) == Flow::Quit {
                return Err(String::new());
            }
            window.request_redraw();
        }
        Ok(())
    }
}

/// Begins a colour-only pass that keeps what was drawn (for the UI).
///
/// # Safety
/// `cmd` must be recording outside rendering, `view` in the colour-attachment layout.
unsafe fn begin_overlay(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    view: vk::ImageView,
    extent: vk::Extent2D,
) {
    let color = [vk::RenderingAttachmentInfo::default()
        .image_view(view)
        .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
        .load_op(vk::AttachmentLoadOp::LOAD)
        .store_op(vk::AttachmentStoreOp::STORE)];
    let info = vk::RenderingInfo::default()
        .render_area(vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent,
        })
        .layer_count(1)
        .color_attachments(&color);
    // SAFETY: guaranteed by the caller.
    unsafe { device.cmd_begin_rendering(cmd, &info) };
}

impl Callbacks for Viewer {
    fn create(&mut self, window: &Arc<Window>) -> Result<(), String> {
        use raw_window_handle::HasDisplayHandle;
        let display = window.display_handle().map_err(|e| e.to_string())?;
        let extensions = ash_window::enumerate_required_extensions(display.as_raw())
            .map_err(|e| format!("no Vulkan surface support for this display: {e}"))?;
        let context =
            Context::new(extensions, true, DevicePreference::Fastest).map_err(|e| e.to_string())?;
        let size = window.inner_size();
        let swapchain = Swapchain::new(&context, window.as_ref(), size.width, size.height)
            .map_err(|e| e.to_string())?;
        let pipelines = Pipelines::new(&context, swapchain.format).map_err(|e| e.to_string())?;
        let textures = Textures::new(
            &context,
            pipelines.texture_layout,
            texture_image::reader(&self.controller.input_dir),
        )
        .map_err(|e| e.to_string())?;
        let ui = UiLayer::new(&context, window, swapchain.format)?;
        eprintln!("decimate: drawing with {}", context.device_name);
        self.gpu = Some(Gpu {
            ui,
            scenes: Vec::new(),
            textures,
            pipelines,
            frame_commands: Commands::new(&context).map_err(|e| e.to_string())?,
            upload_commands: Commands::new(&context).map_err(|e| e.to_string())?,
            swapchain,
            context,
        });
        Ok(())
    }

    fn display(&mut self, window: &Window) -> Flow {
        match self.draw_frame(window) {
            Ok(()) => Flow::Continue,
            Err(e) if e.is_empty() => Flow::Quit,
            Err(e) => {
                eprintln!("decimate: {e}");
                Flow::Quit
            }
        }
    }

    fn reshape(&mut self, width: u32, height: u32) {
        self.size = (width.max(1), height.max(1));
        self.controller.resize(self.size.0, self.size.1);
        self.resized = true;
    }

    fn keyboard(&mut self, key: Key) -> Flow {
        if self.popup_at.is_some() && key == Key::Escape {
            self.popup_at = None;
            return Flow::Continue;
        }
        // W / S walk in eye control; elsewhere they keep their menu meaning.
        let eye = self.controller.current_viewport().camera.navigation == Navigation::Eye;
        match key {
            Key::Char('w') if eye => {
                self.controller.walk(0.1, 0.0);
                return Flow::Continue;
            }
            Key::Char('S') if eye => {
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

    fn special(&mut self, key: Special) {
        let (forward, right) = match key {
            Special::Up => (0.1, 0.0),
            Special::Down => (-0.1, 0.0),
            Special::Left => (0.0, -0.1),
            Special::Right => (0.0, 0.1),
        };
        self.controller.walk(forward, right);
    }

    fn mouse(&mut self, button: Button, pressed: bool, x: f64, y: f64) -> Flow {
        match (button, pressed) {
            (Button::Right, true) => {
                self.controller.pointer_at(x, y);
                self.popup_at = Some(egui::pos2(x as f32, y as f32));
                self.popup_just_opened = true;
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
            self.controller.drag(delta);
        } else if self.panning {
            self.controller.pan(delta);
        } else if self.popup_at.is_none() {
            self.controller.pointer_at(x, y);
        }
    }

    fn wheel(&mut self, steps: f32) {
        self.controller.wheel(steps);
    }

    fn filter(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        let Some(gpu) = self.gpu.as_mut() else {
            return false;
        };
        let consumed = gpu.ui.on_event(window, event);
        // While the popup or the field is open, egui owns the pointer and keyboard it uses.
        let ui_open = self.popup_at.is_some() || self.field.is_some();
        consumed && (ui_open || gpu.ui.wants_pointer())
    }

    fn destroy(&mut self) {
        if let Some(gpu) = &self.gpu {
            let _ = gpu.context.wait_idle();
        }
        self.gpu = None;
    }
}

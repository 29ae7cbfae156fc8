//! `UiLayer`: egui over the Vulkan window — the right-click popup menu (`popup`, built from
//! the menu data), the "decimate to N vertices" text field, the quit question, and what
//! `overlay` paints (status strip, captions, legends, help).
//! Drawn in its own colour-only rendering pass after the viewports.

use std::sync::Arc;

use ash::vk;
use egui_ash_renderer::allocator::GpuAllocator;
use egui_ash_renderer::{DynamicRendering, Options, RenderMode, Renderer};
use winit::window::Window;

use crate::render::commands::Commands;
use crate::render::context::Context;

use super::app_error::AppError;
use super::file_dialog::{self, DialogOutcome, FileDialog};
use super::menu::{Action, MenuEntry};
use super::modal::{confirm_or_cancel, modal, refusal, text_line};
use super::overlay::{self, Overlay};
use super::panel::{self, ViewportPanel};
use super::popup;

/// What the user did in the UI this frame.
#[derive(Debug, Default)]
pub struct UiResult {
    /// A menu entry was chosen.
    pub action: Option<Action>,
    /// The vertex-count field was submitted (Enter or the button) with this text.
    pub vertex_count: Option<String>,
    /// The popup or the field was dismissed.
    pub close_popup: bool,
    pub close_field: bool,
    /// egui wants another frame soon (a popup being measured, hover animation).
    pub repaint: bool,
    /// The level-of-detail slider of a viewport (index from 0) was moved to this many
    /// vertices.
    pub lod_vertices: Option<(usize, usize)>,
    /// The quit question was answered: quit (`true`) or stay.
    pub quit_answer: Option<bool>,
    /// The Open… or Save as… dialog was answered.
    pub dialog: Option<DialogOutcome>,
    /// A viewport's panel was used: the viewport (from 0) and the action.
    pub panel_action: Option<(usize, Action)>,
}

/// The "decimate to N vertices" field while it is open.
#[derive(Debug, Clone, Default)]
pub struct VertexField {
    pub text: String,
    /// Why the last submitted text was refused, shown under the field.
    pub error: Option<String>,
    /// The counts the field accepts, shown as its hint.
    pub hint: String,
}

/// A viewport's level-of-detail slider: inside the viewport, at its top-left corner.
#[derive(Debug, Clone, Copy)]
pub struct LodSlider {
    /// The viewport, from 0.
    pub viewport: usize,
    /// The viewport's top-left corner, in points.
    pub corner: egui::Pos2,
    /// The least and most vertices, and the count it is at.
    pub range: (usize, usize),
    pub at: usize,
}

/// What the UI shows this frame.
pub struct UiState<'a> {
    pub menu: &'a [MenuEntry],
    /// Whether a toggle of the menu is on (`None`: not a toggle).
    pub checked: &'a dyn Fn(Action) -> Option<bool>,
    /// Where the popup is open (logical points), if it is.
    pub popup_at: Option<egui::Pos2>,
    /// The popup opened with this frame's click, which must not count as "clicked elsewhere".
    pub popup_just_opened: bool,
    /// The vertex-count field, if it is open.
    pub field: Option<&'a mut VertexField>,
    /// Captions, legends, status line and help.
    pub overlay: Overlay<'a>,
    /// The level-of-detail slider of each viewport that has it on.
    pub lods: &'a [LodSlider],
    /// The quit question, while it is asked.
    pub confirm: Option<&'a str>,
    /// The Open… or Save as… dialog, while it is shown.
    pub dialog: Option<&'a mut FileDialog>,
    /// Each viewport's panel.
    pub panels: &'a [ViewportPanel],
}

/// egui context, winit glue and Vulkan renderer.
pub struct UiLayer {
    // Field order is drop order: the renderer (which holds an allocator reference) goes first.
    renderer: Renderer<GpuAllocator>,
    state: egui_winit::State,
    ctx: egui::Context,
    primitives: Vec<egui::ClippedPrimitive>,
    textures_to_free: Vec<egui::TextureId>,
    pixels_per_point: f32,
}

impl UiLayer {
    pub fn new(
        context: &Arc<Context>,
        window: &Window,
        color_format: vk::Format,
    ) -> Result<Self, AppError> {
        let ctx = egui::Context::default();
        let state = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            None,
        );
        let renderer = Renderer::with_gpu_allocator(
            context.allocator().clone(),
            context.device.clone(),
            RenderMode::DynamicRendering(DynamicRendering {
                color_attachment_format: color_format,
                depth_attachment_format: None,
                stencil_attachment_format: None,
            }),
            Options {
                in_flight_frames: 1,
                ..Options::default()
            },
        )
        .map_err(|e| AppError::ui("egui renderer", e))?;
        Ok(Self {
            renderer,
            state,
            ctx,
            primitives: Vec::new(),
            textures_to_free: Vec::new(),
            pixels_per_point: 1.0,
        })
    }

    /// Passes a window event to egui; `true` when egui used it (typing in the field, clicking
    /// the menu), so the viewer must not.
    pub fn on_event(&mut self, window: &Window, event: &winit::event::WindowEvent) -> bool {
        self.state.on_window_event(window, event).consumed
    }

    /// Physical pixels per egui point: the window's scale factor times the text zoom.
    pub fn pixels_per_point(&self) -> f32 {
        self.ctx.pixels_per_point()
    }

    /// True when egui wants the pointer (over the popup or the field).
    pub fn wants_pointer(&self) -> bool {
        self.ctx.egui_wants_pointer_input() || self.ctx.is_pointer_over_egui()
    }

    /// Lays out this frame's UI and uploads its textures.
    pub fn run(
        &mut self,
        window: &Window,
        context: &Arc<Context>,
        commands: &Commands,
        ui_state: UiState<'_>,
    ) -> Result<UiResult, AppError> {
        let size = window.inner_size();
        self.ctx
            .set_zoom_factor(overlay::text_scale(size.width, size.height));
        let input = self.state.take_egui_input(window);
        let mut result = UiResult::default();
        let UiState {
            menu,
            checked,
            popup_at,
            popup_just_opened,
            mut field,
            overlay: painted,
            lods,
            confirm,
            mut dialog,
            panels,
        } = ui_state;
        let output = self.ctx.run_ui(input, |ui| {
            let ctx = ui.ctx().clone();
            overlay::paint(&ctx, &painted);
            for p in panels {
                if let Some(chosen) = panel::show(&ctx, p) {
                    result.panel_action = Some(chosen);
                }
            }
            for slider in lods {
                if let Some(n) = lod_slider(&ctx, slider) {
                    result.lod_vertices = Some((slider.viewport, n));
                }
            }
            if let Some(pos) = popup_at {
                let outcome = popup::show(&ctx, menu, checked, pos, popup_just_opened);
                result.action = outcome.action;
                result.close_popup = outcome.close && outcome.action.is_none();
            }
            if let Some(field) = field.as_deref_mut() {
                vertex_field(&ctx, field, &mut result);
            }
            if let Some(dialog) = dialog.as_deref_mut() {
                result.dialog = file_dialog::show(&ctx, dialog);
            }
            if let Some(question) = confirm {
                result.quit_answer = quit_question(&ctx, question);
            }
        });
        result.repaint = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .is_some_and(|v| v.repaint_delay.is_zero());
        self.state
            .handle_platform_output(window, output.platform_output);
        self.pixels_per_point = output.pixels_per_point;
        self.primitives = self.ctx.tessellate(output.shapes, output.pixels_per_point);
        let mut delta = output.textures_delta;
        for (id, deltas) in std::mem::take(&mut delta.set) {
            for d in &deltas {
                self.renderer
                    .set_texture(context.queue, commands.pool(), id, d)
                    .map_err(|e| AppError::ui("egui textures", e))?;
            }
        }
        self.textures_to_free = std::mem::take(&mut delta.free).into_iter().collect();
        Ok(result)
    }

    /// Records the UI into `cmd`, inside a colour-only rendering pass of `extent`.
    pub fn draw(&mut self, cmd: vk::CommandBuffer, extent: vk::Extent2D) -> Result<(), AppError> {
        self.renderer
            .cmd_draw(cmd, extent, self.pixels_per_point, &self.primitives)
            .map_err(|e| AppError::ui("egui draw", e))
    }

    /// After the frame has finished on the GPU: textures egui no longer needs.
    pub fn end_frame(&mut self) -> Result<(), AppError> {
        for id in std::mem::take(&mut self.textures_to_free) {
            self.renderer
                .free_texture(id)
                .map_err(|e| AppError::ui("egui textures", e))?;
        }
        Ok(())
    }
}

/// `slider` in its viewport's top-left corner; the count it was dragged to, if it moved.
/// No number box beside it (typing there took the viewer's keys): the count is a label.
fn lod_slider(ctx: &egui::Context, slider: &LodSlider) -> Option<usize> {
    let (lo, hi) = slider.range;
    let mut moved = None;
    egui::Area::new(egui::Id::new(("level of detail", slider.viewport)))
        .fixed_pos(slider.corner + egui::vec2(6.0, 6.0))
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.label(format!(
                    "Level of detail: {} vertices  [L: off]",
                    super::labels::grouped(slider.at)
                ));
                let mut value = slider.at;
                ui.spacing_mut().slider_width = 240.0;
                let bar = egui::Slider::new(&mut value, lo..=hi)
                    .show_value(false)
                    .logarithmic(hi > 100 * lo.max(1));
                if ui.add(bar).changed() && value != slider.at {
                    moved = Some(value);
                }
            });
        });
    moved
}

/// The "decimate to N vertices" window: Enter or the button submits the text (the viewer
/// checks it and either closes the field or shows why not), Escape or Cancel closes it.
fn vertex_field(ctx: &egui::Context, field: &mut VertexField, result: &mut UiResult) {
    modal(ctx, "Decimate to N vertices", |ui, keys| {
        text_line(ui, &mut field.text, &field.hint, None, keys);
        refusal(ui, field.error.as_deref());
        match confirm_or_cancel(ui, "Decimate", keys) {
            Some(true) => result.vertex_count = Some(field.text.clone()),
            Some(false) => result.close_field = true,
            None => {}
        }
    });
}

/// The quit question over everything: "Quit" (or q / y) quits, "Stay" (or n / Esc) stays;
/// the keys reach the viewer, which answers for them.
fn quit_question(ctx: &egui::Context, question: &str) -> Option<bool> {
    let mut answer = None;
    modal(ctx, "Quit?", |ui, _| {
        ui.label(question);
        ui.horizontal(|ui| {
            if ui.button("Quit (y)").clicked() {
                answer = Some(true);
            }
            if ui.button("Stay (n)").clicked() {
                answer = Some(false);
            }
        });
    });
    answer
}

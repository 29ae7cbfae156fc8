//! The per-viewport panel (MeshLab-style, collapsed until opened): the viewport's algorithm,
//! a removal target with its Decimate button, keep border, Measure, and the level-of-detail
//! slider's switch — each the same action as its key, for that viewport. Drawn at the
//! viewport's top-left corner, below its level-of-detail slider when that is shown. It has no
//! text field, so the keys stay the 3D view's.

use super::menu::{Action, DecimateEvent, DecimateKind};

/// What one viewport's panel shows.
#[derive(Debug, Clone, Copy)]
pub struct ViewportPanel {
    /// The viewport, from 0, and its id (the panel's state is kept by id).
    pub viewport: usize,
    pub id: u64,
    /// Where the panel's top-left corner goes, in points.
    pub corner: egui::Pos2,
    /// Quadric edge collapse (else vertex removal), border kept, level-of-detail slider on.
    pub qem: bool,
    pub keep_border: bool,
    pub lod: bool,
}

/// The points the level-of-detail slider takes above the panel, when it is shown.
pub const BELOW_LOD_SLIDER: f32 = 64.0;

/// Draws `panel`; the action chosen in it this frame, for its viewport.
pub fn show(ctx: &egui::Context, panel: &ViewportPanel) -> Option<(usize, Action)> {
    let mut action = None;
    let id = egui::Id::new(("viewport panel", panel.id));
    egui::Area::new(id)
        .fixed_pos(panel.corner + egui::vec2(6.0, 6.0))
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                egui::CollapsingHeader::new(format!("Viewport {}", panel.viewport + 1))
                    .id_salt(id)
                    .default_open(false)
                    .show(ui, |ui| action = contents(ui, panel, id));
            });
        });
    action.map(|a| (panel.viewport, a))
}

/// The panel's rows; the action of the control used, if any.
fn contents(ui: &mut egui::Ui, panel: &ViewportPanel, id: egui::Id) -> Option<Action> {
    let mut action = None;
    ui.horizontal(|ui| {
        ui.label("Algorithm:");
        if ui.radio(!panel.qem, "vertex removal").clicked() && panel.qem {
            action = Some(Action::ToggleAlgorithm);
        }
        if ui.radio(panel.qem, "edge collapse (qem)").clicked() && !panel.qem {
            action = Some(Action::ToggleAlgorithm);
        }
    });
    let target_id = id.with("target");
    let mut percent: f64 = ui.data_mut(|d| *d.get_temp_mut_or(target_id, 90.0));
    ui.horizontal(|ui| {
        // No number box beside the slider: typing there would take the viewer's keys.
        ui.label(format!("Remove {percent:.0} %"));
        let slider = egui::Slider::new(&mut percent, 0.0..=100.0)
            .step_by(1.0)
            .show_value(false);
        ui.add(slider);
        if ui.button("Decimate").clicked() {
            action = Some(Action::Decimate(DecimateEvent {
                amount: percent,
                kind: DecimateKind::Percentage,
            }));
        }
    });
    ui.data_mut(|d| d.insert_temp(target_id, percent));
    let mut border = panel.keep_border;
    if ui.checkbox(&mut border, "Keep the open border").changed() {
        action = Some(Action::ToggleKeepBorder);
    }
    let mut lod = panel.lod;
    if ui.checkbox(&mut lod, "Level-of-detail slider").changed() {
        action = Some(Action::ToggleLod);
    }
    if ui.button("Measure the distance to the input").clicked() {
        action = Some(Action::MeasureError);
    }
    action
}

//! The set-up the viewer's modal windows share — the vertex-count field, the Open… and Save
//! as… dialogs, the quit question: a window centred over everything, neither collapsible
//! nor resizable, which reads Enter and Esc itself, keeps the keyboard in its text field,
//! shows why its last answer was refused, and ends in a confirm / Cancel row.

/// Enter and Esc this frame, read before the window's text field, which gives up its focus
/// on Enter.
#[derive(Debug, Clone, Copy, Default)]
pub struct ModalKeys {
    pub entered: bool,
    pub escaped: bool,
}

/// Shows the window `title` over everything, centred; `contents` draws what is in it.
pub fn modal(ctx: &egui::Context, title: &str, contents: impl FnOnce(&mut egui::Ui, ModalKeys)) {
    egui::Window::new(title)
        .order(egui::Order::Foreground)
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
        .show(ctx, |ui| {
            let keys = ui.input(|i| ModalKeys {
                entered: i.key_pressed(egui::Key::Enter),
                escaped: i.key_pressed(egui::Key::Escape),
            });
            contents(ui, keys);
        });
}

/// A one-line text field holding `text` (`width` points wide, egui's default when `None`)
/// that keeps the keyboard: typing goes to it, never to the viewer's keys (except on the
/// frame Enter or Esc answers the window).
pub fn text_line(
    ui: &mut egui::Ui,
    text: &mut String,
    hint: &str,
    width: Option<f32>,
    keys: ModalKeys,
) {
    let mut edit = egui::TextEdit::singleline(text).hint_text(hint);
    if let Some(width) = width {
        edit = edit.desired_width(width);
    }
    let edit = ui.add(edit);
    if !keys.entered && !keys.escaped {
        edit.request_focus();
    }
}

/// Why the last answer was refused, in the window's warning colour.
pub fn refusal(ui: &mut egui::Ui, error: Option<&str>) {
    if let Some(error) = error {
        ui.colored_label(egui::Color32::from_rgb(255, 140, 110), error);
    }
}

/// The `confirm` and Cancel buttons: `Some(true)` for `confirm` or Enter, `Some(false)` for
/// Cancel or Esc (Cancel wins when both), `None` while neither.
pub fn confirm_or_cancel(ui: &mut egui::Ui, confirm: &str, keys: ModalKeys) -> Option<bool> {
    let mut answer = None;
    ui.horizontal(|ui| {
        if ui.button(confirm).clicked() || keys.entered {
            answer = Some(true);
        }
        if ui.button("Cancel").clicked() || keys.escaped {
            answer = Some(false);
        }
    });
    answer
}

//! The right-click popup menu drawn with egui over `menu_layout`'s boxes, GLUT-style: each
//! row shows a check mark for toggles, its label and its key; hovering a submenu's row opens
//! it beside its parent; a click on an entry runs it, a click anywhere else closes the menu.
//! The open submenus are kept in egui's memory between frames.

use super::menu::{Action, MenuEntry, MenuItem};
use super::menu_layout::{layout, Area, MenuBox, Metrics};

/// Text size of the menu, in points.
const TEXT_SIZE: f32 = 13.0;

/// What the user did with the popup this frame.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct PopupOutcome {
    pub action: Option<Action>,
    /// A click outside every box: the popup closes.
    pub close: bool,
}

fn path_id() -> egui::Id {
    egui::Id::new("popup menu open path")
}

fn to_rect(a: &Area) -> egui::Rect {
    egui::Rect::from_min_size(egui::pos2(a.x, a.y), egui::vec2(a.width, a.height))
}

/// The boxes of the popup at `at` with the submenus of `open`, on `ctx`'s screen.
pub fn boxes(
    ctx: &egui::Context,
    menu: &[MenuEntry],
    at: egui::Pos2,
    open: &[usize],
) -> Vec<MenuBox> {
    let painter = ctx.layer_painter(egui::LayerId::background());
    let measure = |text: &str| {
        let font = egui::FontId::proportional(TEXT_SIZE);
        (painter.layout_no_wrap(text.to_string(), font, egui::Color32::WHITE))
            .size()
            .x
    };
    let screen = ctx.content_rect();
    layout(
        menu,
        (at.x, at.y),
        open,
        (screen.width(), screen.height()),
        &Metrics::default(),
        &measure,
    )
}

/// Shows the popup at `at` (points); `just_opened` on the frame of the opening click (which
/// resets the open submenus and must not count as a click outside).
pub fn show(
    ctx: &egui::Context,
    menu: &[MenuEntry],
    checked: &dyn Fn(Action) -> Option<bool>,
    at: egui::Pos2,
    just_opened: bool,
) -> PopupOutcome {
    if just_opened {
        ctx.data_mut(|d| d.remove::<Vec<usize>>(path_id()));
    }
    let path: Vec<usize> = ctx.data(|d| d.get_temp(path_id())).unwrap_or_default();
    let shown = boxes(ctx, menu, at, &path);
    let mut outcome = PopupOutcome::default();
    let mut new_path = path.clone();
    let mut list = menu;
    for b in &shown {
        let entries = list;
        egui::Area::new(egui::Id::new(("popup menu box", b.depth)))
            .fixed_pos(egui::pos2(b.area.x, b.area.y))
            .order(egui::Order::Foreground)
            .show(ctx, |ui| {
                ui.allocate_exact_size(
                    egui::vec2(b.area.width, b.area.height),
                    egui::Sense::hover(),
                );
                paint_box(ui.painter(), b, entries, checked, &path);
                for row in &b.rows {
                    let id = egui::Id::new(("popup menu row", b.depth, row.index));
                    let response = ui.interact(to_rect(&row.area), id, egui::Sense::click());
                    let Some(entry) = entries.get(row.index) else {
                        continue;
                    };
                    if response.hovered() {
                        new_path.truncate(b.depth);
                        if matches!(entry.item, MenuItem::Submenu(_)) {
                            new_path.push(row.index);
                        }
                    }
                    if let (true, MenuItem::Action(a)) = (response.clicked(), &entry.item) {
                        outcome.action = Some(*a);
                    }
                }
            });
        list = match path.get(b.depth).and_then(|&i| list.get(i)) {
            Some(MenuEntry {
                item: MenuItem::Submenu(sub),
                ..
            }) => sub,
            _ => list,
        };
    }
    let (pressed, pointer) = ctx.input(|i| (i.pointer.any_pressed(), i.pointer.interact_pos()));
    let inside = pointer.is_some_and(|p| shown.iter().any(|b| b.area.contains(p.x, p.y)));
    if pressed && !inside && !just_opened {
        outcome.close = true;
    }
    if new_path != path {
        ctx.data_mut(|d| d.insert_temp(path_id(), new_path));
        ctx.request_repaint();
    }
    outcome
}

/// Paints one box: frame, then per row the highlight (the row under the pointer or whose
/// submenu is open), a check mark or an empty box for toggles, the label and the hint.
pub fn paint_box(
    painter: &egui::Painter,
    b: &MenuBox,
    entries: &[MenuEntry],
    checked: &dyn Fn(Action) -> Option<bool>,
    open: &[usize],
) {
    let style = painter.ctx().global_style();
    let visuals = &style.visuals;
    let frame = to_rect(&b.area);
    painter.rect_filled(frame, 4.0, visuals.window_fill);
    painter.rect_stroke(frame, 4.0, visuals.window_stroke, egui::StrokeKind::Inside);
    let pointer = painter.ctx().input(|i| i.pointer.hover_pos());
    let font = egui::FontId::proportional(TEXT_SIZE);
    let text = visuals.text_color();
    let faint = visuals.weak_text_color();
    let check_width = Metrics::default().check_width;
    for row in &b.rows {
        let Some(entry) = entries.get(row.index) else {
            continue;
        };
        let rect = to_rect(&row.area);
        let lit =
            open.get(b.depth) == Some(&row.index) || pointer.is_some_and(|p| rect.contains(p));
        if lit {
            painter.rect_filled(rect, 2.0, visuals.widgets.hovered.weak_bg_fill);
        }
        let mid = rect.center().y;
        if let MenuItem::Action(a) = &entry.item {
            if let Some(on) = checked(*a) {
                let mark = egui::Rect::from_center_size(
                    egui::pos2(rect.min.x + check_width / 2.0, mid),
                    egui::vec2(10.0, 10.0),
                );
                painter.rect_stroke(
                    mark,
                    1.0,
                    egui::Stroke::new(1.0, faint),
                    egui::StrokeKind::Inside,
                );
                if on {
                    let stroke = egui::Stroke::new(2.0, text);
                    let points = [
                        egui::pos2(mark.min.x + 2.0, mid),
                        egui::pos2(mark.min.x + 4.5, mark.max.y - 2.0),
                        egui::pos2(mark.max.x - 1.5, mark.min.y + 1.5),
                    ];
                    painter.line_segment([points[0], points[1]], stroke);
                    painter.line_segment([points[1], points[2]], stroke);
                }
            }
        }
        painter.text(
            egui::pos2(rect.min.x + check_width, mid),
            egui::Align2::LEFT_CENTER,
            &entry.label,
            font.clone(),
            text,
        );
        painter.text(
            egui::pos2(rect.max.x - 4.0, mid),
            egui::Align2::RIGHT_CENTER,
            &row.hint,
            font.clone(),
            faint,
        );
    }
}

//! The popup menu: submenus open beside their parent (never over it) and stay on the screen
//! wherever the menu is opened; every entry with a key shows it; and a golden of the menu
//! with its Draw submenu open, painted on lavapipe by the same code as the window's.

use decimate_core::decimate::Params;
use decimate_viewer::app::controller::ViewportController;
use decimate_viewer::app::labels::HeadlessCaptions;
use decimate_viewer::app::menu::{action_for_key, actions, menu, Key, MenuEntry, MenuItem};
use decimate_viewer::app::menu_layout::{hint, layout, MenuBox, Metrics};
use decimate_viewer::app::popup;
use decimate_viewer::render::commands::Commands;
use decimate_viewer::render::context::{Context, DevicePreference};
use decimate_viewer::render::offscreen::{OffscreenTarget, OFFSCREEN_FORMAT};
use decimate_viewer::render::pipeline::Pipelines;

use crate::support::shot::*;

/// A text's width in points, as a proportional font of the menu's size gives at most.
fn width(text: &str) -> f32 {
    8.0 * text.chars().count() as f32
}

const SCREEN: (f32, f32) = (1024.0, 720.0);

/// Index of every top-level submenu.
fn submenus(entries: &[MenuEntry]) -> Vec<usize> {
    (entries.iter().enumerate())
        .filter(|(_, e)| matches!(e.item, MenuItem::Submenu(_)))
        .map(|(i, _)| i)
        .collect()
}

#[test]
fn submenus_open_beside_their_parent_and_stay_on_the_screen() {
    let entries = menu();
    let subs = submenus(&entries);
    assert!(subs.len() >= 3, "the menu has {} submenus", subs.len());
    let (w, h) = SCREEN;
    // Opened in each corner and the middle, with each submenu open.
    for at in [
        (0.0, 0.0),
        (w - 1.0, 0.0),
        (0.0, h - 1.0),
        (w - 1.0, h - 1.0),
        (500.0, 300.0),
    ] {
        for &sub in &subs {
            let boxes = layout(&entries, at, &[sub], SCREEN, &Metrics::default(), &width);
            assert_eq!(boxes.len(), 2, "submenu {sub} at {at:?} did not open");
            let (parent, child) = (&boxes[0], &boxes[1]);
            assert!(
                !child.area.overlaps(&parent.area),
                "at {at:?}, submenu {sub} {:?} covers its parent {:?}",
                child.area,
                parent.area
            );
            for b in &boxes {
                assert!(
                    b.area.x >= 0.0
                        && b.area.y >= 0.0
                        && b.area.right() <= w
                        && b.area.bottom() <= h,
                    "at {at:?} a box leaves the screen: {:?}",
                    b.area
                );
            }
            // Beside: the submenu touches its parent's side and starts near its row.
            let row = &parent.rows[sub];
            let touching = (child.area.x - parent.area.right()).abs() < 1e-3
                || (child.area.right() - parent.area.x).abs() < 1e-3;
            assert!(
                touching,
                "at {at:?}, submenu {sub} is not beside its parent"
            );
            assert!(
                child.area.y <= row.area.y,
                "submenu {sub} starts below its row"
            );
            // Its rows are the submenu's entries, each inside it.
            let MenuItem::Submenu(items) = &entries[sub].item else {
                unreachable!()
            };
            assert_eq!(child.rows.len(), items.len());
        }
    }
}

#[test]
fn every_entry_shows_its_key() {
    fn walk(entries: &[MenuEntry], out: &mut Vec<(String, String, MenuItem)>) {
        for e in entries {
            out.push((e.label.clone(), hint(e), e.item.clone()));
            if let MenuItem::Submenu(sub) = &e.item {
                walk(sub, out);
            }
        }
    }
    let mut all = Vec::new();
    walk(&menu(), &mut all);
    for (label, hint, item) in &all {
        match item {
            MenuItem::Submenu(_) => assert_eq!(hint, ">", "{label}"),
            MenuItem::Action(a) => {
                let key = match hint.as_str() {
                    "F2" => Key::F2,
                    "F3" => Key::F3,
                    "Tab" => Key::Tab,
                    k => Key::Char(
                        k.chars()
                            .next()
                            .unwrap_or_else(|| panic!("{label}: no key")),
                    ),
                };
                assert_eq!(action_for_key(key), Some(*a), "{label} shows [{hint}]");
            }
        }
    }
    // And the other way: every printable key bound to a menu action is shown on its entry.
    let offered = actions(&menu());
    for c in ' '..='~' {
        let Some(a) = action_for_key(Key::Char(c)) else {
            continue;
        };
        if offered.contains(&a) {
            assert!(
                all.iter()
                    .any(|(_, h, item)| *item == MenuItem::Action(a) && *h == c.to_string()),
                "key {c:?} does {a:?} but no entry shows it"
            );
        }
    }
}

#[test]
fn the_open_draw_submenu_matches_its_golden() {
    let fail = |e: &dyn std::fmt::Display| -> ! {
        panic!("Vulkan rendering is unavailable, so the menu golden cannot be drawn: {e}")
    };
    let (width, height) = (640, 360);
    let context = Context::new(&[], false, DevicePreference::Cpu).unwrap_or_else(|e| fail(&e));
    let commands = Commands::new(&context).unwrap_or_else(|e| fail(&e));
    let pipelines = Pipelines::new(&context, OFFSCREEN_FORMAT).unwrap_or_else(|e| fail(&e));
    let target = OffscreenTarget::new(&context, width, height).unwrap_or_else(|e| fail(&e));
    let entries = menu();
    let draw = (entries.iter())
        .position(|e| e.label == "Draw")
        .unwrap_or_else(|| panic!("no Draw submenu"));
    let controller = ViewportController::new(cube(2), Params::default(), width, height);
    let checked = |a| controller.checked(a);
    let shown = std::cell::RefCell::new(Vec::<MenuBox>::new());
    let paint = |ctx: &egui::Context| {
        let boxes = popup::boxes(ctx, &entries, egui::pos2(30.0, 20.0), &[draw]);
        let painter = ctx.layer_painter(egui::LayerId::new(
            egui::Order::Foreground,
            egui::Id::new("menu"),
        ));
        let mut list: &[MenuEntry] = &entries;
        for b in &boxes {
            popup::paint_box(&painter, b, list, &checked, &[draw]);
            if let MenuItem::Submenu(sub) = &entries[draw].item {
                list = sub;
            }
        }
        *shown.borrow_mut() = boxes;
    };
    let extent = target.extent;
    let mut overlay = HeadlessCaptions::with_painter(&context, &commands, extent, &paint)
        .unwrap_or_else(|e| fail(&e));
    let mut record = |cmd| overlay.record(cmd);
    let image = target
        .render_with_overlay(&commands, &pipelines, &[], true, Some(&mut record))
        .unwrap_or_else(|e| fail(&e))
        .unwrap_or_else(|| panic!("no picture was read back"));
    let boxes = shown.into_inner();
    assert_eq!(boxes.len(), 2);
    assert!(!boxes[1].area.overlaps(&boxes[0].area));
    // Both boxes are painted: their middles differ from the empty picture's corner.
    let corner = pixel(&image, width - 1, height - 1);
    for b in &boxes {
        let (x, y) = (b.area.x + b.area.width / 2.0, b.area.y + 3.0);
        assert_ne!(
            pixel(&image, x as u32, y as u32),
            corner,
            "box {:?} is not drawn",
            b.area
        );
    }
    assert_matches_golden("menu_draw_submenu_open", &image);
}

//! Where the popup menu's boxes go: the top box at the click, each open submenu beside the
//! row that opened it — to its right, or to its left when the screen ends — never over its
//! parent, and every box kept on the screen. Pure geometry over the menu data (text widths come
//! from the caller), so it is tested without a window.

use super::menu::{MenuEntry, MenuItem};

/// A rectangle in points, origin at the top left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Area {
    pub x: f32,
    pub y: f32,
    pub width: f32,
    pub height: f32,
}

impl Area {
    pub fn right(&self) -> f32 {
        self.x + self.width
    }

    pub fn bottom(&self) -> f32 {
        self.y + self.height
    }

    pub fn contains(&self, x: f32, y: f32) -> bool {
        (self.x..self.right()).contains(&x) && (self.y..self.bottom()).contains(&y)
    }

    /// True when the two share some inside (touching edges do not count).
    pub fn overlaps(&self, other: &Self) -> bool {
        self.x < other.right()
            && other.x < self.right()
            && self.y < other.bottom()
            && other.y < self.bottom()
    }
}

/// Sizes of the menu's parts, in points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metrics {
    pub row_height: f32,
    /// Room for the check mark, left of the label.
    pub check_width: f32,
    /// Between the label and the key hint.
    pub gap: f32,
    /// Inside the box, around the rows.
    pub padding: f32,
}

impl Default for Metrics {
    fn default() -> Self {
        Self {
            row_height: 20.0,
            check_width: 18.0,
            gap: 24.0,
            padding: 4.0,
        }
    }
}

/// One row of a box: its entry's place in its list, and where it is.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub index: usize,
    pub area: Area,
    /// The text right of the label: the key that does the same, or `>` for a submenu.
    pub hint: String,
}

/// One box of the open menu: the top menu (`depth` 0) or a submenu.
#[derive(Debug, Clone, PartialEq)]
pub struct MenuBox {
    pub depth: usize,
    pub area: Area,
    pub rows: Vec<Row>,
}

/// The hint shown right of an entry.
pub fn hint(entry: &MenuEntry) -> String {
    match (&entry.item, entry.key) {
        (MenuItem::Submenu(_), _) => ">".into(),
        (MenuItem::Action(_), Some(key)) => key.into(),
        (MenuItem::Action(_), None) => String::new(),
    }
}

/// The boxes of `entries` opened at `at` with the submenus of `open` (a row index per level:
/// `[1, 0]` is the second top entry's submenu and that one's first entry's submenu; indices
/// that are no submenu end the path), on a screen of `screen` points. `measure` gives a
/// text's width in points.
pub fn layout(
    entries: &[MenuEntry],
    at: (f32, f32),
    open: &[usize],
    screen: (f32, f32),
    metrics: &Metrics,
    measure: &dyn Fn(&str) -> f32,
) -> Vec<MenuBox> {
    let mut boxes = Vec::new();
    let mut list = entries;
    let mut place = Place::At(at);
    for depth in 0..=open.len() {
        let menu = boxed(list, depth, place, screen, metrics, measure);
        let next = open.get(depth).and_then(|&i| {
            let row = menu.rows.iter().find(|r| r.index == i)?;
            match &list.get(i)?.item {
                MenuItem::Submenu(sub) => Some((sub, row.area, menu.area)),
                MenuItem::Action(_) => None,
            }
        });
        boxes.push(menu);
        let Some((sub, row, parent)) = next else {
            break;
        };
        list = sub;
        place = Place::Beside { row, parent };
    }
    boxes
}

/// Where a box goes: at a point (the top menu) or beside its parent's row.
enum Place {
    At((f32, f32)),
    Beside { row: Area, parent: Area },
}

fn boxed(
    entries: &[MenuEntry],
    depth: usize,
    place: Place,
    (screen_w, screen_h): (f32, f32),
    m: &Metrics,
    measure: &dyn Fn(&str) -> f32,
) -> MenuBox {
    let hints: Vec<String> = entries.iter().map(hint).collect();
    let label = (entries.iter())
        .map(|e| measure(&e.label))
        .fold(0.0, f32::max);
    let key = hints.iter().map(|h| measure(h)).fold(0.0, f32::max);
    let width = 2.0 * m.padding + m.check_width + label + m.gap + key;
    let height = 2.0 * m.padding + m.row_height * entries.len() as f32;
    let (x, y) = match place {
        Place::At((x, y)) => (x.min(screen_w - width), y.min(screen_h - height)),
        Place::Beside { row, parent } => {
            // Right of the parent if it fits, else left of it; never over it.
            let x = if parent.right() + width <= screen_w || parent.x - width < 0.0 {
                parent.right()
            } else {
                parent.x - width
            };
            (x, (row.y - m.padding).min(screen_h - height))
        }
    };
    let area = Area {
        x: x.max(0.0),
        y: y.max(0.0),
        width,
        height,
    };
    let rows = (hints.into_iter().enumerate())
        .map(|(index, hint)| Row {
            index,
            area: Area {
                x: area.x + m.padding,
                y: area.y + m.padding + m.row_height * index as f32,
                width: width - 2.0 * m.padding,
                height: m.row_height,
            },
            hint,
        })
        .collect();
    MenuBox { depth, area, rows }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::menu::menu;

    fn chars(s: &str) -> f32 {
        7.0 * s.chars().count() as f32
    }

    #[test]
    fn a_submenu_near_the_right_edge_opens_to_the_left() {
        let entries = menu();
        let boxes = layout(
            &entries,
            (900.0, 100.0),
            &[1],
            (1024.0, 720.0),
            &Metrics::default(),
            &chars,
        );
        assert_eq!(boxes.len(), 2);
        assert!(boxes[1].area.right() <= boxes[0].area.x + 1e-3);
        assert!(boxes
            .iter()
            .all(|b| b.area.x >= 0.0 && b.area.right() <= 1024.0));
    }
}

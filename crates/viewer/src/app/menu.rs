//! The viewer's commands as data: the `Action` enum, the popup menu (entries and submenus,
//! each bound to an action and shown with its key), and the fixed key bindings. Built once and
//! shared by the right-click popup, the keyboard and the help text, so they never disagree.

/// How a decimate event counts (the original's PERCENTAGE and NUMBER).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DecimateKind {
    /// Remove this percentage of the original's vertices.
    Percentage,
    /// Remove this many of the original's vertices.
    Number,
}

/// A decimate event: a number and a kind, always counted from the original scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecimateEvent {
    pub amount: f64,
    pub kind: DecimateKind,
}

/// Everything a key or a menu entry can do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action {
    Decimate(DecimateEvent),
    /// Open the "decimate to N vertices" text field.
    AskVertexCount,
    /// The level-of-detail slider (a progressive mesh by quadric edge collapse) on or off.
    ToggleLod,
    /// Measure the current viewport's metro error against the original (its caption says it).
    MeasureError,
    /// The current viewport's algorithm: vertex removal ↔ quadric edge collapse (its last
    /// decimation is made again with the other).
    ToggleAlgorithm,
    /// The current viewport's open border kept or free (`--keep-border`; its last decimation
    /// is made again).
    ToggleKeepBorder,
    ToggleTriangles,
    ToggleEdges,
    TogglePoints,
    ToggleFaceNormals,
    ToggleVertexNormals,
    ToggleLighting,
    ToggleSmooth,
    /// Textured models textured or in their material colour.
    ToggleTexture,
    /// Decimated viewports coloured by their distance to the original (the error heat-map).
    ToggleErrorMap,
    /// Multisample anti-aliasing (4×) on or off, for the whole window.
    ToggleMsaa,
    /// The current viewport's crease angle up or down by this many degrees (0 to 180).
    CreaseAngle(i16),
    /// Model control (trackball) ↔ eye control (first person).
    ToggleNavigation,
    /// Every viewport follows the current one's camera (on) or keeps its own (off).
    ToggleLinkedCameras,
    AddViewport,
    RemoveViewport,
    NextViewport,
    ResetView,
    ToggleHelp,
    /// Save the current viewport's scene as `out.wrl`.
    Save,
    /// Save a picture of the window's viewports as `window.png`.
    SavePicture,
    /// The Open… dialog: another model instead.
    Open,
    /// The Save as… dialog: the current viewport's scene, named, in the format its
    /// extension names.
    SaveAs,
    Quit,
}

/// A key the viewer binds, independent of the window system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    Char(char),
    F2,
    F3,
    Tab,
    Escape,
}

/// One line of the popup menu.
#[derive(Debug, Clone, PartialEq)]
pub struct MenuEntry {
    pub label: String,
    /// The key that does the same, shown beside the label.
    pub key: Option<&'static str>,
    pub item: MenuItem,
}

#[derive(Debug, Clone, PartialEq)]
pub enum MenuItem {
    Action(Action),
    Submenu(Vec<MenuEntry>),
}

fn entry(label: &str, key: Option<&'static str>, action: Action) -> MenuEntry {
    MenuEntry {
        label: label.into(),
        key,
        item: MenuItem::Action(action),
    }
}

fn submenu(label: &str, entries: Vec<MenuEntry>) -> MenuEntry {
    MenuEntry {
        label: label.into(),
        key: None,
        item: MenuItem::Submenu(entries),
    }
}

/// Keys 1…9, 0 → remove 10…90 %, 100 % of the original's vertices.
pub const PERCENT_KEYS: [(char, &str, f64); 10] = [
    ('1', "1", 10.0),
    ('2', "2", 20.0),
    ('3', "3", 30.0),
    ('4', "4", 40.0),
    ('5', "5", 50.0),
    ('6', "6", 60.0),
    ('7', "7", 70.0),
    ('8', "8", 80.0),
    ('9', "9", 90.0),
    ('0', "0", 100.0),
];

fn percent(p: f64) -> Action {
    Action::Decimate(DecimateEvent {
        amount: p,
        kind: DecimateKind::Percentage,
    })
}

/// The popup menu: every action of the viewer.
pub fn menu() -> Vec<MenuEntry> {
    vec![
        submenu("Decimate", decimate_entries()),
        submenu("Draw", draw_entries()),
        submenu("View", view_entries()),
    ]
    .into_iter()
    .chain(file_entries())
    .chain([
        entry("Help", Some("h"), Action::ToggleHelp),
        entry("Quit", Some("q"), Action::Quit),
    ])
    .collect()
}

/// The Decimate submenu: the ten percentages, a vertex count, then the settings.
fn decimate_entries() -> Vec<MenuEntry> {
    let percentages = PERCENT_KEYS.iter().map(|&(_, key, p)| {
        let label = if p >= 100.0 {
            "Remove 100 % (as far as possible)".to_string()
        } else {
            format!("Remove {p:.0} % of the vertices")
        };
        entry(&label, Some(key), percent(p))
    });
    percentages
        .chain([
            entry("Decimate to N vertices…", Some("v"), Action::AskVertexCount),
            entry(
                "Quadric edge collapse (unchecked: vertex removal)",
                Some("A"),
                Action::ToggleAlgorithm,
            ),
            entry(
                "Keep the open border / let it go",
                Some("b"),
                Action::ToggleKeepBorder,
            ),
            entry(
                "Level-of-detail slider (qem, geomorph)",
                Some("L"),
                Action::ToggleLod,
            ),
            entry(
                "Measure the distance to the original (metro)",
                Some("d"),
                Action::MeasureError,
            ),
        ])
        .collect()
}

/// The Draw submenu: what each viewport draws.
fn draw_entries() -> Vec<MenuEntry> {
    vec![
        entry("Triangles", Some("t"), Action::ToggleTriangles),
        entry("Edges", Some("e"), Action::ToggleEdges),
        entry("Points", Some("p"), Action::TogglePoints),
        entry("Face normals", Some("n"), Action::ToggleFaceNormals),
        entry("Vertex normals", Some("N"), Action::ToggleVertexNormals),
        entry("Lighting", Some("l"), Action::ToggleLighting),
        entry("Smooth / flat shading", Some("s"), Action::ToggleSmooth),
        entry("Texture", Some("T"), Action::ToggleTexture),
        entry(
            "Error heat-map (distance to the original)",
            Some("E"),
            Action::ToggleErrorMap,
        ),
        entry("Anti-aliasing (4× MSAA)", Some("M"), Action::ToggleMsaa),
        entry(
            "Crease angle −15° (sharper)",
            Some("["),
            Action::CreaseAngle(-15),
        ),
        entry(
            "Crease angle +15° (smoother)",
            Some("]"),
            Action::CreaseAngle(15),
        ),
    ]
}

/// The View submenu: cameras and viewports.
fn view_entries() -> Vec<MenuEntry> {
    vec![
        entry("Model / eye control", Some("m"), Action::ToggleNavigation),
        entry("Reset view", Some("r"), Action::ResetView),
        entry("Linked cameras", Some("c"), Action::ToggleLinkedCameras),
        entry("Add viewport (original)", Some("a"), Action::AddViewport),
        entry("Remove viewport", Some("x"), Action::RemoveViewport),
        entry("Next viewport", Some("Tab"), Action::NextViewport),
    ]
}

/// The menu's file entries: open, save as, save, picture.
fn file_entries() -> [MenuEntry; 4] {
    [
        entry("Open…", Some("o"), Action::Open),
        entry("Save as…", Some("O"), Action::SaveAs),
        entry(&save_label("out.wrl"), Some("F3"), Action::Save),
        entry(
            "Save a picture as window.png",
            Some("F2"),
            Action::SavePicture,
        ),
    ]
}

/// The Save entry's label: the name F3 writes next (`out.wrl`, then `out-1.wrl`…), as F3
/// never writes over a file.
pub fn save_label(next: &str) -> String {
    format!("Save as {next} (the next free number)")
}

/// Sets the Save entry's label to name `next`, the file F3 writes next.
pub fn name_next_save(entries: &mut [MenuEntry], next: &str) {
    for e in entries {
        match &mut e.item {
            MenuItem::Action(Action::Save) => e.label = save_label(next),
            MenuItem::Action(_) => {}
            MenuItem::Submenu(sub) => name_next_save(sub, next),
        }
    }
}

/// The action bound to `key`, if any.
pub fn action_for_key(key: Key) -> Option<Action> {
    Some(match key {
        Key::F2 => Action::SavePicture,
        Key::F3 => Action::Save,
        Key::Tab => Action::NextViewport,
        // Esc closes what is open and cancels jobs (the window's business); it never quits.
        Key::Escape => return None,
        Key::Char(c) => {
            if let Some(&(_, _, p)) = PERCENT_KEYS.iter().find(|(k, _, _)| *k == c) {
                return Some(percent(p));
            }
            match c {
                't' => Action::ToggleTriangles,
                'e' => Action::ToggleEdges,
                'p' => Action::TogglePoints,
                'n' => Action::ToggleFaceNormals,
                'N' => Action::ToggleVertexNormals,
                'l' => Action::ToggleLighting,
                's' => Action::ToggleSmooth,
                'T' => Action::ToggleTexture,
                'E' => Action::ToggleErrorMap,
                'M' => Action::ToggleMsaa,
                'm' => Action::ToggleNavigation,
                'a' => Action::AddViewport,
                'x' => Action::RemoveViewport,
                'r' => Action::ResetView,
                'c' => Action::ToggleLinkedCameras,
                '[' => Action::CreaseAngle(-15),
                ']' => Action::CreaseAngle(15),
                'h' => Action::ToggleHelp,
                'v' => Action::AskVertexCount,
                'L' => Action::ToggleLod,
                'd' => Action::MeasureError,
                'A' => Action::ToggleAlgorithm,
                'b' => Action::ToggleKeepBorder,
                'o' => Action::Open,
                'O' => Action::SaveAs,
                'q' => Action::Quit,
                _ => return None,
            }
        }
    })
}

/// Every action of the menu, depth first.
pub fn actions(entries: &[MenuEntry]) -> Vec<Action> {
    let mut out = Vec::new();
    for e in entries {
        match &e.item {
            MenuItem::Action(a) => out.push(*a),
            MenuItem::Submenu(sub) => out.extend(actions(sub)),
        }
    }
    out
}

/// The key help printed at start and shown by `h`, generated from the menu.
pub fn key_help() -> String {
    let mut text = String::from("keys (right mouse button: the same as a menu):\n");
    fn walk(entries: &[MenuEntry], text: &mut String) {
        for e in entries {
            match &e.item {
                MenuItem::Action(_) => {
                    if let Some(key) = e.key {
                        text.push_str(&format!("  {key:<5} {}\n", e.label));
                    }
                }
                MenuItem::Submenu(sub) => walk(sub, text),
            }
        }
    }
    walk(&menu(), &mut text);
    text.push_str(
        "  Esc   Cancel the decimation or measurement running, else quit\n\
         mouse: left drag turns the model (looks around in eye control), wheel zooms (walks),\n\
         \x20      middle or Shift + left drag pans (steps sideways)\n\
         eye control: arrows and W/S walk\n",
    );
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key_of(label_key: &str) -> Key {
        match label_key {
            "F2" => Key::F2,
            "F3" => Key::F3,
            "Tab" => Key::Tab,
            k => Key::Char(k.chars().next().unwrap_or(' ')),
        }
    }

    #[test]
    fn every_menu_entry_with_a_key_does_what_the_key_does() {
        fn check(entries: &[MenuEntry]) {
            for e in entries {
                match &e.item {
                    MenuItem::Action(a) => {
                        let key = e.key.unwrap_or_else(|| panic!("{} has no key", e.label));
                        assert_eq!(action_for_key(key_of(key)), Some(*a), "{}", e.label);
                    }
                    MenuItem::Submenu(sub) => check(sub),
                }
            }
        }
        check(&menu());
    }

    #[test]
    fn digit_keys_remove_ten_to_a_hundred_percent() {
        for (c, p) in [('1', 10.0), ('5', 50.0), ('9', 90.0), ('0', 100.0)] {
            assert_eq!(
                action_for_key(Key::Char(c)),
                Some(Action::Decimate(DecimateEvent {
                    amount: p,
                    kind: DecimateKind::Percentage
                }))
            );
        }
    }

    #[test]
    fn fixed_keys() {
        assert_eq!(action_for_key(Key::F3), Some(Action::Save));
        assert_eq!(action_for_key(Key::Escape), None, "Esc never quits");
        assert_eq!(action_for_key(Key::Char('q')), Some(Action::Quit));
        assert_eq!(
            action_for_key(Key::Char('n')),
            Some(Action::ToggleFaceNormals)
        );
        assert_eq!(
            action_for_key(Key::Char('N')),
            Some(Action::ToggleVertexNormals)
        );
        assert_eq!(action_for_key(Key::Char('z')), None);
    }

    #[test]
    fn the_save_entry_names_the_file_f3_writes_next() {
        let labels = |entries: &[MenuEntry]| -> Vec<String> {
            let file = entries.iter().filter(|e| e.key == Some("F3"));
            file.map(|e| e.label.clone()).collect()
        };
        let mut entries = menu();
        assert_eq!(labels(&entries), ["Save as out.wrl (the next free number)"]);
        name_next_save(&mut entries, "out-2.wrl");
        assert_eq!(
            labels(&entries),
            ["Save as out-2.wrl (the next free number)"]
        );
    }

    #[test]
    fn menu_offers_every_action() {
        let all = actions(&menu());
        for a in [
            Action::AskVertexCount,
            Action::ToggleLod,
            Action::ToggleAlgorithm,
            Action::ToggleKeepBorder,
            Action::ToggleTriangles,
            Action::ToggleEdges,
            Action::TogglePoints,
            Action::ToggleFaceNormals,
            Action::ToggleVertexNormals,
            Action::ToggleLighting,
            Action::ToggleSmooth,
            Action::ToggleErrorMap,
            Action::ToggleMsaa,
            Action::ToggleNavigation,
            Action::AddViewport,
            Action::RemoveViewport,
            Action::NextViewport,
            Action::ResetView,
            Action::ToggleLinkedCameras,
            Action::CreaseAngle(15),
            Action::CreaseAngle(-15),
            Action::ToggleHelp,
            Action::Save,
            Action::SavePicture,
            Action::Open,
            Action::SaveAs,
            Action::Quit,
        ] {
            assert!(all.contains(&a), "{a:?} is missing from the menu");
        }
        assert_eq!(
            all.iter()
                .filter(|a| matches!(a, Action::Decimate(_)))
                .count(),
            10
        );
    }

    #[test]
    fn help_lists_the_keys() {
        let help = key_help();
        for k in ["F3", "Tab", "  9 ", "  N ", "Esc"] {
            assert!(help.contains(k), "help lacks {k}:\n{help}");
        }
    }
}

//! The Open… and Save as… dialogs (`o`, `O`, the menu): a folder's listing — its folders,
//! then the model files the viewer reads — a name field, and buttons, drawn with egui. Save
//! as takes the format from the name's extension and asks before writing over a file that
//! exists. The state and its checks are plain data (tested without a window); `show` draws
//! it. A small dialog of its own: no file-dialog crate is available to this build offline.

use std::path::{Path, PathBuf};

use decimate_core::io::Format;

use super::modal::{confirm_or_cancel, modal, refusal, text_line};

/// Which dialog.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DialogKind {
    Open,
    SaveAs,
}

/// What the user chose.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DialogOutcome {
    /// Open this file.
    Open(PathBuf),
    /// Save the current viewport as this file (asked about if it existed).
    Save(PathBuf),
    /// Closed without choosing.
    Cancel,
}

/// One Open… or Save as… dialog while it is shown.
#[derive(Debug, Clone)]
pub struct FileDialog {
    pub kind: DialogKind,
    /// The folder listed, and the name typed (a plain name, or a path from the folder).
    pub folder: PathBuf,
    pub name: String,
    /// The folder's folders and model files, folders first, each sorted by name.
    entries: Vec<(String, bool)>,
    /// Why the last choice was refused, shown under the field.
    pub error: Option<String>,
    /// Save as: the file that exists, while the dialog asks whether to replace it.
    pub replacing: Option<PathBuf>,
    /// What the status line should say since the last look (the question asked, the answer).
    news: Option<String>,
}

/// The extensions the Open dialog lists (`.gz` of them too): what the readers take.
const READ_EXTENSIONS: [&str; 9] = [
    "wrl", "vrml", "iv", "ply", "obj", "stl", "off", "gltf", "glb",
];

/// What Save as writes, by extension, for its message.
const WRITE_EXTENSIONS: &str = ".wrl, .ply, .obj, .stl, .off, .gltf or .glb";

impl FileDialog {
    /// A dialog listing `folder`, with `name` typed in.
    pub fn new(kind: DialogKind, folder: &Path, name: &str) -> Self {
        let mut dialog = Self {
            kind,
            folder: folder.to_path_buf(),
            name: name.to_string(),
            entries: Vec::new(),
            error: None,
            replacing: None,
            news: None,
        };
        dialog.list();
        dialog
    }

    /// The title of its window.
    pub fn title(&self) -> &'static str {
        match self.kind {
            DialogKind::Open => "Open",
            DialogKind::SaveAs => "Save as",
        }
    }

    /// Reads the folder's listing again (an unreadable folder lists nothing and says why).
    fn list(&mut self) {
        self.entries.clear();
        let read = match std::fs::read_dir(&self.folder) {
            Ok(read) => read,
            Err(e) => {
                self.error = Some(format!("cannot list {}: {e}", self.folder.display()));
                return;
            }
        };
        for entry in read.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let folder = entry.path().is_dir();
            if name.starts_with('.') || !(folder || readable_model(Path::new(&name))) {
                continue;
            }
            self.entries.push((name, folder));
        }
        self.entries
            .sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    }

    /// What the status line should say, once.
    pub fn take_news(&mut self) -> Option<String> {
        self.news.take()
    }

    /// The listing: (name, is a folder).
    pub fn entries(&self) -> &[(String, bool)] {
        &self.entries
    }

    /// Goes into `folder` (a name from the listing, or `..`).
    pub fn enter(&mut self, folder: &str) {
        let next = if folder == ".." {
            match self.folder.canonicalize() {
                Ok(full) => full.parent().map_or(full.clone(), Path::to_path_buf),
                Err(_) => self.folder.join(".."),
            }
        } else {
            self.folder.join(folder)
        };
        self.folder = next;
        self.error = None;
        self.list();
    }

    /// The name typed, from the folder listed.
    pub fn chosen(&self) -> PathBuf {
        self.folder.join(self.name.trim())
    }

    /// The name typed is submitted (Enter or the button): a folder is entered; Open takes a
    /// file that exists; Save as takes a name whose extension names a format it writes, and
    /// first asks when the file exists. `None` while the dialog stays (refused, or asking);
    /// a refusal is said in the status line too.
    pub fn submit(&mut self) -> Option<DialogOutcome> {
        let outcome = self.check();
        if let (Some(error), None) = (&self.error, &self.news) {
            self.news = Some(error.clone());
        }
        outcome
    }

    fn check(&mut self) -> Option<DialogOutcome> {
        self.error = None;
        if self.name.trim().is_empty() {
            self.error = Some("type a file name, or pick one above".into());
            return None;
        }
        let path = self.chosen();
        if path.is_dir() {
            self.folder = path;
            self.name.clear();
            self.list();
            return None;
        }
        match self.kind {
            DialogKind::Open if path.is_file() => Some(DialogOutcome::Open(path)),
            DialogKind::Open => {
                self.error = Some(format!("{} does not exist", path.display()));
                None
            }
            DialogKind::SaveAs => self.submit_save(path),
        }
    }

    fn submit_save(&mut self, path: PathBuf) -> Option<DialogOutcome> {
        let gz = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
        if gz || Format::from_path(&path).is_none() {
            self.error = Some(format!(
                "{}: the extension names the format: {WRITE_EXTENSIONS}",
                path.display()
            ));
            return None;
        }
        if path.exists() && self.replacing.as_ref() != Some(&path) {
            self.news = Some(format!(
                "{} exists: replace it? (y replaces, n keeps it)",
                path.display()
            ));
            self.replacing = Some(path);
            return None;
        }
        self.replacing = None;
        Some(DialogOutcome::Save(path))
    }

    /// The replace question's answer: yes saves over the file, no goes back to the name.
    pub fn answer_replace(&mut self, yes: bool) -> Option<DialogOutcome> {
        let path = self.replacing.take()?;
        if yes {
            Some(DialogOutcome::Save(path))
        } else {
            let kept = format!("{} kept: choose another name", path.display());
            self.news = Some(kept.clone());
            self.error = Some(kept);
            None
        }
    }
}

/// Whether the Open dialog lists `name` (a model file by its extension, `.gz` looked
/// through).
fn readable_model(name: &Path) -> bool {
    let stem = match name.extension() {
        Some(e) if e.eq_ignore_ascii_case("gz") => Path::new(name.file_stem().unwrap_or_default()),
        _ => name,
    };
    (stem.extension().and_then(|e| e.to_str())).is_some_and(|e| {
        READ_EXTENSIONS
            .iter()
            .any(|known| known.eq_ignore_ascii_case(e))
    })
}

/// Draws `dialog` over everything; what the user chose this frame, if anything. Enter
/// submits the name, Esc cancels (or, while asking, answers no).
pub fn show(ctx: &egui::Context, dialog: &mut FileDialog) -> Option<DialogOutcome> {
    let mut outcome = None;
    modal(ctx, dialog.title(), |ui, keys| {
        if dialog.replacing.is_some() {
            outcome = replace_question(ui, dialog, keys.escaped);
            return;
        }
        ui.label(format!("Folder: {}", dialog.folder.display()));
        listing(ui, dialog);
        let hint = "file name (the extension names the format)";
        text_line(ui, &mut dialog.name, hint, Some(360.0), keys);
        refusal(ui, dialog.error.as_deref());
        let verb = match dialog.kind {
            DialogKind::Open => "Open",
            DialogKind::SaveAs => "Save",
        };
        outcome = match confirm_or_cancel(ui, verb, keys) {
            Some(true) => dialog.submit(),
            Some(false) => Some(DialogOutcome::Cancel),
            None => None,
        };
    });
    outcome
}

/// The folder's listing, scrolled: `..`, its folders (a click enters one) and files (a click
/// takes the name).
fn listing(ui: &mut egui::Ui, dialog: &mut FileDialog) {
    let (mut enter, mut pick) = (None, None);
    egui::ScrollArea::vertical()
        .max_height(220.0)
        .show(ui, |ui| {
            ui.set_min_width(360.0);
            if ui.selectable_label(false, "../").clicked() {
                enter = Some("..".to_string());
            }
            for (name, folder) in dialog.entries() {
                let label = if *folder {
                    format!("{name}/")
                } else {
                    name.clone()
                };
                if ui.selectable_label(*name == dialog.name, label).clicked() {
                    match folder {
                        true => enter = Some(name.clone()),
                        false => pick = Some(name.clone()),
                    }
                }
            }
        });
    if let Some(name) = pick {
        dialog.name = name;
    }
    if let Some(folder) = enter {
        dialog.enter(&folder);
    }
}

/// "NAME exists. Replace it?": Replace (or y) saves over it, Keep (or n / Esc) goes
/// back to the name.
fn replace_question(
    ui: &mut egui::Ui,
    dialog: &mut FileDialog,
    escaped: bool,
) -> Option<DialogOutcome> {
    let (yes, no) = ui.input(|i| (i.key_pressed(egui::Key::Y), i.key_pressed(egui::Key::N)));
    let path = dialog.replacing.clone().unwrap_or_default();
    ui.label(format!("{} exists. Replace it?", path.display()));
    let mut answer = None;
    ui.horizontal(|ui| {
        if ui.button("Replace (y)").clicked() || yes {
            answer = Some(true);
        }
        if ui.button("Keep (n)").clicked() || no || escaped {
            answer = Some(false);
        }
    });
    answer.and_then(|yes| dialog.answer_replace(yes))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("decimate-dialog-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("sub")).unwrap_or_else(|e| panic!("{e}"));
        for f in ["b.ply", "a.wrl", "notes.txt", "c.iv.gz"] {
            std::fs::write(dir.join(f), "x").unwrap_or_else(|e| panic!("{e}"));
        }
        dir
    }

    #[test]
    fn the_listing_has_folders_first_then_model_files_by_name() {
        let dir = scratch("list");
        let d = FileDialog::new(DialogKind::Open, &dir, "");
        let names: Vec<&str> = d.entries().iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["sub", "a.wrl", "b.ply", "c.iv.gz"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn open_takes_an_existing_file_and_enters_a_folder() {
        let dir = scratch("open");
        let mut d = FileDialog::new(DialogKind::Open, &dir, "missing.ply");
        assert_eq!(d.submit(), None);
        assert!(d
            .error
            .as_deref()
            .is_some_and(|e| e.ends_with("does not exist")));
        let news = d.take_news().unwrap_or_default();
        assert!(news.ends_with("missing.ply does not exist"), "{news}");
        d.name = "sub".into();
        assert_eq!(d.submit(), None);
        assert_eq!(d.folder, dir.join("sub"));
        d.enter("..");
        d.name = "b.ply".into();
        let chosen = d.submit();
        assert!(matches!(chosen, Some(DialogOutcome::Open(p)) if p.ends_with("b.ply")));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn save_as_wants_a_known_extension_and_asks_before_replacing() {
        let dir = scratch("save");
        let mut d = FileDialog::new(DialogKind::SaveAs, &dir, "new");
        assert_eq!(d.submit(), None, "no extension");
        d.name = "new.iv".into();
        assert_eq!(d.submit(), None, "no Inventor writer");
        d.name = "new.obj".into();
        assert_eq!(d.submit(), Some(DialogOutcome::Save(dir.join("new.obj"))));
        d.name = "b.ply".into();
        assert_eq!(d.submit(), None, "asks first");
        assert_eq!(d.replacing, Some(dir.join("b.ply")));
        assert_eq!(d.answer_replace(false), None);
        assert!(d.replacing.is_none());
        assert_eq!(d.submit(), None, "asks again");
        assert_eq!(
            d.answer_replace(true),
            Some(DialogOutcome::Save(dir.join("b.ply")))
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}

//! Texture image names across folders: a relative name (`Model::texture`) means "beside the
//! file that named it", so when a scene is written to another folder the name must change
//! for the link to keep working.
//!
//! [`rebase`] re-expresses one name read relative to `from_dir` so that it points at the same
//! image from `to_dir`: relative to `to_dir` when the two share more than the file system's
//! root, absolute otherwise. Names with a URL scheme (`http:`, `file:` …), absolute paths
//! (`/…`, `\…`, `C:…`) and names read and written in the same folder are left exactly as they
//! are. The rest is worked out on the names alone (the image need not exist): `.` and `..`
//! are folded in, `\` is taken as a separator too (Windows exporters write it), and the
//! result uses `/`. Both folders are resolved first (symbolic links followed where they
//! exist). [`rebase_textures`] and [`rebased`] apply it to every model of a scene; every
//! place that writes a scene read from another folder calls one of them.

use crate::io::warning::{Warning, WarningKind};
use std::borrow::Cow;
use std::path::{Component, Path, PathBuf};

use crate::mesh::Scene;

/// The folder a file's relative names are relative to: its parent, `.` for a bare name.
pub fn folder_of(file: &Path) -> &Path {
    match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Drops (with one warning per name) the texture names of a scene read from `path` that
/// leave its folder: a path from the root, `..` above the folder, a `file:` URI. A model may
/// not make the program read files elsewhere unless `file_limits::outside_allowed`. `data:`
/// URIs and other URLs are kept (they are never read as files).
pub(crate) fn drop_outside_textures(outcome: &mut super::ReadOutcome, path: &Path) {
    let folder = folder_of(path);
    let mut said = std::collections::HashSet::new();
    for m in &mut outcome.scene.models {
        let Some(name) = m.texture.as_deref() else {
            continue;
        };
        let file_uri = name
            .get(..5)
            .is_some_and(|s| s.eq_ignore_ascii_case("file:"));
        if has_url_scheme(name) && !file_uri {
            continue;
        }
        let plain = name.replace('\\', "/");
        let refused = match super::file_limits::resolve_reference(folder, &plain) {
            Err(why) => Some(why),
            Ok(_) if is_absolute(name) && !super::file_limits::outside_allowed() => Some(format!(
                "'{name}' is outside the model's folder: only files in it are read"
            )),
            Ok(_) => None,
        };
        if let Some(why) = refused {
            if said.insert(name.to_string()) {
                outcome.warnings.push(Warning::new(
                    WarningKind::SkippedAttribute,
                    format!("texture {why}; its models are drawn untextured"),
                ));
            }
            m.texture = None;
        }
    }
}

/// True when `name` starts with a URL scheme (`http:`, `file:`, `data:` …): letters, digits,
/// `+`, `-` or `.` after a letter, then `:`. One letter before the colon is a Windows drive.
pub fn has_url_scheme(name: &str) -> bool {
    let Some((scheme, _)) = name.split_once(':') else {
        return false;
    };
    let mut chars = scheme.chars();
    scheme.len() >= 2
        && chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
}

/// True for a name that does not depend on the folder it is read from: a path from the root
/// (`/`, `\`) or a Windows drive (`C:`).
fn is_absolute(name: &str) -> bool {
    let b = name.as_bytes();
    name.starts_with(['/', '\\']) || (b.len() >= 2 && b[0].is_ascii_alphabetic() && b[1] == b':')
}

/// `dir` as an absolute path without `.` or `..`: resolved on disk when it exists, else
/// worked out from the current directory.
fn resolve_dir(dir: &Path) -> Option<PathBuf> {
    if let Ok(p) = dir.canonicalize() {
        return Some(p);
    }
    let abs = std::path::absolute(dir).ok()?;
    Some(normalize(abs.components()))
}

/// Folds `.` and `..` into the path (`..` never climbs above the root).
fn normalize<'a>(components: impl IntoIterator<Item = Component<'a>>) -> PathBuf {
    let mut out = PathBuf::new();
    for c in components {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if !matches!(
                    out.components().next_back(),
                    None | Some(Component::RootDir | Component::Prefix(_))
                ) {
                    out.pop();
                }
            }
            c => out.push(c),
        }
    }
    out
}

/// `name`, read relative to `from_dir`, as a name that points at the same image from
/// `to_dir` (see the module documentation for the rules).
pub fn rebase(name: &str, from_dir: &Path, to_dir: &Path) -> String {
    match Folders::resolve(from_dir, to_dir) {
        Some(folders) => folders.rebase(name),
        None => name.to_string(),
    }
}

/// The two folders of a rebase, resolved once for all the names it applies to.
struct Folders {
    from: PathBuf,
    to: PathBuf,
}

impl Folders {
    /// Both folders resolved; `None` when one cannot be, or they are the same folder (names
    /// then stay as they are).
    fn resolve(from_dir: &Path, to_dir: &Path) -> Option<Self> {
        let (from, to) = (resolve_dir(from_dir)?, resolve_dir(to_dir)?);
        (from != to).then_some(Self { from, to })
    }

    fn rebase(&self, name: &str) -> String {
        if name.is_empty() || has_url_scheme(name) || is_absolute(name) {
            return name.to_string();
        }
        let parts = name
            .split(['/', '\\'])
            .filter(|p| !p.is_empty())
            .map(|p| match p {
                "." => Component::CurDir,
                ".." => Component::ParentDir,
                p => Component::Normal(p.as_ref()),
            });
        let image = normalize(self.from.components().chain(parts));
        relative_to(&image, &self.to).unwrap_or_else(|| image.to_string_lossy().into_owned())
    }
}

/// `path` relative to the folder `dir` (both absolute and normalized), with `/`; `None` when
/// they share nothing but the root (or not even that), or `path` is `dir` itself.
fn relative_to(path: &Path, dir: &Path) -> Option<String> {
    let (p, d): (Vec<Component<'_>>, Vec<Component<'_>>) =
        (path.components().collect(), dir.components().collect());
    let common = p.iter().zip(&d).take_while(|(a, b)| a == b).count();
    let shared_folder = p[..common]
        .iter()
        .any(|c| matches!(c, Component::Normal(_)));
    if !shared_folder || common == p.len() {
        return None;
    }
    let ups = std::iter::repeat_n("..".to_string(), d.len() - common);
    let downs = p[common..]
        .iter()
        .map(|c| c.as_os_str().to_string_lossy().into_owned());
    Some(ups.chain(downs).collect::<Vec<_>>().join("/"))
}

/// Rebases every model's texture name from `from_dir` (the folder of the file it was read
/// from) to `to_dir` (the folder of the file about to be written).
pub fn rebase_textures(scene: &mut Scene, from_dir: &Path, to_dir: &Path) {
    let Some(folders) = Folders::resolve(from_dir, to_dir) else {
        return;
    };
    for m in &mut scene.models {
        if let Some(t) = &mut m.texture {
            *t = folders.rebase(t);
        }
    }
}

/// `scene` with its texture names rebased as [`rebase_textures`] does; borrowed when no
/// name changes (nothing is copied for an untextured scene).
pub fn rebased<'a>(scene: &'a Scene, from_dir: &Path, to_dir: &Path) -> Cow<'a, Scene> {
    let Some(folders) = Folders::resolve(from_dir, to_dir) else {
        return Cow::Borrowed(scene);
    };
    let names: Vec<Option<String>> = scene
        .models
        .iter()
        .map(|m| m.texture.as_deref().map(|t| folders.rebase(t)))
        .collect();
    if names
        .iter()
        .zip(&scene.models)
        .all(|(n, m)| *n == m.texture)
    {
        return Cow::Borrowed(scene);
    }
    let mut scene = scene.clone();
    for (m, name) in scene.models.iter_mut().zip(names) {
        m.texture = name;
    }
    Cow::Owned(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_worked_out_on_the_names_alone() {
        let (a, b) = (Path::new("/data/scans/in"), Path::new("/data/out"));
        let r = |n: &str| relative_to(&normalize(a.join(n).components()), b);
        assert_eq!(
            r("tex/skin.jpg").as_deref(),
            Some("../scans/in/tex/skin.jpg")
        );
        assert_eq!(r("../skin.jpg").as_deref(), Some("../scans/skin.jpg"));
        assert_eq!(r("../../out/skin.jpg").as_deref(), Some("skin.jpg"));
        // Sharing only the root: no relative name.
        assert_eq!(relative_to(Path::new("/a/x.jpg"), Path::new("/b")), None);
    }

    #[test]
    fn schemes_and_drives_are_told_apart() {
        for url in [
            "http://x/y.jpg",
            "file:///t/y.png",
            "data:image/png;base64,AA",
        ] {
            assert!(has_url_scheme(url), "{url}");
        }
        for not in ["C:\\t\\y.png", "y.png", "a/b:c.png", ":x"] {
            assert!(!has_url_scheme(not), "{not}");
        }
        assert!(is_absolute("C:\\t\\y.png") && is_absolute("/t/y.png"));
    }
}

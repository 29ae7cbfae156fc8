//! Wavefront MTL material libraries, the companions of OBJ files: reading them for an OBJ
//! that names them, and writing one beside an OBJ output.
//!
//! Read ([`parse_mtl`]): `newmtl NAME`, `Kd r [g b]` (the diffuse colour, clamped to 0..1;
//! one value means grey) and `map_Kd [options] FILE` (the diffuse texture; the options
//! `-blendu`, `-blendv`, `-cc`, `-clamp`, `-imfchan`, `-type`, `-bm`, `-boost`, `-texres`
//! (one value), `-mm` (two) and `-o`, `-s`, `-t` (one to three numbers) are skipped, but
//! for `-clamp on`, which makes the texture clamp instead of repeat; what is left is the file
//! name, spaces included). Other texture maps (`map_Ks`, `bump`, …) are
//! skipped with one warning per file, other statements (`Ka`, `Ks`, `Ns`, `d`, `illum`, …)
//! silently. A bad line is a warning naming the file and line, and is skipped: materials
//! only change how a model looks, so they never stop a file from being read.
//!
//! `apply_materials` is what `io::read_scene` does for an OBJ: load each `mtllib` relative
//! to the OBJ's folder (a name with spaces is tried whole first, then as a list of files),
//! and give each model whose `usemtl` names a material its `Kd` as `Model::diffuse` and its
//! `map_Kd` as `Model::texture` (models with texture coordinates only), re-expressed
//! relative to the OBJ's folder. The first library to define a name wins. A library that
//! cannot be read and a material no library defines are warnings naming the file.
//!
//! Write ([`plan`], [`write_mtl_to`]): one `newmtl` per distinct material of the scene, named
//! after the model's material, else after the model (spaces and `#` made `_`; `_2`, `_3` …
//! added where two different materials would share a name), with `Ka 0 0 0`, `Kd`,
//! `Ks 0 0 0`, `d 1`, `illum 1` (plain diffuse shading in every viewer) and `map_Kd` for a
//! model whose texture the OBJ maps (it has one texture coordinate pair per vertex), with
//! `-clamp on` when the texture repeats along neither direction.

use crate::io::warning::{Warning, WarningKind};
use std::collections::{HashMap, HashSet};
use std::io::Write;
use std::path::{Path, PathBuf};

use super::text::Lines;
use super::texture_path::{folder_of, rebase};
use super::{file_limits, ReadError, ReadOutcome};
use crate::mesh::{Model, Scene};

/// One material of an MTL file, as far as this program uses it.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    /// `Kd`, if given.
    pub diffuse: Option<[f32; 3]>,
    /// `map_Kd`'s file name as written (relative to the MTL file's folder), if given.
    pub texture: Option<String>,
    /// `map_Kd -clamp on`: the texture does not repeat (coordinates outside 0..=1 take the
    /// image's edge texels).
    pub clamp: bool,
}

/// Reads an MTL file's materials, in file order; `file` is named in the warnings. Its text
/// is taken like an OBJ's (`text_encoding`): a UTF-8 byte-order mark dropped, lone carriage
/// returns read as line ends; UTF-16 or UTF-32 text is a warning, and no materials.
pub fn parse_mtl(bytes: &[u8], file: &Path) -> (Vec<Material>, Vec<Warning>) {
    let f = file.display();
    let bytes = match super::text_encoding::plain_text(bytes.to_vec()) {
        Ok(b) => b,
        Err(why) => {
            let message = format!("{f}:1: {why}; its materials are not applied");
            return (Vec::new(), vec![lost(file, 1, message)]);
        }
    };
    let mut materials: Vec<Material> = Vec::new();
    let mut warnings = Vec::new();
    let mut skipped_maps: Vec<String> = Vec::new();
    let mut outside_warned = false;
    for (line, text) in Lines::new(&bytes, false) {
        let text = String::from_utf8_lossy(&text);
        let mut w = text.split_whitespace();
        let Some(key) = w.next() else { continue };
        let rest = text.trim().get(key.len()..).unwrap_or("").trim();
        if key == "newmtl" {
            if rest.is_empty() {
                warnings.push(lost(
                    file,
                    line,
                    format!("{f}:{line}: 'newmtl' without a name skipped"),
                ));
            }
            materials.push(Material {
                name: rest.to_string(),
                diffuse: None,
                texture: None,
                clamp: false,
            });
            continue;
        }
        let is_map =
            key.starts_with("map_") || matches!(key, "bump" | "disp" | "decal" | "refl" | "norm");
        if key != "Kd" && key != "map_Kd" {
            if is_map && !skipped_maps.iter().any(|k| k == key) {
                skipped_maps.push(key.to_string());
            }
            continue;
        }
        let Some(m) = materials.last_mut() else {
            if !outside_warned {
                outside_warned = true;
                warnings.push(lost(
                    file,
                    line,
                    format!("{f}:{line}: '{key}' before any 'newmtl' skipped (it belongs to no material)"),
                ));
            }
            continue;
        };
        let read = if key == "Kd" {
            kd(rest).map(|c| m.diffuse = Some(c))
        } else {
            map_file(rest).map(|(t, clamp)| (m.texture, m.clamp) = (Some(t), clamp))
        };
        if let Err(why) = read {
            warnings.push(lost(
                file,
                line,
                format!("{f}:{line}: {key}: {why}; line skipped"),
            ));
        }
    }
    materials.retain(|m| !m.name.is_empty());
    if !skipped_maps.is_empty() {
        let mut w = Warning::new(
            WarningKind::SkippedMaterial,
            format!(
                "{f}: texture maps other than map_Kd are not used ({})",
                skipped_maps.join(", ")
            ),
        );
        w.file = Some(file.to_path_buf());
        warnings.push(w);
    }
    (materials, warnings)
}

/// A line of the MTL file `file` not applied.
fn lost(file: &Path, line: usize, message: String) -> Warning {
    let mut w = Warning::new(WarningKind::SkippedMaterial, message).at(line);
    w.file = Some(file.to_path_buf());
    w
}

/// `Kd`'s colour: `r g b`, or `r` alone for grey; `spectral` and `xyz` forms are refused.
fn kd(rest: &str) -> Result<[f32; 3], String> {
    let values: Vec<&str> = rest.split_whitespace().collect();
    if matches!(values.first(), Some(&("spectral" | "xyz"))) {
        return Err(format!("the '{}' form is not supported", values[0]));
    }
    let number = |s: &str| -> Result<f32, String> {
        match s.parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v.clamp(0.0, 1.0)),
            _ => Err(format!(
                "expected a number, found '{}'",
                s.chars().take(40).collect::<String>()
            )),
        }
    };
    match values[..] {
        [r] => Ok([number(r)?; 3]),
        [r, g, b] => Ok([number(r)?, number(g)?, number(b)?]),
        _ => Err(format!(
            "expected 'Kd r g b', found {} values",
            values.len()
        )),
    }
}

/// How many values each `map_Kd` option takes: a fixed count, or up to three numbers.
fn option_values(option: &str) -> Option<(usize, bool)> {
    Some(match option {
        "-blendu" | "-blendv" | "-cc" | "-clamp" | "-imfchan" | "-type" | "-bm" | "-boost"
        | "-texres" => (1, false),
        "-mm" => (2, false),
        "-o" | "-s" | "-t" => (3, true),
        _ => return None,
    })
}

/// `map_Kd`'s file name (what is left after the options, spaces inside kept) and whether
/// its options say `-clamp on`.
fn map_file(rest: &str) -> Result<(String, bool), String> {
    // Each word with where it starts, so the file name can be cut out whole.
    let mut spans = Vec::new();
    let mut start = None;
    for (i, c) in rest.char_indices().chain([(rest.len(), ' ')]) {
        match (c.is_whitespace(), start) {
            (false, None) => start = Some(i),
            (true, Some(s)) => {
                spans.push((s, &rest[s..i]));
                start = None;
            }
            _ => {}
        }
    }
    let mut i = 0;
    let mut clamp = false;
    while let Some(&(_, word)) = spans.get(i) {
        if !word.starts_with('-') {
            break;
        }
        let Some((count, numbers_only)) = option_values(word) else {
            // The last word is the file name even when it starts with '-'.
            if i + 1 == spans.len() {
                break;
            }
            return Err(format!("unknown option '{word}'"));
        };
        i += 1;
        if i == spans.len() {
            return Err("no file name".to_string());
        }
        let mut taken = 0;
        // Always leave one word for the file name.
        while taken < count && i + 1 < spans.len() {
            if numbers_only && spans[i].1.parse::<f32>().is_err() {
                break;
            }
            i += 1;
            taken += 1;
        }
        if taken == 0 {
            return Err(format!("option '{word}' without a value"));
        }
        if word == "-clamp" {
            clamp = spans[i - 1].1 == "on";
        }
    }
    match spans.get(i) {
        Some(&(at, _)) => Ok((rest[at..].trim_end().to_string(), clamp)),
        None => Err("no file name".to_string()),
    }
}

/// The files one `mtllib` statement names: the whole text when such a file exists (names
/// with spaces), else each word.
fn library_files(obj_dir: &Path, lib: &str) -> Vec<String> {
    if obj_dir.join(lib).is_file() {
        return vec![lib.to_string()];
    }
    lib.split_whitespace().map(str::to_string).collect()
}

/// Loads the OBJ's material libraries (named relative to `obj`'s folder) and applies their
/// materials to the models that use them; problems become warnings.
pub(crate) fn apply_materials(outcome: &mut ReadOutcome, obj: &Path) -> Result<(), ReadError> {
    let used = outcome.scene.models.iter().any(|m| m.material.is_some());
    if outcome.material_libraries.is_empty() && !used {
        return Ok(());
    }
    let obj_dir = folder_of(obj);
    let mut table: HashMap<String, Material> = HashMap::new();
    let mut loaded: Vec<PathBuf> = Vec::new();
    for lib in &outcome.material_libraries {
        for name in library_files(obj_dir, lib) {
            // A library outside the folder, a FIFO or a device, or one over the byte limit is
            // refused: the file is hostile, not merely incomplete.
            let refuse = |message: String| ReadError::Unsupported {
                file: obj.to_path_buf(),
                message: format!("mtllib {message}"),
            };
            let path = file_limits::resolve_reference(obj_dir, &name).map_err(refuse)?;
            let bytes = match file_limits::read_regular(&path) {
                Ok(b) => b,
                Err(e) if e.kind() == std::io::ErrorKind::InvalidInput => {
                    return Err(refuse(format!("{}: {e}", path.display())));
                }
                Err(e) => {
                    outcome.warnings.push(Warning::new(
                        WarningKind::SkippedMaterial,
                        format!(
                            "{}: cannot read its material library {}: {e}; its materials are not \
                         applied",
                            obj.display(),
                            path.display()
                        ),
                    ));
                    continue;
                }
            };
            let (materials, warnings) = parse_mtl(&bytes, &path);
            outcome.warnings.extend(warnings);
            let mtl_dir = folder_of(&path);
            for mut m in materials {
                m.texture = m.texture.map(|t| rebase(&t, mtl_dir, obj_dir));
                table.entry(m.name.clone()).or_insert(m);
            }
            loaded.push(path);
        }
    }
    let mut unknown: Vec<String> = Vec::new();
    let mut unknown_seen: HashSet<String> = HashSet::new();
    for model in &mut outcome.scene.models {
        let Some(name) = &model.material else {
            continue;
        };
        let Some(m) = table.get(name) else {
            if unknown_seen.insert(name.clone()) {
                unknown.push(name.clone());
            }
            continue;
        };
        if let Some(kd) = m.diffuse {
            model.diffuse = kd;
        }
        if model.texcoords.is_some() {
            model.texture.clone_from(&m.texture);
            model.texture_repeat = [!m.clamp; 2];
        }
    }
    warn_unknown(outcome, obj, &unknown, &loaded);
    Ok(())
}

/// One warning naming the materials used but defined in no library read.
fn warn_unknown(outcome: &mut ReadOutcome, obj: &Path, unknown: &[String], loaded: &[PathBuf]) {
    if !unknown.is_empty() {
        let quoted: Vec<String> = unknown.iter().map(|n| format!("'{n}'")).collect();
        let where_ = if loaded.is_empty() {
            "no material library could be read".to_string()
        } else {
            let files: Vec<String> = loaded.iter().map(|p| p.display().to_string()).collect();
            format!("not defined in {}", files.join(", "))
        };
        outcome.warnings.push(Warning::new(
            WarningKind::SkippedMaterial,
            format!(
                "{}: material {} {where_}; the default grey is used",
                obj.display(),
                quoted.join(", ")
            ),
        ));
    }
}

/// One `newmtl` of an MTL output.
#[derive(Debug, Clone, PartialEq)]
pub struct MtlEntry {
    pub name: String,
    pub diffuse: [f32; 3],
    pub texture: Option<String>,
    /// Written as `-clamp on`: the texture repeats along neither u nor v. (MTL has one
    /// setting for both: a texture that repeats along one only is written repeating.)
    pub clamp: bool,
}

/// The materials an OBJ output needs, and each model's entry; `None` when no model has a
/// texture the OBJ maps, a material name or a diffuse colour other than the default (a
/// plain conversion stays a plain OBJ).
pub struct MtlPlan {
    pub entries: Vec<MtlEntry>,
    /// For each model, its entry's index.
    pub of_model: Vec<usize>,
}

/// The texture an OBJ output maps for `m`: only with one coordinate pair per vertex.
fn mapped_texture(m: &Model) -> Option<&String> {
    let t = m.texcoords.as_ref()?;
    (t.len() == m.positions.len())
        .then_some(m.texture.as_ref())
        .flatten()
}

/// A material name as one MTL word: whitespace, control characters and `#` become `_`.
fn clean(name: &str) -> String {
    name.trim()
        .chars()
        .map(|c| {
            if c.is_whitespace() || c.is_control() || c == '#' {
                '_'
            } else {
                c
            }
        })
        .collect()
}

/// Works out the `newmtl` entries for `scene` (see the module documentation).
pub fn plan(scene: &Scene) -> Option<MtlPlan> {
    let needed = scene.models.iter().any(|m| {
        m.material.is_some() || mapped_texture(m).is_some() || m.diffuse != Model::DEFAULT_DIFFUSE
    });
    if !needed {
        return None;
    }
    let mut entries: Vec<MtlEntry> = Vec::new();
    let mut names: HashSet<String> = HashSet::new();
    // Each entry by the name it was wanted under (before `_K` was added) and its look.
    let mut by_look: HashMap<(String, [u32; 3], Option<String>, bool), usize> = HashMap::new();
    let mut next_suffix: HashMap<String, usize> = HashMap::new();
    let mut of_model = Vec::with_capacity(scene.models.len());
    for (i, m) in scene.models.iter().enumerate() {
        let wanted = match clean(m.material.as_deref().unwrap_or(&m.name)) {
            n if n.is_empty() => format!("material_{}", i + 1),
            n => n,
        };
        let (diffuse, texture) = (m.diffuse, mapped_texture(m).cloned());
        let clamp = texture.is_some() && m.texture_repeat == [false; 2];
        // Same wanted name and same look: the same entry.
        let look = (
            wanted.clone(),
            diffuse.map(f32::to_bits),
            texture.clone(),
            clamp,
        );
        let index = match by_look.get(&look) {
            Some(&e) => e,
            None => {
                // Suffixes go on from the last one given for this name: no rescans.
                let k = next_suffix.entry(wanted.clone()).or_insert(2);
                let mut name = wanted.clone();
                while names.contains(&name) {
                    name = format!("{wanted}_{k}");
                    *k += 1;
                }
                names.insert(name.clone());
                entries.push(MtlEntry {
                    name,
                    diffuse,
                    texture,
                    clamp,
                });
                by_look.insert(look, entries.len() - 1);
                entries.len() - 1
            }
        };
        of_model.push(index);
    }
    Some(MtlPlan { entries, of_model })
}

/// Writes the MTL text for `entries` to `w`.
pub fn write_mtl_to(w: &mut impl Write, entries: &[MtlEntry]) -> std::io::Result<()> {
    writeln!(w, "# written by decimate: {} materials", entries.len())?;
    for e in entries {
        let [r, g, b] = e.diffuse;
        writeln!(w, "\nnewmtl {}", e.name)?;
        writeln!(w, "Ka 0 0 0")?;
        writeln!(w, "Kd {r} {g} {b}")?;
        writeln!(w, "Ks 0 0 0")?;
        writeln!(w, "d 1")?;
        writeln!(w, "illum 1")?;
        if let Some(t) = &e.texture {
            let t: String = t.chars().filter(|c| !c.is_control()).collect();
            // A name starting with '-' would read as an option.
            let dot = if t.starts_with('-') { "./" } else { "" };
            let clamp = if e.clamp { "-clamp on " } else { "" };
            writeln!(w, "map_Kd {clamp}{dot}{t}")?;
        }
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_and_lone_carriage_returns_are_read_like_an_obj() {
        let text = "newmtl skin\rKd 0.5 0.25 1\rmap_Kd tex.png\rnewmtl b\r";
        let expect = Material {
            name: "skin".into(),
            diffuse: Some([0.5, 0.25, 1.0]),
            texture: Some("tex.png".into()),
            clamp: false,
        };
        let bom = [&[0xEF, 0xBB, 0xBF][..], text.as_bytes()].concat();
        let (materials, warnings) = parse_mtl(&bom, Path::new("m.mtl"));
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(materials.len(), 2);
        assert_eq!(materials[0], expect);
        let mut wide = vec![0xFF, 0xFE];
        text.encode_utf16()
            .for_each(|u| wide.extend(u.to_le_bytes()));
        let (materials, warnings) = parse_mtl(&wide, Path::new("m.mtl"));
        assert!(materials.is_empty());
        assert!(warnings[0].message.contains("m.mtl:1: the file is UTF-16"));
    }

    #[test]
    fn map_kd_options_are_skipped_and_the_file_name_kept_whole() {
        let file = |rest: &str| map_file(rest).map(|(f, _)| f);
        assert_eq!(map_file("skin.jpg"), Ok(("skin.jpg".into(), false)));
        assert_eq!(
            map_file("-s 1 1 1 -o 0 0 -clamp on -bm 0.5 my skin.jpg"),
            Ok(("my skin.jpg".into(), true))
        );
        assert_eq!(map_file("-clamp off a.png"), Ok(("a.png".into(), false)));
        // Fewer numbers than three: the next option or the file name ends them.
        assert_eq!(file("-s 2 tex/a.png").as_deref(), Ok("tex/a.png"));
        assert_eq!(file("-mm 0 1 b.png").as_deref(), Ok("b.png"));
        // An option needs its value and leaves a file name, or the line is refused.
        assert!(map_file("-o 1")
            .unwrap_err()
            .contains("'-o' without a value"));
        assert!(map_file("-clamp").unwrap_err().contains("no file name"));
        assert_eq!(file("-s 1 -x.png").as_deref(), Ok("-x.png"));
        assert!(map_file("-zz a.png").unwrap_err().contains("'-zz'"));
        assert!(map_file("").is_err());
    }

    #[test]
    fn kd_reads_grey_and_rgb_and_refuses_the_rest() {
        assert_eq!(kd("0.5"), Ok([0.5; 3]));
        assert_eq!(kd("0.1 0.2 1.5"), Ok([0.1, 0.2, 1.0]));
        assert!(kd("0.1 0.2").is_err());
        assert!(kd("spectral a.rfl").unwrap_err().contains("spectral"));
        assert!(kd("0.1 x 0.3").unwrap_err().contains("'x'"));
    }

    #[test]
    fn entries_are_shared_by_equal_materials_and_renamed_when_they_differ() {
        let model = |name: &str, material: Option<&str>, diffuse| Model {
            name: name.into(),
            material: material.map(String::from),
            diffuse,
            ..Model::default()
        };
        let scene = Scene {
            models: vec![
                model("a", Some("skin"), [1.0, 0.0, 0.0]),
                model("b", Some("skin"), [1.0, 0.0, 0.0]),
                model("c", Some("skin"), [0.0, 1.0, 0.0]),
                model("my part", None, Model::DEFAULT_DIFFUSE),
            ],
        };
        let plan = plan(&scene).expect("materials are needed");
        let names: Vec<&str> = plan.entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["skin", "skin_2", "my_part"]);
        assert_eq!(plan.of_model, [0, 0, 1, 2]);
        let plain = Scene {
            models: vec![model("a", None, Model::DEFAULT_DIFFUSE)],
        };
        assert!(super::plan(&plain).is_none());
    }
}

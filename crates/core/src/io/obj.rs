//! Wavefront OBJ: a reader for polygon meshes and a writer, plus the logical-line splitter
//! that the OFF reader shares.
//!
//! Read: `v x y z [w]` or `v x y z r g b` (per-vertex colours, 0..1), `vn` (indices checked,
//! values not kept: OBJ normals are per corner and are recomputed with the crease angle like
//! any file without normals), `vt u [v [w]]` (texture coordinates, per corner: a point with
//! different ones in different faces becomes one vertex per seam side; a group where some
//! corner has none is read without them, with a warning), `f` with `v`, `v/vt`, `v//vn` or
//! `v/vt/vn` corners
//! and 1-based or negative (relative) indices, polygons of any size (triangulated, concave
//! ones included), `o` / `g` starting a new model (named after them; groups without faces are
//! dropped), `\` line continuation, `#` comments. `usemtl NAME` sets the material of the faces
//! after it (`Model::material`; it carries over `o` / `g`): a group whose faces use several
//! materials becomes one model per material, in the order they are first used, named
//! `group (material)` (`group (no material)` for faces before the first `usemtl`); a group
//! with one material keeps its own name. `mtllib` names are handed back
//! (`ReadOutcome::material_libraries`): this reader sees only bytes, `io::read_scene` loads
//! them (`mtl`). `s`, `l`, `p` and any other statement are skipped with one warning per kind.
//! A face may only use vertices defined above it (every exporter writes them first), so a bad
//! index is reported on its own line.
//! Write: one `o` per model, positions in world space (OBJ has no transforms), per-vertex
//! colours as `v x y z r g b`, texture coordinates as one `vt` per vertex (`f v/vt`), 1-based
//! indices, counter-clockwise triangles. When a model has a texture, a material name or a
//! diffuse colour other than the default, `FILE.mtl` is written beside `FILE.obj` (`mtl`),
//! named by `mtllib`, and each model's `o` is followed by its `usemtl`.

use crate::io::warning::{Warning, WarningKind};
use std::collections::{HashMap, HashSet};
use std::io::Write;
use std::path::{Path, PathBuf};

use glam::Mat4;

use super::mtl::MtlPlan;

use super::origin::Recentre;
use super::shape_to_model::{build, Bind, ShapeSpec, TexCoords};
use super::text::{
    coordinate, number, parse_int, relative_point, shown, words, Lines, PResult, ParseError,
};
use super::{ReadOutcome, WriteError};
use crate::mesh::{Attribute, Model, Scene};

/// True when the first statement of the file (after comments) is an OBJ one.
pub(crate) fn looks_like_obj(bytes: &[u8]) -> bool {
    Lines::new(bytes, false)
        .take(1000)
        .find_map(|(_, text)| words(&text).next().map(|w| w.to_vec()))
        .is_some_and(|w| {
            matches!(
                w.as_slice(),
                b"v" | b"vn" | b"vt" | b"f" | b"o" | b"g" | b"mtllib" | b"usemtl" | b"s"
            )
        })
}

/// The faces of one `o` / `g` group that use one material.
struct MaterialPart {
    /// The `usemtl` name in force for these faces, if any.
    material: Option<String>,
    corners: Vec<u32>,
    /// Each corner's texture coordinate index, `u32::MAX` where it has none.
    texcoords: Vec<u32>,
    ends: Vec<u32>,
    /// The line of the first face (for messages).
    line: usize,
}

/// One `o` / `g` group: its faces, one part per material in the order the materials are
/// first used in it.
#[derive(Default)]
struct Group {
    name: String,
    parts: Vec<MaterialPart>,
    /// Each material's part (a file may switch materials very often).
    by_material: HashMap<Option<String>, usize>,
}

impl Group {
    fn new(name: String) -> Self {
        Self {
            name,
            parts: Vec::new(),
            by_material: HashMap::new(),
        }
    }

    /// The part for faces under `material`, made (starting at `line`) when there is none.
    fn part(&mut self, material: &Option<String>, line: usize) -> usize {
        let parts = &mut self.parts;
        *self.by_material.entry(material.clone()).or_insert_with(|| {
            parts.push(MaterialPart {
                material: material.clone(),
                corners: Vec::new(),
                texcoords: Vec::new(),
                ends: Vec::new(),
                line,
            });
            parts.len() - 1
        })
    }

    /// The group's models-to-be with their names: the group's own name when all its faces
    /// share one material, else `group (material)` for each part (`(no material)` for faces
    /// before the first `usemtl`).
    fn into_named_parts(self) -> impl Iterator<Item = (String, MaterialPart)> {
        let split = self.parts.len() > 1;
        let name = self.name;
        self.parts.into_iter().map(move |p| {
            let n = if !split {
                name.clone()
            } else {
                let m = p.material.as_deref().unwrap_or("no material");
                if name.is_empty() {
                    m.to_string()
                } else {
                    format!("{name} ({m})")
                }
            };
            (n, p)
        })
    }
}

/// The rest of a statement's line after its keyword, spaces inside kept (names and file
/// names may hold them), `None` when empty.
fn rest_of_line(text: &[u8]) -> Option<String> {
    let text = String::from_utf8_lossy(text);
    let rest = text.trim().split_once(|c: char| c.is_ascii_whitespace())?.1;
    let rest = rest.trim();
    (!rest.is_empty()).then(|| rest.to_string())
}

/// Resolves one OBJ index (1-based, or negative: relative to the `count` defined so far).
fn resolve(w: &[u8], count: usize, line: usize, what: &str) -> PResult<u32> {
    let i = parse_int(w).ok_or_else(|| {
        ParseError::new(
            line,
            format!("expected a {what} index, found '{}'", shown(w)),
        )
    })?;
    let resolved = if i > 0 && (i as u64) <= count as u64 {
        i - 1
    } else if i < 0 && i.unsigned_abs() <= count as u64 {
        count as i64 + i
    } else if i == 0 {
        return Err(ParseError::new(
            line,
            format!("{what} index 0 is invalid (OBJ indices start at 1)"),
        ));
    } else {
        return Err(ParseError::new(
            line,
            format!(
                "{what} index {i} is out of range: {count} {} defined above this line",
                match what {
                    "vertex" => "vertices are",
                    "normal" => "normals are",
                    _ => "texture coordinates are",
                }
            ),
        ));
    };
    u32::try_from(resolved)
        .map_err(|_| ParseError::new(line, format!("{what} index {i} is too large")))
}

/// The values of a `v` statement (`v x y z [w]` or `v x y z r g b`): the position, and the
/// colour when it has one, the position relative to the origin `recentre` picks. Shared by
/// the ordinary and the streaming reader.
pub(super) fn vertex_values<'a>(
    mut w: impl Iterator<Item = &'a [u8]>,
    line: usize,
    recentre: &mut Recentre,
) -> PResult<([f32; 3], Option<[f32; 3]>)> {
    let x = coordinate(w.next(), line, "a vertex's x")?;
    let y = coordinate(w.next(), line, "a vertex's y")?;
    let z = coordinate(w.next(), line, "a vertex's z")?;
    let p = relative_point(recentre, [x, y, z], line)?;
    let rest: [Option<&[u8]>; 5] = std::array::from_fn(|_| w.next());
    let color = match rest {
        [None, ..] | [Some(_), None, ..] => None,
        [Some(r), Some(g), Some(b), None | Some(_), None] => Some([
            number(Some(r), line, "a vertex's red")?,
            number(Some(g), line, "a vertex's green")?,
            number(Some(b), line, "a vertex's blue")?,
        ]),
        _ => {
            return Err(ParseError::new(
                line,
                "a vertex has too many values (expected 'v x y z [w]' or 'v x y z r g b')",
            ))
        }
    };
    if let [Some(wv), None, ..] = rest {
        number(Some(wv), line, "a vertex's w")?;
    }
    Ok((p, color))
}

/// One face corner (`v`, `v/vt`, `v//vn` or `v/vt/vn`) checked against the `counts` of
/// vertices, texture coordinates and normals defined so far: its vertex index and its
/// texture coordinate index (`u32::MAX` when it has none). Shared by both readers.
pub(super) fn face_corner(corner: &[u8], counts: [usize; 3], line: usize) -> PResult<(u32, u32)> {
    let mut parts = corner.split(|&b| b == b'/');
    let v = parts.next().unwrap_or(corner);
    let v = resolve(v, counts[0], line, "vertex")?;
    let t = match parts.next().filter(|t| !t.is_empty()) {
        Some(t) => resolve(t, counts[1], line, "texture coordinate")?,
        None => u32::MAX,
    };
    if let Some(n) = parts.next().filter(|n| !n.is_empty()) {
        resolve(n, counts[2], line, "normal")?;
    }
    if parts.next().is_some() {
        return Err(ParseError::new(
            line,
            format!(
                "bad face corner '{}' (expected v, v/vt, v//vn or v/vt/vn)",
                shown(corner)
            ),
        ));
    }
    Ok((v, t))
}

/// Tiling's read: hands each triangle of an OBJ (polygons fanned from their first corner) to
/// `triangle` as its `f` line is read, holding only the positions. Lines (comments,
/// continuations), `v` values and face corners are read by the ordinary reader's code.
pub(super) fn stream_obj(
    input: impl std::io::BufRead,
    recentre: &mut Recentre,
    triangle: &mut dyn FnMut([[f32; 3]; 3]),
) -> PResult<()> {
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let (mut uv_count, mut normal_count) = (0usize, 0usize);
    let mut face: Vec<[f32; 3]> = Vec::new();
    for item in super::text::StreamedLines::new(input, true) {
        let (line, text) = item?;
        let mut w = words(&text);
        match w.next() {
            Some(b"v") => positions.push(vertex_values(w, line, recentre)?.0),
            Some(b"vt") => uv_count += 1,
            Some(b"vn") => normal_count += 1,
            Some(b"f") => {
                face.clear();
                let counts = [positions.len(), uv_count, normal_count];
                for corner in w {
                    let (v, _) = face_corner(corner, counts, line)?;
                    face.push(positions[v as usize]);
                }
                if face.len() >= 3 {
                    for w in face[1..].windows(2) {
                        triangle([face[0], w[0], w[1]]);
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Reads an OBJ file into one model per non-empty `o` / `g` group and material; the
/// `mtllib` names come back in `material_libraries` (the caller knows where to look).
pub fn read_obj(bytes: &[u8]) -> PResult<ReadOutcome> {
    let mut r = ObjReader::default();
    for (line, text) in Lines::new(bytes, true) {
        let mut w = words(&text);
        let Some(key) = w.next() else { continue };
        match key {
            b"v" => r.vertex(w, line)?,
            b"vn" => {
                for what in ["a normal's x", "a normal's y", "a normal's z"] {
                    number(w.next(), line, what)?;
                }
                r.normal_count += 1;
            }
            b"vt" => {
                r.uv.push(number(w.next(), line, "a texture coordinate's u")?);
                r.uv.push(match w.next() {
                    Some(v) => number(Some(v), line, "a texture coordinate's v")?,
                    None => 0.0,
                });
            }
            b"f" => r.face(w, line)?,
            b"o" | b"g" => r.group(&text),
            b"usemtl" => r.use_material(&text, line),
            b"mtllib" => match rest_of_line(&text) {
                Some(lib) => r.libraries.push(lib),
                None => r.warnings.push(
                    Warning::new(
                        WarningKind::SkippedMaterial,
                        format!("OBJ 'mtllib' without a file name on line {line} skipped"),
                    )
                    .at(line),
                ),
            },
            _ => r.skip(key, line),
        }
    }
    r.finish()
}

/// An OBJ file's statements read so far.
#[derive(Default)]
struct ObjReader {
    warnings: Vec<Warning>,
    /// Statement keys (and other things) already warned about, to warn once.
    warned: HashSet<Vec<u8>>,
    coords: Vec<f32>,
    /// Per-vertex colours (MeshLab's `v x y z r g b`), grey before the first coloured vertex.
    rgb: Vec<f32>,
    colored: bool,
    normal_count: usize,
    uv: Vec<f32>,
    groups: Vec<Group>,
    cur: Group,
    libraries: Vec<String>,
    /// The `usemtl` in force (it carries over `o` / `g`), and its part of `cur` once a face
    /// has used it.
    material: Option<String>,
    part: Option<usize>,
    /// The origin, picked from the first vertex; all models of the file share it.
    recentre: Recentre,
}

impl ObjReader {
    /// `v x y z [w]` or `v x y z r g b`.
    fn vertex<'a>(&mut self, w: impl Iterator<Item = &'a [u8]>, line: usize) -> PResult<()> {
        let ([x, y, z], color) = vertex_values(w, line, &mut self.recentre)?;
        self.coords.extend([x, y, z]);
        match color {
            Some(c) => {
                if !self.colored {
                    self.colored = true;
                    self.rgb.resize(self.coords.len() - 3, 0.8);
                }
                self.rgb.extend(c);
            }
            None if self.colored => self.rgb.extend([0.8; 3]),
            None => {}
        }
        Ok(())
    }

    /// `f v/vt/vn …`: a polygon in the current group's part for the material in force.
    fn face<'a>(&mut self, w: impl Iterator<Item = &'a [u8]>, line: usize) -> PResult<()> {
        let (material, group) = (&self.material, &mut self.cur);
        let i = *self.part.get_or_insert_with(|| group.part(material, line));
        let cur = &mut group.parts[i];
        let counts = [self.coords.len() / 3, self.uv.len() / 2, self.normal_count];
        for corner in w {
            let (v, t) = face_corner(corner, counts, line)?;
            cur.corners.push(v);
            cur.texcoords.push(t);
        }
        cur.ends.push(cur.corners.len() as u32);
        Ok(())
    }

    /// `o NAME` / `g NAME`: a new group (`default` when unnamed); the last one is kept if it
    /// has faces.
    fn group(&mut self, text: &[u8]) {
        let name = words(text)
            .skip(1)
            .map(|n| String::from_utf8_lossy(n).into_owned())
            .collect::<Vec<_>>()
            .join(" ");
        let name = if name.is_empty() {
            "default".to_string()
        } else {
            name
        };
        let done = std::mem::replace(&mut self.cur, Group::new(name));
        self.part = None;
        if !done.parts.is_empty() {
            self.groups.push(done);
        }
    }

    /// `usemtl NAME`: the material of the faces that follow.
    fn use_material(&mut self, text: &[u8], line: usize) {
        let name = rest_of_line(text);
        if name.is_none() && self.warned.insert(b"usemtl without a name".to_vec()) {
            self.warnings.push(
                Warning::new(
                    WarningKind::SkippedMaterial,
                    format!(
                        "OBJ 'usemtl' without a material name on line {line}: the faces after \
                         it have no material"
                    ),
                )
                .at(line),
            );
        }
        if name != self.material {
            self.material = name;
            self.part = None;
        }
    }

    /// A statement the reader does not use: warned about once per key.
    fn skip(&mut self, key: &[u8], line: usize) {
        if self.warned.insert(key.to_vec()) {
            let k = shown(key);
            let message = match key {
                b"s" => "OBJ 's' (smoothing group) statements skipped".to_string(),
                b"l" | b"p" => format!("OBJ '{k}' statements skipped (only faces are read)"),
                _ => format!("unknown OBJ statement '{k}' skipped (first on line {line})"),
            };
            self.warnings
                .push(Warning::new(WarningKind::SkippedNode, message).at(line));
        }
    }

    /// One model per group and material, built from the faces read.
    fn finish(mut self) -> PResult<ReadOutcome> {
        if !self.cur.parts.is_empty() {
            self.groups.push(std::mem::take(&mut self.cur));
        }
        if self.groups.is_empty() {
            return Err(ParseError::new(
                1,
                "the OBJ file has no faces ('f' lines): nothing to read",
            ));
        }
        let mut warnings = self.warnings;
        let mut models = Vec::with_capacity(self.groups.len());
        for (name, mut g) in self.groups.into_iter().flat_map(Group::into_named_parts) {
            let texcoords = if g.texcoords.iter().all(|&t| t == u32::MAX) {
                None
            } else if g.texcoords.contains(&u32::MAX) {
                warnings.push(Warning::new(
                    WarningKind::SkippedAttribute,
                    format!(
                        "{}: some face corners have texture coordinates ('v/vt') and some do \
                         not; texture coordinates ignored",
                        name
                    ),
                ));
                None
            } else {
                Some(TexCoords {
                    values: &self.uv,
                    index: std::mem::take(&mut g.texcoords),
                })
            };
            let colors = if self.colored {
                Bind::PerCorner {
                    values: &self.rgb,
                    index: g.corners.clone(),
                }
            } else {
                Bind::None
            };
            let mut model = build(
                ShapeSpec {
                    name,
                    transform: Mat4::IDENTITY,
                    coords: &self.coords,
                    corners: g.corners,
                    ends: g.ends,
                    colors,
                    normals: Bind::None,
                    texcoords,
                    ccw: true,
                    solid: false,
                    crease_angle: None,
                    diffuse: Model::DEFAULT_DIFFUSE,
                    line: g.line,
                    index_field: "f",
                },
                &mut warnings,
            )?;
            model.material = g.material;
            model.origin = self.recentre.origin();
            models.push(model);
        }
        Ok(ReadOutcome {
            scene: Scene { models },
            warnings,
            progressive: None,
            material_libraries: self.libraries,
        })
    }
}

/// A model name as one OBJ word list (no line breaks or comment signs).
fn clean_name(name: &str, i: usize) -> String {
    let n: String = name
        .chars()
        .map(|c| if c.is_control() || c == '#' { '_' } else { c })
        .collect();
    let n = n.trim();
    if n.is_empty() {
        format!("shape_{}", i + 1)
    } else {
        n.to_string()
    }
}

/// The MTL file written beside the OBJ output `path`: its name with `.mtl` for `.obj`
/// (`.obj.gz` too).
pub fn mtl_path_for(path: &Path) -> PathBuf {
    let mut stem = path
        .file_stem()
        .map(Path::new)
        .unwrap_or(Path::new("materials"));
    let is_gz = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
    if is_gz {
        stem = stem.file_stem().map(Path::new).unwrap_or(stem);
    }
    path.with_file_name(stem).with_extension("mtl")
}

/// Writes all models as one OBJ, via a temporary file and a rename; when the scene has
/// materials worth keeping (see `mtl::plan`), first writes them to the MTL file beside it
/// ([`mtl_path_for`]) the same way, and the OBJ names it (`mtllib`) and one material per
/// model (`usemtl`).
pub fn write_obj(scene: &Scene, path: &Path) -> Result<(), WriteError> {
    let Some(plan) = super::mtl::plan(scene) else {
        return super::write_atomically(path, |w| write_obj_to(w, scene));
    };
    let mtl_path = mtl_path_for(path);
    super::write_atomically(&mtl_path, |w| super::mtl::write_mtl_to(w, &plan.entries))?;
    let library = mtl_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let materials = Materials {
        library: &library,
        plan: &plan,
    };
    super::write_atomically(path, |w| write_obj_with(w, scene, Some(materials)))
}

/// What an OBJ with materials names: its library and each model's entry in it.
#[derive(Clone, Copy)]
struct Materials<'a> {
    library: &'a str,
    plan: &'a MtlPlan,
}

/// Writes the OBJ text to `w`, without materials.
pub fn write_obj_to(w: &mut impl Write, scene: &Scene) -> std::io::Result<()> {
    write_obj_with(w, scene, None)
}

fn write_obj_with(
    w: &mut impl Write,
    scene: &Scene,
    materials: Option<Materials<'_>>,
) -> std::io::Result<()> {
    writeln!(
        w,
        "# written by decimate: {} models, {} vertices, {} triangles",
        scene.models.len(),
        scene.vertex_count(),
        scene.triangle_count()
    )?;
    writeln!(
        w,
        "# positions are in world space (model transforms applied)"
    )?;
    if let Some(m) = materials {
        writeln!(w, "mtllib {}", m.library)?;
    }
    let (mut base, mut tbase) = (1u64, 1u64);
    for (i, m) in scene.models.iter().enumerate() {
        writeln!(w, "o {}", clean_name(&m.name, i))?;
        let entry = materials.and_then(|mm| {
            let e = *mm.plan.of_model.get(i)?;
            mm.plan.entries.get(e)
        });
        if let Some(entry) = entry {
            writeln!(w, "usemtl {}", entry.name)?;
        }
        let colors = match &m.colors {
            Some(Attribute::PerVertex(c)) if c.len() == m.positions.len() => Some(c),
            _ => None,
        };
        for (k, &p) in m.positions.iter().enumerate() {
            let [x, y, z] = super::origin::coords(m, m.transform.transform_point3(p));
            match colors {
                Some(c) => {
                    let [r, g, b] = c[k];
                    writeln!(w, "v {x} {y} {z} {r:?} {g:?} {b:?}")?
                }
                None => writeln!(w, "v {x} {y} {z}")?,
            }
        }
        // One `vt` per vertex, in the vertices' order; `vt` numbers run on across models,
        // counting only those of textured models.
        let textured = match &m.texcoords {
            Some(t) if t.len() == m.positions.len() => {
                for [u, v] in t {
                    writeln!(w, "vt {u:?} {v:?}")?;
                }
                true
            }
            _ => false,
        };
        for t in super::outward_triangles(m) {
            let [a, b, c] = t.map(|v| v as u64 + base);
            let (at, bt, ct) = (a - base + tbase, b - base + tbase, c - base + tbase);
            if textured {
                writeln!(w, "f {a}/{at} {b}/{bt} {c}/{ct}")?;
            } else {
                writeln!(w, "f {a} {b} {c}")?;
            }
        }
        if textured {
            tbase += m.positions.len() as u64;
        }
        base += m.positions.len() as u64;
    }
    w.flush()
}

#[cfg(test)]
mod stream_tests {
    use super::super::source::testing::{sorted_bits, sorted_triangles};
    use super::*;

    #[test]
    fn the_stream_gives_the_ordinary_reads_triangles() {
        let text = b"# a comment\nv 0 0 0\nv 1 0 0 \\\n\nv 1 1 0.5\nv 0 1 0.25 0.1 0.2 0.3\n\
                     vt 0 0\nvn 0 0 1\nf 1/1/1 2 3\ng x\nf -4 -2 -1\nusemtl m\nf 2 3 4\n";
        let read = read_obj(text).unwrap();
        assert_eq!(read.scene.triangle_count(), 3);
        let mut streamed = Vec::new();
        stream_obj(&text[..], &mut Recentre::default(), &mut |t| {
            streamed.push(t)
        })
        .unwrap();
        assert_eq!(sorted_bits(streamed), sorted_triangles(&read.scene));
    }
}

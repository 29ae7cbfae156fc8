//! The progressive-mesh file (`decimate … nogui --progressive FILE`, `.pm` by convention): a
//! [`ProgressiveScene`] — each model's base mesh, its vertex splits and the map back to the
//! original's numbering — in a binary, little-endian, versioned layout that is read back
//! exactly (every `f32` bit for bit).
//!
//! [`write_progressive`] goes through a temporary file and a rename, as every writer does.
//! [`read_progressive`] reads the whole file at once and checks everything before it is used:
//! truncation, the magic and version, counts against the bytes left, every index against the
//! level it is used at, non-finite reals, and finally [`ProgressiveModel::validate`]. Errors
//! name the file and the byte offset of what is wrong ([`ReadError::Binary`]); no input
//! panics it or makes it allocate more than the file's length allows.
//!
//! # Layout, version 1 (and 2)
//!
//! Integers are unsigned little-endian (`u8`, `u32`); reals are little-endian IEEE-754 `f32`
//! and finite; `vec3` is three reals (x, y, z), `rgb` three reals (red, green, blue, 0..=1),
//! `uv` two reals (u, v); a flag is a `u8`, 0 or 1. Nothing is padded or aligned; a count
//! comes before what it counts. The file ends right after the last model.
//!
//! | field                      | type             | notes                                                     |
//! |----------------------------|------------------|-----------------------------------------------------------|
//! | magic                      | 8 bytes          | `DECIMPM\0`                                               |
//! | version                    | u32              | 1                                                         |
//! | model count                | u32              | M; M model records follow                                 |
//! | *model:* name length       | u32              | L                                                         |
//! | name                       | L bytes          | UTF-8                                                     |
//! | transform                  | 16 × f32         | local to world, column-major (column 0 first)             |
//! | origin                     | 3 × f64          | version 2 only: added after the transform (`Model::origin`) |
//! | diffuse                    | rgb              | the material's colour                                     |
//! | crease flag, crease angle  | flag, f32        | radians; the angle is there (0) when the flag is 0        |
//! | solid                      | flag             |                                                           |
//! | attributes                 | u8               | bit 0 per-vertex colours, bit 1 per-face colours, bit 2 per-vertex normals, bit 3 texture coordinates, bit 4 texture image, bit 5 material name, bits 6 and 7 the image clamps along u and along v (with bit 4 only; otherwise it repeats); bits 0 and 1 exclusive |
//! | image name length          | u32              | bit 4 only: N                                             |
//! | image name                 | N bytes          | bit 4 only: UTF-8, the texture image as the input named it |
//! | material name length       | u32              | bit 5 only: N                                             |
//! | material name              | N bytes          | bit 5 only: UTF-8, the material (OBJ `usemtl`)            |
//! | base vertex count          | u32              | V                                                         |
//! | base face count            | u32              | F                                                         |
//! | positions                  | V × vec3         |                                                           |
//! | vertex colours             | V × rgb          | bit 0 only                                                |
//! | vertex normals             | V × vec3         | bit 2 only                                                |
//! | texture coordinates        | V × uv           | bit 3 only                                                |
//! | triangles                  | F × 3 u32        | vertex ids below V, counter-clockwise from the front      |
//! | face colours               | F × rgb          | bit 1 only                                                |
//! | split count                | u32              | S; S split records follow, split i adds vertex V + i      |
//! | *split i:* keep            | u32              | the vertex that splits, below V + i                       |
//! | keep coarse, keep fine     | vec3, vec3       | `keep`'s position before the split and after it           |
//! | new position               | vec3             | vertex V + i                                              |
//! | colours                    | 3 × rgb          | bit 0 only: keep coarse, keep fine, new                   |
//! | normals                    | 3 × vec3         | bit 2 only, same order                                    |
//! | texture coordinates        | 3 × uv           | bit 3 only, same order                                    |
//! | renamed count              | u32              | R                                                         |
//! | renamed                    | R × u32          | faces (ids at this level) whose `keep` corner becomes V + i |
//! | added count                | u8               | A (1 on a boundary edge, 2 inside)                        |
//! | added                      | A × 3 u32        | faces appended at this level, vertex ids up to V + i      |
//! | added colours              | A × rgb          | bit 1 only                                                |
//! | *after the splits:* vertex ids | (V + S) × u32 | the original model's id of each vertex                    |
//! | face ids                   | (F + ΣA) × u32   | the original model's id of each face                      |
//!
//! Faces are numbered as they appear: the F base faces, then each split's added faces in
//! order. A split's renamed faces are those that exist before it (ids below F plus the faces
//! the earlier splits added).
//!
//! Bits 3 to 5 came after the first files were written; those have them clear and read as
//! before.

use std::io::{self, Write};
use std::path::Path;

use glam::{Mat4, Vec3};

use super::{write_atomically, ReadError, WriteError};
use crate::mesh::progressive::{ProgressiveModel, ProgressiveScene, VertexSplit};
use crate::mesh::{Attribute, Model};

/// The first eight bytes of every progressive-mesh file.
pub const MAGIC: [u8; 8] = *b"DECIMPM\0";
/// The layout version this build writes for models near zero, and reads.
pub const VERSION: u32 = 1;
/// The layout version with each model's f64 origin: written when a model has a far one.
pub const VERSION_ORIGIN: u32 = 2;

const VERTEX_COLORS: u8 = 1;
const FACE_COLORS: u8 = 2;
const VERTEX_NORMALS: u8 = 4;
const TEXCOORDS: u8 = 8;
const TEXTURE_IMAGE: u8 = 16;
const MATERIAL_NAME: u8 = 32;
const CLAMP_U: u8 = 64;
const CLAMP_V: u8 = 128;

/// Writes `pm` to `path` via a temporary file beside it and a rename. A model that fails
/// [`ProgressiveModel::validate`] (or that the layout cannot hold, such as per-face normals)
/// is an error, and nothing is left at `path`.
pub fn write_progressive(pm: &ProgressiveScene, path: &Path) -> Result<(), WriteError> {
    write_atomically(path, |w| write_progressive_to(w, pm))
}

/// Writes the bytes of `pm` to `w` (see the module documentation for the layout).
pub fn write_progressive_to(w: &mut impl Write, pm: &ProgressiveScene) -> io::Result<()> {
    let attributes = pm
        .models
        .iter()
        .enumerate()
        .map(|(i, m)| check(m).map_err(|e| invalid(format!("model {i} ('{}'): {e}", m.base.name))))
        .collect::<io::Result<Vec<_>>>()?;
    let mut out = Out(w);
    out.bytes(&MAGIC)?;
    let far = pm.models.iter().any(|m| m.base.origin != glam::DVec3::ZERO);
    out.u32(if far { VERSION_ORIGIN } else { VERSION })?;
    out.len(pm.models.len())?;
    for (m, &a) in pm.models.iter().zip(&attributes) {
        write_model(&mut out, m, a, far)?;
    }
    Ok(())
}

/// Reads a progressive-mesh file written by [`write_progressive`].
pub fn read_progressive(path: &Path) -> Result<ProgressiveScene, ReadError> {
    let bytes = super::file_limits::read_regular(path).map_err(|source| ReadError::Io {
        file: path.to_path_buf(),
        source,
    })?;
    parse_progressive(&bytes, path)
}

/// Reads a progressive mesh from memory; `file_name` is used in messages.
pub fn parse_progressive(bytes: &[u8], file_name: &Path) -> Result<ProgressiveScene, ReadError> {
    scene(&mut Cursor { bytes, pos: 0 }).map_err(|e| ReadError::Binary {
        file: file_name.to_path_buf(),
        offset: e.offset,
        message: e.message,
    })
}

/// Which attributes a model carries, as the layout's attribute byte says.
#[derive(Debug, Clone, Copy)]
struct Attributes {
    vertex_colors: bool,
    face_colors: bool,
    normals: bool,
    texcoords: bool,
    texture_image: bool,
    material_name: bool,
    /// The image does not repeat along u, along v (`Model::texture_repeat`).
    clamp: [bool; 2],
}

impl Attributes {
    fn of(m: &Model) -> Self {
        Self {
            vertex_colors: matches!(m.colors, Some(Attribute::PerVertex(_))),
            face_colors: matches!(m.colors, Some(Attribute::PerFace(_))),
            normals: m.normals.is_some(),
            texcoords: m.texcoords.is_some(),
            texture_image: m.texture.is_some(),
            material_name: m.material.is_some(),
            clamp: m.texture_repeat.map(|r| m.texture.is_some() && !r),
        }
    }

    fn bits(self) -> u8 {
        let bit = |on: bool, b: u8| if on { b } else { 0 };
        bit(self.vertex_colors, VERTEX_COLORS)
            | bit(self.face_colors, FACE_COLORS)
            | bit(self.normals, VERTEX_NORMALS)
            | bit(self.texcoords, TEXCOORDS)
            | bit(self.texture_image, TEXTURE_IMAGE)
            | bit(self.material_name, MATERIAL_NAME)
            | bit(self.clamp[0], CLAMP_U)
            | bit(self.clamp[1], CLAMP_V)
    }

    fn from_bits(bits: u8) -> Option<Self> {
        let all = VERTEX_COLORS
            | FACE_COLORS
            | VERTEX_NORMALS
            | TEXCOORDS
            | TEXTURE_IMAGE
            | MATERIAL_NAME
            | CLAMP_U
            | CLAMP_V;
        let both_colors = VERTEX_COLORS | FACE_COLORS;
        let clamp_without_image = bits & (CLAMP_U | CLAMP_V) != 0 && bits & TEXTURE_IMAGE == 0;
        if bits & !all != 0 || bits & both_colors == both_colors || clamp_without_image {
            return None;
        }
        Some(Self {
            vertex_colors: bits & VERTEX_COLORS != 0,
            face_colors: bits & FACE_COLORS != 0,
            normals: bits & VERTEX_NORMALS != 0,
            texcoords: bits & TEXCOORDS != 0,
            texture_image: bits & TEXTURE_IMAGE != 0,
            material_name: bits & MATERIAL_NAME != 0,
            clamp: [bits & CLAMP_U != 0, bits & CLAMP_V != 0],
        })
    }

    /// Bytes of one base vertex, one base face and one split before its lists.
    fn vertex_size(self) -> usize {
        12 + 12 * (self.vertex_colors as usize + self.normals as usize)
            + 8 * self.texcoords as usize
    }

    fn face_size(self) -> usize {
        12 + 12 * self.face_colors as usize
    }

    fn split_size(self) -> usize {
        4 + 36
            + 36 * (self.vertex_colors as usize + self.normals as usize)
            + 24 * self.texcoords as usize
            + 4
            + 1
    }
}

// ---------------------------------------------------------------------------------------
// Writing

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// What the layout needs of a model before any byte is written.
fn check(m: &ProgressiveModel) -> Result<Attributes, String> {
    // `validate` also refuses per-face normals, which the layout has no room for.
    m.validate()?;
    if let Some(i) = m
        .splits
        .iter()
        .position(|s| s.added.len() > u8::MAX as usize)
    {
        return Err(format!("split {i} adds more than {} faces", u8::MAX));
    }
    Ok(Attributes::of(&m.base))
}

/// Little-endian output.
struct Out<'w, W: Write>(&'w mut W);

impl<W: Write> Out<'_, W> {
    fn bytes(&mut self, b: &[u8]) -> io::Result<()> {
        self.0.write_all(b)
    }

    fn u8(&mut self, v: u8) -> io::Result<()> {
        self.bytes(&[v])
    }

    fn u32(&mut self, v: u32) -> io::Result<()> {
        self.bytes(&v.to_le_bytes())
    }

    /// A count or length, which the layout holds in a `u32`.
    fn len(&mut self, n: usize) -> io::Result<()> {
        let n = u32::try_from(n).map_err(|_| invalid(format!("{n} is too many for the file")))?;
        self.u32(n)
    }

    fn f32s(&mut self, v: &[f32]) -> io::Result<()> {
        v.iter().try_for_each(|x| self.bytes(&x.to_le_bytes()))
    }

    fn vec3(&mut self, v: Vec3) -> io::Result<()> {
        self.f32s(&v.to_array())
    }

    fn u32s(&mut self, v: &[u32]) -> io::Result<()> {
        v.iter().try_for_each(|&x| self.u32(x))
    }
}

fn write_model<W: Write>(
    out: &mut Out<'_, W>,
    pm: &ProgressiveModel,
    a: Attributes,
    with_origin: bool,
) -> io::Result<()> {
    write_header(out, &pm.base, a, with_origin)?;
    write_base(out, &pm.base)?;
    out.len(pm.splits.len())?;
    for s in &pm.splits {
        write_split(out, s, a)?;
    }
    out.u32s(&pm.vertex_ids)?;
    out.u32s(&pm.face_ids)
}

fn write_header<W: Write>(
    out: &mut Out<'_, W>,
    m: &Model,
    a: Attributes,
    with_origin: bool,
) -> io::Result<()> {
    out.len(m.name.len())?;
    out.bytes(m.name.as_bytes())?;
    out.f32s(&m.transform.to_cols_array())?;
    if with_origin {
        for v in m.origin.to_array() {
            out.bytes(&v.to_le_bytes())?;
        }
    }
    out.f32s(&m.diffuse)?;
    out.u8(m.crease_angle.is_some() as u8)?;
    out.f32s(&[m.crease_angle.unwrap_or(0.0)])?;
    out.u8(m.solid as u8)?;
    out.u8(a.bits())?;
    for name in [&m.texture, &m.material].into_iter().flatten() {
        out.len(name.len())?;
        out.bytes(name.as_bytes())?;
    }
    out.len(m.positions.len())?;
    out.len(m.triangles.len())
}

fn write_base<W: Write>(out: &mut Out<'_, W>, m: &Model) -> io::Result<()> {
    m.positions.iter().try_for_each(|&p| out.vec3(p))?;
    if let Some(Attribute::PerVertex(c)) = &m.colors {
        c.iter().try_for_each(|c| out.f32s(c))?;
    }
    if let Some(Attribute::PerVertex(n)) = &m.normals {
        n.iter().try_for_each(|&n| out.vec3(n))?;
    }
    if let Some(t) = &m.texcoords {
        t.iter().try_for_each(|t| out.f32s(t))?;
    }
    m.triangles.iter().try_for_each(|t| out.u32s(t))?;
    if let Some(Attribute::PerFace(c)) = &m.colors {
        c.iter().try_for_each(|c| out.f32s(c))?;
    }
    Ok(())
}

fn write_split<W: Write>(out: &mut Out<'_, W>, s: &VertexSplit, a: Attributes) -> io::Result<()> {
    out.u32(s.keep)?;
    out.vec3(s.keep_coarse)?;
    out.vec3(s.keep_fine)?;
    out.vec3(s.position)?;
    if let (true, Some(c)) = (a.vertex_colors, &s.colors) {
        c.iter().try_for_each(|c| out.f32s(c))?;
    }
    if let (true, Some(n)) = (a.normals, &s.normals) {
        n.iter().try_for_each(|&n| out.vec3(n))?;
    }
    if let (true, Some(t)) = (a.texcoords, &s.texcoords) {
        t.iter().try_for_each(|t| out.f32s(t))?;
    }
    out.len(s.renamed.len())?;
    out.u32s(&s.renamed)?;
    // `check` made sure the count fits.
    out.u8(s.added.len().min(u8::MAX as usize) as u8)?;
    s.added.iter().try_for_each(|t| out.u32s(t))?;
    if a.face_colors {
        s.added_colors.iter().try_for_each(|c| out.f32s(c))?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Reading

/// What is wrong, and where.
#[derive(Debug)]
struct Bad {
    offset: usize,
    message: String,
}

type Parse<T> = Result<T, Bad>;

/// Little-endian input over the whole file.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    fn left(&self) -> usize {
        self.bytes.len() - self.pos
    }

    fn bad(&self, offset: usize, message: String) -> Bad {
        Bad { offset, message }
    }

    fn take(&mut self, n: usize, what: &str) -> Parse<&'a [u8]> {
        match self.bytes.get(self.pos..self.pos.saturating_add(n)) {
            Some(s) => {
                self.pos += n;
                Ok(s)
            }
            None => Err(self.bad(
                self.pos,
                format!(
                    "the file ends before {what} ({n} bytes needed, {} left)",
                    self.left()
                ),
            )),
        }
    }

    fn array<const N: usize>(&mut self, what: &str) -> Parse<[u8; N]> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(N, what)?);
        Ok(a)
    }

    fn u8(&mut self, what: &str) -> Parse<u8> {
        Ok(self.array::<1>(what)?[0])
    }

    fn flag(&mut self, what: &str) -> Parse<bool> {
        match self.u8(what)? {
            0 => Ok(false),
            1 => Ok(true),
            v => Err(self.bad(self.pos - 1, format!("{what}: expected 0 or 1, found {v}"))),
        }
    }

    fn u32(&mut self, what: &str) -> Parse<u32> {
        Ok(u32::from_le_bytes(self.array(what)?))
    }

    /// A finite real.
    fn f32(&mut self, what: &str) -> Parse<f32> {
        let v = f32::from_le_bytes(self.array(what)?);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.bad(self.pos - 4, format!("{what} is not a finite number ({v})")))
        }
    }

    /// A finite f64 (a model's origin).
    fn f64(&mut self, what: &str) -> Parse<f64> {
        let v = f64::from_le_bytes(self.array(what)?);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.bad(self.pos - 8, format!("{what} is not a finite number ({v})")))
        }
    }

    fn vec3(&mut self, what: &str) -> Parse<Vec3> {
        Ok(Vec3::new(self.f32(what)?, self.f32(what)?, self.f32(what)?))
    }

    fn rgb(&mut self, what: &str) -> Parse<[f32; 3]> {
        Ok([self.f32(what)?, self.f32(what)?, self.f32(what)?])
    }

    fn uv(&mut self, what: &str) -> Parse<[f32; 2]> {
        Ok([self.f32(what)?, self.f32(what)?])
    }

    /// An id below `limit`.
    fn index(&mut self, limit: usize, what: &str) -> Parse<u32> {
        let v = self.u32(what)?;
        if (v as usize) < limit {
            Ok(v)
        } else {
            Err(self.bad(
                self.pos - 4,
                format!("{what} {v} is out of range (expected below {limit})"),
            ))
        }
    }

    fn triangle(&mut self, limit: usize, what: &str) -> Parse<[u32; 3]> {
        Ok([
            self.index(limit, what)?,
            self.index(limit, what)?,
            self.index(limit, what)?,
        ])
    }

    /// A `u32` count of items at least `size` bytes each, which the rest of the file must be
    /// able to hold.
    fn count(&mut self, size: usize, what: &str) -> Parse<usize> {
        let at = self.pos;
        let n = self.u32(what)? as usize;
        self.fits(at, n, size, what)?;
        Ok(n)
    }

    /// Checks that `n` items of at least `size` bytes fit in the rest of the file; `at` is
    /// where their count is (or where they start, when the count is implied).
    fn fits(&self, at: usize, n: usize, size: usize, what: &str) -> Parse<()> {
        if n.saturating_mul(size) <= self.left() {
            return Ok(());
        }
        Err(self.bad(
            at,
            format!(
                "{what} is {n}, but {n} × {size} bytes do not fit in the {} bytes left: the \
                 file is truncated or damaged",
                self.left()
            ),
        ))
    }

    /// `n` items read by `item`, after checking that the rest of the file can hold them.
    fn list<T>(
        &mut self,
        n: usize,
        size: usize,
        what: &str,
        mut item: impl FnMut(&mut Self) -> Parse<T>,
    ) -> Parse<Vec<T>> {
        self.fits(self.pos, n, size, what)?;
        let mut v = Vec::with_capacity(n);
        for _ in 0..n {
            v.push(item(self)?);
        }
        Ok(v)
    }
}

/// The smallest model record: an empty name, no vertices, faces or splits.
const MIN_MODEL_SIZE: usize = 4 + 64 + 12 + 5 + 1 + 1 + 8 + 4;

fn scene(c: &mut Cursor<'_>) -> Parse<ProgressiveScene> {
    if c.bytes.is_empty() {
        return Err(c.bad(0, "the file is empty: not a progressive mesh".into()));
    }
    if c.bytes.get(..MAGIC.len()) != Some(&MAGIC[..]) {
        return Err(c.bad(
            0,
            "not a progressive mesh: the file does not start with \"DECIMPM\\0\"".into(),
        ));
    }
    c.pos = MAGIC.len();
    let version = c.u32("the format version")?;
    if version != VERSION && version != VERSION_ORIGIN {
        return Err(c.bad(
            MAGIC.len(),
            format!(
                "format version {version} is not supported (this decimate reads versions \
                 {VERSION} and {VERSION_ORIGIN})"
            ),
        ));
    }
    let n = c.count(MIN_MODEL_SIZE, "the model count")?;
    let mut models = Vec::with_capacity(n);
    for i in 0..n {
        let m = model(c, version == VERSION_ORIGIN).map_err(|e| Bad {
            message: format!("model {i}: {}", e.message),
            ..e
        })?;
        models.push(m);
    }
    match c.left() {
        0 => Ok(ProgressiveScene { models }),
        1 => Err(c.bad(c.pos, "1 byte after the last model".into())),
        n => Err(c.bad(c.pos, format!("{n} bytes after the last model"))),
    }
}

fn model(c: &mut Cursor<'_>, with_origin: bool) -> Parse<ProgressiveModel> {
    let start = c.pos;
    let (mut base, a, vertices, faces) = header(c, with_origin)?;
    read_base(c, &mut base, a, vertices, faces)?;
    let splits = read_splits(c, a, vertices, faces)?;
    let vertex_ids = c.list(vertices + splits.len(), 4, "vertex ids", |c| {
        c.u32("a vertex id")
    })?;
    let all_faces = faces + splits.iter().map(|s| s.added.len()).sum::<usize>();
    let face_ids = c.list(all_faces, 4, "face ids", |c| c.u32("a face id"))?;
    let pm = ProgressiveModel {
        base,
        splits,
        vertex_ids,
        face_ids,
    };
    pm.validate().map_err(|e| c.bad(start, e))?;
    Ok(pm)
}

/// The model's name, transform and material, its attribute flags and base counts.
fn header(c: &mut Cursor<'_>, with_origin: bool) -> Parse<(Model, Attributes, usize, usize)> {
    let name_len = c.count(1, "the name length")?;
    let at = c.pos;
    let name = std::str::from_utf8(c.take(name_len, "the name")?)
        .map_err(|e| c.bad(at, format!("the name is not UTF-8 ({e})")))?
        .to_string();
    let mut transform = [0f32; 16];
    for v in &mut transform {
        *v = c.f32("the transform")?;
    }
    let mut origin = [0f64; 3];
    if with_origin {
        for v in &mut origin {
            *v = c.f64("the origin")?;
        }
    }
    let diffuse = c.rgb("the diffuse colour")?;
    let creased = c.flag("the crease flag")?;
    let crease = c.f32("the crease angle")?;
    let solid = c.flag("the solid flag")?;
    let at = c.pos;
    let bits = c.u8("the attribute flags")?;
    let a = Attributes::from_bits(bits).ok_or_else(|| {
        c.bad(
            at,
            format!("attribute flags {bits:#04x}: expected bits 0, 1 (not both) and 2 to 7 only, 6 and 7 with 4"),
        )
    })?;
    let mut text = |what: &str| -> Parse<String> {
        let len = c.count(1, &format!("the {what} length"))?;
        let at = c.pos;
        let bytes = c.take(len, &format!("the {what}"))?;
        match std::str::from_utf8(bytes) {
            Ok(s) => Ok(s.to_string()),
            Err(e) => Err(c.bad(at, format!("the {what} is not UTF-8 ({e})"))),
        }
    };
    let texture = a
        .texture_image
        .then(|| text("texture image name"))
        .transpose()?;
    let material = a.material_name.then(|| text("material name")).transpose()?;
    let vertices = c.count(a.vertex_size(), "the base vertex count")?;
    let faces = c.count(a.face_size(), "the base face count")?;
    let model = Model {
        name,
        transform: Mat4::from_cols_array(&transform),
        origin: glam::DVec3::from(origin),
        diffuse,
        crease_angle: creased.then_some(crease),
        solid,
        texture,
        texture_repeat: a.clamp.map(|c| !c),
        material,
        ..Model::default()
    };
    Ok((model, a, vertices, faces))
}

fn read_base(
    c: &mut Cursor<'_>,
    m: &mut Model,
    a: Attributes,
    vertices: usize,
    faces: usize,
) -> Parse<()> {
    m.positions = c.list(vertices, 12, "positions", |c| c.vec3("a position"))?;
    if a.vertex_colors {
        let colors = c.list(vertices, 12, "vertex colours", |c| c.rgb("a colour"))?;
        m.colors = Some(Attribute::PerVertex(colors));
    }
    if a.normals {
        let normals = c.list(vertices, 12, "normals", |c| c.vec3("a normal"))?;
        m.normals = Some(Attribute::PerVertex(normals));
    }
    if a.texcoords {
        let texcoords = c.list(vertices, 8, "texture coordinates", |c| {
            c.uv("a texture coordinate")
        })?;
        m.texcoords = Some(texcoords);
    }
    m.triangles = c.list(faces, 12, "triangles", |c| {
        c.triangle(vertices, "a base face's vertex")
    })?;
    if a.face_colors {
        let colors = c.list(faces, 12, "face colours", |c| c.rgb("a face colour"))?;
        m.colors = Some(Attribute::PerFace(colors));
    }
    Ok(())
}

fn read_splits(
    c: &mut Cursor<'_>,
    a: Attributes,
    vertices: usize,
    faces: usize,
) -> Parse<Vec<VertexSplit>> {
    let n = c.count(a.split_size(), "the split count")?;
    let mut splits = Vec::with_capacity(n);
    let mut faces = faces;
    for i in 0..n {
        let s = split(c, a, vertices + i, faces).map_err(|e| Bad {
            message: format!("split {i}: {}", e.message),
            ..e
        })?;
        faces += s.added.len();
        splits.push(s);
    }
    Ok(splits)
}

/// Split adding vertex `new`, when `faces` faces exist.
fn split(c: &mut Cursor<'_>, a: Attributes, new: usize, faces: usize) -> Parse<VertexSplit> {
    let keep = c.index(new, "the vertex that splits")?;
    let keep_coarse = c.vec3("a position")?;
    let keep_fine = c.vec3("a position")?;
    let position = c.vec3("a position")?;
    let colors = if a.vertex_colors {
        Some([c.rgb("a colour")?, c.rgb("a colour")?, c.rgb("a colour")?])
    } else {
        None
    };
    let normals = if a.normals {
        Some([
            c.vec3("a normal")?,
            c.vec3("a normal")?,
            c.vec3("a normal")?,
        ])
    } else {
        None
    };
    let texcoords = if a.texcoords {
        let what = "a texture coordinate";
        Some([c.uv(what)?, c.uv(what)?, c.uv(what)?])
    } else {
        None
    };
    let renamed = c.count(4, "the renamed face count")?;
    let renamed = c.list(renamed, 4, "renamed faces", |c| {
        c.index(faces, "a renamed face")
    })?;
    let added = c.u8("the added face count")? as usize;
    let added_faces = c.list(added, 12, "added faces", |c| {
        c.triangle(new + 1, "an added face's vertex")
    })?;
    let added_colors = if a.face_colors {
        c.list(added, 12, "added face colours", |c| c.rgb("a face colour"))?
    } else {
        Vec::new()
    };
    Ok(VertexSplit {
        keep,
        keep_coarse,
        keep_fine,
        position,
        colors,
        normals,
        texcoords,
        renamed,
        added: added_faces,
        added_colors,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decimate::{simplify_scene_progressive, Algorithm, Params, Target};
    use crate::mesh::{shapes, Scene};

    fn progressive(models: Vec<Model>) -> ProgressiveScene {
        let mut scene = Scene { models };
        let params = Params {
            target: Target::RemovePercent(90.0),
            algorithm: Algorithm::Qem,
            ..Params::default()
        };
        simplify_scene_progressive(&mut scene, &params, &mut |_| {}).1
    }

    fn bytes(pm: &ProgressiveScene) -> Vec<u8> {
        let mut b = Vec::new();
        write_progressive_to(&mut b, pm).unwrap_or_else(|e| panic!("write: {e}"));
        b
    }

    fn parse(b: &[u8]) -> Result<ProgressiveScene, ReadError> {
        parse_progressive(b, Path::new("t.pm"))
    }

    #[test]
    fn bytes_read_back_equal_with_every_attribute() {
        let mut colored = shapes::uv_sphere(8, 12);
        let n = colored.positions.len();
        colored.colors = Some(Attribute::PerVertex(vec![[0.25, 0.5, 1.0]; n]));
        colored.normals = Some(Attribute::PerVertex(vec![Vec3::Y; n]));
        colored.crease_angle = Some(0.5);
        colored.solid = true;
        let mut faced = shapes::cube(3, 1.0);
        faced.name = "façade".into();
        let f = faced.triangles.len();
        faced.colors = Some(Attribute::PerFace(
            (0..f).map(|i| [i as f32 / f as f32, 0.0, 1.0]).collect(),
        ));
        faced.transform = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0));
        let pm = progressive(vec![colored, faced]);
        assert_eq!(pm.models.len(), 2);
        let b = bytes(&pm);
        assert_eq!(&b[..8], b"DECIMPM\0");
        assert_eq!(parse(&b).unwrap_or_else(|e| panic!("{e}")), pm);
    }

    #[test]
    fn a_far_origin_is_written_in_version_2_and_read_back_whole() {
        let near = progressive(vec![shapes::uv_sphere(8, 12)]);
        assert_eq!(bytes(&near)[8..12], VERSION.to_le_bytes());
        let mut far = shapes::uv_sphere(8, 12);
        far.origin = glam::DVec3::new(300000.0, 1200000.0, 51.0);
        let pm = progressive(vec![far]);
        assert_eq!(
            pm.models[0].base.origin,
            glam::DVec3::new(300000.0, 1200000.0, 51.0)
        );
        let b = bytes(&pm);
        assert_eq!(b[8..12], VERSION_ORIGIN.to_le_bytes());
        assert_eq!(parse(&b).unwrap_or_else(|e| panic!("{e}")), pm);
    }

    /// `m` with texture coordinates from its positions (no two vertices alike).
    fn textured(mut m: Model) -> Model {
        m.texcoords = Some(m.positions.iter().map(|p| [p.x + 0.5 * p.z, p.y]).collect());
        m
    }

    #[test]
    fn texture_coordinates_read_back_equal_and_a_cut_through_them_is_named() {
        let pm = progressive(vec![textured(shapes::uv_sphere(8, 12))]);
        let m = &pm.models[0];
        assert!(m.base.texcoords.is_some());
        let b = bytes(&pm);
        // The attribute byte, after the magic, version, model count, name and material.
        let header = 16 + 4 + m.base.name.len() + 64 + 12 + 5 + 1;
        assert_eq!(b[header], 8, "bit 3, texture coordinates, only");
        assert_eq!(parse(&b).unwrap_or_else(|e| panic!("{e}")), pm);
        // Cut in the middle of the last split's coordinates.
        let (v, f) = (m.base.positions.len(), m.base.triangles.len());
        let split =
            |s: &VertexSplit| 4 + 36 + 24 + 4 + 4 * s.renamed.len() + 1 + 12 * s.added.len();
        let earlier = &m.splits[..m.splits.len().saturating_sub(1)];
        let at = header + 1 + 8 + 20 * v + 12 * f + 4 + earlier.iter().map(split).sum::<usize>();
        let e = parse(&b[..at + 40 + 12]).err().map(|e| e.to_string());
        let expected = format!(
            "split {}: the file ends before a texture coordinate (4 bytes needed, 0 left)",
            earlier.len()
        );
        assert!(e.as_ref().is_some_and(|e| e.contains(&expected)), "{e:?}");
    }

    #[test]
    fn the_texture_image_and_material_names_read_back_after_the_attribute_byte() {
        let mut m = textured(shapes::uv_sphere(6, 8));
        m.texture = Some("maps/scan ü.png".into());
        m.material = Some("skin".into());
        let pm = progressive(vec![m]);
        let b = bytes(&pm);
        let header = 16 + 4 + pm.models[0].base.name.len() + 64 + 12 + 5 + 1;
        assert_eq!(b[header], 8 | 16 | 32, "bits 3, 4 and 5");
        let len = "maps/scan ü.png".len();
        assert_eq!(&b[header + 1..header + 5], &(len as u32).to_le_bytes());
        let image = header + 5;
        assert_eq!(&b[image..image + len], "maps/scan ü.png".as_bytes());
        let material = image + len;
        assert_eq!(&b[material..material + 4], &4u32.to_le_bytes());
        assert_eq!(&b[material + 4..material + 8], b"skin");
        let back = parse(&b).unwrap_or_else(|e| panic!("{e}"));
        let base = &back.models[0].base;
        assert_eq!(base.texture.as_deref(), Some("maps/scan ü.png"));
        assert_eq!(base.material.as_deref(), Some("skin"));
        assert_eq!(back, pm);
        for (at, what) in [
            (image, "texture image name"),
            (material + 4, "material name"),
        ] {
            let mut bad = b.clone();
            bad[at] = 0xff;
            let e = parse(&bad).err().map(|e| e.to_string());
            let expected = format!("the {what} is not UTF-8");
            assert!(e.as_ref().is_some_and(|e| e.contains(&expected)), "{e:?}");
        }
    }

    #[test]
    fn a_clamped_texture_reads_back_clamped_and_clamp_bits_need_an_image() {
        let mut m = textured(shapes::uv_sphere(6, 8));
        m.texture = Some("decal.png".into());
        m.texture_repeat = [false, true];
        let pm = progressive(vec![m]);
        let b = bytes(&pm);
        let header = 16 + 4 + pm.models[0].base.name.len() + 64 + 12 + 5 + 1;
        assert_eq!(b[header], 8 | 16 | 64, "bits 3, 4 and 6");
        let back = parse(&b).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back.models[0].base.texture_repeat, [false, true]);
        assert_eq!(back, pm);
        // Clamping with no image named: refused at the attribute byte.
        let mut plain = textured(shapes::uv_sphere(6, 8));
        plain.texture = None;
        let mut b = bytes(&progressive(vec![plain]));
        b[header] |= 128;
        let e = parse(&b).err().map(|e| e.to_string());
        assert!(
            e.as_ref().is_some_and(|e| e.contains("6 and 7 with 4")),
            "{e:?}"
        );
    }

    #[test]
    fn every_prefix_and_every_flipped_byte_is_handled() {
        let mut named = textured(shapes::cube(2, 1.0));
        named.texture = Some("t.png".into());
        named.material = Some("m".into());
        for model in [shapes::cube(2, 1.0), textured(shapes::cube(2, 1.0)), named] {
            let pm = progressive(vec![model]);
            let b = bytes(&pm);
            for len in 0..b.len() {
                let e = parse(&b[..len]).err();
                assert!(e.is_some(), "a file cut to {len} bytes was read");
            }
            for i in 0..b.len() {
                let mut bad = b.clone();
                bad[i] ^= 0x5a;
                // Either read (an id or position changed) or refused: never a panic.
                if let Ok(read) = parse(&bad) {
                    assert!(read.models.iter().all(|m| m.validate().is_ok()));
                }
            }
        }
    }

    #[test]
    fn per_face_normals_are_refused_by_the_writer() {
        let mut pm = progressive(vec![shapes::cube(2, 1.0)]);
        let f = pm.models[0].base.triangles.len();
        pm.models[0].base.normals = Some(Attribute::PerFace(vec![Vec3::Z; f]));
        let mut b = Vec::new();
        let e = write_progressive_to(&mut b, &pm).err();
        assert!(e.is_some_and(|e| e.to_string().contains("normals")));
        assert!(b.is_empty());
    }
}

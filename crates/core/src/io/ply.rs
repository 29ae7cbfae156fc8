//! PLY (Stanford polygon format): a reader for ASCII and binary (little / big endian) files and
//! a binary little-endian writer.
//!
//! Read: `element vertex` with `x y z` (float or double, any other properties skipped),
//! optional `red green blue` (uchar, becoming per-vertex colours) and optional texture
//! coordinates as one of the pairs `s t` (Blender), `u v`, `texture_u texture_v` (MeshLab),
//! `texture_s texture_t` (any numeric type; half a pair is skipped with a warning),
//! `element face` with a `vertex_indices` / `vertex_index` list (any integer count and index
//! types) and optionally MeshLab's per-corner `texcoord` list (`u v` per corner, taking the
//! place of per-vertex ones; a point with different ones in different faces becomes one
//! vertex per seam side); polygons are triangulated like VRML faces. Other elements are
//! skipped. The result is one model. A `comment TextureFile NAME` header line (MeshLab's
//! convention) names the image the coordinates map.
//! Write: one binary little-endian file of all models, transforms baked in, with per-vertex
//! colours (`red green blue`) and texture coordinates (`s t`) when every model has them, and
//! `comment TextureFile NAME` when they all map the same image.

use crate::io::warning::{Warning, WarningKind};
use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

use glam::{Mat4, Vec3};

use super::origin::{self, Recentre};
use super::shape_to_model::{build, Bind, ShapeSpec, TexCoords};
use super::source::Input;
use super::text::{PResult, ParseError};
use super::WriteError;
use crate::mesh::{Attribute, Scene};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Ascii,
    Little,
    Big,
}

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Ty {
    fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "char" | "int8" => Self::I8,
            "uchar" | "uint8" => Self::U8,
            "short" | "int16" => Self::I16,
            "ushort" | "uint16" => Self::U16,
            "int" | "int32" => Self::I32,
            "uint" | "uint32" => Self::U32,
            "float" | "float32" => Self::F32,
            "double" | "float64" => Self::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }
}

#[derive(Debug)]
struct Property {
    name: String,
    ty: Ty,
    /// For list properties, the type of the count.
    list: Option<Ty>,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: usize,
    props: Vec<Property>,
    line: usize,
}

/// The vertex property pairs that hold texture coordinates, as tools write them.
const UV_NAMES: [[&str; 2]; 4] = [
    ["s", "t"],
    ["u", "v"],
    ["texture_u", "texture_v"],
    ["texture_s", "texture_t"],
];

/// Reads scalar values in one of the three encodings, from a file in memory or streamed.
struct Body<I> {
    format: Format,
    input: I,
    pos: usize,
    /// Current line (ASCII) for messages.
    line: usize,
    /// The element being read, its record and its count, for messages.
    element: String,
    record: usize,
    records: usize,
}

impl<I: Input> Body<I> {
    fn new(format: Format, input: I, pos: usize, line: usize) -> Self {
        Self {
            format,
            input,
            pos,
            line,
            element: String::new(),
            record: 0,
            records: 0,
        }
    }

    /// Starts reading element `el`'s records.
    fn start(&mut self, el: &Element) {
        self.element.clone_from(&el.name);
        self.record = 0;
        self.records = el.count;
    }

    fn eof(&self, what: &str) -> ParseError {
        ParseError::new(
            self.line,
            format!(
                "unexpected end of file: the PLY body ends inside {} {} of {} (expected {what})",
                self.element, self.record, self.records
            ),
        )
    }

    /// More bytes from the input, keeping those from `keep` on; false at the end.
    fn more(&mut self, keep: usize) -> PResult<Option<usize>> {
        self.input
            .more(keep)
            .map_err(|e| ParseError::new(self.line, format!("the file could not be read: {e}")))
    }

    /// Makes `n` bytes from the position available, or fails naming `what`.
    fn ensure(&mut self, n: usize, what: &str) -> PResult<()> {
        while self.pos + n > self.input.bytes().len() {
            match self.more(self.pos)? {
                Some(dropped) => self.pos -= dropped,
                None => return Err(self.eof(what)),
            }
        }
        Ok(())
    }

    /// The next whitespace-separated token, as a range of `input.bytes()`.
    fn token(&mut self, what: &str) -> PResult<std::ops::Range<usize>> {
        loop {
            let b = self.input.bytes();
            while self.pos < b.len() && b[self.pos].is_ascii_whitespace() {
                if b[self.pos] == b'\n' {
                    self.line += 1;
                }
                self.pos += 1;
            }
            if self.pos < b.len() {
                break;
            }
            match self.more(self.pos)? {
                Some(dropped) => self.pos -= dropped,
                None => return Err(self.eof(what)),
            }
        }
        let mut start = self.pos;
        loop {
            let b = self.input.bytes();
            while self.pos < b.len() && !b[self.pos].is_ascii_whitespace() {
                self.pos += 1;
            }
            if self.pos < b.len() {
                break;
            }
            match self.more(start)? {
                Some(dropped) => {
                    self.pos -= dropped;
                    start -= dropped;
                }
                None => break,
            }
        }
        Ok(start..self.pos)
    }

    fn raw<const N: usize>(&mut self, what: &str) -> PResult<[u8; N]> {
        self.ensure(N, what)?;
        let mut a = [0u8; N];
        a.copy_from_slice(&self.input.bytes()[self.pos..self.pos + N]);
        self.pos += N;
        if self.format == Format::Big {
            a.reverse();
        }
        Ok(a)
    }

    /// One value as f64 (exact for every PLY integer type).
    fn value(&mut self, ty: Ty, what: &str) -> PResult<f64> {
        if self.format == Format::Ascii {
            let t = self.token(what)?;
            return self.ascii_value(&self.input.bytes()[t], what);
        }
        Ok(match ty {
            Ty::I8 => i8::from_le_bytes(self.raw::<1>(what)?) as f64,
            Ty::U8 => self.raw::<1>(what)?[0] as f64,
            Ty::I16 => i16::from_le_bytes(self.raw::<2>(what)?) as f64,
            Ty::U16 => u16::from_le_bytes(self.raw::<2>(what)?) as f64,
            Ty::I32 => i32::from_le_bytes(self.raw::<4>(what)?) as f64,
            Ty::U32 => u32::from_le_bytes(self.raw::<4>(what)?) as f64,
            Ty::F32 => f32::from_le_bytes(self.raw::<4>(what)?) as f64,
            Ty::F64 => f64::from_le_bytes(self.raw::<8>(what)?),
        })
    }

    /// The ASCII token `t` as a number.
    fn ascii_value(&self, t: &[u8], what: &str) -> PResult<f64> {
        let s = std::str::from_utf8(t).unwrap_or("?");
        s.parse::<f64>().map_err(|_| {
            ParseError::new(
                self.line,
                format!("expected a number for {what}, found '{s}'"),
            )
        })
    }

    /// An index or count: a non-negative integer.
    fn index(&mut self, ty: Ty, what: &str) -> PResult<u32> {
        let v = if self.format == Format::Ascii {
            let r = self.token(what)?;
            let t = &self.input.bytes()[r];
            // Nearly every index and count is plain decimal digits: read them without a
            // float parse (nine digits cannot overflow).
            if t.len() <= 9 && t.iter().all(u8::is_ascii_digit) {
                return Ok(t.iter().fold(0, |n, &d| 10 * n + u32::from(d - b'0')));
            }
            self.ascii_value(t, what)?
        } else {
            self.value(ty, what)?
        };
        if v >= 0.0 && v <= u32::MAX as f64 && v.fract() == 0.0 {
            Ok(v as u32)
        } else {
            Err(ParseError::new(
                self.line,
                format!("expected a non-negative integer for {what}, found {v}"),
            ))
        }
    }

    /// Bytes left after the last element read (whitespace does not count in ASCII).
    fn trailing(&self) -> usize {
        let rest = &self.input.bytes()[self.pos.min(self.input.bytes().len())..];
        match self.format {
            Format::Ascii => rest.iter().filter(|b| !b.is_ascii_whitespace()).count(),
            _ => rest.len(),
        }
    }

    fn skip(&mut self, ty: Ty, what: &str) -> PResult<()> {
        if self.format == Format::Ascii {
            self.token(what)?;
        } else {
            self.ensure(ty.size(), what)?;
            self.pos += ty.size();
        }
        Ok(())
    }
}

/// What a PLY header says.
struct Header {
    format: Format,
    elements: Vec<Element>,
    /// Offset of the body's first byte.
    body_start: usize,
    /// Lines the header takes.
    lines: usize,
    /// The image named by the first `comment TextureFile NAME` (MeshLab's convention).
    texture: Option<String>,
}

/// The body's encoding a `format` line names.
fn parse_format(name: &str, line: usize) -> PResult<Format> {
    Ok(match name {
        "ascii" => Format::Ascii,
        "binary_little_endian" => Format::Little,
        "binary_big_endian" => Format::Big,
        other => {
            return Err(ParseError::new(
                line,
                format!("unknown PLY format '{other}'"),
            ))
        }
    })
}

/// Adds a `property` line's property to the last element declared.
fn add_property(
    elements: &mut [Element],
    name: &str,
    ty: Ty,
    list: Option<Ty>,
    line: usize,
) -> PResult<()> {
    let el = elements
        .last_mut()
        .ok_or_else(|| ParseError::new(line, "'property' before any 'element'"))?;
    el.props.push(Property {
        name: name.to_string(),
        ty,
        list,
    });
    Ok(())
}

/// Reads the header, line by line up to `end_header`.
fn parse_header(bytes: &[u8]) -> PResult<Header> {
    let mut pos = 0;
    let mut line = 0;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut texture = None;
    loop {
        line += 1;
        let end = bytes[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|e| pos + e)
            .ok_or_else(|| {
                ParseError::new(
                    line,
                    "unexpected end of file: the PLY header has no 'end_header'",
                )
            })?;
        let text = String::from_utf8_lossy(&bytes[pos..end]);
        pos = end + 1;
        let words: Vec<&str> = text.split_ascii_whitespace().collect();
        match words.as_slice() {
            ["ply"] if line == 1 => {}
            _ if line == 1 => return Err(ParseError::new(1, "expected 'ply' on the first line")),
            ["format", f, _] => format = Some(parse_format(f, line)?),
            ["comment", "TextureFile", _, ..] if texture.is_none() => {
                // The name is the rest of the line: it may hold spaces.
                let rest = text.trim_start()["comment".len()..].trim_start();
                texture = Some(rest["TextureFile".len()..].trim().to_string());
            }
            ["comment", ..] | ["obj_info", ..] | [] => {}
            ["element", name, count] => elements.push(Element {
                name: name.to_string(),
                count: count.parse().map_err(|_| {
                    ParseError::new(line, format!("expected an element count, found '{count}'"))
                })?,
                props: Vec::new(),
                line,
            }),
            ["property", "list", ct, it, name] => {
                let (Some(ct), Some(it)) = (Ty::parse(ct), Ty::parse(it)) else {
                    return Err(ParseError::new(
                        line,
                        format!("unknown PLY type in '{text}'"),
                    ));
                };
                add_property(&mut elements, name, it, Some(ct), line)?;
            }
            ["property", ty, name] => {
                let ty = Ty::parse(ty)
                    .ok_or_else(|| ParseError::new(line, format!("unknown PLY type '{ty}'")))?;
                add_property(&mut elements, name, ty, None, line)?;
            }
            ["end_header"] => break,
            _ => {
                return Err(ParseError::new(
                    line,
                    format!("unexpected PLY header line '{text}'"),
                ))
            }
        }
    }
    let format =
        format.ok_or_else(|| ParseError::new(line, "the PLY header has no 'format' line"))?;
    Ok(Header {
        format,
        elements,
        body_start: pos,
        lines: line,
        texture,
    })
}

/// What a PLY body holds, gathered element by element before the model is built.
#[derive(Default)]
struct Gathered {
    coords: Vec<f32>,
    rgb: Vec<f32>,
    nxyz: Vec<f32>,
    uv: Vec<f32>,
    /// MeshLab's per-corner `texcoord` lists, flat (u v); `None` once a face's list does not
    /// match its corners.
    corner_uv: Option<Vec<f32>>,
    /// Per-face colours, flat (r g b in 0..1), when the face element has them.
    face_rgb: Vec<f32>,
    corners: Vec<u32>,
    ends: Vec<u32>,
    /// The face element's header line, for errors about its indices.
    face_line: usize,
    /// Streaming: positions only (no colours, normals or texture coordinates), and no room
    /// reserved for faces, which are handed on one by one.
    positions_only: bool,
    /// The model's origin, picked from its first vertex.
    recentre: Recentre,
}

/// Called after each face is read, with the positions, the corners and the face ends so far.
type FaceHook<'a> = dyn FnMut(&[f32], &mut Vec<u32>, &mut Vec<u32>) -> Result<(), String> + 'a;

/// Reads a PLY file into a scene of one model: header, then each element (vertices, faces,
/// others skipped), then the model built from what they held.
pub fn read_ply(bytes: &[u8]) -> PResult<(Scene, Vec<Warning>)> {
    let Header {
        format,
        elements,
        body_start,
        lines: header_lines,
        texture,
    } = parse_header(bytes)?;
    let mut body = Body::new(format, &bytes[body_start..], 0, header_lines + 1);
    let mut warnings = Vec::new();
    let mut data = Gathered {
        face_line: header_lines,
        ..Gathered::default()
    };
    for el in &elements {
        match el.name.as_str() {
            "vertex" => read_vertices(el, &mut body, bytes.len(), &mut data, &mut warnings)?,
            "face" => {
                let keep = &mut |_: &[f32], _: &mut Vec<u32>, _: &mut Vec<u32>| Ok(());
                read_faces(el, &mut body, bytes.len(), &mut data, &mut warnings, keep)?
            }
            _ => skip_element(el, &mut body)?,
        }
    }
    let extra = body.trailing();
    if extra > 0 {
        warnings.push(
            Warning::new(
                WarningKind::SkippedFaces,
                format!(
                    "the PLY body has {extra} more bytes after the elements its header counts \
                     (faces beyond the header's count?); they were ignored"
                ),
            )
            .at(body.line),
        );
    }
    finish(data, texture, warnings)
}

/// Most bytes a PLY header may take: a file with no `end_header` in its first 16 MiB is not
/// a PLY file a tool wrote.
const MAX_HEADER: usize = 16 << 20;

/// Reads the header from a streamed input, reading more until `end_header` comes.
fn stream_header(input: &mut impl Input) -> PResult<Header> {
    loop {
        let err = match parse_header(input.bytes()) {
            Ok(h) => return Ok(h),
            Err(e) => e,
        };
        let short = err.message.starts_with("unexpected end of file");
        if !short || input.bytes().len() > MAX_HEADER {
            return Err(err);
        }
        let more = input
            .more(0)
            .map_err(|e| ParseError::new(err.line, format!("the file could not be read: {e}")))?;
        if more.is_none() {
            return Err(err);
        }
    }
}

/// Tiling's read: hands each triangle of a PLY file (polygons fanned from their first
/// corner) to `triangle` as its face is read, holding only the vertex positions. The header,
/// value decoding and element reading are the ordinary reader's; `file_len` bounds the
/// counts the header announces.
pub(super) fn stream_ply(
    mut input: impl Input,
    file_len: usize,
    recentre: &mut Recentre,
    triangle: &mut dyn FnMut([[f32; 3]; 3]),
) -> PResult<()> {
    let header = stream_header(&mut input)?;
    let mut body = Body::new(header.format, input, header.body_start, header.lines + 1);
    let mut data = Gathered {
        face_line: header.lines,
        positions_only: true,
        recentre: *recentre,
        ..Gathered::default()
    };
    let mut unused = Vec::new();
    let fan = &mut |coords: &[f32], corners: &mut Vec<u32>, ends: &mut Vec<u32>| {
        fan_face(coords, corners, triangle)?;
        corners.clear();
        ends.clear();
        Ok(())
    };
    for el in &header.elements {
        match el.name.as_str() {
            "vertex" => read_vertices(el, &mut body, file_len, &mut data, &mut unused)?,
            "face" => read_faces(el, &mut body, file_len, &mut data, &mut unused, fan)?,
            _ => skip_element(el, &mut body)?,
        }
    }
    *recentre = data.recentre;
    Ok(())
}

/// Fans one face (`corners`, vertex indices) into triangles from its first corner.
fn fan_face(
    coords: &[f32],
    corners: &[u32],
    triangle: &mut dyn FnMut([[f32; 3]; 3]),
) -> Result<(), String> {
    let n = coords.len() / 3;
    let at = |v: u32| {
        let i = v as usize;
        coords
            .get(3 * i..3 * i + 3)
            .filter(|_| i < n)
            .map(|p| [p[0], p[1], p[2]])
            .ok_or_else(|| format!("vertex index {v} is out of range (the file has {n} vertices)"))
    };
    if corners.len() < 3 {
        return Ok(());
    }
    let first = at(corners[0])?;
    for w in corners[1..].windows(2) {
        triangle([first, at(w[0])?, at(w[1])?]);
    }
    Ok(())
}

/// Where the vertex element's properties are: position, and colour, normal and texture
/// coordinates when it has them all.
struct VertexSlots {
    position: [usize; 3],
    color: Option<[usize; 3]>,
    normal: Option<[usize; 3]>,
    texture: Option<[usize; 2]>,
}

/// The vertex element's layout; a texture coordinate without its partner is warned about.
fn vertex_slots(el: &Element, warnings: &mut Vec<Warning>) -> PResult<VertexSlots> {
    let slot = |n: &str| {
        el.props
            .iter()
            .position(|p| p.name == n && p.list.is_none())
    };
    let (Some(x), Some(y), Some(z)) = (slot("x"), slot("y"), slot("z")) else {
        return Err(ParseError::new(
            el.line,
            "the vertex element has no x, y, z properties",
        ));
    };
    let color = match (slot("red"), slot("green"), slot("blue")) {
        (Some(r), Some(g), Some(b)) => Some([r, g, b]),
        _ => None,
    };
    let normal = match (slot("nx"), slot("ny"), slot("nz")) {
        (Some(a), Some(b), Some(c)) => Some([a, b, c]),
        _ => None,
    };
    let texture = UV_NAMES
        .iter()
        .find_map(|[u, v]| Some([slot(u)?, slot(v)?]));
    if texture.is_none() {
        for [u, v] in UV_NAMES {
            if let (Some(_), None) | (None, Some(_)) = (slot(u), slot(v)) {
                let (has, lacks) = if slot(u).is_some() { (u, v) } else { (v, u) };
                warnings.push(
                    Warning::new(
                        WarningKind::SkippedAttribute,
                        format!(
                            "the vertex element has '{has}' but no '{lacks}'; \
                             texture coordinates skipped"
                        ),
                    )
                    .at(el.line),
                );
            }
        }
    }
    Ok(VertexSlots {
        position: [x, y, z],
        color,
        normal,
        texture,
    })
}

/// Reads the vertex element: finite positions, and the colours, normals and texture
/// coordinates its layout has. `file_len` bounds the count the header announces.
fn read_vertices(
    el: &Element,
    body: &mut Body<impl Input>,
    file_len: usize,
    data: &mut Gathered,
    warnings: &mut Vec<Warning>,
) -> PResult<()> {
    body.start(el);
    let mut slots = vertex_slots(el, warnings)?;
    if data.positions_only {
        (slots.color, slots.normal, slots.texture) = (None, None, None);
    }
    let VertexSlots {
        position: [x, y, z],
        color,
        normal,
        texture,
    } = slots;
    if el.count > file_len {
        return Err(body.eof("all the vertices the header announces"));
    }
    data.coords.reserve(el.count * 3);
    let mut vals = vec![0f64; el.props.len()];
    for i in 0..el.count {
        body.record = i;
        for (k, p) in el.props.iter().enumerate() {
            if let Some(ct) = p.list {
                let n = body.index(ct, "a vertex list count")?;
                for _ in 0..n {
                    body.skip(p.ty, "a vertex list value")?;
                }
            } else {
                vals[k] = body.value(p.ty, "a vertex")?;
            }
        }
        let [px, py, pz] = data.recentre.relative([vals[x], vals[y], vals[z]]);
        if !(px.is_finite() && py.is_finite() && pz.is_finite()) {
            return Err(ParseError::new(
                body.line,
                format!(
                    "vertex {} is not finite ({px} {py} {pz})",
                    data.coords.len() / 3
                ),
            ));
        }
        data.coords.extend([px, py, pz]);
        // Colours and normals are numbers too: an infinite one would reach the renderer and
        // every writer (texture coordinates that are not finite are skipped later, with a warning).
        let mut used = color.iter().flatten().chain(normal.iter().flatten());
        if let Some(&k) = used.find(|&&k| !(vals[k] as f32).is_finite()) {
            return Err(ParseError::new(
                body.line,
                format!(
                    "vertex {}'s {} is not a finite number ({})",
                    data.coords.len() / 3 - 1,
                    el.props[k].name,
                    vals[k] as f32
                ),
            ));
        }
        if let Some(c) = color {
            let scale = if el.props[c[0]].ty == Ty::U8 {
                1.0 / 255.0
            } else {
                1.0
            };
            data.rgb.extend(c.map(|i| vals[i] as f32 * scale));
        }
        if let Some(n) = normal {
            data.nxyz.extend(n.map(|i| vals[i] as f32));
        }
        if let Some(t) = texture {
            data.uv.extend(t.map(|i| vals[i] as f32));
        }
    }
    Ok(())
}

/// Reads the face element: each face's corners, and its `texcoord` list when it has one
/// (dropped, with a warning, at the first face whose list does not match its corners).
fn read_faces(
    el: &Element,
    body: &mut Body<impl Input>,
    file_len: usize,
    data: &mut Gathered,
    warnings: &mut Vec<Warning>,
    each_face: &mut FaceHook<'_>,
) -> PResult<()> {
    data.face_line = el.line;
    body.start(el);
    let list = el.props.iter().position(|p| {
        p.list.is_some() && matches!(p.name.as_str(), "vertex_indices" | "vertex_index")
    });
    let Some(list) = list else {
        return Err(ParseError::new(
            el.line,
            "the face element has no vertex_indices list",
        ));
    };
    let texture = el
        .props
        .iter()
        .position(|p| p.list.is_some() && p.name == "texcoord");
    if texture.is_some() {
        data.corner_uv = Some(Vec::new());
    }
    let color = (!data.positions_only)
        .then(|| face_color_slots(el))
        .flatten();
    if el.count > file_len {
        return Err(body.eof("all the faces the header announces"));
    }
    let Gathered {
        coords,
        corners,
        ends,
        corner_uv,
        face_rgb,
        positions_only,
        ..
    } = data;
    if !*positions_only {
        corners.reserve(el.count * 3);
        ends.reserve(el.count);
    }
    for f in 0..el.count {
        body.record = f;
        let first = corners.len();
        let lists = [Some(list), texture];
        let values = read_face(el, body, lists, color, corners, corner_uv, face_rgb)?;
        if corner_uv.is_some() && values != 2 * (corners.len() - first) {
            warnings.push(
                Warning::new(
                    WarningKind::SkippedAttribute,
                    format!(
                        "face {f} has {values} 'texcoord' values for {} corners \
                         (expected u v per corner); texture coordinates skipped",
                        corners.len() - first
                    ),
                )
                .at(body.line),
            );
            *corner_uv = None;
        }
        ends.push(corners.len() as u32);
        each_face(coords, corners, ends)
            .map_err(|m| ParseError::new(body.line, format!("face {f}: {m}")))?;
    }
    Ok(())
}

/// The face element's red, green and blue properties and the scale that takes them to
/// 0..1 (bytes are 0..255), when it has all three.
fn face_color_slots(el: &Element) -> Option<([usize; 3], f32)> {
    let slot = |n: &str| (el.props.iter()).position(|p| p.name == n && p.list.is_none());
    let slots = [slot("red")?, slot("green")?, slot("blue")?];
    let scale = if el.props[slots[0]].ty == Ty::U8 {
        1.0 / 255.0
    } else {
        1.0
    };
    Some((slots, scale))
}

/// One face record: its corners onto `corners`, its texture coordinates onto `corner_uv`
/// (while kept), its colour onto `face_rgb` (when `color` gives its slots); the other
/// properties skipped. `lists` are the slots of the corner list and the `texcoord` list.
/// Returns how many texture coordinate values it had.
fn read_face(
    el: &Element,
    body: &mut Body<impl Input>,
    [list, texture]: [Option<usize>; 2],
    color: Option<([usize; 3], f32)>,
    corners: &mut Vec<u32>,
    corner_uv: &mut Option<Vec<f32>>,
    face_rgb: &mut Vec<f32>,
) -> PResult<usize> {
    let mut values = 0;
    let mut rgb = [0f32; 3];
    for (k, p) in el.props.iter().enumerate() {
        let Some(ct) = p.list else {
            match color.and_then(|(slots, _)| slots.iter().position(|&s| s == k)) {
                Some(c) => rgb[c] = body.value(p.ty, "a face's colour")? as f32,
                None => body.skip(p.ty, "a face property")?,
            }
            continue;
        };
        let n = body.index(ct, "a face's corner count")?;
        for _ in 0..n {
            if Some(k) == list {
                corners.push(body.index(p.ty, "a face's vertex index")?);
            } else if Some(k) == texture {
                let v = body.value(p.ty, "a face's texture coordinate")?;
                if let Some(c) = corner_uv {
                    c.push(v as f32);
                }
                values += 1;
            } else {
                body.skip(p.ty, "a face list value")?;
            }
        }
    }
    if let Some((_, scale)) = color {
        if let Some(bad) = rgb.iter().find(|c| !c.is_finite()) {
            let message = format!("a face's colour is not a finite number ({bad})");
            return Err(ParseError::new(body.line, message));
        }
        face_rgb.extend(rgb.map(|c| c * scale));
    }
    Ok(values)
}

/// Skips an element the reader does not use, value by value.
fn skip_element(el: &Element, body: &mut Body<impl Input>) -> PResult<()> {
    body.start(el);
    for i in 0..el.count {
        body.record = i;
        for p in &el.props {
            if let Some(ct) = p.list {
                let n = body.index(ct, "a list count")?;
                for _ in 0..n {
                    body.skip(p.ty, "a list value")?;
                }
            } else {
                body.skip(p.ty, "a value")?;
            }
        }
    }
    Ok(())
}

/// Equal per-corner (u, v) pairs given one index, so that corners of a point that agree on
/// their coordinates stay one vertex: the distinct pairs go to `pairs`, the indices back.
fn shared_corner_pairs(per_corner: &[f32], pairs: &mut Vec<f32>) -> Vec<u32> {
    let mut seen: HashMap<[u32; 2], u32> = HashMap::new();
    let mut index = Vec::with_capacity(per_corner.len() / 2);
    for p in per_corner.chunks_exact(2) {
        let next = seen.len() as u32;
        let i = *seen.entry([p[0].to_bits(), p[1].to_bits()]).or_insert(next);
        if i == next {
            pairs.extend(p);
        }
        index.push(i);
    }
    index
}

/// Per-vertex values (flat, three per vertex) bound through each corner's vertex; none when
/// the file has none.
fn per_corner<'a>(values: &'a [f32], corners: &[u32]) -> Bind<'a> {
    if values.is_empty() {
        Bind::None
    } else {
        Bind::PerCorner {
            values,
            index: corners.to_vec(),
        }
    }
}

/// The model built from what the elements held; a file without faces is a point cloud and
/// gives an empty scene, with a warning.
fn finish(
    data: Gathered,
    texture: Option<String>,
    mut warnings: Vec<Warning>,
) -> PResult<(Scene, Vec<Warning>)> {
    let Gathered {
        coords,
        rgb,
        nxyz,
        uv,
        corner_uv,
        face_rgb,
        corners,
        ends,
        face_line,
        positions_only: _,
        recentre,
    } = data;
    if ends.is_empty() {
        warnings.push(Warning::new(
            WarningKind::Note,
            "the PLY file has no faces (a point cloud); nothing to decimate",
        ));
        return Ok((Scene::default(), warnings));
    }
    let colors = match per_corner(&rgb, &corners) {
        Bind::None if !face_rgb.is_empty() => Bind::PerFace {
            values: &face_rgb,
            index: (0..ends.len() as u32).collect(),
        },
        bind => bind,
    };
    let normals = per_corner(&nxyz, &corners);
    // Per-corner pairs win over per-vertex ones.
    let mut pairs: Vec<f32> = Vec::new();
    let texcoords = match corner_uv {
        Some(c) if !c.is_empty() => {
            let index = shared_corner_pairs(&c, &mut pairs);
            Some(TexCoords {
                values: &pairs,
                index,
            })
        }
        _ if !uv.is_empty() => Some(TexCoords {
            values: &uv,
            index: corners.clone(),
        }),
        _ => None,
    };
    let spec = ShapeSpec {
        name: "ply".into(),
        transform: Mat4::IDENTITY,
        coords: &coords,
        corners,
        ends,
        colors,
        normals,
        texcoords,
        ccw: true,
        solid: false,
        crease_angle: None,
        diffuse: [0.8; 3],
        line: face_line,
        index_field: "vertex_indices",
    };
    let mut model = build(spec, &mut warnings)?;
    model.origin = recentre.origin();
    // An image means nothing without coordinates to map it.
    model.texture = texture.filter(|_| model.texcoords.is_some());
    Ok((
        Scene {
            models: vec![model],
        },
        warnings,
    ))
}

/// Writes all models as one binary little-endian PLY (transforms baked in; per-vertex colours
/// and texture coordinates kept when every model has them), via a temporary file and a rename.
pub fn write_ply(scene: &Scene, path: &Path) -> Result<(), WriteError> {
    super::write_atomically(path, |w| write_ply_to(w, scene))
}

/// The one image every model maps, if they all name the same one (a PLY holds one mesh: it
/// cannot say which part maps which image). Names with a line break cannot be written.
pub(crate) fn shared_texture(scene: &Scene) -> Option<&str> {
    let first = scene.models.first()?.texture.as_deref()?;
    let same = scene
        .models
        .iter()
        .all(|m| m.texture.as_deref() == Some(first));
    (same && !first.contains(['\n', '\r'])).then_some(first)
}

/// The colour properties of a vertex or face element, as bytes.
const RGB_PROPERTIES: &str = "property uchar red\nproperty uchar green\nproperty uchar blue";

/// A colour in 0..1 as the bytes a PLY colour property holds.
fn colour_bytes(c: [f32; 3]) -> [u8; 3] {
    c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// Which properties a written PLY has: per-vertex colours, per-face colours, texture
/// coordinates (each when every model has them), and doubles for far coordinates.
struct Layout {
    colored: bool,
    face_colored: bool,
    textured: bool,
    far: bool,
}

impl Layout {
    fn of(scene: &Scene) -> Self {
        let colored = !scene.models.is_empty()
            && (scene.models.iter()).all(|m| matches!(m.colors, Some(Attribute::PerVertex(_))));
        Self {
            colored,
            face_colored: !colored && super::all_face_colored(scene),
            textured: super::all_textured(scene),
            // Far coordinates need doubles: f32 would round them as the input's f32 reading
            // would.
            far: origin::any_far(scene),
        }
    }
}

/// Writes the PLY bytes to `w`.
pub fn write_ply_to(w: &mut impl Write, scene: &Scene) -> std::io::Result<()> {
    let layout = Layout::of(scene);
    write_header(w, scene, &layout)?;
    write_vertices(w, scene, &layout)?;
    write_faces(w, scene, &layout)?;
    w.flush()
}

/// The header: the vertex and face elements with the properties `layout` names.
fn write_header(w: &mut impl Write, scene: &Scene, layout: &Layout) -> std::io::Result<()> {
    writeln!(
        w,
        "ply\nformat binary_little_endian 1.0\ncomment written by decimate"
    )?;
    if let Some(image) = shared_texture(scene).filter(|_| layout.textured) {
        writeln!(w, "comment TextureFile {image}")?;
    }
    writeln!(w, "element vertex {}", scene.vertex_count())?;
    let ty = if layout.far { "double" } else { "float" };
    writeln!(w, "property {ty} x\nproperty {ty} y\nproperty {ty} z")?;
    if layout.colored {
        writeln!(w, "{RGB_PROPERTIES}")?;
    }
    if layout.textured {
        writeln!(w, "property float s\nproperty float t")?;
    }
    writeln!(w, "element face {}", scene.triangle_count())?;
    writeln!(w, "property list uchar int vertex_indices")?;
    if layout.face_colored {
        writeln!(w, "{RGB_PROPERTIES}")?;
    }
    writeln!(w, "end_header")?;
    Ok(())
}

/// Every model's vertices, transformed, with their colours and texture coordinates.
fn write_vertices(w: &mut impl Write, scene: &Scene, layout: &Layout) -> std::io::Result<()> {
    for m in &scene.models {
        let colors = match &m.colors {
            Some(Attribute::PerVertex(c)) if layout.colored => Some(c),
            _ => None,
        };
        for (i, &p) in m.positions.iter().enumerate() {
            let p: Vec3 = m.transform.transform_point3(p);
            if layout.far {
                for c in origin::coords(m, p) {
                    w.write_all(&c.to_f64().to_le_bytes())?;
                }
            } else {
                for v in [p.x, p.y, p.z] {
                    w.write_all(&v.to_le_bytes())?;
                }
            }
            if let Some(c) = colors {
                w.write_all(&colour_bytes(c.get(i).copied().unwrap_or(m.diffuse)))?;
            }
            if let Some(t) = m.texcoords.as_ref().filter(|_| layout.textured) {
                for v in t[i] {
                    w.write_all(&v.to_le_bytes())?;
                }
            }
        }
    }
    Ok(())
}

/// Every model's triangles, numbered on across models, with their colours.
fn write_faces(w: &mut impl Write, scene: &Scene, layout: &Layout) -> std::io::Result<()> {
    let mut base = 0u32;
    for m in &scene.models {
        let colors = match &m.colors {
            Some(Attribute::PerFace(c)) if layout.face_colored => &c[..],
            _ => &[],
        };
        for (k, [a, b, c]) in super::outward_triangles(m).enumerate() {
            w.write_all(&[3])?;
            for v in [a, b, c] {
                w.write_all(&(v + base).to_le_bytes())?;
            }
            if let Some(&c) = colors.get(k) {
                w.write_all(&colour_bytes(c))?;
            }
        }
        base += m.positions.len() as u32;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::source::testing::{sorted_bits, sorted_triangles, OneByte};
    use super::super::source::Streamed;
    use super::*;

    /// A PLY of `n` × `n` grid squares as triangles, with a colour and an extra element.
    fn grid(format: &str, n: usize) -> Vec<u8> {
        let mut v = Vec::new();
        let mut f = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                v.push([i as f32 * 0.5, j as f32 * 0.25, (i * j) as f32 * 0.125]);
            }
        }
        for j in 0..n {
            for i in 0..n {
                let a = (j * (n + 1) + i) as u32;
                f.push([a, a + 1, a + n as u32 + 2]);
                f.push([a, a + n as u32 + 2, a + n as u32 + 1]);
            }
        }
        let mut out = format!(
            "ply\nformat {format} 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
             property float z\nproperty uchar red\nelement face {}\n\
             property list uchar int vertex_indices\nelement extra 1\nproperty short k\n\
             end_header\n",
            v.len(),
            f.len()
        )
        .into_bytes();
        let big = format == "binary_big_endian";
        let num = |out: &mut Vec<u8>, x: f32| {
            out.extend(if big {
                x.to_be_bytes()
            } else {
                x.to_le_bytes()
            })
        };
        for p in &v {
            if format == "ascii" {
                out.extend(format!("{} {} {} 7\n", p[0], p[1], p[2]).bytes());
            } else {
                p.iter().for_each(|&x| num(&mut out, x));
                out.push(7);
            }
        }
        for t in &f {
            if format == "ascii" {
                out.extend(format!("3 {} {} {}\n", t[0], t[1], t[2]).bytes());
            } else {
                out.push(3);
                for &i in t {
                    out.extend(if big {
                        i.to_be_bytes()
                    } else {
                        i.to_le_bytes()
                    });
                }
            }
        }
        out.extend(if format == "ascii" {
            &b"5\n"[..]
        } else {
            &[0, 5][..]
        });
        out
    }

    #[test]
    fn the_stream_gives_the_ordinary_reads_triangles_in_every_encoding() {
        for format in ["ascii", "binary_little_endian", "binary_big_endian"] {
            let bytes = grid(format, 6);
            let (scene, _) = read_ply(&bytes).unwrap();
            assert_eq!(scene.triangle_count(), 72, "{format}");
            let mut streamed = Vec::new();
            stream_ply(
                Streamed::new(OneByte(&bytes)),
                bytes.len(),
                &mut Recentre::default(),
                &mut |t| streamed.push(t),
            )
            .unwrap();
            assert_eq!(sorted_bits(streamed), sorted_triangles(&scene), "{format}");
        }
    }

    #[test]
    fn a_stream_cut_short_names_the_element_and_record() {
        let bytes = grid("binary_little_endian", 2);
        let cut = &bytes[..bytes.len() - 40];
        let e = stream_ply(
            Streamed::new(OneByte(cut)),
            cut.len(),
            &mut Recentre::default(),
            &mut |_| {},
        )
        .unwrap_err();
        assert!(
            e.message.contains("ends inside face 5 of 8"),
            "{}",
            e.message
        );
    }
}

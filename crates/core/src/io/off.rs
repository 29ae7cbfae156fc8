//! OFF (Geomview Object File Format): an ASCII reader and writer.
//!
//! Read: an `OFF` header with optional `ST`, `C`, `N` prefixes (`COFF`, `NOFF`, `CNOFF`...;
//! the 4-D and n-D variants and binary OFF are refused), `#` comments, the counts line
//! `vertices faces [edges]` (on the header line or the next), one vertex per line
//! (`x y z`, then normal / colour / `s t` texture coordinates as the prefixes say, in that
//! order; a colour is also taken from a plain `OFF` vertex line with 3 or 4 extra values), one
//! face per line (`n i1 … in`, optionally followed by a colour: 3 or 4 values, or 1 colour-map
//! index that is ignored). Colours are 0..1 floats, or 0..255 when all three are integers.
//! `ST` texture coordinates are kept per vertex. Polygons are triangulated. Counts are checked
//! against the file size before anything is reserved.
//! Write: ASCII `OFF`, with `C` (`r g b a`) when every model has per-vertex colours and `ST`
//! (`s t`, after the colour) when every model has texture coordinates (`STCOFF`, `STOFF`,
//! `COFF`), all models in one file, world positions.

use crate::io::warning::{Warning, WarningKind};
use std::io::Write;
use std::path::Path;

use glam::Mat4;

use super::shape_to_model::{build, Bind, ShapeSpec, TexCoords};
use super::text::{coordinate, number, relative_point, shown, words, Lines, StreamedLines};
use super::text::{parse_int, PResult, ParseError};
use super::WriteError;
use crate::mesh::{Attribute, Scene};

/// A line with something on it (comments cut off) and its number.
type Record = (usize, Vec<u8>);

/// True when the first word of the file (after comments) is an OFF header keyword.
pub(crate) fn looks_like_off(bytes: &[u8]) -> bool {
    next_record(&mut Lines::new(bytes, false))
        .and_then(|(_, text)| words(text).next())
        .is_some_and(|w| header_kind(w).is_some())
}

/// The next line with something on it (comments cut off).
fn next_record<'a>(lines: &mut Lines<'a>) -> Option<(usize, &'a [u8])> {
    loop {
        let text = lines.physical()?;
        if words(text).next().is_some() {
            return Some((lines.last_line(), text));
        }
    }
}

#[derive(Default, Clone, Copy)]
struct Kind {
    texture: bool,
    color: bool,
    normal: bool,
    /// `4OFF` / `nOFF`: not three-dimensional.
    dims: bool,
}

fn header_kind(w: &[u8]) -> Option<Kind> {
    let mut prefix = w.strip_suffix(b"OFF")?;
    let mut k = Kind::default();
    if let Some(p) = prefix.strip_prefix(b"ST") {
        k.texture = true;
        prefix = p;
    }
    for &c in prefix {
        match c {
            b'C' if !k.color => k.color = true,
            b'N' if !k.normal => k.normal = true,
            b'4' | b'n' => k.dims = true,
            _ => return None,
        }
    }
    Some(k)
}

/// One colour from three (or four) words: integers mean 0..255.
fn color(ws: &[&[u8]], line: usize) -> PResult<[f32; 3]> {
    let ints = ws[..3].iter().all(|w| parse_int(w).is_some());
    let mut c = [0f32; 3];
    for (k, w) in ws[..3].iter().enumerate() {
        c[k] = number(Some(w), line, "a colour component")?;
        if ints {
            c[k] /= 255.0;
        }
    }
    if let Some(a) = ws.get(3) {
        number(Some(a), line, "a colour's alpha")?;
    }
    Ok(c)
}

/// A count from the counts line; one record takes at least two bytes, so a count above half
/// the file's size is refused before anything is reserved.
fn count(w: Option<&[u8]>, line: usize, what: &str, file_len: usize) -> PResult<usize> {
    let limit = file_len / 2;
    let w = w.ok_or_else(|| {
        ParseError::new(
            line,
            format!("missing the {what} count (expected 'vertices faces edges')"),
        )
    })?;
    let n = parse_int(w).filter(|&n| n >= 0).ok_or_else(|| {
        ParseError::new(
            line,
            format!("expected a {what} count, found '{}'", shown(w)),
        )
    })? as u64;
    if n > limit as u64 {
        return Err(ParseError::new(
            line,
            format!(
                "the file declares {n} {}, more than its {} bytes can hold",
                if what == "vertex" {
                    "vertices"
                } else {
                    "faces"
                },
                limit * 2
            ),
        ));
    }
    Ok(n as usize)
}

/// What an OFF header says: the kind of vertex lines (its keyword, for messages) and the
/// counts, with the line they are on.
struct Header {
    kind: Kind,
    keyword: Vec<u8>,
    counts_line: usize,
    vertices: usize,
    faces: usize,
}

/// What the vertex lines hold; colours are per vertex, filled with grey before the first
/// coloured one.
#[derive(Default)]
struct Vertices {
    coords: Vec<f32>,
    /// The origin, picked from the first vertex.
    recentre: super::origin::Recentre,
    rgb: Vec<f32>,
    st: Vec<f32>,
}

/// What the face lines hold; colours are per face, filled with grey before the first
/// coloured one.
#[derive(Default)]
struct Faces {
    corners: Vec<u32>,
    ends: Vec<u32>,
    rgb: Vec<f32>,
    /// Line of the first face, for errors about its indices.
    first_line: usize,
}

/// Reads an OFF file into a scene of one model: header, vertex lines, face lines, then the
/// model built from them.
pub fn read_off(bytes: &[u8]) -> PResult<(Scene, Vec<Warning>)> {
    let mut warnings = Vec::new();
    let mut lines = Lines::new(bytes, false);
    let mut next = || Ok(next_record(&mut lines).map(|(l, t)| (l, t.to_vec())));
    let header = read_header(&mut next, bytes.len())?;
    let mut last = header.counts_line;
    let vertices = read_vertices(&mut lines, &header, &mut last)?;
    let faces = read_faces(&mut lines, &header, &mut last)?;
    if next_record(&mut lines).is_some() {
        warnings.push(Warning::new(
            WarningKind::SkippedFaces,
            format!(
                "the OFF file has more lines after its {} faces; they were ignored",
                header.faces
            ),
        ));
    }
    finish(&header, vertices, faces, warnings)
}

/// Reads the header: the `[ST][C][N]OFF` keyword and the vertex and face counts (on its line
/// or the next), from the records `next` hands out (lines with something on them).
fn read_header(
    next: &mut impl FnMut() -> PResult<Option<Record>>,
    file_len: usize,
) -> PResult<Header> {
    let (hline, htext) = next()?.ok_or_else(|| ParseError::new(1, "the OFF file is empty"))?;
    let mut hw = words(&htext);
    let first = hw.next().unwrap_or_default();
    let kind = header_kind(first).ok_or_else(|| {
        ParseError::new(
            hline,
            format!("expected an 'OFF' header, found '{}'", shown(first)),
        )
    })?;
    if kind.dims {
        return Err(ParseError::new(
            hline,
            format!("'{}' (4-D or n-D OFF) is not supported", shown(first)),
        ));
    }
    let rest: Vec<&[u8]> = hw.collect();
    if rest
        .first()
        .is_some_and(|w| w.eq_ignore_ascii_case(b"BINARY"))
    {
        return Err(ParseError::new(hline, "binary OFF is not supported"));
    }
    let counts_record;
    let (counts_line, counts): (usize, Vec<&[u8]>) = if rest.is_empty() {
        counts_record = next()?.ok_or_else(|| {
            ParseError::new(hline, "unexpected end of file: expected the counts line")
        })?;
        (counts_record.0, words(&counts_record.1).collect())
    } else {
        (hline, rest)
    };
    let nv = count(counts.first().copied(), counts_line, "vertex", file_len)?;
    let nf = count(counts.get(1).copied(), counts_line, "face", file_len)?;
    if nv == 0 || nf == 0 {
        return Err(ParseError::new(
            counts_line,
            format!("the file declares {nv} vertices and {nf} faces: nothing to read"),
        ));
    }
    Ok(Header {
        kind,
        keyword: first.to_vec(),
        counts_line,
        vertices: nv,
        faces: nf,
    })
}

/// Reads the header's count of vertex lines; `last` follows the line read last.
fn read_vertices(lines: &mut Lines<'_>, header: &Header, last: &mut usize) -> PResult<Vertices> {
    let nv = header.vertices;
    let mut out = Vertices {
        coords: Vec::with_capacity(nv * 3),
        ..Vertices::default()
    };
    let mut ws: Vec<&[u8]> = Vec::new();
    for i in 0..nv {
        let (line, text) = next_record(lines).ok_or_else(|| {
            ParseError::new(
                *last,
                format!("unexpected end of file after {i} of {nv} vertices"),
            )
        })?;
        *last = line;
        ws.clear();
        ws.extend(words(text));
        vertex_line(&ws, line, i, header, &mut out)?;
    }
    Ok(out)
}

/// One vertex line `x y z [nx ny nz] [r g b [a]] [s t]`, as the header's kind says.
fn vertex_line(
    ws: &[&[u8]],
    line: usize,
    i: usize,
    header: &Header,
    out: &mut Vertices,
) -> PResult<()> {
    let kind = header.kind;
    let mut it = ws.iter().copied();
    let x = coordinate(it.next(), line, "a vertex's x")?;
    let y = coordinate(it.next(), line, "a vertex's y")?;
    let z = coordinate(it.next(), line, "a vertex's z")?;
    let p = relative_point(&mut out.recentre, [x, y, z], line)?;
    out.coords.extend(p);
    let mut extra = &ws[3..];
    if kind.normal {
        for what in ["a normal's x", "a normal's y", "a normal's z"] {
            number(extra.first().copied(), line, what)?;
            extra = &extra[1..];
        }
    }
    let texture = if kind.texture { 2 } else { 0 };
    if extra.len() < texture {
        return Err(ParseError::new(
            line,
            format!(
                "expected texture coordinates 's t' at the end of an {} vertex line, \
                 found {} values",
                shown(&header.keyword),
                ws.len()
            ),
        ));
    }
    let ncolor = extra.len() - texture;
    let has_color = if kind.color {
        if !(3..=4).contains(&ncolor) {
            return Err(ParseError::new(
                line,
                format!(
                    "expected 'x y z r g b [a]' on a COFF vertex line, found {} values",
                    ws.len()
                ),
            ));
        }
        true
    } else {
        match ncolor {
            0 => false,
            3 | 4 if !kind.normal => true,
            _ => {
                return Err(ParseError::new(
                    line,
                    format!(
                        "unexpected values after vertex {i}: {} values on the line",
                        ws.len()
                    ),
                ))
            }
        }
    };
    if has_color {
        if out.rgb.len() < i * 3 {
            out.rgb.resize(i * 3, 0.8);
        }
        out.rgb.extend(color(&extra[..ncolor], line)?);
    } else if !out.rgb.is_empty() {
        out.rgb.extend([0.8; 3]);
    }
    for w in &extra[ncolor..] {
        out.st.push(number(Some(w), line, "a texture coordinate")?);
    }
    Ok(())
}

/// Reads the header's count of face lines; `last` follows the line read last.
fn read_faces(lines: &mut Lines<'_>, header: &Header, last: &mut usize) -> PResult<Faces> {
    let nf = header.faces;
    let mut out = Faces {
        corners: Vec::with_capacity(nf * 3),
        ends: Vec::with_capacity(nf),
        first_line: *last,
        ..Faces::default()
    };
    let mut ws: Vec<&[u8]> = Vec::new();
    for f in 0..nf {
        let (line, text) = next_record(lines).ok_or_else(|| {
            ParseError::new(
                *last,
                format!("unexpected end of file after {f} of {nf} faces"),
            )
        })?;
        if f == 0 {
            out.first_line = line;
        }
        *last = line;
        ws.clear();
        ws.extend(words(text));
        face_line(&ws, text, line, f, header.vertices, &mut out)?;
    }
    Ok(out)
}

/// One face line `n i1 … in [r g b [a] | colour-map index]`.
fn face_line(
    ws: &[&[u8]],
    text: &[u8],
    line: usize,
    f: usize,
    nv: usize,
    out: &mut Faces,
) -> PResult<()> {
    match face_corners(ws, text, (line, f), nv, &mut out.corners)? {
        Some(rgb) => {
            if out.rgb.len() < f * 3 {
                out.rgb.resize(f * 3, 0.8);
            }
            out.rgb.extend(rgb);
        }
        None if !out.rgb.is_empty() => out.rgb.extend([0.8; 3]),
        None => {}
    }
    out.ends.push(out.corners.len() as u32);
    Ok(())
}

/// Face `f`'s corner indices, checked against the `nv` vertices and pushed on `corners`, and
/// its colour when the line gives one (a colour-map index is read and dropped).
fn face_corners(
    ws: &[&[u8]],
    text: &[u8],
    (line, f): (usize, usize),
    nv: usize,
    corners: &mut Vec<u32>,
) -> PResult<Option<[f32; 3]>> {
    let n = ws
        .first()
        .and_then(|w| parse_int(w))
        .filter(|&n| n >= 0 && (n as u64) < ws.len() as u64)
        .ok_or_else(|| {
            ParseError::new(
                line,
                format!("expected 'n i1 … in' for face {f}, found '{}'", shown(text)),
            )
        })? as usize;
    for w in &ws[1..=n] {
        let i = parse_int(w)
            .filter(|&i| i >= 0 && (i as u64) < nv as u64)
            .ok_or_else(|| {
                ParseError::new(
                    line,
                    format!("face {f}: vertex index '{}' is not in 0..{nv}", shown(w)),
                )
            })?;
        corners.push(i as u32);
    }
    let extra = &ws[n + 1..];
    match extra.len() {
        0 => Ok(None),
        1 => number(extra.first().copied(), line, "a colour-map index").map(|_| None),
        3 | 4 => color(extra, line).map(Some),
        k => Err(ParseError::new(
            line,
            format!("face {f}: {k} values after its {n} indices (expected a colour of 3 or 4)"),
        )),
    }
}

/// The next record of a streamed read, the `i`-th of `n` `what`; the end of the file there
/// is an error on the `last` line read.
fn expect_record(
    next: &mut impl FnMut() -> PResult<Option<Record>>,
    last: usize,
    (i, n, what): (usize, usize, &str),
) -> PResult<Record> {
    next()?.ok_or_else(|| {
        ParseError::new(
            last,
            format!("unexpected end of file after {i} of {n} {what}"),
        )
    })
}

/// Tiling's read of an OFF file too big to hold (`io::stream`): each face's triangles (a
/// polygon fanned from its first corner) handed to `triangle` as its line is read, positions
/// relative to `recentre`'s origin. Holds what the vertex lines give (positions, and
/// colours or texture coordinates where they have them), never the faces.
pub(super) fn stream_off(
    input: impl std::io::BufRead,
    file_len: usize,
    recentre: &mut super::origin::Recentre,
    triangle: &mut dyn FnMut([[f32; 3]; 3]),
) -> PResult<()> {
    let mut lines = StreamedLines::new(input, false);
    let mut next = || loop {
        match lines.next().transpose()? {
            Some((_, t)) if words(&t).next().is_none() => {}
            record => return Ok(record),
        }
    };
    let header = read_header(&mut next, file_len)?;
    let mut last = header.counts_line;
    let mut vertices = Vertices {
        recentre: *recentre,
        ..Vertices::default()
    };
    for i in 0..header.vertices {
        let (line, text) = expect_record(&mut next, last, (i, header.vertices, "vertices"))?;
        last = line;
        let ws: Vec<&[u8]> = words(&text).collect();
        vertex_line(&ws, line, i, &header, &mut vertices)?;
    }
    *recentre = vertices.recentre;
    let at = |v: u32| {
        let i = 3 * v as usize;
        [
            vertices.coords[i],
            vertices.coords[i + 1],
            vertices.coords[i + 2],
        ]
    };
    let mut corners = Vec::new();
    for f in 0..header.faces {
        let (line, text) = expect_record(&mut next, last, (f, header.faces, "faces"))?;
        last = line;
        let ws: Vec<&[u8]> = words(&text).collect();
        corners.clear();
        face_corners(&ws, &text, (line, f), header.vertices, &mut corners)?;
        if let [first, rest @ ..] = corners.as_slice() {
            for pair in rest.windows(2) {
                triangle([at(*first), at(pair[0]), at(pair[1])]);
            }
        }
    }
    Ok(())
}

/// The model built from the vertex and face lines: per-vertex colours win over per-face ones.
fn finish(
    header: &Header,
    vertices: Vertices,
    faces: Faces,
    mut warnings: Vec<Warning>,
) -> PResult<(Scene, Vec<Warning>)> {
    let (nv, nf) = (header.vertices, header.faces);
    let Vertices {
        coords,
        recentre,
        mut rgb,
        st,
    } = vertices;
    let Faces {
        corners,
        ends,
        rgb: mut face_rgb,
        first_line,
    } = faces;
    let colors = if !rgb.is_empty() {
        rgb.resize(nv * 3, 0.8);
        Bind::PerCorner {
            values: &rgb,
            index: corners.clone(),
        }
    } else if !face_rgb.is_empty() {
        face_rgb.resize(nf * 3, 0.8);
        Bind::PerFace {
            values: &face_rgb,
            index: (0..nf as u32).collect(),
        }
    } else {
        Bind::None
    };
    let texcoords = header.kind.texture.then(|| TexCoords {
        values: &st,
        index: corners.clone(),
    });
    let mut model = build(
        ShapeSpec {
            name: "off".into(),
            transform: Mat4::IDENTITY,
            coords: &coords,
            corners,
            ends,
            colors,
            normals: Bind::None,
            texcoords,
            ccw: true,
            solid: false,
            crease_angle: None,
            diffuse: [0.8; 3],
            line: first_line,
            index_field: "faces",
        },
        &mut warnings,
    )?;
    model.origin = recentre.origin();
    Ok((
        Scene {
            models: vec![model],
        },
        warnings,
    ))
}

/// Writes all models as one ASCII OFF, via a temporary file and a rename.
pub fn write_off(scene: &Scene, path: &Path) -> Result<(), WriteError> {
    super::write_atomically(path, |w| write_off_to(w, scene))
}

/// Writes the OFF text to `w`.
pub fn write_off_to(w: &mut impl Write, scene: &Scene) -> std::io::Result<()> {
    let colored = !scene.models.is_empty()
        && scene.models.iter().all(
            |m| matches!(&m.colors, Some(Attribute::PerVertex(c)) if c.len() == m.positions.len()),
        );
    let face_colored = !colored && super::all_face_colored(scene);
    let textured = super::all_textured(scene);
    // Prefixes in the order readers expect: [ST][C][N]OFF.
    writeln!(
        w,
        "{}{}OFF",
        if textured { "ST" } else { "" },
        if colored { "C" } else { "" }
    )?;
    writeln!(
        w,
        "# written by decimate: {} models, world positions (model transforms applied)",
        scene.models.len()
    )?;
    writeln!(w, "{} {} 0", scene.vertex_count(), scene.triangle_count())?;
    for m in &scene.models {
        let colors = match &m.colors {
            Some(Attribute::PerVertex(c)) if colored => Some(c),
            _ => None,
        };
        let texcoords = m.texcoords.as_ref().filter(|_| textured);
        for (k, &p) in m.positions.iter().enumerate() {
            let [x, y, z] = super::origin::coords(m, m.transform.transform_point3(p));
            write!(w, "{x} {y} {z}")?;
            if let Some(c) = colors {
                let [r, g, b] = c[k];
                write!(w, " {r:?} {g:?} {b:?} 1.0")?;
            }
            if let Some(t) = texcoords {
                let [s, t] = t[k];
                write!(w, " {s:?} {t:?}")?;
            }
            writeln!(w)?;
        }
    }
    let mut base = 0u64;
    for m in &scene.models {
        let colors = match &m.colors {
            Some(Attribute::PerFace(c)) if face_colored => &c[..],
            _ => &[],
        };
        for (k, [a, b, c]) in super::outward_triangles(m).enumerate() {
            let [a, b, c] = [a, b, c].map(|v| v as u64 + base);
            write!(w, "3 {a} {b} {c}")?;
            if let Some([r, g, b]) = colors.get(k) {
                write!(w, " {r:?} {g:?} {b:?}")?;
            }
            writeln!(w)?;
        }
        base += m.positions.len() as u64;
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle's corners, each listed from its smallest, the list sorted.
    fn sorted(mut ts: Vec<[[f32; 3]; 3]>) -> Vec<[[u32; 3]; 3]> {
        let key = |t: [[f32; 3]; 3]| t.map(|p| p.map(f32::to_bits));
        let mut out: Vec<[[u32; 3]; 3]> = ts
            .drain(..)
            .map(|t| {
                let k = key(t);
                let first = (0..3).min_by_key(|&i| k[i]).unwrap_or(0);
                [k[first], k[(first + 1) % 3], k[(first + 2) % 3]]
            })
            .collect();
        out.sort_unstable();
        out
    }

    // A streamed read (tiling's) gives the triangles the whole read gives, with normals,
    // colours and texture coordinates on the vertex lines and colours on the faces to step
    // over, a quad fanned, comments and blank lines between records.
    #[test]
    fn a_streamed_read_gives_the_whole_reads_triangles() {
        let text = "STCNOFF # all the extras\n\n5 2 0\n\
                    0 0 0  0 0 1  1 0 0 1  0 0\n\
                    1 0 0  0 0 1  0 1 0 1  1 0\n\
                    1 1 0.5  0 0 1  0 0 1 1  1 1\n\
                    # a comment between vertices\n\
                    0 1 0  0 0 1  1 1 1 1  0 1\n\
                    2 2 1  0 0 1  0.5 0.5 0.5 1  0.5 0.5\n\
                    4 0 1 2 3  255 0 0\n\
                    3 1 4 2 0.2 0.4 0.6 1\n";
        let (scene, _) = read_off(text.as_bytes()).expect("read whole");
        let m = &scene.models[0];
        let whole: Vec<[[f32; 3]; 3]> = (m.triangles.iter())
            .map(|t| t.map(|v| m.positions[v as usize].to_array()))
            .collect();
        let mut streamed = Vec::new();
        let mut recentre = super::super::origin::Recentre::default();
        stream_off(text.as_bytes(), text.len(), &mut recentre, &mut |t| {
            streamed.push(t)
        })
        .expect("streamed");
        assert_eq!(streamed.len(), 3);
        assert_eq!(sorted(streamed), sorted(whole));
    }

    // A streamed read refuses what the whole read refuses, on the same line.
    #[test]
    fn a_streamed_read_refuses_a_bad_index_and_a_short_file_on_their_lines() {
        let mut recentre = super::super::origin::Recentre::default();
        let mut stream = |text: &str| {
            stream_off(text.as_bytes(), text.len(), &mut recentre, &mut |_| {})
                .map_err(|e| (e.line, e.message))
        };
        let bad = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
        assert_eq!(
            stream(bad),
            Err((6, "face 0: vertex index '7' is not in 0..3".to_string()))
        );
        let short = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert_eq!(
            stream(short),
            Err((6, "unexpected end of file after 1 of 2 faces".to_string()))
        );
        assert_eq!(
            read_off(bad.as_bytes()).map(|_| ()).map_err(|e| e.line),
            Err(6)
        );
    }
}

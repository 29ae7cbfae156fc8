//! STL (stereolithography): a reader for ASCII and binary files and a binary writer.
//!
//! Read: a file is binary when its size is exactly 84 + 50·n bytes for the triangle count n
//! stored at byte 80 — even when its 80-byte header starts with "solid", as many exporters'
//! do; otherwise a file starting with `solid` is ASCII (`solid name`, `facet normal`,
//! `outer loop`, `vertex` ×3 or more, `endloop`, `endfacet`, `endsolid`), several solids giving
//! several models. Facet normals are checked but not kept (recomputed later). Every facet has
//! its own three vertices; `mesh::build_scene` welds them afterwards.
//! Write: binary little-endian, all models in one file, world positions, facet normals
//! computed, an 80-byte header that does not start with "solid".

use crate::io::warning::{Warning, WarningKind};
use std::io::Write;
use std::path::Path;

use glam::{Mat4, Vec3};

use super::origin::Recentre;

use super::shape_to_model::{build, Bind, ShapeSpec};
use super::source::Input;
use super::text::shown;
use super::text::ParseError;
use super::WriteError;
use crate::mesh::{Model, Scene};

/// What can go wrong reading STL: a line of an ASCII file or a record of a binary one.
#[derive(Debug)]
pub(crate) enum StlError {
    Line(ParseError),
    /// About the whole file (its size, its header): reported on line 1.
    Header(String),
    Record {
        record: usize,
        message: String,
    },
}

impl From<ParseError> for StlError {
    fn from(e: ParseError) -> Self {
        Self::Line(e)
    }
}

/// True when `bytes` has the exact size of a binary STL with the count it stores.
pub(crate) fn is_binary(bytes: &[u8]) -> bool {
    is_binary_of_size(bytes, bytes.len() as u64)
}

/// True when a file of `len` bytes that starts with `head` has the exact size of a binary
/// STL with the count it stores.
pub(crate) fn is_binary_of_size(head: &[u8], len: u64) -> bool {
    binary_count(head).is_some_and(|n| 84 + 50 * n as u64 == len)
}

fn binary_count(bytes: &[u8]) -> Option<u32> {
    let c = bytes.get(80..84)?;
    Some(u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

/// True when the file starts (after blanks) with the ASCII keyword `solid`.
pub(crate) fn starts_with_solid(bytes: &[u8]) -> bool {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    bytes[start..]
        .get(..5)
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"))
        && bytes.get(start + 5).is_none_or(|b| b.is_ascii_whitespace())
}

/// Reads an STL file, binary or ASCII.
pub(crate) fn read_stl(bytes: &[u8]) -> Result<(Scene, Vec<Warning>), StlError> {
    if is_binary(bytes) {
        return read_binary(bytes);
    }
    if starts_with_solid(bytes) {
        let Some(at) = bytes.iter().position(|&b| b == 0) else {
            return read_ascii(bytes).map_err(StlError::Line);
        };
        // Facets before the NUL: ASCII with a stray NUL (or a binary STL whose header
        // says "facet" and whose count does not fit: the message says both). Otherwise a
        // binary STL with a "solid" header, told below what is wrong with its count.
        if bytes[..at]
            .windows(5)
            .any(|w| w.eq_ignore_ascii_case(b"facet"))
        {
            return Err(ascii_with_nul(bytes, at));
        }
    }
    binary_count_error(bytes)
}

/// A file starting with `solid` and facets that holds a NUL byte at `at`.
fn ascii_with_nul(bytes: &[u8], at: usize) -> StlError {
    let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
    let binary = binary_count(bytes).map_or(String::new(), |n| {
        format!(" ({n} triangles, {} bytes)", 84 + 50 * n as u64)
    });
    StlError::Line(ParseError::new(
        line,
        format!(
            "the file starts with 'solid' and facets like an ASCII STL but holds a NUL byte \
             (byte {at}), and its size ({} bytes) is not the one a binary STL's count \
             gives{binary}",
            bytes.len()
        ),
    ))
}

/// What is wrong with a file that is neither ASCII nor a binary STL of the size its count
/// gives.
fn binary_count_error(bytes: &[u8]) -> Result<(Scene, Vec<Warning>), StlError> {
    let Some(n) = binary_count(bytes) else {
        return Err(StlError::Header(format!(
            "not an STL file: {} bytes is too short for a binary STL header and it does not start with 'solid'",
            bytes.len()
        )));
    };
    let have = (bytes.len() - 84) / 50;
    if (have as u64) >= n as u64 {
        return Err(StlError::Header(format!(
            "the binary STL has {} bytes after its last record ({n} triangles announced, {} bytes expected)",
            bytes.len() as u64 - (84 + 50 * n as u64),
            84 + 50 * n as u64
        )));
    }
    Err(StlError::Record {
        record: have + 1,
        message: format!(
            "the binary STL is truncated: its header announces {n} triangles ({} bytes) but the file has only {} bytes",
            84 + 50 * n as u64,
            bytes.len(),
        ),
    })
}

fn model(
    name: String,
    coords: Vec<f32>,
    line: usize,
    warnings: &mut Vec<Warning>,
) -> Result<Model, ParseError> {
    let n = coords.len() / 3;
    let spec = ShapeSpec {
        name,
        transform: Mat4::IDENTITY,
        coords: &coords,
        corners: (0..n as u32).collect(),
        ends: (1..=(n / 3) as u32).map(|t| t * 3).collect(),
        colors: Bind::None,
        normals: Bind::None,
        texcoords: None,
        ccw: true,
        solid: false,
        crease_angle: None,
        diffuse: [0.8; 3],
        line,
        index_field: "vertex",
    };
    build(spec, warnings)
}

fn read_binary(bytes: &[u8]) -> Result<(Scene, Vec<Warning>), StlError> {
    let mut warnings = Vec::new();
    let body = &bytes[84..];
    if body.is_empty() {
        return Err(StlError::Header(
            "the binary STL has no triangles (its count is 0)".into(),
        ));
    }
    let mut coords = Vec::with_capacity(body.len() / 50 * 9);
    for (r, rec) in body.chunks_exact(50).enumerate() {
        let corners = record_corners(rec).map_err(|message| StlError::Record {
            record: r + 1,
            message,
        })?;
        coords.extend(corners);
    }
    let name = String::from_utf8_lossy(&bytes[..80])
        .trim_matches(|c: char| c == '\0' || c.is_whitespace())
        .to_string();
    let name = match name.strip_prefix("solid") {
        Some(rest) => rest.trim().to_string(),
        None => String::new(),
    };
    let m = model(name, coords, 1, &mut warnings)?;
    Ok((Scene { models: vec![m] }, warnings))
}

/// The three corners of a 50-byte binary record (after its normal), all finite.
fn record_corners(rec: &[u8]) -> Result<[f32; 9], String> {
    let mut out = [0f32; 9];
    for (k, o) in out.iter_mut().enumerate() {
        let b = &rec[12 + k * 4..16 + k * 4];
        let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        if !v.is_finite() {
            return Err(format!("a vertex coordinate is not finite ({v})"));
        }
        *o = v;
    }
    Ok(out)
}

/// Tiling's read: hands each facet of an STL file to `triangle` as it is read, holding
/// nothing. Binary or ASCII is told as the ordinary reader tells it (the size the header's
/// count implies, else the `solid` keyword), and both are parsed by its code.
pub(super) fn stream_stl(
    mut input: impl Input,
    file_len: u64,
    recentre: &mut Recentre,
    triangle: &mut dyn FnMut([[f32; 3]; 3]),
) -> Result<(), StlError> {
    while input.bytes().len() < 84 {
        if input.more(0).map_err(read_failed)?.is_none() {
            break;
        }
    }
    let head = input.bytes();
    let binary = is_binary_of_size(head, file_len);
    if !binary {
        if !starts_with_solid(head) {
            return Err(StlError::Header(
                "not an STL file: its size does not match a binary STL's count and it does not start with 'solid'"
                    .into(),
            ));
        }
        let mut w = Words::new(input);
        let mut out = Streamed(triangle, recentre);
        return parse_ascii(&mut w, &mut out, &mut Vec::new()).map_err(StlError::Line);
    }
    let count = binary_count(head).unwrap_or(0) as usize;
    let mut pos = 84;
    for r in 0..count {
        while input.bytes().len() < pos + 50 {
            match input.more(pos).map_err(read_failed)? {
                Some(dropped) => pos -= dropped,
                None => {
                    return Err(StlError::Record {
                        record: r + 1,
                        message: format!(
                            "the file ends before the {count} triangles its header counts"
                        ),
                    })
                }
            }
        }
        let c =
            record_corners(&input.bytes()[pos..pos + 50]).map_err(|message| StlError::Record {
                record: r + 1,
                message,
            })?;
        let c = c.map(f64::from);
        triangle(
            [[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]]
                .map(|p| recentre.relative(p)),
        );
        pos += 50;
    }
    Ok(())
}

fn read_failed(e: std::io::Error) -> StlError {
    StlError::Header(format!("the file could not be read: {e}"))
}

/// Words of an ASCII STL with line numbers, from a file in memory or streamed.
struct Words<I> {
    input: I,
    pos: usize,
    /// Line of the scanning position.
    at: usize,
    /// Line of the last word read (messages name it, also at the end of the file).
    line: usize,
}

impl<I: Input> Words<I> {
    fn new(input: I) -> Self {
        Self {
            input,
            pos: 0,
            at: 1,
            line: 1,
        }
    }

    /// More bytes, keeping those from `keep` on (positions move down); false at the end.
    fn more(&mut self, keep: &mut usize) -> Result<bool, ParseError> {
        let more = self
            .input
            .more(*keep)
            .map_err(|e| ParseError::new(self.at, format!("the file could not be read: {e}")))?;
        if let Some(dropped) = more {
            self.pos -= dropped;
            *keep -= dropped;
        }
        Ok(more.is_some())
    }

    /// Moves on while `take` holds for the next byte, counting lines; returns where it began.
    fn scan(&mut self, take: impl Fn(u8) -> bool) -> Result<usize, ParseError> {
        let mut start = self.pos;
        loop {
            let b = self.input.bytes();
            while self.pos < b.len() && take(b[self.pos]) {
                if b[self.pos] == b'\n' {
                    self.at += 1;
                }
                self.pos += 1;
            }
            if self.pos < b.len() || !self.more(&mut start)? {
                return Ok(start);
            }
        }
    }

    /// The next word, as a range of `input.bytes()`.
    fn next(&mut self) -> Result<Option<std::ops::Range<usize>>, ParseError> {
        self.scan(|b| b.is_ascii_whitespace())?;
        let start = self.scan(|b| !b.is_ascii_whitespace())?;
        if self.pos == start {
            return Ok(None);
        }
        self.line = self.at;
        Ok(Some(start..self.pos))
    }

    fn is(&self, r: &std::ops::Range<usize>, word: &[u8]) -> bool {
        self.input.bytes()[r.clone()].eq_ignore_ascii_case(word)
    }

    fn shown(&self, r: std::ops::Range<usize>) -> String {
        shown(&self.input.bytes()[r])
    }

    /// The rest of the current line, trimmed (solid names).
    fn rest_of_line(&mut self) -> Result<String, ParseError> {
        let start = self.scan(|b| b != b'\n')?;
        Ok(
            String::from_utf8_lossy(&self.input.bytes()[start..self.pos])
                .trim()
                .to_string(),
        )
    }

    fn expect(&mut self, word: &str) -> Result<(), ParseError> {
        match self.next()? {
            Some(r) if self.is(&r, word.as_bytes()) => Ok(()),
            Some(r) => Err(ParseError::new(
                self.line,
                format!("expected '{word}', found '{}'", self.shown(r)),
            )),
            None => Err(ParseError::new(
                self.line,
                format!("unexpected end of file: expected '{word}'"),
            )),
        }
    }

    fn number(&mut self, what: &str) -> Result<f32, ParseError> {
        let r = self.next()?;
        super::text::number(r.map(|r| &self.input.bytes()[r]), self.line, what)
    }

    /// A vertex coordinate, in f64 (far coordinates keep their digits) but within f32's range.
    fn coordinate(&mut self, what: &str) -> Result<f64, ParseError> {
        let r = self.next()?;
        let word = r.map(|r| &self.input.bytes()[r]);
        let v = super::text::coordinate(word, self.line, what)?;
        if (v as f32).is_finite() {
            Ok(v)
        } else {
            Err(ParseError::new(
                self.line,
                format!("{what} ({v}) is too large for 32-bit floats"),
            ))
        }
    }
}

/// Where an ASCII STL's facets go: the ordinary read's models, or tiling's callback.
trait Solids {
    fn facet(&mut self, corners: [f64; 9]);
    /// The end of a solid with facets, named `name`, starting on `line`.
    fn end_solid(
        &mut self,
        name: String,
        line: usize,
        warnings: &mut Vec<Warning>,
    ) -> Result<(), ParseError>;
}

/// The ordinary read: one model per solid.
#[derive(Default)]
struct Models {
    coords: Vec<f32>,
    models: Vec<Model>,
    /// The origin, picked from the file's first vertex; all solids share it.
    recentre: Recentre,
}

impl Solids for Models {
    fn facet(&mut self, c: [f64; 9]) {
        for p in [[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]] {
            self.coords.extend(self.recentre.relative(p));
        }
    }

    fn end_solid(
        &mut self,
        name: String,
        line: usize,
        warnings: &mut Vec<Warning>,
    ) -> Result<(), ParseError> {
        let coords = std::mem::take(&mut self.coords);
        let mut m = model(name, coords, line, warnings)?;
        m.origin = self.recentre.origin();
        self.models.push(m);
        Ok(())
    }
}

/// Tiling's read: each facet handed on, relative to the origin the `Recentre` picks.
struct Streamed<'a>(&'a mut dyn FnMut([[f32; 3]; 3]), &'a mut Recentre);

impl Solids for Streamed<'_> {
    fn facet(&mut self, c: [f64; 9]) {
        let corners = [[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]];
        (self.0)(corners.map(|p| self.1.relative(p)));
    }

    fn end_solid(&mut self, _: String, _: usize, _: &mut Vec<Warning>) -> Result<(), ParseError> {
        Ok(())
    }
}

fn read_ascii(bytes: &[u8]) -> Result<(Scene, Vec<Warning>), ParseError> {
    let mut warnings = Vec::new();
    let mut out = Models::default();
    parse_ascii(&mut Words::new(bytes), &mut out, &mut warnings)?;
    Ok((Scene { models: out.models }, warnings))
}

/// Reads every `solid … endsolid` of an ASCII STL into `out`.
fn parse_ascii<I: Input>(
    w: &mut Words<I>,
    out: &mut impl Solids,
    warnings: &mut Vec<Warning>,
) -> Result<(), ParseError> {
    let mut total = 0usize;
    while let Some(word) = w.next()? {
        if !w.is(&word, b"solid") {
            return Err(ParseError::new(
                w.line,
                format!("expected 'solid', found '{}'", w.shown(word)),
            ));
        }
        let solid_line = w.line;
        let name = w.rest_of_line()?;
        let mut facets = 0usize;
        loop {
            let Some(word) = w.next()? else {
                warnings.push(
                    Warning::new(
                        WarningKind::Note,
                        format!("the STL solid '{name}' (line {solid_line}) has no 'endsolid'"),
                    )
                    .at(solid_line),
                );
                break;
            };
            if w.is(&word, b"endsolid") {
                w.rest_of_line()?;
                break;
            }
            if !w.is(&word, b"facet") {
                return Err(ParseError::new(
                    w.line,
                    format!("expected 'facet' or 'endsolid', found '{}'", w.shown(word)),
                ));
            }
            out.facet(read_facet(w)?);
            facets += 1;
        }
        if facets == 0 {
            warnings.push(
                Warning::new(
                    WarningKind::Note,
                    format!("the STL solid '{name}' (line {solid_line}) has no facets"),
                )
                .at(solid_line),
            );
            continue;
        }
        total += facets;
        out.end_solid(name, solid_line, warnings)?;
    }
    if total == 0 {
        return Err(ParseError::new(
            w.line,
            "the STL file has no facets: nothing to read",
        ));
    }
    Ok(())
}

/// One facet after its `facet` keyword: normal, `outer loop`, three vertices, `endloop`,
/// `endfacet`.
fn read_facet<I: Input>(w: &mut Words<I>) -> Result<[f64; 9], ParseError> {
    w.expect("normal")?;
    for what in [
        "the facet normal's x",
        "the facet normal's y",
        "the facet normal's z",
    ] {
        w.number(what)?;
    }
    w.expect("outer")?;
    w.expect("loop")?;
    let facet_line = w.line;
    let mut corners = 0;
    let mut out = [0f64; 9];
    loop {
        match w.next()? {
            Some(v) if w.is(&v, b"vertex") => {
                for k in 0..3 {
                    let what = ["a vertex's x", "a vertex's y", "a vertex's z"][k];
                    let value = w.coordinate(what)?;
                    if let Some(o) = out.get_mut(3 * corners + k) {
                        *o = value;
                    }
                }
                corners += 1;
            }
            Some(v) if w.is(&v, b"endloop") => break,
            Some(v) => {
                return Err(ParseError::new(
                    w.line,
                    format!("expected 'vertex' or 'endloop', found '{}'", w.shown(v)),
                ))
            }
            None => {
                return Err(ParseError::new(
                    w.line,
                    "unexpected end of file inside a facet: expected 'endloop'",
                ))
            }
        }
    }
    if corners != 3 {
        return Err(ParseError::new(
            facet_line,
            format!("a facet has {corners} vertices (STL facets are triangles)"),
        ));
    }
    w.expect("endfacet")?;
    Ok(out)
}

/// Writes all models as one binary little-endian STL, via a temporary file and a rename.
pub fn write_stl(scene: &Scene, path: &Path) -> Result<(), WriteError> {
    super::write_atomically(path, |w| write_stl_to(w, scene))
}

/// Writes the binary STL bytes to `w`.
pub fn write_stl_to(w: &mut impl Write, scene: &Scene) -> std::io::Result<()> {
    let count = u32::try_from(scene.triangle_count()).map_err(|_| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "more than 4294967295 triangles do not fit in a binary STL",
        )
    })?;
    let mut header = [b' '; 80];
    let text = b"binary STL written by decimate (world coordinates)";
    header[..text.len()].copy_from_slice(text);
    w.write_all(&header)?;
    w.write_all(&count.to_le_bytes())?;
    let mut rec = [0u8; 50];
    for m in &scene.models {
        // Binary STL holds f32 only: a far model is written in the file's frame all the
        // same, rounded as f32 rounds (`losses` says so before writing); its normals come
        // from the positions relative to its origin, which f32 holds well.
        let world: Vec<Vec3> = m
            .positions
            .iter()
            .map(|&p| m.transform.transform_point3(p))
            .collect();
        let far = m.origin != glam::DVec3::ZERO;
        let file_frame = |p: Vec3| {
            let [x, y, z] = super::origin::coords(m, p).map(|c| c.to_f64() as f32);
            Vec3::new(x, y, z)
        };
        for [a, b, c] in super::outward_triangles(m) {
            let [a, b, c] = [a, b, c].map(|i| world.get(i as usize).copied().unwrap_or(Vec3::ZERO));
            let n = (b - a).cross(c - a).normalize_or_zero();
            let [a, b, c] = if far {
                [a, b, c].map(file_frame)
            } else {
                [a, b, c]
            };
            for (k, v) in [n, a, b, c].iter().flat_map(|v| v.to_array()).enumerate() {
                rec[k * 4..k * 4 + 4].copy_from_slice(&v.to_le_bytes());
            }
            w.write_all(&rec)?;
        }
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solid_keyword_needs_a_word_boundary() {
        assert!(starts_with_solid(b"  solid cube\n"));
        assert!(starts_with_solid(b"solid"));
        assert!(!starts_with_solid(b"solidworks binary"));
    }
}

#[cfg(test)]
mod stream_tests {
    use super::super::source::testing::{sorted_bits, sorted_triangles, OneByte};
    use super::super::source::Streamed;
    use super::*;

    #[test]
    fn the_stream_gives_the_ordinary_reads_facets_ascii_and_binary() {
        let facet = |x: f32| {
            format!(
                "facet normal 0 0 1\nouter loop\nvertex {x} 0 0\nvertex 1 {x} 0\n\
                 vertex 0 1 {x}\nendloop\nendfacet\n"
            )
        };
        let ascii = format!(
            "solid a\n{}{}endsolid a\nsolid b\n{}endsolid b\n",
            facet(0.5),
            facet(1.5),
            facet(2.5)
        );
        let mut binary = Vec::new();
        let (read, _) = read_stl(ascii.as_bytes()).unwrap();
        write_stl_to(&mut binary, &read).unwrap();
        for bytes in [ascii.as_bytes(), &binary[..]] {
            let (read, _) = read_stl(bytes).unwrap();
            assert_eq!(read.triangle_count(), 3);
            let mut streamed = Vec::new();
            stream_stl(
                Streamed::new(OneByte(bytes)),
                bytes.len() as u64,
                &mut Recentre::default(),
                &mut |t| streamed.push(t),
            )
            .unwrap();
            assert_eq!(sorted_bits(streamed), sorted_triangles(&read));
        }
    }
}

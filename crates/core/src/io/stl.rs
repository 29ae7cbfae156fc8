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

use std::io::Write;
use std::path::Path;

use glam::{Mat4, Vec3};

use super::shape_to_model::{build, Bind, ShapeSpec};
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
    binary_count(bytes).is_some_and(|n| 84 + 50 * n as u64 == bytes.len() as u64)
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
pub(crate) fn read_stl(bytes: &[u8]) -> Result<(Scene, Vec<String>), StlError> {
    if is_binary(bytes) {
        return read_binary(bytes);
    }
    if starts_with_solid(bytes) && !bytes.contains(&0) {
        return read_ascii(bytes).map_err(StlError::Line);
    }
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
    warnings: &mut Vec<String>,
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

fn read_binary(bytes: &[u8]) -> Result<(Scene, Vec<String>), StlError> {
    let mut warnings = Vec::new();
    let body = &bytes[84..];
    if body.is_empty() {
        return Err(StlError::Header(
            "the binary STL has no triangles (its count is 0)".into(),
        ));
    }
    let mut coords = Vec::with_capacity(body.len() / 50 * 9);
    for (r, rec) in body.chunks_exact(50).enumerate() {
        for k in 3..12 {
            let b = &rec[k * 4..k * 4 + 4];
            let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            if !v.is_finite() {
                return Err(StlError::Record {
                    record: r + 1,
                    message: format!("a vertex coordinate is not finite ({v})"),
                });
            }
            coords.push(v);
        }
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

/// Words of an ASCII STL with line numbers.
struct Words<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Line of the scanning position.
    at: usize,
    /// Line of the last word read (messages name it, also at the end of the file).
    line: usize,
}

impl<'a> Words<'a> {
    fn skip_blanks(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.at += 1;
            }
            self.pos += 1;
        }
    }

    fn next(&mut self) -> Option<&'a [u8]> {
        self.skip_blanks();
        let start = self.pos;
        while self.pos < self.bytes.len() && !self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if self.pos == start {
            return None;
        }
        self.line = self.at;
        Some(&self.bytes[start..self.pos])
    }

    /// The rest of the current line, trimmed (solid names).
    fn rest_of_line(&mut self) -> String {
        let start = self.pos;
        while self.pos < self.bytes.len() && self.bytes[self.pos] != b'\n' {
            self.pos += 1;
        }
        String::from_utf8_lossy(&self.bytes[start..self.pos])
            .trim()
            .to_string()
    }

    fn expect(&mut self, word: &str) -> Result<(), ParseError> {
        match self.next() {
            Some(w) if w.eq_ignore_ascii_case(word.as_bytes()) => Ok(()),
            Some(w) => Err(ParseError::new(
                self.line,
                format!("expected '{word}', found '{}'", shown(w)),
            )),
            None => Err(ParseError::new(
                self.line,
                format!("unexpected end of file: expected '{word}'"),
            )),
        }
    }

    fn number(&mut self, what: &str) -> Result<f32, ParseError> {
        let w = self.next();
        super::text::number(w, self.line, what)
    }
}

fn read_ascii(bytes: &[u8]) -> Result<(Scene, Vec<String>), ParseError> {
    let mut warnings = Vec::new();
    let mut models = Vec::new();
    let mut w = Words {
        bytes,
        pos: 0,
        at: 1,
        line: 1,
    };
    while let Some(word) = w.next() {
        if !word.eq_ignore_ascii_case(b"solid") {
            return Err(ParseError::new(
                w.line,
                format!("expected 'solid', found '{}'", shown(word)),
            ));
        }
        let solid_line = w.line;
        let name = w.rest_of_line();
        let mut coords: Vec<f32> = Vec::new();
        loop {
            let Some(word) = w.next() else {
                warnings.push(format!(
                    "the STL solid '{name}' (line {solid_line}) has no 'endsolid'"
                ));
                break;
            };
            if word.eq_ignore_ascii_case(b"endsolid") {
                w.rest_of_line();
                break;
            }
            if !word.eq_ignore_ascii_case(b"facet") {
                return Err(ParseError::new(
                    w.line,
                    format!("expected 'facet' or 'endsolid', found '{}'", shown(word)),
                ));
            }
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
            loop {
                match w.next() {
                    Some(v) if v.eq_ignore_ascii_case(b"vertex") => {
                        coords.push(w.number("a vertex's x")?);
                        coords.push(w.number("a vertex's y")?);
                        coords.push(w.number("a vertex's z")?);
                        corners += 1;
                    }
                    Some(v) if v.eq_ignore_ascii_case(b"endloop") => break,
                    Some(v) => {
                        return Err(ParseError::new(
                            w.line,
                            format!("expected 'vertex' or 'endloop', found '{}'", shown(v)),
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
        }
        if coords.is_empty() {
            warnings.push(format!(
                "the STL solid '{name}' (line {solid_line}) has no facets"
            ));
            continue;
        }
        models.push(model(name, coords, solid_line, &mut warnings)?);
    }
    if models.is_empty() {
        return Err(ParseError::new(
            w.line,
            "the STL file has no facets: nothing to read",
        ));
    }
    Ok((Scene { models }, warnings))
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
        let world: Vec<Vec3> = m
            .positions
            .iter()
            .map(|&p| m.transform.transform_point3(p))
            .collect();
        for [a, b, c] in super::outward_triangles(m) {
            let [a, b, c] = [a, b, c].map(|i| world.get(i as usize).copied().unwrap_or(Vec3::ZERO));
            let n = (b - a).cross(c - a).normalize_or_zero();
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

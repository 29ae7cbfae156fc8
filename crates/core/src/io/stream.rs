//! Streaming triangle readers for meshes too big to hold: PLY (ASCII, binary little and big
//! endian), STL (binary and ASCII) and OBJ hand each triangle's three positions to a callback
//! as they are read, through a buffered reader, never building a `Scene`.
//!
//! Memory: STL holds nothing; PLY and OBJ hold the vertex positions only (12 bytes a vertex,
//! about 6 bytes a triangle on a closed mesh), since their faces index them. Polygons are
//! fanned into triangles from their first corner. Positions are read as `f32` (doubles are
//! rounded once), so a position is the same bits wherever it is read again.

use std::fs::File;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use super::ply::Ty;
use super::ReadError;

/// One triangle: three positions, counter-clockwise seen from the front.
pub type Corners = [[f32; 3]; 3];

/// Buffer of the streaming reader: large enough that reads are a small part of the time.
const BUFFER: usize = 1 << 20;

/// Calls `triangle` with every triangle of the PLY, STL or OBJ file at `path` (the
/// extension says which; PLY and STL also by their first bytes), in file order.
pub fn for_each_triangle(path: &Path, triangle: &mut dyn FnMut(Corners)) -> Result<(), ReadError> {
    let file = File::open(path).map_err(|source| io_error(path, source))?;
    let mut r = BufReader::with_capacity(BUFFER, file);
    let head = r.fill_buf().map_err(|source| io_error(path, source))?;
    let kind = if head.starts_with(b"ply") {
        Kind::Ply
    } else {
        match super::Format::from_path(path) {
            Some(super::Format::Ply) => Kind::Ply,
            Some(super::Format::Stl) => Kind::Stl,
            Some(super::Format::Obj) => Kind::Obj,
            _ => {
                return Err(ReadError::Unsupported {
                    file: path.to_path_buf(),
                    message: "tiling streams PLY, STL and OBJ files only; convert it first \
                              (decimate FILE nogui -p 0 -o FILE.ply)"
                        .into(),
                })
            }
        }
    };
    let mut s = Stream {
        r,
        file: path.to_path_buf(),
        line: 0,
    };
    match kind {
        Kind::Ply => ply(&mut s, triangle),
        Kind::Stl => stl(&mut s, triangle),
        Kind::Obj => obj(&mut s, triangle),
    }
}

enum Kind {
    Ply,
    Stl,
    Obj,
}

fn io_error(path: &Path, source: std::io::Error) -> ReadError {
    ReadError::Io {
        file: path.to_path_buf(),
        source,
    }
}

/// A buffered file with the line count for messages.
struct Stream {
    r: BufReader<File>,
    file: PathBuf,
    line: usize,
}

impl Stream {
    fn syntax(&self, message: impl Into<String>) -> ReadError {
        ReadError::Syntax {
            file: self.file.clone(),
            line: self.line,
            message: message.into(),
        }
    }

    /// The next line without its end, or `None` at the end of the file.
    fn next_line(&mut self, buf: &mut String) -> Result<Option<()>, ReadError> {
        buf.clear();
        let mut bytes = Vec::new();
        let n = self
            .r
            .read_until(b'\n', &mut bytes)
            .map_err(|e| io_error(&self.file, e))?;
        if n == 0 {
            return Ok(None);
        }
        self.line += 1;
        let text = String::from_utf8_lossy(&bytes);
        buf.push_str(text.trim_end_matches(['\n', '\r']));
        Ok(Some(()))
    }

    fn exact(&mut self, out: &mut [u8], what: &str) -> Result<(), ReadError> {
        self.r.read_exact(out).map_err(|e| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                self.syntax(format!("the file ends inside {what}"))
            } else {
                io_error(&self.file, e)
            }
        })
    }
}

/// A PLY property: a scalar, or a list with its count and item types.
#[derive(Debug, Clone)]
struct Property {
    name: String,
    ty: Ty,
    list: Option<Ty>,
}

#[derive(Debug, Clone)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
}

fn ply(s: &mut Stream, triangle: &mut dyn FnMut(Corners)) -> Result<(), ReadError> {
    let mut line = String::new();
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if s.next_line(&mut line)?.is_none() {
            return Err(s.syntax("the header has no end_header"));
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["ply"] | [] => {}
            ["comment" | "obj_info", ..] => {}
            ["format", f, _] => {
                format = Some(match *f {
                    "ascii" => None,
                    "binary_little_endian" => Some(false),
                    "binary_big_endian" => Some(true),
                    other => return Err(s.syntax(format!("unknown PLY format '{other}'"))),
                })
            }
            ["element", name, count] => {
                let count = count
                    .parse()
                    .map_err(|_| s.syntax(format!("bad element count '{count}'")))?;
                elements.push(Element {
                    name: (*name).to_string(),
                    count,
                    properties: Vec::new(),
                });
            }
            ["property", "list", count, item, name] => {
                let (Some(c), Some(i)) = (Ty::parse(count), Ty::parse(item)) else {
                    return Err(s.syntax(format!("unknown list types '{count} {item}'")));
                };
                let prop = Property {
                    name: (*name).to_string(),
                    ty: i,
                    list: Some(c),
                };
                let e = elements
                    .last_mut()
                    .ok_or_else(|| s.syntax("a property before any element"))?;
                e.properties.push(prop);
            }
            ["property", ty, name] => {
                let ty = Ty::parse(ty).ok_or_else(|| s.syntax(format!("unknown type '{ty}'")))?;
                let e = elements
                    .last_mut()
                    .ok_or_else(|| s.syntax("a property before any element"))?;
                e.properties.push(Property {
                    name: (*name).to_string(),
                    ty,
                    list: None,
                });
            }
            ["end_header"] => break,
            _ => return Err(s.syntax(format!("unexpected header line '{line}'"))),
        }
    }
    let Some(big) = format else {
        return Err(s.syntax("the header has no format line"));
    };
    let mut positions: Vec<[f32; 3]> = Vec::new();
    for e in &elements {
        match e.name.as_str() {
            "vertex" => {
                let axis = |n: &str| {
                    e.properties
                        .iter()
                        .position(|p| p.name == n && p.list.is_none())
                };
                let (Some(x), Some(y), Some(z)) = (axis("x"), axis("y"), axis("z")) else {
                    return Err(s.syntax("element vertex has no x, y and z properties"));
                };
                positions.reserve_exact(e.count);
                read_element(s, e, big, &mut |values, _| {
                    positions.push([values[x] as f32, values[y] as f32, values[z] as f32]);
                    Ok(())
                })?;
            }
            "face" => {
                let Some(list) = e.properties.iter().position(|p| {
                    p.list.is_some() && (p.name == "vertex_indices" || p.name == "vertex_index")
                }) else {
                    return Err(s.syntax("element face has no vertex_indices list"));
                };
                let n = positions.len();
                read_element(s, e, big, &mut |_, lists| {
                    fan(&lists[list], n, &positions, triangle)
                })?;
            }
            _ => read_element(s, e, big, &mut |_, _| Ok(()))?,
        }
    }
    Ok(())
}

/// Fans polygon `corners` (vertex indices) into triangles.
fn fan(
    corners: &[f64],
    n: usize,
    positions: &[[f32; 3]],
    triangle: &mut dyn FnMut(Corners),
) -> Result<(), String> {
    let index = |v: f64| {
        if v >= 0.0 && (v as usize) < n && v.fract() == 0.0 {
            Ok(positions[v as usize])
        } else {
            Err(format!(
                "vertex index {v} is out of range (the file has {n} vertices)"
            ))
        }
    };
    if corners.len() < 3 {
        return Ok(());
    }
    let first = index(corners[0])?;
    for w in corners[1..].windows(2) {
        triangle([first, index(w[0])?, index(w[1])?]);
    }
    Ok(())
}

/// What a record hands on: its scalar values and its lists, indexed like the properties.
type Record<'a> = dyn FnMut(&[f64], &[Vec<f64>]) -> Result<(), String> + 'a;

/// Reads `e.count` records, handing `record` the scalar values (lists as 0) and the lists
/// (empty for scalars), both indexed like the properties.
fn read_element(
    s: &mut Stream,
    e: &Element,
    big: Option<bool>,
    record: &mut Record<'_>,
) -> Result<(), ReadError> {
    let mut values = vec![0.0; e.properties.len()];
    let mut lists: Vec<Vec<f64>> = vec![Vec::new(); e.properties.len()];
    let mut line = String::new();
    let mut bytes = [0u8; 8];
    for i in 0..e.count {
        match big {
            None => {
                if s.next_line(&mut line)?.is_none() {
                    return Err(s.syntax(format!("the file ends at {} {i} of {}", e.name, e.count)));
                }
                let mut words = line.split_whitespace();
                let mut next = |what: &str| -> Result<f64, ReadError> {
                    let w = words
                        .next()
                        .ok_or_else(|| s.syntax(format!("{} {i}: missing {what}", e.name)))?;
                    w.parse()
                        .map_err(|_| s.syntax(format!("{} {i}: '{w}' is not a number", e.name)))
                };
                for (k, p) in e.properties.iter().enumerate() {
                    lists[k].clear();
                    if p.list.is_some() {
                        let count = next(&p.name)?;
                        if !(0.0..=1e6).contains(&count) {
                            return Err(
                                s.syntax(format!("{} {i}: bad list length {count}", e.name))
                            );
                        }
                        for _ in 0..count as usize {
                            let v = next(&p.name)?;
                            lists[k].push(v);
                        }
                    } else {
                        values[k] = next(&p.name)?;
                    }
                }
            }
            Some(big) => {
                for (k, p) in e.properties.iter().enumerate() {
                    lists[k].clear();
                    if let Some(count_ty) = p.list {
                        s.exact(&mut bytes[..count_ty.size()], &e.name)?;
                        let count = count_ty.decode(&bytes, big);
                        if !(0.0..=1e6).contains(&count) {
                            return Err(
                                s.syntax(format!("{} {i}: bad list length {count}", e.name))
                            );
                        }
                        for _ in 0..count as usize {
                            s.exact(&mut bytes[..p.ty.size()], &e.name)?;
                            lists[k].push(p.ty.decode(&bytes, big));
                        }
                    } else {
                        s.exact(&mut bytes[..p.ty.size()], &e.name)?;
                        values[k] = p.ty.decode(&bytes, big);
                    }
                }
            }
        }
        record(&values, &lists).map_err(|m| s.syntax(format!("{} {i}: {m}", e.name)))?;
    }
    Ok(())
}

fn stl(s: &mut Stream, triangle: &mut dyn FnMut(Corners)) -> Result<(), ReadError> {
    let head = s.r.fill_buf().map_err(|e| io_error(&s.file, e))?;
    let ascii = head.starts_with(b"solid")
        && head[..head.len().min(512)]
            .windows(5)
            .any(|w| w == b"facet");
    if ascii {
        return stl_ascii(s, triangle);
    }
    let mut header = [0u8; 84];
    s.exact(&mut header, "the 84-byte binary STL header")?;
    let count = u32::from_le_bytes([header[80], header[81], header[82], header[83]]);
    let mut rec = [0u8; 50];
    for i in 0..count as usize {
        s.r.read_exact(&mut rec).map_err(|_| ReadError::Record {
            file: s.file.clone(),
            record: i + 1,
            message: format!("the file ends before the {count} triangles its header counts"),
        })?;
        let f = |k: usize| {
            let o = 12 + 4 * k;
            f32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]])
        };
        triangle([[f(0), f(1), f(2)], [f(3), f(4), f(5)], [f(6), f(7), f(8)]]);
    }
    Ok(())
}

fn stl_ascii(s: &mut Stream, triangle: &mut dyn FnMut(Corners)) -> Result<(), ReadError> {
    let mut line = String::new();
    let mut corners: Vec<[f32; 3]> = Vec::with_capacity(3);
    while s.next_line(&mut line)?.is_some() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vertex") => {
                let mut p = [0f32; 3];
                for v in &mut p {
                    let w = words.next().ok_or_else(|| s.syntax("vertex needs x y z"))?;
                    *v = w
                        .parse()
                        .map_err(|_| s.syntax(format!("'{w}' is not a number")))?;
                }
                corners.push(p);
            }
            Some("endloop") => {
                if corners.len() >= 3 {
                    for w in corners[1..].windows(2) {
                        triangle([corners[0], w[0], w[1]]);
                    }
                }
                corners.clear();
            }
            _ => {}
        }
    }
    Ok(())
}

fn obj(s: &mut Stream, triangle: &mut dyn FnMut(Corners)) -> Result<(), ReadError> {
    let mut line = String::new();
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let mut face: Vec<[f32; 3]> = Vec::new();
    while s.next_line(&mut line)?.is_some() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let mut p = [0f32; 3];
                for v in &mut p {
                    let w = words.next().ok_or_else(|| s.syntax("v needs x y z"))?;
                    *v = w
                        .parse()
                        .map_err(|_| s.syntax(format!("'{w}' is not a number")))?;
                }
                positions.push(p);
            }
            Some("f") => {
                face.clear();
                for w in words {
                    let first = w.split('/').next().unwrap_or("");
                    let i: i64 = first
                        .parse()
                        .map_err(|_| s.syntax(format!("'{w}' is not a vertex index")))?;
                    let n = positions.len() as i64;
                    let at = if i < 0 { n + i } else { i - 1 };
                    if !(0..n).contains(&at) {
                        return Err(s.syntax(format!(
                            "vertex index {i} is out of range ({n} vertices so far)"
                        )));
                    }
                    face.push(positions[at as usize]);
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

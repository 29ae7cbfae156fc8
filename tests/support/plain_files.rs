//! An independent reader of what our OBJ and binary PLY writers produce — a few lines of
//! parsing of the tests' own, sharing nothing with `decimate_core::io` — and the comparison
//! of what it reads with the scene that was written: every point (transforms applied),
//! every triangle (numbered across models, wound outward) and every per-vertex colour.

use decimate_core::io;
use decimate_core::mesh::{Attribute, Model, Scene};

/// A triangle mesh as a file holds it.
#[derive(Debug, Default, PartialEq)]
pub struct Plain {
    pub points: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
    /// Per-vertex colours as the file has them (0..=1 for OBJ, bytes / 255 for PLY).
    pub colors: Option<Vec<[f32; 3]>>,
}

/// Reads OBJ text: `v x y z [r g b]` and `f a b c` with `a`, `a/t` or `a/t/n` corners
/// (1-based); any other line but comments, `o`, `vt`, `usemtl` and `mtllib` is refused.
pub fn read_obj(text: &str) -> Result<Plain, String> {
    let mut plain = Plain::default();
    let mut colors = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let numbers = |words: std::str::SplitWhitespace| -> Result<Vec<f32>, String> {
            words
                .map(|w| {
                    w.parse::<f32>()
                        .map_err(|e| format!("line {}: {w}: {e}", n + 1))
                })
                .collect()
        };
        match words.next() {
            Some("v") => {
                let xs = numbers(words)?;
                match xs[..] {
                    [x, y, z] => plain.points.push([x, y, z]),
                    [x, y, z, r, g, b] => {
                        plain.points.push([x, y, z]);
                        colors.push([r, g, b]);
                    }
                    _ => return Err(format!("line {}: {line}", n + 1)),
                }
            }
            Some("f") => {
                let corners: Vec<u32> = words
                    .map(|w| {
                        let first = w.split('/').next().unwrap_or("");
                        match first.parse::<u32>() {
                            Ok(i) if i >= 1 => Ok(i - 1),
                            _ => Err(format!("line {}: corner {w}", n + 1)),
                        }
                    })
                    .collect::<Result<_, _>>()?;
                match corners[..] {
                    [a, b, c] => plain.triangles.push([a, b, c]),
                    _ => return Err(format!("line {}: not a triangle: {line}", n + 1)),
                }
            }
            None | Some("#" | "o" | "vt" | "usemtl" | "mtllib") => {}
            Some(_) => return Err(format!("line {}: {line}", n + 1)),
        }
    }
    // Colours on some points only (some models coloured): not compared.
    if !colors.is_empty() && colors.len() == plain.points.len() {
        plain.colors = Some(colors);
    }
    Ok(plain)
}

/// Reads a binary little-endian PLY with float x, y, z, optional uchar red, green, blue and
/// float s, t per vertex, and faces as a uchar count and int indices.
pub fn read_ply(bytes: &[u8]) -> Result<Plain, String> {
    let end = b"end_header\n";
    let at = bytes
        .windows(end.len())
        .position(|w| w == end)
        .ok_or("no end_header")?;
    let header = std::str::from_utf8(&bytes[..at]).map_err(|e| e.to_string())?;
    let mut body = &bytes[at + end.len()..];
    let (vertices, faces, properties) = ply_header(header)?;
    let mut take = |n: usize| -> Result<&[u8], String> {
        if body.len() < n {
            return Err("the file ends early".into());
        }
        let (head, rest) = body.split_at(n);
        body = rest;
        Ok(head)
    };
    let mut plain = Plain::default();
    let colored = properties.iter().any(|p| p == "uchar red");
    let mut colors = Vec::new();
    for _ in 0..vertices {
        let (mut point, mut color) = ([0.0f32; 3], [0.0f32; 3]);
        for p in &properties {
            match p.as_str() {
                "float x" | "float y" | "float z" | "float s" | "float t" => {
                    let b = take(4)?;
                    let x = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                    match p.as_str() {
                        "float x" => point[0] = x,
                        "float y" => point[1] = x,
                        "float z" => point[2] = x,
                        _ => {}
                    }
                }
                // Far coordinates are written as doubles; compared here as f32.
                "double x" | "double y" | "double z" => {
                    let b: [u8; 8] = take(8)?.try_into().map_err(|_| "short double")?;
                    let k = ["double x", "double y", "double z"]
                        .iter()
                        .position(|q| q == p)
                        .unwrap_or(0);
                    point[k] = f64::from_le_bytes(b) as f32;
                }
                "uchar red" | "uchar green" | "uchar blue" => {
                    let k = ["uchar red", "uchar green", "uchar blue"]
                        .iter()
                        .position(|q| q == p)
                        .unwrap_or(0);
                    color[k] = f32::from(take(1)?[0]) / 255.0;
                }
                other => return Err(format!("property {other}")),
            }
        }
        plain.points.push(point);
        colors.push(color);
    }
    for _ in 0..faces {
        if take(1)?[0] != 3 {
            return Err("a face that is not a triangle".into());
        }
        let mut t = [0u32; 3];
        for v in &mut t {
            let b = take(4)?;
            let i = i32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            *v = u32::try_from(i).map_err(|_| format!("index {i}"))?;
        }
        plain.triangles.push(t);
    }
    if !body.is_empty() {
        return Err(format!("{} bytes after the faces", body.len()));
    }
    if colored {
        plain.colors = Some(colors);
    }
    Ok(plain)
}

/// The two formats the reader reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Obj,
    Ply,
}

/// A PLY header's vertex and face counts and vertex properties ("float x", ...).
fn ply_header(header: &str) -> Result<(usize, usize, Vec<String>), String> {
    let (mut vertices, mut faces) = (0usize, 0usize);
    let mut properties: Vec<String> = Vec::new();
    let mut element = "";
    for line in header.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words[..] {
            ["element", "vertex", n] => {
                vertices = n.parse().map_err(|_| format!("count {n}"))?;
                element = "vertex";
            }
            ["element", "face", n] => {
                faces = n.parse().map_err(|_| format!("count {n}"))?;
                element = "face";
            }
            ["property", kind, name] if element == "vertex" => {
                properties.push(format!("{kind} {name}"));
            }
            ["property", "list", "uchar", "int", "vertex_indices"] if element == "face" => {}
            ["ply"] | ["format", "binary_little_endian", "1.0"] | ["comment", ..] => {}
            _ => return Err(format!("header line {line:?}")),
        }
    }
    Ok((vertices, faces, properties))
}

/// A point relative to a model's origin in the file's frame, as f32: the origin plus the
/// value each f32 coordinate's shortest decimal stands for (docs/design.md#far-coordinates).
fn in_file_frame(local: [f32; 3], origin: [f64; 3]) -> [f32; 3] {
    std::array::from_fn(|k| {
        if origin[k] == 0.0 {
            return local[k];
        }
        let decimal: f64 = local[k].to_string().parse().unwrap_or(f64::from(local[k]));
        (origin[k] + decimal) as f32
    })
}

/// What a writer should have written for `scene`: the points with each model's transform
/// applied and its origin added, triangles numbered on across models and wound the other way under a mirroring
/// transform, and the per-vertex colours where every model has them (as bytes for PLY,
/// missing ones the model's diffuse colour; as they are for OBJ, where each model's count
/// matches its points).
pub fn expected(scene: &Scene, format: Format) -> Plain {
    let mut plain = Plain::default();
    let colored = |m: &Model| match &m.colors {
        Some(Attribute::PerVertex(c)) => format == Format::Ply || c.len() == m.positions.len(),
        _ => false,
    };
    let all_colored = !scene.models.is_empty() && scene.models.iter().all(colored);
    let mut colors = Vec::new();
    for m in &scene.models {
        let base = plain.points.len() as u32;
        let mirrored = m.transform.determinant() < 0.0;
        for (i, p) in m.positions.iter().enumerate() {
            let local = m.transform.transform_point3(*p).to_array();
            plain.points.push(in_file_frame(local, m.origin.to_array()));
            if let Some(Attribute::PerVertex(c)) = &m.colors {
                let c = c.get(i).copied().unwrap_or(m.diffuse);
                colors.push(match format {
                    Format::Obj => c,
                    Format::Ply => {
                        c.map(|x| f32::from((x.clamp(0.0, 1.0) * 255.0).round() as u8) / 255.0)
                    }
                });
            }
        }
        for &[a, b, c] in &m.triangles {
            let t = if mirrored { [a, c, b] } else { [a, b, c] };
            plain.triangles.push(t.map(|v| v + base));
        }
    }
    if all_colored {
        plain.colors = Some(colors);
    }
    plain
}

/// Writes `scene` with our writer for `format`, reads it back with this module's reader
/// and compares: the first difference, as a message.
pub fn round_trip(scene: &Scene, format: Format) -> Result<(), String> {
    let mut bytes = Vec::new();
    let read = match format {
        Format::Obj => {
            io::obj::write_obj_to(&mut bytes, scene).map_err(|e| e.to_string())?;
            read_obj(&String::from_utf8_lossy(&bytes))
        }
        Format::Ply => {
            io::ply::write_ply_to(&mut bytes, scene).map_err(|e| e.to_string())?;
            read_ply(&bytes)
        }
    };
    let read = read.map_err(|e| format!("{format:?} as written does not read: {e}"))?;
    compare(&read, &expected(scene, format)).map_err(|e| format!("{format:?} as written: {e}"))
}

/// Compares what was read with what was expected, exactly. Reports the first difference.
pub fn compare(read: &Plain, want: &Plain) -> Result<(), String> {
    if read.points.len() != want.points.len() {
        return Err(format!(
            "{} points, not {}",
            read.points.len(),
            want.points.len()
        ));
    }
    let same = |a: &[f32; 3], b: &[f32; 3]| {
        (0..3).all(|k| a[k] == b[k] || (a[k].is_nan() && b[k].is_nan()))
    };
    if let Some(i) = (0..want.points.len()).find(|&i| !same(&read.points[i], &want.points[i])) {
        return Err(format!(
            "point {i}: {:?}, not {:?}",
            read.points[i], want.points[i]
        ));
    }
    if read.triangles.len() != want.triangles.len() {
        return Err(format!(
            "{} triangles, not {}",
            read.triangles.len(),
            want.triangles.len()
        ));
    }
    if let Some(i) = (0..want.triangles.len()).find(|&i| read.triangles[i] != want.triangles[i]) {
        return Err(format!(
            "triangle {i}: {:?}, not {:?}",
            read.triangles[i], want.triangles[i]
        ));
    }
    match (&read.colors, &want.colors) {
        (None, None) => Ok(()),
        (Some(r), Some(w)) => match (0..w.len()).find(|&i| r[i] != w[i]) {
            Some(i) => Err(format!("colour {i}: {:?}, not {:?}", r[i], w[i])),
            None => Ok(()),
        },
        (r, w) => Err(format!("colours {}, expected {}", r.is_some(), w.is_some())),
    }
}

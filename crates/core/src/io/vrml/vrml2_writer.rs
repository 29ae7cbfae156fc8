//! VRML 2.0 output: one `Transform { children [ Shape { ... IndexedFaceSet ... } ] }` per model.
//!
//! The model's transform is written as translation / rotation / scale when it decomposes
//! exactly that way (positive scale, no shear); otherwise it is baked into the coordinates
//! (normals by the inverse transpose, and triangle winding reversed for a mirroring transform
//! so faces keep facing outwards). Numbers use Rust's shortest round-trip formatting of `f32`,
//! written straight into the buffered writer (no allocation per number). Colours and normals
//! keep their binding: per vertex (`colorPerVertex TRUE`, indexed by `coordIndex`) or per face.
//! Texture coordinates are per vertex (`texCoord`, indexed by `coordIndex`), the texture's
//! image an `ImageTexture` with the URL as the model holds it (callers rebase relative names
//! for the output's folder first: `io::rebase_textures`).

use std::collections::HashSet;
use std::io::{self, Write};

use glam::{Mat3, Mat4, Quat, Vec3};

use crate::mesh::{Attribute, Model, Scene};

/// True for names a VRML 2.0 reader accepts after DEF (a conservative subset).
pub fn is_valid_vrml_name(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !matches!(
            name,
            "DEF"
                | "USE"
                | "ROUTE"
                | "TO"
                | "IS"
                | "PROTO"
                | "EXTERNPROTO"
                | "NULL"
                | "TRUE"
                | "FALSE"
        )
}

/// Splits `m` into translation, rotation and positive scale if that reproduces it.
fn decompose(m: &Mat4) -> Option<(Vec3, Quat, Vec3)> {
    let (s, r, t) = m.to_scale_rotation_translation();
    if !(s.is_finite() && r.is_finite() && t.is_finite()) || s.min_element() <= 0.0 {
        return None;
    }
    let back = Mat4::from_scale_rotation_translation(s, r, t);
    let size = m
        .to_cols_array()
        .iter()
        .fold(1.0f32, |a, &v| a.max(v.abs()));
    back.abs_diff_eq(*m, 1e-6 * size).then_some((t, r, s))
}

/// An SFString: quoted, with `"` and `\\` escaped and control characters (which no reader
/// expects inside a URL) dropped.
fn write_string(w: &mut impl Write, s: &str) -> io::Result<()> {
    w.write_all(b"\"")?;
    for c in s.chars().filter(|c| !c.is_control()) {
        if matches!(c, '"' | '\\') {
            w.write_all(b"\\")?;
        }
        write!(w, "{c}")?;
    }
    w.write_all(b"\"")
}

fn vec(w: &mut (impl Write + ?Sized), v: Vec3) -> io::Result<()> {
    write!(w, "{} {} {}", v.x, v.y, v.z)
}

fn write_list<T: Copy>(
    w: &mut impl Write,
    values: &[T],
    each: impl Fn(&mut dyn Write, T) -> io::Result<()>,
) -> io::Result<()> {
    writeln!(w, "[")?;
    for &v in values {
        w.write_all(b"          ")?;
        each(w, v)?;
        w.write_all(b",\n")?;
    }
    w.write_all(b"        ]")
}

/// Writes the whole scene as VRML 2.0 to `w`.
pub fn write_vrml2_to(w: &mut impl Write, scene: &Scene) -> io::Result<()> {
    writeln!(w, "#VRML V2.0 utf8")?;
    writeln!(w, "# written by decimate {}", env!("CARGO_PKG_VERSION"))?;
    let mut names = HashSet::new();
    for model in &scene.models {
        // A far model stands in a Transform that moves it to its origin, written in full.
        let far = model.origin != glam::DVec3::ZERO;
        if far {
            let o = model.origin;
            writeln!(w, "\nTransform {{\n  translation {} {} {}", o.x, o.y, o.z)?;
            writeln!(w, "  children [")?;
        }
        write_model(w, model, &mut names)?;
        if far {
            writeln!(w, "  ]\n}}")?;
        }
    }
    w.flush()
}

fn write_model(w: &mut impl Write, m: &Model, names: &mut HashSet<String>) -> io::Result<()> {
    let parts = decompose(&m.transform);
    // Baking: world positions, normals by the inverse transpose, winding kept facing out.
    let bake = if parts.is_none() {
        Some(m.transform)
    } else {
        None
    };

    writeln!(w)?;
    writeln!(w, "Transform {{")?;
    if let Some(parts) = parts {
        write_transform(w, parts)?;
    }
    writeln!(w, "  children [")?;
    if is_valid_vrml_name(&m.name) && names.insert(m.name.clone()) {
        writeln!(w, "    DEF {} Shape {{", m.name)?;
    } else {
        writeln!(w, "    Shape {{")?;
    }
    write_appearance(w, m)?;
    writeln!(w, "      geometry IndexedFaceSet {{")?;
    writeln!(w, "        ccw TRUE")?;
    writeln!(
        w,
        "        solid {}",
        if m.solid { "TRUE" } else { "FALSE" }
    )?;
    if let Some(a) = m.crease_angle {
        writeln!(w, "        creaseAngle {a}")?;
    }
    write_coordinates(w, m, bake)?;
    write_attributes(w, m, bake)?;
    writeln!(w, "      }}")?;
    writeln!(w, "    }}")?;
    writeln!(w, "  ]")?;
    writeln!(w, "}}")
}

/// The Transform's fields that differ from the identity.
fn write_transform(w: &mut impl Write, (t, r, s): (Vec3, Quat, Vec3)) -> io::Result<()> {
    if t != Vec3::ZERO {
        w.write_all(b"  translation ")?;
        vec(w, t)?;
        writeln!(w)?;
    }
    let (axis, angle) = r.to_axis_angle();
    if angle != 0.0 && axis.is_finite() {
        w.write_all(b"  rotation ")?;
        vec(w, axis)?;
        writeln!(w, " {angle}")?;
    }
    if s != Vec3::ONE {
        w.write_all(b"  scale ")?;
        vec(w, s)?;
        writeln!(w)?;
    }
    Ok(())
}

/// The Appearance: diffuse colour, and the texture with its wrapping.
fn write_appearance(w: &mut impl Write, m: &Model) -> io::Result<()> {
    let [r, g, b] = m.diffuse;
    write!(
        w,
        "      appearance Appearance {{ material Material {{ diffuseColor {r} {g} {b} }}"
    )?;
    if let Some(url) = &m.texture {
        write!(w, " texture ImageTexture {{ url ")?;
        write_string(w, url)?;
        for (field, repeat) in ["repeatS", "repeatT"].iter().zip(m.texture_repeat) {
            if !repeat {
                write!(w, " {field} FALSE")?;
            }
        }
        write!(w, " }}")?;
    }
    writeln!(w, " }}")?;
    Ok(())
}

/// The points (baked into world space when `bake` is set) and the triangles.
fn write_coordinates(w: &mut impl Write, m: &Model, bake: Option<Mat4>) -> io::Result<()> {
    let flip = bake.is_some_and(|t| t.determinant() < 0.0);
    w.write_all(b"        coord Coordinate { point ")?;
    match bake {
        Some(t) => write_list(w, &m.positions, |w, p| vec(w, t.transform_point3(p)))?,
        None => write_list(w, &m.positions, |w, p| vec(w, p))?,
    }
    w.write_all(b" }\n        coordIndex [\n")?;
    for t in &m.triangles {
        let [a, b, c] = if flip { [t[0], t[2], t[1]] } else { *t };
        writeln!(w, "          {a}, {b}, {c}, -1,")?;
    }
    w.write_all(b"        ]\n")?;
    Ok(())
}

/// Colours, texture coordinates and normals (turned into world space when `bake` is set).
fn write_attributes(w: &mut impl Write, m: &Model, bake: Option<Mat4>) -> io::Result<()> {
    let normal_matrix = bake.map(|t| Mat3::from_mat4(t).inverse().transpose());
    if let Some(colors) = &m.colors {
        w.write_all(b"        color Color { color ")?;
        write_list(w, colors.values(), |w, [r, g, b]| write!(w, "{r} {g} {b}"))?;
        w.write_all(b" }\n")?;
        let per_vertex = matches!(colors, Attribute::PerVertex(_));
        writeln!(
            w,
            "        colorPerVertex {}",
            if per_vertex { "TRUE" } else { "FALSE" }
        )?;
    }
    // Texture coordinates per vertex: without a texCoordIndex, coordIndex indexes them.
    if let Some(t) = m
        .texcoords
        .as_ref()
        .filter(|t| t.len() == m.positions.len())
    {
        w.write_all(b"        texCoord TextureCoordinate { point ")?;
        write_list(w, t, |w, [u, v]| write!(w, "{u} {v}"))?;
        w.write_all(b" }\n")?;
    }
    if let Some(normals) = &m.normals {
        w.write_all(b"        normal Normal { vector ")?;
        match normal_matrix {
            Some(nm) => write_list(w, normals.values(), |w, n| {
                vec(w, (nm * n).normalize_or_zero())
            })?,
            None => write_list(w, normals.values(), |w, n| vec(w, n))?,
        }
        w.write_all(b" }\n")?;
        let per_vertex = matches!(normals, Attribute::PerVertex(_));
        writeln!(
            w,
            "        normalPerVertex {}",
            if per_vertex { "TRUE" } else { "FALSE" }
        )?;
    }
    Ok(())
}

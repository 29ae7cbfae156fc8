//! Turning one parsed shape (polygons over a coordinate array, with bound colours and
//! normals) into a [`Model`]: index validation, compaction of the coordinate array to the
//! vertices the shape uses, triangulation, orientation and attribute alignment.
//!
//! Attribute bindings are normalised by the readers into [`Bind`]: per face (one value index
//! per polygon) or per corner (one value index per polygon corner). Per-corner values cannot be
//! stored exactly per vertex when a vertex has different values in different faces; the value
//! at the vertex's first use in the file wins (documented behaviour, never an error).
//! A polygon's per-face value goes to every triangle cut from it.

use crate::io::warning::{Warning, WarningKind};
use std::collections::HashMap;

use glam::{Mat4, Vec3};

use super::text::{PResult, ParseError};
use super::triangulate::{triangulate, EarBuffers};
use crate::mesh::{Attribute, Model};

/// How an attribute's values (flat, three floats each) are bound to a shape's polygons.
#[derive(Debug, Clone)]
pub enum Bind<'a> {
    None,
    /// `index[f]` is the value of polygon `f`.
    PerFace {
        values: &'a [f32],
        index: Vec<u32>,
    },
    /// `index[k]` is the value of the `k`-th polygon corner (over all polygons in order).
    PerCorner {
        values: &'a [f32],
        index: Vec<u32>,
    },
}

/// Texture coordinates of a shape: `values` flat (u v), `index[k]` the pair of the `k`-th
/// polygon corner (a per-vertex binding repeats the coordinate indices).
#[derive(Debug, Clone)]
pub struct TexCoords<'a> {
    pub values: &'a [f32],
    pub index: Vec<u32>,
}

/// One shape to build: polygons as corner lists over `coords` (flat x y z).
pub struct ShapeSpec<'a> {
    pub name: String,
    pub transform: Mat4,
    pub coords: &'a [f32],
    /// Corner coordinate indices of all polygons, concatenated.
    pub corners: Vec<u32>,
    /// End (exclusive) of each polygon in `corners`.
    pub ends: Vec<u32>,
    pub colors: Bind<'a>,
    pub normals: Bind<'a>,
    /// Texture coordinates: a corner whose vertex already has other coordinates gets a vertex
    /// of its own, so seams are kept.
    pub texcoords: Option<TexCoords<'a>>,
    pub ccw: bool,
    pub solid: bool,
    pub crease_angle: Option<f32>,
    pub diffuse: [f32; 3],
    /// Line of the index field, for errors.
    pub line: usize,
    /// Which field held the indices, for errors ("coordIndex", "numVertices"...).
    pub index_field: &'static str,
}

fn value3(values: &[f32], i: u32) -> Option<[f32; 3]> {
    let i = i as usize * 3;
    values.get(i..i + 3).map(|s| [s[0], s[1], s[2]])
}

/// Checks that every index of a binding is in range; a short array drops the attribute with a
/// warning rather than failing the file.
/// The warning for a shape's faces with fewer than 3 corners.
fn degenerate_faces(name: &str, count: usize) -> Warning {
    Warning::new(
        WarningKind::SkippedFaces,
        format!(
            "{}: {count} face(s) with fewer than 3 corners skipped",
            label(name)
        ),
    )
    .times(count)
}

/// A model's name for messages: an unnamed one (a binary STL's empty header) is said so.
fn label(name: &str) -> &str {
    match name.trim() {
        "" => "an unnamed model",
        _ => name,
    }
}

/// An index as the file wrote it: a negative one (read into 32 bits) is shown negative,
/// not as 4294967295.
fn signed(index: u32) -> i32 {
    index as i32
}

fn check_bind<'a>(
    bind: Bind<'a>,
    what: &str,
    spec_name: &str,
    warnings: &mut Vec<Warning>,
) -> Bind<'a> {
    let (values, index) = match &bind {
        Bind::None => return bind,
        Bind::PerFace { values, index } | Bind::PerCorner { values, index } => (values, index),
    };
    let count = (values.len() / 3) as u32;
    if let Some(bad) = index.iter().find(|&&i| i >= count) {
        warnings.push(Warning::new(
            WarningKind::SkippedAttribute,
            format!(
                "{}: {what} index {} is out of range ({count} values); {what} ignored",
                label(spec_name),
                signed(*bad)
            ),
        ));
        return Bind::None;
    }
    bind
}

/// Vertex index map old → new, dense for shapes that use much of the array, hashed for small
/// shapes over a big shared array (so many small shapes stay linear overall).
enum Remap {
    Dense(Vec<u32>),
    Sparse(HashMap<(u64, [u32; 3]), u32>),
}

impl Remap {
    /// `old`: a point index, or a point index and a texture coordinate index and the
    /// corner's colour bits (sparse only).
    fn get_or_insert(&mut self, old: (u64, [u32; 3]), next: u32) -> (u32, bool) {
        match self {
            Self::Dense(v) => {
                let slot = &mut v[old.0 as usize];
                if *slot == u32::MAX {
                    *slot = next;
                    (next, true)
                } else {
                    (*slot, false)
                }
            }
            Self::Sparse(m) => {
                let mut inserted = false;
                let v = *m.entry(old).or_insert_with(|| {
                    inserted = true;
                    next
                });
                (v, inserted)
            }
        }
    }
}

/// Builds the model; out-of-range coordinate indices and non-finite used coordinates are errors.
pub fn build(spec: ShapeSpec<'_>, warnings: &mut Vec<Warning>) -> PResult<Model> {
    let ShapeSpec {
        name,
        transform,
        coords,
        corners,
        ends,
        colors,
        normals,
        texcoords,
        ccw,
        solid,
        crease_angle,
        diffuse,
        line,
        index_field,
    } = spec;
    check_corners(&corners, coords.len() / 3, line, index_field)?;
    let colors = check_bind(colors, "colour", &name, warnings);
    let normals = check_bind(normals, "normal", &name, warnings);
    let texcoords = texcoords.filter(|t| texcoords_fit(t, corners.len(), &name, warnings));
    let binds = Binds {
        colors: &colors,
        normals: &normals,
        texcoords: texcoords.as_ref(),
        diffuse,
    };

    // Each corner's point index is replaced by its vertex's, in place: no second array.
    let mut local = corners;
    let vertices = make_vertices(&mut local, coords, &binds, line, index_field)?;
    // A shape of triangles only (most files) takes its triangles from the corners as they
    // are; polygons are cut.
    let only_triangles = (ends.iter().enumerate()).all(|(f, &end)| end as usize == 3 * (f + 1));
    let mut faces = cut_faces(&local, &ends, &vertices.positions, &binds, only_triangles);
    if only_triangles {
        faces.triangles = into_triples(local);
    } else {
        drop(local);
    }
    let Faces {
        mut triangles,
        colors: fcolors,
        normals: fnormals,
        degenerate,
    } = faces;
    if degenerate > 0 {
        warnings.push(degenerate_faces(&name, degenerate));
    }
    if !ccw {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    let colors = attribute(&colors, fcolors, vertices.colors);
    let normals = attribute(&normals, fnormals, vertices.normals);
    Ok(Model {
        name,
        transform,
        origin: glam::DVec3::ZERO,
        positions: vertices.positions,
        triangles,
        colors,
        normals,
        texcoords: texcoords.map(|_| vertices.texcoords),
        texture: None,
        texture_repeat: [true; 2],
        material: None,
        diffuse,
        crease_angle,
        solid,
        instance: None,
    })
}

/// Every corner indexes one of the `npoints` points.
fn check_corners(corners: &[u32], npoints: usize, line: usize, index_field: &str) -> PResult<()> {
    match corners.iter().find(|&&c| c as usize >= npoints) {
        Some(&bad) => Err(ParseError::new(
            line,
            format!(
                "index {} in '{index_field}' is out of range: the coordinates have {npoints} points",
                signed(bad)
            ),
        )),
        None => Ok(()),
    }
}

/// The attribute a binding gives: the per-face values or the per-vertex ones.
fn attribute<T>(bind: &Bind<'_>, per_face: Vec<T>, per_vertex: Vec<T>) -> Option<Attribute<T>> {
    match bind {
        Bind::None => None,
        Bind::PerFace { .. } => Some(Attribute::PerFace(per_face)),
        Bind::PerCorner { .. } => Some(Attribute::PerVertex(per_vertex)),
    }
}

/// A shape's checked bindings, and the colour of corners and faces without one.
struct Binds<'a, 'b> {
    colors: &'a Bind<'b>,
    normals: &'a Bind<'b>,
    texcoords: Option<&'a TexCoords<'b>>,
    diffuse: [f32; 3],
}

/// The vertices of a shape: positions and their per-corner attributes.
struct Vertices {
    positions: Vec<Vec3>,
    colors: Vec<[f32; 3]>,
    normals: Vec<Vec3>,
    texcoords: Vec<[f32; 2]>,
}

/// One vertex per distinct point (per point, texture coordinate pair and colour when there
/// are texture coordinates or per-corner colours: the sides of a seam, `mesh::seams`); each
/// corner's point index in `local` becomes its vertex's.
fn make_vertices(
    local: &mut [u32],
    coords: &[f32],
    binds: &Binds<'_, '_>,
    line: usize,
    index_field: &str,
) -> PResult<Vertices> {
    let npoints = coords.len() / 3;
    let (colors, normals, texcoords, diffuse) =
        (binds.colors, binds.normals, binds.texcoords, binds.diffuse);
    let corner_colors = match colors {
        Bind::PerCorner { values, index } => Some((*values, index.as_slice())),
        _ => None,
    };
    let mut remap = if texcoords.is_some() || corner_colors.is_some() || local.len() * 4 < npoints {
        Remap::Sparse(HashMap::with_capacity(local.len()))
    } else {
        Remap::Dense(vec![u32::MAX; npoints])
    };
    let mut positions: Vec<Vec3> = Vec::new();
    let mut vcolors: Vec<[f32; 3]> = Vec::new();
    let mut vnormals: Vec<Vec3> = Vec::new();
    let mut vtexcoords: Vec<[f32; 2]> = Vec::new();
    for (k, corner) in local.iter_mut().enumerate() {
        let c = *corner;
        // With texture coordinates a vertex is a (point, coordinate pair) pair; with
        // per-corner colours, also a colour.
        let point = match texcoords {
            Some(t) => u64::from(c) | u64::from(t.index[k]) << 32,
            None => u64::from(c),
        };
        let colour = corner_colors.map_or([0; 3], |(values, index)| {
            let rgb = index
                .get(k)
                .and_then(|&i| value3(values, i))
                .unwrap_or(diffuse);
            rgb.map(|x| (x + 0.0).to_bits())
        });
        let key = (point, colour);
        let (v, fresh) = remap.get_or_insert(key, positions.len() as u32);
        if fresh {
            let i = c as usize * 3;
            let p = Vec3::new(coords[i], coords[i + 1], coords[i + 2]);
            if !p.is_finite() {
                return Err(ParseError::new(
                    line,
                    format!("coordinate {c} used by '{index_field}' is not a finite number"),
                ));
            }
            positions.push(p);
            if let Bind::PerCorner { values, index } = colors {
                vcolors.push(
                    index
                        .get(k)
                        .and_then(|&i| value3(values, i))
                        .unwrap_or(diffuse),
                );
            }
            if let Bind::PerCorner { values, index } = normals {
                let n = index
                    .get(k)
                    .and_then(|&i| value3(values, i))
                    .unwrap_or([0.0; 3]);
                vnormals.push(Vec3::from(n));
            }
            if let Some(t) = texcoords {
                let i = t.index[k] as usize * 2;
                vtexcoords.push([t.values[i], t.values[i + 1]]);
            }
        }
        *corner = v;
    }

    Ok(Vertices {
        positions,
        colors: vcolors,
        normals: vnormals,
        texcoords: vtexcoords,
    })
}

/// A shape's triangles (polygons cut by ear clipping), their per-face attributes, and how
/// many faces had fewer than 3 corners.
struct Faces {
    triangles: Vec<[u32; 3]>,
    colors: Vec<[f32; 3]>,
    normals: Vec<Vec3>,
    degenerate: usize,
}

/// Cuts the faces (`ends` over the corners' vertices `local`) into triangles; a shape of
/// triangles only (`only_triangles`) leaves its triangles to the caller.
fn cut_faces(
    local: &[u32],
    ends: &[u32],
    positions: &[Vec3],
    binds: &Binds<'_, '_>,
    only_triangles: bool,
) -> Faces {
    let (colors, normals, diffuse) = (binds.colors, binds.normals, binds.diffuse);
    let mut triangles: Vec<[u32; 3]> = if only_triangles {
        Vec::new()
    } else {
        Vec::with_capacity(local.len().saturating_sub(ends.len() * 2))
    };
    let mut fcolors: Vec<[f32; 3]> = Vec::new();
    let mut fnormals: Vec<Vec3> = Vec::new();
    let mut scratch = EarBuffers::default();
    let mut pts: Vec<Vec3> = Vec::new();
    let mut cut: Vec<[u32; 3]> = Vec::new();
    let mut degenerate = 0usize;
    let mut start = 0usize;
    for (f, &end) in ends.iter().enumerate() {
        let end = end as usize;
        let face = &local[start..end];
        let before = triangles.len();
        match face.len() {
            0..=2 => degenerate += 1,
            3 if only_triangles => {}
            3 => triangles.push([face[0], face[1], face[2]]),
            _ => {
                pts.clear();
                pts.extend(face.iter().map(|&v| positions[v as usize]));
                cut.clear();
                triangulate(&pts, &mut cut, &mut scratch);
                triangles.extend(cut.iter().map(|t| {
                    [
                        face[t[0] as usize],
                        face[t[1] as usize],
                        face[t[2] as usize],
                    ]
                }));
            }
        }
        let made = if only_triangles {
            1
        } else {
            triangles.len() - before
        };
        if let Bind::PerFace { values, index } = colors {
            let c = index
                .get(f)
                .and_then(|&i| value3(values, i))
                .unwrap_or(diffuse);
            fcolors.extend(std::iter::repeat_n(c, made));
        }
        if let Bind::PerFace { values, index } = normals {
            let n = index
                .get(f)
                .and_then(|&i| value3(values, i))
                .unwrap_or([0.0; 3]);
            fnormals.extend(std::iter::repeat_n(Vec3::from(n), made));
        }
        start = end;
    }
    Faces {
        triangles,
        colors: fcolors,
        normals: fnormals,
        degenerate,
    }
}

/// Flat corner indices, three a triangle, as triangles: the same allocation when its size
/// allows (`len` and capacity multiples of three), else a copy.
fn into_triples(flat: Vec<u32>) -> Vec<[u32; 3]> {
    if !(flat.len().is_multiple_of(3) && flat.capacity().is_multiple_of(3)) {
        return flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    }
    let mut flat = std::mem::ManuallyDrop::new(flat);
    let (ptr, len, capacity) = (flat.as_mut_ptr(), flat.len(), flat.capacity());
    // SAFETY: the allocation is `flat`'s own (never freed by it, being ManuallyDrop), and
    // `[u32; 3]` has `u32`'s alignment and three times its size: `len / 3` triples are
    // initialised and `capacity / 3` of them make exactly the layout it was allocated with.
    unsafe { Vec::from_raw_parts(ptr.cast::<[u32; 3]>(), len / 3, capacity / 3) }
}

/// True when every corner has a texture coordinate pair in range and every used pair is
/// finite; otherwise the shape's texture coordinates are dropped with a warning (the shape
/// itself is still read).
fn texcoords_fit(
    t: &TexCoords<'_>,
    corners: usize,
    name: &str,
    warnings: &mut Vec<Warning>,
) -> bool {
    let count = t.values.len() / 2;
    let problem = if t.index.len() < corners {
        Some(format!(
            "{} texture coordinate indices for {corners} polygon corners",
            t.index.len()
        ))
    } else if let Some(bad) = t.index[..corners].iter().find(|&&i| i as usize >= count) {
        Some(format!(
            "texture coordinate index {} is out of range ({count} pairs)",
            signed(*bad)
        ))
    } else {
        t.index[..corners]
            .iter()
            .find(|&&i| {
                !(t.values[i as usize * 2].is_finite() && t.values[i as usize * 2 + 1].is_finite())
            })
            .map(|bad| format!("texture coordinate {bad} is not a finite pair"))
    };
    match problem {
        Some(p) => {
            warnings.push(Warning::new(
                WarningKind::SkippedAttribute,
                format!("{}: {p}; texture coordinates ignored", label(name)),
            ));
            false
        }
        None => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_corners_become_triangles_in_place_or_copied() {
        let mut flat = Vec::with_capacity(6);
        flat.extend([0, 1, 2, 2, 1, 3]);
        let at = flat.as_ptr() as usize;
        let triangles = into_triples(flat);
        assert_eq!(triangles, vec![[0, 1, 2], [2, 1, 3]]);
        assert_eq!(triangles.as_ptr() as usize, at, "the same allocation");
        // A capacity that is no multiple of three is copied.
        let mut flat = Vec::with_capacity(7);
        flat.extend([4, 5, 6]);
        assert_eq!(into_triples(flat), vec![[4, 5, 6]]);
        assert!(into_triples(Vec::new()).is_empty());
    }
}

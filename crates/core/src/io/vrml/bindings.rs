//! VRML 1.0 / Inventor and VRML 2.0 index lists and bindings turned into the per-face or
//! per-corner [`Bind`]s that `io::shape_to_model::build` takes: polygons split at `-1`,
//! triangle strips, and the binding modes (PER_FACE, PER_VERTEX_INDEXED ...).

use crate::io::shape_to_model::{Bind, TexCoords};
use crate::io::text::{PResult, ParseError};

/// Splits an MFInt32 index list with `-1` separators into corners and polygon ends. A missing
/// final `-1` closes the last polygon. Other negative values are errors.
pub fn split_polygons(
    raw: &[i32],
    line: usize,
    field: &str,
) -> PResult<(Vec<u32>, Vec<u32>, Vec<usize>)> {
    let mut corners = Vec::with_capacity(raw.len());
    let mut ends = Vec::with_capacity(raw.len() / 3 + 1);
    // Position in `raw` of each corner, to align parallel index lists (normalIndex...).
    let mut pos = Vec::with_capacity(raw.len());
    for (p, &i) in raw.iter().enumerate() {
        if i >= 0 {
            corners.push(i as u32);
            pos.push(p);
        } else if i == -1 {
            if ends.last().copied().unwrap_or(0) as usize != corners.len() {
                ends.push(corners.len() as u32);
            }
        } else {
            return Err(ParseError::new(
                line,
                format!("negative index {i} in '{field}' (only -1 separates faces)"),
            ));
        }
    }
    if ends.last().copied().unwrap_or(0) as usize != corners.len() {
        ends.push(corners.len() as u32);
    }
    Ok((corners, ends, pos))
}

/// Builds the triangles of triangle strips (`strips` as corner lists) as 3-corner polygons,
/// alternating the winding so every triangle has the strip's orientation. Returns corners,
/// ends, and for each triangle the strip it came from and its position in the corners of the
/// strip list (to map per-face / per-part / per-vertex bindings).
pub struct Strips {
    pub corners: Vec<u32>,
    pub ends: Vec<u32>,
    /// Strip index of each triangle.
    pub part: Vec<u32>,
    /// For each output corner, the position of its source corner in the strips' corner list.
    pub source: Vec<u32>,
}

pub fn strips_to_triangles(strip_corners: &[u32], strip_ends: &[u32]) -> Strips {
    let mut s = Strips {
        corners: Vec::new(),
        ends: Vec::new(),
        part: Vec::new(),
        source: Vec::new(),
    };
    let mut start = 0usize;
    for (part, &end) in strip_ends.iter().enumerate() {
        let end = end as usize;
        for i in start..end.saturating_sub(2) {
            let (a, b, c) = if (i - start).is_multiple_of(2) {
                (i, i + 1, i + 2)
            } else {
                (i + 1, i, i + 2)
            };
            for k in [a, b, c] {
                s.corners.push(strip_corners[k]);
                s.source.push(k as u32);
            }
            s.ends.push(s.corners.len() as u32);
            s.part.push(part as u32);
        }
        start = end;
    }
    s
}

/// A shape's polygons plus what each binding mode indexes by.
pub struct Geo {
    /// Coordinate index of each polygon corner.
    pub corners: Vec<u32>,
    /// End (exclusive) of each polygon in `corners`.
    pub ends: Vec<u32>,
    /// PER_FACE number of each polygon (triangle number for strips).
    pub face_no: Vec<u32>,
    /// PER_PART number of each polygon (strip or row number; the face for face sets).
    pub part_no: Vec<u32>,
    /// PER_VERTEX number of each corner (sequential, or the vertex number for non-indexed
    /// shapes).
    pub seq_no: Vec<u32>,
    /// Position of each corner in the raw index lists (for materialIndex / normalIndex /
    /// colorIndex that parallel coordIndex).
    pub raw_pos: Vec<u32>,
}

impl Geo {
    /// Polygons from an indexed face set's split coordIndex.
    pub fn faces(corners: Vec<u32>, ends: Vec<u32>, pos: Vec<usize>) -> Self {
        let nf = ends.len() as u32;
        Self {
            seq_no: (0..corners.len() as u32).collect(),
            raw_pos: pos.into_iter().map(|p| p as u32).collect(),
            corners,
            ends,
            face_no: (0..nf).collect(),
            part_no: (0..nf).collect(),
        }
    }

    /// Polygons of a non-indexed shape: its corners are coordinate numbers, which both
    /// PER_VERTEX and the raw index lists count by; `part_no` gives each polygon's part.
    pub fn non_indexed(corners: Vec<u32>, ends: Vec<u32>, part_no: Vec<u32>) -> Self {
        Self {
            seq_no: corners.clone(),
            raw_pos: corners.clone(),
            face_no: (0..ends.len() as u32).collect(),
            corners,
            ends,
            part_no,
        }
    }
}

/// Inventor / VRML 1.0 binding values (MaterialBinding, NormalBinding).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Binding {
    Default,
    Overall,
    PerPart,
    PerPartIndexed,
    PerFace,
    PerFaceIndexed,
    PerVertex,
    PerVertexIndexed,
}

impl Binding {
    pub fn parse(word: &str) -> Option<Self> {
        Some(match word {
            "DEFAULT" => Self::Default,
            "OVERALL" | "NONE" => Self::Overall,
            "PER_PART" => Self::PerPart,
            "PER_PART_INDEXED" => Self::PerPartIndexed,
            "PER_FACE" => Self::PerFace,
            "PER_FACE_INDEXED" => Self::PerFaceIndexed,
            "PER_VERTEX" => Self::PerVertex,
            "PER_VERTEX_INDEXED" => Self::PerVertexIndexed,
            _ => return None,
        })
    }
}

/// An index list that is absent, empty or just `[-1]` (Inventor's default) means "use the
/// natural order".
pub fn explicit(index: Option<&[i32]>) -> Option<&[i32]> {
    index.filter(|i| !(i.is_empty() || *i == [-1]))
}

fn lookup(index: &[i32], at: u32) -> u32 {
    match index.get(at as usize) {
        Some(&v) if v >= 0 => v as u32,
        _ => u32::MAX,
    }
}

/// Texture coordinates (flat u v) bound per vertex over `geo`: through `index` (VRML's
/// `texCoordIndex`, Inventor's `textureCoordIndex`, parallel to the coordinate index) when
/// the file gives one, else as the coordinates are indexed (`indexed` shapes) or in corner
/// sequence. `None` without values; a bad index is caught by `build` (coordinates dropped
/// with a warning).
pub fn texcoords_per_vertex<'a>(
    values: &'a [f32],
    index: Option<&[i32]>,
    geo: &Geo,
    indexed: bool,
) -> Option<TexCoords<'a>> {
    if values.len() < 2 {
        return None;
    }
    let index = match (indexed, explicit(index)) {
        (true, Some(ix)) => geo.raw_pos.iter().map(|&p| lookup(ix, p)).collect(),
        (true, None) => geo.corners.clone(),
        (false, _) => geo.seq_no.clone(),
    };
    Some(TexCoords { values, index })
}

/// Resolves a binding over `geo` into per-face / per-corner value indices. `index` is the
/// explicit index list (materialIndex, normalIndex, colorIndex) if the file gave one.
pub fn resolve<'a>(
    binding: Binding,
    values: &'a [f32],
    index: Option<&[i32]>,
    geo: &Geo,
) -> Bind<'a> {
    if values.len() < 3 {
        return Bind::None;
    }
    let index = explicit(index);
    let per_poly = |nums: &[u32]| -> Vec<u32> {
        match index {
            Some(ix) => nums.iter().map(|&n| lookup(ix, n)).collect(),
            None => nums.to_vec(),
        }
    };
    match binding {
        Binding::Default | Binding::Overall => Bind::None,
        Binding::PerPart => Bind::PerFace {
            values,
            index: geo.part_no.clone(),
        },
        Binding::PerFace => Bind::PerFace {
            values,
            index: geo.face_no.clone(),
        },
        Binding::PerPartIndexed => Bind::PerFace {
            values,
            index: per_poly(&geo.part_no),
        },
        Binding::PerFaceIndexed => Bind::PerFace {
            values,
            index: per_poly(&geo.face_no),
        },
        Binding::PerVertex => Bind::PerCorner {
            values,
            index: geo.seq_no.clone(),
        },
        Binding::PerVertexIndexed => Bind::PerCorner {
            values,
            index: match index {
                Some(ix) => geo.raw_pos.iter().map(|&p| lookup(ix, p)).collect(),
                None => geo.corners.clone(),
            },
        },
    }
}

//! What a textured or coloured model's vertices start with for the attributes' part of the
//! cost: each vertex's [`AttributeQuadric`] from its triangles, in model units, on all
//! cores.
//!
//! Texture coordinates are scaled to model units by one factor for the whole model, the
//! square root of its surface area over its area in the texture, so that a step of the
//! coordinates is priced as the distance the image slides over the surface, and the
//! texture's error and the geometric error add up in one unit. Colours are scaled by the
//! square root of the surface area: a step across the whole range of a channel is priced as
//! a step off the surface of the model's size (weighted by the caller, `part`).

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::collapse_plan::Kind;
use super::quadric::AttributeQuadric;
use crate::mesh::topology::Connectivity;

/// Vertices (or triangles) per rayon task.
const PER_TASK: usize = 4096;

/// An attribute's quadrics of a model.
pub(super) struct AttributeQuadrics<const N: usize> {
    /// Model units per unit of the attribute.
    pub scale: f64,
    /// By vertex (empty for a fixed vertex, which never collapses).
    pub quadrics: Vec<AttributeQuadric<N>>,
}

/// The texture's quadrics.
pub(super) type TextureQuadrics = AttributeQuadrics<2>;

/// The colours' quadrics.
pub(super) type ColourQuadrics = AttributeQuadrics<3>;

/// Every vertex's texture quadric, or `None` when the texture has no area (nothing to
/// slide).
pub(super) fn texture_quadrics(
    conn: &Connectivity,
    positions: &[Vec3],
    texcoords: &[[f32; 2]],
    kinds: &[Kind],
) -> Option<TextureQuadrics> {
    let (surface, texture) = summed_areas(conn, |t| {
        let tri = conn.triangle(t);
        let [a, b, c] = tri.map(|v| positions[v as usize].as_dvec3());
        let [s, u, w] = tri.map(|v| glam::DVec2::from(texcoords[v as usize].map(f64::from)));
        (
            0.5 * (b - a).cross(c - a).length(),
            0.5 * (u - s).perp_dot(w - s).abs(),
        )
    });
    let scale = (surface / texture).sqrt();
    if !(texture > 0.0 && scale.is_finite() && scale > 0.0) {
        return None;
    }
    let quadrics = attribute_quadrics::<2>(conn, positions, texcoords, kinds, scale);
    Some(TextureQuadrics { scale, quadrics })
}

/// Every vertex's colour quadric, or `None` when the surface has no area.
pub(super) fn colour_quadrics(
    conn: &Connectivity,
    positions: &[Vec3],
    colors: &[[f32; 3]],
    kinds: &[Kind],
) -> Option<ColourQuadrics> {
    let (surface, _) = summed_areas(conn, |t| {
        let [a, b, c] = conn.triangle(t).map(|v| positions[v as usize].as_dvec3());
        (0.5 * (b - a).cross(c - a).length(), 0.0)
    });
    let scale = surface.sqrt();
    if !(scale.is_finite() && scale > 0.0) {
        return None;
    }
    let quadrics = attribute_quadrics::<3>(conn, positions, colors, kinds, scale);
    Some(ColourQuadrics { scale, quadrics })
}

/// Two areas summed over the live triangles, `area(t)` each: in fixed chunks, in order, so
/// that the sums are the same, to the last bit, on any number of cores (rayon's own
/// reduction splits by the thread count).
fn summed_areas(conn: &Connectivity, area: impl Fn(u32) -> (f64, f64) + Sync) -> (f64, f64) {
    conn.triangles()
        .par_chunks(PER_TASK)
        .enumerate()
        .map(|(c, chunk)| {
            let first = (c * PER_TASK) as u32;
            (first..first + chunk.len() as u32)
                .filter(|&t| conn.is_alive(t))
                .map(&area)
                .fold((0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1))
        })
        .collect::<Vec<(f64, f64)>>()
        .into_iter()
        .fold((0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1))
}

/// Every vertex's quadric of the per-vertex `values` scaled by `scale` (empty for a fixed
/// vertex).
fn attribute_quadrics<const N: usize>(
    conn: &Connectivity,
    positions: &[Vec3],
    values: &[[f32; N]],
    kinds: &[Kind],
    scale: f64,
) -> Vec<AttributeQuadric<N>> {
    let corners = |t: u32| {
        let tri = conn.triangle(t);
        (
            tri.map(|v| positions[v as usize].as_dvec3()),
            tri.map(|v| values[v as usize].map(|x| f64::from(x) * scale)),
        )
    };
    (0..positions.len() as u32)
        .into_par_iter()
        .with_min_len(PER_TASK)
        .map(|v| {
            let mut sum = AttributeQuadric::<N>::default();
            if kinds[v as usize] != Kind::Fixed {
                for &t in conn.incident(v) {
                    let (p, s): ([DVec3; 3], _) = corners(t);
                    if let Some(face) = AttributeQuadric::face(p, s) {
                        sum.add(&face);
                    }
                }
            }
            sum
        })
        .collect()
}

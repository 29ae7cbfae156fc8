//! What a textured model's vertices start with for the texture's part of the cost: each
//! vertex's [`TextureQuadric`] from its triangles, in model units, on all cores.
//!
//! Texture coordinates are scaled to model units by one factor for the whole model, the
//! square root of its surface area over its area in the texture, so that a step of the
//! coordinates is priced as the distance the image slides over the surface, and the
//! texture's error and the geometric error add up in one unit.

use glam::{DVec2, Vec3};
use rayon::prelude::*;

use super::collapse_plan::Kind;
use super::quadric::TextureQuadric;
use crate::mesh::topology::Connectivity;

/// Vertices (or triangles) per rayon task.
const PER_TASK: usize = 4096;

/// The texture's quadrics of a model.
pub(super) struct TextureQuadrics {
    /// Model units per unit of texture coordinates.
    pub scale: f64,
    /// By vertex (empty for a fixed vertex, which never collapses).
    pub quadrics: Vec<TextureQuadric>,
}

/// Every vertex's texture quadric, or `None` when the texture has no area (nothing to
/// slide).
pub(super) fn texture_quadrics(
    conn: &Connectivity,
    positions: &[Vec3],
    texcoords: &[[f32; 2]],
    kinds: &[Kind],
) -> Option<TextureQuadrics> {
    let corners = |t: u32| {
        let tri = conn.triangle(t);
        (
            tri.map(|v| positions[v as usize].as_dvec3()),
            tri.map(|v| DVec2::from(texcoords[v as usize].map(f64::from))),
        )
    };
    // Summed in fixed chunks, in order: the same scale, to the last bit, on any number of
    // cores (rayon's own reduction splits by the thread count).
    let (surface, texture) = conn
        .triangles()
        .par_chunks(PER_TASK)
        .enumerate()
        .map(|(c, chunk)| {
            let first = (c * PER_TASK) as u32;
            (first..first + chunk.len() as u32)
                .filter(|&t| conn.is_alive(t))
                .map(|t| {
                    let ([a, b, c], [s, u, w]) = corners(t);
                    let surface = 0.5 * (b - a).cross(c - a).length();
                    let texture = 0.5 * (u - s).perp_dot(w - s).abs();
                    (surface, texture)
                })
                .fold((0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1))
        })
        .collect::<Vec<(f64, f64)>>()
        .into_iter()
        .fold((0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1));
    let scale = (surface / texture).sqrt();
    if !(texture > 0.0 && scale.is_finite() && scale > 0.0) {
        return None;
    }
    let quadrics = (0..positions.len() as u32)
        .into_par_iter()
        .with_min_len(PER_TASK)
        .map(|v| {
            let mut sum = TextureQuadric::default();
            if kinds[v as usize] != Kind::Fixed {
                for &t in conn.incident(v) {
                    let (p, s) = corners(t);
                    if let Some(face) = TextureQuadric::face(p, s.map(|s| s * scale)) {
                        sum.add(&face);
                    }
                }
            }
            sum
        })
        .collect();
    Some(TextureQuadrics { scale, quadrics })
}

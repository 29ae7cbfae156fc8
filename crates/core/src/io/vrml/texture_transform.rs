//! Texture transforms: VRML 2.0's `TextureTransform` (an `Appearance`'s) and VRML 1.0 /
//! Inventor's `Texture2Transform` (a property that accumulates as the transform does),
//! applied to a model's texture coordinates once it is built.

use glam::{Affine2, Vec2};

use super::parse::Node;
use crate::mesh::Model;

fn vec2(v: Option<&[f32]>, default: Vec2) -> Vec2 {
    match v {
        Some(&[x, y, ..]) => Vec2::new(x, y),
        _ => default,
    }
}

/// A texture transform's translation, rotation, scale (its field `scale`) and centre, as
/// given or their defaults.
fn parts(node: &Node, scale: &str) -> (Vec2, f32, Vec2, Vec2) {
    (
        vec2(node.floats("translation"), Vec2::ZERO),
        node.float("rotation").unwrap_or(0.0),
        vec2(node.floats(scale), Vec2::ONE),
        vec2(node.floats("center"), Vec2::ZERO),
    )
}

/// VRML 2.0 §6.50, as its formula writes it: `Tc' = -C × S × R × C × T × Tc` (translated,
/// then rotated and scaled about the centre's opposite; the centre defaults to 0).
pub fn vrml2(node: &Node) -> Affine2 {
    let (t, r, s, c) = parts(node, "scale");
    Affine2::from_translation(-c)
        * Affine2::from_scale(s)
        * Affine2::from_angle(r)
        * Affine2::from_translation(c)
        * Affine2::from_translation(t)
}

/// Inventor's `Texture2Transform` (VRML 1.0 the same): scaled about the centre, rotated
/// about it (counter-clockwise, radians), then translated.
pub fn inventor(node: &Node) -> Affine2 {
    let (t, r, s, c) = parts(node, "scaleFactor");
    Affine2::from_translation(t + c)
        * Affine2::from_angle(r)
        * Affine2::from_scale(s)
        * Affine2::from_translation(-c)
}

/// Transforms `model`'s texture coordinates, if it has any, by `m`.
pub fn apply(model: &mut Model, m: Affine2) {
    if m == Affine2::IDENTITY {
        return;
    }
    for uv in model.texcoords.iter_mut().flatten() {
        *uv = m.transform_point2(Vec2::from(*uv)).to_array();
    }
}

//! Far coordinates in VRML and Inventor scenes (see `io::origin`): the walk's world
//! transform composed in f64 beside the f32 one, and the model of a shape whose points or
//! transform are far built relative to the scene's origin.

use glam::{DMat4, DQuat, DVec3};

use super::parse::Node;
use super::Ctx;
use crate::io::origin;
use crate::io::shape_to_model::{build, ShapeSpec};
use crate::io::text::PResult;
use crate::mesh::Model;

/// An SFVec3f placing geometry (a translation, a centre) in f64, or `default`.
pub fn dvec3(node: &Node, field: &str, default: DVec3) -> DVec3 {
    match node.exact(field).as_deref() {
        Some(&[x, y, z, ..]) => DVec3::new(x, y, z),
        _ => default,
    }
}

/// An SFRotation (axis x y z, angle in radians) in f64; a zero axis is no rotation.
pub fn rotation(v: Option<&[f32]>) -> DQuat {
    match v {
        Some(&[x, y, z, angle, ..]) => {
            let axis = DVec3::new(x.into(), y.into(), z.into()).normalize_or_zero();
            if axis == DVec3::ZERO {
                DQuat::IDENTITY
            } else {
                DQuat::from_axis_angle(axis, angle.into())
            }
        }
        _ => DQuat::IDENTITY,
    }
}

/// An SFVec3f of f32 values (a scale) in f64, or `default`.
pub fn scale(v: Option<&[f32]>, default: DVec3) -> DVec3 {
    match v {
        Some(&[x, y, z, ..]) => DVec3::new(x.into(), y.into(), z.into()),
        _ => default,
    }
}

/// The VRML transform `T * C * R * SR * S * -SR * -C` in f64.
pub fn compose(t: DVec3, r: DQuat, s: DVec3, so: DQuat, c: DVec3) -> DMat4 {
    DMat4::from_translation(t + c)
        * DMat4::from_quat(r)
        * DMat4::from_quat(so)
        * DMat4::from_scale(s)
        * DMat4::from_quat(so.inverse())
        * DMat4::from_translation(-c)
}

/// Builds a shape's model. Where its points (`far_points`, in f64) or its world transform
/// `exact` are far, the model gets the scene's origin and its points and transform are
/// taken relative to it; otherwise it is built from the f32 values as it always was.
pub fn build_placed(
    spec: ShapeSpec<'_>,
    exact: &DMat4,
    far_points: Option<&[f64]>,
    ctx: &mut Ctx<'_>,
) -> PResult<Model> {
    let Some(placed) = origin::place(exact, far_points, &mut ctx.origin) else {
        return build(spec, ctx.warnings);
    };
    let relative = placed.points.unwrap_or_default();
    let coords = match relative.is_empty() {
        true => spec.coords,
        false => &relative,
    };
    let spec = ShapeSpec {
        coords,
        transform: placed.transform,
        ..spec
    };
    let mut model = build(spec, ctx.warnings)?;
    model.origin = placed.origin;
    Ok(model)
}

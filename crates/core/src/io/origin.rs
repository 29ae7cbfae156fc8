//! Far coordinates (georeferenced scans, GIS, BIM): the origin a reader picks from the first
//! vertex it reads, the f32 positions relative to it, and the digits text writers print for
//! `origin + position`.
//!
//! A model's file coordinates are `origin + transform * position` (see `Model::origin`).
//! The origin is zero unless the first vertex has a coordinate of magnitude [`FAR`] or more;
//! then that vertex, rounded to integers, becomes the origin, so the rest of the model is
//! small f32 numbers around zero that every algorithm handles as usual. Files near
//! zero read, decimate and write exactly as they did without it.

use std::fmt;

use glam::{DMat4, DVec3, Mat4, Vec3};

use crate::mesh::Model;

/// Coordinates of this magnitude or more are moved to the origin: f32's step there is 2^-10,
/// a thousandth, where a scanned patch of a few decimetres starts to lose its shape.
pub const FAR: f64 = 8192.0;

/// The origin picked from a model's first vertex: zero when all its coordinates are near
/// zero, else all three rounded to integers (a near one too, so that the model's positions
/// relative to the origin are the same numbers wherever the model stands).
pub fn origin_for(p: [f64; 3]) -> DVec3 {
    // Beyond f32's range a point is refused by the reader's finiteness check, as before.
    let finite = p.iter().all(|&c| (c as f32).is_finite());
    if finite && p.iter().any(|c| c.abs() >= FAR) {
        DVec3::new(p[0].round(), p[1].round(), p[2].round())
    } else {
        DVec3::ZERO
    }
}

/// Turns a reader's f64 coordinates into f32 positions relative to the origin it picks from
/// the first point it is given.
#[derive(Debug, Clone, Copy, Default)]
pub struct Recentre {
    origin: Option<DVec3>,
}

impl Recentre {
    /// One that keeps the origin at zero whatever the points (f32 coordinates as read): for
    /// streamed reads, whose triangles carry no origin.
    pub fn at_zero() -> Self {
        Self {
            origin: Some(DVec3::ZERO),
        }
    }

    /// The position relative to the origin (picked now if this is the first point). A
    /// coordinate too large for f32 even relative to it comes back infinite: the reader's
    /// finiteness check reports it.
    pub fn relative(&mut self, p: [f64; 3]) -> [f32; 3] {
        let o = *self.origin.get_or_insert_with(|| origin_for(p));
        [
            (p[0] - o.x) as f32,
            (p[1] - o.y) as f32,
            (p[2] - o.z) as f32,
        ]
    }

    /// The origin picked; zero before any point.
    pub fn origin(&self) -> DVec3 {
        self.origin.unwrap_or(DVec3::ZERO)
    }
}

/// A shape of a scene-graph file (VRML, Inventor, glTF) placed in the file by a transform
/// composed in f64: the f32 transform and positions its model gets, and the model's origin.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// The model's transform: `exact`'s linear part, and a translation relative to `origin`.
    pub transform: Mat4,
    /// The points relative to their own rounded first point (flat x y z), when the shape's
    /// points were far; `None` when the f32 points stay as they are.
    pub points: Option<Vec<f32>>,
    /// The model's origin.
    pub origin: DVec3,
}

/// Places a shape whose file coordinates are `exact * point`: `far_points` are its points
/// in f64 (flat x y z), given only when some coordinate is far.
/// `None` when neither the points nor the transform's translation are far: the shape is
/// read with its f32 transform as it always was. Otherwise the points are taken relative to
/// their rounded first point `c`, and the model's origin is `shared` (picked now, from
/// `exact * c` rounded, when no shape had a far one yet), so that the f32 transform's
/// translation is small.
pub fn place(
    exact: &DMat4,
    far_points: Option<&[f64]>,
    shared: &mut Option<DVec3>,
) -> Option<Placed> {
    let far_translation = exact.w_axis.truncate().abs().max_element() >= FAR;
    if far_points.is_none() && !far_translation {
        return None;
    }
    let (c, relative) = match far_points {
        Some(p) if p.len() >= 3 => {
            let c = DVec3::new(p[0].round(), p[1].round(), p[2].round());
            let rel = p
                .chunks_exact(3)
                .flat_map(|q| [q[0] - c.x, q[1] - c.y, q[2] - c.z].map(|v| v as f32))
                .collect();
            (c, Some(rel))
        }
        _ => (DVec3::ZERO, None),
    };
    let at = exact.transform_point3(c);
    let origin = match *shared {
        Some(o) => o,
        None => {
            let o = origin_for(at.to_array());
            if o != DVec3::ZERO {
                *shared = Some(o);
            }
            o
        }
    };
    let mut transform = exact.as_mat4();
    transform.w_axis = (at - origin).as_vec3().extend(exact.w_axis.w as f32);
    Some(Placed {
        transform,
        points: relative,
        origin,
    })
}

/// One coordinate of a vertex as text writers print it: the f32 as before when the origin
/// is zero; else the origin plus the f32's shortest decimal, summed in f64 and printed as
/// the shortest decimal that reads back as that sum (so 1200000 + 0.35 prints `1200000.35`).
#[derive(Debug, Clone, Copy)]
pub struct Coord {
    /// The origin's coordinate.
    pub origin: f64,
    /// The f32 coordinate relative to it (transform applied).
    pub value: f32,
}

impl Coord {
    /// The coordinate as an f64 in the file's frame.
    pub fn to_f64(self) -> f64 {
        if self.origin == 0.0 {
            return f64::from(self.value);
        }
        // The f32's own shortest decimal, read as f64, is what the value stands for.
        let decimal = format!("{}", self.value).parse::<f64>();
        self.origin + decimal.unwrap_or(f64::from(self.value))
    }
}

impl fmt::Display for Coord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.origin == 0.0 {
            fmt::Display::fmt(&self.value, f)
        } else {
            fmt::Display::fmt(&self.to_f64(), f)
        }
    }
}

/// The three coordinates of a world-space position `p` (transform applied) of model `m`.
pub fn coords(m: &Model, p: Vec3) -> [Coord; 3] {
    let o = m.origin;
    [
        Coord {
            origin: o.x,
            value: p.x,
        },
        Coord {
            origin: o.y,
            value: p.y,
        },
        Coord {
            origin: o.z,
            value: p.z,
        },
    ]
}

/// True when any model of the scene has a far origin.
pub fn any_far(scene: &crate::mesh::Scene) -> bool {
    scene.models.iter().any(|m| m.origin != DVec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_points_keep_a_zero_origin_and_their_f32_values() {
        let mut r = Recentre::default();
        assert_eq!(r.relative([0.1, -8000.0, 3.0]), [0.1f32, -8000.0, 3.0]);
        assert_eq!(r.origin(), DVec3::ZERO);
    }

    #[test]
    fn a_far_first_point_rounded_becomes_the_origin() {
        let mut r = Recentre::default();
        assert_eq!(r.relative([300000.25, 1.5, -1.2e7]), [0.25, -0.5, 0.0]);
        assert_eq!(r.origin(), DVec3::new(300000.0, 2.0, -1.2e7));
        assert_eq!(
            r.relative([300001.0, 2.0, -1.2e7 + 0.125]),
            [1.0, 0.0, 0.125]
        );
    }

    #[test]
    fn a_first_point_beyond_f32_keeps_a_zero_origin_and_reads_as_infinite() {
        let mut r = Recentre::default();
        assert!(r.relative([1e39, 0.0, 0.0])[0].is_infinite());
        assert_eq!(r.origin(), DVec3::ZERO);
    }

    #[test]
    fn far_coordinates_print_the_digits_they_were_read_with() {
        let c = |origin: f64, value: f32| Coord { origin, value }.to_string();
        assert_eq!(c(1200000.0, 0.35), "1200000.35");
        assert_eq!(c(-1.0e7, -0.125), "-10000000.125");
        assert_eq!(c(0.0, 0.35), "0.35");
    }
}

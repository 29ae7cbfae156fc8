//! Folded triangles: output triangles whose normal turns more than 90° from the input surface
//! they stand for — the "no flipped triangles" invariant, checked geometrically for any
//! decimation (vertices moved or not, ours or a peer's).
//!
//! Owns [`Folds`] and [`measure`]. An output triangle is sampled on a grid (at least four
//! points, the centroid among them; more where it covers many input triangles). Each sample
//! stands for the nearest input triangle, unless that one faces away from the output triangle
//! and another, facing like it, lies within the nearest input triangle's size of the nearest
//! point, or the sample lies inside a thin part, behind both, the other within `(1 + reach)`
//! times the nearest distance. The triangle is folded when the sum of its
//! samples' unit stood-for normals points away from its own normal. Why this reach and not
//! the nearest triangle alone (thin parts: both sides near): docs/design.md
//! [Folded triangles](../../docs/design.md#folds). Triangles with no normal count as
//! degenerate.

use glam::DVec3;
use rayon::prelude::*;

use super::bvh::Bvh;
use super::Surface;
use crate::cancel::Cancel;

/// Input triangles a sample looks at, at most, for one facing like it: the cost of a sample
/// that has none stays bounded whatever the mesh (docs/design.md#folds).
const BUDGET: usize = 512;

/// A sample inside a thin part (behind the nearest input triangle, which faces away) is backed
/// by a triangle facing like it, also behind it, within `1 + DEFAULT_REACH` times the
/// nearest distance: the output crossed the middle of a part up to about three times as thick
/// as its error (docs/design.md#folds).
pub const DEFAULT_REACH: f64 = 1.0;

/// A triangle facing like the sample within this many times the nearest input triangle's size
/// of the nearest point backs it: sides closer than the input's own triangles are one sheet
/// (docs/design.md#folds).
const SIZE_SHARE: f64 = 1.0;

/// Largest grid side: at most `MAX_SIDE²` samples on one output triangle (docs/design.md#folds).
const MAX_SIDE: usize = 16;

/// The folded and degenerate triangles of an output against its input.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Folds {
    /// Output triangles whose normal turns more than 90° from the input they stand for.
    pub triangles: usize,
    /// Their total area.
    pub area: f64,
    /// Their area over the output's whole area (0 when it has none).
    pub area_fraction: f64,
    /// Output triangles with no normal: a repeated corner, or a height under the `f32`
    /// resolution of the coordinates (neither folded nor checked).
    pub degenerate: usize,
    /// Output triangles judged (all but the degenerate ones).
    pub checked: usize,
    /// Sample points taken on them.
    pub samples: usize,
    /// Centroid of the largest folded triangle, if any.
    pub largest_at: Option<DVec3>,
}

/// Sums over a share of the output triangles.
#[derive(Debug, Clone, Copy, Default)]
struct Acc {
    folded: usize,
    area: f64,
    degenerate: usize,
    checked: usize,
    samples: usize,
    /// (area, index, centroid) of the largest folded triangle so far.
    largest: Option<(f64, usize, DVec3)>,
}

impl Acc {
    fn merge(self, o: Self) -> Self {
        let largest = match (self.largest, o.largest) {
            (Some(x), Some(y)) => Some(
                if (y.0, std::cmp::Reverse(y.1)) > (x.0, std::cmp::Reverse(x.1)) {
                    y
                } else {
                    x
                },
            ),
            (x, y) => x.or(y),
        };
        Self {
            folded: self.folded + o.folded,
            area: self.area + o.area,
            degenerate: self.degenerate + o.degenerate,
            checked: self.checked + o.checked,
            samples: self.samples + o.samples,
            largest,
        }
    }
}

/// Counts the triangles of `output` folded against `input` (whose hierarchy is `input_bvh`).
/// `reach` is [`DEFAULT_REACH`] unless measuring the definition itself; distances under
/// `floor` are rounding noise. O(S log n) for S samples (at most about four per output
/// triangle plus one per input triangle covered) and n input triangles. Once `cancel` is
/// requested the rest is skipped and the counts are partial.
pub fn measure(
    input: &Surface,
    input_bvh: &Bvh,
    output: &Surface,
    reach: f64,
    floor: f64,
    cancel: &Cancel,
) -> Folds {
    // Twice each input triangle's area, along its normal.
    let input_normals: Vec<DVec3> = input
        .triangles
        .par_iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| input.positions[v as usize]);
            (b - a).cross(c - a)
        })
        .collect();
    let mean_input_area = if input.triangles.is_empty() {
        0.0
    } else {
        input.area() / input.triangles.len() as f64
    };
    // Heights under the spacing of f32 numbers at the coordinates' magnitude are noise.
    let magnitude = output
        .bounds()
        .map_or(0.0, |(lo, hi)| lo.abs().max(hi.abs()).max_element());
    let resolution = f64::from(f32::EPSILON) * magnitude;

    let acc = (0..output.triangles.len())
        .into_par_iter()
        .map_init(
            || Vec::with_capacity(64),
            |stack, f| {
                if cancel.requested() {
                    return Acc::default();
                }
                let corners = output.triangles[f].map(|v| output.positions[v as usize]);
                let judged = Judge {
                    input_bvh,
                    input_normals: &input_normals,
                    mean_input_area,
                    reach,
                    floor,
                    resolution,
                }
                .triangle(corners, stack);
                let mut acc = Acc::default();
                match judged {
                    None => acc.degenerate = 1,
                    Some(j) => {
                        acc.checked = 1;
                        acc.samples = j.samples;
                        if j.folded {
                            acc.folded = 1;
                            acc.area = output.areas[f];
                            let centroid = corners.iter().sum::<DVec3>() / 3.0;
                            acc.largest = Some((output.areas[f], f, centroid));
                        }
                    }
                }
                acc
            },
        )
        .reduce(Acc::default, Acc::merge);
    let total = output.area();
    Folds {
        triangles: acc.folded,
        area: acc.area,
        area_fraction: if total > 0.0 { acc.area / total } else { 0.0 },
        degenerate: acc.degenerate + output.skipped_triangles,
        checked: acc.checked,
        samples: acc.samples,
        largest_at: acc.largest.map(|(_, _, c)| c),
    }
}

/// What one output triangle was found to be.
struct Judged {
    folded: bool,
    samples: usize,
}

/// The fixed inputs of judging one output triangle.
struct Judge<'a> {
    input_bvh: &'a Bvh,
    input_normals: &'a [DVec3],
    mean_input_area: f64,
    reach: f64,
    floor: f64,
    resolution: f64,
}

impl Judge<'_> {
    /// Folded or not; `None` when the triangle is degenerate.
    fn triangle(&self, [a, b, c]: [DVec3; 3], stack: &mut Vec<(u32, f64)>) -> Option<Judged> {
        let cross = (b - a).cross(c - a);
        let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
        // cross.length() / longest is the height on the longest edge.
        if cross.length() <= self.resolution * longest || !cross.is_finite() {
            return None;
        }
        let normal = cross.normalize();
        let area = 0.5 * cross.length();
        let side = if self.mean_input_area > 0.0 {
            ((area / self.mean_input_area).sqrt().ceil() as usize).clamp(2, MAX_SIDE)
        } else {
            2
        };
        let mut agreement = 0.0;
        let mut samples = 0;
        for (u, v) in grid(side) {
            let p = a + (b - a) * u + (c - a) * v;
            agreement += self.stood_for(p, normal, stack).dot(normal);
            samples += 1;
        }
        Some(Judged {
            folded: agreement < 0.0,
            samples,
        })
    }

    /// The unit normal of the input surface that the output point `p` (on a triangle facing
    /// `normal`) stands for: the nearest input triangle's, unless that faces away and another,
    /// facing like `normal`, is at the same place (see [`SIZE_SHARE`]) or `p`
    /// lies inside a thin part between the two, both behind it (see [`DEFAULT_REACH`]).
    fn stood_for(&self, p: DVec3, normal: DVec3, stack: &mut Vec<(u32, f64)>) -> DVec3 {
        let Some(nearest) = self.input_bvh.nearest(p, None, stack) else {
            return DVec3::ZERO;
        };
        let own = self.input_normals[nearest.triangle as usize];
        if own.dot(normal) > 0.0 {
            return own.normalize_or_zero();
        }
        let facing = |id: u32| self.input_normals[id as usize].dot(normal) > 0.0;
        // √(2 × area): about the nearest input triangle's edge length.
        let size = own.length().sqrt();
        let same_place = SIZE_SHARE * size + self.floor;
        let at_nearest = self.input_bvh.nearest_where(
            nearest.point,
            same_place * same_place,
            BUDGET,
            |id, _| facing(id),
            stack,
        );
        let inside = (p - nearest.point).dot(own) <= 0.0;
        let backing = at_nearest.or_else(|| {
            if !inside {
                return None;
            }
            let across = (1.0 + self.reach) * nearest.dist2.sqrt() + self.floor;
            let behind = |id: u32, q: DVec3| {
                let n = self.input_normals[id as usize];
                n.dot(normal) > 0.0 && (p - q).dot(n) <= 0.0
            };
            self.input_bvh
                .nearest_where(p, across * across, BUDGET, behind, stack)
        });
        match backing {
            Some(hit) => self.input_normals[hit.triangle as usize].normalize_or_zero(),
            None => own.normalize_or_zero(),
        }
    }
}

/// The centroids of the `side²` sub-triangles of a triangle cut by a grid of `side` steps per
/// edge, as coordinates `(u, v)` along its second and third corner: interior points, evenly
/// spread (for `side` 2, the centroid and one towards each corner).
fn grid(side: usize) -> impl Iterator<Item = (f64, f64)> {
    let s = side as f64;
    (0..side).flat_map(move |i| {
        (0..side - i).flat_map(move |j| {
            let (i, j) = (i as f64, j as f64);
            let up = ((i + 1.0 / 3.0) / s, (j + 1.0 / 3.0) / s);
            let down = ((i + 2.0 / 3.0) / s, (j + 2.0 / 3.0) / s);
            // The downward sub-triangle exists inside the triangle only when i + j < side - 1.
            let has_down = (i + j) < s - 1.0;
            std::iter::once(up).chain(has_down.then_some(down))
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_spreads_side_squared_interior_points() {
        for side in 1..=MAX_SIDE {
            let points: Vec<(f64, f64)> = grid(side).collect();
            assert_eq!(points.len(), side * side);
            for &(u, v) in &points {
                assert!(u > 0.0 && v > 0.0 && u + v < 1.0, "({u}, {v}) of {side}");
            }
            // The sub-triangles' centroids average to the triangle's.
            let mean = points
                .iter()
                .fold((0.0, 0.0), |(x, y), &(u, v)| (x + u, y + v));
            let n = points.len() as f64;
            assert!((mean.0 / n - 1.0 / 3.0).abs() < 1e-12);
            assert!((mean.1 / n - 1.0 / 3.0).abs() < 1e-12);
        }
        // Side 2: three corner sub-triangles and the middle one, whose centroid is the centroid.
        assert!(
            grid(2).any(|(u, v)| (u - 1.0 / 3.0).abs() < 1e-12 && (v - 1.0 / 3.0).abs() < 1e-12)
        );
    }
}

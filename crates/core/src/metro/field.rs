//! The error heat-map's data: how far each vertex of a decimated scene is from its original,
//! measured with Metro's nearest-point search (`bvh`) in both directions and spread over the
//! decimated vertices, so that a renderer interpolating them colours each face by the error
//! around it.
//!
//! A decimated vertex's value is the largest of: its own distance to the original surface;
//! the distances of sample points on its incident faces (centroid, edge midpoints and one
//! point towards each corner) that lie nearest to it; and the distances of original vertices
//! whose closest point on the decimated surface lies on an incident face, nearest to it (what
//! a flattened bump leaves behind). Every query is one nearest-point search: O((n + m) log)
//! for n and m triangles, on every core.

use glam::DVec3;
use rayon::prelude::*;

use super::bvh::Bvh;
use super::Surface;
use crate::cancel::Cancel;
use crate::mesh::Scene;

/// Per-vertex distances of a decimated scene from its original, in world (model) units.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ErrorField {
    /// For each model of the decimated scene, a distance per vertex (indexed like its
    /// positions; 0 for vertices no triangle uses).
    pub distances: Vec<Vec<f32>>,
    /// The largest distance.
    pub max: f64,
    /// The original's bounding-box diagonal (world units), for distances in percent of it.
    pub diagonal: f64,
}

/// Sample points of a face, as barycentric weights, and the corners each one counts for:
/// the corners of largest weight (docs/design.md#error-map).
const FACE_SAMPLES: [([f64; 3], [bool; 3]); 7] = [
    ([1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0], [true, true, true]),
    ([0.5, 0.5, 0.0], [true, true, false]),
    ([0.0, 0.5, 0.5], [false, true, true]),
    ([0.5, 0.0, 0.5], [true, false, true]),
    ([4.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0], [true, false, false]),
    ([1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0], [false, true, false]),
    ([1.0 / 6.0, 1.0 / 6.0, 4.0 / 6.0], [false, false, true]),
];

/// The distance of every vertex of `decimated` from `original` (see the module's doc). Pure
/// and possibly long on big meshes: callers may run it on a worker thread.
pub fn error_field(original: &Scene, decimated: &Scene) -> ErrorField {
    field_of(original, decimated, &Cancel::default())
}

/// [`error_field`], stopping soon after `cancel` is requested (the viewer's `Esc`): `None`.
pub fn error_field_cancellable(
    original: &Scene,
    decimated: &Scene,
    cancel: &Cancel,
) -> Option<ErrorField> {
    let field = field_of(original, decimated, cancel);
    (!cancel.requested()).then_some(field)
}

/// Once `cancel` is requested every query left answers 0 at once: the field is then partial.
fn field_of(original: &Scene, decimated: &Scene, cancel: &Cancel) -> ErrorField {
    let source = Surface::from_scene(original);
    let diagonal = source.diagonal();
    let source_bvh = Bvh::new(&source.positions, &source.triangles);
    let soup = Soup::of(decimated);
    let mut values = vec![0.0f64; soup.positions.len()];
    if !source_bvh.is_empty() {
        from_source(&soup, &source_bvh, cancel, &mut values);
    }
    let decimated_bvh = Bvh::new(&soup.positions, &soup.triangles);
    if !decimated_bvh.is_empty() {
        to_source(&soup, &decimated_bvh, &source, cancel, &mut values);
    }
    let max = values.iter().copied().fold(0.0, f64::max);
    let distances = (decimated.models.iter().zip(&soup.offsets))
        .map(|(model, &first)| {
            values[first..first + model.positions.len()]
                .iter()
                .map(|&d| d as f32)
                .collect()
        })
        .collect();
    ErrorField {
        distances,
        max,
        diagonal,
    }
}

/// The decimated scene as one world-space soup: model m's vertex v is `offsets[m] + v`.
struct Soup {
    offsets: Vec<usize>,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

impl Soup {
    fn of(scene: &Scene) -> Self {
        let mut soup = Self {
            offsets: Vec::with_capacity(scene.models.len()),
            positions: Vec::new(),
            triangles: Vec::new(),
        };
        for model in &scene.models {
            let first = soup.positions.len() as u32;
            soup.offsets.push(first as usize);
            let m = model.transform.as_dmat4();
            // In the file's frame, as `Surface::from_scene` puts the original.
            let o = model.origin;
            (soup.positions)
                .extend((model.positions.iter()).map(|p| m.transform_point3(p.as_dvec3()) + o));
            let count = model.positions.len() as u32;
            soup.triangles.extend(
                (model.triangles.iter())
                    .filter(|t| t.iter().all(|&v| v < count))
                    .map(|t| t.map(|v| v + first)),
            );
        }
        soup
    }
}

/// Distances from the decimated surface to the source: at each vertex, and at samples on
/// the faces, each sample counted for its nearest corners.
fn from_source(soup: &Soup, source_bvh: &Bvh, cancel: &Cancel, values: &mut [f64]) {
    let nearest = |p: DVec3, stack: &mut Vec<(u32, f64)>| {
        if cancel.requested() || !p.is_finite() {
            return 0.0;
        }
        source_bvh
            .nearest(p, None, stack)
            .map_or(0.0, |hit| hit.dist2.sqrt())
    };
    values
        .par_iter_mut()
        .zip(soup.positions.par_iter())
        .for_each_init(Vec::new, |stack, (value, &p)| *value = nearest(p, stack));
    let samples: Vec<[f64; 7]> = (soup.triangles)
        .par_iter()
        .map_init(Vec::new, |stack, t| {
            let [a, b, c] = t.map(|v| soup.positions[v as usize]);
            FACE_SAMPLES.map(|(w, _)| nearest(a * w[0] + b * w[1] + c * w[2], stack))
        })
        .collect();
    for (t, distances) in soup.triangles.iter().zip(&samples) {
        for ((_, corners), &d) in FACE_SAMPLES.iter().zip(distances) {
            for (&v, _) in t.iter().zip(corners).filter(|(_, &on)| on) {
                let value = &mut values[v as usize];
                *value = value.max(d);
            }
        }
    }
}

/// The other way: source vertices far from the decimated surface raise the nearest corner
/// of the decimated triangle they are nearest to.
fn to_source(
    soup: &Soup,
    decimated_bvh: &Bvh,
    source: &Surface,
    cancel: &Cancel,
    values: &mut [f64],
) {
    let hits: Vec<Option<(u32, f64)>> = source
        .used_vertices
        .par_iter()
        .map_init(Vec::new, |stack, &v| {
            if cancel.requested() {
                return None;
            }
            let p = source.positions[v as usize];
            let hit = decimated_bvh.nearest(p, None, stack)?;
            let t = soup.triangles[hit.triangle as usize];
            let corner = nearest_corner(hit.point, t.map(|v| soup.positions[v as usize]));
            Some((t[corner], hit.dist2.sqrt()))
        })
        .collect();
    for (v, d) in hits.into_iter().flatten() {
        let value = &mut values[v as usize];
        *value = value.max(d);
    }
}

/// Which corner of `corners` is nearest to `p`.
fn nearest_corner(p: DVec3, corners: [DVec3; 3]) -> usize {
    (0..3)
        .min_by(|&i, &j| {
            let (di, dj) = (
                p.distance_squared(corners[i]),
                p.distance_squared(corners[j]),
            );
            di.total_cmp(&dj)
        })
        .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{shapes, Model};
    use glam::Vec3;

    fn scene(model: Model) -> Scene {
        Scene {
            models: vec![model],
        }
    }

    #[test]
    fn an_unchanged_scene_has_no_error() {
        let s = scene(shapes::unit_box());
        let field = error_field(&s, &s);
        assert!(field.max < 1e-12, "max {}", field.max);
        assert_eq!(field.distances.len(), 1);
        assert_eq!(field.distances[0].len(), s.models[0].positions.len());
        assert!(field.diagonal > 1.0);
    }

    #[test]
    fn a_cancelled_field_gives_nothing_and_an_uncancelled_one_the_plain_field() {
        let original = scene(shapes::unit_box());
        let mut moved = original.clone();
        moved.models[0].positions[7] += Vec3::splat(0.25);
        let cancel = Cancel::new();
        let field = error_field_cancellable(&original, &moved, &cancel);
        let plain = error_field(&original, &moved);
        let field = field.unwrap_or_else(|| panic!("not cancelled, yet no field"));
        assert_eq!(field.distances, plain.distances);
        assert!(plain.max > 0.4, "max {}", plain.max);
        cancel.request();
        assert!(error_field_cancellable(&original, &moved, &cancel).is_none());
    }

    #[test]
    fn a_vertex_moved_out_carries_its_distance_and_its_neighbours_less() {
        let original = scene(shapes::unit_box());
        let mut moved = original.clone();
        // Corner (1, 1, 1) of the unit box, pushed 0.5 out along the diagonal.
        let corner = 7;
        let p = moved.models[0].positions[corner];
        let out = (p - Vec3::splat(0.5)).normalize() * 0.5;
        moved.models[0].positions[corner] = p + out;
        let field = error_field(&original, &moved);
        let d = &field.distances[0];
        // The moved corner's nearest point on the box is where it was; it is the farthest.
        assert!(
            (d[corner] - 0.5).abs() < 1e-5,
            "moved corner: {}",
            d[corner]
        );
        assert!((field.max - f64::from(d[corner])).abs() < 1e-6);
        for (v, &dv) in d.iter().enumerate() {
            if v != corner {
                assert!(dv < d[corner], "vertex {v}: {dv} ≥ {}", d[corner]);
            }
        }
    }

    #[test]
    fn a_flattened_bump_is_seen_from_the_original_side() {
        // The original has a spike the decimated square lacks: no decimated vertex moved,
        // yet the corner nearest the spike must carry its height.
        let square = Model {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..Model::default()
        };
        let mut spiked = square.clone();
        spiked.positions.push(Vec3::new(0.9, 0.1, 0.4));
        spiked.triangles = vec![[0, 1, 4], [1, 2, 4], [2, 0, 4], [0, 2, 3]];
        let field = error_field(&scene(spiked), &scene(square));
        assert!((field.max - 0.4).abs() < 1e-6, "max {}", field.max);
        let d = &field.distances[0];
        assert!((f64::from(d[1]) - 0.4).abs() < 1e-6, "corner 1: {d:?}");
        assert!(d[3] < 0.2, "the far corner: {d:?}");
    }

    #[test]
    fn a_far_model_is_measured_in_its_own_frame() {
        // Both scenes stand at one far origin: the field is the one at zero.
        let square = Model {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            origin: DVec3::new(3.0e5, 1.2e6, 50.0),
            ..Model::default()
        };
        let mut lifted = square.clone();
        lifted.positions.iter_mut().for_each(|p| p.z = 0.25);
        let field = error_field(&scene(square), &scene(lifted));
        assert!((field.max - 0.25).abs() < 1e-6, "max {}", field.max);
    }
}

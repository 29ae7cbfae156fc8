//! Metro: the geometric distance between two surfaces, after Cignoni, Rocchini and Scopigno,
//! "Metro: measuring error on simplified surfaces", Computer Graphics Forum 17(2), 1998.
//!
//! Owns the measurement as a library: [`Surface`] (a scene flattened into one world-space
//! triangle soup, welded by exact position, with areas, edges, closedness and volume),
//! [`compare`] (samples each surface and measures the distance of every sample from the other,
//! in both directions) and the [`Comparison`] it returns. `bvh` answers the nearest-point
//! queries, `sampling` places the samples and reduces their distances, `folds` counts B's
//! triangles folded over A (optional), `report` prints the result as a table or JSON. The
//! `metro` binary (src/bin/metro.rs) is a thin shell over this.
//!
//! Definitions, as in the paper: the one-sided distance `E(A, B)` is the distance of points of
//! A from surface B; the Hausdorff distance is `max(E(A, B), E(B, A))`. Max is taken over every
//! sample (vertices, edge points, face points); mean and RMS are area-weighted averages,
//! estimated from the face samples, which are spread in proportion to area.

pub mod bvh;
pub mod field;
pub mod folds;
pub mod report;
pub(crate) mod sampling;

use std::collections::HashMap;
use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use crate::cancel::Cancel;
use crate::mesh::{union_find, Scene};
use bvh::Bvh;

/// A scene as one world-space triangle soup, ready to be sampled or searched.
#[derive(Debug, Clone, Default)]
pub struct Surface {
    /// Distinct world-space positions (corners at exactly the same place share one entry).
    pub positions: Vec<DVec3>,
    /// Triangles with three distinct corners, indexing `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Area of each triangle.
    pub areas: Vec<f64>,
    /// Each undirected edge once, smaller index first.
    pub edges: Vec<[u32; 2]>,
    /// Positions used by at least one triangle, ascending.
    pub used_vertices: Vec<u32>,
    /// Edges used by one triangle only.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub nonmanifold_edges: usize,
    /// Edges used twice in the same direction (neighbours with opposite orientation).
    pub misoriented_edges: usize,
    /// Connected pieces: triangles joined through shared positions (a surface torn apart
    /// comes back as several).
    pub components: usize,
    /// Triangles dropped: a repeated corner, or a coordinate that is not finite.
    pub skipped_triangles: usize,
}

impl Surface {
    /// Flattens every model of `scene` into world space (each model's transform applied and
    /// its origin added, in `f64`: the file's own frame, so that two files whose readers
    /// picked different origins are compared where they stand) and concatenates them.
    pub fn from_scene(scene: &Scene) -> Self {
        let mut positions = Vec::with_capacity(scene.vertex_count());
        let mut triangles = Vec::with_capacity(scene.triangle_count());
        let mut skipped = 0;
        let mut weld = WeldMap::with_capacity(scene.vertex_count());
        for model in &scene.models {
            let m = model.transform.as_dmat4();
            let ids: Vec<Option<u32>> = model
                .positions
                .iter()
                .map(|p| {
                    let w = m.transform_point3(p.as_dvec3()) + model.origin;
                    w.is_finite().then(|| weld_id(&mut weld, &mut positions, w))
                })
                .collect();
            for t in &model.triangles {
                let corners = t.map(|v| ids.get(v as usize).copied().flatten());
                match corners {
                    [Some(a), Some(b), Some(c)] => triangles.push([a, b, c]),
                    _ => skipped += 1,
                }
            }
        }
        let mut s = Self::from_welded(positions, triangles);
        s.skipped_triangles += skipped;
        s
    }

    /// A surface from world-space positions and triangles (indices out of range, non-finite
    /// corners and repeated corners are dropped and counted in `skipped_triangles`).
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Self {
        let mut welded = Vec::with_capacity(positions.len());
        let mut weld = WeldMap::with_capacity(positions.len());
        let ids: Vec<Option<u32>> = positions
            .iter()
            .map(|&p| p.is_finite().then(|| weld_id(&mut weld, &mut welded, p)))
            .collect();
        let mut kept = Vec::with_capacity(triangles.len());
        let mut skipped = 0;
        for t in triangles {
            match t.map(|v| ids.get(v as usize).copied().flatten()) {
                [Some(a), Some(b), Some(c)] => kept.push([a, b, c]),
                _ => skipped += 1,
            }
        }
        let mut s = Self::from_welded(welded, kept);
        s.skipped_triangles += skipped;
        s
    }

    fn from_welded(positions: Vec<DVec3>, mut triangles: Vec<[u32; 3]>) -> Self {
        let before = triangles.len();
        triangles.retain(|&[a, b, c]| a != b && b != c && c != a);
        let skipped_triangles = before - triangles.len();
        let areas: Vec<f64> = triangles
            .par_iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| positions[v as usize]);
                0.5 * (b - a).cross(c - a).length()
            })
            .collect();

        // Edges: sort the directed edges by their undirected key and read off the runs.
        let mut directed: Vec<(u64, bool)> = (0..3 * triangles.len())
            .into_par_iter()
            .map(|k| {
                let t = triangles[k / 3];
                let (u, v) = (t[k % 3], t[(k + 1) % 3]);
                (u64::from(u.min(v)) << 32 | u64::from(u.max(v)), u < v)
            })
            .collect();
        directed.par_sort_unstable();
        let mut edges = Vec::with_capacity(directed.len() / 2 + 1);
        let (mut boundary_edges, mut nonmanifold_edges, mut misoriented_edges) = (0, 0, 0);
        for run in directed.chunk_by(|x, y| x.0 == y.0) {
            let key = run[0].0;
            edges.push([(key >> 32) as u32, key as u32]);
            match run {
                [_] => boundary_edges += 1,
                [x, y] if x.1 == y.1 => misoriented_edges += 1,
                [_, _] => {}
                _ => nonmanifold_edges += 1,
            }
        }

        let mut used = vec![false; positions.len()];
        for t in &triangles {
            for &v in t {
                used[v as usize] = true;
            }
        }
        let used_vertices = (0..positions.len() as u32)
            .filter(|&v| used[v as usize])
            .collect();
        let components = count_components(positions.len(), &triangles);
        Self {
            positions,
            triangles,
            areas,
            edges,
            used_vertices,
            boundary_edges,
            nonmanifold_edges,
            misoriented_edges,
            components,
            skipped_triangles,
        }
    }

    /// Total area.
    pub fn area(&self) -> f64 {
        self.areas.iter().sum()
    }

    /// True when every edge is shared by exactly two triangles of opposite orientation.
    pub fn is_closed(&self) -> bool {
        !self.triangles.is_empty()
            && self.boundary_edges == 0
            && self.nonmanifold_edges == 0
            && self.misoriented_edges == 0
    }

    /// Enclosed volume (sum of signed tetrahedra from the box centre; negative when the
    /// triangles face inwards), for closed surfaces only.
    pub fn volume(&self) -> Option<f64> {
        if !self.is_closed() {
            return None;
        }
        let (lo, hi) = self.bounds()?;
        let o = (lo + hi) * 0.5;
        let six_v: f64 = self
            .triangles
            .par_iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| self.positions[v as usize] - o);
                a.dot(b.cross(c))
            })
            .sum();
        Some(six_v / 6.0)
    }

    /// Bounds of the used vertices, `None` when there are no triangles.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = self.positions[*self.used_vertices.first()? as usize];
        Some(
            self.used_vertices
                .iter()
                .fold((first, first), |(lo, hi), &v| {
                    let p = self.positions[v as usize];
                    (lo.min(p), hi.max(p))
                }),
        )
    }

    /// Length of the bounding-box diagonal (0 when empty).
    pub fn diagonal(&self) -> f64 {
        self.bounds().map_or(0.0, |(lo, hi)| lo.distance(hi))
    }

    /// What the report says about this surface.
    pub fn info(&self) -> SurfaceInfo {
        let (lo, hi) = self.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
        SurfaceInfo {
            triangles: self.triangles.len(),
            vertices: self.used_vertices.len(),
            area: self.area(),
            volume: self.volume(),
            boundary_edges: self.boundary_edges,
            nonmanifold_edges: self.nonmanifold_edges,
            components: self.components,
            skipped_triangles: self.skipped_triangles,
            bbox_min: lo,
            bbox_max: hi,
        }
    }
}

/// Pieces of `triangles` over `vertices` positions joined through shared corners
/// (union-find: near-linear).
fn count_components(vertices: usize, triangles: &[[u32; 3]]) -> usize {
    use union_find::root;
    let mut parent = union_find::singletons(vertices);
    for t in triangles {
        let a = root(&mut parent, t[0]);
        for &v in &t[1..] {
            let b = root(&mut parent, v);
            parent[b as usize] = a;
        }
    }
    let mut is_root = vec![false; vertices];
    for t in triangles {
        is_root[root(&mut parent, t[0]) as usize] = true;
    }
    is_root.iter().filter(|&&r| r).count()
}

/// Exact bit patterns of positions to their index.
type WeldMap = HashMap<[u64; 3], u32>;

fn weld_id(map: &mut WeldMap, positions: &mut Vec<DVec3>, p: DVec3) -> u32 {
    // +0.0 and -0.0 are the same place.
    let key = (p + DVec3::ZERO).to_array().map(f64::to_bits);
    *map.entry(key).or_insert_with(|| {
        positions.push(p);
        (positions.len() - 1) as u32
    })
}

/// Summary of one surface for the report.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceInfo {
    /// Triangles measured.
    pub triangles: usize,
    /// Distinct positions.
    pub vertices: usize,
    /// Total area.
    pub area: f64,
    /// Enclosed volume when the surface is closed and consistently oriented.
    pub volume: Option<f64>,
    /// Edges of one triangle.
    pub boundary_edges: usize,
    /// Edges of three or more triangles.
    pub nonmanifold_edges: usize,
    /// Connected pieces (through shared positions).
    pub components: usize,
    /// Triangles with no area, left out of the sampling.
    pub skipped_triangles: usize,
    /// Bounding box, lower corner.
    pub bbox_min: DVec3,
    /// Bounding box, upper corner.
    pub bbox_max: DVec3,
}

/// Distances of the samples of one surface from the other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionStats {
    /// Samples taken inside triangles.
    pub face_samples: usize,
    /// Samples taken on edges.
    pub edge_samples: usize,
    /// Samples taken at vertices.
    pub vertex_samples: usize,
    /// Largest distance of any sample.
    pub max: f64,
    /// Where that sample lies (on the sampled surface).
    pub max_at: DVec3,
    /// Area-weighted mean distance.
    pub mean: f64,
    /// Area-weighted root mean square distance.
    pub rms: f64,
}

impl DirectionStats {
    /// All samples taken.
    pub fn samples(&self) -> usize {
        self.face_samples + self.edge_samples + self.vertex_samples
    }
}

/// How to sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Face samples per direction; `None`: ten per triangle of the sampled surface (at least
    /// [`MIN_DEFAULT_SAMPLES`]). Edge samples are a tenth of this; every vertex is sampled too.
    pub samples: Option<usize>,
    /// Seed of the sample placement: the same seed gives the same numbers.
    pub seed: u64,
    /// Also count B's triangles folded over A ([`folds`]: A the input, B the output).
    pub folds: bool,
    /// How far beyond its nearest input a fold sample inside a thin part looks for backing
    /// ([`folds::measure`]).
    pub fold_reach: f64,
}

/// Face samples used by default on tiny meshes.
pub const MIN_DEFAULT_SAMPLES: usize = 10_000;

impl Default for Options {
    fn default() -> Self {
        Self {
            samples: None,
            seed: 1,
            folds: false,
            fold_reach: folds::DEFAULT_REACH,
        }
    }
}

impl Options {
    fn face_samples(&self, from: &Surface) -> usize {
        self.samples
            .unwrap_or_else(|| (10 * from.triangles.len()).max(MIN_DEFAULT_SAMPLES))
    }
}

/// Seconds spent in each phase of [`compare`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timings {
    /// Building the bounding-volume hierarchies.
    pub bvh: f64,
    /// Sampling A against B.
    pub a_to_b: f64,
    /// Sampling B against A.
    pub b_to_a: f64,
    /// Looking for folded triangles.
    pub folds: f64,
}

/// Everything Metro measured between two surfaces A and B.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Surface A (the reference, usually the input).
    pub a: SurfaceInfo,
    /// Surface B (usually the decimated result).
    pub b: SurfaceInfo,
    /// A's bounding-box diagonal: relative errors are fractions of it.
    pub diagonal: f64,
    /// The sampling's random seed: the same seed gives the same figures.
    pub seed: u64,
    /// Distances of A's samples from B.
    pub a_to_b: DirectionStats,
    /// Distances of B's samples from A.
    pub b_to_a: DirectionStats,
    /// B's triangles folded over A, when [`Options::folds`] asked for them.
    pub folds: Option<folds::Folds>,
    /// Where the time went.
    pub timings: Timings,
}

/// The larger of the two directions, statistic by statistic.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Symmetric {
    /// The Hausdorff distance.
    pub max: f64,
    /// The larger area-weighted mean distance.
    pub mean: f64,
    /// The larger root mean square distance.
    pub rms: f64,
}

impl Comparison {
    /// The (symmetric) Hausdorff distance: the larger of the two one-sided maxima.
    pub fn hausdorff(&self) -> f64 {
        self.a_to_b.max.max(self.b_to_a.max)
    }

    /// Max, mean and RMS each taken as the larger of the two directions.
    pub fn symmetric(&self) -> Symmetric {
        Symmetric {
            max: self.hausdorff(),
            mean: self.a_to_b.mean.max(self.b_to_a.mean),
            rms: self.a_to_b.rms.max(self.b_to_a.rms),
        }
    }

    /// `value` as a fraction of A's bounding-box diagonal (0 for a degenerate box).
    pub fn relative(&self, value: f64) -> f64 {
        if self.diagonal > 0.0 {
            value / self.diagonal
        } else {
            0.0
        }
    }
}

/// Which input a problem is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The first surface.
    A,
    /// The second surface.
    B,
}

/// Why two surfaces cannot be compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum MetroError {
    /// A surface has no triangle with an area.
    #[error("surface {0:?} has no triangles to measure")]
    NoTriangles(Side),
    /// The cancel flag was raised.
    #[error("the measurement was cancelled")]
    Cancelled,
}

/// Measures A against B in both directions.
pub fn compare(a: &Surface, b: &Surface, options: &Options) -> Result<Comparison, MetroError> {
    compare_cancellable(a, b, options, &Cancel::default())
}

/// [`compare`], stopping soon after `cancel` is requested (the viewer's `Esc`) with
/// [`MetroError::Cancelled`].
pub fn compare_cancellable(
    a: &Surface,
    b: &Surface,
    options: &Options,
    cancel: &Cancel,
) -> Result<Comparison, MetroError> {
    let (Some((alo, ahi)), Some((blo, bhi))) = (a.bounds(), b.bounds()) else {
        let side = if a.triangles.is_empty() {
            Side::A
        } else {
            Side::B
        };
        return Err(MetroError::NoTriangles(side));
    };
    // The closest-point arithmetic rounds at a few ulps of the coordinates' magnitude; any
    // distance under this floor is indistinguishable from zero and reported as zero.
    let magnitude = [alo, ahi, blo, bhi]
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    let floor = 64.0 * f64::EPSILON * magnitude;

    let start = Instant::now();
    let (bvh_a, bvh_b) = rayon::join(
        || Bvh::new(&a.positions, &a.triangles),
        || Bvh::new(&b.positions, &b.triangles),
    );
    let t_bvh = start.elapsed().as_secs_f64();
    let measure = |from: &Surface, to: &Bvh| {
        let stats = sampling::measure(
            from,
            to,
            options.face_samples(from),
            options.seed,
            floor,
            cancel,
        );
        if cancel.requested() {
            Err(MetroError::Cancelled)
        } else {
            Ok(stats)
        }
    };
    let a_to_b = measure(a, &bvh_b)?;
    let t_ab = start.elapsed().as_secs_f64();
    let b_to_a = measure(b, &bvh_a)?;
    let t_ba = start.elapsed().as_secs_f64();
    let folds = options
        .folds
        .then(|| folds::measure(a, &bvh_a, b, options.fold_reach, floor, cancel));
    if cancel.requested() {
        return Err(MetroError::Cancelled);
    }
    let t_folds = start.elapsed().as_secs_f64();
    Ok(Comparison {
        a: a.info(),
        b: b.info(),
        diagonal: alo.distance(ahi),
        seed: options.seed,
        a_to_b,
        b_to_a,
        folds,
        timings: Timings {
            bvh: t_bvh,
            a_to_b: t_ab - t_bvh,
            b_to_a: t_ba - t_ab,
            folds: t_folds - t_ba,
        },
    })
}

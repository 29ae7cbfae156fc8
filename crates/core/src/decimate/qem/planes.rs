//! What every vertex starts with, read off its ordered one-ring in one pass on all cores:
//! its kind (interior, boundary, fixed) and its quadric — the planes of its triangles,
//! weighted by area × √(area / mean area) (docs/design.md#qem-face-weight), plus the
//! constraint planes of its boundary and feature edges (a fold's angle first scaled to how
//! finely the mesh is sampled: docs/design.md#qem-fold-scale). A non-manifold ("complex")
//! vertex has no planes through its non-manifold edges, and a fin's rim (a short boundary
//! chain between two of them) is not constrained (docs/design.md#qem-non-manifold-weights).
//!
//! In the ring (`mesh::topology::Ring`) triangle `i` is `(v, verts[i], verts[i + 1])`, so the
//! edge to `verts[j]` lies between ring triangles `j - 1` and `j` (wrapping round a closed
//! ring; an open ring's first and last edges have one triangle: the boundary).

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::collapse_plan::Kind;
use super::quadric::{LocalQuadric, Quadric};
use crate::mesh::topology::{corner_of, Adjacency, Connectivity, Ring, RingShape, MAX_VALENCE};

/// Weight of a boundary edge's constraint plane, times its length² and its triangle's face
/// weight scale, relative to an area-weighted face plane
/// (docs/design.md#qem-constraint-weight).
const CONSTRAINT_WEIGHT: f64 = 30.0;

/// Weight of a texture seam's constraint planes (an edge between two vertices on seams),
/// relative to an area-weighted face plane: a seam's sides collapse together, so it is priced
/// as a face plane, not a boundary (docs/design.md#qem-seam-weight).
const SEAM_WEIGHT: f64 = 1.0;

/// Weight of a feature edge's planes, times `(1 - cos(dihedral))⁶` (15 at a right angle,
/// 0.2 at 60°, 0.01 at 45°): sharp creases hold, a scan's mild "features" barely constrain
/// (docs/design.md#qem-feature-weight).
const FEATURE_WEIGHT: f64 = 15.0;

/// A mesh whose median fold (the angle between the normals of an edge's two triangles) is
/// at most this many degrees is finely sampled: its folds are weighed as they are. A coarser
/// mesh's folds are scaled down first (docs/design.md#qem-fold-scale).
const FINE_FOLD_DEG: f64 = 3.0;

/// How sharply a coarser mesh's folds shrink: by `(FINE_FOLD_DEG / median fold)` to this power
/// (docs/design.md#qem-fold-scale).
const FOLD_SCALE_POWER: i32 = 4;

/// Vertices whose rings estimate the median fold (every n-th vertex, so it costs nothing on
/// a large mesh).
const FOLD_SAMPLES: usize = 1 << 14;

/// A fold whose cosine is below this (sharper than about 172°: a triangle folded flat onto
/// another, the two sides of a zero-thick fin or flake a scan leaves standing on its
/// surface) is a *flat fold*. No sampling of a smooth surface makes one, so it is never
/// scaled, and at a complex vertex it is constrained too (docs/design.md#qem-flat-folds).
const COS_FLAT_FOLD: f64 = -0.99;

/// A flat fold is held only when its edge is at least this many times √a long, `a` the
/// mean area one of the result's triangles covers: a smaller fin is below the result's
/// resolution (the size `hanging_sheets` removes) and goes freely
/// (docs/design.md#qem-flat-folds).
const FLAT_FOLD_MIN_EDGE: f64 = 0.4;

/// Weight of a flat fold's constraint plane at a complex vertex, times its length² and its
/// triangle's face weight scale (docs/design.md#qem-flat-folds).
const FLAT_FOLD_WEIGHT: f64 = 10.0;

/// Vertices per rayon task.
const PER_TASK: usize = 4096;

/// Which edges are constrained, and how.
#[derive(Debug, Clone, Copy)]
pub(super) struct Constraints<'a> {
    /// The cosine of the feature angle: an edge whose dihedral angle is above it is a
    /// feature edge, constrained from both sides.
    pub cos_feature: f64,
    /// Whether fold angles are scaled to the mesh's median fold first ([`FoldScale`]).
    pub scale_folds: bool,
    /// Vertices on a texture seam (empty when there is none): a boundary edge between two
    /// is constrained by `SEAM_WEIGHT`, any other by `CONSTRAINT_WEIGHT`.
    pub seam: &'a [bool],
    /// How many triangles the result is expected to have (`None`: no count target): flat
    /// folds much smaller than one of them are not held (`FLAT_FOLD_MIN_EDGE`).
    pub result_triangles: Option<usize>,
}

impl Constraints<'_> {
    fn on_seam(&self, v: u32) -> bool {
        self.seam.get(v as usize).copied().unwrap_or(false)
    }
}

/// Every vertex's kind and starting quadric (about its position). A fixed vertex never
/// collapses, so its quadric is left empty.
pub(super) fn kinds_and_quadrics(
    conn: &Connectivity,
    positions: &[Vec3],
    constraints: Constraints<'_>,
) -> (Vec<Kind>, Vec<LocalQuadric>) {
    let planes = face_planes(conn, positions);
    let folds = if constraints.scale_folds {
        FoldScale::of(conn, positions.len(), &planes)
    } else {
        FoldScale(1.0)
    };
    let folds = Folds {
        scale: folds,
        flat: FlatFolds {
            min_length2: flat_fold_min_length2(&planes, constraints),
        },
    };
    let (kinds, mut quadrics) =
        ring_kinds_and_quadrics(conn, positions, &planes, constraints, folds);
    let taken = constrain_outlines(conn, positions, &planes, &kinds, &mut quadrics, constraints);
    let rings = (positions, planes.as_slice(), constraints, folds);
    take_back(conn, rings, &mut quadrics, taken);
    constrain_complex_flat_folds(conn, positions, &planes, &kinds, &mut quadrics, folds.flat);
    (kinds, quadrics)
}

/// Each triangle's plane once (a triangle is in three rings), on all cores.
fn face_planes(conn: &Connectivity, positions: &[Vec3]) -> Vec<FacePlane> {
    let mut planes: Vec<FacePlane> = conn
        .triangles()
        .par_iter()
        .with_min_len(PER_TASK)
        .map(|tri| {
            let [a, b, c] = tri.map(|w| positions[w as usize].as_dvec3());
            FacePlane::of(a, b, c)
        })
        .collect();
    set_scales(&mut planes);
    planes
}

/// Every vertex's kind and quadric from its own ring, on all cores.
fn ring_kinds_and_quadrics(
    conn: &Connectivity,
    positions: &[Vec3],
    planes: &[FacePlane],
    constraints: Constraints<'_>,
    folds: Folds,
) -> (Vec<Kind>, Vec<LocalQuadric>) {
    let local = |q: Quadric, v: u32| LocalQuadric::new(&q, positions[v as usize].as_dvec3());
    (0..positions.len() as u32)
        .into_par_iter()
        .with_min_len(PER_TASK)
        .map_init(Ring::default, |ring, v| {
            let kind = match conn.ring(v, ring) {
                RingShape::Closed => Kind::Interior,
                RingShape::Open => Kind::Boundary,
                RingShape::Isolated => Kind::Fixed,
                RingShape::Complex => {
                    return complex_quadric(conn, planes, v)
                        .map_or((Kind::Fixed, LocalQuadric::default()), |q| {
                            (Kind::Complex, local(q, v))
                        });
                }
            };
            let quadric = if kind == Kind::Fixed {
                Quadric::default()
            } else {
                ring_quadric(positions, planes, v, ring, kind, constraints, folds)
            };
            (kind, local(quadric, v))
        })
        .unzip()
}

/// A triangle's unit normal, plane offset and area (a zero normal: no area, no plane).
#[derive(Debug, Clone, Copy)]
struct FacePlane {
    normal: DVec3,
    d: f64,
    area: f64,
    /// √(area / the mesh's mean triangle area): a plane weighs its area times this, and a
    /// border edge's constraint on it this much more (docs/design.md#qem-face-weight).
    scale: f64,
}

/// Sets each plane's `scale` from the mean area of the triangles that have one (summed in
/// order, so the result is the same on any number of cores).
fn set_scales(planes: &mut [FacePlane]) {
    let (sum, count) = planes
        .iter()
        .filter(|p| p.area > 0.0)
        .fold((0.0, 0usize), |(s, n), p| (s + p.area, n + 1));
    if count > 0 {
        let mean = sum / count as f64;
        planes
            .par_iter_mut()
            .for_each(|p| p.scale = (p.area / mean).sqrt());
    }
}

impl FacePlane {
    fn of(a: DVec3, b: DVec3, c: DVec3) -> Self {
        let cross = (b - a).cross(c - a);
        let len = cross.length();
        if len <= 0.0 {
            return Self {
                normal: DVec3::ZERO,
                d: 0.0,
                area: 0.0,
                scale: 1.0,
            };
        }
        let normal = cross / len;
        Self {
            normal,
            d: -normal.dot(a),
            area: 0.5 * len,
            scale: 1.0,
        }
    }

    /// Its unit normal, when it has a plane.
    fn normal(&self) -> Option<DVec3> {
        (self.normal != DVec3::ZERO).then_some(self.normal)
    }

    /// Its plane weighted by its area times `scale`, with the area, when it has a plane.
    fn quadric(&self) -> Option<Quadric> {
        self.normal().map(|n| {
            let mut q = Quadric::plane(n, self.d, self.area * self.scale);
            q.area = self.area;
            q
        })
    }
}

/// The planes a non-manifold vertex `v` stands for from its own fan: its triangles' planes,
/// none through its non-manifold edges (its sheets' own planes price moving it off any of
/// them) and none yet through its boundary edges ([`constrain_outlines`] adds those that are
/// not a fin's rim; docs/design.md#qem-non-manifold-weights). `None` when a triangle at `v`
/// is degenerate (a corner repeated) or `v` has more than `MAX_VALENCE` triangles: such a
/// vertex stays fixed.
fn complex_quadric(conn: &Connectivity, planes: &[FacePlane], v: u32) -> Option<Quadric> {
    let incident = conn.incident(v);
    if incident.len() > MAX_VALENCE {
        return None;
    }
    let mut sum = Quadric::default();
    for &t in incident {
        let (_, next, prev) = corner_of(conn.triangle(t), v);
        if next == v || prev == v || next == prev {
            return None;
        }
        if let Some(q) = planes[t as usize].quadric() {
            sum.add(&q);
        }
    }
    Some(sum)
}

/// The factor every fold angle is scaled by before the feature test and weight: 1 on a
/// finely sampled mesh, `(FINE_FOLD_DEG / median fold)^FOLD_SCALE_POWER` on a coarser one,
/// where an ordinary fold is curvature sampled coarsely or scanner noise, not a crease
/// (docs/design.md#qem-fold-scale).
#[derive(Debug, Clone, Copy, PartialEq)]
struct FoldScale(f64);

/// How a vertex's folds are weighed: every fold scaled, flat folds held.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Folds {
    scale: FoldScale,
    flat: FlatFolds,
}

impl Folds {
    /// [`FoldScale::feature_cos`] of the fold along edge `a`–`b`: a flat fold held keeps its
    /// full angle, a feature however finely the mesh is sampled.
    fn feature_cos(self, cos: f64, (a, b): (DVec3, DVec3), cos_feature: f64) -> Option<f64> {
        let scale = if self.flat.holds(cos, a, b) {
            FoldScale(1.0)
        } else {
            self.scale
        };
        scale.feature_cos(cos, cos_feature)
    }
}

/// Which flat folds are held: those whose edge is at least this long, squared.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FlatFolds {
    min_length2: f64,
}

impl FlatFolds {
    /// Whether the edge `a`–`b` between triangles whose normals' cosine is `cos` is a flat
    /// fold to hold.
    fn holds(self, cos: f64, a: DVec3, b: DVec3) -> bool {
        cos < COS_FLAT_FOLD && a.distance_squared(b) >= self.min_length2
    }
}

/// The shortest flat fold held, squared: `FLAT_FOLD_MIN_EDGE² a` with `a` the model's area
/// over the result's triangles; every one without a count target.
fn flat_fold_min_length2(planes: &[FacePlane], constraints: Constraints<'_>) -> f64 {
    constraints.result_triangles.map_or(0.0, |kept| {
        let area: f64 = planes.iter().map(|p| p.area).sum();
        FLAT_FOLD_MIN_EDGE * FLAT_FOLD_MIN_EDGE * area / kept.max(1) as f64
    })
}

impl FoldScale {
    /// The scale for the mesh, from the folds of every n-th vertex's ring (a complex
    /// vertex's fan has no order, so it is passed over).
    fn of(conn: &Connectivity, n: usize, planes: &[FacePlane]) -> Self {
        let stride = n.div_ceil(FOLD_SAMPLES).max(1);
        let mut ring = Ring::default();
        let mut folds = Vec::new();
        for v in (0..n as u32).step_by(stride) {
            let closed = match conn.ring(v, &mut ring) {
                RingShape::Closed => true,
                RingShape::Open => false,
                RingShape::Isolated | RingShape::Complex => continue,
            };
            let k = ring.triangles.len();
            let normal = |i: usize| planes[ring.triangles[i] as usize].normal();
            // The edge to `verts[j]` lies between ring triangles `j - 1` and `j`.
            let first = if closed { 0 } else { 1 };
            for j in first..k {
                let before = if j == 0 { k - 1 } else { j - 1 };
                if let (Some(a), Some(b)) = (normal(before), normal(j)) {
                    folds.push(a.dot(b).clamp(-1.0, 1.0).acos());
                }
            }
        }
        Self::from_folds(&mut folds)
    }

    /// The scale for these fold angles (radians; reordered).
    fn from_folds(folds: &mut [f64]) -> Self {
        if folds.is_empty() {
            return Self(1.0);
        }
        let mid = folds.len() / 2;
        let (_, &mut median, _) = folds.select_nth_unstable_by(mid, f64::total_cmp);
        let fine = FINE_FOLD_DEG.to_radians();
        Self(if median <= fine {
            1.0
        } else {
            (fine / median).powi(FOLD_SCALE_POWER)
        })
    }

    /// The scaled cosine of a fold whose cosine is `cos`, when that is below `cos_feature`
    /// (a feature edge). Scaling only narrows a fold, so one within the feature angle by
    /// more than rounding stays within it: most edges need no `acos` and `cos`.
    fn feature_cos(self, cos: f64, cos_feature: f64) -> Option<f64> {
        if cos > cos_feature + 1e-9 {
            return None;
        }
        let scaled = self.cos(cos);
        (scaled < cos_feature).then_some(scaled)
    }

    /// The cosine of a fold whose cosine is `cos`, scaled.
    fn cos(self, cos: f64) -> f64 {
        if self.0 >= 1.0 {
            cos
        } else {
            (cos.clamp(-1.0, 1.0).acos() * self.0).cos()
        }
    }
}

/// The boundary edges at complex vertices, one pass over their fans. A fin's rim (a chain
/// of one or two boundary edges whose ends are both complex: a flap standing on a
/// non-manifold edge) is not constrained, and its boundary vertex takes back the plane it
/// put there; any other boundary edge of a complex vertex gets its constraint plane, as an
/// outline does (docs/design.md#qem-non-manifold-weights). A seam's edges keep theirs.
/// Returns the planes taken back, by boundary vertex, for [`take_back`].
fn constrain_outlines(
    conn: &Connectivity,
    positions: &[Vec3],
    planes: &[FacePlane],
    kinds: &[Kind],
    quadrics: &mut [LocalQuadric],
    constraints: Constraints<'_>,
) -> Vec<(u32, Quadric)> {
    let mut taken = Vec::new();
    let at = |w: u32| positions[w as usize].as_dvec3();
    let is = |v: u32, kind: Kind| kinds[v as usize] == kind;
    for c in (0..positions.len() as u32).filter(|&c| is(c, Kind::Complex)) {
        for &t in conn.incident(c) {
            let Some(n) = planes[t as usize].normal() else {
                continue;
            };
            let (_, next, prev) = corner_of(conn.triangle(t), c);
            for x in [next, prev] {
                if edge_triangles(conn, c, x) != 1 {
                    continue;
                }
                let fin = is(x, Kind::Complex)
                    || (is(x, Kind::Boundary)
                        && other_boundary_neighbour(conn, x, c)
                            .is_some_and(|y| is(y, Kind::Complex)));
                let seam = constraints.on_seam(c) && constraints.on_seam(x);
                let (pc, px) = (at(c), at(x));
                let edge = px - pc;
                let side = edge.cross(n).normalize_or_zero();
                let plane = |weight: f64| {
                    Quadric::plane(side, -side.dot(pc), weight * edge.length_squared())
                };
                let weight =
                    planes[t as usize].scale * if seam { SEAM_WEIGHT } else { CONSTRAINT_WEIGHT };
                if !fin {
                    quadrics[c as usize].add(&plane(weight), pc);
                } else if is(x, Kind::Boundary) && !seam {
                    taken.push((x, plane(-weight)));
                }
            }
        }
    }
    taken
}

/// Stores again each boundary vertex's quadric that `taken` takes planes back from (see
/// [`constrain_outlines`]): its ring's quadric made again in f64, less those planes, so
/// that a plane cancels against itself and not against the f32 rounding of the stored sum
/// (the heavy constraint plane's rounding error would be left as a false error, enough to
/// block a fin's zero-error collapses).
fn take_back(
    conn: &Connectivity,
    (positions, planes, constraints, folds): (&[Vec3], &[FacePlane], Constraints<'_>, Folds),
    quadrics: &mut [LocalQuadric],
    mut taken: Vec<(u32, Quadric)>,
) {
    taken.sort_by_key(|&(x, _)| x);
    let mut ring = Ring::default();
    for group in taken.chunk_by(|a, b| a.0 == b.0) {
        let x = group[0].0;
        if conn.ring(x, &mut ring) != RingShape::Open {
            continue;
        }
        let mut q = ring_quadric(
            positions,
            planes,
            x,
            &ring,
            Kind::Boundary,
            constraints,
            folds,
        );
        for (_, plane) in group {
            q.add(plane);
        }
        quadrics[x as usize] = LocalQuadric::new(&q, positions[x as usize].as_dvec3());
    }
}

/// The flat folds at complex vertices, which their rings cannot see: an edge of exactly two
/// triangles folded flat onto each other (a fin's or a doubled flake's side) gets a
/// constraint plane from each triangle, half of `FLAT_FOLD_WEIGHT` each, so the fin is not
/// folded away for nothing (docs/design.md#qem-flat-folds).
fn constrain_complex_flat_folds(
    conn: &Connectivity,
    positions: &[Vec3],
    planes: &[FacePlane],
    kinds: &[Kind],
    quadrics: &mut [LocalQuadric],
    flat: FlatFolds,
) {
    let at = |w: u32| positions[w as usize].as_dvec3();
    let complex = (0..positions.len() as u32).filter(|&c| kinds[c as usize] == Kind::Complex);
    for c in complex {
        for &t in conn.incident(c) {
            let Some(n) = planes[t as usize].normal() else {
                continue;
            };
            let (_, next, prev) = corner_of(conn.triangle(t), c);
            for x in [next, prev] {
                let mut others =
                    (conn.incident(c).iter()).filter(|&&u| u != t && conn.triangle(u).contains(&x));
                let (Some(&o), None) = (others.next(), others.next()) else {
                    continue;
                };
                let n2 = planes[o as usize].normal().unwrap_or(DVec3::ZERO);
                let (pc, px) = (at(c), at(x));
                if !flat.holds(n.dot(n2), pc, px) {
                    continue;
                }
                let edge = px - pc;
                let side = edge.cross(n).normalize_or_zero();
                let weight = 0.5 * FLAT_FOLD_WEIGHT * planes[t as usize].scale;
                let plane = Quadric::plane(side, -side.dot(pc), weight * edge.length_squared());
                quadrics[c as usize].add(&plane, pc);
            }
        }
    }
}

/// How many triangles at `a` have the edge `a`–`b` (a complex or boundary vertex's fan is
/// at most `MAX_VALENCE` long).
fn edge_triangles(conn: &Connectivity, a: u32, b: u32) -> usize {
    let incident = conn.incident(a);
    incident
        .iter()
        .filter(|&&u| conn.triangle(u).contains(&b))
        .count()
}

/// The boundary vertex `x`'s neighbour along its boundary other than `c`, when it has one.
fn other_boundary_neighbour(conn: &Connectivity, x: u32, c: u32) -> Option<u32> {
    conn.incident(x).iter().find_map(|&t| {
        let (_, next, prev) = corner_of(conn.triangle(t), x);
        [next, prev]
            .into_iter()
            .find(|&y| y != c && edge_triangles(conn, x, y) == 1)
    })
}

/// The planes `v` stands for, from its ring and the triangles' `planes`.
fn ring_quadric(
    positions: &[Vec3],
    planes: &[FacePlane],
    v: u32,
    ring: &Ring,
    kind: Kind,
    constraints: Constraints<'_>,
    folds: Folds,
) -> Quadric {
    let at = |w: u32| positions[w as usize].as_dvec3();
    // Ring triangle `i`'s normal, when it has a plane.
    let normal = |i: usize| planes[ring.triangles[i] as usize].normal();
    let mut sum = Quadric::default();
    for q in ring
        .triangles
        .iter()
        .filter_map(|&t| planes[t as usize].quadric())
    {
        sum.add(&q);
    }
    let k = ring.triangles.len();
    let closed = kind == Kind::Interior;
    for (j, &x) in ring.verts.iter().enumerate() {
        let before = if j > 0 {
            Some(j - 1)
        } else {
            closed.then(|| k - 1)
        };
        let after = (j < k).then_some(j);
        // The edge as its triangle `i` runs it: v → x in triangle j, x → v in triangle j - 1.
        let run = |i: usize| if i == j { (v, x) } else { (x, v) };
        let mut constrain = |(u, w): (u32, u32), n: DVec3, weight: f64| {
            let (pu, pw) = (at(u), at(w));
            let edge = pw - pu;
            let side = edge.cross(n).normalize_or_zero();
            sum.add(&Quadric::plane(
                side,
                -side.dot(pu),
                weight * edge.length_squared(),
            ));
        };
        match (before, after) {
            (Some(i), None) | (None, Some(i)) => {
                if let Some(n) = normal(i) {
                    let weight = if constraints.on_seam(v) && constraints.on_seam(x) {
                        SEAM_WEIGHT
                    } else {
                        CONSTRAINT_WEIGHT
                    };
                    let scale = planes[ring.triangles[i] as usize].scale;
                    constrain(run(i), n, weight * scale);
                }
            }
            (Some(a), Some(b)) => {
                // Seen from the triangle whose id is smaller, as the edge runs there.
                let (i, o) = if ring.triangles[a] < ring.triangles[b] {
                    (a, b)
                } else {
                    (b, a)
                };
                let Some(n) = normal(i) else {
                    continue;
                };
                let n2 = normal(o).unwrap_or(DVec3::ZERO);
                let cos = n.dot(n2);
                if let Some(cos) = folds.feature_cos(cos, (at(v), at(x)), constraints.cos_feature) {
                    let weight = FEATURE_WEIGHT * (1.0 - cos).powi(6);
                    constrain(run(i), n, weight);
                    constrain(run(i), n2, weight);
                }
            }
            (None, None) => {}
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    fn start(model: &crate::mesh::Model) -> (Vec<Kind>, Vec<Quadric>) {
        start_scaled(model, true)
    }

    fn start_scaled(model: &crate::mesh::Model, scale_folds: bool) -> (Vec<Kind>, Vec<Quadric>) {
        let conn = Connectivity::new(model.positions.len(), &model.triangles);
        let (kinds, quadrics) = kinds_and_quadrics(
            &conn,
            &model.positions,
            Constraints {
                cos_feature: 60f64.to_radians().cos(),
                scale_folds,
                seam: &[],
                result_triangles: None,
            },
        );
        let positions = model.positions.iter().map(|p| p.as_dvec3());
        let quadrics = quadrics.iter().zip(positions).map(|(q, p)| q.at(p));
        (kinds, quadrics.collect())
    }

    fn vertex_at(model: &crate::mesh::Model, p: Vec3) -> usize {
        model
            .positions
            .iter()
            .position(|&q| q == p)
            .unwrap_or(usize::MAX)
    }

    #[test]
    fn a_cube_corner_is_pinned_and_a_face_vertex_slides_in_its_face() {
        let cube = shapes::test002(); // side 2, centred at the origin
        let (kinds, quadrics) = start(&cube);
        assert!(kinds.iter().all(|&k| k == Kind::Interior));
        let corner = vertex_at(&cube, Vec3::ONE);
        let q = &quadrics[corner];
        let at = q.minimum().unwrap_or(DVec3::ZERO);
        assert!((at - DVec3::ONE).length() < 1e-9, "corner moves to {at}");
        // The centre of the +x face: free in its plane, held off it.
        let centre = vertex_at(&cube, Vec3::X);
        let q = &quadrics[centre];
        assert!(q.eval(DVec3::new(1.0, 0.3, -0.2)) < 1e-12);
        assert!(q.eval(DVec3::new(1.1, 0.0, 0.0)) > 1e-3);
    }

    /// An `n` × `n` sheet of unit squares in z = 0 whose inner vertices are lifted by
    /// `lift(i, j)`, each square split along one diagonal.
    fn sheet(n: u32, lift: impl Fn(u32, u32) -> f32) -> crate::mesh::Model {
        let inner = |i: u32, j: u32| i > 0 && j > 0 && i < n && j < n;
        shapes::height_grid(n, |i, j| if inner(i, j) { lift(i, j) } else { 0.0 })
    }

    /// The sum of `v`'s triangles' area-weighted planes: its quadric without constraints.
    fn face_quadric(model: &crate::mesh::Model, v: u32) -> Quadric {
        let conn = Connectivity::new(model.positions.len(), &model.triangles);
        let planes = face_planes(&conn, &model.positions);
        let mut sum = Quadric::default();
        for &t in conn.incident(v) {
            if let Some(q) = planes[t as usize].quadric() {
                sum.add(&q);
            }
        }
        sum
    }

    fn fold_scale(model: &crate::mesh::Model) -> FoldScale {
        let conn = Connectivity::new(model.positions.len(), &model.triangles);
        FoldScale::of(
            &conn,
            model.positions.len(),
            &face_planes(&conn, &model.positions),
        )
    }

    #[test]
    fn the_fold_scale_is_one_up_to_a_fine_median_fold_and_shrinks_as_its_fourth_power() {
        let deg = |d: f64| d.to_radians();
        let scale = |folds: &[f64]| FoldScale::from_folds(&mut folds.to_vec()).0;
        assert_eq!(scale(&[]), 1.0);
        assert_eq!(
            scale(&[deg(90.0), deg(2.0), deg(3.0), 0.0, deg(170.0)]),
            1.0
        );
        let s = scale(&[deg(6.0), deg(90.0), deg(6.0), deg(1.0), deg(6.0)]);
        assert!((s - 1.0 / 16.0).abs() < 1e-12, "{s}");
        // Scaled, a right angle on that mesh is a fold of 90° / 16.
        let cos = FoldScale(s).cos(0.0);
        assert!((cos - deg(90.0 / 16.0).cos()).abs() < 1e-12);
        assert_eq!(FoldScale(1.0).cos(0.3), 0.3, "untouched when fine");
    }

    #[test]
    fn the_feature_test_skips_the_scaled_cosine_only_where_it_cannot_change_the_answer() {
        // Every fold, scale and feature angle, near the threshold too: the quick answer is
        // the scaled cosine's own.
        for scale in [1.0, 0.9, 1.0 / 16.0, 1e-3] {
            let folds = FoldScale(scale);
            for feature_deg in [0.0, 10.0, 30.0, 60.0, 89.0, 179.0] {
                let cos_feature: f64 = f64::to_radians(feature_deg).cos();
                let near = (-20..=20).map(|k| cos_feature + f64::from(k) * 1e-10);
                for cos in (-100..=100).map(|k| f64::from(k) / 100.0).chain(near) {
                    let scaled = folds.cos(cos);
                    let expected = (scaled < cos_feature).then_some(scaled);
                    assert_eq!(
                        folds.feature_cos(cos, cos_feature),
                        expected,
                        "cos {cos}, scale {scale}, feature angle {feature_deg}°"
                    );
                }
            }
        }
    }

    #[test]
    fn a_box_of_flat_faces_is_fine_and_its_crease_vertex_is_held_on_its_crease() {
        let cube = shapes::cube(4, 2.0); // side 2, 4 × 4 squares a face
        assert_eq!(fold_scale(&cube), FoldScale(1.0), "most folds are flat");
        let (_, quadrics) = start(&cube);
        // On the edge y = z = 1, between two corners: it slides along it, not off it.
        let v = vertex_at(&cube, Vec3::new(0.5, 1.0, 1.0));
        let q = &quadrics[v];
        assert!(
            q.eval(DVec3::new(0.2, 1.0, 1.0)) < 1e-12,
            "along the crease"
        );
        let face_only = face_quadric(&cube, v as u32);
        let off = DVec3::new(0.5, 0.9, 0.9);
        assert!(
            q.eval(off) > 10.0 * face_only.eval(off),
            "its feature planes hold it: {} against {}",
            q.eval(off),
            face_only.eval(off)
        );
    }

    #[test]
    fn a_noisy_sheets_folds_are_not_features() {
        // Every inner vertex lifted up or down by 0.5 in a fixed pseudo-random pattern: most
        // folds are tens of degrees, many beyond the 60° feature angle of `start`.
        let noisy = sheet(12, |i, j| if (i * 7 + j * 3) % 5 < 2 { 0.5 } else { -0.5 });
        let FoldScale(s) = fold_scale(&noisy);
        assert!(s < 0.01, "fold scale {s}");
        let (kinds, quadrics) = start(&noisy);
        let conn = Connectivity::new(noisy.positions.len(), &noisy.triangles);
        let planes = face_planes(&conn, &noisy.positions);
        let mut sharp = 0;
        for v in (0..noisy.positions.len() as u32).filter(|&v| kinds[v as usize] == Kind::Interior)
        {
            let t: Vec<u32> = conn.incident(v).to_vec();
            for (a, b) in t.iter().flat_map(|&a| t.iter().map(move |&b| (a, b))) {
                let (ta, tb) = (conn.triangle(a), conn.triangle(b));
                let shared = ta.iter().filter(|w| tb.contains(w)).count();
                let (na, nb) = (planes[a as usize].normal, planes[b as usize].normal);
                if a < b && shared == 2 && na.dot(nb) < 0.5 {
                    sharp += 1;
                }
            }
            // Its quadric is its triangles' planes and nothing more (to f32's precision:
            // it is stored in f32).
            let (q, face_only) = (&quadrics[v as usize], face_quadric(&noisy, v));
            for p in [DVec3::new(3.0, 4.0, 1.0), DVec3::new(6.5, 2.0, -2.0)] {
                let (e, f) = (q.eval(p), face_only.eval(p));
                assert!(
                    (e - f).abs() <= 1e-6 * f.max(1.0),
                    "vertex {v}: {e} against {f}"
                );
            }
        }
        assert!(sharp > 20, "only {sharp} folds beyond 60°");
        // Unscaled (a tile, a merge of decimated tiles), its sharp folds are features.
        let (_, held) = start_scaled(&noisy, false);
        let p = DVec3::new(6.5, 2.0, -2.0);
        let more = (0..noisy.positions.len() as u32)
            .filter(|&v| held[v as usize].eval(p) > 1.5 * face_quadric(&noisy, v).eval(p))
            .count();
        assert!(more > 20, "only {more} vertices hold feature planes");
    }

    #[test]
    fn a_plane_boundary_vertex_slides_only_along_the_outline() {
        let plane = shapes::test003(); // 10 × 10 in z = 0
        let (kinds, quadrics) = start(&plane);
        let edge = vertex_at(&plane, Vec3::new(5.0, 0.0, 0.0));
        let inside = vertex_at(&plane, Vec3::new(5.0, 5.0, 0.0));
        assert_eq!(kinds[edge], Kind::Boundary);
        assert_eq!(kinds[inside], Kind::Interior);
        let q = &quadrics[edge];
        assert!(
            q.eval(DVec3::new(5.5, 0.0, 0.0)) < 1e-12,
            "along the outline"
        );
        assert!(q.eval(DVec3::new(5.0, 0.5, 0.0)) > 1.0, "into the plane");
        let q = &quadrics[inside];
        assert!(
            q.eval(DVec3::new(5.5, 4.5, 0.0)) < 1e-12,
            "an interior vertex is free"
        );
        assert!(q.eval(DVec3::new(5.0, 5.0, 0.1)) > 1e-3, "off the plane");
    }
}

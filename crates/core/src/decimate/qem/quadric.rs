//! The Garland–Heckbert error quadric: the summed squared distance to a set of weighted
//! planes, `Q(p) = pᵀAp + 2b·p + c`, with the triangle area behind it.
//!
//! Arithmetic is in f64 in model coordinates ([`Quadric`]). Each vertex's quadric is stored
//! in f32 about the vertex's own position ([`LocalQuadric`], 44 bytes): there its terms are
//! of the order of the error itself, where in model coordinates `c` and `2b·p` would cancel
//! down to `weight × error²` and lose it in f32 (docs/design.md#quadric-precision).

use glam::{DMat2, DVec2, DVec3};

/// A symmetric 4×4 quadric `Q(p) = pᵀAp + 2b·p + c`, with the area behind it.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Quadric {
    /// `a00 a01 a02 a11 a12 a22`.
    a: [f64; 6],
    b: [f64; 3],
    c: f64,
    /// Summed area of the triangles whose planes are in the quadric.
    pub area: f64,
}

impl Quadric {
    /// The plane `n·p + d = 0` (unit `n`) with `weight`.
    pub fn plane(n: DVec3, d: f64, weight: f64) -> Self {
        Self {
            a: [
                weight * n.x * n.x,
                weight * n.x * n.y,
                weight * n.x * n.z,
                weight * n.y * n.y,
                weight * n.y * n.z,
                weight * n.z * n.z,
            ],
            b: [weight * n.x * d, weight * n.y * d, weight * n.z * d],
            c: weight * d * d,
            area: 0.0,
        }
    }

    #[inline]
    pub fn add(&mut self, o: &Self) {
        for i in 0..6 {
            self.a[i] += o.a[i];
        }
        for i in 0..3 {
            self.b[i] += o.b[i];
        }
        self.c += o.c;
        self.area += o.area;
    }

    #[inline]
    pub fn sum(&self, o: &Self) -> Self {
        let mut s = *self;
        s.add(o);
        s
    }

    /// `A·p`.
    #[inline]
    fn a_times(&self, p: DVec3) -> DVec3 {
        let [a00, a01, a02, a11, a12, a22] = self.a;
        DVec3::new(
            a00 * p.x + a01 * p.y + a02 * p.z,
            a01 * p.x + a11 * p.y + a12 * p.z,
            a02 * p.x + a12 * p.y + a22 * p.z,
        )
    }

    /// The same quadric about `s`: `Q(s + d)` as a quadric in `d` (`A` stays, `b` becomes
    /// `b + A·s`, `c` becomes `Q(s)`).
    #[inline]
    fn shifted(&self, s: DVec3) -> Self {
        let a_s = self.a_times(s);
        let b = DVec3::from_array(self.b);
        Self {
            a: self.a,
            b: (b + a_s).to_array(),
            c: s.dot(a_s) + 2.0 * b.dot(s) + self.c,
            area: self.area,
        }
    }

    /// `Q(p)`, never negative.
    #[inline]
    pub fn eval(&self, p: DVec3) -> f64 {
        let ap = self.a_times(p);
        let b = DVec3::from_array(self.b);
        (p.dot(ap) + 2.0 * b.dot(p) + self.c).max(0.0)
    }

    /// The minimiser `-A⁻¹b`, or `None` when `A` is (nearly) singular.
    #[inline]
    pub fn minimum(&self) -> Option<DVec3> {
        let [a00, a01, a02, a11, a12, a22] = self.a;
        let c0 = a11 * a22 - a12 * a12;
        let c1 = a02 * a12 - a01 * a22;
        let c2 = a01 * a12 - a02 * a11;
        let det = a00 * c0 + a01 * c1 + a02 * c2;
        let trace = a00 + a11 + a22;
        let singular = det.abs() <= 1e-9 * trace * trace * trace;
        if singular || !det.is_finite() {
            return None;
        }
        // Inverse of a symmetric matrix from its cofactors.
        let i01 = c1;
        let i02 = c2;
        let i11 = a00 * a22 - a02 * a02;
        let i12 = a01 * a02 - a00 * a12;
        let i22 = a00 * a11 - a01 * a01;
        let [b0, b1, b2] = self.b;
        let inv = -1.0 / det;
        let x = (c0 * b0 + i01 * b1 + i02 * b2) * inv;
        let y = (i01 * b0 + i11 * b1 + i12 * b2) * inv;
        let z = (i02 * b0 + i12 * b1 + i22 * b2) * inv;
        let p = DVec3::new(x, y, z);
        p.is_finite().then_some(p)
    }
}

/// A vertex's quadric as stored: `Q(p + d)` as a quadric in `d`, about the vertex's own
/// position `p`, in f32 (10 numbers and the area, 44 bytes). About `p` the coefficients are
/// of the order of the error near the vertex, so f32 keeps what model coordinates would
/// cancel away; adding and evaluating go through [`Self::at`] in f64. `A` is kept as its
/// factors `L·D·Lᵀ`: rounding those keeps a direction that costs nothing (along a flat
/// sheet, along a border) costing nothing, where rounding `A`'s entries one by one would
/// price it at f32's precision times the planes' weight. Whoever moves a vertex stores its
/// quadric again about the new position.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct LocalQuadric {
    /// `d0 d1 d2 l10 l20 l21`: `A = L·diag(d)·Lᵀ`, `L` unit lower triangular.
    ldl: [f32; 6],
    b: [f32; 3],
    c: f32,
    area: f32,
}

impl LocalQuadric {
    /// `q` (model coordinates) stored about `p`.
    #[inline]
    pub fn new(q: &Quadric, p: DVec3) -> Self {
        let l = q.shifted(p);
        Self {
            ldl: factors(l.a).map(|x| x as f32),
            b: l.b.map(|x| x as f32),
            c: l.c as f32,
            area: l.area as f32,
        }
    }

    /// The quadric in model coordinates, for its vertex at `p`.
    #[inline]
    pub fn at(&self, p: DVec3) -> Quadric {
        let [d0, d1, d2, l10, l20, l21] = self.ldl.map(f64::from);
        let (e10, e20) = (l10 * d0, l20 * d0);
        let local = Quadric {
            a: [
                d0,
                e10,
                e20,
                l10 * e10 + d1,
                l20 * e10 + l21 * d1,
                l20 * e20 + l21 * l21 * d1 + d2,
            ],
            b: self.b.map(f64::from),
            c: f64::from(self.c),
            area: f64::from(self.area),
        };
        local.shifted(-p)
    }

    /// Adds `q` (model coordinates) to the quadric of a vertex at `p`.
    pub fn add(&mut self, q: &Quadric, p: DVec3) {
        *self = Self::new(&self.at(p).sum(q), p);
    }

    /// Asks the CPU to start loading every cache line the quadric spans (a hint).
    #[inline]
    pub fn prefetch(&self) {
        crate::mesh::prefetch_all(self);
    }
}

/// `a00 a01 a02 a11 a12 a22` (symmetric, positive semi-definite up to rounding) as
/// `d0 d1 d2 l10 l20 l21` of `L·diag(d)·Lᵀ`; a pivot below `1e-20 × trace` (nothing left in
/// that direction) gets no column below it.
fn factors(a: [f64; 6]) -> [f64; 6] {
    let [a00, a01, a02, a11, a12, a22] = a;
    let tiny = 1e-20 * (a00.abs() + a11.abs() + a22.abs());
    let below = |x: f64, pivot: f64| if pivot > tiny { x / pivot } else { 0.0 };
    let d0 = a00;
    let (l10, l20) = (below(a01, d0), below(a02, d0));
    let d1 = a11 - l10 * l10 * d0;
    let l21 = below(a12 - l20 * l10 * d0, d1);
    let d2 = a22 - l20 * l20 * d0 - l21 * l21 * d1;
    [d0, d1, d2, l10, l20, l21]
}

/// The attributes' part of a vertex's error (H. Hoppe, "New Quadric Metric for Simplifying
/// Meshes with Appearance Attributes", IEEE Visualization 1999), for `N` channels: texture
/// coordinates (u, v) or a colour (r, g, b). Each triangle's values define an affine map
/// `s(p) = g·p + d` over its plane, one per channel. A vertex at `p` with values `s` is off
/// the maps of the triangles it stands for by `E(p, s) = Σ area·|g·p + d − s|²`; the sums
/// kept here give `E` for any `p` and `s`, and the best `s` at `p` (the area-weighted mean
/// of the maps). The values are in model units (scaled by the caller), so that `E` is in the
/// units of the geometric quadric. 88 + 32·N bytes a vertex, on models with the attribute
/// only.
#[derive(Debug, Clone, Copy)]
pub(super) struct AttributeQuadric<const N: usize> {
    /// `Σ area·|g·p + d|²` over the channels, as a quadric in `p`, with `Σ area`.
    maps: Quadric,
    /// `Σ area·g` and `Σ area·d`, per channel.
    g: [DVec3; N],
    d: [f64; N],
}

/// Texture coordinates' quadric: u and v.
pub(super) type TextureQuadric = AttributeQuadric<2>;

/// A colour's quadric: r, g and b.
pub(super) type ColourQuadric = AttributeQuadric<3>;

impl<const N: usize> Default for AttributeQuadric<N> {
    fn default() -> Self {
        Self {
            maps: Quadric::default(),
            g: [DVec3::ZERO; N],
            d: [0.0; N],
        }
    }
}

impl<const N: usize> AttributeQuadric<N> {
    /// The maps of the triangle `p` with values `s` (model units), weighted by its area;
    /// `None` when the triangle has no area.
    pub fn face(p: [DVec3; 3], s: [[f64; N]; 3]) -> Option<Self> {
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let gram = DMat2::from_cols_array(&[e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2)]);
        let det = gram.determinant();
        // |e1 × e2|² = det: the triangle's doubled area, squared.
        if det <= 0.0 || !det.is_finite() {
            return None;
        }
        let area = 0.5 * det.sqrt();
        let inverse = gram.inverse();
        let mut q = Self::default();
        q.maps.area = area;
        let [s0, s1, s2] = s;
        for (j, ((x0, x1), x2)) in s0.into_iter().zip(s1).zip(s2).enumerate() {
            // g in the triangle's plane with g·e1 = ds1, g·e2 = ds2.
            let ab = inverse * DVec2::new(x1 - x0, x2 - x0);
            let g = ab.x * e1 + ab.y * e2;
            let d = x0 - g.dot(p[0]);
            let n = g.length();
            if n > 0.0 {
                // The map's square as a plane's: area·|g|²·(ĝ·p + d/|g|)².
                q.maps.add(&Quadric::plane(g / n, d / n, area * n * n));
            } else {
                q.maps.c += area * d * d;
            }
            q.g[j] = area * g;
            q.d[j] = area * d;
        }
        q.is_finite().then_some(q)
    }

    fn is_finite(&self) -> bool {
        let m = &self.maps;
        m.a.iter().chain(&m.b).all(|x| x.is_finite())
            && m.c.is_finite()
            && self.g.iter().all(|g| g.is_finite())
    }

    #[inline]
    pub fn add(&mut self, o: &Self) {
        self.maps.add(&o.maps);
        for j in 0..N {
            self.g[j] += o.g[j];
            self.d[j] += o.d[j];
        }
    }

    #[inline]
    pub fn sum(&self, o: &Self) -> Self {
        let mut s = *self;
        s.add(o);
        s
    }

    /// `E(p, s)` at the best `s` for each `p`, as a quadric in `p` alone, times `weight`: to
    /// add to the geometric quadric, so that a placement minimises both.
    pub fn at_best_coordinates(&self, weight: f64) -> Quadric {
        let mut q = Quadric::default();
        let m = &self.maps;
        if m.area <= 0.0 {
            return q;
        }
        let w = 1.0 / m.area;
        let (g, d) = (&self.g, &self.d);
        let outer = |i: usize, k: usize| g.iter().map(|g| g[i] * g[k]).sum::<f64>();
        let pairs = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];
        for (a, (i, k)) in q.a.iter_mut().zip(pairs) {
            *a = weight * (m.a[a_index(i, k)] - w * outer(i, k));
        }
        for (i, b) in q.b.iter_mut().enumerate() {
            let gd = g.iter().zip(d).map(|(g, d)| g[i] * d).sum::<f64>();
            *b = weight * (m.b[i] - w * gd);
        }
        q.c = weight * (m.c - w * d.iter().map(|d| d * d).sum::<f64>());
        q
    }

    /// The best values at `p`: the area-weighted mean of the triangles' maps there.
    pub fn best_coordinates(&self, p: DVec3) -> [f64; N] {
        let w = 1.0 / self.maps.area.max(f64::MIN_POSITIVE);
        std::array::from_fn(|j| (self.g[j].dot(p) + self.d[j]) * w)
    }

    /// How much `E(p, s)` exceeds `E` at the best values (see
    /// [`Self::at_best_coordinates`]), for the values `s`.
    pub fn excess(&self, p: DVec3, s: [f64; N]) -> f64 {
        if self.maps.area <= 0.0 {
            return 0.0;
        }
        let best = self.best_coordinates(p);
        let d2 = best
            .iter()
            .zip(&s)
            .map(|(b, s)| (b - s) * (b - s))
            .sum::<f64>();
        d2 * self.maps.area
    }
}

/// The index in `a00 a01 a02 a11 a12 a22` of `a_ik` (`i <= k`).
fn a_index(i: usize, k: usize) -> usize {
    match (i, k) {
        (0, k) => k,
        (1, k) => 2 + k,
        _ => 5,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_planes_meet_at_their_corner() {
        let mut q = Quadric::default();
        for (n, d) in [(DVec3::X, -1.0), (DVec3::Y, -2.0), (DVec3::Z, -3.0)] {
            q.add(&Quadric::plane(n, d, 1.0));
        }
        let p = q.minimum().unwrap_or(DVec3::ZERO);
        assert!((p - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
        assert!(q.eval(p) < 1e-12);
        // Two planes leave a line: singular.
        let mut line = Quadric::default();
        line.add(&Quadric::plane(DVec3::X, 0.0, 1.0));
        line.add(&Quadric::plane(DVec3::Y, 0.0, 1.0));
        assert!(line.minimum().is_none());
        assert_eq!(line.eval(DVec3::new(0.0, 0.0, 5.0)), 0.0);
        assert_eq!(line.eval(DVec3::new(3.0, 4.0, 0.0)), 25.0);
    }

    #[test]
    fn a_far_vertex_keeps_its_error_in_f32() {
        // Planes through points a millimetre around a vertex 200 m from the origin: stored
        // about the vertex, the quadric's error near it is the f64 one to f32's precision
        // (in model coordinates f32 would cancel it away: `c` alone is ~1e4 × weight, the
        // error ~1e-6 × weight).
        let p = DVec3::new(100.0, -200.0, 50.0);
        let mut q = Quadric::default();
        for (i, n) in [
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.2),
            DVec3::new(-0.3, 0.5, 1.0),
        ]
        .into_iter()
        .enumerate()
        {
            let n = n.normalize();
            let through = p + DVec3::splat(1e-3 * (i as f64 - 1.0));
            let mut plane = Quadric::plane(n, -n.dot(through), 2.0 + i as f64);
            plane.area = 0.5;
            q.add(&plane);
        }
        let stored = LocalQuadric::new(&q, p);
        let back = stored.at(p);
        assert!((back.area - 1.5).abs() < 1e-6);
        for d in [
            DVec3::ZERO,
            DVec3::new(2e-3, -1e-3, 0.5e-3),
            DVec3::splat(-3e-3),
        ] {
            let (x, y) = (q.eval(p + d), back.eval(p + d));
            assert!(x > 1e-7 && (x - y).abs() < 1e-4 * x, "{x} vs {y} at {d}");
        }
        let (m, n) = (q.minimum(), back.minimum());
        assert!(m.zip(n).is_some_and(|(m, n)| (m - n).length() < 1e-6));
    }

    #[test]
    fn a_tilted_flat_fan_stays_flat_in_f32() {
        // Planes of one tilted plane (no axis in it), and a border's constraint plane across
        // it: moving the vertex along the border costs nothing in f64, and must in f32 too.
        // Rounding `A`'s entries one by one would leave ~6e-8 × weight in every direction.
        let n = DVec3::new(0.3, -0.5, 0.8).normalize();
        let along = n.cross(DVec3::new(1.0, 0.2, 0.1)).normalize();
        let side = along.cross(n);
        let p = DVec3::new(0.7, -0.2, 0.4);
        let mut q = Quadric::plane(n, -n.dot(p), 1.7);
        q.add(&Quadric::plane(side, -side.dot(p), 30.0));
        let stored = LocalQuadric::new(&q, p).at(p);
        for t in [0.25, -1.0, 3.0] {
            let x = p + t * along;
            assert!(q.eval(x) < 1e-12, "{}", q.eval(x));
            assert!(stored.eval(x) < 1e-12, "{} at {t}", stored.eval(x));
        }
        // Across the border and off the plane it costs what f64 says, to f32's precision.
        for d in [0.1 * side, 0.2 * n, 0.3 * (n + side)] {
            let (x, y) = (q.eval(p + d), stored.eval(p + d));
            assert!((x - y).abs() < 1e-6 * x, "{x} vs {y} at {d}");
        }
    }

    #[test]
    fn an_affine_texture_costs_nothing_anywhere_in_its_plane() {
        // A tilted fan whose coordinates are one affine map of the position: moving the
        // vertex anywhere in the plane slides nothing, and the best coordinates are the map.
        let map = |p: DVec3| DVec2::new(0.3 * p.x - 0.2 * p.y + 1.0, 0.5 * p.y + 0.1 * p.x);
        let lift = |x: f64, y: f64| DVec3::new(x, y, 0.25 * x - 0.5 * y + 2.0);
        let ring = [
            (1.0, 0.0),
            (0.0, 1.0),
            (-1.0, 0.2),
            (-0.3, -1.0),
            (0.8, -0.7),
        ];
        let centre = lift(0.1, 0.05);
        let mut t = TextureQuadric::default();
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            let p = [centre, lift(a.0, a.1), lift(b.0, b.1)];
            if let Some(f) = TextureQuadric::face(p, p.map(|q| map(q).to_array())) {
                t.add(&f);
            }
        }
        assert!(t.maps.area > 1.0);
        let q = t.at_best_coordinates(1.0);
        for p in [lift(0.5, -0.4), lift(-3.0, 2.0)] {
            assert!(q.eval(p) < 1e-9, "{}", q.eval(p));
            assert!((DVec2::from(t.best_coordinates(p)) - map(p)).length() < 1e-9);
            // Other coordinates cost area × distance².
            let off = map(p) + DVec2::new(0.1, 0.0);
            assert!((t.excess(p, off.to_array()) - 0.01 * t.maps.area).abs() < 1e-9);
        }
        // Off the plane the map still holds: a texture alone does not hold the surface.
        assert!(q.eval(centre + DVec3::Z) >= 0.0);
    }

    #[test]
    fn a_bent_texture_costs_where_the_maps_disagree() {
        // Two triangles sharing the edge x = 0; u = x on the left, u = 2x on the right.
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let uv = |x: f64, y: f64| DVec2::new(if x < 0.0 { x } else { 2.0 * x }, y);
        let left = [p(0.0, 0.0), p(-1.0, 0.5), p(0.0, 1.0)];
        let right = [p(0.0, 0.0), p(0.0, 1.0), p(1.0, 0.5)];
        let mut t = TextureQuadric::default();
        for tri in [left, right] {
            let s = tri.map(|q| uv(q.x, q.y).to_array());
            if let Some(f) = TextureQuadric::face(tri, s) {
                t.add(&f);
            }
        }
        let q = t.at_best_coordinates(1.0);
        // On the shared edge both maps agree; at x = 1 they differ by 1.
        assert!(q.eval(p(0.0, 0.3)) < 1e-12);
        let off = q.eval(p(1.0, 0.3));
        // Best u = 1.5 (equal areas), each map 0.5 off: 0.5 × (0.25 + 0.25).
        assert!((off - 0.25).abs() < 1e-9, "{off}");
        assert!((t.best_coordinates(p(1.0, 0.3))[0] - 1.5).abs() < 1e-12);
    }
}

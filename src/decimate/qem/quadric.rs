//! The Garland–Heckbert error quadric: the summed squared distance to a set of weighted
//! planes, `Q(p) = pᵀAp + 2b·p + c`, with the triangle area behind it.
//!
//! Kept in f64 in model coordinates, 88 bytes a vertex. In f32 in model coordinates it
//! cannot work: `c` and `2b·p` are of the order of `weight × (distance to the origin)²` and
//! cancel down to `weight × error²`, about eight orders of magnitude less on the dragon. In
//! f32 about each vertex's own position (44 bytes padded to one 64-byte line, 28 MB instead
//! of 38 on the dragon; a plan moves one end's quadric to the other's position first, a
//! collapse both to the new one) the terms stay of the order of the error and it works, but
//! on the dragon kept at 10 % it was no faster (16 alternating pairs of runs, median ratio
//! 1.00; presumably the plan's extra arithmetic ate the lighter loads) and the mean error
//! rose from 9.160e-6 to 9.170e-6, so it was not adopted.

use glam::DVec3;

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

    /// Asks the CPU to start loading every cache line the quadric spans (a hint).
    #[inline]
    pub fn prefetch(&self) {
        crate::mesh::prefetch_all(self);
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

    /// `Q(p)`, never negative.
    #[inline]
    pub fn eval(&self, p: DVec3) -> f64 {
        let [a00, a01, a02, a11, a12, a22] = self.a;
        let ap = DVec3::new(
            a00 * p.x + a01 * p.y + a02 * p.z,
            a01 * p.x + a11 * p.y + a12 * p.z,
            a02 * p.x + a12 * p.y + a22 * p.z,
        );
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
}

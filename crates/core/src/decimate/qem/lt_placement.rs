//! Lindström–Turk placement (Lindström, Turk, "Fast and memory efficient polygonal
//! simplification", 1998): the kept vertex is the solution of three linear constraints,
//! gathered in a fixed order of priority (volume kept, boundary kept, volume and boundary
//! change least, triangle shape) until three are independent. A constraint that is nearly
//! a combination of those taken already is left out (the paper's α test), so that the
//! solution never hangs on a near-singular system.

use glam::{DMat3, DVec3};

/// The α test's angle: a new constraint is taken only when its normal is at least this far
/// from the line or plane spanned by those taken (1° in the paper).
const ALPHA_DEG: f64 = 1.0;

/// Up to three independent linear constraints `rows[i] · v = rhs[i]`, rows of unit length.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Constraints {
    rows: [DVec3; 3],
    rhs: [f64; 3],
    n: usize,
}

impl Constraints {
    /// True once three constraints are taken: the placement is decided.
    pub fn full(&self) -> bool {
        self.n == 3
    }

    /// Takes `a · v = b` when it is independent enough of those taken (the α test);
    /// returns whether it did.
    pub fn add(&mut self, a: DVec3, b: f64) -> bool {
        let len = a.length();
        if self.full() || !(len > 0.0 && len.is_finite() && b.is_finite()) {
            return false;
        }
        let (a, b) = (a / len, b / len);
        let (sin, cos) = ALPHA_DEG.to_radians().sin_cos();
        let independent = match self.n {
            0 => true,
            1 => a.dot(self.rows[0]).powi(2) < cos * cos,
            _ => {
                let normal = self.rows[0].cross(self.rows[1]);
                a.dot(normal).powi(2) > sin * sin * normal.length_squared()
            }
        };
        if independent {
            self.rows[self.n] = a;
            self.rhs[self.n] = b;
            self.n += 1;
        }
        independent
    }

    /// Takes the constraints that put `v` at the minimum of `vᵀHv − 2c·v` within those
    /// taken already: the gradient's components along the directions still free vanish.
    pub fn add_objective(&mut self, h: DMat3, c: DVec3) {
        match self.n {
            0 => {
                for i in 0..3 {
                    self.add(h.row(i), c[i]);
                }
            }
            1 => {
                let (q1, q2) = self.rows[0].any_orthonormal_pair();
                for q in [q1, q2] {
                    self.add(h * q, q.dot(c));
                }
            }
            2 => {
                let q = self.rows[0].cross(self.rows[1]).normalize_or_zero();
                self.add(h * q, q.dot(c));
            }
            _ => {}
        }
    }

    /// The point that meets all three constraints, once [`Self::full`].
    pub fn solve(&self) -> Option<DVec3> {
        if !self.full() {
            return None;
        }
        let m = DMat3::from_cols(self.rows[0], self.rows[1], self.rows[2]).transpose();
        let det = m.determinant();
        if det.abs() < 1e-12 {
            return None;
        }
        let p = m.inverse() * DVec3::from(self.rhs);
        p.is_finite().then_some(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_independent_planes_meet_at_their_point() {
        let mut c = Constraints::default();
        assert!(c.add(DVec3::X, 1.0));
        // Half a degree off the first: left out by the α test.
        let near = DVec3::new(1.0, 0.5_f64.to_radians().tan(), 0.0);
        assert!(!c.add(near, 5.0));
        assert!(c.add(DVec3::new(0.0, 2.0, 0.0), 4.0));
        // In the plane of the first two: left out.
        assert!(!c.add(DVec3::new(1.0, 1.0, 0.0), 3.0));
        assert!(c.add(DVec3::Z, -3.0));
        let p = c.solve().expect("three constraints");
        assert!((p - DVec3::new(1.0, 2.0, -3.0)).length() < 1e-12, "{p}");
    }

    #[test]
    fn an_objective_fills_the_directions_the_constraints_leave_free() {
        // Kept on the plane x = 1, the nearest point to (5, 2, 3) by |v − q|²: H = I, c = q.
        let mut c = Constraints::default();
        c.add(DVec3::X, 1.0);
        c.add_objective(DMat3::IDENTITY, DVec3::new(5.0, 2.0, 3.0));
        let p = c.solve().expect("filled");
        assert!((p - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12, "{p}");
    }
}

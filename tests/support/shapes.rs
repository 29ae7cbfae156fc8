//! The test shapes the test files share: the grid of squares that most of them write as
//! OBJ, VRML, Inventor or PLY text or build as arrays, numbered one way everywhere. Solid
//! shapes (boxes, spheres, the report's models) come from `decimate_core::mesh::shapes`.

/// A grid of `nu` × `nv` squares: `(nu + 1) × (nv + 1)` points in rows (u fastest), point
/// (i, j) numbered `j * (nu + 1) + i`.
#[derive(Debug, Clone, Copy)]
pub struct Grid {
    pub nu: usize,
    pub nv: usize,
}

impl Grid {
    /// `n` × `n` squares.
    pub fn square(n: usize) -> Self {
        Self { nu: n, nv: n }
    }

    /// Point (i, j)'s number.
    pub fn point(&self, i: usize, j: usize) -> usize {
        j * (self.nu + 1) + i
    }

    /// Every point as (i, j), in number order.
    pub fn points(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..=self.nv).flat_map(move |j| (0..=self.nu).map(move |i| (i, j)))
    }

    /// Points' count.
    pub fn point_count(&self) -> usize {
        (self.nu + 1) * (self.nv + 1)
    }

    /// Every square as (i, j, its corners counter-clockwise seen from +z starting at
    /// (i, j)), rows first.
    pub fn squares(&self) -> impl Iterator<Item = (usize, usize, [usize; 4])> + '_ {
        (0..self.nv).flat_map(move |j| {
            (0..self.nu).map(move |i| {
                let a = self.point(i, j);
                let d = self.point(i, j + 1);
                (i, j, [a, a + 1, d + 1, d])
            })
        })
    }

    /// Every square cut in two along its diagonal from (i, j): [a, b, c] then [a, c, d].
    pub fn triangles(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        self.squares().flat_map(|(_, _, q)| split(q))
    }
}

/// A square's two triangles, cut from its first corner: [a, b, c] then [a, c, d].
pub fn split([a, b, c, d]: [usize; 4]) -> [[usize; 3]; 2] {
    [[a, b, c], [a, c, d]]
}

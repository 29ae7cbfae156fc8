//! A complex vertex's triangles split into manifold fans ("sheets"), so that vertex removal
//! takes part on non-manifold input instead of freezing every complex vertex: a vertex inside
//! a non-manifold crease line (on exactly two edges of k ≥ 3 triangles, every fan running
//! from one of their far ends to the other), a pinch (the end of a non-manifold edge, every
//! fan closed through its far end), a fin's end (the same meeting a border, its one-triangle
//! flap dropped) and a bowtie (fans meeting only at the vertex).
//! `plan` fills each fan on its own: an open one like a boundary vertex's hole, closed by the
//! edge between its ends (on a crease line the k fans share that one new edge, so the line
//! stays glued and keeps k triangles; at a bowtie the fans come apart), a closed one like a
//! simple vertex's (docs/design.md#schroeder-non-manifold).

use rayon::prelude::*;

use crate::mesh::topology::{corner_of, Adjacency, Connectivity, MAX_VALENCE};

/// How a complex vertex's fans lie, when it may be removed through them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum SheetShape {
    /// Every fan runs between `a` and `b`, the far ends of the vertex's two non-manifold
    /// edges (each of as many triangles as there are fans).
    CreaseLine { a: u32, b: u32 },
    /// The vertex ends one non-manifold edge, and every fan is closed through its far end:
    /// removed, the surfaces it joined touch at that end only.
    Pinch,
    /// The vertex ends one non-manifold edge, to `a`, and meets a border (a fin's end): one
    /// fan or more closed through `a`, the others open from `a` (or between two border
    /// neighbours); an open fan of one triangle `(v, a, x)` is a flap the removal drops.
    FinEnd { a: u32 },
    /// Two or more fans, no non-manifold edge: each open one runs between two border
    /// neighbours of its own, each closed one around the vertex.
    Bowtie,
}

/// One neighbour's triangles on its edge to the vertex: as the corner after the vertex
/// (`outs`) and before it (`ins`).
#[derive(Debug, Clone, Copy)]
struct Use {
    vertex: u32,
    outs: u32,
    ins: u32,
}

impl Use {
    fn total(self) -> u32 {
        self.outs + self.ins
    }
}

/// A complex vertex's fans, and the buffers splitting reuses from one vertex to the next.
#[derive(Debug, Clone, Default)]
pub(super) struct Sheets {
    /// Each incident triangle's corners after and before the vertex, and its id.
    pairs: Vec<(u32, u32, u32)>,
    uses: Vec<Use>,
    taken: Vec<bool>,
    /// The fans' paths one after another: fan `i`'s path ends at `path_ends[i]`, its
    /// triangles (`(v, path[j], path[j + 1])`, one fewer) at `triangle_ends[i]`.
    paths: Vec<u32>,
    triangles: Vec<u32>,
    path_ends: Vec<usize>,
    triangle_ends: Vec<usize>,
    /// The removal's fill, fan after fan, while the ring holds one fan at a time.
    pub fill: Vec<[u32; 3]>,
    /// The shape the last [`Self::split`] found.
    shape: Option<SheetShape>,
}

impl Sheets {
    /// How many fans the last [`Self::split`] found.
    pub fn count(&self) -> usize {
        self.path_ends.len()
    }

    /// Fan `i`'s path (its ring, open) and its triangles.
    pub fn fan(&self, i: usize) -> (&[u32], &[u32]) {
        let p0 = if i == 0 { 0 } else { self.path_ends[i - 1] };
        let t0 = if i == 0 { 0 } else { self.triangle_ends[i - 1] };
        (
            &self.paths[p0..self.path_ends[i]],
            &self.triangles[t0..self.triangle_ends[i]],
        )
    }

    /// Whether fan `i` is a fin's flap: one triangle from the non-manifold edge's far end
    /// to a border neighbour, dropped with the vertex (its far edge must keep a triangle
    /// each way, `keeps_both_sides`).
    pub fn is_fin_flap(&self, i: usize) -> bool {
        matches!(self.shape, Some(SheetShape::FinEnd { .. })) && self.fan(i).1.len() == 1
    }

    /// Every triangle of the vertex, fan after fan.
    pub fn all_triangles(&self) -> &[u32] {
        &self.triangles
    }

    /// Every neighbour of the vertex once.
    pub fn neighbours(&self) -> impl Iterator<Item = u32> + '_ {
        self.uses.iter().map(|u| u.vertex)
    }

    /// Splits `v`'s triangles into fans; their shape when `v` may be removed through them
    /// (each fan consistently oriented, of two triangles or more, three when closed, or on
    /// a crease line one; every triangle in one), `None` otherwise: a degenerate triangle, a misoriented pair, a fan
    /// ending where its shape does not allow (a crease line's back where it began, a
    /// pinch's across), a fan too small, or any other mix of non-manifold and border edges.
    pub fn split(&mut self, conn: &impl Adjacency, v: u32) -> Option<SheetShape> {
        self.shape = self.split_fans(conn, v);
        self.shape
    }

    fn split_fans(&mut self, conn: &impl Adjacency, v: u32) -> Option<SheetShape> {
        self.pairs.clear();
        self.uses.clear();
        self.paths.clear();
        self.triangles.clear();
        self.path_ends.clear();
        self.triangle_ends.clear();
        let incident = conn.incident(v);
        if incident.is_empty() || incident.len() > MAX_VALENCE {
            return None;
        }
        for &t in incident {
            let tri = conn.triangle(t);
            let (_, x, y) = corner_of(tri, v);
            if x == v || y == v || x == y {
                return None;
            }
            self.pairs.push((x, y, t));
        }
        for i in 0..self.pairs.len() {
            let (x, y, _) = self.pairs[i];
            self.count_use(x, true);
            self.count_use(y, false);
        }
        // A neighbour inside a fan is after the vertex in one triangle and before it in the
        // next: two triangles the other way round are misoriented.
        if (self.uses.iter()).any(|u| u.total() == 2 && (u.outs, u.ins) != (1, 1)) {
            return None;
        }
        let mut non_manifold = self.uses.iter().filter(|u| u.total() >= 3);
        let shape = match (
            non_manifold.next(),
            non_manifold.next(),
            non_manifold.next(),
        ) {
            (Some(a), Some(b), None) => {
                let borders = self.uses.iter().any(|u| u.total() == 1);
                (a.total() == b.total() && !borders).then_some(SheetShape::CreaseLine {
                    a: a.vertex,
                    b: b.vertex,
                })
            }
            (Some(a), None, _) => Some(if self.uses.iter().any(|u| u.total() == 1) {
                SheetShape::FinEnd { a: a.vertex }
            } else {
                SheetShape::Pinch
            }),
            (None, _, _) => Some(SheetShape::Bowtie),
            _ => None,
        }?;
        self.walk_fans(shape)?;
        (self.count() >= 2).then_some(shape)
    }

    /// Counts `u`'s use after (`out`) or before the vertex.
    fn count_use(&mut self, u: u32, out: bool) {
        let at = match self.uses.iter().position(|x| x.vertex == u) {
            Some(at) => at,
            None => {
                self.uses.push(Use {
                    vertex: u,
                    outs: 0,
                    ins: 0,
                });
                self.uses.len() - 1
            }
        };
        let entry = &mut self.uses[at];
        if out {
            entry.outs += 1;
        } else {
            entry.ins += 1;
        }
    }

    /// Whether `u` ends fans: a non-manifold edge's far end, or a border neighbour.
    fn is_stop(&self, u: u32) -> bool {
        self.uses.iter().any(|x| x.vertex == u && x.total() != 2)
    }

    /// Walks every fan from a stop to a stop; `None` when one is not as `shape` needs, or
    /// a triangle is in none (a closed fan).
    fn walk_fans(&mut self, shape: SheetShape) -> Option<()> {
        let k = self.pairs.len();
        self.taken.clear();
        self.taken.resize(k, false);
        for start in 0..k {
            let (first, _, _) = self.pairs[start];
            if !self.is_stop(first) {
                continue;
            }
            self.paths.push(first);
            let mut cur = start;
            let last = loop {
                if std::mem::replace(&mut self.taken[cur], true) {
                    return None;
                }
                let (_, y, t) = self.pairs[cur];
                self.triangles.push(t);
                self.paths.push(y);
                if self.is_stop(y) {
                    break y;
                }
                cur = self.pairs.iter().position(|q| q.0 == y)?;
            };
            let path_start = self.path_ends.last().copied().unwrap_or(0);
            let length = self.paths.len() - path_start;
            let fits = match shape {
                // A lone triangle `(v, a, b)` too: a flap the removal drops.
                SheetShape::CreaseLine { a, b } => {
                    (first, last) == (a, b) || (first, last) == (b, a)
                }
                // Closed through the far end, of three triangles or more.
                SheetShape::Pinch => first == last && length >= 4,
                // Open from `a` (a flap too) or between two border neighbours, or closed.
                SheetShape::FinEnd { a } => match (first == a, last == a) {
                    (true, true) => length >= 4,
                    (true, false) | (false, true) => true,
                    (false, false) => length >= 3,
                },
                SheetShape::Bowtie => length >= 3,
            };
            if !fits {
                return None;
            }
            self.end_fan();
        }
        // The fin stands on a surface closed around the vertex: the ends of three sheets'
        // borders on one edge (a spine's end) stay.
        if let SheetShape::FinEnd { a } = shape {
            if !(0..self.count()).any(|i| {
                let path = self.fan(i).0;
                path[0] == a && path[path.len() - 1] == a
            }) {
                return None;
            }
        }
        if shape == SheetShape::Bowtie {
            self.walk_closed_fans()?;
        }
        self.taken.iter().all(|&t| t).then_some(())
    }

    /// Walks the fans left once the open ones are taken, each closed (at a bowtie, where
    /// no neighbour stops a fan): `None` when one has fewer than three triangles.
    fn walk_closed_fans(&mut self) -> Option<()> {
        for start in 0..self.pairs.len() {
            if self.taken[start] {
                continue;
            }
            let (first, _, _) = self.pairs[start];
            self.paths.push(first);
            let mut cur = start;
            loop {
                if std::mem::replace(&mut self.taken[cur], true) {
                    return None;
                }
                let (_, y, t) = self.pairs[cur];
                self.triangles.push(t);
                self.paths.push(y);
                if y == first {
                    break;
                }
                cur = self.pairs.iter().position(|q| q.0 == y)?;
            }
            let path_start = self.path_ends.last().copied().unwrap_or(0);
            if self.paths.len() - path_start < 4 {
                return None;
            }
            self.end_fan();
        }
        Some(())
    }

    /// Closes the fan being walked.
    fn end_fan(&mut self) {
        self.path_ends.push(self.paths.len());
        self.triangle_ends.push(self.triangles.len());
    }
}

/// Whether some edge has three triangles or more, on all cores (each vertex looks at its
/// own triangles; one of more than `MAX_VALENCE` is left out, as it is never removed).
pub(super) fn any_non_manifold_edge(conn: &Connectivity, vertices: usize) -> bool {
    (0..vertices as u32).into_par_iter().any(|v| {
        let incident = conn.incident(v);
        incident.len() <= MAX_VALENCE
            && incident.iter().any(|&t| {
                let (_, x, _) = corner_of(conn.triangle(t), v);
                let with_x = |&s: &u32| conn.triangle(s).contains(&x);
                incident.iter().filter(|s| with_x(s)).count() >= 3
            })
    })
}

/// Whether the triangles with the edge `p`–`q` and not the vertex `v` are two or more,
/// at least one each way: dropping `v`'s triangle on that edge then leaves it with a
/// consistently oriented pair (no flipped neighbours), not a border.
pub(super) fn keeps_both_sides(conn: &impl Adjacency, p: u32, q: u32, v: u32) -> bool {
    let (mut forward, mut backward) = (false, false);
    for &t in conn.incident(p) {
        let tri = conn.triangle(t);
        if tri.contains(&q) && !tri.contains(&v) {
            let (_, next, _) = corner_of(tri, p);
            forward |= next == q;
            backward |= next != q;
        }
    }
    forward && backward
}

/// When `v` is the apex of one lone triangle standing on an edge of two other triangles or
/// more (a dangling flap on a non-manifold edge, as reconstructed scans leave them), that
/// edge's two ends: removing `v` drops the flap and leaves the edge manifold or less
/// non-manifold. Such an apex is a corner by its sharp turn, and would stay for ever.
pub(super) fn flap_apex(conn: &impl Adjacency, v: u32) -> Option<(u32, u32)> {
    let &[t] = conn.incident(v) else {
        return None;
    };
    let (_, a, b) = corner_of(conn.triangle(t), v);
    (a != b && a != v && b != v && keeps_both_sides(conn, a, b, v)).then_some((a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Vertex 0 at the centre of `fans`, each a path of neighbours around it (ccw).
    fn around(fans: &[&[u32]]) -> Connectivity {
        let tris: Vec<[u32; 3]> = fans
            .iter()
            .flat_map(|f| f.windows(2).map(|w| [0, w[0], w[1]]))
            .collect();
        let n = tris.iter().flatten().max().map_or(1, |&m| m as usize + 1);
        Connectivity::new(n, &tris)
    }

    #[test]
    fn three_fans_between_two_neighbours_are_a_crease_line() {
        let conn = around(&[&[1, 3, 4, 2], &[2, 5, 1], &[1, 6, 7, 2]]);
        let mut s = Sheets::default();
        assert_eq!(
            s.split(&conn, 0),
            Some(SheetShape::CreaseLine { a: 1, b: 2 })
        );
        assert_eq!(s.count(), 3);
        assert_eq!(s.all_triangles().len(), 8);
        let (path, tris) = s.fan(1);
        assert_eq!((path, tris.len()), (&[2, 5, 1][..], 2));
        // A flap, one triangle from one end to the other: still a crease line.
        let conn = around(&[&[1, 3, 4, 2], &[2, 5, 1], &[1, 2]]);
        assert_eq!(
            s.split(&conn, 0),
            Some(SheetShape::CreaseLine { a: 1, b: 2 })
        );
        assert_eq!(s.fan(2).0, &[1, 2][..]);
    }

    #[test]
    fn two_open_fans_are_a_bowtie_and_a_fan_of_one_triangle_is_refused() {
        let conn = around(&[&[1, 2, 3], &[4, 5, 6]]);
        let mut s = Sheets::default();
        assert_eq!(s.split(&conn, 0), Some(SheetShape::Bowtie));
        assert_eq!(s.count(), 2);
        let conn = around(&[&[1, 2, 3], &[4, 5]]);
        assert_eq!(s.split(&conn, 0), None);
    }

    #[test]
    fn two_closed_fans_through_one_neighbour_are_a_pinch() {
        let conn = around(&[&[1, 2, 3, 1], &[1, 4, 5, 6, 1]]);
        let mut s = Sheets::default();
        assert_eq!(s.split(&conn, 0), Some(SheetShape::Pinch));
        assert_eq!(s.count(), 2);
        assert_eq!(s.fan(1).0, &[1, 4, 5, 6, 1][..]);
    }

    #[test]
    fn a_closed_fan_and_a_flap_through_one_neighbour_are_a_fin_end() {
        let conn = around(&[&[1, 2, 3, 1], &[1, 4]]);
        let mut s = Sheets::default();
        assert_eq!(s.split(&conn, 0), Some(SheetShape::FinEnd { a: 1 }));
        assert_eq!(s.count(), 2);
        assert!(!s.is_fin_flap(0) && s.is_fin_flap(1));
        assert_eq!(s.fan(1).0, &[1, 4][..]);
        // The end of three sheets' borders on one edge, no surface around it: kept.
        let conn = around(&[&[1, 2, 3], &[1, 4, 5], &[1, 6, 7]]);
        assert_eq!(s.split(&conn, 0), None);
        assert!(!s.is_fin_flap(0));
    }

    #[test]
    fn a_flap_standing_on_an_edge_of_two_triangles_has_its_apex_removable() {
        // Triangles 0-1-2 and 0-2-3 share 0-2; the flap 0-2-4 stands on it.
        let tris = [[0, 1, 2], [0, 2, 3], [2, 0, 4]];
        let conn = Connectivity::new(5, &tris);
        assert_eq!(flap_apex(&conn, 4), Some((2, 0)));
        assert_eq!(flap_apex(&conn, 0), None);
        assert!(keeps_both_sides(&conn, 0, 2, 4));
        // Standing on two triangles that both run 2 -> 0 (flipped neighbours): dropping
        // the flap would leave a misoriented pair, so it stays.
        let conn = Connectivity::new(5, &[[0, 1, 2], [2, 0, 3], [0, 2, 4]]);
        assert!(!keeps_both_sides(&conn, 0, 2, 4));
        assert_eq!(flap_apex(&conn, 4), None);
        // Without the flap, 1 is an ordinary border corner.
        let conn = Connectivity::new(4, &tris[..2]);
        assert_eq!(flap_apex(&conn, 1), None);
    }

    #[test]
    fn a_closed_and_an_open_fan_are_a_bowtie_and_a_misoriented_pair_is_refused() {
        let conn = around(&[&[1, 2, 3, 1], &[4, 5, 6]]);
        let mut s = Sheets::default();
        assert_eq!(s.split(&conn, 0), Some(SheetShape::Bowtie));
        assert_eq!(s.fan(1).0, &[1, 2, 3, 1][..]);
        let tris = [[0, 1, 2], [0, 3, 2], [0, 3, 4]];
        let conn = Connectivity::new(5, &tris);
        assert_eq!(Sheets::default().split(&conn, 0), None);
    }
}

//! Closed shapes' volumes, so that no decimation step turns a closed shape inside out or
//! flattens it. A step's checks look at the triangles around it, each of which may turn by
//! up to a right angle: on a small closed shape (a box going to a tetrahedron) a few such
//! steps carry a vertex through the opposite side, and the shape's signed volume changes
//! sign or drops to nothing while every local check passes. So every connected part of a
//! model whose edges each have two triangles running them opposite ways has its signed
//! volume tracked, and a step that would take it below a share of its starting volume (or
//! across zero) is refused, keeping the vertex. A texture seam cuts a closed shape open
//! (one vertex per side, same position): closedness is judged with the seam's copies
//! welded ([`ClosedVolumes::with_seams`]), so a textured sphere is guarded like a plain one.

use std::collections::HashMap;

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::mesh::seams;
use crate::mesh::topology::{corner_of, Connectivity};
use crate::mesh::union_find;

/// A closed shape keeps at least this share of its starting volume: the largest
/// tetrahedron inside a box holds a third of it, inside a sphere an eighth, so decimating
/// down to four vertices stays possible (see docs/design.md#closed-shapes).
const MIN_VOLUME_SHARE: f64 = 0.05;

/// No closed component (`ClosedVolumes::component`).
const NONE: u32 = u32::MAX;

/// Vertices an edge key ([`edge_key`]) can tell apart: two ids and a direction in 64 bits.
const MAX_VERTICES: usize = 1 << 31;

/// Six times the signed volume of the tetrahedron (o, a, b, c): positive when triangle
/// (a, b, c) faces away from `o`.
#[inline]
pub fn tet6(o: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    (a - o).dot((b - o).cross(c - o))
}

/// Each closed component's signed volume (six times it), kept up to date step by step.
#[derive(Debug, Clone, Default)]
pub struct ClosedVolumes {
    /// Each vertex's closed component, `NONE` when it is on no closed component.
    component: Vec<u32>,
    /// Six times each component's signed volume now.
    volume6: Vec<f64>,
    /// The volume (six times it) each component must stay beyond, with its starting sign.
    floor6: Vec<f64>,
}

impl ClosedVolumes {
    /// The closed components of `triangles` over `positions` (vertices `0..positions.len()`;
    /// triangles with an index out of range are ignored, and make nothing closed).
    pub fn new(positions: &[Vec3], triangles: &[[u32; 3]]) -> Self {
        Self::welded(positions, triangles, &[])
    }

    /// As [`Self::new`], with each texture seam's copies of a point taken as one vertex:
    /// the two sides `twins` pairs and the junction copies `cycles` links
    /// (`mesh::seams::copies`; either may be empty).
    pub fn with_seams(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        twins: &[u32],
        cycles: &[u32],
    ) -> Self {
        if twins.is_empty() && cycles.is_empty() {
            return Self::new(positions, triangles);
        }
        let weld: Vec<u32> = (0..positions.len() as u32)
            .map(|v| seams::copies(v, twins, cycles).min().unwrap_or(v))
            .collect();
        Self::welded(positions, triangles, &weld)
    }

    /// As [`Self::new`] for the triangles `conn` connects (its slots, none removed yet),
    /// judging each edge from its ends' fans instead of sorting every edge: the same
    /// components and volumes. Triangles with a repeated or missing corner take the sort.
    pub fn connected(positions: &[Vec3], conn: &Connectivity) -> Self {
        let (n, triangles) = (positions.len(), conn.triangles());
        let plain = |t: &[u32; 3]| {
            t.iter().all(|&v| (v as usize) < n) && t[0] != t[1] && t[1] != t[2] && t[2] != t[0]
        };
        if n > MAX_VERTICES || !triangles.par_iter().all(plain) {
            return Self::new(positions, triangles);
        }
        let mut parent = components(n, triangles, |v| v);
        let unclosed: Vec<u32> = (0..n as u32)
            .into_par_iter()
            .with_min_len(1 << 12)
            .map_init(Vec::new, |keys, v| {
                (!fan_runs_each_edge_both_ways(conn, v, keys)).then_some(v)
            })
            .flatten_iter()
            .collect();
        let mut open = vec![false; n];
        for v in unclosed {
            let root = union_find::root(&mut parent, v);
            open[root as usize] = true;
        }
        Self::summed(positions, triangles, |v| v, &mut parent, &open)
    }

    /// The closed components with vertex `v` standing for `weld[v]` in the topology (itself
    /// when `weld` is empty); positions are each vertex's own.
    fn welded(positions: &[Vec3], triangles: &[[u32; 3]], weld: &[u32]) -> Self {
        let n = positions.len();
        if n > MAX_VERTICES {
            return Self::default(); // no edge key for them: nothing is taken as closed
        }
        let valid = |t: &[u32; 3]| t.iter().all(|&v| (v as usize) < n);
        let one = |v: u32| weld.get(v as usize).copied().unwrap_or(v);
        let mut parent = components(n, triangles, one);
        // A component is closed when every directed edge appears once and so does its
        // reverse: sort the edges, each with its direction beside it, and check that each
        // edge is run exactly once each way.
        let mut edges: Vec<u64> = triangles
            .iter()
            .filter(|t| valid(t))
            .flat_map(|t| (0..3).map(move |k| edge_key(one(t[k]), one(t[(k + 1) % 3]))))
            .collect();
        edges.par_sort_unstable();
        let mut open = vec![false; n];
        for run in edges.chunk_by(|x, y| x >> 1 == y >> 1) {
            let a = (run[0] >> 33) as u32;
            let b = (run[0] >> 1) as u32;
            // A degenerate edge (a, a) is its own reverse: it must only not repeat.
            let once_each_way = if a == b {
                run.len() == 1
            } else {
                run.len() == 2 && run[0] & 1 == 0 && run[1] & 1 == 1
            };
            if !once_each_way {
                let root = union_find::root(&mut parent, a);
                open[root as usize] = true;
            }
        }
        for t in triangles.iter().filter(|t| !valid(t)) {
            for &v in t.iter().filter(|&&v| (v as usize) < n) {
                let root = union_find::root(&mut parent, one(v));
                open[root as usize] = true;
            }
        }
        Self::summed(positions, triangles, one, &mut parent, &open)
    }

    /// The closed components' volumes, from the union-find `parent` of the vertices (each
    /// standing for `one(v)`) and the roots of the `open` ones, summed about each
    /// component's first vertex.
    fn summed(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        one: impl Fn(u32) -> u32,
        parent: &mut [u32],
        open: &[bool],
    ) -> Self {
        let n = positions.len();
        let valid = |t: &[u32; 3]| t.iter().all(|&v| (v as usize) < n);
        let mut id = vec![NONE; n];
        let mut component = vec![NONE; n];
        let mut origin = Vec::new();
        let mut volume6 = Vec::new();
        for t in triangles.iter().filter(|t| valid(t)) {
            let root = union_find::root(parent, one(t[0]));
            if open[root as usize] {
                continue;
            }
            if id[root as usize] == NONE {
                id[root as usize] = origin.len() as u32;
                origin.push(positions[t[0] as usize].as_dvec3());
                volume6.push(0.0);
            }
            let c = id[root as usize];
            let [a, b, d] = t.map(|v| positions[v as usize].as_dvec3());
            volume6[c as usize] += tet6(origin[c as usize], a, b, d);
            for &v in t {
                component[v as usize] = c;
            }
        }
        let floor6 = volume6.iter().map(|v| v * MIN_VOLUME_SHARE).collect();
        Self {
            component,
            volume6,
            floor6,
        }
    }

    /// `v`'s closed component, if it is on one.
    #[inline]
    pub fn component(&self, v: u32) -> Option<u32> {
        self.component
            .get(v as usize)
            .copied()
            .filter(|&c| c != NONE)
    }

    /// Whether changing component `c`'s volume (six times it) by `change6` keeps it beyond
    /// its floor, on its starting side; `margin` multiplies the floor (a part working on
    /// one core, which cannot see the others' changes, keeps a wider one).
    pub fn allows(&self, c: u32, change6: f64, margin: f64) -> bool {
        let (now, floor) = (self.volume6[c as usize], self.floor6[c as usize]);
        let after = now + change6;
        change6 * floor >= 0.0 || after * floor.signum() > floor.abs() * margin
    }

    /// Records a step that changed component `c`'s volume by `change6`.
    pub fn apply(&mut self, c: u32, change6: f64) {
        self.volume6[c as usize] += change6;
    }

    /// Asks for `v`'s component ahead of [`Self::component`] (a hint only).
    pub fn prefetch(&self, v: u32) {
        if let Some(component) = self.component.get(v as usize) {
            crate::mesh::prefetch(component);
        }
    }

    /// Six times component `c`'s signed volume now.
    #[cfg(test)]
    pub fn volume6(&self, c: u32) -> f64 {
        self.volume6[c as usize]
    }
}

/// The components of the vertices of the valid `triangles` (each vertex standing for
/// `one(v)`), as a union-find parent array.
fn components(n: usize, triangles: &[[u32; 3]], one: impl Fn(u32) -> u32) -> Vec<u32> {
    let mut parent = union_find::singletons(n);
    let valid = |t: &[u32; 3]| t.iter().all(|&v| (v as usize) < n);
    for t in triangles.iter().filter(|t| valid(t)) {
        let a = union_find::root(&mut parent, one(t[0]));
        for &v in &t[1..] {
            let b = union_find::root(&mut parent, one(v));
            parent[b as usize] = a;
        }
    }
    parent
}

/// Whether every edge of `v`'s fan is run by exactly one of its triangles each way (`keys`:
/// scratch): each neighbour's edge out of `v` and back, sorted by neighbour, must pair up.
fn fan_runs_each_edge_both_ways(conn: &Connectivity, v: u32, keys: &mut Vec<u64>) -> bool {
    keys.clear();
    for &t in conn.incident(v) {
        let (_, next, prev) = corner_of(conn.triangle(t), v);
        keys.push(u64::from(next) << 1);
        keys.push(u64::from(prev) << 1 | 1);
    }
    keys.sort_unstable();
    keys.chunks_exact(2)
        .all(|pair| pair[0] & 1 == 0 && pair[1] == pair[0] | 1)
}

/// A part working on one core keeps its closed components this many times their floor
/// away from it: it cannot see what the other parts change (see `ClosedView`).
const PART_MARGIN: f64 = 2.0;

/// The volumes as one decimation step sees them: the whole mesh's, changed in place; or,
/// for a part working on one core, the volumes as its round started plus its own changes,
/// handed back at the round's end ([`ClosedVolumes::absorb`]).
#[derive(Debug)]
pub enum ClosedView<'a> {
    Whole(&'a mut ClosedVolumes),
    Part(&'a ClosedVolumes, HashMap<u32, f64>),
}

impl ClosedView<'_> {
    /// `v`'s closed component, if it is on one.
    #[inline]
    pub fn component(&self, v: u32) -> Option<u32> {
        match self {
            Self::Whole(c) => c.component(v),
            Self::Part(c, _) => c.component(v),
        }
    }

    /// Asks for `v`'s component ahead of [`Self::component`] (a hint only).
    pub fn prefetch(&self, v: u32) {
        match self {
            Self::Whole(c) => c.prefetch(v),
            Self::Part(c, _) => c.prefetch(v),
        }
    }

    /// Whether a step changing component `c`'s volume by `change6` may be made.
    pub fn allows(&self, c: u32, change6: f64) -> bool {
        match self {
            Self::Whole(v) => v.allows(c, change6, 1.0),
            Self::Part(v, own) => {
                let own = own.get(&c).copied().unwrap_or(0.0);
                v.allows(c, own + change6, PART_MARGIN)
            }
        }
    }

    /// Records a step that changed component `c`'s volume by `change6`.
    pub fn apply(&mut self, c: u32, change6: f64) {
        match self {
            Self::Whole(v) => v.apply(c, change6),
            Self::Part(_, own) => *own.entry(c).or_default() += change6,
        }
    }

    /// A part's own changes (none for the whole, which made them in place).
    pub fn into_changes(self) -> HashMap<u32, f64> {
        match self {
            Self::Whole(_) => HashMap::new(),
            Self::Part(_, own) => own,
        }
    }
}

impl ClosedVolumes {
    /// Adds a part's changes (see [`ClosedView`]).
    pub fn absorb(&mut self, changes: HashMap<u32, f64>) {
        for (c, change6) in changes {
            self.apply(c, change6);
        }
    }
}

/// The directed edge a → b as a sort key.
/// Edge `a`–`b` as a sort key: its smaller vertex, its larger one, then one bit for its
/// direction (set when it runs from the larger to the smaller); ids below `MAX_VERTICES`.
fn edge_key(a: u32, b: u32) -> u64 {
    let (lo, hi) = (a.min(b), a.max(b));
    u64::from(lo) << 33 | u64::from(hi) << 1 | u64::from(a > b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    fn box_mesh() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let m = shapes::unit_box();
        (m.positions, m.triangles)
    }

    #[test]
    fn a_box_is_one_closed_component_of_its_volume_and_an_open_box_is_none() {
        let (p, t) = box_mesh();
        let c = ClosedVolumes::new(&p, &t);
        assert_eq!(c.component(0), Some(0));
        assert!((c.volume6(0) - 6.0).abs() < 1e-12);
        // Steps that keep at least the floor are allowed, those past it (or past 0) not.
        assert!(c.allows(0, -5.0, 1.0));
        assert!(!c.allows(0, -5.8, 1.0));
        assert!(!c.allows(0, -7.0, 1.0));
        assert!(c.allows(0, 3.0, 1.0));
        let open = ClosedVolumes::new(&p, &t[2..]);
        assert_eq!(open.component(0), None);
    }

    #[test]
    fn reading_closedness_off_the_fans_finds_what_sorting_the_edges_finds() {
        // Two boxes apart (one closed, then one open, flipped, with a fin, with a
        // triangle doubled, with a degenerate one) beside a closed sphere.
        let (p, t) = box_mesh();
        let sphere = shapes::uv_sphere(6, 8);
        let flip = |mut t: Vec<[u32; 3]>| {
            t[3].swap(1, 2);
            t
        };
        let fin = |mut t: Vec<[u32; 3]>| {
            // A third triangle on the first one's first edge, to a corner off it.
            let apex = (0..8).find(|v| !t[0].contains(v)).unwrap_or(7);
            t.push([t[0][1], t[0][0], apex]);
            t
        };
        let doubled = |mut t: Vec<[u32; 3]>| {
            t.push(t[5]);
            t
        };
        let degenerate = |mut t: Vec<[u32; 3]>| {
            // On the first triangle's first edge, which it runs a second time.
            t.push([t[0][0], t[0][0], t[0][1]]);
            t
        };
        let second: [Vec<[u32; 3]>; 6] = [
            t.clone(),
            t[2..].to_vec(),
            flip(t.clone()),
            fin(t.clone()),
            doubled(t.clone()),
            degenerate(t.clone()),
        ];
        for (case, second) in second.into_iter().enumerate() {
            let mut positions = p.clone();
            let mut triangles = t.clone();
            let base = positions.len() as u32;
            positions.extend(p.iter().map(|q| *q + Vec3::splat(3.0)));
            triangles.extend(second.iter().map(|tri| tri.map(|v| v + base)));
            let base = positions.len() as u32;
            positions.extend(sphere.positions.iter().map(|q| *q - Vec3::splat(3.0)));
            triangles.extend(sphere.triangles.iter().map(|tri| tri.map(|v| v + base)));
            let sorted = ClosedVolumes::new(&positions, &triangles);
            let conn = Connectivity::new(positions.len(), &triangles);
            let fans = ClosedVolumes::connected(&positions, &conn);
            assert_eq!(fans.component, sorted.component, "case {case}");
            assert_eq!(fans.volume6, sorted.volume6, "case {case}");
            let closed = usize::from(case == 0) + 2;
            assert_eq!(sorted.volume6.len(), closed, "case {case}");
        }
    }

    #[test]
    fn a_box_cut_open_by_a_seam_is_closed_once_its_copies_are_welded() {
        // The unit box with vertex 0 split: the triangles on one side use a copy (8).
        let (mut p, mut t) = box_mesh();
        p.push(p[0]);
        let first = t.iter().position(|t| t.contains(&0)).unwrap_or(0);
        for v in t[first].iter_mut().filter(|v| **v == 0) {
            *v = 8;
        }
        assert_eq!(ClosedVolumes::new(&p, &t).component(0), None, "cut open");
        let mut twins = vec![u32::MAX; 9];
        (twins[0], twins[8]) = (8, 0);
        let welded = ClosedVolumes::with_seams(&p, &t, &twins, &[]);
        assert_eq!(welded.component(0), Some(0));
        assert_eq!(welded.component(8), Some(0));
        assert!((welded.volume6(0) - 6.0).abs() < 1e-12);
    }
}

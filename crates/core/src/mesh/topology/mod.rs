//! Dynamic triangle connectivity: flat triangle array with alive flags and free-slot reuse,
//! plus vertex → incident-triangle lists, and the ordered one-ring ("loop") of a vertex that
//! every local operation starts from.
//!
//! The ring of a vertex `v` is the sequence of its neighbours in counter-clockwise order:
//! closed for an interior manifold vertex, an open path for a boundary vertex, and "complex"
//! for anything else (non-manifold edge, two fans meeting at a point, inconsistent
//! orientation). Ring triangle `i` is `(v, verts[i], verts[i + 1])` (indices modulo the length
//! for closed rings).

mod connectivity_part;

use std::collections::HashMap;

use rayon::prelude::*;

pub use connectivity_part::{split_mut, ConnectivityPart, FanTriangle};

/// The corner of `tri` at `v` (the first one, in a degenerate triangle), and the corners
/// after and before it: without branches, as a fan walk meets `v` at a random corner in
/// each triangle and a branch on it would be mispredicted about every other time.
#[inline(always)]
pub fn corner_of(tri: [u32; 3], v: u32) -> (usize, u32, u32) {
    const NEXT: [usize; 3] = [1, 2, 0];
    const PREV: [usize; 3] = [2, 0, 1];
    let i = usize::from(tri[0] != v) * (1 + usize::from(tri[1] != v));
    (i, tri[NEXT[i]], tri[PREV[i]])
}

/// Largest valence handled; vertices above it are reported as complex (kept).
pub const MAX_VALENCE: usize = 256;

/// Incident triangles kept inline per vertex; more spill to a side table.
pub const INLINE: usize = 15;

/// One vertex's incident triangles: a cache line holding up to `INLINE` ids inline, so a
/// lookup costs one memory access instead of two (a `Vec` header, then its heap data).
#[derive(Debug, Clone, Copy)]
#[repr(align(64))]
struct Incidence {
    len: u32,
    ids: [u32; INLINE],
}

/// Incident lists longer than `INLINE`, by vertex, with each entry's place in its list, so
/// that unlinking a triangle from a vertex of any valence takes constant time.
#[derive(Debug, Clone, Default)]
struct Spilled {
    lists: HashMap<u32, Vec<u32>>,
    places: HashMap<(u32, u32), u32>,
}

impl Spilled {
    fn get(&self, v: u32) -> Option<&Vec<u32>> {
        self.lists.get(&v)
    }

    /// Appends `t` to `v`'s list, starting it from the inline ids when it spills now.
    fn push(&mut self, v: u32, t: u32, inline: &[u32]) {
        let list = self.lists.entry(v).or_insert_with(|| {
            for (i, &id) in inline.iter().enumerate() {
                self.places.entry((v, id)).or_insert(i as u32);
            }
            inline.to_vec()
        });
        self.places.entry((v, t)).or_insert(list.len() as u32);
        list.push(t);
    }

    /// Removes one `t` from `v`'s list as `swap_remove` does; the list left, if `t` was in it.
    fn remove(&mut self, v: u32, t: u32) -> Option<&[u32]> {
        let list = self.lists.get_mut(&v)?;
        let recorded = self.places.remove(&(v, t)).map(|p| p as usize);
        // A degenerate triangle can be listed twice: fall back to a search then.
        let pos = match recorded {
            Some(p) if list.get(p) == Some(&t) => p,
            _ => list.iter().position(|&x| x == t)?,
        };
        list.swap_remove(pos);
        if let Some(&moved) = list.get(pos) {
            self.places.insert((v, moved), pos as u32);
        }
        Some(list)
    }

    /// Forgets `v`'s list.
    fn remove_vertex(&mut self, v: u32) {
        if let Some(list) = self.lists.remove(&v) {
            for t in list {
                self.places.remove(&(v, t));
            }
        }
    }

    fn extend(&mut self, other: Self) {
        self.lists.extend(other.lists);
        self.places.extend(other.places);
    }
}

/// Triangles with per-vertex incidence, editable in place.
#[derive(Debug, Clone)]
pub struct Connectivity {
    triangles: Vec<[u32; 3]>,
    alive: Vec<bool>,
    incidence: Vec<Incidence>,
    /// Incident lists of vertices with more than `INLINE` triangles.
    spilled: Spilled,
    free: Vec<u32>,
    alive_count: usize,
}

/// The shape of a vertex's one-ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RingShape {
    /// No incident triangle.
    Isolated,
    /// A closed loop: interior manifold vertex.
    Closed,
    /// An open path: manifold boundary vertex.
    Open,
    /// Non-manifold or inconsistently oriented neighbourhood.
    Complex,
}

/// Scratch buffers for a ring, reused between calls to avoid allocation.
#[derive(Debug, Clone, Default)]
pub struct Ring {
    /// Neighbours in counter-clockwise order (one more than `triangles` when open).
    pub verts: Vec<u32>,
    /// Incident triangle ids, `triangles[i]` = `(v, verts[i], verts[i+1])`.
    pub triangles: Vec<u32>,
    pairs: Vec<(u32, u32, u32)>,
}

impl Connectivity {
    /// Builds connectivity for `vertex_count` vertices; triangles with an index out of range
    /// must have been rejected by the caller.
    pub fn new(vertex_count: usize, triangles: &[[u32; 3]]) -> Self {
        Self::from_triangles(vertex_count, triangles.to_vec())
    }

    /// As [`Self::new`], taking the triangle array over instead of copying it.
    pub fn from_triangles(vertex_count: usize, triangles: Vec<[u32; 3]>) -> Self {
        let mut incidence: Vec<Incidence> = (0..vertex_count)
            .into_par_iter()
            .with_min_len(1 << 14)
            .map(|_| Incidence {
                len: 0,
                ids: [0; INLINE],
            })
            .collect();
        // On all cores, one range of vertices each: every range scans the triangles in
        // order, so each list comes out as one scan would make it, on any number of cores.
        let ranges = rayon::current_num_threads().clamp(1, 64);
        let chunk = vertex_count.div_ceil(ranges).max(1);
        let spills: Vec<Spilled> = incidence
            .par_chunks_mut(chunk)
            .enumerate()
            .map(|(i, lists)| {
                let v0 = (i * chunk) as u32;
                let mut spilled = Spilled::default();
                for (t, tri) in triangles.iter().enumerate() {
                    for &v in tri {
                        if let Some(inc) = lists.get_mut(v.wrapping_sub(v0) as usize) {
                            link(inc, Some(&mut spilled), v, t as u32);
                        }
                    }
                }
                spilled
            })
            .collect();
        Self {
            alive: vec![true; triangles.len()],
            alive_count: triangles.len(),
            triangles,
            incidence,
            spilled: spills
                .into_iter()
                .fold(Spilled::default(), |mut all, part| {
                    all.extend(part);
                    all
                }),
            free: Vec::new(),
        }
    }

    /// Adds `t` to `v`'s incident list.
    fn link(&mut self, v: u32, t: u32) {
        link(
            &mut self.incidence[v as usize],
            Some(&mut self.spilled),
            v,
            t,
        );
    }

    /// Removes `t` from `v`'s incident list (order is not kept).
    fn unlink(&mut self, v: u32, t: u32) {
        unlink(
            &mut self.incidence[v as usize],
            Some(&mut self.spilled),
            v,
            t,
        );
    }

    /// Triangle slots, dead ones included (check [`Self::is_alive`]).
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    pub fn is_alive(&self, t: u32) -> bool {
        self.alive[t as usize]
    }

    pub fn triangle(&self, t: u32) -> [u32; 3] {
        self.triangles[t as usize]
    }

    /// Number of live triangles.
    pub fn triangle_count(&self) -> usize {
        self.alive_count
    }

    /// Asks the CPU to start loading `v`'s incident list (a hint; no effect on results).
    #[inline]
    pub fn prefetch_incident(&self, v: u32) {
        if let Some(inc) = self.incidence.get(v as usize) {
            crate::mesh::prefetch(inc);
        }
    }

    /// Asks the CPU to start loading triangle `t`'s corners (a hint).
    #[inline]
    pub fn prefetch_triangle(&self, t: u32) {
        if let Some(tri) = self.triangles.get(t as usize) {
            crate::mesh::prefetch(tri);
        }
    }

    /// Live triangles incident to `v`.
    pub fn incident(&self, v: u32) -> &[u32] {
        incident(&self.incidence[v as usize], Some(&self.spilled), v)
    }

    /// Ids of live triangle slots, ascending.
    pub fn alive_ids(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.triangles.len() as u32).filter(|&t| self.alive[t as usize])
    }

    /// Kills triangle `t` and unlinks it from its vertices; its slot is reused later.
    pub fn remove_triangle(&mut self, t: u32) {
        if !self.alive[t as usize] {
            return;
        }
        self.alive[t as usize] = false;
        self.alive_count -= 1;
        for v in self.triangles[t as usize] {
            self.unlink(v, t);
        }
        self.free.push(t);
    }

    /// Adds a triangle, reusing the most recently freed slot; returns its id.
    pub fn add_triangle(&mut self, tri: [u32; 3]) -> u32 {
        let t = match self.free.pop() {
            Some(t) => {
                self.triangles[t as usize] = tri;
                self.alive[t as usize] = true;
                t
            }
            None => {
                self.triangles.push(tri);
                self.alive.push(true);
                (self.triangles.len() - 1) as u32
            }
        };
        self.alive_count += 1;
        for v in tri {
            self.link(v, t);
        }
        t
    }

    /// Replaces corner `from` of live triangle `t` by `to`, in place: the slot and the corner
    /// order stay, so a face keeps its id and its orientation (edge collapse, vertex split).
    pub fn rename_corner(&mut self, t: u32, from: u32, to: u32) {
        let tri = &mut self.triangles[t as usize];
        let Some(corner) = tri.iter().position(|&v| v == from) else {
            return;
        };
        tri[corner] = to;
        self.unlink(from, t);
        self.link(to, t);
    }
}

/// Read access to a mesh's incidence, whole or a part of it: what the one-ring and the edge
/// queries are made of, so that they run the same on a [`Connectivity`] and on a
/// [`ConnectivityPart`] (which answers only for what it owns: ask first).
pub trait Adjacency {
    /// Live triangles incident to `v`.
    fn incident(&self, v: u32) -> &[u32];

    /// The corners of triangle slot `t`.
    fn triangle(&self, t: u32) -> [u32; 3];

    /// True when some live triangle not incident to `except` has the edge `a`–`b`.
    fn has_edge_avoiding(&self, a: u32, b: u32, except: u32) -> bool {
        self.incident(a).iter().any(|&t| {
            let tri = self.triangle(t);
            tri.contains(&b) && !tri.contains(&except)
        })
    }

    /// True when a live triangle with exactly the vertices `a`, `b`, `c` exists.
    fn has_triangle(&self, a: u32, b: u32, c: u32) -> bool {
        self.incident(a).iter().any(|&t| {
            let tri = self.triangle(t);
            tri.contains(&b) && tri.contains(&c)
        })
    }

    /// Fills `ring` with the ordered one-ring of `v` and says what shape it has.
    fn ring(&self, v: u32, ring: &mut Ring) -> RingShape {
        ring.verts.clear();
        ring.triangles.clear();
        ring.pairs.clear();
        let incident = self.incident(v);
        if incident.is_empty() {
            return RingShape::Isolated;
        }
        if incident.len() > MAX_VALENCE {
            return RingShape::Complex;
        }
        for &t in incident {
            let [a, b, c] = self.triangle(t);
            let (x, y) = if a == v {
                (b, c)
            } else if b == v {
                (c, a)
            } else {
                (a, b)
            };
            if x == v || y == v || x == y {
                return RingShape::Complex;
            }
            ring.pairs.push((x, y, t));
        }
        // Walk forward from the first ring edge (x -> y), then, if the walk ends open, walk
        // backward from it. The neighbourhood is one manifold fan exactly when the walks
        // visit every incident triangle once: a repeated neighbour (non-manifold edge,
        // inconsistent orientation) or a second fan leaves some triangle unvisited.
        let k = ring.pairs.len();
        let Some(closed) = walk_forward(ring) else {
            return RingShape::Complex;
        };
        if !closed && !walk_backward(ring) {
            return RingShape::Complex;
        }
        if ring.triangles.len() != k {
            return RingShape::Complex; // several fans meet at v
        }
        // Distinct neighbours (hence distinct triangles): a neighbour met twice means a
        // non-manifold edge or an inconsistently oriented triangle.
        let verts = &ring.verts;
        if (1..verts.len()).any(|i| verts[..i].contains(&verts[i])) {
            return RingShape::Complex;
        }
        if closed {
            RingShape::Closed
        } else {
            RingShape::Open
        }
    }
}

/// Fills the ring from its first edge forward, following each edge's end to the edge
/// that starts there. Returns whether the walk came back to the start (a closed fan), or
/// `None` when it visits more triangles than there are (a non-manifold neighbourhood).
fn walk_forward(ring: &mut Ring) -> Option<bool> {
    let pairs = &ring.pairs;
    let k = pairs.len();
    let first = pairs[0].0;
    let mut cur = 0;
    loop {
        let (x, y, t) = pairs[cur];
        ring.verts.push(x);
        ring.triangles.push(t);
        if ring.triangles.len() > k {
            return None;
        }
        if y == first {
            return Some(true);
        }
        match pairs.iter().position(|q| q.0 == y) {
            Some(next) => cur = next,
            None => {
                ring.verts.push(y);
                return Some(false);
            }
        }
    }
}

/// Prepends the part of an open fan before its first edge, found walking backward; false
/// when the walk visits more triangles than there are.
fn walk_backward(ring: &mut Ring) -> bool {
    let pairs = &ring.pairs;
    let k = pairs.len();
    let forward = ring.triangles.len();
    let mut x = pairs[0].0;
    while let Some(prev) = pairs.iter().position(|q| q.1 == x) {
        let (px, _, t) = pairs[prev];
        ring.verts.push(px);
        ring.triangles.push(t);
        if ring.triangles.len() > k {
            return false;
        }
        x = px;
    }
    let back = ring.triangles.len() - forward;
    if back > 0 {
        // verts: [forward (forward + 1 items)][back items, nearest first] -> rotate so the
        // back part, reversed, comes first.
        ring.verts[forward + 1..].reverse();
        ring.verts.rotate_right(back);
        ring.triangles[forward..].reverse();
        ring.triangles.rotate_right(back);
    }
    true
}

impl Adjacency for Connectivity {
    #[inline]
    fn incident(&self, v: u32) -> &[u32] {
        Self::incident(self, v)
    }

    #[inline]
    fn triangle(&self, t: u32) -> [u32; 3] {
        Self::triangle(self, t)
    }
}

impl Adjacency for ConnectivityPart<'_> {
    #[inline]
    fn incident(&self, v: u32) -> &[u32] {
        ConnectivityPart::incident(self, v)
    }

    #[inline]
    fn triangle(&self, t: u32) -> [u32; 3] {
        ConnectivityPart::triangle(self, t)
    }
}

/// `v`'s incident list, from its record `inc` and, when it spilled, the side table.
fn incident<'a>(inc: &'a Incidence, spilled: Option<&'a Spilled>, v: u32) -> &'a [u32] {
    let len = inc.len as usize;
    if len <= INLINE {
        &inc.ids[..len]
    } else {
        spilled.and_then(|s| s.get(v)).map_or(&[], Vec::as_slice)
    }
}

/// Adds `t` to `v`'s incident list. Without a side table (`spilled` is `None`) the list
/// must have room inline; the caller checks (a full list is left unchanged).
fn link(inc: &mut Incidence, spilled: Option<&mut Spilled>, v: u32, t: u32) {
    let len = inc.len as usize;
    debug_assert!(
        len < INLINE || spilled.is_some(),
        "a part's incident list overflowed"
    );
    if len < INLINE {
        inc.ids[len] = t;
    } else if let Some(spilled) = spilled {
        spilled.push(v, t, &inc.ids);
    } else {
        return;
    }
    inc.len += 1;
}

/// Removes `t` from `v`'s incident list (order is not kept). Without a side table the list
/// must be inline.
fn unlink(inc: &mut Incidence, spilled: Option<&mut Spilled>, v: u32, t: u32) {
    let len = inc.len as usize;
    if len <= INLINE {
        if let Some(pos) = inc.ids[..len].iter().position(|&x| x == t) {
            inc.ids[pos] = inc.ids[len - 1];
            inc.len -= 1;
        }
        return;
    }
    let Some(spilled) = spilled else {
        return;
    };
    let Some(list) = spilled.remove(v, t) else {
        return;
    };
    inc.len = list.len() as u32;
    if list.len() <= INLINE {
        inc.ids[..list.len()].copy_from_slice(list);
        spilled.remove_vertex(v);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hub_keeps_exactly_its_live_triangles_as_they_go_and_come() {
        // A fan of 200 triangles around vertex 0: its list spills, shrinks back inline,
        // and spills again, removed in an order that moves entries within the list.
        let n = 200u32;
        let tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
        let mut c = Connectivity::new(n as usize + 1, &tris);
        let mut live: Vec<u32> = (0..n).collect();
        let order: Vec<u32> = (0..n).map(|i| (i * 37) % n).collect();
        for (k, &t) in order.iter().enumerate() {
            c.remove_triangle(t);
            live.retain(|&x| x != t);
            if k % 50 == 0 {
                let mut got = c.incident(0).to_vec();
                got.sort_unstable();
                assert_eq!(got, live, "after removing {} triangles", k + 1);
            }
        }
        assert!(c.incident(0).is_empty());
        let added: Vec<u32> = (0..n).map(|i| c.add_triangle(tris[i as usize])).collect();
        let mut got = c.incident(0).to_vec();
        got.sort_unstable();
        let mut want = added;
        want.sort_unstable();
        assert_eq!(got, want);
    }

    #[test]
    fn corner_of_finds_the_corner_and_its_neighbours_in_cyclic_order() {
        assert_eq!(corner_of([7, 8, 9], 7), (0, 8, 9));
        assert_eq!(corner_of([7, 8, 9], 8), (1, 9, 7));
        assert_eq!(corner_of([7, 8, 9], 9), (2, 7, 8));
        // A degenerate triangle: the first corner at `v`.
        assert_eq!(corner_of([7, 7, 9], 7), (0, 7, 9));
        assert_eq!(corner_of([9, 7, 7], 7), (1, 7, 9));
    }

    //        3
    //      / | \
    //    4 - 0 - 2      vertex 0 with neighbours 1..=4 counter-clockwise;
    //      \ | /        the closed fan has four triangles, the open one drops 0-4-1
    //        1
    fn fan(closed: bool) -> Connectivity {
        // Vertex 0 at the centre, neighbours 1..=4 counter-clockwise.
        let mut tris = vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]];
        if closed {
            tris.push([0, 4, 1]);
        }
        Connectivity::new(5, &tris)
    }

    #[test]
    fn closed_and_open_rings_are_ordered_counter_clockwise() {
        let mut r = Ring::default();
        assert_eq!(fan(true).ring(0, &mut r), RingShape::Closed);
        assert_eq!(r.verts.len(), 4);
        let i = r.verts.iter().position(|&x| x == 1).unwrap();
        let rotated: Vec<u32> = (0..4).map(|k| r.verts[(i + k) % 4]).collect();
        assert_eq!(rotated, vec![1, 2, 3, 4]);
        assert_eq!(fan(false).ring(0, &mut r), RingShape::Open);
        assert_eq!(r.verts, vec![1, 2, 3, 4]);
        assert_eq!(r.triangles, vec![0, 1, 2]);
    }

    #[test]
    fn non_manifold_and_bowtie_are_complex() {
        let mut r = Ring::default();
        // Three triangles on edge 0-1.
        let c = Connectivity::new(5, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
        assert_eq!(c.ring(0, &mut r), RingShape::Complex);
        // Two fans touching at vertex 0.
        let c = Connectivity::new(5, &[[0, 1, 2], [0, 3, 4]]);
        assert_eq!(c.ring(0, &mut r), RingShape::Complex);
        // Inconsistent orientation.
        let c = Connectivity::new(4, &[[0, 1, 2], [0, 1, 3]]);
        assert_eq!(c.ring(0, &mut r), RingShape::Complex);
    }

    #[test]
    fn high_valence_spills_and_comes_back() {
        // A fan of 40 triangles around vertex 0.
        let tris: Vec<[u32; 3]> = (1..=40).map(|i| [0, i, i % 40 + 1]).collect();
        let mut c = Connectivity::new(41, &tris);
        let mut r = Ring::default();
        assert_eq!(c.incident(0).len(), 40);
        assert_eq!(c.ring(0, &mut r), RingShape::Closed);
        assert_eq!(r.verts.len(), 40);
        for t in 0..30 {
            c.remove_triangle(t);
        }
        let mut left: Vec<u32> = c.incident(0).to_vec();
        left.sort_unstable();
        assert_eq!(left, (30..40).collect::<Vec<u32>>());
        assert_eq!(c.ring(0, &mut r), RingShape::Open);
    }

    #[test]
    fn slots_are_reused_and_counts_follow() {
        let mut c = fan(true);
        c.remove_triangle(1);
        assert_eq!(c.triangle_count(), 3);
        assert!(!c.has_edge_avoiding(2, 3, 99));
        assert_eq!(c.add_triangle([1, 2, 3]), 1);
        assert_eq!(c.triangle_count(), 4);
        assert!(c.has_triangle(3, 1, 2));
        assert!(c.has_edge_avoiding(2, 3, 0));
    }
}

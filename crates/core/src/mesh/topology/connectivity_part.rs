//! A mutable view of part of a [`Connectivity`]: the vertices of one id range and the
//! triangle slots of one slot range, so that disjoint parts of a mesh can be edited on
//! different threads, each holding plain `&mut` slices (no locks, no `unsafe`).
//!
//! A part answers only for what it owns: [`ConnectivityPart::owns_vertex`] and
//! [`ConnectivityPart::owns_slot`] say what that is, and an operation must check before it
//! touches anything. A part split off a mesh has no side table for long incident lists:
//! it must not touch a vertex whose list spilled, nor grow one past [`INLINE`]
//! ([`ConnectivityPart::has_room`]). The whole mesh as one part ([`Connectivity::whole`])
//! owns everything and may spill.

use super::{incident, link, unlink, Connectivity, Incidence, Spilled, INLINE};

/// One triangle of the fan around a vertex `v`: its slot, which of its corners is `v`,
/// and the other two in the triangle's cyclic order after `v`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FanTriangle {
    pub t: u32,
    pub corner: u8,
    pub next: u32,
    pub prev: u32,
}

impl FanTriangle {
    /// True when `x` is one of the two corners other than the fan's vertex.
    #[inline]
    pub fn touches(&self, x: u32) -> bool {
        self.next == x || self.prev == x
    }
}

/// Vertices `v0..` and triangle slots `t0..` of a connectivity, editable.
#[derive(Debug)]
pub struct ConnectivityPart<'a> {
    v0: u32,
    t0: u32,
    triangles: &'a mut [[u32; 3]],
    alive: &'a mut [bool],
    incidence: &'a mut [Incidence],
    spilled: Option<&'a mut Spilled>,
    /// Live triangles of the whole mesh when the part was made (meaningful for a whole part).
    live_before: usize,
    /// Slots killed through this part, in order: free once the part is given back.
    removed: Vec<u32>,
}

/// Splits `slice` at `starts` (ascending offsets, the first 0): part `i` is
/// `starts[i]..starts[i + 1]`, the last runs to the end. Offsets past the end are clamped.
pub fn split_mut<'a, T>(mut slice: &'a mut [T], starts: &[usize]) -> Vec<&'a mut [T]> {
    let mut parts = Vec::with_capacity(starts.len());
    let mut at = 0;
    for (i, _) in starts.iter().enumerate() {
        let end = starts.get(i + 1).map_or(usize::MAX, |&e| e);
        let len = end.saturating_sub(at).min(slice.len());
        let (head, tail) = std::mem::take(&mut slice).split_at_mut(len);
        parts.push(head);
        slice = tail;
        at += len;
    }
    parts
}

impl Connectivity {
    /// The whole mesh as one part.
    pub fn whole(&mut self) -> ConnectivityPart<'_> {
        ConnectivityPart {
            v0: 0,
            t0: 0,
            live_before: self.alive_count,
            triangles: &mut self.triangles,
            alive: &mut self.alive,
            incidence: &mut self.incidence,
            spilled: Some(&mut self.spilled),
            removed: Vec::new(),
        }
    }

    /// Disjoint parts: part `i` owns the vertices from `vertex_starts[i]` and the slots from
    /// `slot_starts[i]` up to the next part's (both ascending, starting at 0, equally long).
    pub fn split(
        &mut self,
        vertex_starts: &[u32],
        slot_starts: &[u32],
    ) -> Vec<ConnectivityPart<'_>> {
        let as_usize = |s: &[u32]| s.iter().map(|&x| x as usize).collect::<Vec<_>>();
        let (vs, ts) = (as_usize(vertex_starts), as_usize(slot_starts));
        let incidence = split_mut(&mut self.incidence, &vs);
        let triangles = split_mut(&mut self.triangles, &ts);
        let alive = split_mut(&mut self.alive, &ts);
        let live_before = self.alive_count;
        incidence
            .into_iter()
            .zip(triangles)
            .zip(alive)
            .zip(vertex_starts.iter().zip(slot_starts))
            .map(
                |(((incidence, triangles), alive), (&v0, &t0))| ConnectivityPart {
                    v0,
                    t0,
                    triangles,
                    alive,
                    incidence,
                    spilled: None,
                    live_before,
                    removed: Vec::new(),
                },
            )
            .collect()
    }

    /// Takes back the slots parts killed (`removed`, from [`ConnectivityPart::finish`]):
    /// they count as dead and their slots become free, in the given order.
    pub fn absorb(&mut self, removed: Vec<u32>) {
        self.alive_count -= removed.len();
        self.free.extend(removed);
    }

    /// As [`Self::absorb`], for a decimation that never adds a triangle (edge collapse):
    /// the slots count as dead but are not kept for reuse, so no free list grows with them.
    pub fn retire(&mut self, removed: &[u32]) {
        self.alive_count -= removed.len();
    }
}

impl ConnectivityPart<'_> {
    /// True when vertex `v` is in this part.
    #[inline]
    pub fn owns_vertex(&self, v: u32) -> bool {
        (v.wrapping_sub(self.v0) as usize) < self.incidence.len()
    }

    /// True when triangle slot `t` is in this part.
    #[inline]
    pub fn owns_slot(&self, t: u32) -> bool {
        (t.wrapping_sub(self.t0) as usize) < self.triangles.len()
    }

    /// True when `v` (owned) can take `extra` more incident triangles: its list neither
    /// spilled nor would spill, or the part has the side table.
    pub fn has_room(&self, v: u32, extra: usize) -> bool {
        self.spilled.is_some() || self.incidence[self.vertex(v)].len as usize + extra <= INLINE
    }

    #[inline]
    fn vertex(&self, v: u32) -> usize {
        (v - self.v0) as usize
    }

    #[inline]
    fn slot(&self, t: u32) -> usize {
        (t - self.t0) as usize
    }

    /// Live triangles incident to the owned vertex `v`.
    #[inline]
    pub fn incident(&self, v: u32) -> &[u32] {
        incident(&self.incidence[self.vertex(v)], self.spilled.as_deref(), v)
    }

    /// The corners of the owned slot `t`.
    #[inline]
    pub fn triangle(&self, t: u32) -> [u32; 3] {
        self.triangles[self.slot(t)]
    }

    /// Live triangles of the whole mesh, for a part made by [`Connectivity::whole`].
    pub fn triangle_count(&self) -> usize {
        self.live_before - self.removed.len()
    }

    /// Asks the CPU to start loading `v`'s incident list, if owned (a hint).
    #[inline]
    pub fn prefetch_incident(&self, v: u32) {
        if let Some(inc) = self.incidence.get(v.wrapping_sub(self.v0) as usize) {
            crate::mesh::prefetch(inc);
        }
    }

    /// Asks the CPU to start loading slot `t`'s corners, if owned (a hint).
    #[inline]
    pub fn prefetch_triangle(&self, t: u32) {
        if let Some(tri) = self.triangles.get(t.wrapping_sub(self.t0) as usize) {
            crate::mesh::prefetch(tri);
        }
    }

    fn link(&mut self, v: u32, t: u32) {
        let i = self.vertex(v);
        link(&mut self.incidence[i], self.spilled.as_deref_mut(), v, t);
    }

    fn unlink(&mut self, v: u32, t: u32) {
        let i = self.vertex(v);
        unlink(&mut self.incidence[i], self.spilled.as_deref_mut(), v, t);
    }

    /// `v`'s incident triangles as a fan into `out` (cleared first); false, with `out`
    /// partly filled, when one of them lies in a slot this part does not own. A split-off
    /// part sees a spilled list as empty: ask [`Self::has_room`] first.
    #[inline]
    pub fn fan(&self, v: u32, out: &mut Vec<FanTriangle>) -> bool {
        out.clear();
        for &t in self.incident(v) {
            if !self.owns_slot(t) {
                return false;
            }
            let (corner, next, prev) = super::corner_of(self.triangle(t), v);
            out.push(FanTriangle {
                t,
                corner: corner as u8,
                next,
                prev,
            });
        }
        true
    }

    /// The topology of collapsing the edge `remove`–`keep`, `fan` being `remove`'s (from
    /// [`Self::fan`], unchanged since): the triangles on the edge are killed (into
    /// `deleted`, with their corners), `remove`'s others are renamed to `keep` in place
    /// (into `renamed`), and `remove`'s list is emptied at once rather than entry by entry.
    /// Everything touched must be owned, with room in `keep`'s list (see
    /// [`Self::has_room`]).
    pub fn collapse_edge(
        &mut self,
        remove: u32,
        keep: u32,
        fan: &[FanTriangle],
        renamed: &mut Vec<u32>,
        deleted: &mut Vec<(u32, [u32; 3])>,
    ) {
        renamed.clear();
        deleted.clear();
        // Without a side table, `keep`'s list can hold no more than `INLINE` even for a
        // moment: where fan order would overfill it, the edge's triangles leave it before
        // the others join it (fan order otherwise).
        let tight = self.spilled.is_none() && {
            let mut len = self.incidence[self.vertex(keep)].len as usize;
            fan.iter().any(|f| {
                if !f.touches(keep) {
                    len += 1;
                } else if self.alive[self.slot(f.t)] {
                    len = len.saturating_sub(1);
                }
                len > INLINE
            })
        };
        if tight {
            for f in fan.iter().filter(|f| f.touches(keep)) {
                self.kill_edge_triangle(f, remove, deleted);
            }
            for f in fan.iter().filter(|f| !f.touches(keep)) {
                self.rename_corner_to(f, keep, renamed);
            }
        } else {
            for f in fan {
                if f.touches(keep) {
                    self.kill_edge_triangle(f, remove, deleted);
                } else {
                    self.rename_corner_to(f, keep, renamed);
                }
            }
        }
        let r = self.vertex(remove);
        if self.incidence[r].len as usize > INLINE {
            if let Some(spilled) = self.spilled.as_deref_mut() {
                spilled.remove_vertex(remove);
            }
        }
        self.incidence[r].len = 0;
    }

    /// Kills the edge triangle `f` of a collapse removing `remove` (once: a doubled fan may
    /// list it twice), into `deleted`.
    fn kill_edge_triangle(
        &mut self,
        f: &FanTriangle,
        remove: u32,
        deleted: &mut Vec<(u32, [u32; 3])>,
    ) {
        let i = self.slot(f.t);
        if !self.alive[i] {
            return;
        }
        self.alive[i] = false;
        let tri = self.triangles[i];
        for v in tri {
            if v != remove {
                self.unlink(v, f.t);
            }
        }
        self.removed.push(f.t);
        deleted.push((f.t, tri));
    }

    /// Renames the removed end's corner of `f` to `keep`, into `renamed`.
    fn rename_corner_to(&mut self, f: &FanTriangle, keep: u32, renamed: &mut Vec<u32>) {
        let i = self.slot(f.t);
        self.triangles[i][f.corner as usize] = keep;
        self.link(keep, f.t);
        renamed.push(f.t);
    }

    /// Replaces the live triangles in slots `old` by `fill` (no more of them), as removing
    /// a vertex and filling its hole does. `fill[i]` takes slot `old[old.len() - 1 - i]`,
    /// the slot the whole mesh's free list gives it when `old` is removed in order and
    /// `fill` added in order (so what a slot carries, a per-face attribute, passes to the
    /// triangle that covers its place the same way); the slots left over are killed. Every
    /// corner, old and new, must be owned, each with room for the triangles it gains (see
    /// [`Self::has_room`]).
    pub fn replace_triangles(&mut self, old: &[u32], fill: &[[u32; 3]]) {
        debug_assert!(fill.len() <= old.len(), "a fill larger than its hole");
        for &t in old {
            let tri = self.triangles[self.slot(t)];
            for v in tri {
                self.unlink(v, t);
            }
        }
        let (left_over, reused) = old.split_at(old.len().saturating_sub(fill.len()));
        for (&t, &tri) in reused.iter().rev().zip(fill) {
            let i = self.slot(t);
            self.triangles[i] = tri;
            for v in tri {
                self.link(v, t);
            }
        }
        for &t in left_over {
            let i = self.slot(t);
            self.alive[i] = false;
            self.removed.push(t);
        }
    }

    /// Ends the part: the slots it killed, for [`Connectivity::absorb`].
    pub fn finish(self) -> Vec<u32> {
        self.removed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_mut_cuts_at_the_offsets() {
        let mut v: Vec<u32> = (0..10).collect();
        let parts = split_mut(&mut v, &[0, 3, 3, 8]);
        let lens: Vec<usize> = parts.iter().map(|p| p.len()).collect();
        assert_eq!(lens, vec![3, 0, 5, 2]);
        assert_eq!(parts[2][0], 3);
    }

    #[test]
    fn parts_edit_their_own_vertices_and_slots() {
        // Two strips: vertices 0..4 with slots 0..2, vertices 4..8 with slots 2..4.
        let tris = [[0, 1, 2], [1, 3, 2], [4, 5, 6], [5, 7, 6]];
        let mut c = Connectivity::new(8, &tris);
        let mut parts = c.split(&[0, 4], &[0, 2]);
        assert!(parts[0].owns_vertex(3) && !parts[0].owns_vertex(4));
        assert!(parts[1].owns_slot(3) && !parts[1].owns_slot(1));
        // Collapse 3 into 2 in part 0 (slot 1 goes), 6 into 7 in part 1 (slot 3 goes, slot
        // 2 is renamed).
        let (mut fan, mut renamed, mut deleted) = (Vec::new(), Vec::new(), Vec::new());
        assert!(parts[0].fan(3, &mut fan));
        assert_eq!(
            fan,
            vec![FanTriangle {
                t: 1,
                corner: 1,
                next: 2,
                prev: 1
            }]
        );
        parts[0].collapse_edge(3, 2, &fan, &mut renamed, &mut deleted);
        assert_eq!(
            (renamed.as_slice(), deleted.as_slice()),
            (&[][..], &[(1, [1, 3, 2])][..])
        );
        assert!(parts[1].fan(6, &mut fan));
        parts[1].collapse_edge(6, 7, &fan, &mut renamed, &mut deleted);
        assert_eq!(renamed, vec![2]);
        assert_eq!(deleted, vec![(3, [5, 7, 6])]);
        assert_eq!(parts[1].triangle(2), [4, 5, 7]);
        assert_eq!(parts[0].incident(1), &[0]);
        assert!(parts[0].incident(3).is_empty());
        let removed: Vec<u32> = parts
            .into_iter()
            .flat_map(ConnectivityPart::finish)
            .collect();
        c.absorb(removed);
        assert_eq!(c.triangle_count(), 2);
        assert_eq!(c.incident(7), &[2]);
        assert!(c.incident(6).is_empty());
        // Freed slots are reused in the order the parts gave them back.
        assert_eq!(c.add_triangle([0, 1, 3]), 3);
    }

    #[test]
    fn retired_slots_are_dead_and_never_reused() {
        let mut c = Connectivity::new(5, &[[0, 1, 2], [1, 3, 2], [2, 3, 4]]);
        let mut parts = c.split(&[0], &[0]);
        let mut fan = Vec::new();
        let (mut renamed, mut deleted) = (Vec::new(), Vec::new());
        assert!(parts[0].fan(3, &mut fan));
        parts[0].collapse_edge(3, 2, &fan, &mut renamed, &mut deleted);
        let removed: Vec<u32> = parts
            .pop()
            .map(ConnectivityPart::finish)
            .unwrap_or_default();
        // Both triangles on edge 3–2 go; 3's renamed corners leave it with none.
        assert_eq!(removed, vec![1, 2]);
        c.retire(&removed);
        assert_eq!(c.triangle_count(), 1);
        assert_eq!(c.alive_ids().collect::<Vec<_>>(), vec![0]);
        // A new triangle takes a new slot: the retired one stays dead.
        assert_eq!(c.add_triangle([0, 1, 3]), 3);
    }

    #[test]
    fn a_fan_reaching_into_another_parts_slots_is_refused() {
        // Vertex 2 (part 0's) is in slot 0 (part 0's) and slot 1 (part 1's).
        let tris = [[0, 1, 2], [2, 4, 3]];
        let mut c = Connectivity::new(5, &tris);
        let parts = c.split(&[0, 3], &[0, 1]);
        let mut fan = Vec::new();
        assert!(parts[0].fan(1, &mut fan));
        assert_eq!(fan.len(), 1);
        assert!(!parts[0].fan(2, &mut fan));
        assert!(parts[1].fan(4, &mut fan));
        let whole_fan = |c: &mut Connectivity| {
            let mut fan = Vec::new();
            let ok = c.whole().fan(2, &mut fan);
            (ok, fan)
        };
        drop(parts);
        let (ok, fan) = whole_fan(&mut c);
        assert!(ok);
        assert_eq!(
            fan,
            vec![
                FanTriangle {
                    t: 0,
                    corner: 2,
                    next: 0,
                    prev: 1
                },
                FanTriangle {
                    t: 1,
                    corner: 0,
                    next: 4,
                    prev: 3
                }
            ]
        );
        assert!(fan[1].touches(3) && !fan[1].touches(2));
    }

    #[test]
    fn replacing_a_fan_in_a_part_matches_the_whole_meshs_remove_and_add() {
        // Vertex 0 in the middle of a closed fan of six (rim 1..=6), in part 0 (vertices
        // 0..7, slots 0..6), beside a lone triangle in part 1 (vertices 7..10, slot 6).
        let mut tris: Vec<[u32; 3]> = (1..=6u32).map(|i| [0, i, i % 6 + 1]).collect();
        tris.push([7, 8, 9]);
        let fill = [[1, 2, 3], [1, 3, 4], [1, 4, 6], [4, 5, 6]];
        let old: Vec<u32> = (0..6).collect();
        let mut serial = Connectivity::new(10, &tris);
        for &t in &old {
            serial.remove_triangle(t);
        }
        let slots: Vec<u32> = fill.iter().map(|&tri| serial.add_triangle(tri)).collect();
        assert_eq!(slots, vec![5, 4, 3, 2]);

        let mut c = Connectivity::new(10, &tris);
        let mut parts = c.split(&[0, 7], &[0, 6]);
        parts[0].replace_triangles(&old, &fill);
        for (&t, tri) in slots.iter().zip(fill) {
            assert_eq!(parts[0].triangle(t), tri);
        }
        assert!(parts[0].incident(0).is_empty());
        for v in 1..=6 {
            let mut mine = parts[0].incident(v).to_vec();
            let mut theirs = serial.incident(v).to_vec();
            mine.sort_unstable();
            theirs.sort_unstable();
            assert_eq!(mine, theirs, "vertex {v}");
        }
        let removed: Vec<u32> = parts
            .into_iter()
            .flat_map(ConnectivityPart::finish)
            .collect();
        assert_eq!(removed, vec![0, 1]);
        c.absorb(removed);
        assert_eq!(c.triangle_count(), serial.triangle_count());
        assert_eq!(c.alive_ids().collect::<Vec<_>>(), vec![2, 3, 4, 5, 6]);
    }

    #[test]
    fn collapsing_into_a_vertex_spills_its_list_on_the_whole_mesh() {
        // A closed fan of 20 triangles around vertex 0, rim 1..=20.
        let tris: Vec<[u32; 3]> = (1..=20u32).map(|i| [0, i, i % 20 + 1]).collect();
        let mut c = Connectivity::new(21, &tris);
        let mut whole = c.whole();
        let (mut fan, mut renamed, mut deleted) = (Vec::new(), Vec::new(), Vec::new());
        assert!(whole.fan(0, &mut fan));
        whole.collapse_edge(0, 1, &fan, &mut renamed, &mut deleted);
        assert_eq!(deleted.len(), 2);
        assert_eq!(renamed.len(), 18);
        assert!(whole.incident(0).is_empty());
        let at_one = whole.incident(1);
        assert_eq!(at_one.len(), 18);
        assert!(at_one.len() > INLINE);
        assert!(at_one.iter().all(|&t| whole.triangle(t).contains(&1)));
        let removed = whole.finish();
        c.absorb(removed);
        assert_eq!(c.triangle_count(), 18);
    }
}

//! `--max-error` as a distance between surfaces (docs/design.md#max-error): every input
//! triangle is assigned to one triangle slot of the current surface, and a change (a qem
//! collapse, a Schroeder removal) goes only if
//! - input → output: each input triangle of the changed slots lies within the bound of one
//!   triangle after the change, measured at its three corners. The distance to one triangle
//!   is convex, so the whole input triangle lies within the bound: this side is exact.
//! - output → input: samples of the new triangles' new parts (grid points at most a fifth
//!   of the bound apart, within 0.9 of the bound to leave room between them) lie within
//!   the bound of an input triangle assigned near the change.
//!
//! Only a run with `--max-error` builds one; only the changed slots' input triangles are
//! looked at, so the work per change is that of its neighbourhood.

use glam::{DVec3, Vec3};

/// No slot, no next input triangle.
const NONE: u32 = u32::MAX;

/// Output → input samples must lie within this share of the bound: the rest is the room
/// between samples (at most a fifth of the bound apart, see [`grid_steps`]).
const SAMPLE_SHARE: f64 = 0.9;

/// An input triangle across an edge of the surface is cut in four until each piece lies
/// within the bound of one triangle, at most this many times; a piece still across an edge
/// then needs its corners within `SAMPLE_SHARE` of the bound of some triangle.
const PIECE_DEPTH: u32 = 3;

/// Most grid steps along a new triangle's longest edge.
const MAX_STEPS: usize = 10;

/// Fills in the unchanged slots around a change, each with its corners.
pub(crate) type Near<'a> = &'a mut dyn FnMut(&mut Vec<(u32, [DVec3; 3])>);

/// A triangle of the surface after a change.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NewTriangle {
    /// Its slot (qem: slots stay) or its place among the change's new triangles (Schroeder:
    /// slots are handed out as they are made); [`DistanceBound::commit`] resolves it.
    pub id: u32,
    pub corners: [DVec3; 3],
    /// Which corners (bits 0–2) and edges (bits 3–5, edge `i` from corner `i` to `i + 1`)
    /// the change makes: only these and the inside are sampled output → input.
    pub fresh: u8,
}

/// Where a checked change puts one input triangle.
#[derive(Debug, Clone, Copy)]
enum Target {
    /// One of the change's new triangles, by id.
    New(u32),
    /// A slot the change leaves as it is.
    Slot(u32),
}

/// A checked change, waiting to be committed: its old slots and its moves, as ranges of
/// the flat lists.
#[derive(Debug, Clone, Copy)]
struct Group {
    old: (usize, usize),
    moves: (usize, usize),
}

/// The input triangles and which current slot stands for each.
#[derive(Debug)]
pub(crate) struct DistanceBound {
    bound: f64,
    /// Each input triangle's corners.
    input: Vec<[Vec3; 3]>,
    /// Per slot, its first input triangle; per input triangle, the next of its slot.
    head: Vec<u32>,
    next: Vec<u32>,
    /// Checked changes not yet committed, in order, over `old` and `moves`.
    groups: Vec<Group>,
    committed: usize,
    old: Vec<u32>,
    moves: Vec<(u32, Target)>,
    /// Scratch: the changed slots' input triangles, and the slots near the change.
    gathered: Vec<u32>,
    near: Vec<(u32, [DVec3; 3])>,
    near_input: Vec<u32>,
    /// Where the change being checked starts in `old` and in `moves`.
    checking: usize,
    moves_from: usize,
    own: Vec<(u32, u32)>,
    candidates: Vec<[DVec3; 3]>,
    sorted: Vec<u32>,
}

impl DistanceBound {
    /// Input triangle `i` starts in slot `i`.
    pub fn new(positions: &[Vec3], triangles: &[[u32; 3]], bound: f64) -> Self {
        let corner = |v: u32| positions.get(v as usize).copied().unwrap_or(Vec3::ZERO);
        Self {
            bound,
            input: triangles.iter().map(|t| t.map(corner)).collect(),
            head: (0..triangles.len() as u32).collect(),
            next: vec![NONE; triangles.len()],
            groups: Vec::new(),
            committed: 0,
            old: Vec::new(),
            moves: Vec::new(),
            gathered: Vec::new(),
            near: Vec::new(),
            near_input: Vec::new(),
            checking: 0,
            moves_from: 0,
            own: Vec::new(),
            candidates: Vec::new(),
            sorted: Vec::new(),
        }
    }

    /// Whether replacing the triangles in slots `old` by `new` keeps the surface within the
    /// bound of the input. `near` fills in the unchanged slots around the change (with their
    /// corners), asked only when the new triangles alone do not do; a change whose slots
    /// may be taken by another change checked before the commit passes `None`. When true,
    /// the change waits for [`Self::commit`]; when false, nothing is kept.
    pub fn check(&mut self, old: &[u32], new: &[NewTriangle], near: Option<Near<'_>>) -> bool {
        let mut near = near;
        let mut near_read = false;
        let (old_from, moves_from) = (self.old.len(), self.moves.len());
        // Each slot once, sorted (near slots are looked up in it).
        let mut sorted = std::mem::take(&mut self.sorted);
        sorted.clear();
        sorted.extend_from_slice(old);
        sorted.sort_unstable();
        sorted.dedup();
        self.old.extend_from_slice(&sorted);
        self.sorted = sorted;
        self.checking = old_from;
        self.moves_from = moves_from;
        self.gather(old_from);
        let placed = self.place_gathered(new, &mut near, &mut near_read)
            && self.samples_covered(new, &mut near, &mut near_read);
        if !placed {
            self.old.truncate(old_from);
            self.moves.truncate(moves_from);
            return false;
        }
        self.groups.push(Group {
            old: (old_from, self.old.len()),
            moves: (moves_from, self.moves.len()),
        });
        true
    }

    /// Forgets every checked change not committed.
    pub fn discard(&mut self) {
        self.groups.truncate(self.committed);
        let (old, moves) = self.groups.last().map_or((0, 0), |g| (g.old.1, g.moves.1));
        self.old.truncate(old);
        self.moves.truncate(moves);
        if self.committed == self.groups.len() {
            self.clear();
        }
    }

    /// Makes the oldest checked change not yet committed, its new triangles' ids resolved
    /// to slots by `slot`; nothing when none waits.
    pub fn commit(&mut self, slot: impl Fn(u32) -> u32) {
        let Some(&group) = self.groups.get(self.committed) else {
            return;
        };
        for i in group.old.0..group.old.1 {
            if let Some(h) = self.head.get_mut(self.old[i] as usize) {
                *h = NONE;
            }
        }
        for i in group.moves.0..group.moves.1 {
            let (t, target) = self.moves[i];
            let s = match target {
                Target::New(id) => slot(id),
                Target::Slot(s) => s,
            } as usize;
            if s >= self.head.len() {
                self.head.resize(s + 1, NONE);
            }
            self.next[t as usize] = self.head[s];
            self.head[s] = t;
        }
        self.committed += 1;
        if self.committed == self.groups.len() {
            self.clear();
        }
    }

    /// Commits every checked change (resolved by `slot`).
    pub fn commit_all(&mut self, slot: impl Fn(u32) -> u32) {
        while self.committed < self.groups.len() {
            self.commit(&slot);
        }
    }

    fn clear(&mut self) {
        self.groups.clear();
        self.old.clear();
        self.moves.clear();
        self.committed = 0;
    }

    /// The input triangles of the slots in `old` from `from` on (each once) into
    /// `gathered`.
    fn gather(&mut self, from: usize) {
        self.gathered.clear();
        for &s in &self.old[from..] {
            let mut t = self.head.get(s as usize).copied().unwrap_or(NONE);
            while t != NONE {
                self.gathered.push(t);
                t = self.next[t as usize];
            }
        }
    }

    /// Reads the slots near the change once, with their input triangles.
    fn read_near(&mut self, near: &mut Option<Near<'_>>, read: &mut bool) {
        if *read {
            return;
        }
        *read = true;
        self.near.clear();
        self.near_input.clear();
        if let Some(fill) = near.as_mut() {
            fill(&mut self.near);
        }
        // Each slot once, and none the change replaces.
        self.near.sort_unstable_by_key(|n| n.0);
        self.near.dedup_by_key(|n| n.0);
        let old = &self.old[self.checking..];
        self.near.retain(|n| old.binary_search(&n.0).is_err());
        for &(s, _) in &self.near {
            let mut t = self.head.get(s as usize).copied().unwrap_or(NONE);
            while t != NONE {
                self.near_input.push(t);
                t = self.next[t as usize];
            }
        }
    }

    /// Input → output: a target within the bound for every gathered input triangle (the new
    /// triangle nearest at its farthest corner, else a near slot), into `moves`.
    fn place_gathered(
        &mut self,
        new: &[NewTriangle],
        near: &mut Option<Near<'_>>,
        near_read: &mut bool,
    ) -> bool {
        for g in 0..self.gathered.len() {
            let t = self.gathered[g];
            let corners = self.input[t as usize].map(|c| c.as_dvec3());
            let best = nearest_at_corners(&corners, new.iter().map(|n| (n.id, &n.corners)));
            if let Some((id, _)) = best.filter(|b| b.1 <= self.bound) {
                self.moves.push((t, Target::New(id)));
                continue;
            }
            self.read_near(near, near_read);
            let tris = self.near.iter().map(|(s, c)| (*s, c));
            if let Some((s, _)) = nearest_at_corners(&corners, tris).filter(|b| b.1 <= self.bound) {
                self.moves.push((t, Target::Slot(s)));
                continue;
            }
            // Across an edge of the surface: each piece within the bound of one triangle,
            // and the whole listed where its middle is nearest.
            if !self.covered_by_pieces(&corners, new) {
                return false;
            }
            let middle = (corners[0] + corners[1] + corners[2]) / 3.0;
            let to = |tri: &[DVec3; 3]| point_triangle_distance2(middle, tri);
            let by_new = new.iter().map(|n| (Target::New(n.id), to(&n.corners)));
            let by_near = self.near.iter().map(|(s, c)| (Target::Slot(*s), to(c)));
            let home = by_new.chain(by_near).min_by(|a, b| a.1.total_cmp(&b.1));
            match home {
                Some((target, _)) => self.moves.push((t, target)),
                None => return false,
            }
        }
        true
    }

    /// Whether every piece of the triangle `corners` is covered ([`covered_in_pieces`]) by
    /// the new and near triangles that come within the bound of its bounding box.
    fn covered_by_pieces(&mut self, corners: &[DVec3; 3], new: &[NewTriangle]) -> bool {
        let reach = DVec3::splat(self.bound);
        let lo = corners[0].min(corners[1]).min(corners[2]) - reach;
        let hi = corners[0].max(corners[1]).max(corners[2]) + reach;
        let meets = |t: &[DVec3; 3]| {
            let (tlo, thi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
            tlo.cmple(hi).all() && thi.cmpge(lo).all()
        };
        let mut candidates = std::mem::take(&mut self.candidates);
        candidates.clear();
        candidates.extend(new.iter().map(|n| n.corners).filter(|t| meets(t)));
        candidates.extend(self.near.iter().map(|n| n.1).filter(|t| meets(t)));
        let covered = covered_in_pieces(corners, &candidates, self.bound, PIECE_DEPTH);
        self.candidates = candidates;
        covered
    }

    /// Output → input: every sample of the new triangles' fresh parts within
    /// `SAMPLE_SHARE` of the bound of a gathered or near input triangle.
    fn samples_covered(
        &mut self,
        new: &[NewTriangle],
        near: &mut Option<Near<'_>>,
        near_read: &mut bool,
    ) -> bool {
        let limit = SAMPLE_SHARE * self.bound;
        let limit2 = limit * limit;
        // The input each new triangle took (this change's moves), looked at first: near it.
        let mut own = std::mem::take(&mut self.own);
        own.clear();
        let moves = &self.moves[self.moves_from..];
        own.extend(moves.iter().filter_map(|&(t, target)| match target {
            Target::New(id) => Some((id, t)),
            Target::Slot(_) => None,
        }));
        own.sort_unstable();
        let mut last = NONE;
        let mut covered = true;
        'triangles: for n in new {
            let from = own.partition_point(|&(id, _)| id < n.id);
            let to = own.partition_point(|&(id, _)| id <= n.id);
            let mine = &own[from..to];
            let steps = grid_steps(&n.corners, self.bound);
            for (i, j) in grid(steps) {
                let Some(p) = sample(n, steps, i, j) else {
                    continue;
                };
                let within = |t: u32| distance2(p, &self.input[t as usize]) <= limit2;
                if last != NONE && within(last) {
                    continue;
                }
                let found = (mine.iter().map(|&(_, t)| t))
                    .chain(self.gathered.iter().copied())
                    .find(|&t| within(t));
                let found = match found {
                    Some(t) => Some(t),
                    None => {
                        self.read_near(near, near_read);
                        let within = |t: u32| distance2(p, &self.input[t as usize]) <= limit2;
                        self.near_input.iter().copied().find(|&t| within(t))
                    }
                };
                match found {
                    Some(t) => last = t,
                    None => {
                        covered = false;
                        break 'triangles;
                    }
                }
            }
        }
        self.own = own;
        covered
    }
}

/// Whether every piece of the triangle `corners`, cut in four `depth` times at most, lies
/// within `bound` of one of `triangles` (at its corners: the distance to one triangle is
/// convex), or, the last cut's pieces, has each corner within `SAMPLE_SHARE` of `bound` of
/// some triangle.
fn covered_in_pieces(
    corners: &[DVec3; 3],
    triangles: &[[DVec3; 3]],
    bound: f64,
    depth: u32,
) -> bool {
    let bound2 = bound * bound;
    let within =
        |tri: &[DVec3; 3]| (corners.iter()).all(|&c| point_triangle_distance2(c, tri) <= bound2);
    if triangles.iter().any(within) {
        return true;
    }
    if depth == 0 {
        let limit2 = (SAMPLE_SHARE * bound).powi(2);
        return (corners.iter())
            .all(|&c| (triangles.iter()).any(|t| point_triangle_distance2(c, t) <= limit2));
    }
    let [a, b, c] = *corners;
    let (ab, bc, ca) = ((a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0);
    [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
        .iter()
        .all(|piece| covered_in_pieces(piece, triangles, bound, depth - 1))
}

/// Grid steps along the longest edge of `corners`: samples at most a fifth of `bound`
/// apart, between 2 and `MAX_STEPS`.
fn grid_steps(corners: &[DVec3; 3], bound: f64) -> usize {
    let longest = (0..3)
        .map(|i| corners[i].distance(corners[(i + 1) % 3]))
        .fold(0.0, f64::max);
    let steps = (5.0 * longest / bound.max(f64::MIN_POSITIVE)).ceil();
    if steps.is_finite() {
        (steps as usize).clamp(2, MAX_STEPS)
    } else {
        MAX_STEPS
    }
}

/// The barycentric grid of `steps`: (i, j) with i + j ≤ steps.
fn grid(steps: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..=steps).flat_map(move |i| (0..=steps - i).map(move |j| (i, j)))
}

/// Grid point (i, j) of `n` (weights i, j, steps − i − j on its corners 0, 1, 2), when it
/// lies inside or on a fresh edge or corner.
fn sample(n: &NewTriangle, steps: usize, i: usize, j: usize) -> Option<DVec3> {
    let k = steps - i - j;
    let weights = [i, j, k];
    let zeros = weights.iter().filter(|&&w| w == 0).count();
    let fresh = |bit: usize| n.fresh & (1 << bit) != 0;
    let keep = match zeros {
        0 => true,
        // On edge c → c + 1: the corner opposite has weight 0.
        1 => {
            let opposite = weights.iter().position(|&w| w == 0).unwrap_or(0);
            fresh(3 + (opposite + 1) % 3)
        }
        _ => fresh(weights.iter().position(|&w| w != 0).unwrap_or(0)),
    };
    let s = steps as f64;
    keep.then(|| (n.corners[0] * i as f64 + n.corners[1] * j as f64 + n.corners[2] * k as f64) / s)
}

/// Of `tris`, the one whose farthest distance from the three `corners` is smallest, with
/// that distance.
fn nearest_at_corners<'a>(
    corners: &[DVec3; 3],
    tris: impl Iterator<Item = (u32, &'a [DVec3; 3])>,
) -> Option<(u32, f64)> {
    let mut best: Option<(u32, f64)> = None;
    for (id, tri) in tris {
        let cap = best.map_or(f64::INFINITY, |b| b.1);
        let mut worst2: f64 = 0.0;
        for &c in corners {
            worst2 = worst2.max(point_triangle_distance2(c, tri));
            if worst2 >= cap * cap {
                break;
            }
        }
        let worst = worst2.sqrt();
        if worst < cap {
            best = Some((id, worst));
        }
    }
    best
}

/// Squared distance from `p` to input triangle `t`.
fn distance2(p: DVec3, t: &[Vec3; 3]) -> f64 {
    point_triangle_distance2(p, &t.map(|c| c.as_dvec3()))
}

/// Squared distance from `p` to the triangle `[a, b, c]` (a degenerate one as its
/// segments), by the region of the triangle's plane `p` projects into.
pub(crate) fn point_triangle_distance2(p: DVec3, [a, b, c]: &[DVec3; 3]) -> f64 {
    let (ab, ac, ap) = (*b - *a, *c - *a, p - *a);
    let n = ab.cross(ac);
    let n2 = n.length_squared();
    if n2 > 1e-30 * ab.length_squared().max(ac.length_squared()).powi(2) {
        // Inside the triangle's prism: the distance to its plane.
        let inside = |u: DVec3, v: DVec3, q: DVec3| (v - u).cross(q - u).dot(n) >= 0.0;
        if inside(*a, *b, p) && inside(*b, *c, p) && inside(*c, *a, p) {
            let d = ap.dot(n);
            return d * d / n2;
        }
    }
    segment_distance2(p, *a, *b)
        .min(segment_distance2(p, *b, *c))
        .min(segment_distance2(p, *c, *a))
}

/// Squared distance from `p` to the segment `a`–`b`.
fn segment_distance2(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    let s = if l2 > 0.0 {
        ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * s).distance_squared(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: [DVec3; 3] = [DVec3::ZERO, DVec3::X, DVec3::Y];

    #[test]
    fn distance_to_a_triangle_by_region() {
        let d = |p: DVec3| point_triangle_distance2(p, &TRI).sqrt();
        assert!((d(DVec3::new(0.2, 0.2, 0.5)) - 0.5).abs() < 1e-12);
        assert!((d(DVec3::new(-1.0, 0.0, 0.0)) - 1.0).abs() < 1e-12);
        assert!((d(DVec3::new(1.0, 1.0, 0.0)) - 0.5f64.sqrt()).abs() < 1e-12);
        assert!((d(DVec3::new(0.5, -2.0, 0.0)) - 2.0).abs() < 1e-12);
    }

    /// A square of four triangles around a centre raised by 0.2, its centre removed.
    fn pyramid(bound: f64) -> (DistanceBound, [NewTriangle; 2]) {
        let positions = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::Y,
            Vec3::new(0.5, 0.5, 0.2),
        ];
        let triangles = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
        let p = |v: usize| positions[v].as_dvec3();
        // Only the diagonal (edge 2 → 0 of the first, 0 → 1 of the second) and the inside
        // are new.
        let fill = [
            NewTriangle {
                id: 0,
                corners: [p(0), p(1), p(2)],
                fresh: 1 << 5,
            },
            NewTriangle {
                id: 1,
                corners: [p(0), p(2), p(3)],
                fresh: 1 << 3,
            },
        ];
        (DistanceBound::new(&positions, &triangles, bound), fill)
    }

    #[test]
    fn a_removal_past_the_bound_is_refused_and_one_within_it_moves_the_input() {
        let (mut b, fill) = pyramid(0.15);
        assert!(!b.check(&[0, 1, 2, 3], &fill, None));
        b.discard();
        let (mut b, fill) = pyramid(0.25);
        assert!(b.check(&[0, 1, 2, 3], &fill, None));
        b.commit(|id| 10 + id);
        let listed = |s: usize| {
            let mut list = Vec::new();
            let mut t = b.head.get(s).copied().unwrap_or(NONE);
            while t != NONE {
                list.push(t);
                t = b.next[t as usize];
            }
            list.sort_unstable();
            list
        };
        let (a, c) = (listed(10), listed(11));
        assert_eq!(a.len() + c.len(), 4, "{a:?} {c:?}");
        assert!((0..4).all(|s| listed(s).is_empty()));
    }
}

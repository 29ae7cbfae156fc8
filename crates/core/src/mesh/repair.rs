//! Repair of damaged input before decimation, with a count of everything changed: vertices
//! welded within a tolerance (`--weld-tolerance`), null edges (two vertices at one point
//! joined by an edge) collapsed, triangles with a repeated corner or no area, duplicated
//! triangles (the same three vertices, either way round; a reversed copy kept where
//! removing it would open a border in the surface), triangles facing against their
//! neighbours across manifold edges (flipped to the majority of their connected surface),
//! and vertices no triangle uses. Everything here is a sort or a walk
//! over the triangles: O(n log n) at worst.

use glam::DVec3;

use super::{union_find, weld, Attribute, Model};

/// How close two vertices must be to merge, as `--weld-tolerance` gave it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// In model units.
    Absolute(f64),
    /// A fraction of the model's bounding-box diagonal.
    DiagonalFraction(f64),
}

impl Tolerance {
    /// The tolerance in `model`'s units.
    pub fn for_model(self, model: &Model) -> f64 {
        match self {
            Self::Absolute(e) => e,
            Self::DiagonalFraction(f) => model
                .bounds()
                .map_or(0.0, |(lo, hi)| f64::from((hi - lo).length()) * f),
        }
    }
}

/// What [`repair`] changed in a model (or, summed, in a scene).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Repairs {
    /// Vertices merged into another within the weld tolerance.
    pub welded: usize,
    /// Vertices merged into another at the same point across an edge (a null edge).
    pub null_edges: usize,
    /// Triangles with a repeated corner or zero area (collinear corners), removed.
    pub degenerate: usize,
    /// Triangles on the same three vertices as an earlier one, removed (a reversed copy only
    /// where that opens no border).
    pub duplicates: usize,
    /// Triangles flipped to face the same way as their neighbours.
    pub reoriented: usize,
    /// Vertices no triangle uses, removed.
    pub unreferenced: usize,
}

impl Repairs {
    /// Adds `other`'s counts to these.
    pub fn add(&mut self, other: &Self) {
        self.welded += other.welded;
        self.degenerate += other.degenerate;
        self.duplicates += other.duplicates;
        self.null_edges += other.null_edges;
        self.reoriented += other.reoriented;
        self.unreferenced += other.unreferenced;
    }

    /// True when nothing was changed.
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// One line saying what was repaired (`None` when nothing was), for the summary.
    pub fn summary(&self) -> Option<String> {
        let plural =
            |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        let mut parts = Vec::new();
        if self.welded > 0 {
            parts.push(format!(
                "{} welded within the tolerance",
                plural(self.welded, "vertex", "vertices")
            ));
        }
        if self.null_edges > 0 {
            parts.push(format!(
                "{} collapsed",
                plural(self.null_edges, "null edge", "null edges")
            ));
        }
        if self.degenerate > 0 {
            parts.push(format!(
                "{} with no area removed",
                plural(self.degenerate, "triangle", "triangles")
            ));
        }
        if self.duplicates > 0 {
            parts.push(format!(
                "{} removed",
                plural(self.duplicates, "duplicate triangle", "duplicate triangles")
            ));
        }
        if self.reoriented > 0 {
            parts.push(format!(
                "{} flipped to face like their neighbours",
                plural(self.reoriented, "triangle", "triangles")
            ));
        }
        if self.unreferenced > 0 {
            parts.push(format!(
                "{} removed",
                plural(self.unreferenced, "unused vertex", "unused vertices")
            ));
        }
        (!parts.is_empty()).then(|| format!("repaired input: {}\n", parts.join(", ")))
    }
}

/// Repairs `model` in place (see the module's doc), welding first within `tolerance` model
/// units when it is positive; returns what it changed.
pub fn repair(model: &mut Model, tolerance: f64) -> Repairs {
    let mut r = Repairs::default();
    if tolerance > 0.0 {
        // Triangles the weld collapses have no area left: counted as degenerate below.
        let before = model.triangles.len();
        r.welded = weld::weld(model, tolerance as f32);
        r.degenerate += before - model.triangles.len();
    }
    r.null_edges = collapse_null_edges(model);
    let keep = keep_proper_triangles(model, &mut r);
    retain_triangles(model, &keep);
    r.reoriented = orient_consistently(&mut model.triangles);
    r.unreferenced = drop_unused_vertices(model);
    r
}

/// Marks the triangles to keep: not degenerate (a repeated or out-of-range corner, or
/// collinear corners) and not on the same three vertices as an earlier kept one.
fn keep_proper_triangles(model: &Model, r: &mut Repairs) -> Vec<bool> {
    let p = |v: u32| model.positions.get(v as usize).map(|&q| q.as_dvec3());
    let mut keep: Vec<bool> = model
        .triangles
        .iter()
        .map(|t| {
            let (Some(a), Some(b), Some(c)) = (p(t[0]), p(t[1]), p(t[2])) else {
                return false;
            };
            // From f32 coordinates the products are exact: zero means collinear.
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2] && (b - a).cross(c - a) != DVec3::ZERO
        })
        .collect();
    r.degenerate += keep.iter().filter(|&&k| !k).count();
    let keyed = keyed_by_corners(&model.triangles, &keep, model.positions.len());
    // Sorted by index within a run of equal keys: the first in the file stays. A copy the
    // same way round is an error of the file and goes; a reversed one may be the other side
    // of a doubled sheet, and goes only where that opens nothing.
    let mut reversed = Vec::new();
    let mut start = 0;
    for i in 1..=keyed.len() {
        if i < keyed.len() && keyed[i].0 == keyed[start].0 {
            let (first, copy) = (keyed[start].1 as usize, keyed[i].1);
            if same_way_round(model.triangles[first], model.triangles[copy as usize]) {
                keep[copy as usize] = false;
                r.duplicates += 1;
            } else {
                reversed.push(copy);
            }
        } else {
            start = i;
        }
    }
    r.duplicates += remove_reversed_copies(&model.triangles, &reversed, &mut keep);
    keep
}

/// The kept triangles' corners sorted, each with its triangle's index, in the order of
/// those keys and then of the index: bucketed by the smallest corner (a counting sort over
/// the `n` vertices) and each bucket sorted on its own — linear but for the buckets' sorts,
/// where one sort of all the keys cost a third of the repair.
fn keyed_by_corners(triangles: &[[u32; 3]], keep: &[bool], n: usize) -> Vec<([u32; 3], u32)> {
    let key = |t: [u32; 3]| {
        let mut k = t;
        k.sort_unstable();
        k
    };
    let kept = || (0..triangles.len()).filter(|&i| keep[i]);
    let mut start = vec![0u32; n + 1];
    for i in kept() {
        start[key(triangles[i])[0] as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut keyed = vec![([0u32; 3], 0u32); start[n] as usize];
    let mut next = start[..n].to_vec();
    for i in kept() {
        let k = key(triangles[i]);
        let slot = &mut next[k[0] as usize];
        keyed[*slot as usize] = (k, i as u32);
        *slot += 1;
    }
    drop(next);
    for v in 0..n {
        let bucket = &mut keyed[start[v] as usize..start[v + 1] as usize];
        if bucket.len() > 1 {
            bucket.sort_unstable();
        }
    }
    keyed
}

/// Whether `b` is `a` rotated (the same corners in the same cyclic order).
fn same_way_round(a: [u32; 3], b: [u32; 3]) -> bool {
    b == a || b == [a[1], a[2], a[0]] || b == [a[2], a[0], a[1]]
}

/// Removes the reversed copies, a connected group of them at a time (copies sharing an
/// edge), where removing the whole group leaves every edge on no triangle or on two or
/// more; returns how many went. A doubled sheet (each triangle beside its reversed twin: a
/// two-sided leaf, a fin of a scan) is a closed surface: deleting one side would open it,
/// so both sides of it stay, whole.
fn remove_reversed_copies(triangles: &[[u32; 3]], reversed: &[u32], keep: &mut [bool]) -> usize {
    if reversed.is_empty() {
        return 0;
    }
    let edges_of = |t: u32| {
        let t = triangles[t as usize];
        [0, 1, 2].map(|k| edge_key(t[k], t[(k + 1) % 3]))
    };
    // Only the copies' own edges are counted: an edge of a kept triangle is looked up only
    // where both its ends are corners of a copy.
    let mut edges: Vec<u64> = reversed.iter().flat_map(|&t| edges_of(t)).collect();
    edges.sort_unstable();
    edges.dedup();
    // Sized by the copies' corners alone: a triangle not kept may name any index.
    let copies = reversed.iter().flat_map(|&t| triangles[t as usize]);
    let mut corner = vec![false; copies.max().map_or(0, |v| v as usize + 1)];
    for &t in reversed {
        triangles[t as usize]
            .iter()
            .for_each(|&v| corner[v as usize] = true);
    }
    let is_corner = |v: u32| corner.get(v as usize).copied().unwrap_or(false);
    let slot = |e: u64| edges.partition_point(|&x| x < e);
    let mut count = vec![0u32; edges.len()];
    for t in (0..triangles.len()).filter(|&t| keep[t]) {
        let tri = triangles[t];
        for k in (0..3).filter(|&k| is_corner(tri[k]) && is_corner(tri[(k + 1) % 3])) {
            let e = edge_key(tri[k], tri[(k + 1) % 3]);
            let i = slot(e);
            if edges.get(i) == Some(&e) {
                count[i] += 1;
            }
        }
    }
    let mut removed = 0;
    for group in groups_sharing_edges(reversed, &edges_of) {
        let mut slots: Vec<usize> = group.iter().flat_map(|&t| edges_of(t).map(slot)).collect();
        slots.sort_unstable();
        let opens = slots.chunk_by(|a, b| a == b).any(|run| {
            let left = count[run[0]] as usize - run.len();
            left == 1
        });
        if opens {
            continue;
        }
        slots.iter().for_each(|&i| count[i] -= 1);
        group.iter().for_each(|&t| keep[t as usize] = false);
        removed += group.len();
    }
    removed
}

/// `members` in groups joined through shared edges (union-find over an edge sort).
fn groups_sharing_edges(members: &[u32], edges_of: &impl Fn(u32) -> [u64; 3]) -> Vec<Vec<u32>> {
    let mut by_edge: Vec<(u64, u32)> = (0..members.len() as u32)
        .flat_map(|i| edges_of(members[i as usize]).map(|e| (e, i)))
        .collect();
    by_edge.sort_unstable();
    let mut parent = union_find::singletons(members.len());
    for w in by_edge.windows(2) {
        if w[0].0 == w[1].0 {
            let (a, b) = (
                union_find::root(&mut parent, w[0].1),
                union_find::root(&mut parent, w[1].1),
            );
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    let mut groups: Vec<Vec<u32>> = Vec::new();
    let mut group_of = vec![u32::MAX; members.len()];
    for i in 0..members.len() as u32 {
        let r = union_find::root(&mut parent, i) as usize;
        if group_of[r] == u32::MAX {
            group_of[r] = groups.len() as u32;
            groups.push(Vec::new());
        }
        groups[group_of[r] as usize].push(members[i as usize]);
    }
    groups
}

/// Merges the two ends of every edge whose ends are at the same point (bit-equal
/// positions), so that the triangles on it lose a corner and go, and the surface around
/// stays closed; returns the vertices merged away. Without a weld, a null edge is the only
/// link between the triangles on its two sides: deleting those triangles would cut a slit.
fn collapse_null_edges(model: &mut Model) -> usize {
    let n = model.positions.len();
    let same = |a: u32, b: u32| {
        a != b
            && (a as usize) < n
            && (b as usize) < n
            && model.positions[a as usize] == model.positions[b as usize]
    };
    let mut parent: Option<Vec<u32>> = None;
    for t in &model.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if same(a, b) {
                let parent = parent.get_or_insert_with(|| union_find::singletons(n));
                let (ra, rb) = (union_find::root(parent, a), union_find::root(parent, b));
                // The smaller index stands for the set: the first in the file.
                parent[ra.max(rb) as usize] = ra.min(rb);
            }
        }
    }
    let Some(mut parent) = parent else {
        return 0;
    };
    let mut merged = 0;
    for v in 0..n as u32 {
        if union_find::root(&mut parent, v) != v {
            merged += 1;
        }
    }
    for t in &mut model.triangles {
        for v in t.iter_mut().filter(|v| (**v as usize) < n) {
            *v = union_find::root(&mut parent, *v);
        }
    }
    merged
}

/// Keeps the triangles marked in `keep`, with their per-face attributes.
pub fn retain_triangles(model: &mut Model, keep: &[bool]) {
    if keep.iter().all(|&k| k) {
        return;
    }
    fn retain<T>(v: &mut Vec<T>, keep: &[bool]) {
        let mut k = keep.iter();
        v.retain(|_| k.next().copied().unwrap_or(false));
    }
    retain(&mut model.triangles, keep);
    if let Some(Attribute::PerFace(c)) = &mut model.colors {
        retain(c, keep);
    }
    if let Some(Attribute::PerFace(n)) = &mut model.normals {
        retain(n, keep);
    }
}

/// Flips triangles so that neighbours across every manifold edge (one used by exactly two
/// triangles) traverse it in opposite directions; in each connected surface the
/// orientation most of its triangles have wins. Returns how many were flipped. (Beyond
/// `MAX_ORIENTED` triangles, more than memory holds in core, nothing is flipped.)
pub fn orient_consistently(triangles: &mut [[u32; 3]]) -> usize {
    if triangles.len() > MAX_ORIENTED {
        return 0;
    }
    let across = manifold_neighbours(triangles);
    // Where every neighbour already runs its shared edge the other way (a clean surface),
    // the walk would flip nothing.
    let opposed = |a: u32| a == NO_NEIGHBOUR || a & SAME_WAY == 0;
    if across.iter().flatten().all(|&a| opposed(a)) {
        return 0;
    }
    // Breadth-first over each connected surface: flip[t] relative to the first triangle,
    // meeting each triangle's neighbours in the order of their shared edges' keys.
    let mut flip: Vec<Option<bool>> = vec![None; triangles.len()];
    let mut queue = Vec::new();
    let mut flipped = 0;
    for seed in 0..triangles.len() {
        if flip[seed].is_some() {
            continue;
        }
        flip[seed] = Some(false);
        queue.clear();
        queue.push(seed as u32);
        let mut at = 0;
        while let Some(&t) = queue.get(at) {
            at += 1;
            let ft = flip[t as usize] == Some(true);
            let tri = triangles[t as usize];
            let mut next: [(u64, u32); 3] = [(u64::MAX, NO_NEIGHBOUR); 3];
            for (k, slot) in next.iter_mut().enumerate() {
                if across[t as usize][k] != NO_NEIGHBOUR {
                    *slot = (edge_key(tri[k], tri[(k + 1) % 3]), across[t as usize][k]);
                }
            }
            next.sort_unstable();
            for &(_, packed) in next.iter().filter(|n| n.1 != NO_NEIGHBOUR) {
                let (u, same) = (packed & !SAME_WAY, packed & SAME_WAY != 0);
                if flip[u as usize].is_none() {
                    flip[u as usize] = Some(ft ^ same);
                    queue.push(u);
                }
            }
        }
        // A non-orientable surface (a Möbius strip) keeps the walk's choice.
        flipped += flip_minority(&queue, &flip, triangles);
    }
    flipped
}

/// Turns over the triangles of one walked surface (`queue`) whose flip differs from the
/// majority's, so most of the surface keeps its orientation; returns how many turned.
fn flip_minority(queue: &[u32], flip: &[Option<bool>], triangles: &mut [[u32; 3]]) -> usize {
    let ones = queue
        .iter()
        .filter(|&&t| flip[t as usize] == Some(true))
        .count();
    let invert = ones * 2 > queue.len();
    let mut flipped = 0;
    for &t in queue {
        if (flip[t as usize] == Some(true)) != invert {
            triangles[t as usize].swap(1, 2);
            flipped += 1;
        }
    }
    flipped
}

/// No triangle across an edge ([`manifold_neighbours`]).
const NO_NEIGHBOUR: u32 = u32::MAX;

/// The bit of a [`manifold_neighbours`] entry set when the neighbour runs the shared edge
/// the same way (one of the two must then flip); triangle ids stay below it.
const SAME_WAY: u32 = 1 << 31;

/// Most triangles [`orient_consistently`] handles: half-edge ids (three a triangle) fit in
/// a `u32`, triangle ids below [`SAME_WAY`].
const MAX_ORIENTED: usize = (u32::MAX / 3) as usize;

/// The undirected edge `a`–`b` as one sortable number.
fn edge_key(a: u32, b: u32) -> u64 {
    u64::from(a.min(b)) << 32 | u64::from(a.max(b))
}

/// For each triangle and each of its edges `k` (corner `k` to `k + 1`), the triangle across
/// it when the edge is manifold (exactly two triangles), with [`SAME_WAY`], else
/// [`NO_NEIGHBOUR`]. The half-edges are bucketed by their smaller vertex (a counting sort),
/// each with its larger vertex above its id in one `u64`, and each bucket sorted as plain
/// numbers: 24 bytes a triangle beside the result, linear but for the buckets' own sorts.
fn manifold_neighbours(triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let n = triangles
        .iter()
        .flatten()
        .max()
        .map_or(0, |&v| v as usize + 1);
    let ends = |h: u32| {
        let tri = triangles[h as usize / 3];
        let k = h as usize % 3;
        (tri[k], tri[(k + 1) % 3])
    };
    let mut start = vec![0u32; n + 1];
    for h in 0..triangles.len() as u32 * 3 {
        let (a, b) = ends(h);
        start[a.min(b) as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut half = vec![0u64; triangles.len() * 3];
    let mut next = start[..n].to_vec();
    for h in 0..triangles.len() as u32 * 3 {
        let (a, b) = ends(h);
        let slot = &mut next[a.min(b) as usize];
        half[*slot as usize] = u64::from(a.max(b)) << 32 | u64::from(h);
        *slot += 1;
    }
    drop(next);
    let mut across = vec![[NO_NEIGHBOUR; 3]; triangles.len()];
    let forward = |h: u32| {
        let (a, b) = ends(h);
        a < b
    };
    for v in 0..n {
        let bucket = &mut half[start[v] as usize..start[v + 1] as usize];
        bucket.sort_unstable();
        for run in bucket.chunk_by(|&g, &h| g >> 32 == h >> 32) {
            let &[g, h] = run else { continue };
            let (g, h) = (g as u32, h as u32);
            let (s, t) = (g / 3, h / 3);
            if s != t {
                let same = if forward(g) == forward(h) {
                    SAME_WAY
                } else {
                    0
                };
                across[s as usize][g as usize % 3] = t | same;
                across[t as usize][h as usize % 3] = s | same;
            }
        }
    }
    across
}

/// Removes the vertices no triangle uses, with their per-vertex attributes; returns how
/// many.
pub(crate) fn drop_unused_vertices(model: &mut Model) -> usize {
    let n = model.positions.len();
    let mut used = vec![false; n];
    for t in &model.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let kept: Vec<u32> = (0..n as u32).filter(|&v| used[v as usize]).collect();
    if kept.len() == n {
        return 0;
    }
    let mut map = vec![u32::MAX; n];
    for (new, &old) in kept.iter().enumerate() {
        map[old as usize] = new as u32;
    }
    for t in &mut model.triangles {
        *t = t.map(|v| map[v as usize]);
    }
    model.positions = kept.iter().map(|&i| model.positions[i as usize]).collect();
    if let Some(Attribute::PerVertex(c)) = &mut model.colors {
        if c.len() == n {
            *c = kept.iter().map(|&i| c[i as usize]).collect();
        }
    }
    if let Some(Attribute::PerVertex(nv)) = &mut model.normals {
        if nv.len() == n {
            *nv = kept.iter().map(|&i| nv[i as usize]).collect();
        }
    }
    if let Some(t) = &mut model.texcoords {
        if t.len() == n {
            *t = kept.iter().map(|&i| t[i as usize]).collect();
        }
    }
    n - kept.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::octahedron;
    use glam::Vec3;

    fn volume6(m: &Model) -> f64 {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| m.positions[v as usize].as_dvec3());
                a.dot(b.cross(c))
            })
            .sum()
    }

    #[test]
    fn a_clean_octahedron_is_left_alone() {
        let mut m = octahedron();
        assert!(volume6(&m) > 0.0);
        let before = m.clone();
        assert!(repair(&mut m, 0.0).is_empty());
        assert_eq!(m, before);
    }

    #[test]
    fn every_kind_of_damage_is_counted_and_fixed() {
        let mut m = octahedron();
        // Two faces turned inside out, one face twice (once each way round), a triangle
        // with a repeated corner, one with collinear corners, and two unused vertices.
        m.triangles[1].swap(0, 1);
        m.triangles[6].swap(1, 2);
        m.triangles.push([4, 0, 2]);
        m.triangles.push([0, 0, 5]);
        m.positions.push(Vec3::new(0.5, 0.0, 0.0)); // 6, on the segment 0..1
        m.positions.push(Vec3::new(9.0, 9.0, 9.0)); // 7, used by nothing
        m.triangles.push([0, 6, 1]);
        m.colors = Some(Attribute::PerFace((0..11).map(|i| [i as f32; 3]).collect()));
        let r = repair(&mut m, 0.0);
        assert_eq!(
            r,
            Repairs {
                welded: 0,
                null_edges: 0,
                degenerate: 2,
                duplicates: 1,
                reoriented: 2,
                unreferenced: 2,
            }
        );
        assert_eq!(m.triangles.len(), 8);
        assert_eq!(m.positions.len(), 6);
        assert!((volume6(&m) - 8.0).abs() < 1e-12, "{}", volume6(&m));
        let Some(Attribute::PerFace(c)) = &m.colors else {
            panic!("per-face colours lost")
        };
        assert_eq!(c.len(), 8);
        assert_eq!(c[7], [7.0; 3]);
        let line = r.summary().unwrap_or_default();
        assert!(line.contains("2 triangles with no area removed"), "{line}");
        assert!(line.contains("1 duplicate triangle removed"), "{line}");
        assert!(line.contains("2 triangles flipped"), "{line}");
        assert!(line.contains("2 unused vertices removed"), "{line}");
    }

    /// Edges used by exactly one triangle.
    fn border_edges(m: &Model) -> usize {
        let mut edges: Vec<u64> = (m.triangles.iter())
            .flat_map(|t| [0, 1, 2].map(|k| edge_key(t[k], t[(k + 1) % 3])))
            .collect();
        edges.sort_unstable();
        let mut border = 0;
        let mut i = 0;
        while i < edges.len() {
            let j = i + edges[i..].iter().take_while(|&&e| e == edges[i]).count();
            border += usize::from(j - i == 1);
            i = j;
        }
        border
    }

    #[test]
    fn a_null_edge_is_collapsed_and_the_surface_stays_closed() {
        // Vertex 4 (+z) split in two at one point: triangles 0 and 1 keep it, 2 and 3 take
        // its copy 6, and two zero-area triangles join them across the null edge 4–6.
        let mut m = octahedron();
        m.positions.push(Vec3::Z);
        m.triangles[2] = [1, 3, 6];
        m.triangles[3] = [3, 0, 6];
        m.triangles.push([4, 1, 6]);
        m.triangles.push([6, 0, 4]);
        assert_eq!(border_edges(&m), 0);
        let r = repair(&mut m, 0.0);
        assert_eq!((r.null_edges, r.degenerate, r.unreferenced), (1, 2, 1));
        assert_eq!((m.positions.len(), m.triangles.len()), (6, 8));
        assert_eq!(border_edges(&m), 0);
        assert!((volume6(&m) - 8.0).abs() < 1e-12, "{}", volume6(&m));
        assert!(r
            .summary()
            .unwrap_or_default()
            .contains("1 null edge collapsed"));
    }

    #[test]
    fn a_doubled_sheet_keeps_both_sides_and_a_plain_copy_goes() {
        // A square sheet seen from both sides: each triangle beside its reversed twin. It is
        // closed (every edge on two triangles); removing one side would open all four rims.
        let mut m = Model {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3], [0, 2, 1], [0, 3, 2]],
            ..Model::default()
        };
        let r = repair(&mut m, 0.0);
        assert_eq!(
            (r.duplicates, m.triangles.len(), border_edges(&m)),
            (0, 4, 0)
        );
        // A third copy of a triangle whose edges keep two triangles without it does go.
        m.triangles.push([0, 1, 2]);
        let r = repair(&mut m, 0.0);
        assert_eq!(
            (r.duplicates, m.triangles.len(), border_edges(&m)),
            (1, 4, 0)
        );
    }

    #[test]
    fn a_wholly_inverted_surface_keeps_its_orientation() {
        // The file's majority orientation wins: an inside-out octahedron stays so.
        let mut m = octahedron();
        m.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        m.triangles[3].swap(1, 2);
        assert_eq!(orient_consistently(&mut m.triangles), 1);
        assert!((volume6(&m) + 8.0).abs() < 1e-12);
    }

    #[test]
    fn near_duplicates_weld_within_a_fraction_of_the_diagonal() {
        // Two triangles of a square whose shared edge's ends are 1e-4 apart.
        let mut m = Model {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::new(1.0, 1e-4, 0.0),
                Vec3::new(1e-4, 1.0, 0.0),
                Vec3::ONE.with_z(0.0),
            ],
            triangles: vec![[0, 1, 2], [3, 5, 4]],
            ..Model::default()
        };
        let mut untouched = m.clone();
        assert!(repair(&mut untouched, 0.0).is_empty());
        let tol = Tolerance::DiagonalFraction(0.001).for_model(&m);
        assert!((tol - 2f64.sqrt() * 1e-3).abs() < 1e-9);
        let r = repair(&mut m, tol);
        assert_eq!(r.welded, 2);
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [1, 3, 2]]);
    }

    /// The walk as first written, with every neighbour list in memory: the reference the
    /// compact one must match flip for flip.
    fn orient_reference(triangles: &mut [[u32; 3]]) -> usize {
        let mut half: Vec<(u64, u32, bool)> = Vec::new();
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                half.push((edge_key(a, b), t as u32, a < b));
            }
        }
        half.sort_unstable();
        let mut adjacent: Vec<Vec<(u32, bool)>> = vec![Vec::new(); triangles.len()];
        for run in half.chunk_by(|x, y| x.0 == y.0) {
            if let &[(_, s, ds), (_, t, dt)] = run {
                if s != t {
                    adjacent[s as usize].push((t, ds == dt));
                    adjacent[t as usize].push((s, ds == dt));
                }
            }
        }
        let mut flip: Vec<Option<bool>> = vec![None; triangles.len()];
        let mut flipped = 0;
        for seed in 0..triangles.len() {
            if flip[seed].is_some() {
                continue;
            }
            flip[seed] = Some(false);
            let mut queue = vec![seed as u32];
            let mut at = 0;
            while let Some(&t) = queue.get(at) {
                at += 1;
                let ft = flip[t as usize] == Some(true);
                for &(u, same) in &adjacent[t as usize] {
                    if flip[u as usize].is_none() {
                        flip[u as usize] = Some(ft ^ same);
                        queue.push(u);
                    }
                }
            }
            flipped += flip_minority(&queue, &flip, triangles);
        }
        flipped
    }

    #[test]
    fn reorienting_matches_the_reference_walk_on_tangled_soups() {
        // Möbius strips (no orientation fits: the walk's order decides) and random
        // triangles over few vertices (non-manifold edges, surfaces of every size).
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: u32| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % u64::from(n)) as u32
        };
        let mut flips = 0;
        for round in 0..300 {
            let mut soup: Vec<[u32; 3]> = Vec::new();
            if round % 3 == 0 {
                // A Möbius strip of `m` quads, its last quad joined twisted, with random
                // triangles turned and the list shuffled.
                let m = 3 + next(8);
                for i in 0..m {
                    let (a, b) = (2 * i, 2 * i + 1);
                    let (c, d) = if i + 1 == m { (1, 0) } else { (a + 2, b + 2) };
                    soup.push([a, b, d]);
                    soup.push([a, d, c]);
                }
                for i in (1..soup.len()).rev() {
                    soup.swap(i, next(i as u32 + 1) as usize);
                }
                for t in &mut soup {
                    if next(2) == 0 {
                        t.swap(1, 2);
                    }
                }
            } else {
                let vertices = [6, 9, 12][round % 3];
                while soup.len() < 14 {
                    let t = [next(vertices), next(vertices), next(vertices)];
                    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                        soup.push(t);
                    }
                }
            }
            let mut expected = soup.clone();
            let flipped = orient_reference(&mut expected);
            assert_eq!(orient_consistently(&mut soup), flipped, "round {round}");
            assert_eq!(soup, expected, "round {round}");
            flips += flipped;
        }
        assert!(flips > 1000, "the soups exercise flipping ({flips} flips)");
    }

    #[test]
    fn one_turned_triangle_of_a_clean_sphere_is_turned_back_alone() {
        let clean = crate::mesh::shapes::uv_sphere(8, 16).triangles;
        let mut same = clean.clone();
        assert_eq!(orient_consistently(&mut same), 0);
        assert_eq!(same, clean);
        for t in [0, clean.len() / 2, clean.len() - 1] {
            let mut turned = clean.clone();
            turned[t].swap(0, 1);
            assert_eq!(orient_consistently(&mut turned), 1, "triangle {t}");
            let again = (turned.iter().zip(&clean)).all(|(&a, &b)| same_way_round(a, b));
            assert!(again, "triangle {t} alone turned, back to the sphere's way");
        }
    }

    /// Reversed copies removed as first written, every kept edge counted: the reference
    /// the counting of the copies' edges alone must match.
    fn remove_reversed_reference(t: &[[u32; 3]], reversed: &[u32], keep: &mut [bool]) -> usize {
        let edges_of = |i: u32| {
            let tri = t[i as usize];
            [0, 1, 2].map(|k| edge_key(tri[k], tri[(k + 1) % 3]))
        };
        let kept: Vec<u32> = (0..t.len() as u32).filter(|&i| keep[i as usize]).collect();
        let mut edges: Vec<u64> = kept.iter().flat_map(|&i| edges_of(i)).collect();
        edges.sort_unstable();
        edges.dedup();
        let slot = |e: u64| edges.partition_point(|&x| x < e);
        let mut count = vec![0usize; edges.len()];
        for &i in &kept {
            edges_of(i).into_iter().for_each(|e| count[slot(e)] += 1);
        }
        let mut removed = 0;
        for group in groups_sharing_edges(reversed, &edges_of) {
            let mut slots: Vec<usize> = group.iter().flat_map(|&i| edges_of(i).map(slot)).collect();
            slots.sort_unstable();
            if slots
                .chunk_by(|a, b| a == b)
                .any(|r| count[r[0]] - r.len() == 1)
            {
                continue;
            }
            slots.iter().for_each(|&i| count[i] -= 1);
            group.iter().for_each(|&i| keep[i as usize] = false);
            removed += group.len();
        }
        removed
    }

    #[test]
    fn reversed_copies_go_as_the_reference_removes_them() {
        // Random triangles over few vertices, a random share of them named reversed copies:
        // groups that open an edge and groups that do not.
        let mut state = 0x1234_5678_9abc_def1u64;
        let mut next = |n: u32| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % u64::from(n)) as u32
        };
        let mut removed = 0;
        for round in 0..300 {
            let n = 5 + round % 6;
            let mut triangles: Vec<[u32; 3]> = Vec::new();
            while triangles.len() < 24 {
                let t = [next(n), next(n), next(n)];
                if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                    triangles.push(t);
                }
            }
            let keep: Vec<bool> = (0..24).map(|_| next(5) != 0).collect();
            let reversed: Vec<u32> = (0..24u32)
                .filter(|&i| keep[i as usize] && next(3) == 0)
                .collect();
            let (mut a, mut b) = (keep.clone(), keep.clone());
            let got = remove_reversed_copies(&triangles, &reversed, &mut a);
            let expected = remove_reversed_reference(&triangles, &reversed, &mut b);
            assert_eq!((got, &a), (expected, &b), "round {round}");
            removed += got;
        }
        assert!(removed > 100, "the soups remove copies ({removed})");
    }

    #[test]
    fn bucketed_keys_come_in_the_order_of_one_global_sort() {
        // Random triangles over few vertices: many repeated corner sets, either way round,
        // some triangles not kept.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = |n: u32| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % u64::from(n)) as u32
        };
        for round in 0..100 {
            let n = 5 + round % 7;
            let triangles: Vec<[u32; 3]> = (0..40).map(|_| [0; 3].map(|_| next(n))).collect();
            let keep: Vec<bool> = (0..40).map(|_| next(4) != 0).collect();
            let mut expected: Vec<([u32; 3], u32)> = (0..40)
                .filter(|&i| keep[i])
                .map(|i| {
                    let mut k = triangles[i];
                    k.sort_unstable();
                    (k, i as u32)
                })
                .collect();
            expected.sort_unstable();
            let got = keyed_by_corners(&triangles, &keep, n as usize);
            assert_eq!(got, expected, "round {round}");
        }
    }
}

//! Nearest-point queries on a triangle soup: a bounding-volume hierarchy over flat arrays and
//! the closest point on a triangle, for Metro's point-to-surface distance (Cignoni, Rocchini,
//! Scopigno, "Metro: measuring error on simplified surfaces", Computer Graphics Forum 17(2),
//! 1998, section 3: the distance of a sample from the other surface).
//!
//! Owns: [`Bvh`] (binned surface-area-heuristic build, ordered depth-first nearest search with
//! pruning by the best squared distance so far) and [`closest_point_on_triangle`] (the
//! Voronoi-region method of Ericson, *Real-Time Collision Detection*, 2005, §5.1.5).
//!
//! Everything is `f64`: the inputs are `f32` files, so `f64` arithmetic keeps the rounding noise
//! of a distance some nine orders of magnitude under the input's own resolution.

use glam::DVec3;

/// Largest number of triangles in a leaf.
const MAX_LEAF: usize = 4;
/// Bins per axis for the surface-area heuristic.
const BINS: usize = 16;
/// Nodes of at most this many triangles are split at the median instead.
const SMALL_NODE: usize = 16;

/// One node: a box and either two children (`count == 0`, children at `first` and
/// `first + 1`) or a leaf of `count` triangles starting at `first` in [`Bvh`]'s leaf order.
#[derive(Debug, Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    first: u32,
    count: u32,
}

/// The result of a nearest-point query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Squared distance from the query point to `point`.
    pub dist2: f64,
    /// The closest point on the surface.
    pub point: DVec3,
    /// Index of the triangle it lies on, as given to [`Bvh::new`].
    pub triangle: u32,
}

/// A bounding-volume hierarchy over triangles, answering closest-point queries.
#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Triangle corners in leaf order.
    tris: Vec<[DVec3; 3]>,
    /// For each entry of `tris`, its index in the caller's triangle list.
    ids: Vec<u32>,
    /// For each caller triangle index, its position in `tris` (for query hints).
    slot_of: Vec<u32>,
}

/// Squared distance from `p` to the box `[lo, hi]` (0 inside).
#[inline]
fn box_dist2(p: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    let d = (lo - p).max(p - hi).max(DVec3::ZERO);
    d.dot(d)
}

/// Surface area of a box (half of it, which is all the heuristic needs).
#[inline]
fn half_area(lo: DVec3, hi: DVec3) -> f64 {
    let e = (hi - lo).max(DVec3::ZERO);
    e.x * e.y + e.y * e.z + e.z * e.x
}

/// The point of triangle `abc` closest to `p` (Ericson's Voronoi-region tests). Degenerate
/// (collinear) triangles fall back to the closest point on their edges.
pub fn closest_point_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a; // vertex region A
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b; // vertex region B
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0 {
        return a + ab * (d1 / (d1 - d3)); // edge region AB
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c; // vertex region C
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0 {
        return a + ac * (d2 / (d2 - d6)); // edge region AC
    }
    let va = d3 * d6 - d5 * d4;
    let e4 = d4 - d3;
    let e5 = d5 - d6;
    if va <= 0.0 && e4 >= 0.0 && e5 >= 0.0 && e4 + e5 > 0.0 {
        return b + (c - b) * (e4 / (e4 + e5)); // edge region BC
    }
    // Face region: barycentric coordinates from the three signed sub-areas.
    let sum = va + vb + vc;
    if sum > 0.0 {
        let v = vb / sum;
        let w = vc / sum;
        if v >= 0.0 && w >= 0.0 && v + w <= 1.0 {
            return a + ab * v + ac * w;
        }
    }
    // Only a degenerate (zero-area) triangle reaches here: its closest point is on an edge.
    let mut best = closest_point_on_segment(p, a, b);
    for q in [
        closest_point_on_segment(p, b, c),
        closest_point_on_segment(p, c, a),
    ] {
        if q.distance_squared(p) < best.distance_squared(p) {
            best = q;
        }
    }
    best
}

/// The point of segment `ab` closest to `p`.
pub fn closest_point_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let len2 = ab.dot(ab);
    if len2 <= 0.0 {
        return a;
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    a + ab * t
}

/// Bounds of a triangle's corners and of its centroid, kept during the build.
struct BuildItem {
    lo: DVec3,
    hi: DVec3,
    centroid: DVec3,
    id: u32,
}

impl Bvh {
    /// Builds the hierarchy over `triangles` (indices into `positions`). Triangle `i` of the
    /// input is reported as `Hit::triangle == i`. An empty list gives a hierarchy whose
    /// queries return `None`.
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Self {
        let mut items: Vec<BuildItem> = triangles
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let [a, b, c] = t.map(|v| positions[v as usize]);
                BuildItem {
                    lo: a.min(b).min(c),
                    hi: a.max(b).max(c),
                    centroid: (a + b + c) / 3.0,
                    id: i as u32,
                }
            })
            .collect();
        let nodes = if items.is_empty() {
            Vec::new()
        } else {
            build_parallel(&mut items, 0)
        };
        let tris = items
            .iter()
            .map(|it| triangles[it.id as usize].map(|v| positions[v as usize]))
            .collect();
        let ids: Vec<u32> = items.iter().map(|it| it.id).collect();
        let mut slot_of = vec![0u32; ids.len()];
        for (slot, &id) in ids.iter().enumerate() {
            slot_of[id as usize] = slot as u32;
        }
        Self {
            nodes,
            tris,
            ids,
            slot_of,
        }
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// True when there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// Number of nodes (for statistics).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The closest point of the surface to `p`. `hint` is a triangle likely to be near (the
    /// previous query's, for coherent samples): its distance seeds the pruning bound.
    /// `stack` is scratch space, reused between calls.
    pub fn nearest(&self, p: DVec3, hint: Option<u32>, stack: &mut Vec<(u32, f64)>) -> Option<Hit> {
        let root = self.nodes.first()?;
        let mut best = Hit {
            dist2: f64::INFINITY,
            point: DVec3::ZERO,
            triangle: u32::MAX,
        };
        if let Some(slot) = hint.and_then(|h| self.slot_of.get(h as usize)) {
            let [a, b, c] = self.tris[*slot as usize];
            let q = closest_point_on_triangle(p, a, b, c);
            best = Hit {
                dist2: q.distance_squared(p),
                point: q,
                triangle: self.ids[*slot as usize],
            };
        }
        stack.clear();
        stack.push((0, box_dist2(p, root.lo, root.hi)));
        while let Some((index, d2)) = stack.pop() {
            if d2 >= best.dist2 {
                continue;
            }
            let node = self.nodes[index as usize];
            if node.count > 0 {
                let first = node.first as usize;
                for slot in first..first + node.count as usize {
                    let [a, b, c] = self.tris[slot];
                    let q = closest_point_on_triangle(p, a, b, c);
                    let qd2 = q.distance_squared(p);
                    if qd2 < best.dist2 {
                        best = Hit {
                            dist2: qd2,
                            point: q,
                            triangle: self.ids[slot],
                        };
                    }
                }
            } else {
                let [(far, df), (near, dn)] = self.children_far_first(&node, p);
                if df < best.dist2 {
                    stack.push((far, df));
                }
                if dn < best.dist2 {
                    stack.push((near, dn));
                }
            }
        }
        (best.dist2.is_finite()).then_some(best)
    }

    /// An inner node's two children with their boxes' squared distances to `p`, the
    /// farther first (pushed first, so the nearer is searched first).
    fn children_far_first(&self, node: &Node, p: DVec3) -> [(u32, f64); 2] {
        let (l, r) = (node.first, node.first + 1);
        let dist2 = |i: u32| {
            let n = &self.nodes[i as usize];
            box_dist2(p, n.lo, n.hi)
        };
        let (dl, dr) = (dist2(l), dist2(r));
        if dl <= dr {
            [(r, dr), (l, dl)]
        } else {
            [(l, dl), (r, dr)]
        }
    }

    /// The triangle nearest to `p` among those for which `accept(triangle index, closest
    /// point)` holds and whose distance is at most `max_dist2` (squared). Stops early, with the best found so far,
    /// once `budget` triangles have been looked at (accepted or not), so that a query whose answer is "none" costs
    /// at most that much whatever the mesh. `stack` is scratch space, as for [`Bvh::nearest`].
    pub fn nearest_where(
        &self,
        p: DVec3,
        max_dist2: f64,
        budget: usize,
        accept: impl Fn(u32, DVec3) -> bool,
        stack: &mut Vec<(u32, f64)>,
    ) -> Option<Hit> {
        let root = self.nodes.first()?;
        let mut best: Option<Hit> = None;
        let mut tested = 0;
        let bound = |best: &Option<Hit>| best.map_or(max_dist2, |h| h.dist2);
        stack.clear();
        stack.push((0, box_dist2(p, root.lo, root.hi)));
        while let Some((index, d2)) = stack.pop() {
            if d2 > bound(&best) {
                continue;
            }
            let node = self.nodes[index as usize];
            if node.count > 0 {
                let first = node.first as usize;
                for slot in first..first + node.count as usize {
                    if tested == budget {
                        return best;
                    }
                    tested += 1;
                    let id = self.ids[slot];
                    let [a, b, c] = self.tris[slot];
                    let q = closest_point_on_triangle(p, a, b, c);
                    let qd2 = q.distance_squared(p);
                    if qd2 <= bound(&best) && best.is_none_or(|h| qd2 < h.dist2) && accept(id, q) {
                        best = Some(Hit {
                            dist2: qd2,
                            point: q,
                            triangle: id,
                        });
                    }
                }
            } else {
                let [(far, df), (near, dn)] = self.children_far_first(&node, p);
                let limit = bound(&best);
                if df <= limit {
                    stack.push((far, df));
                }
                if dn <= limit {
                    stack.push((near, dn));
                }
            }
        }
        best
    }
}

/// Subtrees smaller than this are built on one thread.
const PARALLEL_MIN: usize = 32 * 1024;

const EMPTY_NODE: Node = Node {
    lo: DVec3::ZERO,
    hi: DVec3::ZERO,
    first: 0,
    count: 0,
};

fn bounds(items: &[BuildItem]) -> (DVec3, DVec3) {
    items.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), it| (lo.min(it.lo), hi.max(it.hi)),
    )
}

/// Builds the subtree over `items` (which start at `offset` in the final leaf order), its
/// root at index 0. Large, balanced splits build their two halves in parallel; anything else
/// goes to [`build_sequential`], so the recursion stays shallow whatever the input.
fn build_parallel(items: &mut [BuildItem], offset: usize) -> Vec<Node> {
    let n = items.len();
    if n < PARALLEL_MIN {
        return build_sequential(items, offset);
    }
    let (lo, hi) = bounds(items);
    let Some(mid) = split(items, lo, hi) else {
        return build_sequential(items, offset);
    };
    if mid.min(n - mid) < n / 8 {
        return build_sequential(items, offset);
    }
    let (left, right) = items.split_at_mut(mid);
    let (l, r) = rayon::join(
        || build_parallel(left, offset),
        || build_parallel(right, offset + mid),
    );
    // Layout: [root, left root, right root, rest of left, rest of right]; a child pair stays
    // adjacent, so interior references shift by where their subtree's rest now starts.
    let mut nodes = Vec::with_capacity(1 + l.len() + r.len());
    nodes.push(Node {
        lo,
        hi,
        first: 1,
        count: 0,
    });
    let l_shift = 2u32; // left index i >= 1 moves to i + 2
    let r_shift = l.len() as u32 + 1; // right index j >= 1 moves to j + |left| + 1
    let fix = |node: &Node, shift: u32| {
        let mut node = *node;
        if node.count == 0 {
            node.first += shift;
        }
        node
    };
    nodes.push(fix(&l[0], l_shift));
    nodes.push(fix(&r[0], r_shift));
    nodes.extend(l[1..].iter().map(|x| fix(x, l_shift)));
    nodes.extend(r[1..].iter().map(|x| fix(x, r_shift)));
    nodes
}

/// Builds the subtree over `items` on this thread with an explicit stack (no recursion, so
/// no input can exhaust the call stack), its root at index 0.
fn build_sequential(items: &mut [BuildItem], offset: usize) -> Vec<Node> {
    let mut nodes = Vec::with_capacity(2 * items.len() / MAX_LEAF + 1);
    nodes.push(EMPTY_NODE);
    let mut stack = vec![(0usize, 0usize, items.len())];
    while let Some((node, start, end)) = stack.pop() {
        let slice = &mut items[start..end];
        let (lo, hi) = bounds(slice);
        nodes[node].lo = lo;
        nodes[node].hi = hi;
        match split(slice, lo, hi) {
            Some(mid) => {
                let left = nodes.len();
                nodes[node].first = left as u32;
                nodes[node].count = 0;
                nodes.push(EMPTY_NODE);
                nodes.push(EMPTY_NODE);
                stack.push((left, start, start + mid));
                stack.push((left + 1, start + mid, end));
            }
            None => {
                nodes[node].first = (offset + start) as u32;
                nodes[node].count = (end - start) as u32;
            }
        }
    }
    nodes
}

/// Chooses a split of `items` by the binned surface-area heuristic and partitions them in
/// place; returns the size of the left part, or `None` to make a leaf.
fn split(items: &mut [BuildItem], plo: DVec3, phi: DVec3) -> Option<usize> {
    let n = items.len();
    if n <= 2 {
        return None;
    }
    let (clo, chi) = items.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), it| (lo.min(it.centroid), hi.max(it.centroid)),
    );
    let extent = chi - clo;
    if n <= SMALL_NODE {
        return median_split(items, extent);
    }
    let usable = [0, 1, 2].map(|axis| extent[axis] > 0.0 && extent[axis].is_finite());
    let scale = DVec3::from_array([0, 1, 2].map(|axis| {
        if usable[axis] {
            BINS as f64 / extent[axis]
        } else {
            0.0
        }
    }));
    let bins = Bins::of(items, clo, scale);
    let best = (0..3)
        .filter(|&a| usable[a])
        .filter_map(|axis| bins.best_boundary(axis).map(|(cost, b)| (cost, axis, b)))
        .fold(None, |best: Option<(f64, usize, usize)>, c| match best {
            // Only a strictly lower cost wins: ties keep the first axis.
            Some(b) if c.0.partial_cmp(&b.0) != Some(std::cmp::Ordering::Less) => Some(b),
            _ => Some(c),
        });
    match best {
        Some((cost, axis, boundary)) => {
            // Leaf cost n (one test per triangle) against traversal + the children's tests.
            let split_cost = 1.0 + cost / half_area(plo, phi).max(f64::MIN_POSITIVE);
            if n <= MAX_LEAF && split_cost >= n as f64 {
                return None;
            }
            Some(partition(items, axis, boundary, clo[axis], scale[axis]))
        }
        // All centroids coincide: no plane separates them; halve the list to bound leaf size.
        None if n > MAX_LEAF => Some(n / 2),
        None => None,
    }
}

/// Binning costs more than it gains on a handful of triangles: split at the median
/// centroid along the longest axis, down to leaves of at most MAX_LEAF.
fn median_split(items: &mut [BuildItem], extent: DVec3) -> Option<usize> {
    let n = items.len();
    if n <= MAX_LEAF {
        return None;
    }
    let axis = extent.max_position();
    let mid = n / 2;
    items.select_nth_unstable_by(mid, |x, y| x.centroid[axis].total_cmp(&y.centroid[axis]));
    Some(mid)
}

/// The bin of a centroid coordinate already shifted and scaled to bin units.
fn bin_of(rel: f64) -> usize {
    (rel as usize).min(BINS - 1)
}

/// Moves the items whose centroid's bin on `axis` is left of `boundary` to the front;
/// returns how many there are.
fn partition(items: &mut [BuildItem], axis: usize, boundary: usize, lo: f64, scale: f64) -> usize {
    let mut left = 0;
    for i in 0..items.len() {
        if bin_of((items[i].centroid[axis] - lo) * scale) < boundary {
            items.swap(i, left);
            left += 1;
        }
    }
    left
}

/// Per axis and bin: how many centroids fall in it, and the box of their triangles.
struct Bins {
    count: [[usize; BINS]; 3],
    lo: [[DVec3; BINS]; 3],
    hi: [[DVec3; BINS]; 3],
}

impl Bins {
    /// One pass bins every item on all three axes at once.
    fn of(items: &[BuildItem], clo: DVec3, scale: DVec3) -> Self {
        let mut bins = Self {
            count: [[0usize; BINS]; 3],
            lo: [[DVec3::splat(f64::INFINITY); BINS]; 3],
            hi: [[DVec3::splat(f64::NEG_INFINITY); BINS]; 3],
        };
        for it in items {
            let rel = (it.centroid - clo) * scale;
            for axis in 0..3 {
                let b = bin_of(rel[axis]);
                bins.count[axis][b] += 1;
                bins.lo[axis][b] = bins.lo[axis][b].min(it.lo);
                bins.hi[axis][b] = bins.hi[axis][b].max(it.hi);
            }
        }
        bins
    }

    /// The cheapest bin boundary on `axis` with items on both sides, and its cost (area
    /// times count, summed over the two sides).
    fn best_boundary(&self, axis: usize) -> Option<(f64, usize)> {
        let (count, blo, bhi) = (&self.count[axis], &self.lo[axis], &self.hi[axis]);
        // Sweep from the right to get suffix areas, then from the left for the cost.
        let mut right_area = [0.0f64; BINS];
        let mut right_count = [0usize; BINS];
        let (mut lo, mut hi, mut c) = (
            DVec3::splat(f64::INFINITY),
            DVec3::splat(f64::NEG_INFINITY),
            0usize,
        );
        for b in (1..BINS).rev() {
            lo = lo.min(blo[b]);
            hi = hi.max(bhi[b]);
            c += count[b];
            right_area[b] = half_area(lo, hi);
            right_count[b] = c;
        }
        let (mut lo, mut hi, mut c) = (
            DVec3::splat(f64::INFINITY),
            DVec3::splat(f64::NEG_INFINITY),
            0usize,
        );
        let mut best: Option<(f64, usize)> = None;
        for b in 1..BINS {
            lo = lo.min(blo[b - 1]);
            hi = hi.max(bhi[b - 1]);
            c += count[b - 1];
            if c == 0 || right_count[b] == 0 {
                continue;
            }
            let cost = half_area(lo, hi) * c as f64 + right_area[b] * right_count[b] as f64;
            if best.is_none_or(|(bc, _)| cost < bc) {
                best = Some((cost, b));
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_point_regions() {
        let a = DVec3::new(0.0, 0.0, 0.0);
        let b = DVec3::new(1.0, 0.0, 0.0);
        let c = DVec3::new(0.0, 1.0, 0.0);
        let cp = |p: DVec3| closest_point_on_triangle(p, a, b, c);
        assert_eq!(cp(DVec3::new(-1.0, -1.0, 3.0)), a);
        assert_eq!(cp(DVec3::new(2.0, -0.5, 0.0)), b);
        assert_eq!(cp(DVec3::new(-0.5, 2.0, 0.0)), c);
        assert_eq!(cp(DVec3::new(0.5, -2.0, 1.0)), DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(cp(DVec3::new(-2.0, 0.25, 1.0)), DVec3::new(0.0, 0.25, 0.0));
        assert_eq!(cp(DVec3::new(1.0, 1.0, 0.0)), DVec3::new(0.5, 0.5, 0.0));
        assert_eq!(
            cp(DVec3::new(0.25, 0.25, -7.0)),
            DVec3::new(0.25, 0.25, 0.0)
        );
    }

    #[test]
    fn collinear_triangle_uses_its_edges() {
        let a = DVec3::ZERO;
        let b = DVec3::new(1.0, 0.0, 0.0);
        let c = DVec3::new(2.0, 0.0, 0.0);
        let q = closest_point_on_triangle(DVec3::new(1.5, 1.0, 0.0), a, b, c);
        assert_eq!(q, DVec3::new(1.5, 0.0, 0.0));
    }

    /// A bumpy `n`×`n` grid over the unit square.
    fn bumpy_grid(n: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
                positions.push(DVec3::new(x, y, 0.1 * (7.0 * x).sin() * (5.0 * y).cos()));
            }
        }
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let v = (j * (n + 1) + i) as u32;
                let w = v + n as u32 + 1;
                triangles.push([v, v + 1, w + 1]);
                triangles.push([v, w + 1, w]);
            }
        }
        (positions, triangles)
    }

    #[test]
    fn tree_holds_every_triangle_once_inside_its_boxes() {
        // 2 × 130² triangles: above PARALLEL_MIN, so the parallel top and its merge run.
        let (positions, triangles) = bumpy_grid(130);
        assert!(triangles.len() > PARALLEL_MIN);
        let bvh = Bvh::new(&positions, &triangles);
        let mut seen = vec![0u32; triangles.len()];
        let mut stack = vec![0usize];
        let mut leaves = 0;
        while let Some(i) = stack.pop() {
            let node = bvh.nodes[i];
            if node.count == 0 {
                for child in [node.first as usize, node.first as usize + 1] {
                    let c = bvh.nodes[child];
                    assert!(c.lo.cmpge(node.lo).all() && c.hi.cmple(node.hi).all());
                    stack.push(child);
                }
            } else {
                leaves += 1;
                assert!(node.count as usize <= MAX_LEAF);
                for slot in node.first as usize..(node.first + node.count) as usize {
                    seen[bvh.ids[slot] as usize] += 1;
                    for p in bvh.tris[slot] {
                        assert!(p.cmpge(node.lo).all() && p.cmple(node.hi).all());
                    }
                }
            }
        }
        assert!(seen.iter().all(|&k| k == 1));
        assert_eq!(bvh.node_count(), 2 * leaves - 1);
        let mut stack = Vec::new();
        for k in 0..20 {
            let p = DVec3::new(
                0.05 * k as f64,
                1.0 - 0.045 * k as f64,
                0.2 - 0.02 * k as f64,
            );
            let brute = triangles
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|v| positions[v as usize]);
                    closest_point_on_triangle(p, a, b, c).distance_squared(p)
                })
                .fold(f64::INFINITY, f64::min);
            assert_eq!(
                bvh.nearest(p, None, &mut stack).map(|h| h.dist2),
                Some(brute)
            );
        }
    }

    #[test]
    fn nearest_matches_brute_force() {
        // The hierarchy must find exactly the brute-force minimum, with or without a hint.
        let (positions, triangles) = bumpy_grid(40);
        let bvh = Bvh::new(&positions, &triangles);
        let mut stack = Vec::new();
        let mut state = 12345u64;
        let mut rnd = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut hint = None;
        for _ in 0..500 {
            let p = DVec3::new(1.4 * rnd() - 0.2, 1.4 * rnd() - 0.2, 0.6 * rnd() - 0.3);
            let brute = triangles
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|v| positions[v as usize]);
                    closest_point_on_triangle(p, a, b, c).distance_squared(p)
                })
                .fold(f64::INFINITY, f64::min);
            let hit = bvh.nearest(p, hint, &mut stack).map(|h| h.dist2);
            assert_eq!(hit, Some(brute));
            hint = bvh.nearest(p, None, &mut stack).map(|h| h.triangle);
        }
    }

    #[test]
    fn nearest_where_matches_brute_force() {
        // The nearest accepted triangle within the bound, exactly as a scan of all finds it;
        // none when no accepted triangle is that near.
        let (positions, triangles) = bumpy_grid(30);
        let bvh = Bvh::new(&positions, &triangles);
        let mut stack = Vec::new();
        let accept = |id: u32, _| id % 7 == 3;
        for i in 0..200 {
            let t = i as f64 / 200.0;
            let p = DVec3::new(1.3 * t - 0.15, (17.0 * t).fract(), 0.4 * (11.0 * t).sin());
            let brute = triangles
                .iter()
                .enumerate()
                .filter(|&(id, _)| id % 7 == 3)
                .map(|(_, t)| {
                    let [a, b, c] = t.map(|v| positions[v as usize]);
                    closest_point_on_triangle(p, a, b, c).distance_squared(p)
                })
                .fold(f64::INFINITY, f64::min);
            let max2 = 0.01 * (i % 5) as f64;
            let found = bvh.nearest_where(p, max2, usize::MAX, accept, &mut stack);
            let expected = (brute <= max2).then_some(brute);
            assert_eq!(found.map(|h| h.dist2), expected);
            assert!(found.is_none_or(|h| h.triangle % 7 == 3));
            // A budget of a few triangles tested gives an accepted one or none, never nearer.
            let few = bvh.nearest_where(p, f64::INFINITY, 8, accept, &mut stack);
            assert!(few.is_none_or(|h| h.triangle % 7 == 3 && h.dist2 >= brute));
        }
    }
}

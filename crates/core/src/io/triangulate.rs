//! Polygon triangulation for faces of any size, concave ones included, in near-linear time.
//!
//! A polygon is projected onto its best-fit plane (the Newell normal picks the plane and its
//! orientation), then cut by ear clipping. The triangles keep the polygon's own winding, so a
//! counter-clockwise face gives counter-clockwise triangles, and a polygon of n corners gives
//! n − 2 triangles. Convex polygons take a fan fast path, polygons monotone along x or y a
//! linear stack walk. Otherwise the reflex corners (the only ones that can lie inside an
//! ear) are kept in a 2-d tree, so an ear test visits only those near the ear instead of
//! the whole ring, and the walk clips every other corner per turn, so ears stay small. Degenerate or self-intersecting polygons still
//! terminate in near-linear time: when a full turn finds no ear, convex corners are clipped
//! without the containment test until half the ring is gone.

use glam::{DVec2, Vec3};

/// The Newell normal of a polygon (not normalised; zero for a degenerate polygon). Its length
/// is twice the polygon's area.
pub fn newell_normal(pts: &[Vec3]) -> Vec3 {
    let mut n = Vec3::ZERO;
    for (i, &a) in pts.iter().enumerate() {
        let b = pts[(i + 1) % pts.len()];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    n
}

/// Buffers reused across polygons to avoid allocating per face.
#[derive(Default)]
pub struct EarBuffers {
    flat: Vec<DVec2>,
    prev: Vec<usize>,
    next: Vec<usize>,
    removed: Vec<bool>,
    /// The reflex corners, for the ear test.
    reflex: ReflexTree,
    /// A monotone polygon's corners in sweep order.
    order: Vec<u32>,
}

/// Twice the signed area of triangle (o, a, b); positive when it turns left. The corners
/// come from `f32` coordinates, so the differences and products are exact in `f64` and the
/// sign is exact too.
fn cross(o: DVec2, a: DVec2, b: DVec2) -> f64 {
    (a - o).perp_dot(b - o)
}

fn inside(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0
}

/// Corners per leaf of [`ReflexTree`].
const LEAF: usize = 8;

/// The reflex corners in a static 2-d tree: `corners` reordered so that every node's are
/// one range, halved at the middle along its box's longer side; `boxes` holds each node's
/// box, children of node i at 2i + 1 and 2i + 2. An ear test descends only into the nodes
/// whose box meets the ear itself, not just its bounding box: a long thin ear (a star's
/// spike) then visits a few nodes, where a grid or a Z-order range would scan its whole box.
#[derive(Default)]
struct ReflexTree {
    corners: Vec<u32>,
    boxes: Vec<(DVec2, DVec2)>,
}

impl ReflexTree {
    fn build(&mut self, flat: &[DVec2], corners: impl Iterator<Item = u32>) {
        self.corners.clear();
        self.corners.extend(corners);
        self.boxes.clear();
        self.build_node(flat, 0, 0, self.corners.len());
    }

    fn build_node(&mut self, flat: &[DVec2], node: usize, lo: usize, hi: usize) {
        let (min, max) = self.corners[lo..hi].iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(min, max), &j| (min.min(flat[j as usize]), max.max(flat[j as usize])),
        );
        if node >= self.boxes.len() {
            self.boxes.resize(node + 1, (DVec2::ZERO, DVec2::ZERO));
        }
        self.boxes[node] = (min, max);
        if hi - lo <= LEAF {
            return;
        }
        let mid = (lo + hi) / 2;
        let axis = usize::from(max.y - min.y > max.x - min.x);
        self.corners[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
            flat[a as usize][axis].total_cmp(&flat[b as usize][axis])
        });
        self.build_node(flat, 2 * node + 1, lo, mid);
        self.build_node(flat, 2 * node + 2, mid, hi);
    }
}

/// Whether box `min`..`max` meets triangle (a, b, c), wound positively: the boxes overlap
/// and no edge of the triangle has the whole box strictly outside it.
fn box_meets_triangle(min: DVec2, max: DVec2, [a, b, c]: [DVec2; 3]) -> bool {
    let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
    if max.x < lo.x || min.x > hi.x || max.y < lo.y || min.y > hi.y {
        return false;
    }
    let corners = [min, DVec2::new(max.x, min.y), max, DVec2::new(min.x, max.y)];
    [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(p, q)| corners.iter().any(|&k| cross(p, q, k) >= 0.0))
}

/// Appends the fan (0, i, i + 1) of an `n`-gon: exact for convex polygons, and as good as
/// anything for degenerate ones.
fn fan(n: usize, out: &mut Vec<[u32; 3]>) {
    out.extend((1..n as u32 - 1).map(|i| [0, i, i + 1]));
}

/// Triangulates polygon `pts` (in order), appending n − 2 index triples into `pts` to `out`.
/// Polygons with fewer than three corners give nothing.
pub fn triangulate(pts: &[Vec3], out: &mut Vec<[u32; 3]>, scratch: &mut EarBuffers) {
    let n = pts.len();
    if n < 3 {
        return;
    }
    if n == 3 {
        out.push([0, 1, 2]);
        return;
    }
    let normal = newell_normal(pts);
    let a = normal.abs();
    if !a.is_finite() || a.max_element() <= 0.0 || pts.iter().any(|p| !p.is_finite()) {
        fan(n, out);
        return;
    }
    // Drop the dominant axis.
    let (u, v) = if a.z >= a.x && a.z >= a.y {
        (0, 1)
    } else if a.x >= a.y {
        (1, 2)
    } else {
        (2, 0)
    };
    let flat = &mut scratch.flat;
    flat.clear();
    flat.extend(
        pts.iter()
            .map(|p| DVec2::new(f64::from(p[u]), f64::from(p[v]))),
    );
    // Make the polygon wind positively in 2D (negating y is exact).
    let area2: f64 = (0..n).map(|i| flat[i].perp_dot(flat[(i + 1) % n])).sum();
    if area2 < 0.0 {
        flat.iter_mut().for_each(|p| p.y = -p.y);
    }
    // Convex fast path: every turn is left (or straight).
    let convex = (0..n).all(|i| cross(flat[i], flat[(i + 1) % n], flat[(i + 2) % n]) >= 0.0);
    if convex {
        fan(n, out);
        return;
    }
    if triangulate_monotone(&scratch.flat, out, &mut scratch.order) {
        return;
    }
    clip_ears(scratch, out);
}

/// Triangulates `flat` (wound positively) in linear time when it is monotone along x
/// (vertices compared by x, then y), or along y; false (nothing appended) when it is
/// neither. The stack walk of de Berg et al., "Computational Geometry", § 3.3.
fn triangulate_monotone(flat: &[DVec2], out: &mut Vec<[u32; 3]>, order: &mut Vec<u32>) -> bool {
    // Along y: rotated a quarter turn, which keeps the winding.
    let along_y = |p: DVec2| DVec2::new(p.y, -p.x);
    monotone_along(flat, |p| p, out, order) || monotone_along(flat, along_y, out, order)
}

/// [`triangulate_monotone`] along the x axis of `frame(p)`.
fn monotone_along(
    flat: &[DVec2],
    frame: impl Fn(DVec2) -> DVec2,
    out: &mut Vec<[u32; 3]>,
    order: &mut Vec<u32>,
) -> bool {
    let n = flat.len();
    let at = |i: usize| frame(flat[i % n]);
    let before = |a: DVec2, b: DVec2| a.x < b.x || (a.x == b.x && a.y < b.y);
    let (mut first, mut last) = (0, 0);
    for i in 1..n {
        if before(at(i), at(first)) {
            first = i;
        }
        if before(at(last), at(i)) {
            last = i;
        }
    }
    // The lower chain runs forward from `first` to `last`, the upper one on back to `first`.
    let lower = (last + n - first) % n;
    let increasing = (0..lower).all(|k| before(at(first + k), at(first + k + 1)));
    let decreasing = (0..n - lower).all(|k| before(at(last + k + 1), at(last + k)));
    if !increasing || !decreasing {
        return false;
    }
    // A vertex is on the upper chain when its index is past `last` going forward from
    // `first`.
    merge_chains(n, (first, last, lower), |l, u| before(at(l), at(u)), order);
    let upper = |i: u32| (i as usize + n - first) % n > lower;
    let mut emit = |a: u32, b: u32, c: u32| {
        let t = if cross(flat[a as usize], flat[b as usize], flat[c as usize]) < 0.0 {
            [a, c, b]
        } else {
            [a, b, c]
        };
        out.push(t);
    };
    let mut stack: Vec<u32> = vec![order[0], order[1]];
    for &v in &order[2..n - 1] {
        let top = stack[stack.len() - 1];
        if upper(v) != upper(top) {
            // Across the polygon: v sees every vertex on the stack.
            for w in stack.windows(2) {
                emit(v, w[0], w[1]);
            }
            stack.clear();
            stack.extend([top, v]);
        } else {
            let mut popped = top;
            stack.pop();
            while let Some(&t) = stack.last() {
                let turn = cross(at(t as usize), at(popped as usize), at(v as usize));
                let inside = if upper(v) { turn < 0.0 } else { turn > 0.0 };
                if !inside {
                    break;
                }
                emit(v, popped, t);
                popped = t;
                stack.pop();
            }
            stack.extend([popped, v]);
        }
    }
    let end = order[n - 1];
    for w in stack.windows(2) {
        emit(end, w[0], w[1]);
    }
    true
}

/// Merges a monotone polygon's lower chain (`first` forward to `last`, `lower` edges) and
/// upper chain (on back to `first`) into one sweep order in `order`; `before(l, u)` says
/// whether corner `l` comes before corner `u` along the sweep.
fn merge_chains(
    n: usize,
    (first, last, lower): (usize, usize, usize),
    before: impl Fn(usize, usize) -> bool,
    order: &mut Vec<u32>,
) {
    order.clear();
    let (mut lo, mut up) = (1, 1);
    order.push(first as u32);
    while lo < lower || up < n - lower {
        let l = (first + lo) % n;
        let u = (first + n - up) % n;
        if up >= n - lower || (lo < lower && before(l, u)) {
            order.push(l as u32);
            lo += 1;
        } else {
            order.push(u as u32);
            up += 1;
        }
    }
    order.push(last as u32);
}

/// Ear clipping of `scratch.flat` (wound positively) over a doubly linked ring of corners.
fn clip_ears(scratch: &mut EarBuffers, out: &mut Vec<[u32; 3]>) {
    let EarBuffers {
        flat,
        prev,
        next,
        removed,
        reflex,
        ..
    } = scratch;
    let flat = &flat[..];
    let n = flat.len();
    prev.clear();
    next.clear();
    removed.clear();
    prev.extend((0..n).map(|i| (i + n - 1) % n));
    next.extend((0..n).map(|i| (i + 1) % n));
    removed.resize(n, false);
    let is_reflex = |prev: &[usize], next: &[usize], j: usize| {
        cross(flat[prev[j]], flat[j], flat[next[j]]) <= 0.0
    };
    reflex.build(
        flat,
        (0..n as u32).filter(|&j| is_reflex(prev, next, j as usize)),
    );

    let mut count = n;
    let mut cur = 0;
    let mut misses = 0;
    // While `count` is above this, ears are clipped without the containment test.
    let mut relaxed_down_to = n;
    // The ring's size when the reflex list was last compacted.
    let mut compacted_at = n;
    while count > 3 {
        let (p, q) = (prev[cur], next[cur]);
        let (a, b, c) = (flat[p], flat[cur], flat[q]);
        let strict = count <= relaxed_down_to;
        let is_ear = cross(a, b, c) > 0.0
            && !(strict && blocked([p, cur, q], flat, prev, next, removed, reflex));
        if !is_ear {
            misses += 1;
            if misses < count {
                cur = q;
                continue;
            }
            misses = 0;
            if strict {
                // A full turn without an ear: not a simple polygon. Clip convex corners
                // without the containment test until half the ring is gone.
                relaxed_down_to = count / 2;
                cur = q;
                continue;
            }
            // Not even a convex corner in a full turn: clip this one so the loop ends.
        }
        out.push([p as u32, cur as u32, q as u32]);
        next[p] = q;
        prev[q] = p;
        removed[cur] = true;
        count -= 1;
        misses = 0;
        // Skip a corner: one turn clips every other corner, so ears stay small.
        cur = next[q];
        if count <= compacted_at / 2 {
            compacted_at = count;
            let live = reflex.corners.clone();
            let live = live
                .into_iter()
                .filter(|&j| !removed[j as usize] && is_reflex(prev, next, j as usize));
            reflex.build(flat, live);
        }
    }
    out.push([prev[cur] as u32, cur as u32, next[cur] as u32]);
}

/// True when a reflex corner other than the ear's own lies inside ear `corners` (corners at
/// the same place as the ear's, as at the bridges between an outline and a hole, do not
/// block it). Visits only the tree's nodes whose boxes meet the ear.
fn blocked(
    corners: [usize; 3],
    flat: &[DVec2],
    prev: &[usize],
    next: &[usize],
    removed: &[bool],
    reflex: &ReflexTree,
) -> bool {
    let ear = corners.map(|i| flat[i]);
    let [a, b, c] = ear;
    if reflex.corners.is_empty() {
        return false;
    }
    // Depth-first; a tree over u32 corners is under 32 levels deep, so this never fills.
    let mut stack = [(0u32, 0u32, 0u32); 64];
    stack[0] = (0, 0, reflex.corners.len() as u32);
    let mut top = 1;
    while top > 0 {
        top -= 1;
        let (node, lo, hi) = stack[top];
        let (min, max) = reflex.boxes[node as usize];
        if !box_meets_triangle(min, max, ear) {
            continue;
        }
        if (hi - lo) as usize > LEAF {
            let mid = (lo + hi) / 2;
            stack[top] = (2 * node + 1, lo, mid);
            stack[top + 1] = (2 * node + 2, mid, hi);
            top += 2;
            continue;
        }
        for &j in &reflex.corners[lo as usize..hi as usize] {
            let j = j as usize;
            let s = flat[j];
            if removed[j] || corners.contains(&j) || s == a || s == b || s == c {
                continue;
            }
            if cross(flat[prev[j]], s, flat[next[j]]) <= 0.0 && inside(s, a, b, c) {
                return true;
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(pts: &[Vec3], tris: &[[u32; 3]], normal: Vec3) -> f32 {
        tris.iter()
            .map(|t| {
                let (a, b, c) = (pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]);
                (b - a).cross(c - a).dot(normal) * 0.5
            })
            .sum()
    }

    /// Checks that `pts` (in the z = 0 plane, counter-clockwise) cut into n − 2 triangles,
    /// none clockwise and with areas summing to the polygon's: so none overlap.
    fn assert_exact_cover(pts: &[Vec3]) {
        let mut out = Vec::new();
        triangulate(pts, &mut out, &mut EarBuffers::default());
        assert_eq!(out.len(), pts.len() - 2);
        let p = |i: u32| DVec2::new(f64::from(pts[i as usize].x), f64::from(pts[i as usize].y));
        let mut sum = 0.0;
        for t in &out {
            let a = cross(p(t[0]), p(t[1]), p(t[2]));
            assert!(a >= 0.0, "triangle {t:?} is clockwise ({a})");
            sum += a;
        }
        let n = pts.len() as u32;
        let polygon: f64 = (0..n).map(|i| p(i).perp_dot(p((i + 1) % n))).sum();
        assert!(
            (sum - polygon).abs() <= 1e-9 * polygon,
            "triangles cover {sum}, the polygon {polygon}"
        );
    }

    #[test]
    fn l_shape_gives_four_ccw_triangles_of_the_right_area() {
        let pts: Vec<Vec3> = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
            .iter()
            .map(|&(x, y)| Vec3::new(x, y, 0.0))
            .collect();
        let mut out = Vec::new();
        triangulate(&pts, &mut out, &mut EarBuffers::default());
        assert_eq!(out.len(), 4);
        for t in &out {
            let (a, b, c) = (pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]);
            assert!(
                (b - a).cross(c - a).z > 0.0,
                "triangle {t:?} is not counter-clockwise"
            );
        }
        assert!((area(&pts, &out, Vec3::Z) - 3.0).abs() < 1e-6);
    }

    #[test]
    fn clockwise_polygon_in_a_tilted_plane_keeps_its_winding() {
        // An L in the y-z plane, wound clockwise when seen from +x.
        let pts: Vec<Vec3> = [(0., 0.), (0., 2.), (1., 2.), (1., 1.), (2., 1.), (2., 0.)]
            .iter()
            .map(|&(y, z)| Vec3::new(0.0, y, z))
            .collect();
        let n = newell_normal(&pts).normalize();
        assert!(n.x < -0.99);
        let mut out = Vec::new();
        triangulate(&pts, &mut out, &mut EarBuffers::default());
        assert_eq!(out.len(), 4);
        assert!((area(&pts, &out, n) - 3.0).abs() < 1e-6);
        for t in &out {
            let (a, b, c) = (pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]);
            assert!((b - a).cross(c - a).dot(n) > 0.0);
        }
    }

    #[test]
    fn degenerate_polygons_terminate() {
        let line: Vec<Vec3> = (0..5).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
        let mut out = Vec::new();
        triangulate(&line, &mut out, &mut EarBuffers::default());
        assert_eq!(out.len(), 3);
        // A bow-tie (self-intersecting).
        let bow = [
            Vec3::new(0., 0., 0.),
            Vec3::new(1., 1., 0.),
            Vec3::new(1., 0., 0.),
            Vec3::new(0., 1., 0.),
            Vec3::new(0.5, 2., 0.),
        ];
        out.clear();
        triangulate(&bow, &mut out, &mut EarBuffers::default());
        assert_eq!(out.len(), 3);
    }

    #[test]
    fn a_circle_of_100000_corners_is_covered_exactly() {
        // In f32 the corners wiggle off the circle, so this takes the ear-clipping path.
        let n = 100_000;
        let pts: Vec<Vec3> = (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                Vec3::new(t.cos() as f32, t.sin() as f32, 0.0)
            })
            .collect();
        assert_exact_cover(&pts);
    }

    #[test]
    fn a_star_of_100000_corners_is_covered_exactly() {
        let n = 100_000;
        let pts: Vec<Vec3> = (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                let r = if i % 2 == 0 { 1.0 } else { 0.6 };
                Vec3::new((r * t.cos()) as f32, (r * t.sin()) as f32, 0.0)
            })
            .collect();
        assert_exact_cover(&pts);
    }

    #[test]
    fn a_comb_of_20000_teeth_is_covered_exactly() {
        // Teeth of width 1 and height 10 on a base: every valley corner is reflex.
        let teeth = 20_000;
        let mut pts = vec![Vec3::new(teeth as f32 * 2.0, -1.0, 0.0)];
        for k in (0..teeth).rev() {
            let x = k as f32 * 2.0;
            pts.extend([
                Vec3::new(x + 2.0, 0.0, 0.0),
                Vec3::new(x + 1.0, 10.0, 0.0),
                Vec3::new(x + 1.0, 0.0, 0.0),
            ]);
        }
        pts.push(Vec3::new(0.0, -1.0, 0.0));
        assert_exact_cover(&pts);
    }

    #[test]
    fn a_square_with_a_bridged_hole_is_covered_exactly() {
        // Outline, then a bridge into a clockwise hole and back along the same edge.
        let xy = [
            (0., 0.),
            (4., 0.),
            (4., 4.),
            (0., 4.),
            (0., 0.),
            (1., 1.),
            (1., 3.),
            (3., 3.),
            (3., 1.),
            (1., 1.),
        ];
        let pts: Vec<Vec3> = xy.iter().map(|&(x, y)| Vec3::new(x, y, 0.0)).collect();
        assert_exact_cover(&pts);
    }
}

//! Polygon triangulation for faces of any size, concave ones included.
//!
//! A polygon is projected onto its best-fit plane (the Newell normal picks the plane and its
//! orientation), then cut by ear clipping. The triangles keep the polygon's own winding, so a
//! counter-clockwise face gives counter-clockwise triangles. Convex polygons take a fan fast
//! path; degenerate or self-intersecting ones still terminate, clipping the most convex
//! corner when no proper ear exists.

use glam::{Vec2, Vec3};

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

/// EarBuffers buffers reused across polygons to avoid allocating per face.
#[derive(Default)]
pub struct EarBuffers {
    flat: Vec<Vec2>,
    prev: Vec<usize>,
    next: Vec<usize>,
}

fn cross(o: Vec2, a: Vec2, b: Vec2) -> f32 {
    (a - o).perp_dot(b - o)
}

fn inside(p: Vec2, a: Vec2, b: Vec2, c: Vec2) -> bool {
    cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0
}

/// Triangulates polygon `pts` (in order), appending index triples into `pts` to `out`.
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
    if a.max_element().is_nan() || a.max_element() <= 0.0 {
        // Degenerate (all corners on a line or a point): a fan is as good as anything.
        for i in 1..n - 1 {
            out.push([0, i as u32, i as u32 + 1]);
        }
        return;
    }
    // Drop the dominant axis; order the other two so the polygon winds positively in 2D.
    let (u, v) = if a.z >= a.x && a.z >= a.y {
        if normal.z > 0.0 {
            (0, 1)
        } else {
            (1, 0)
        }
    } else if a.x >= a.y {
        if normal.x > 0.0 {
            (1, 2)
        } else {
            (2, 1)
        }
    } else if normal.y > 0.0 {
        (2, 0)
    } else {
        (0, 2)
    };
    let flat = &mut scratch.flat;
    flat.clear();
    flat.extend(pts.iter().map(|p| Vec2::new(p[u], p[v])));

    // Convex fast path: every turn is left (or straight).
    let convex = (0..n).all(|i| cross(flat[i], flat[(i + 1) % n], flat[(i + 2) % n]) >= 0.0);
    if convex {
        for i in 1..n - 1 {
            out.push([0, i as u32, i as u32 + 1]);
        }
        return;
    }

    // Ear clipping over a doubly linked ring of corners.
    let prev = &mut scratch.prev;
    let next = &mut scratch.next;
    prev.clear();
    next.clear();
    prev.extend((0..n).map(|i| (i + n - 1) % n));
    next.extend((0..n).map(|i| (i + 1) % n));
    let turn =
        |prev: &[usize], next: &[usize], i: usize| cross(flat[prev[i]], flat[i], flat[next[i]]);
    let mut count = n;
    let mut cur = 0;
    let mut misses = 0;
    while count > 3 {
        let (p, q) = (prev[cur], next[cur]);
        let (a, b, c) = (flat[p], flat[cur], flat[q]);
        let mut is_ear = cross(a, b, c) > 0.0;
        if is_ear {
            let mut j = next[q];
            while j != p {
                let s = flat[j];
                // Only reflex corners can lie inside an ear; corners coinciding with the
                // ear's own (bridges between outline and hole) do not block it.
                if turn(prev, next, j) <= 0.0 && s != a && s != b && s != c && inside(s, a, b, c) {
                    is_ear = false;
                    break;
                }
                j = next[j];
            }
        }
        if !is_ear && misses < count {
            misses += 1;
            cur = q;
            continue;
        }
        if !is_ear {
            // No ear in a full turn (self-intersecting or degenerate): clip the most convex
            // corner so the loop always ends.
            let mut best = cur;
            let mut best_turn = f32::NEG_INFINITY;
            let mut j = cur;
            for _ in 0..count {
                let t = turn(prev, next, j);
                if t > best_turn {
                    best_turn = t;
                    best = j;
                }
                j = next[j];
            }
            cur = best;
        }
        let (p, q) = (prev[cur], next[cur]);
        out.push([p as u32, cur as u32, q as u32]);
        next[p] = q;
        prev[q] = p;
        count -= 1;
        misses = 0;
        cur = p;
    }
    out.push([prev[cur] as u32, cur as u32, next[cur] as u32]);
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
}

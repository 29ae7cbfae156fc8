//! Hole filling by recursive loop splitting (Schroeder, Zarge, Lorensen 1992, §3.3).
//!
//! The loop of vertices left around a removed vertex is split in two by a "split line"
//! between two non-neighbouring loop vertices. The split plane contains that line and is
//! orthogonal to the loop's average plane; a split is valid only when the two sub-loops lie
//! strictly on opposite sides of it. Among valid splits the one with the best aspect ratio
//! (smallest distance of a sub-loop vertex to the plane over the split line's length) wins,
//! and each half is split again until only triangles are left. When no valid split exists the
//! hole cannot be filled and the vertex is kept.

use glam::{DVec3, Vec3};

/// Smallest aspect ratio accepted for a split: the halves must be clearly separated.
const MIN_ASPECT: f64 = 1e-7;

/// Buffers a triangulation works in, kept from one to the next: no allocation per hole.
#[derive(Debug, Clone, Default)]
pub struct SplitBuffers {
    /// The sub-loops, each a range of `buf`.
    buf: Vec<u32>,
    pending: Vec<(usize, usize)>,
    /// The positions of the loop being split.
    points: Vec<DVec3>,
}

/// Triangulates the polygon `loop_verts` (counter-clockwise around `normal`), appending
/// triangles in loop order (so they keep its orientation) to `out`. Returns false when some
/// sub-loop has no valid split; `out` may then hold a partial result the caller discards.
pub fn triangulate(
    positions: &[Vec3],
    loop_verts: &[u32],
    normal: DVec3,
    out: &mut Vec<[u32; 3]>,
    scratch: &mut SplitBuffers,
) -> bool {
    // Sub-loops pending a split, as ranges of one buffer: no allocation per sub-loop.
    let SplitBuffers {
        buf,
        pending,
        points,
    } = scratch;
    buf.clear();
    pending.clear();
    buf.extend_from_slice(loop_verts);
    pending.push((0, loop_verts.len()));
    while let Some((start, end)) = pending.pop() {
        let n = end - start;
        if n < 3 {
            continue;
        }
        if n == 3 {
            out.push([buf[start], buf[start + 1], buf[start + 2]]);
            continue;
        }
        let Some((i, j)) = best_split(positions, &buf[start..end], normal, points) else {
            return false;
        };
        let (i, j) = (start + i, start + j);
        let first = buf.len();
        buf.extend_from_within(i..=j);
        pending.push((first, buf.len()));
        let second = buf.len();
        buf.extend_from_within(j..end);
        buf.extend_from_within(start..=i);
        pending.push((second, buf.len()));
    }
    true
}

/// The split `(i, j)`, `i < j`, with the best aspect ratio, if any is valid. A candidate is
/// abandoned as soon as its aspect can no longer beat the best so far (the aspect only falls
/// as more vertices are measured), so the result is that of the full search, which is cubic
/// in the loop's length, at a fraction of its cost on large loops.
fn best_split(
    positions: &[Vec3],
    lp: &[u32],
    normal: DVec3,
    points: &mut Vec<DVec3>,
) -> Option<(usize, usize)> {
    let n = lp.len();
    points.clear();
    points.extend(lp.iter().map(|&v| positions[v as usize].as_dvec3()));
    let p = |k: usize| points[k];
    let mut best: Option<(f64, usize, usize)> = None;
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue; // neighbours around the loop
            }
            let (a, b) = (p(i), p(j));
            let dir = b - a;
            let len = dir.length();
            let m = dir.cross(normal);
            let m_len = m.length();
            if len <= 0.0 || m_len <= 0.0 {
                continue;
            }
            let m = m / m_len;
            let bar = best.map_or(MIN_ASPECT, |(b, _, _)| b.max(MIN_ASPECT));
            // Vertices strictly between i and j go on one side, the rest on the other.
            let mut min_dist = f64::INFINITY;
            let mut ok = true;
            for k in (0..n).filter(|&k| k != i && k != j) {
                let s = m.dot(p(k) - a);
                let inside = k > i && k < j;
                // Counter-clockwise loops put the i..j run on the positive side of m.
                let signed = if inside { s } else { -s };
                if signed <= 0.0 {
                    ok = false;
                    break;
                }
                if signed < min_dist {
                    min_dist = signed;
                    if min_dist / len <= bar {
                        ok = false; // valid or not, it cannot win
                        break;
                    }
                }
            }
            if !ok {
                continue;
            }
            let aspect = min_dist / len;
            if aspect > MIN_ASPECT && best.is_none_or(|(b, _, _)| aspect > b) {
                best = Some((aspect, i, j));
            }
        }
    }
    best.map(|(_, i, j)| (i, j))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The triangles filling loop `lp` over the xy plane, `None` when it cannot be split.
    fn fill(p: &[Vec3], lp: &[u32]) -> Option<Vec<[u32; 3]>> {
        let mut out = Vec::new();
        triangulate(p, lp, DVec3::Z, &mut out, &mut SplitBuffers::default()).then_some(out)
    }

    fn area_z(p: &[Vec3], tris: &[[u32; 3]]) -> f64 {
        tris.iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| p[i as usize].as_dvec3());
                (b - a).cross(c - a).z / 2.0
            })
            .sum()
    }

    #[test]
    fn convex_hexagon_gives_four_counter_clockwise_triangles() {
        let p: Vec<Vec3> = (0..6)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / 6.0;
                Vec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let out = fill(&p, &[0, 1, 2, 3, 4, 5]).unwrap_or_default();
        assert_eq!(out.len(), 4);
        let expected = 6.0 * 3f64.sqrt() / 4.0;
        assert!((area_z(&p, &out) - expected).abs() < 1e-6);
        assert!(out.iter().all(|t| area_z(&p, &[*t]) > 0.0));
    }

    //  4-------3
    //  |       |
    //  |   1---2      an L shape: a split from 0 to 2 or 3 would cross the notch
    //  |   |
    //  5---0
    #[test]
    fn l_shape_is_filled_without_overlap() {
        let p = vec![
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
        ];
        let out = fill(&p, &[0, 1, 2, 3, 4, 5]).unwrap_or_default();
        assert_eq!(out.len(), 4);
        assert!((area_z(&p, &out) - 3.0).abs() < 1e-12);
        assert!(out.iter().all(|t| area_z(&p, &[*t]) > 0.0));
    }

    #[test]
    fn collinear_loop_cannot_be_split() {
        let p: Vec<Vec3> = (0..4).map(|k| Vec3::new(k as f32, 0.0, 0.0)).collect();
        assert!(fill(&p, &[0, 1, 2, 3]).is_none());
    }
}

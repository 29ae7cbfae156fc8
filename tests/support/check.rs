//! The geometric checks the random and fuzz tests run on every decimated model, against
//! the model it came from (same coordinates): indices in range, no output triangle turned
//! more than a right angle from the input surface it stands for, closed parts keeping the
//! sign of their volume, and every output vertex near the input surface. Nearest input
//! triangles are found through a uniform grid, so that a check costs about the output's
//! size times a few cells.

use std::collections::HashMap;

use decimate_core::mesh::Model;
use glam::DVec3;

/// What one model's checks found; `Default` is "nothing checked".
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct Findings {
    /// Output triangles compared with the input surface.
    pub triangles_checked: usize,
    /// Of those, turned more than 90° from every nearest input triangle.
    pub folds: usize,
    /// Closed output parts whose volume sign was compared with the input's.
    pub closed_checked: usize,
    /// Of those, with the other sign.
    pub inverted: usize,
    /// The farthest output vertex's distance to the input surface, over the input's
    /// bounding-box diagonal.
    pub farthest: f64,
}

/// Triangle `t`'s unit normal (none for a degenerate one).
fn normal(m: &Model, t: u32) -> Option<DVec3> {
    let [a, b, c] = m.triangles[t as usize].map(|v| m.positions[v as usize].as_dvec3());
    (b - a).cross(c - a).try_normalize()
}

/// Output triangles referring to a point that does not exist, as a message (none: `Ok`).
pub fn index_range(m: &Model) -> Result<(), String> {
    let n = m.positions.len();
    match m.triangles.iter().flatten().find(|&&v| v as usize >= n) {
        Some(v) => Err(format!("{}: index {v} of {n} points", m.name)),
        None => Ok(()),
    }
}

/// Runs every geometric check of `after` against `before` (same coordinates). Returns
/// the default (nothing checked) where the input has no usable size: no triangle, or a
/// bounding box that is empty or not finite.
pub fn geometry(before: &Model, after: &Model) -> Findings {
    let Some(grid) = TriangleGrid::new(before) else {
        return Findings::default();
    };
    let mut found = Findings::default();
    let diag = grid.diag;
    let slack = 1e-3 * diag;
    let point = |m: &Model, v: u32| m.positions[v as usize].as_dvec3();
    let normals: Vec<Option<DVec3>> = (0..before.triangles.len() as u32)
        .map(|i| normal(before, i))
        .collect();
    // Each used output vertex's nearest input triangles, looked up once: for every
    // triangle at it and for its distance to the input.
    let mut at_vertex: Vec<Vec<(f64, u32)>> = vec![Vec::new(); after.positions.len()];
    for v in used_points(after) {
        at_vertex[v as usize] = grid.near(before, point(after, v), slack);
    }
    for t in &after.triangles {
        let [a, b, c] = t.map(|v| point(after, v));
        let cross = (b - a).cross(c - a);
        // Degenerate output triangles face no way; the algorithms keep none, and their
        // tests count them elsewhere.
        if cross.length() <= 1e-9 * diag * diag {
            continue;
        }
        found.triangles_checked += 1;
        // The input surface the triangle stands for: the input triangles nearest its
        // centre and nearest each of its corners (where a shape cut down to a few vertices
        // has triangles far inside, the centre's alone would say little).
        let unit = cross.normalize();
        let centre = grid.near(before, (a + b + c) / 3.0, slack);
        let facing = centre
            .iter()
            .chain(t.iter().flat_map(|&v| &at_vertex[v as usize]))
            .filter_map(|&(_, i)| normals[i as usize])
            .map(|n| n.dot(unit))
            .fold(f64::NEG_INFINITY, f64::max);
        if facing < -1e-9 {
            found.folds += 1;
        }
    }
    for list in &at_vertex {
        if let Some(d) = list.iter().map(|f| f.0).reduce(f64::min) {
            found.farthest = found.farthest.max(d / diag);
        }
    }
    let (checked, inverted) = volume_signs(before, after, diag);
    found.closed_checked = checked;
    found.inverted = inverted;
    found
}

/// The points some triangle uses.
fn used_points(m: &Model) -> Vec<u32> {
    let mut used = vec![false; m.positions.len()];
    for &v in m.triangles.iter().flatten() {
        if let Some(u) = used.get_mut(v as usize) {
            *u = true;
        }
    }
    (0..m.positions.len() as u32)
        .filter(|&v| used[v as usize])
        .collect()
}

/// Closed parts of `after` compared by volume sign with `before`'s, where every part of
/// `before` is closed and all of them share one sign: (compared, with the other sign).
fn volume_signs(before: &Model, after: &Model, diag: f64) -> (usize, usize) {
    let least = 1e-6 * diag * diag * diag;
    let parts_before = closed_part_volumes(before);
    if parts_before.iter().any(|v| v.is_none()) {
        return (0, 0);
    }
    let signs: Vec<f64> = parts_before
        .iter()
        .flatten()
        .filter(|v| v.abs() > least)
        .map(|v| v.signum())
        .collect();
    let Some(&sign) = signs.first() else {
        return (0, 0);
    };
    if signs.iter().any(|&s| s != sign) {
        return (0, 0);
    }
    let measured: Vec<f64> = closed_part_volumes(after)
        .into_iter()
        .flatten()
        .filter(|v| v.abs() > least)
        .collect();
    let inverted = measured.iter().filter(|v| v.signum() != sign).count();
    (measured.len(), inverted)
}

/// Each connected part's signed volume (six times, in f64) where the part is closed: every
/// edge used once each way. `None` for an open or non-manifold part.
fn closed_part_volumes(m: &Model) -> Vec<Option<f64>> {
    let n = m.positions.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (
                root(&mut parent, t[k] as usize),
                root(&mut parent, t[(k + 1) % 3] as usize),
            );
            parent[a] = b;
        }
    }
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    let mut parts: HashMap<usize, (f64, bool)> = HashMap::new();
    for t in &m.triangles {
        let [a, b, c] = t.map(|v| m.positions[v as usize].as_dvec3());
        let part = parts
            .entry(root(&mut parent, t[0] as usize))
            .or_insert((0.0, true));
        part.0 += a.dot(b.cross(c));
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    // Closed: each edge used once each way (a repeated corner is never closed).
    for (&(x, y), &count) in &directed {
        if x == y || count != 1 || directed.get(&(y, x)) != Some(&1) {
            let p = root(&mut parent, x as usize);
            if let Some(part) = parts.get_mut(&p) {
                part.1 = false;
            }
        }
    }
    parts
        .into_values()
        .map(|(volume, closed)| closed.then_some(volume))
        .collect()
}

/// The input's triangles bucketed by a uniform grid over its bounding box.
struct TriangleGrid {
    origin: DVec3,
    cell: f64,
    dims: [i64; 3],
    cells: HashMap<[i64; 3], Vec<u32>>,
    diag: f64,
}

impl TriangleGrid {
    fn new(m: &Model) -> Option<Self> {
        let corners = m
            .triangles
            .iter()
            .flatten()
            .map(|&v| m.positions[v as usize].as_dvec3());
        let (lo, hi) = corners.fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p), hi.max(p)),
        );
        let diag = (hi - lo).length();
        if !diag.is_finite() || diag <= 0.0 {
            return None;
        }
        // A surface fills about the square of the cells along an axis: a few triangles
        // a cell.
        let per_axis = (m.triangles.len() as f64).sqrt().clamp(1.0, 48.0);
        let cell = diag / per_axis;
        let dims = ((hi - lo) / cell)
            .ceil()
            .max(DVec3::ONE)
            .to_array()
            .map(|d| d as i64);
        let mut grid = Self {
            origin: lo,
            cell,
            dims,
            cells: HashMap::new(),
            diag,
        };
        for (i, t) in m.triangles.iter().enumerate() {
            let ps = t.map(|v| m.positions[v as usize].as_dvec3());
            let (a, b) = (ps[0].min(ps[1]).min(ps[2]), ps[0].max(ps[1]).max(ps[2]));
            let (a, b) = (grid.at(a), grid.at(b));
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        grid.cells.entry([x, y, z]).or_default().push(i as u32);
                    }
                }
            }
        }
        Some(grid)
    }

    /// The cell holding `p`, clamped into the grid.
    fn at(&self, p: DVec3) -> [i64; 3] {
        let q = ((p - self.origin) / self.cell).floor().to_array();
        [0, 1, 2].map(|k| (q[k] as i64).clamp(0, self.dims[k] - 1))
    }

    /// Every input triangle within `slack` of the nearest one to `p`, as (distance, index).
    fn near(&self, m: &Model, p: DVec3, slack: f64) -> Vec<(f64, u32)> {
        let centre = self.at(p);
        let mut found: Vec<(f64, u32)> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        let reach = self.dims.iter().max().copied().unwrap_or(1);
        for r in 0..=reach {
            let span = |k: usize| (centre[k] - r).max(0)..=(centre[k] + r).min(self.dims[k] - 1);
            for x in span(0) {
                for y in span(1) {
                    for z in span(2) {
                        let shell = [x - centre[0], y - centre[1], z - centre[2]]
                            .iter()
                            .any(|d| d.abs() == r);
                        let Some(list) = shell.then(|| self.cells.get(&[x, y, z])).flatten() else {
                            continue;
                        };
                        for &t in list {
                            if seen.insert(t) {
                                let ps = m.triangles[t as usize]
                                    .map(|v| m.positions[v as usize].as_dvec3());
                                found.push((point_triangle_distance(p, ps), t));
                            }
                        }
                    }
                }
            }
            let best = found.iter().map(|f| f.0).fold(f64::INFINITY, f64::min);
            // Anything not yet seen lies in a cell outside the searched cube: at least `r`
            // cells from `p`.
            if best + slack <= r as f64 * self.cell {
                break;
            }
        }
        let best = found.iter().map(|f| f.0).fold(f64::INFINITY, f64::min);
        found.retain(|f| f.0 <= best + slack);
        found
    }
}

/// The distance from `p` to the triangle `[a, b, c]` (its closest point by regions of the
/// plane: corner, edge or inside).
pub fn point_triangle_distance(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    if ab.cross(ac).length_squared() <= f64::EPSILON * ab.length_squared() * ac.length_squared() {
        // Degenerate (a segment or a point): the nearest of its sides.
        let side = |x: DVec3, y: DVec3| {
            let d = y - x;
            let t = if d.length_squared() > 0.0 {
                ((p - x).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (x + t * d)).length()
        };
        return side(a, b).min(side(b, c)).min(side(c, a));
    }
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (p - (a + v * ab)).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (p - (a + w * ac)).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + w * (c - b))).length();
    }
    let sum = va + vb + vc;
    let (v, w) = (vb / sum, vc / sum);
    (p - (a + ab * v + ac * w)).length()
}

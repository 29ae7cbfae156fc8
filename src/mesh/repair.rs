//! Repair of damaged input before decimation, with a count of everything changed: vertices
//! welded within a tolerance (`--weld-tolerance`), triangles with a repeated corner or no
//! area, duplicated triangles (the same three vertices, either way round), triangles
//! facing against their neighbours across manifold edges (flipped to the majority of their
//! connected surface), and vertices no triangle uses. Everything here is a sort or a walk
//! over the triangles: O(n log n) at worst.

use glam::DVec3;

use super::{weld, Attribute, Model};

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
    /// Triangles with a repeated corner or zero area (collinear corners), removed.
    pub degenerate: usize,
    /// Triangles on the same three vertices as an earlier one, removed.
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
    let mut keyed: Vec<([u32; 3], u32)> = model
        .triangles
        .iter()
        .enumerate()
        .filter(|&(i, _)| keep[i])
        .map(|(i, t)| {
            let mut k = *t;
            k.sort_unstable();
            (k, i as u32)
        })
        .collect();
    keyed.sort_unstable();
    for w in keyed.windows(2) {
        if w[0].0 == w[1].0 {
            // Sorted by index within a run of equal keys: the first in the file stays.
            keep[w[1].1 as usize] = false;
            r.duplicates += 1;
        }
    }
    keep
}

/// Keeps the triangles marked in `keep`, with their per-face attributes.
fn retain_triangles(model: &mut Model, keep: &[bool]) {
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
/// orientation most of its triangles have wins. Returns how many were flipped.
pub fn orient_consistently(triangles: &mut [[u32; 3]]) -> usize {
    // Half-edges keyed by their undirected edge; a run of two is a manifold edge.
    let mut half: Vec<(u64, u32, bool)> = Vec::with_capacity(triangles.len() * 3);
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = u64::from(a.min(b)) << 32 | u64::from(a.max(b));
            half.push((key, t as u32, a < b));
        }
    }
    half.sort_unstable();
    // Each triangle's neighbours across manifold edges, and whether it runs the shared
    // edge the same way (one of the two must then flip).
    let mut adjacent: Vec<Vec<(u32, bool)>> = vec![Vec::new(); triangles.len()];
    let mut i = 0;
    while i < half.len() {
        let mut j = i + 1;
        while j < half.len() && half[j].0 == half[i].0 {
            j += 1;
        }
        if j - i == 2 {
            let ((_, s, ds), (_, t, dt)) = (half[i], half[i + 1]);
            if s != t {
                adjacent[s as usize].push((t, ds == dt));
                adjacent[t as usize].push((s, ds == dt));
            }
        }
        i = j;
    }
    // Breadth-first over each connected surface: flip[t] relative to the first triangle.
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
            for &(u, same) in &adjacent[t as usize] {
                if flip[u as usize].is_none() {
                    flip[u as usize] = Some(ft ^ same);
                    queue.push(u);
                }
            }
        }
        // A non-orientable surface (a Möbius strip) keeps the walk's choice.
        let ones = queue
            .iter()
            .filter(|&&t| flip[t as usize] == Some(true))
            .count();
        let invert = ones * 2 > queue.len();
        for &t in &queue {
            if (flip[t as usize] == Some(true)) != invert {
                triangles[t as usize].swap(1, 2);
                flipped += 1;
            }
        }
    }
    flipped
}

/// Removes the vertices no triangle uses, with their per-vertex attributes; returns how
/// many.
fn drop_unused_vertices(model: &mut Model) -> usize {
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
}

//! Whole-mesh measures a user notices: area, enclosed volume, edge manifoldness, boundary
//! loops, Euler characteristic, and triangles that are degenerate or oriented against their
//! neighbours. Used by tests and summaries.

use std::collections::HashMap;

use glam::DVec3;

use super::Model;

/// Edge statistics of a triangle mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EdgeCounts {
    /// Distinct undirected edges.
    pub edges: usize,
    /// Edges with exactly one triangle.
    pub boundary: usize,
    /// Edges with more than two triangles.
    pub non_manifold: usize,
    /// Edges whose two triangles traverse them in the same direction (inconsistent
    /// orientation: one of them is flipped).
    pub misoriented: usize,
}

fn positions(m: &Model) -> Vec<DVec3> {
    m.positions.iter().map(|p| p.as_dvec3()).collect()
}

/// Total surface area.
pub fn area(m: &Model) -> f64 {
    let p = positions(m);
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| p[i as usize]);
            (b - a).cross(c - a).length() / 2.0
        })
        .sum()
}

/// Signed enclosed volume (positive for a closed, outward-facing mesh).
pub fn volume(m: &Model) -> f64 {
    let p = positions(m);
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| p[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Counts edges by kind.
pub fn edge_counts(m: &Model) -> EdgeCounts {
    // (min, max) → (uses, uses in the min→max direction)
    let mut edges: HashMap<(u32, u32), (u32, u32)> = HashMap::with_capacity(m.triangles.len() * 2);
    for t in &m.triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let e = edges.entry((a.min(b), a.max(b))).or_default();
            e.0 += 1;
            e.1 += u32::from(a < b);
        }
    }
    let mut c = EdgeCounts {
        edges: edges.len(),
        ..EdgeCounts::default()
    };
    for &(uses, forward) in edges.values() {
        match uses {
            1 => c.boundary += 1,
            2 if forward != 1 => c.misoriented += 1,
            2 => {}
            _ => c.non_manifold += 1,
        }
    }
    c
}

/// Vertices on an edge of three or more triangles.
pub fn non_manifold_vertices(m: &Model) -> usize {
    let mut uses: HashMap<(u32, u32), u32> = HashMap::with_capacity(m.triangles.len() * 2);
    for t in &m.triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut on_one = vec![false; m.positions.len()];
    for (&(a, b), &n) in &uses {
        if n > 2 {
            for v in [a, b] {
                if let Some(flag) = on_one.get_mut(v as usize) {
                    *flag = true;
                }
            }
        }
    }
    on_one.iter().filter(|&&f| f).count()
}

/// Euler characteristic V − E + F over the vertices that triangles use.
pub fn euler_characteristic(m: &Model) -> i64 {
    m.used_vertex_count() as i64 - edge_counts(m).edges as i64 + m.triangles.len() as i64
}

/// Number of closed boundary loops (boundary edges chained end to end).
pub fn boundary_loops(m: &Model) -> usize {
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    // Union-find over the boundary edges' vertices: one component per loop.
    let mut parent: HashMap<u32, u32> = HashMap::new();
    fn find(parent: &mut HashMap<u32, u32>, x: u32) -> u32 {
        let p = *parent.entry(x).or_insert(x);
        if p == x {
            return x;
        }
        let r = find(parent, p);
        parent.insert(x, r);
        r
    }
    for (&(a, b), &n) in &uses {
        if n == 1 {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            parent.insert(ra, rb);
        }
    }
    let keys: Vec<u32> = parent.keys().copied().collect();
    let mut roots: Vec<u32> = keys.into_iter().map(|k| find(&mut parent, k)).collect();
    roots.sort_unstable();
    roots.dedup();
    roots.len()
}

/// Triangles whose area is below `relative` times their longest edge squared.
pub fn degenerate_triangles(m: &Model, relative: f64) -> usize {
    let p = positions(m);
    m.triangles
        .iter()
        .filter(|t| {
            let [a, b, c] = t.map(|i| p[i as usize]);
            let longest = (b - a)
                .length_squared()
                .max((c - b).length_squared())
                .max((a - c).length_squared());
            (b - a).cross(c - a).length() <= relative * longest
        })
        .count()
}

/// What a simplification of `before` into `after` broke, in words (empty when nothing):
/// a degenerate triangle, a non-manifold or misoriented (flipped) edge, a changed Euler
/// characteristic or number of boundary loops. The checks every algorithm's output must pass.
pub fn invariant_violations(before: &Model, after: &Model) -> Vec<String> {
    let mut broken = Vec::new();
    let degenerate = degenerate_triangles(after, 1e-9);
    if degenerate > 0 {
        broken.push(format!("{degenerate} degenerate triangles"));
    }
    let e = edge_counts(after);
    if e.non_manifold > 0 {
        broken.push(format!("{} non-manifold edges", e.non_manifold));
    }
    if e.misoriented > 0 {
        broken.push(format!("{} edges of flipped triangles", e.misoriented));
    }
    let (chi0, chi1) = (euler_characteristic(before), euler_characteristic(after));
    if chi0 != chi1 {
        broken.push(format!("Euler characteristic {chi0} -> {chi1}"));
    }
    let (loops0, loops1) = (boundary_loops(before), boundary_loops(after));
    if loops0 != loops1 {
        broken.push(format!("boundary loops {loops0} -> {loops1}"));
    }
    broken
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    #[test]
    fn report_models_have_the_reported_counts_and_are_clean() {
        let expected = shapes::REPORTED_COUNTS;
        assert_eq!(shapes::all().len(), expected.len());
        for (m, (v, t)) in shapes::all().iter().zip(expected) {
            assert_eq!((m.positions.len(), m.triangles.len()), (v, t), "{}", m.name);
            let e = edge_counts(m);
            assert_eq!((e.non_manifold, e.misoriented), (0, 0), "{}", m.name);
            assert_eq!(degenerate_triangles(m, 1e-9), 0, "{}", m.name);
        }
    }

    #[test]
    fn violations_name_what_broke() {
        let cube = shapes::test004();
        assert!(invariant_violations(&cube, &cube).is_empty());
        let mut flipped = cube.clone();
        flipped.triangles[0].swap(1, 2);
        let broken = invariant_violations(&cube, &flipped);
        assert_eq!(broken, vec!["3 edges of flipped triangles".to_string()]);
        let mut holed = cube.clone();
        holed.triangles.pop();
        let broken = invariant_violations(&cube, &holed);
        assert!(
            broken
                .iter()
                .any(|b| b.starts_with("boundary loops 0 -> 1")),
            "{broken:?}"
        );
    }

    #[test]
    fn measures_of_known_shapes() {
        let cube = shapes::test004();
        assert!((volume(&cube) - 1000.0).abs() < 1e-6);
        assert!((area(&cube) - 600.0).abs() < 1e-6);
        assert_eq!(euler_characteristic(&cube), 2);
        assert_eq!(boundary_loops(&cube), 0);
        let plane = shapes::test003();
        assert!((area(&plane) - 100.0).abs() < 1e-9);
        assert_eq!(boundary_loops(&plane), 1);
        assert_eq!(euler_characteristic(&plane), 1);
        let tube = shapes::test005();
        assert_eq!(euler_characteristic(&tube), 0);
        assert!(volume(&tube) > 0.0);
        assert!(volume(&shapes::test001()) > 0.0);
        assert!(volume(&shapes::test006()) > 0.0);
        // The washer: π (2² − 1²) × 0.4 before the noise and waves, which keep it closely.
        let washer = volume(&shapes::test007());
        assert!(
            (washer - 1.2 * std::f64::consts::PI).abs() < 0.05,
            "{washer}"
        );
        assert!((volume(&shapes::test008()) - 8.0).abs() < 1e-5);
    }
}

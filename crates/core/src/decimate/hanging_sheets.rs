//! Sheets hanging on the rest of a mesh by non-manifold edges or vertices, smaller than
//! the result's triangles, removed when quadric decimation meets a non-manifold vertex
//! (`qem::decimate_model_pruning`, so a clean mesh never pays for it): the flaps and tiny
//! closed pockets a reconstructed scan carries. A collapse cannot take a closed pocket away
//! (it needs four triangles) and a flap goes only once its foot has collapsed, so each
//! would hold several of the result's triangles for less area than one of them covers
//! (docs/design.md#hanging-sheets).
//!
//! A *sheet* is a set of triangles joined across edges that exactly two triangles use. It
//! *hangs* when it shares a vertex with another sheet (a separate part never hangs) and is
//! either a *pocket*, every edge of it used by exactly two of its own triangles, or a *flap*,
//! with a free rim (an edge no other triangle uses). A patch of the surface walled in by
//! non-manifold edges is neither, and stays: without it the surface would have a hole.
//! Edges are bucketed by vertex and sorted bucket by bucket: linear time.

use std::borrow::Cow;

use glam::DVec3;
use rayon::prelude::*;

use crate::mesh::{repair, union_find, weld, Attribute, Model};

/// The sheets removed never add up to more than this share of the model's area: where
/// small sheets are a real share of a model (cells or voxels sharing edges: tens of
/// percent), they are the model; a scan's debris (doubled fins, pockets) is a few percent
/// at most (docs/design.md#hanging-sheets).
const MAX_AREA_SHARE: f64 = 0.05;

/// A sheet goes when its bounding-box diagonal is at most this many times √a, `a` the mean
/// area a result triangle covers (about 0.26 of their edges): larger bounds moved the
/// surface further and left folded slivers at non-manifold edges
/// (docs/design.md#hanging-sheets).
const MAX_DIAGONAL: f64 = 0.4;

/// How small a sheet must be to go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SheetLimit {
    /// Triangles the result is to have: a sheet goes when its area is at most the mean
    /// area `a` one of them covers and its bounding-box diagonal at most `MAX_DIAGONAL` √a
    /// (`None`: no count target).
    pub result_triangles: Option<usize>,
    /// The error bound, in model units: a sheet goes only when its bounding-box diagonal
    /// (how far it reaches from the surface it hangs on) is within it.
    pub max_error: f64,
}

/// What [`remove_hanging_sheets`] removed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RemovedSheets {
    /// Sheets removed, pockets among them.
    pub sheets: usize,
    pub pockets: usize,
    pub triangles: usize,
    /// Vertices no triangle uses any more (left in the model for the decimator's compaction).
    pub vertices: usize,
    /// The largest bounding-box diagonal of a removed sheet: how far the surface moved.
    pub max_diagonal: f64,
}

/// One sheet's tally.
#[derive(Clone, Copy)]
struct Sheet {
    closed: bool,
    rim: bool,
    touches: bool,
    pinned: bool,
    area: f64,
    lo: DVec3,
    hi: DVec3,
}

/// Removes `model`'s hanging sheets within `limit` (none with a vertex flagged in `pinned`,
/// indexed like the positions); per-face attributes follow their triangles, vertices stay.
pub fn remove_hanging_sheets(
    model: &mut Model,
    limit: SheetLimit,
    pinned: &dyn Fn(u32) -> bool,
) -> RemovedSheets {
    let n = model.positions.len();
    if model.triangles.len() < 5 || model.triangles.iter().flatten().any(|&v| v as usize >= n) {
        return RemovedSheets::default();
    }
    let corners = point_corners(model);
    let edges = Edges::of(&corners, n);
    let (sheet_of, count) = sheets(model.triangles.len(), &edges);
    let Some(shared) = shared_vertices(&corners, &sheet_of, n) else {
        return RemovedSheets::default();
    };
    let mut sheet = vec![
        Sheet {
            closed: true,
            rim: false,
            touches: false,
            pinned: false,
            area: 0.0,
            lo: DVec3::splat(f64::INFINITY),
            hi: DVec3::splat(f64::NEG_INFINITY),
        };
        count
    ];
    mark_open_sheets(&edges, &sheet_of, &mut sheet);
    drop(edges);
    let total_area = measure_sheets(model, &corners, &sheet_of, &shared, pinned, &mut sheet);
    let max_area = limit
        .result_triangles
        .map_or(f64::INFINITY, |k| total_area / k.max(1) as f64);
    let goes: Vec<bool> = (sheet.iter())
        .map(|s| {
            s.touches
                && (s.closed || s.rim)
                && !s.pinned
                && s.area <= max_area
                && diagonal2(s) <= MAX_DIAGONAL * MAX_DIAGONAL * max_area
                && diagonal2(s) <= limit.max_error * limit.max_error
        })
        .collect();
    let goes = keep_whole_parts(&corners, &sheet_of, (n, count), goes);
    let removed_area: f64 = (0..count).filter(|&s| goes[s]).map(|s| sheet[s].area).sum();
    if !goes.iter().any(|&g| g) || removed_area > MAX_AREA_SHARE * total_area {
        return RemovedSheets::default();
    }
    remove_sheets(model, &sheet, &sheet_of, &goes)
}

/// `goes` less the sheets of every part (sheets joined through shared vertices) where all
/// would go: such a part — a loose doubled flake, sheets hanging only on each other — hangs
/// on nothing, and deleting it whole would make its distance to the rest the result's error.
/// `sizes` are the vertices' and the sheets' counts.
fn keep_whole_parts(
    corners: &[[u32; 3]],
    sheet_of: &[u32],
    (n, count): (usize, usize),
    mut goes: Vec<bool>,
) -> Vec<bool> {
    let mut parent = union_find::singletons(count);
    let mut first = vec![u32::MAX; n];
    for (tri, &s) in corners.iter().zip(sheet_of) {
        for &v in tri {
            let f = &mut first[v as usize];
            if *f == u32::MAX {
                *f = s;
            }
            let f = *f;
            let (a, b) = (
                union_find::root(&mut parent, f),
                union_find::root(&mut parent, s),
            );
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    let mut part_stays = vec![false; count];
    for s in 0..count as u32 {
        let root = union_find::root(&mut parent, s) as usize;
        part_stays[root] |= !goes[s as usize];
    }
    for s in 0..count as u32 {
        let root = union_find::root(&mut parent, s) as usize;
        goes[s as usize] &= part_stays[root];
    }
    goes
}

/// The square of a sheet's bounding-box diagonal.
fn diagonal2(s: &Sheet) -> f64 {
    (s.hi - s.lo).length_squared()
}

/// The triangles' corners as points: copies of a point (the sides of a texture seam or of a
/// normal crease, kept apart by their attributes when the file was welded) are one vertex
/// here, so a seam does not cut a sheet, and a part sharing only copies still hangs.
fn point_corners(model: &Model) -> Cow<'_, [[u32; 3]]> {
    let split = model.texcoords.is_some()
        || matches!(model.normals, Some(Attribute::PerVertex(_)))
        || matches!(model.colors, Some(Attribute::PerVertex(_)));
    if split {
        let point = weld::point_ids(&model.positions);
        let at = |t: &[u32; 3]| t.map(|v| point[v as usize]);
        Cow::Owned(model.triangles.iter().map(at).collect())
    } else {
        Cow::Borrowed(&model.triangles)
    }
}

/// Whether a second sheet uses each vertex (its first sheet noted as it is met): only a
/// sheet with such a vertex hangs; `None` when no vertex is shared, so none hangs.
fn shared_vertices(corners: &[[u32; 3]], sheet_of: &[u32], n: usize) -> Option<Vec<bool>> {
    let mut first = vec![u32::MAX; n];
    let mut shared = vec![false; n];
    for (tri, &s) in corners.iter().zip(sheet_of) {
        for &v in tri {
            let f = &mut first[v as usize];
            if *f == u32::MAX {
                *f = s;
            } else if *f != s {
                shared[v as usize] = true;
            }
        }
    }
    shared.iter().any(|&s| s).then_some(shared)
}

/// Each sheet's area, box, whether it touches a shared vertex and whether it holds a pinned
/// one; returns the model's total area.
fn measure_sheets(
    model: &Model,
    corners: &[[u32; 3]],
    sheet_of: &[u32],
    shared: &[bool],
    pinned: &dyn Fn(u32) -> bool,
    sheet: &mut [Sheet],
) -> f64 {
    let mut total_area = 0.0;
    let p = |v: u32| model.positions[v as usize].as_dvec3();
    for ((tri, corners), &s) in model.triangles.iter().zip(corners.iter()).zip(sheet_of) {
        let [a, b, c] = tri.map(p);
        let area = (b - a).cross(c - a).length() / 2.0;
        total_area += area;
        let st = &mut sheet[s as usize];
        st.area += area;
        for q in [a, b, c] {
            st.lo = st.lo.min(q);
            st.hi = st.hi.max(q);
        }
        st.touches |= corners.iter().any(|&v| shared[v as usize]);
        st.pinned |= tri.iter().any(|&v| pinned(v));
    }
    total_area
}

/// Removes the triangles of the sheets that go; counts what went.
fn remove_sheets(
    model: &mut Model,
    sheet: &[Sheet],
    sheet_of: &[u32],
    goes: &[bool],
) -> RemovedSheets {
    let n = model.positions.len();
    let gone = || (0..sheet.len()).filter(|&s| goes[s]).map(|s| &sheet[s]);
    let keep: Vec<bool> = sheet_of.iter().map(|&s| !goes[s as usize]).collect();
    let removed = RemovedSheets {
        sheets: gone().count(),
        pockets: gone().filter(|s| s.closed).count(),
        triangles: keep.iter().filter(|&&k| !k).count(),
        vertices: 0,
        max_diagonal: gone().map(diagonal2).fold(0.0, f64::max).sqrt(),
    };
    let mut used_before = vec![false; n];
    let mut used_after = vec![false; n];
    for (tri, &k) in model.triangles.iter().zip(&keep) {
        for &v in tri {
            used_before[v as usize] = true;
            used_after[v as usize] |= k;
        }
    }
    repair::retain_triangles(model, &keep);
    RemovedSheets {
        vertices: (0..n).filter(|&v| used_before[v] && !used_after[v]).count(),
        ..removed
    }
}

/// Each of the `triangles`' sheet, numbered from 0 in the order of their first triangles
/// (union–find across the `edges` that exactly two triangles use), and how many.
fn sheets(triangles: usize, edges: &Edges) -> (Vec<u32>, usize) {
    let mut parent = union_find::singletons(triangles);
    for run in edges.runs() {
        if let [(_, s), (_, t)] = run {
            let (a, b) = (
                union_find::root(&mut parent, *s),
                union_find::root(&mut parent, *t),
            );
            // The smaller id roots the set: a sheet's root is its first triangle.
            let (lo, hi) = (a.min(b), a.max(b));
            parent[hi as usize] = lo;
        }
    }
    for t in 0..triangles as u32 {
        parent[t as usize] = union_find::root(&mut parent, t);
    }
    // Now every entry is its root; a root comes before the rest of its sheet, so its entry
    // already holds the sheet's number when they read it.
    let mut count = 0u32;
    for t in 0..triangles {
        let root = parent[t] as usize;
        parent[t] = if root == t {
            count += 1;
            count - 1
        } else {
            parent[root]
        };
    }
    (parent, count as usize)
}

/// Marks open every sheet with an edge (of `edges`) not used by exactly two of
/// its own triangles, and rimmed every sheet with an edge no other triangle uses.
fn mark_open_sheets(edges: &Edges, sheet_of: &[u32], sheet: &mut [Sheet]) {
    let mut owners: Vec<u32> = Vec::new();
    for run in edges.runs() {
        match run {
            [(_, t)] => {
                let s = &mut sheet[sheet_of[*t as usize] as usize];
                (s.closed, s.rim) = (false, true);
            }
            [_, _] => {} // one sheet's, twice
            _ => {
                owners.clear();
                owners.extend(run.iter().map(|&(_, t)| sheet_of[t as usize]));
                owners.sort_unstable();
                for group in owners.chunk_by(|a, b| a == b) {
                    if group.len() != 2 {
                        sheet[group[0] as usize].closed = false;
                    }
                }
            }
        }
    }
}

/// Vertices per task of the buckets' sorts.
const PER_TASK: usize = 1 << 14;

/// Every triangle's three edges, bucketed by their smaller vertex: bucket `v` holds
/// (the larger vertex, the triangle) of `v`'s edges, sorted, in `ends[start[v]..start[v + 1]]`.
struct Edges {
    start: Vec<usize>,
    ends: Vec<(u32, u32)>,
}

impl Edges {
    /// The `triangles`' edges over `n` vertices, bucketed by counting, each bucket then
    /// sorted on its own (on all cores): linear time.
    fn of(triangles: &[[u32; 3]], n: usize) -> Self {
        let mut start = vec![0usize; n + 1];
        for &[a, b, c] in triangles {
            for (x, y) in [(a, b), (b, c), (c, a)] {
                start[x.min(y) as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut ends = vec![(0u32, 0u32); start[n]];
        let mut next = start.clone();
        for (t, &[a, b, c]) in triangles.iter().enumerate() {
            for (x, y) in [(a, b), (b, c), (c, a)] {
                let slot = &mut next[x.min(y) as usize];
                ends[*slot] = (x.max(y), t as u32);
                *slot += 1;
            }
        }
        drop(next);
        let mut tasks = Vec::new();
        let mut rest = ends.as_mut_slice();
        for v in (0..n).step_by(PER_TASK) {
            let end = (v + PER_TASK).min(n);
            let (task, tail) = rest.split_at_mut(start[end] - start[v]);
            tasks.push((v..end, task));
            rest = tail;
        }
        tasks.into_par_iter().for_each(|(vertices, task)| {
            let base = start[vertices.start];
            for v in vertices {
                task[start[v] - base..start[v + 1] - base].sort_unstable();
            }
        });
        Self { start, ends }
    }

    /// Each edge's triangles, as runs of `(larger vertex, triangle)`.
    fn runs(&self) -> impl Iterator<Item = &[(u32, u32)]> + '_ {
        self.start
            .windows(2)
            .flat_map(|w| self.ends[w[0]..w[1]].chunk_by(|a, b| a.0 == b.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A unit square gridded 10 × 10 (z = 0), with a closed tetrahedron hanging on the
    /// diagonal of cell (5, 5): its two own vertices `s` of a cell off the diagonal's middle.
    fn grid_with_pocket(s: f32) -> Model {
        let mut m = Model::default();
        let at = |i: u32, j: u32| j * 11 + i;
        for j in 0..=10 {
            for i in 0..=10 {
                m.positions.push(Vec3::new(i as f32, j as f32, 0.0) * 0.1);
            }
        }
        for j in 0..10 {
            for i in 0..10 {
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                m.triangles.extend([[a, b, c], [a, c, d]]);
            }
        }
        let (a, c) = (at(5, 5), at(6, 6));
        let n = m.positions.len() as u32;
        m.positions.extend(
            [
                Vec3::new(5.5 - s, 5.5 + s, s),
                Vec3::new(5.5 + s, 5.5 - s, s),
            ]
            .map(|p| p * 0.1),
        );
        let (x, y) = (n, n + 1);
        m.triangles
            .extend([[a, c, x], [c, a, y], [a, x, y], [c, y, x]]);
        m
    }

    fn limit(result_triangles: usize) -> SheetLimit {
        SheetLimit {
            result_triangles: Some(result_triangles),
            max_error: f64::INFINITY,
        }
    }

    #[test]
    fn a_tetrahedron_hanging_on_an_edge_goes_when_smaller_than_a_result_triangle() {
        let mut m = grid_with_pocket(0.1);
        let removed = remove_hanging_sheets(&mut m, limit(5), &|_| false);
        assert_eq!((removed.sheets, removed.pockets), (1, 1));
        assert_eq!((removed.triangles, removed.vertices), (4, 2));
        // The pocket spans the cell's diagonal.
        assert!((removed.max_diagonal - 0.1 * 2f64.sqrt()).abs() < 1e-3);
        assert_eq!(m.triangles.len(), 200);
    }

    #[test]
    fn a_flap_on_an_edge_goes_as_a_pocket_does() {
        // One face of the tetrahedron off: three triangles with a free rim.
        let mut m = grid_with_pocket(0.1);
        m.triangles.pop();
        let removed = remove_hanging_sheets(&mut m, limit(5), &|_| false);
        assert_eq!(
            (removed.sheets, removed.pockets, removed.triangles),
            (1, 0, 3)
        );
        assert_eq!(m.triangles.len(), 200);
    }

    #[test]
    fn a_sheet_larger_than_a_result_triangle_a_pinned_one_or_one_over_the_bound_stays() {
        for (result, pinned, bound) in [
            (1000, None, f64::INFINITY),
            (5, Some(121), f64::INFINITY),
            (5, None, 0.1),
        ] {
            let mut m = grid_with_pocket(0.1);
            let limit = SheetLimit {
                result_triangles: Some(result),
                max_error: bound,
            };
            let removed = remove_hanging_sheets(&mut m, limit, &|v| Some(v) == pinned);
            assert_eq!(
                removed,
                RemovedSheets::default(),
                "{result} {pinned:?} {bound}"
            );
            assert_eq!(m.triangles.len(), 204);
        }
    }

    #[test]
    fn a_separate_part_does_not_hang() {
        // The tetrahedron on two vertices of its own, over the grid.
        let mut m = grid_with_pocket(0.1);
        let n = m.positions.len() as u32;
        m.positions
            .extend([Vec3::new(0.5, 0.5, 0.01), Vec3::new(0.6, 0.6, 0.01)]);
        for t in &mut m.triangles[200..] {
            *t = t.map(|v| match v {
                60 => n,
                72 => n + 1,
                v => v,
            });
        }
        assert_eq!(
            remove_hanging_sheets(&mut m, limit(5), &|_| false),
            RemovedSheets::default()
        );
    }

    #[test]
    fn a_patch_walled_in_by_non_manifold_edges_stays_and_its_fins_go() {
        // A fin standing on each of cell (5, 5)'s four sides: the cell's two triangles are a
        // sheet of their own, with no free rim.
        let mut m = Model::default();
        let mut grid = grid_with_pocket(0.1);
        grid.triangles.truncate(200);
        m.positions = grid.positions[..121].to_vec();
        m.triangles = grid.triangles;
        let at = |i: u32, j: u32| j * 11 + i;
        let corners = [at(5, 5), at(6, 5), at(6, 6), at(5, 6)];
        for k in 0..4 {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            let apex = (m.positions[a as usize] + m.positions[b as usize]) * 0.5
                + Vec3::new(0.0, 0.0, 0.02);
            m.positions.push(apex);
            m.triangles.push([b, a, m.positions.len() as u32 - 1]);
        }
        let removed = remove_hanging_sheets(&mut m, limit(5), &|_| false);
        assert_eq!((removed.sheets, removed.triangles), (4, 4));
        assert_eq!(m.triangles.len(), 200);
    }

    #[test]
    fn a_pocket_of_a_few_percent_of_the_area_goes() {
        // Its own vertices half a cell off the diagonal: 2.4 % of the model's area.
        let mut m = grid_with_pocket(0.5);
        let removed = remove_hanging_sheets(&mut m, limit(5), &|_| false);
        assert_eq!((removed.sheets, removed.triangles), (1, 4));
        assert_eq!(m.triangles.len(), 200);
    }

    #[test]
    fn sheets_that_are_a_real_share_of_the_model_stay() {
        // Two unit squares on one edge with a third hanging on it: each is a third of the area.
        let mut m = Model {
            positions: [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
                [1.0, 0.0, 1.0],
                [1.0, 1.0, 1.0],
            ]
            .map(Vec3::from_array)
            .to_vec(),
            triangles: vec![
                [0, 1, 2],
                [0, 2, 3],
                [1, 4, 5],
                [1, 5, 2],
                [1, 2, 7],
                [1, 7, 6],
            ],
            ..Model::default()
        };
        let removed = remove_hanging_sheets(&mut m, limit(1), &|_| false);
        assert_eq!(removed, RemovedSheets::default());
    }
}

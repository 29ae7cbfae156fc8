//! The working state of one model's quadric decimation: the arrays it owns, how they are
//! lent out as one whole [`Part`] or as disjoint parts (one range of vertices and of
//! triangle slots each, for collapsing on several cores), and writing the result back.
//! The operations live on `Part`: planning and collapsing in `part`, the checks in
//! `legality`, the cost cache in `ranking`; the loop is in `collapse_passes`.

use glam::{Vec3, Vec4};

use super::collapse_plan::Kind;
use super::edge_costs::EdgeCosts;
use super::part::{CollapseLists, Part};
#[cfg(test)]
use super::planes::{self, Constraints};
use super::quadric::LocalQuadric;
use super::texture_quadrics::{colour_quadrics, texture_quadrics, ColourQuadrics, TextureQuadrics};
use crate::decimate::closed::{ClosedView, ClosedVolumes};
use crate::decimate::distance_bound::DistanceBound;
use crate::decimate::layout::{compact, Compacted};
use crate::mesh::progressive::Recorder;
use crate::mesh::topology::{split_mut, Connectivity};
use crate::mesh::{Attribute, Model};

/// The working state of one model's decimation.
pub(super) struct Collapser {
    /// f32 as written: a moved vertex is placed at an f32 position (see `Part::plan`).
    positions: Vec<Vec3>,
    pub conn: Connectivity,
    pub kinds: Vec<Kind>,
    /// Each vertex's quadric, about its position.
    quadrics: Vec<LocalQuadric>,
    colors: Option<Vec<[f32; 3]>>,
    normals: Option<Vec<[f32; 3]>>,
    /// Texture coordinates: placed by the texture's quadrics when there are some,
    /// otherwise interpolated as the normals are.
    pub texcoords: Option<Vec<[f32; 2]>>,
    /// The texture's part of every vertex's error, with the texture coordinates' scale to
    /// model units (see [`Self::weigh_texture`]).
    texture: Option<TextureQuadrics>,
    /// The colours' part of every vertex's error, with the colours' scale to model units
    /// (see [`Self::weigh_texture`]).
    colour: Option<ColourQuadrics>,
    /// Planned cost of every edge, per half-edge slot.
    costs: EdgeCosts,
    /// Each vertex's cheapest unblocked edge: the other end (`u32::MAX`: none) and its cost.
    pub best: Vec<u32>,
    pub best_cost: Vec<f32>,
    /// Vertices with a blocked edge.
    has_blocked: Vec<bool>,
    /// What each vertex needs at the end of a pass (`collapse_passes`).
    flags: Vec<u8>,
    /// Set when the collapses are recorded for a progressive mesh.
    pub recorder: Option<Recorder>,
    /// The other side of each texture-seam vertex with exactly two sides (`u32::MAX`:
    /// none); empty when the model has no such seam. Never changes: twins collapse together,
    /// so the kept ones stay twins.
    twins: Vec<u32>,
    /// The next of the pinned vertices at the same position, in a cycle (the copies of a
    /// seam junction, one per side; `u32::MAX`: none); empty when none share a position.
    /// Never changes: pinned vertices never move.
    copies: Vec<u32>,
    /// Each junction copy's way out at the start: the area-weighted normal of all its
    /// copies' triangles (zero for other vertices; empty when `copies` is).
    facing: Vec<Vec3>,
    /// Closed components' volumes: no collapse turns one inside out or flattens it.
    closed: ClosedVolumes,
    /// Per vertex, the summed area vectors of the input triangles it stands for (their
    /// lengths summed in `w`), carried through every collapse: the input surface that
    /// triangles are checked against (docs/design.md#qem-input-surface).
    input_surface: Vec<Vec4>,
    /// Under `--keep-features`, every vertex's feature class (`features::classify`);
    /// otherwise empty.
    features: Vec<u32>,
    /// The cosine of the feature angle.
    cos_feature: f64,
    /// Under `--max-error`, the input each slot stands for: collapses then run on the
    /// whole mesh only (`decimate::distance_bound`).
    pub distance: Option<DistanceBound>,
    /// `--cost lt`: Lindström–Turk's memoryless cost and placement (`lt_cost`).
    pub lt: bool,
}

impl Collapser {
    /// The state for `triangles` over `positions`: connectivity, every vertex's kind and
    /// starting quadric (`planes`, with the edges `constraints` says are constrained).
    #[cfg(test)]
    pub fn new(
        positions: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
        colors: Option<Vec<[f32; 3]>>,
        normals: Option<Vec<[f32; 3]>>,
        constraints: Constraints<'_>,
    ) -> Self {
        let conn = Connectivity::from_triangles(positions.len(), triangles);
        let start = planes::kinds_and_quadrics(&conn, &positions, constraints);
        Self::connected(
            positions,
            conn,
            start,
            colors,
            normals,
            constraints.cos_feature,
        )
    }

    /// As [`Self::new`], from the connectivity and the kinds and quadrics
    /// (`planes::kinds_and_quadrics`) worked out already; `cos_feature` is the cosine of
    /// the feature angle.
    pub fn connected(
        positions: Vec<Vec3>,
        conn: Connectivity,
        (kinds, quadrics): (Vec<Kind>, Vec<LocalQuadric>),
        colors: Option<Vec<[f32; 3]>>,
        normals: Option<Vec<[f32; 3]>>,
        cos_feature: f64,
    ) -> Self {
        let n = positions.len();
        let closed = ClosedVolumes::connected(&positions, &conn);
        let input_surface = input_surface(&positions, conn.triangles());
        let costs = EdgeCosts::new(conn.triangles());
        Self {
            positions,
            costs,
            conn,
            kinds,
            quadrics,
            colors,
            normals,
            texcoords: None,
            texture: None,
            colour: None,
            best: vec![u32::MAX; n],
            best_cost: vec![f32::INFINITY; n],
            has_blocked: vec![false; n],
            flags: vec![0; n],
            recorder: None,
            twins: Vec::new(),
            copies: Vec::new(),
            facing: Vec::new(),
            closed,
            input_surface,
            features: Vec::new(),
            cos_feature,
            distance: None,
            lt: false,
        }
    }

    /// Holds the features in place (`--keep-features`, see `features`): corners are
    /// anchored, crease vertices go only along their crease. Call before [`Self::pin`],
    /// which adds the corners to the vertices it pins. Returns the corners.
    pub fn keep_features(&mut self) -> Vec<bool> {
        self.features = super::features::classify(&self.conn, &self.positions, self.cos_feature);
        (self.features.iter())
            .map(|&f| f == super::features::CORNER)
            .collect()
    }

    /// The state for the valid triangles of `model`, renumbered along a Morton curve as a
    /// decimation loads it, with no attributes and features from 60° (for tests).
    #[cfg(test)]
    pub fn from_model(model: &Model) -> Self {
        let loaded = crate::decimate::layout::load(model);
        let positions = loaded
            .order
            .iter()
            .map(|&v| model.positions[v as usize])
            .collect();
        let constraints = Constraints {
            cos_feature: 0.5,
            scale_folds: true,
            seam: &[],
            result_triangles: None,
        };
        Self::new(positions, loaded.triangles(model), None, None, constraints)
    }

    /// Weighs the texture and the colours into every collapse's cost and placement (Hoppe's
    /// quadric, see `AttributeQuadric`), when there are texture coordinates with an area in
    /// the texture, or per-vertex colours.
    pub fn weigh_texture(&mut self) {
        self.texture = self
            .texcoords
            .as_deref()
            .and_then(|t| texture_quadrics(&self.conn, &self.positions, t, &self.kinds));
        self.colour = self
            .colors
            .as_deref()
            .and_then(|c| colour_quadrics(&self.conn, &self.positions, c, &self.kinds));
    }

    /// Anchors the flagged vertices: they never move nor go, but may take in neighbours
    /// (see [`Kind::Anchored`]; a fixed one stays fixed).
    pub fn pin(&mut self, pinned: &[bool]) {
        for (kind, &pin) in self.kinds.iter_mut().zip(pinned) {
            if pin && *kind != Kind::Fixed {
                *kind = Kind::Anchored;
            }
        }
        self.copies = crate::mesh::seams::copy_cycles(&self.positions, pinned);
        // No copies, no junction normals: the live triangles are listed only for those.
        if self.copies.is_empty() {
            self.facing = Vec::new();
            return;
        }
        let live: Vec<[u32; 3]> = (self.conn.alive_ids())
            .map(|t| self.conn.triangle(t))
            .collect();
        self.facing = crate::mesh::seams::junction_normals(&self.positions, &live, &self.copies);
    }

    /// Pairs the two sides of texture seams: `twins[v]` is `v`'s other side or `u32::MAX`
    /// (internal numbering; empty when no vertex has a twin, see `Loaded::pairs`). A pair
    /// collapses only together, along the seam (see `Part::plan`); a vertex with a twin
    /// never moves otherwise. Closed shapes are then judged with their seams welded (call
    /// after [`Self::pin`], which links a junction's copies).
    pub fn set_twins(&mut self, twins: Vec<u32>) {
        self.twins = twins;
        if !self.twins.is_empty() || !self.copies.is_empty() {
            let triangles = self.conn.triangles();
            self.closed =
                ClosedVolumes::with_seams(&self.positions, triangles, &self.twins, &self.copies);
        }
    }

    /// Vertex count.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Everything, as one part (it records collapses when there is a recorder).
    pub fn whole(&mut self) -> Part<'_> {
        let texture_scale = self.texture.as_ref().map_or(1.0, |t| t.scale);
        let colour_scale = self.colour.as_ref().map_or(1.0, |c| c.scale);
        Part {
            v0: 0,
            whole: true,
            positions: &mut self.positions,
            conn: self.conn.whole(),
            kinds: &mut self.kinds,
            quadrics: &mut self.quadrics,
            colors: self.colors.as_deref_mut(),
            normals: self.normals.as_deref_mut(),
            texcoords: self.texcoords.as_deref_mut(),
            texture_quadrics: self.texture.as_mut().map(|t| &mut t.quadrics[..]),
            texture_scale,
            colour_quadrics: self.colour.as_mut().map(|c| &mut c.quadrics[..]),
            colour_scale,
            costs: &self.costs,
            best: &mut self.best,
            best_cost: &mut self.best_cost,
            has_blocked: &mut self.has_blocked,
            flags: &mut self.flags,
            recorder: self.recorder.as_mut(),
            twins: &self.twins,
            copies: &self.copies,
            facing: &self.facing,
            input_surface: &mut self.input_surface,
            features: &self.features,
            cos_feature: self.cos_feature,
            closed: ClosedView::Whole(&mut self.closed),
            distance: self.distance.as_mut(),
            lt: self.lt,
            scratch: CollapseLists::default(),
        }
    }

    /// Disjoint parts: part `i` owns the vertices from `vertex_starts[i]` and the triangle
    /// slots from `slot_starts[i]` to the next part's (see `ConnectivityPart`). Parts never
    /// record: a progressive mesh is built on the whole.
    pub fn split(&mut self, vertex_starts: &[u32], slot_starts: &[u32]) -> Vec<Part<'_>> {
        let vs: Vec<usize> = vertex_starts.iter().map(|&v| v as usize).collect();
        let mut colors = split_attribute(self.colors.as_deref_mut(), &vs).into_iter();
        let mut normals = split_attribute(self.normals.as_deref_mut(), &vs).into_iter();
        let mut texcoords = split_attribute(self.texcoords.as_deref_mut(), &vs).into_iter();
        let texture_scale = self.texture.as_ref().map_or(1.0, |t| t.scale);
        let texture_quadrics = self.texture.as_mut().map(|t| &mut t.quadrics[..]);
        let mut texture_quadrics = split_attribute(texture_quadrics, &vs).into_iter();
        let colour_scale = self.colour.as_ref().map_or(1.0, |c| c.scale);
        let colour_quadrics = self.colour.as_mut().map(|c| &mut c.quadrics[..]);
        let mut colour_quadrics = split_attribute(colour_quadrics, &vs).into_iter();
        let mut positions = split_mut(&mut self.positions, &vs).into_iter();
        let mut kinds = split_mut(&mut self.kinds, &vs).into_iter();
        let mut quadrics = split_mut(&mut self.quadrics, &vs).into_iter();
        let mut best = split_mut(&mut self.best, &vs).into_iter();
        let mut best_cost = split_mut(&mut self.best_cost, &vs).into_iter();
        let mut has_blocked = split_mut(&mut self.has_blocked, &vs).into_iter();
        let mut flags = split_mut(&mut self.flags, &vs).into_iter();
        let mut input_surface = split_mut(&mut self.input_surface, &vs).into_iter();
        let costs = &self.costs;
        let twins = &self.twins;
        let copies = &self.copies;
        let facing = &self.facing;
        let closed = &self.closed;
        let (features, cos_feature, lt) = (&self.features, self.cos_feature, self.lt);
        let conns = self.conn.split(vertex_starts, slot_starts);
        conns
            .into_iter()
            .zip(vertex_starts)
            .filter_map(|(conn, &v0)| {
                Some(Part {
                    v0,
                    whole: false,
                    positions: positions.next()?,
                    conn,
                    kinds: kinds.next()?,
                    quadrics: quadrics.next()?,
                    colors: colors.next()?,
                    normals: normals.next()?,
                    texcoords: texcoords.next()?,
                    texture_quadrics: texture_quadrics.next()?,
                    texture_scale,
                    colour_quadrics: colour_quadrics.next()?,
                    colour_scale,
                    costs,
                    best: best.next()?,
                    best_cost: best_cost.next()?,
                    has_blocked: has_blocked.next()?,
                    flags: flags.next()?,
                    recorder: None,
                    twins,
                    copies,
                    facing,
                    input_surface: input_surface.next()?,
                    features,
                    cos_feature,
                    closed: ClosedView::Part(closed, Default::default()),
                    distance: None,
                    lt,
                    scratch: CollapseLists::default(),
                })
            })
            .collect()
    }

    /// Adds the volume changes a part made on its own (see `ClosedView`).
    pub fn absorb_volume_changes(&mut self, changes: std::collections::HashMap<u32, f64>) {
        self.closed.absorb(changes);
    }

    /// Gives `model` back the positions and triangles `layout::release` freed, from this
    /// state before any collapse.
    pub fn restore(&self, model: &mut Model, order: &[u32], faces: &[u32]) {
        crate::decimate::layout::restore(model, &self.positions, &self.conn, order, faces);
    }

    /// Writes live vertices (at their new positions) and triangles back into `model`.
    /// `order` maps internal vertex ids to the model's, `faces` internal triangle slots to the
    /// model's faces. Kept vertices keep their relative order from the input.
    /// Returns the kept vertices' internal ids, in the written order.
    pub fn write_back(&self, model: &mut Model, order: &[u32], faces: &[u32]) -> Vec<u32> {
        let mut inverse = vec![0u32; order.len()];
        for (i, &v) in order.iter().enumerate() {
            inverse[v as usize] = i as u32;
        }
        let Compacted {
            kept_vertices,
            faces,
            triangles,
        } = compact(&self.conn, order, faces);
        model.triangles = triangles;
        model.positions = kept_vertices
            .iter()
            .map(|&v| self.positions[inverse[v as usize] as usize])
            .collect();
        let internal_of = |v: &u32| inverse[*v as usize] as usize;
        model.colors = match (&self.colors, &model.colors) {
            (Some(c), _) => Some(Attribute::PerVertex(
                kept_vertices.iter().map(|v| c[internal_of(v)]).collect(),
            )),
            (None, Some(a @ Attribute::PerFace(_))) => Some(a.select(&kept_vertices, &faces)),
            (None, _) => None,
        };
        model.normals = self.normals.as_ref().map(|n| {
            Attribute::PerVertex(
                kept_vertices
                    .iter()
                    .map(|v| Vec3::from_array(n[internal_of(v)]))
                    .collect(),
            )
        });
        model.texcoords = self
            .texcoords
            .as_ref()
            .map(|t| kept_vertices.iter().map(|v| t[internal_of(v)]).collect());
        kept_vertices
            .iter()
            .map(internal_of)
            .map(|i| i as u32)
            .collect()
    }
}

/// Each vertex's input surface: the sum of its triangles' area vectors (normal, twice the
/// area long) and of their lengths, in `f64` and stored as `f32`.
fn input_surface(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec4> {
    let mut sums = vec![glam::DVec4::ZERO; positions.len()];
    let p = |v: u32| positions[v as usize].as_dvec3();
    for &[a, b, c] in triangles {
        let area = (p(b) - p(a)).cross(p(c) - p(a));
        for v in [a, b, c] {
            sums[v as usize] += area.extend(area.length());
        }
    }
    sums.iter().map(|s| s.as_vec4()).collect()
}

/// A per-vertex attribute, when there is one, split at `starts` (see `split_mut`).
fn split_attribute<'a, T>(
    attribute: Option<&'a mut [T]>,
    starts: &[usize],
) -> Vec<Option<&'a mut [T]>> {
    match attribute {
        Some(a) => split_mut(a, starts).into_iter().map(Some).collect(),
        None => starts.iter().map(|_| None).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A 2 × 2 grid of unit squares in z = 0, each cut along its diagonal from its first
    /// corner: point `(x, y)` is vertex `3y + x`; 4 is the only interior one.
    fn grid() -> Collapser {
        grid_raised(0.0)
    }

    /// As [`grid`], the interior vertex 4 raised to `z`.
    fn grid_raised(z: f32) -> Collapser {
        grid_lifted(|i| if i == 4 { z } else { 0.0 })
    }

    /// As [`grid`], each vertex `i` lifted to `z(i)`.
    fn grid_lifted(z: impl Fn(u32) -> f32) -> Collapser {
        let positions = (0..9)
            .map(|i| Vec3::new((i % 3) as f32, (i / 3) as f32, z(i)))
            .collect();
        let triangles = [0, 1, 3, 4]
            .into_iter()
            .flat_map(|a| [[a, a + 1, a + 4], [a, a + 4, a + 3]])
            .collect();
        let constraints = Constraints {
            cos_feature: 0.5,
            scale_folds: true,
            seam: &[],
            result_triangles: None,
        };
        Collapser::new(positions, triangles, None, None, constraints)
    }

    #[test]
    fn a_pinned_vertex_takes_its_neighbours_in_where_it_stands() {
        let mut d = grid();
        d.pin(&(0..9).map(|v| v == 1).collect::<Vec<_>>());
        let part = d.whole();
        assert_eq!(part.kind(1), Kind::Anchored);
        // The interior neighbour goes into it, which stays put.
        let plan = part.plan(1, 4).expect("interior into pinned");
        assert_eq!((plan.remove, plan.keep), (4, 1));
        assert_eq!(plan.position, DVec3::new(1.0, 0.0, 0.0));
        // So does a neighbour along the outline.
        let plan = part.plan(0, 1).expect("along the outline into pinned");
        assert_eq!((plan.remove, plan.keep), (0, 1));
        assert_eq!(plan.position, DVec3::new(1.0, 0.0, 0.0));
        // Two pinned ends: neither may go.
        let mut d = grid();
        d.pin(&(0..9).map(|v| v <= 1).collect::<Vec<_>>());
        assert!(d.whole().plan(0, 1).is_none());
    }

    #[test]
    fn a_boundary_vertex_taking_in_an_interior_one_moves_to_their_optimum() {
        // The raised interior vertex 4 goes into the outline's vertex 1, which rises towards
        // it (cheaper than staying put), held near its outline (the line y = z = 0) by its
        // constraint planes: less than half as far off it as 4 was
        // (docs/design.md#qem-border-placement).
        let mut d = grid_raised(0.5);
        let at = |v: usize| d.quadrics[v].at(d.positions[v].as_dvec3());
        let q = at(1).sum(&at(4));
        let stay = DVec3::new(1.0, 0.0, 0.0);
        let plan = d.whole().plan(1, 4).expect("interior into boundary");
        assert_eq!((plan.remove, plan.keep), (4, 1));
        let p = plan.position;
        assert!(p.z > 0.0, "stays at {p}");
        assert!(plan.cost < q.eval(stay), "{} ≥ {}", plan.cost, q.eval(stay));
        assert!(p.y.hypot(p.z) < 0.25, "{p} left the outline");
        // Flat, staying put is already the best: it does not move.
        let plan = grid().whole().plan(1, 4).expect("interior into boundary");
        assert_eq!((plan.remove, plan.keep, plan.position), (4, 1, stay));
    }

    #[test]
    fn a_moved_vertex_keeps_both_ends_quadrics_about_its_new_position() {
        // The raised interior vertex 4 into the outline's 1, which moves: 1's stored
        // quadric, read at its new position, is the two ends' from before anywhere near.
        let mut d = grid_raised(0.5);
        let at = |d: &Collapser, v: usize| d.quadrics[v].at(d.positions[v].as_dvec3());
        let before = at(&d, 1).sum(&at(&d, 4));
        let mut part = d.whole();
        let plan = part.plan(1, 4).expect("interior into boundary");
        assert!(part.gather(plan.remove, plan.keep));
        part.collapse(&plan);
        assert_ne!(d.positions[1], Vec3::X, "the kept vertex did not move");
        let after = at(&d, 1);
        for p in [
            plan.position,
            DVec3::new(1.5, 0.5, 0.2),
            DVec3::new(0.0, 2.0, -1.0),
        ] {
            let (x, y) = (before.eval(p), after.eval(p));
            assert!((x - y).abs() <= 1e-6 * x.max(1e-6), "{x} vs {y} at {p}");
        }
    }

    #[test]
    fn a_collapse_leaving_triangles_turned_from_the_input_surface_is_refused() {
        // Interior vertex 4 into the outline's 1 on the flat grid: legal over the grid's own
        // input surface. Were that surface (what the current triangles stand for) facing
        // the other way, as after a run of small turns, the same collapse is refused: each
        // step's turn is judged against the input, not only against the step before.
        let mut d = grid();
        let mut part = d.whole();
        let plan = part.plan(1, 4).expect("interior into boundary");
        assert!(part.gather(plan.remove, plan.keep));
        assert!(part.is_collapse_legal(&plan));
        for s in &mut d.input_surface {
            *s = (-s.truncate()).extend(s.w);
        }
        let mut part = d.whole();
        let plan = part.plan(1, 4).expect("interior into boundary");
        assert!(part.gather(plan.remove, plan.keep));
        assert!(!part.is_collapse_legal(&plan));
    }

    #[test]
    fn under_keep_features_a_crease_vertex_goes_only_along_its_crease() {
        // Folded 90° along x = 1: vertex 4 is on the crease (two feature edges), 1 and 7
        // end it on the border (one each: corners).
        let mut d = grid_lifted(|i| -((i % 3) as f32 - 1.0).abs());
        let corners = d.keep_features();
        assert_eq!(
            corners,
            (0..9).map(|v| v == 1 || v == 7).collect::<Vec<_>>()
        );
        d.pin(&corners);
        let part = d.whole();
        assert_eq!(part.kind(1), Kind::Anchored);
        // Off the crease: neither into a slope's vertex nor taking one in while moving.
        assert!(
            part.plan(3, 4).is_none(),
            "the crease vertex into a slope's"
        );
        assert!(part.plan(0, 4).is_none());
        let plan = part.plan(4, 1).expect("along the crease into its end");
        assert_eq!((plan.remove, plan.keep), (4, 1));
        assert_eq!(plan.position, DVec3::new(1.0, 0.0, 0.0));
        // Without the flag the crease vertex may go into a slope's.
        assert!(grid_lifted(|i| -((i % 3) as f32 - 1.0).abs())
            .whole()
            .plan(3, 4)
            .is_some());
    }
}

//! A mutable view of a decimation's state: the whole of it, or one of several disjoint
//! parts collapsed on different cores (each owns a range of vertices and of triangle slots;
//! see `Collapser::split`). What a part does: which way an edge collapses and where the
//! kept vertex goes (`plan`), whether a collapse stays inside the part (`gather`),
//! and performing it (topology, quadrics, attributes, the progressive record).
//!
//! Vertex ids are always the mesh's; a part translates them to its slices. A part touches
//! only what it owns: `gather` is asked before anything else of a collapse.

use glam::{DVec2, DVec3, Vec3};

use super::collapse_plan::{others, Kind, Plan};
use super::edge_costs::EdgeCosts;
use super::features;
use super::quadric::{ColourQuadric, LocalQuadric, Quadric, TextureQuadric};
use crate::decimate::closed::ClosedView;
use crate::decimate::distance_bound::DistanceBound;
use crate::mesh::progressive::{CollapseRecord, Recorder};
use crate::mesh::topology::{Adjacency, ConnectivityPart, FanTriangle, Ring, RingShape};

/// A placement may leave the edge's bounding box by at most this many edge lengths.
const BOX_MARGIN: f64 = 1.0;

/// Under `--cost lt`, weight of the quadrics' squared distance (to the input planes the
/// kept vertex stands for) added to the LT cost's cube root (both length²): the memoryless
/// cost alone lets vertices drift from the input, and the max error with them
/// (docs/benchmarks.md#twelve-cells).
const LT_QUADRIC_WEIGHT: f64 = 10.0;

/// Weight of a per-vertex normal step in a collapse's cost, against a colour step's 1: light,
/// since on curved surfaces the quadric already prices the turn, while on flat stretches the
/// normals alone order the collapses (docs/design.md#qem-normal-weight).
const NORMAL_WEIGHT: f64 = 0.001;

/// Weight of the texture's error (the area × squared distance the image slides over the
/// surface, `TextureQuadric`) against the geometric error's 1 (docs/design.md#qem-texture-weight).
const TEXTURE_WEIGHT: f64 = 0.1;

/// Weight of the colours' error (the area × squared colour step, scaled to model units by
/// `texture_quadrics`) against the geometric error's 1 (docs/design.md#qem-colour-weight).
const COLOUR_WEIGHT: f64 = 0.03;

/// Lists a collapse and its checks fill, kept from one collapse to the next.
#[derive(Debug, Default)]
pub(super) struct CollapseLists {
    /// The candidate edge's ends and their fans, read once by [`Part::gather`] for every
    /// check and for the collapse.
    ends: [u32; 2],
    fans: [Vec<FanTriangle>; 2],
    /// The removed end's triangles renamed to the kept end, and those deleted with the edge.
    renamed: Vec<u32>,
    deleted: Vec<(u32, [u32; 3])>,
    /// The removed end's neighbours (with repeats: two per triangle, see the link
    /// condition), and those it shares with the kept end (each once).
    pub ring: Vec<u32>,
    pub common: Vec<u32>,
    /// The ends and fans of a seam collapse's other side while the first side's are in
    /// `ends` and `fans` (see [`Part::swap_sides`]).
    twin_ends: [u32; 2],
    twin_fans: [Vec<FanTriangle>; 2],
    /// The complex vertices the last collapse made manifold (see [`Part::collapse`]), and
    /// the ring it read them with.
    pub settled: Vec<u32>,
    settle_ring: Ring,
    /// The volume change the last legality check of a collapse on a closed component
    /// worked out: the collapse's ends, the kept end's new position and six times the
    /// change, for the collapse itself to take.
    pub volume_change: Option<([u32; 2], DVec3, f64)>,
}

impl CollapseLists {
    /// The fans [`Part::gather`] read, as `plan`'s (removed end's, kept end's).
    pub fn fans(&self, plan: &Plan) -> (&[FanTriangle], &[FanTriangle]) {
        let [a, b] = &self.fans;
        if self.ends[0] == plan.remove {
            (a, b)
        } else {
            (b, a)
        }
    }
}

/// The state of the vertices `v0..v0 + positions.len()` and of the triangle slots its
/// `conn` owns (everything when `whole`).
pub(super) struct Part<'a> {
    pub v0: u32,
    pub whole: bool,
    /// f32 as written: a moved vertex is placed at an f32 position (see `plan`).
    pub positions: &'a mut [Vec3],
    pub conn: ConnectivityPart<'a>,
    pub kinds: &'a mut [Kind],
    /// Each vertex's quadric, about its position: moving a vertex stores it again.
    pub quadrics: &'a mut [LocalQuadric],
    pub colors: Option<&'a mut [[f32; 3]]>,
    pub normals: Option<&'a mut [[f32; 3]]>,
    pub texcoords: Option<&'a mut [[f32; 2]]>,
    /// The texture's part of each vertex's error (textured models), and the texture
    /// coordinates' scale to the model units it is in.
    pub texture_quadrics: Option<&'a mut [TextureQuadric]>,
    pub texture_scale: f64,
    /// The colours' part of each vertex's error (per-vertex colours), and the colours'
    /// scale to the model units it is in.
    pub colour_quadrics: Option<&'a mut [ColourQuadric]>,
    pub colour_scale: f64,
    /// Planned cost of every edge, per half-edge slot (the whole mesh's: entries are
    /// atomics, and a part writes only its own slots).
    pub costs: &'a EdgeCosts,
    pub best: &'a mut [u32],
    pub best_cost: &'a mut [f32],
    pub has_blocked: &'a mut [bool],
    pub flags: &'a mut [u8],
    pub recorder: Option<&'a mut Recorder>,
    /// Texture-seam twins, by vertex id (the whole mesh's, read only; empty when none).
    pub twins: &'a [u32],
    /// Anchored vertices' next copy at their position (the whole mesh's, read only; see
    /// `Collapser::pin`).
    pub copies: &'a [u32],
    /// Junction copies' starting normals (the whole mesh's, read only; see
    /// `Collapser::pin`).
    pub facing: &'a [Vec3],
    /// Per owned vertex, the summed area vectors of the input triangles it stands for, and
    /// their lengths summed in `w` (see `Collapser`): a collapse's kept vertex takes both
    /// ends'.
    pub input_surface: &'a mut [glam::Vec4],
    /// Feature classes under `--keep-features` (the whole mesh's, read only; empty
    /// otherwise; see `features`), and the feature angle's cosine.
    pub features: &'a [u32],
    pub cos_feature: f64,
    /// Closed components' volumes (see `decimate::closed`).
    pub closed: ClosedView<'a>,
    /// Under `--max-error`, the input each slot stands for (`decimate::distance_bound`;
    /// the whole only: a run with it collapses on the whole mesh).
    pub distance: Option<&'a mut DistanceBound>,
    /// `--cost lt`: collapses are priced and placed by `lt_cost` instead of the quadrics.
    pub lt: bool,
    pub scratch: CollapseLists,
}

/// Which end of an edge goes and how the kept one may move ([`Part::plan`]'s first step).
#[derive(Debug, Clone, Copy)]
struct CollapseEnds {
    remove: u32,
    keep: u32,
    /// The kept end moves to the optimum (else it stays put).
    free: bool,
    /// The kept end moves along its crease only.
    on_crease: bool,
    /// On a texture seam, the other side's edge (its removed end, its kept end).
    twin: Option<[u32; 2]>,
    /// Both ends are interior.
    interior: bool,
}

impl Part<'_> {
    /// `v`'s index in this part's slices, when it owns `v`.
    #[inline]
    pub fn local(&self, v: u32) -> Option<usize> {
        let i = v.wrapping_sub(self.v0) as usize;
        (i < self.positions.len()).then_some(i)
    }

    /// True when this part owns vertex `v`.
    #[inline]
    pub fn owns(&self, v: u32) -> bool {
        self.local(v).is_some()
    }

    /// The index of the owned vertex `v` in this part's slices.
    #[inline]
    pub fn at(&self, v: u32) -> usize {
        (v - self.v0) as usize
    }

    #[inline]
    pub fn kind(&self, v: u32) -> Kind {
        self.kinds[self.at(v)]
    }

    /// True once `v` was removed or when it can never move.
    #[inline]
    pub fn is_fixed(&self, v: u32) -> bool {
        self.kind(v) == Kind::Fixed
    }

    /// Whether the fans in the other side's scratch (see [`Self::swap_sides`]) reach `x`.
    pub fn other_side_touches(&self, x: u32) -> bool {
        self.scratch
            .twin_fans
            .iter()
            .flatten()
            .any(|f| f.touches(x))
    }

    /// Whether `a` and `b` share an edge; `None` when `a`'s fan is not this part's.
    pub fn joined(&self, a: u32, b: u32) -> Option<bool> {
        let fan_owned = self.owns(a)
            && self
                .conn
                .incident(a)
                .iter()
                .all(|&t| self.conn.owns_slot(t));
        fan_owned.then(|| self.edge_triangles(a, b) > 0)
    }

    /// Reads the fans of the edge `v`–`w`'s ends into the scratch, for the checks and the
    /// collapse; false when collapsing it (either way) would read or write what this part
    /// does not own: both ends, their triangles (slots) and those triangles' corners, with
    /// room in the ends' incident lists for the merged fan and unspilled lists at the
    /// edge's apexes (a split-off part has no side table for long lists). The whole owns
    /// everything.
    pub fn gather(&mut self, v: u32, w: u32) -> bool {
        let (v0, len, whole) = (self.v0, self.positions.len(), self.whole);
        let owns = |x: u32| (x.wrapping_sub(v0) as usize) < len;
        if !(whole || (owns(v) && owns(w))) {
            return false;
        }
        let CollapseLists { ends, fans, .. } = &mut self.scratch;
        *ends = [v, w];
        let c = &self.conn;
        for (&x, fan) in ends.iter().zip(fans.iter_mut()) {
            // Asked first: a split-off part sees a spilled list as empty.
            if !c.has_room(x, 0) || !c.fan(x, fan) {
                return false;
            }
            if !whole && !fan.iter().all(|f| owns(f.next) && owns(f.prev)) {
                return false;
            }
        }
        // A collapse keeps one end with both fans, less the (at least one) edge triangle
        // in each: room for the sum less two.
        whole
            || (c.has_room(v, fans[1].len().saturating_sub(2))
                && fans[0]
                    .iter()
                    .all(|f| !f.touches(w) || (c.has_room(f.next, 0) && c.has_room(f.prev, 0))))
    }

    /// The fans [`Self::gather`] read, as `plan`'s (removed end's, kept end's).
    pub fn fans(&self, plan: &Plan) -> (&[FanTriangle], &[FanTriangle]) {
        self.scratch.fans(plan)
    }

    /// The fan [`Self::gather`] read around `v`, one of the edge's ends, to edit.
    pub fn fan_mut(&mut self, v: u32) -> &mut Vec<FanTriangle> {
        let s = &mut self.scratch;
        &mut s.fans[usize::from(s.ends[0] != v)]
    }

    /// Starts loading what collapsing an edge of `v` reads first (a hint; ignored for a
    /// vertex this part does not own).
    pub fn prefetch(&self, v: u32) {
        if let Some(i) = self.local(v) {
            self.quadrics[i].prefetch();
            if let Some(t) = self.texture_quadrics.as_deref() {
                crate::mesh::prefetch_all(&t[i]);
            }
            if let Some(c) = self.colour_quadrics.as_deref() {
                crate::mesh::prefetch_all(&c[i]);
            }
            crate::mesh::prefetch(&self.positions[i]);
            crate::mesh::prefetch(&self.best[i]);
            crate::mesh::prefetch(&self.kinds[i]);
            self.conn.prefetch_incident(v);
        }
    }

    /// Starts loading `v`'s incident triangles: the connectivity's, or with `costs` the
    /// planning's records of them (corners and edge costs) (a hint; `v`'s incident list
    /// should be loaded by now).
    pub fn prefetch_fan(&self, v: u32, costs: bool) {
        if self.owns(v) {
            for &t in self.conn.incident(v) {
                if costs {
                    // The planning's copy of the corners lies beside the costs.
                    self.costs.prefetch(t);
                } else {
                    self.conn.prefetch_triangle(t);
                }
            }
        }
    }

    /// Starts loading the positions, input surface and flags of the neighbours of `v` and `w`
    /// (each once in a closed fan), the ends' own input surface and closed component (the
    /// legality checks read them), and the incident lists of the edge `v`–`w`'s apexes,
    /// which a collapse edits (a hint; the fans' triangles should be loaded by now).
    pub fn prefetch_neighbourhood(&self, v: u32, w: u32) {
        for (x, y) in [(v, w), (w, v)] {
            if !self.owns(x) {
                continue;
            }
            if let Some(i) = self.local(x) {
                crate::mesh::prefetch(&self.input_surface[i]);
                self.closed.prefetch(x);
            }
            for &t in self.conn.incident(x) {
                if !self.conn.owns_slot(t) {
                    continue;
                }
                let [a, b] = others(self.conn.triangle(t), x);
                if let Some(i) = self.local(a) {
                    crate::mesh::prefetch(&self.positions[i]);
                    crate::mesh::prefetch(&self.input_surface[i]);
                    crate::mesh::prefetch(&self.flags[i]);
                }
                if a == y {
                    self.conn.prefetch_incident(b);
                }
            }
        }
    }

    /// Starts loading what planning an edge to `w` reads (a hint).
    pub fn prefetch_end(&self, w: u32) {
        if let Some(i) = self.local(w) {
            self.quadrics[i].prefetch();
            if let Some(t) = self.texture_quadrics.as_deref() {
                crate::mesh::prefetch_all(&t[i]);
            }
            crate::mesh::prefetch(&self.kinds[i]);
            crate::mesh::prefetch(&self.positions[i]);
        }
    }

    pub fn position(&self, v: u32) -> DVec3 {
        self.positions[self.at(v)].as_dvec3()
    }

    /// `v`'s quadric, in model coordinates.
    #[inline]
    fn quadric(&self, v: u32) -> Quadric {
        let i = self.at(v);
        self.quadrics[i].at(self.positions[i].as_dvec3())
    }

    /// How many triangles are on the edge `a`–`b`.
    fn edge_triangles(&self, a: u32, b: u32) -> usize {
        self.conn
            .incident(a)
            .iter()
            .filter(|&&t| self.conn.triangle(t).contains(&b))
            .count()
    }

    /// Which end of `a`–`b` goes and where the other moves, or `None` when the kinds of the
    /// ends forbid any collapse of this edge. The table, from the ends' kinds:
    ///
    /// | a        | b        | edge      | collapse                                          |
    /// |----------|----------|-----------|---------------------------------------------------|
    /// | fixed    | any      | any       | none: a complex vertex never moves                |
    /// | interior | interior | interior  | either way, to the quadric's optimum              |
    /// | interior | boundary | interior  | the interior end into the boundary end, which moves to the optimum (its constraint planes keep it on the outline; docs/design.md#qem-border-placement); a seam's end stays put |
    /// | boundary | boundary | boundary  | either way, to the optimum (the constraint planes keep it on the outline) |
    /// | boundary | boundary | interior  | none: it would pinch the surface                  |
    /// | interior | anchored | any       | the interior end into the anchored end, unmoved   |
    /// | boundary | anchored | boundary  | the boundary end into the anchored end, unmoved   |
    /// | boundary | anchored | interior  | none: it would pinch the surface                  |
    /// | anchored | anchored | any       | none: neither may go                              |
    /// | interior | complex  | any       | the interior end into the complex end, unmoved    |
    /// | boundary | complex  | boundary  | the boundary end into the complex end, unmoved    |
    /// | boundary | complex  | other     | none: it would pinch the surface                  |
    /// | complex  | complex  | non-manifold | the end whose place costs more into the other, unmoved: the sheets on the edge shorten together |
    /// | complex  | complex  | other     | none: it could join two sheets or fans            |
    /// | complex  | anchored | any       | none: neither may go (a complex end may not move onto a seam) |
    #[inline(always)]
    pub fn plan(&self, a: u32, b: u32) -> Option<Plan> {
        let ends = self.collapse_ends(a, b)?;
        let CollapseEnds {
            remove, keep, twin, ..
        } = ends;
        let mut q = self.quadric(a).sum(&self.quadric(b));
        if let Some([r2, k2]) = twin {
            q.add(&self.quadric(r2));
            q.add(&self.quadric(k2));
        }
        let (pr, pk) = (self.position(remove), self.position(keep));
        // A textured model's placement minimises the geometric and the texture's error
        // together (each side's on a seam: each has its own coordinates).
        let texture = self.texture_quadrics.as_deref().map(|t| {
            let side = |r: u32, k: u32| t[self.at(r)].sum(&t[self.at(k)]);
            (side(remove, keep), twin.map(|[r2, k2]| side(r2, k2)))
        });
        let mut placed = q;
        if let Some((side, other)) = &texture {
            placed.add(&side.at_best_coordinates(TEXTURE_WEIGHT));
            if let Some(other) = other {
                placed.add(&other.at_best_coordinates(TEXTURE_WEIGHT));
            }
        }
        let lt = if self.lt {
            Some(self.lt_plan([remove, keep], twin, ends.free, ends.on_crease)?)
        } else {
            None
        };
        let position = if let Some(lt) = &lt {
            lt.position
        } else if ends.on_crease {
            along_crease(&placed, pr, pk)
        } else if ends.free {
            self.place(&placed, pr, pk)
        } else {
            pk
        };
        // What is written is f32: plan with exactly that.
        let position = position.as_vec3().as_dvec3();
        let geometric = q.eval(position);
        let error2 = geometric / q.area.max(f64::MIN_POSITIVE);
        let mut cost = geometric;
        let mut texcoords = None;
        if let Some((side, other)) = &texture {
            // The texture's error at the best coordinates (rounding aside, never below the
            // geometric error alone).
            cost = cost.max(placed.eval(position));
            if ends.interior {
                let best = DVec2::from(side.best_coordinates(position)) / self.texture_scale;
                texcoords = Some(best.as_vec2().to_array());
            } else {
                let ends = ([remove, keep], twin, pr, pk);
                self.add_outline_texture_cost(&mut cost, position, ends, side, other.as_ref());
            }
        }
        cost += self.colour_cost([remove, keep], twin, position);
        cost += self.attribute_cost([remove, keep], twin, q.area, (pk - pr).length_squared());
        if let Some(lt) = &lt {
            // The attributes' terms are area × length²: the edge's length² more makes them
            // length⁶, as the LT cost is; its cube root (the same order) stays in f32's
            // range on small models.
            let extra = (pk - pr).length_squared() * (cost - geometric);
            cost = (lt.cost_at(position) + extra).cbrt() + LT_QUADRIC_WEIGHT * error2;
        }
        Some(Plan {
            remove,
            keep,
            position,
            error2,
            cost,
            twin,
            texcoords,
            junction: None,
        })
    }

    /// The first step of [`Self::plan`]: which end goes, whether the kept one may move
    /// (along a crease only, or not at all), and a seam's other side, from the ends' kinds,
    /// the seams and the features; `None` when they forbid the collapse.
    #[inline(always)]
    fn collapse_ends(&self, a: u32, b: u32) -> Option<CollapseEnds> {
        let (ka, kb) = (self.kind(a), self.kind(b));
        let (remove, keep, free, along_boundary) = self.roles(a, b, ka, kb)?;
        let (remove, keep, twin) = if self.twins.is_empty() {
            (remove, keep, None)
        } else {
            self.seam_sides(remove, keep, free, along_boundary)?
        };
        let interior = ka == Kind::Interior && kb == Kind::Interior;
        let (remove, keep, free, on_crease) = if self.features.is_empty() {
            (remove, keep, free, false)
        } else {
            self.feature_rule(remove, keep, free, interior, twin.is_some())?
        };
        Some(CollapseEnds {
            remove,
            keep,
            free,
            on_crease,
            twin,
            interior,
        })
    }

    /// Colours price a collapse but do not move the point: pulled by a colour field, a
    /// coarse sphere's vertex left its surface and turned a triangle over. 0 without
    /// per-vertex colours.
    #[inline(always)]
    fn colour_cost(&self, [remove, keep]: [u32; 2], twin: Option<[u32; 2]>, at: DVec3) -> f64 {
        let Some(c) = self.colour_quadrics.as_deref() else {
            return 0.0;
        };
        let side = |r: u32, k: u32| c[self.at(r)].sum(&c[self.at(k)]);
        let mut cost = COLOUR_WEIGHT * self.colour_error(&side(remove, keep), [remove, keep], at);
        if let Some([r2, k2]) = twin {
            cost += COLOUR_WEIGHT * self.colour_error(&side(r2, k2), [r2, k2], at);
        }
        cost
    }

    /// Which end of `a`–`b` (of kinds `ka`, `kb`) goes into which, whether the kept end may
    /// move, and whether the edge runs along a boundary; `None` when neither may go (the
    /// table of [`Self::plan`]).
    #[inline(always)]
    fn roles(&self, a: u32, b: u32, ka: Kind, kb: Kind) -> Option<(u32, u32, bool, bool)> {
        let along_boundary = |(remove, keep, free)| {
            (self.edge_triangles(remove, keep) == 1).then_some((remove, keep, free, true))
        };
        Some(match (ka, kb) {
            (Kind::Fixed, _)
            | (_, Kind::Fixed)
            | (Kind::Anchored, Kind::Anchored)
            | (Kind::Anchored, Kind::Complex)
            | (Kind::Complex, Kind::Anchored) => return None,
            (Kind::Interior, Kind::Interior) => (a, b, true, false),
            (Kind::Interior, Kind::Boundary) => (a, b, self.twin(b).is_none(), false),
            (Kind::Boundary, Kind::Interior) => (b, a, self.twin(a).is_none(), false),
            (Kind::Interior, Kind::Anchored | Kind::Complex) => (a, b, false, false),
            (Kind::Anchored | Kind::Complex, Kind::Interior) => (b, a, false, false),
            (Kind::Boundary, Kind::Boundary) => along_boundary((a, b, true))?,
            (Kind::Boundary, Kind::Anchored | Kind::Complex) => along_boundary((a, b, false))?,
            (Kind::Anchored | Kind::Complex, Kind::Boundary) => along_boundary((b, a, false))?,
            (Kind::Complex, Kind::Complex) => self.along_non_manifold_edge(a, b)?,
        })
    }

    /// The texture's excess cost when the kept vertex sits on an outline of the texture (a
    /// boundary, a seam's side) or stays put: its coordinates are interpolated along the
    /// edge, as `collapse` does without a plan's, so they stay on the outline, exactly where
    /// it is straight. Priced as such, on each side of a seam; nothing without coordinates.
    #[inline(always)]
    fn add_outline_texture_cost(
        &self,
        cost: &mut f64,
        position: DVec3,
        ([remove, keep], twin, pr, pk): ([u32; 2], Option<[u32; 2]>, DVec3, DVec3),
        side: &TextureQuadric,
        other: Option<&TextureQuadric>,
    ) {
        let Some(t) = self.texcoords.as_deref() else {
            return;
        };
        let s = f64::from(fraction(position, pr, pk));
        let along = |r: u32, k: u32| {
            let [r, k] = [r, k].map(|v| DVec2::from(t[self.at(v)].map(f64::from)));
            ((k + s * (r - k)) * self.texture_scale).to_array()
        };
        *cost += TEXTURE_WEIGHT * side.excess(position, along(remove, keep));
        if let (Some(other), Some([r2, k2])) = (other, twin) {
            *cost += TEXTURE_WEIGHT * other.excess(position, along(r2, k2));
        }
    }

    /// The colour the kept vertex of the collapse `[remove, keep]` takes at `position`, in
    /// colour units (`side`: the two ends' colour quadrics summed): its own where it stays,
    /// otherwise the best of the input surface it stands for there, within the range of the
    /// channel (0 to 1, or wider where an end's colour is).
    fn colour_at(
        &self,
        side: &ColourQuadric,
        [remove, keep]: [u32; 2],
        position: DVec3,
    ) -> [f32; 3] {
        let Some(c) = self.colors.as_deref() else {
            return [0.0; 3];
        };
        let (r, k) = (c[self.at(remove)], c[self.at(keep)]);
        if position == self.position(keep) {
            return k;
        }
        let best = side.best_coordinates(position);
        std::array::from_fn(|j| {
            let (lo, hi) = (r[j].min(k[j]).min(0.0), r[j].max(k[j]).max(1.0));
            ((best[j] / self.colour_scale) as f32).clamp(lo, hi)
        })
    }

    /// The colours' error of the collapse `ends` with the kept vertex at `position` and the
    /// colour [`Self::colour_at`] gives it: `E(p, s)` of its quadric `side`.
    fn colour_error(&self, side: &ColourQuadric, ends: [u32; 2], position: DVec3) -> f64 {
        let colour = self.colour_at(side, ends, position);
        let scaled = colour.map(|x| f64::from(x) * self.colour_scale);
        side.at_best_coordinates(1.0).eval(position) + side.excess(position, scaled)
    }

    /// What the attribute steps along a collapse's edge (and its seam twin's) add to its
    /// cost, where no quadric prices them: a colour step costs as if it moved the surface by that fraction of the edge
    /// (of the quadric's `area`, the edge `edge2` long squared; see the module doc), a
    /// normal step the same, weighted. 0 without colours or normals.
    #[inline(always)]
    fn attribute_cost(
        &self,
        [remove, keep]: [u32; 2],
        twin: Option<[u32; 2]>,
        area: f64,
        edge2: f64,
    ) -> f64 {
        let colors = (self.colors.as_deref()).filter(|_| self.colour_quadrics.is_none());
        let normals = self.normals.as_deref();
        if colors.is_none() && normals.is_none() {
            return 0.0;
        }
        let step = |r: u32, k: u32| {
            let (i, j) = (self.at(r), self.at(k));
            let step2 = |a: Option<&[[f32; 3]]>| {
                a.map_or(0.0, |a| {
                    let d = Vec3::from_array(a[i]) - Vec3::from_array(a[j]);
                    f64::from(d.length_squared())
                })
            };
            step2(colors) + NORMAL_WEIGHT * step2(normals)
        };
        let mut d2 = step(remove, keep);
        if let Some([r2, k2]) = twin {
            d2 += step(r2, k2);
        }
        area * d2 * edge2
    }

    /// Which end of the edge `a`–`b` between two complex vertices goes, when three or more
    /// triangles share it: the one whose position the ends' quadrics price higher (ties:
    /// `a`), into the other, unmoved; `None` on any other edge.
    fn along_non_manifold_edge(&self, a: u32, b: u32) -> Option<(u32, u32, bool, bool)> {
        if self.edge_triangles(a, b) < 3 {
            return None;
        }
        let q = self.quadric(a).sum(&self.quadric(b));
        Some(if q.eval(self.position(b)) <= q.eval(self.position(a)) {
            (a, b, false, false)
        } else {
            (b, a, false, false)
        })
    }

    /// What `--keep-features` makes of the collapse `remove` → `keep` (`free`: the kept end
    /// may move; `swappable`: either end may go; `seam`: a seam's two sides collapse):
    /// `None` when it would move or remove a corner, take a crease vertex off its crease or
    /// part a seam on a feature; otherwise the ends, whether the kept one moves, and whether
    /// it moves along the crease (on the line between the ends).
    fn feature_rule(
        &self,
        remove: u32,
        keep: u32,
        free: bool,
        swappable: bool,
        seam: bool,
    ) -> Option<(u32, u32, bool, bool)> {
        let class = |v: u32| {
            self.features
                .get(v as usize)
                .copied()
                .unwrap_or(features::NONE)
        };
        match (class(remove), class(keep)) {
            (features::NONE, features::NONE) => Some((remove, keep, free, false)),
            _ if seam => None,
            // Into a feature vertex, which stays where it is.
            (features::NONE, _) => Some((remove, keep, false, false)),
            (features::CORNER, _) => None,
            (_, features::NONE) => swappable.then_some((keep, remove, false, false)),
            (_, features::CORNER) => self
                .feature_edge(remove, keep)
                .then_some((remove, keep, false, false)),
            (r, k) => {
                (r == k && self.feature_edge(remove, keep)).then_some((remove, keep, free, free))
            }
        }
    }

    /// True when `a`–`b` is an edge of two triangles whose normals turn by more than the
    /// feature angle (false when a corner of them is not this part's).
    fn feature_edge(&self, a: u32, b: u32) -> bool {
        let mut normals = [DVec3::ZERO; 2];
        let mut n = 0;
        for &t in self.conn.incident(a) {
            let tri = self.conn.triangle(t);
            if !tri.contains(&b) {
                continue;
            }
            if n == 2 || !tri.iter().all(|&x| self.owns(x)) {
                return false;
            }
            let [p, q, r] = tri.map(|x| self.position(x));
            normals[n] = (q - p).cross(r - p).normalize_or_zero();
            n += 1;
        }
        n == 2 && features::folded(normals[0], normals[1], self.cos_feature)
    }

    /// `v`'s other side on a texture seam, when it has one.
    #[inline]
    pub fn twin(&self, v: u32) -> Option<u32> {
        self.twins
            .get(v as usize)
            .copied()
            .filter(|&w| w != u32::MAX)
    }

    /// What texture seams make of the collapse `remove` → `keep` (`free`: the kept end
    /// moves; `along_boundary`: the edge is on the boundary): `None` when it would part a
    /// seam's sides; otherwise its ends, with the other side's edge when it is a seam edge.
    ///
    /// A vertex with a twin may stay where it is while an interior neighbour collapses into
    /// it; it moves or goes only with its twin, along the seam: both ends of a boundary edge
    /// have twins that are the ends of another boundary edge, and the two edges collapse in
    /// the same step to the same position (the plan's quadric is the four ends'). Which end
    /// goes is decided on the side whose smaller end is the smaller id, so that the plan is
    /// the same from either side. A seam vertex beside a junction goes into it with its
    /// twin, which goes into the junction's copy on its side, both unmoved.
    fn seam_sides(
        &self,
        remove: u32,
        keep: u32,
        free: bool,
        along_boundary: bool,
    ) -> Option<(u32, u32, Option<[u32; 2]>)> {
        match (self.twin(remove), self.twin(keep)) {
            (None, None) => Some((remove, keep, None)),
            (None, Some(_)) if !free => Some((remove, keep, None)),
            // Into a junction's copy along a seam: the other side's edge goes into its own
            // copy, so that the two sides stay together.
            (Some(r2), None) if along_boundary && self.kind(keep) == Kind::Anchored => {
                let k2 = self.anchor_copy(r2, keep)??;
                let owned = self.owns(k2);
                if !(r2 != keep && k2 != remove && owned && self.kind(r2) == Kind::Boundary) {
                    return None;
                }
                Some((remove, keep, Some([r2, k2])))
            }
            (Some(r2), Some(k2)) if free && along_boundary => {
                let distinct = r2 != keep && k2 != remove && r2 != k2;
                let owned = self.owns(r2) && self.owns(k2);
                if !(distinct
                    && owned
                    && self.kind(r2) == Kind::Boundary
                    && self.kind(k2) == Kind::Boundary
                    && self.edge_triangles(r2, k2) == 1)
                {
                    return None;
                }
                // `remove` is the smaller end of its edge (plans are asked as (min, max)).
                if remove < r2.min(k2) {
                    Some((remove, keep, Some([r2, k2])))
                } else {
                    let (r2, k2) = (r2.min(k2), r2.max(k2));
                    let (r, k) = (self.twin(r2)?, self.twin(k2)?);
                    Some((r, k, Some([r2, k2])))
                }
            }
            _ => None,
        }
    }

    /// `x` and the other vertices at its position that stand for the same point of the
    /// surface: its twin across a seam, or a junction's other copies.
    pub fn copies(&self, x: u32) -> impl Iterator<Item = u32> + '_ {
        crate::mesh::seams::copies(x, self.twins, self.copies)
    }

    /// The copy of the anchored `anchor` (a texture-seam junction's, see [`Self::copies`])
    /// that `x` is joined to by a boundary edge: the junction on `x`'s side, or `Some(None)`
    /// when there is none; `None` when `x`'s fan is not all this part's.
    pub fn anchor_copy(&self, x: u32, anchor: u32) -> Option<Option<u32>> {
        let fan_owned = self.owns(x)
            && self.conn.has_room(x, 0)
            && (self.conn.incident(x).iter()).all(|&t| self.conn.owns_slot(t));
        fan_owned.then(|| {
            self.copies(anchor).find(|&c| {
                self.owns(c) && self.kind(c) == Kind::Anchored && self.edge_triangles(x, c) == 1
            })
        })
    }

    /// The other sides of the seam vertices in the fans [`Self::gather`] read (with
    /// `both_sides`, also in the other side's, [`Self::gather_twin`]), with repeats.
    pub fn seam_neighbours_twins(&self, both_sides: bool) -> impl Iterator<Item = u32> + '_ {
        let s = &self.scratch;
        let twin_fans = both_sides.then_some(&s.twin_fans);
        (s.fans.iter().chain(twin_fans.into_iter().flatten()))
            .flatten()
            .flat_map(|f| [f.next, f.prev])
            .filter_map(|x| self.twin(x))
    }

    /// Swaps the ends and fans [`Self::gather`] read with the other side's of a seam
    /// collapse, so that the checks and the collapse work on either side.
    pub fn swap_sides(&mut self) {
        let s = &mut self.scratch;
        std::mem::swap(&mut s.ends, &mut s.twin_ends);
        std::mem::swap(&mut s.fans, &mut s.twin_fans);
    }

    /// As [`Self::gather`], for a seam collapse's other side (`v`–`w`, the twins of the
    /// first side's ends), into the other side's scratch.
    pub fn gather_twin(&mut self, v: u32, w: u32) -> bool {
        self.swap_sides();
        let owned = self.gather(v, w);
        self.swap_sides();
        owned
    }

    /// True when the two sides of a seam collapse (read by [`Self::gather`] and
    /// [`Self::gather_twin`]) share no vertex, so that each collapse leaves the other's fans
    /// as they were read. Seams only: the lists are short, searched linearly.
    pub fn sides_apart(&self) -> bool {
        let s = &self.scratch;
        let corners = |fans: &[Vec<FanTriangle>; 2]| {
            fans.iter()
                .flatten()
                .flat_map(|f| [f.next, f.prev])
                .collect::<Vec<_>>()
        };
        let first = corners(&s.fans);
        corners(&s.twin_fans)
            .iter()
            .all(|x| !s.ends.contains(x) && !first.contains(x))
    }

    /// The quadric's minimum when it exists and stays within a box around the edge `pr`–`pk`;
    /// otherwise the best of the kept end, the removed end and the midpoint.
    #[inline(always)]
    fn place(&self, q: &Quadric, pr: DVec3, pk: DVec3) -> DVec3 {
        let margin = DVec3::splat(BOX_MARGIN * (pk - pr).length());
        let (lo, hi) = (pr.min(pk) - margin, pr.max(pk) + margin);
        if let Some(p) = q.minimum() {
            if p.cmpge(lo).all() && p.cmple(hi).all() {
                return p;
            }
        }
        let mut best = pk;
        let mut best_error = q.eval(pk);
        for p in [pr, 0.5 * (pr + pk)] {
            let e = q.eval(p);
            if e < best_error {
                best = p;
                best_error = e;
            }
        }
        best
    }

    /// Where the kept vertex's attributes are taken along the edge, from the kept end (0) to
    /// the removed one (1): at the projection of its new position on the edge.
    pub fn edge_fraction(&self, plan: &Plan) -> f32 {
        let (pr, pk) = (self.position(plan.remove), self.position(plan.keep));
        fraction(plan.position, pr, pk)
    }

    /// The kept vertex's texture coordinates after the collapse `plan` (`None` without
    /// texture coordinates): the plan's, or interpolated along the edge as the colours are.
    pub fn new_texcoords(&self, plan: &Plan) -> Option<[f32; 2]> {
        let t = self.texcoords.as_deref()?;
        plan.texcoords.or_else(|| {
            let s = self.edge_fraction(plan);
            let [r, k] = [plan.remove, plan.keep].map(|v| glam::Vec2::from(t[self.at(v)]));
            Some((k + s * (r - k)).to_array())
        })
    }

    /// Performs a legal collapse of the edge [`Self::gather`] read last; the kept vertex's
    /// edges are left to be re-planned.
    pub fn collapse(&mut self, plan: &Plan) {
        let (r, k) = (self.at(plan.remove), self.at(plan.keep));
        let (pr, pk) = (self.position(plan.remove), self.position(plan.keep));
        let s = self.edge_fraction(plan);
        let lerp = |x: [f32; 3], y: [f32; 3]| {
            (Vec3::from_array(y) + s * (Vec3::from_array(x) - Vec3::from_array(y))).to_array()
        };
        let colors_before = self.colors.as_deref().map(|c| (c[k], c[r]));
        let normals_before = self.normals.as_deref().map(|n| (n[k], n[r]));
        let texcoords_before = self.texcoords.as_deref().map(|t| (t[k], t[r]));
        let colour = (self.colour_quadrics.as_deref()).map(|q| {
            let side = q[r].sum(&q[k]);
            self.colour_at(&side, [plan.remove, plan.keep], plan.position)
        });
        if let Some(c) = self.colors.as_deref_mut() {
            c[k] = colour.unwrap_or_else(|| lerp(c[r], c[k]));
        }
        if let Some(n) = self.normals.as_deref_mut() {
            n[k] = Vec3::from_array(lerp(n[r], n[k]))
                .normalize_or_zero()
                .to_array();
        }
        let new_texcoords = self.new_texcoords(plan);
        if let (Some(t), Some(uv)) = (self.texcoords.as_deref_mut(), new_texcoords) {
            t[k] = uv;
        }
        // Topology: the edge's triangles go, the removed end's others are renamed in place,
        // so per-face attributes stay with their faces and no slot is ever reused.
        let CollapseLists {
            ends,
            fans,
            renamed,
            deleted,
            ..
        } = &mut self.scratch;
        let fan = &fans[usize::from(ends[0] != plan.remove)];
        self.conn
            .collapse_edge(plan.remove, plan.keep, fan, renamed, deleted);
        for &t in renamed.iter() {
            self.costs.set_corners(t, self.conn.triangle(t));
        }
        if let Some(recorder) = self.recorder.as_deref_mut() {
            recorder.collapse(CollapseRecord {
                keep: plan.keep,
                remove: plan.remove,
                keep_before: pk.as_vec3(),
                keep_after: plan.position.as_vec3(),
                removed_position: pr.as_vec3(),
                colors: colors_before
                    .zip(self.colors.as_deref())
                    .map(|((ck, cr), c)| [ck, c[k], cr]),
                normals: normals_before
                    .zip(self.normals.as_deref())
                    .map(|((nk, nr), n)| [nk, n[k], nr].map(Vec3::from_array)),
                texcoords: texcoords_before
                    .zip(self.texcoords.as_deref())
                    .map(|((tk, tr), t)| [tk, t[k], tr]),
                renamed: &self.scratch.renamed,
                deleted: &self.scratch.deleted,
            });
        }
        let q = self.quadrics[k].at(pk).sum(&self.quadrics[r].at(pr));
        self.positions[k] = plan.position.as_vec3();
        self.quadrics[k] = LocalQuadric::new(&q, self.positions[k].as_dvec3());
        let surface = self.input_surface[r];
        self.input_surface[k] += surface;
        if let Some(t) = self.texture_quadrics.as_deref_mut() {
            let q = t[r];
            t[k].add(&q);
        }
        if let Some(c) = self.colour_quadrics.as_deref_mut() {
            let q = c[r];
            c[k].add(&q);
        }
        self.kinds[r] = Kind::Fixed;
        self.settle_complex(plan);
    }

    /// Re-classifies the complex vertices a collapse touched, the kept end and the edge's
    /// apexes: one whose neighbourhood became a single fan (a doubled flap collapsed away,
    /// the third sheet of an edge gone) is interior or boundary from now on, its quadric as
    /// it stands (its outline's planes are in already). Those are left in
    /// `scratch.settled`. A vertex whose fan is not all this part's stays complex.
    fn settle_complex(&mut self, plan: &Plan) {
        let mut settled = std::mem::take(&mut self.scratch.settled);
        let mut ring = std::mem::take(&mut self.scratch.settle_ring);
        settled.clear();
        let (fan_r, _) = self.scratch.fans(plan);
        let keep = plan.keep;
        settled.push(keep);
        settled.extend((fan_r.iter().filter(|f| f.touches(keep))).map(|f| {
            if f.next == keep {
                f.prev
            } else {
                f.next
            }
        }));
        settled.retain(|&x| {
            let owned = self.owns(x)
                && self.kind(x) == Kind::Complex
                && self.conn.has_room(x, 0)
                && (self.conn.incident(x).iter()).all(|&t| self.conn.owns_slot(t));
            let kind = match owned.then(|| self.conn.ring(x, &mut ring)) {
                Some(RingShape::Closed) => Kind::Interior,
                Some(RingShape::Open) => Kind::Boundary,
                _ => return false,
            };
            let i = self.at(x);
            self.kinds[i] = kind;
            true
        });
        self.scratch.settled = settled;
        self.scratch.settle_ring = ring;
    }
}

/// The point of the segment `pk`–`pr` where `q` is least (a quadric is a parabola along a
/// line: fitted through its ends and midpoint).
fn along_crease(q: &Quadric, pr: DVec3, pk: DVec3) -> DVec3 {
    let at = |t: f64| pk + t * (pr - pk);
    let (f0, fh, f1) = (q.eval(at(0.0)), q.eval(at(0.5)), q.eval(at(1.0)));
    at(parabola_minimum(f0, fh, f1))
}

/// Where in 0..=1 the parabola through `(0, f0)`, `(½, fh)` and `(1, f1)` is least: its
/// vertex when it opens upwards (clamped), else the lower end.
pub(super) fn parabola_minimum(f0: f64, fh: f64, f1: f64) -> f64 {
    let a = 2.0 * (f1 + f0 - 2.0 * fh);
    let b = f1 - f0 - a;
    if a > 0.0 {
        (-b / (2.0 * a)).clamp(0.0, 1.0)
    } else if f1 < f0 {
        1.0
    } else {
        0.0
    }
}

/// Where `p` projects on the edge from `pk` (0) to `pr` (1), clamped to the edge.
fn fraction(p: DVec3, pr: DVec3, pk: DVec3) -> f32 {
    let edge = pr - pk;
    if edge.length_squared() > 0.0 {
        ((p - pk).dot(edge) / edge.length_squared()).clamp(0.0, 1.0) as f32
    } else {
        0.0
    }
}

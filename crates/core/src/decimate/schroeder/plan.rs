//! Planning one vertex removal, reading the mesh only: classify the vertex, measure its
//! decimation criterion, fill its hole by loop splitting and check the fill. Nothing here
//! writes the mesh, so many removals are planned at once on all cores (`removal_passes`), each
//! into its own [`Planning`].

use glam::{DVec2, DVec3, Vec3};

use super::input_surface::{InputCorners, InputSurface};
use super::loop_split;
use super::sheets::{self, Sheets};
use crate::mesh::classify::{classify, classify_ring, RingGeometry, VertexClass};
use crate::mesh::seams::position_key;
use crate::mesh::topology::{Adjacency, Ring, RingShape};

/// A fill is rejected when a new triangle's area is this small relative to its longest edge².
const MIN_RELATIVE_AREA: f64 = 1e-10;

/// A fill is rejected when a new triangle's area in the texture is this small relative to
/// the area there of the old triangles it replaces.
const MIN_TEXTURE_AREA: f64 = 1e-6;

/// What planning one removal writes: the vertex's ring and its geometry, then the fill.
#[derive(Debug, Clone, Default)]
pub(super) struct Planning {
    pub ring: Ring,
    pub geometry: RingGeometry,
    /// The triangles that fill the hole.
    pub fill: Vec<[u32; 3]>,
    /// Per triangle of `fill`: the input surface it stands for (see [`InputSurface`]).
    pub fill_input: Vec<Vec3>,
    /// Which ring triangles each stretch of `fill` replaces: one region for a closed or open
    /// ring, one per side of a crease.
    regions: Vec<FillRegion>,
    loop_buf: Vec<u32>,
    triangulation: loop_split::SplitBuffers,
    /// A complex vertex's fans (`sheets`).
    sheets: Sheets,
    /// The fans' fills' input surfaces, gathered while each fan is filled.
    sheets_input: Vec<Vec3>,
    /// The input surface of each old triangle of the region being checked, read once.
    old_input: Vec<DVec3>,
    /// A ring closed at a seam junction (`Surface::close_at_junction`): the copy left out.
    junction: Option<u32>,
    /// Whether the vertex last evaluated classified as a corner as its ring stands (before
    /// a junction closes it or a fold splits it): what the early relaxation counts.
    pub corner: bool,
}

/// The fill triangles from the previous region's `end` up to this `end` replace the ring
/// triangles `from..to` (indices modulo the ring's length).
#[derive(Debug, Clone, Copy)]
struct FillRegion {
    end: usize,
    from: usize,
    to: usize,
}

/// The mesh as planning reads it: the whole, or a region's part (which must own the
/// vertex planned, its ring and their triangles: see `region_removal`).
pub(super) struct Surface<'a, C> {
    pub conn: &'a C,
    pub positions: &'a [Vec3],
    /// One pair per vertex, when the model has texture coordinates.
    pub texcoords: Option<&'a [[f32; 2]]>,
    pub cos_feature: f64,
    /// Whether a folded ring may be filled: split along its sharpest turns, its triangles
    /// folded back against it left out of the flip check (docs/design.md#schroeder-folds).
    pub unfold: bool,
    /// The two sides of texture seams, on the whole mesh when the model has any; `None` in
    /// a region, which leaves removals next to a seam to the whole mesh.
    pub seams: Option<SeamSides<'a>>,
    /// The input surface each triangle slot stands for, and the input at each vertex.
    pub input: InputSurface<'a>,
    pub corners: &'a InputCorners,
}

/// Each seam vertex's other side (`u32::MAX`: none) and the pinned vertices (seam
/// junctions, shared borders), by vertex id.
#[derive(Debug, Clone, Copy)]
pub(super) struct SeamSides<'a> {
    pub twins: &'a [u32],
    pub pinned: &'a [bool],
    /// Pinned vertices' next copy at their position (`mesh::seams::copy_cycles`).
    pub copies: &'a [u32],
    /// Junction copies' starting normals (`mesh::seams::junction_normals`).
    pub facing: &'a [Vec3],
}

impl<'a> SeamSides<'a> {
    /// `v`'s other side, when it has one.
    pub fn twin(&self, v: u32) -> Option<u32> {
        self.twins
            .get(v as usize)
            .copied()
            .filter(|&w| w != u32::MAX)
    }

    /// On a seam: with a twin, or pinned (a junction's copy, a shared border).
    pub fn on_seam(&self, v: u32) -> bool {
        self.twin(v).is_some() || self.pinned.get(v as usize).copied().unwrap_or(false)
    }

    /// `v` and the other vertices standing for its point: its twin, a junction's copies.
    pub fn copies(self, v: u32) -> impl Iterator<Item = u32> + 'a {
        crate::mesh::seams::copies(v, self.twins, self.copies)
    }

    /// Every pair of a copy of `x` and a copy of `y` (see [`Self::copies`]), `(x, y)` first.
    pub fn copy_pairs(self, x: u32, y: u32) -> impl Iterator<Item = (u32, u32)> + 'a {
        self.copies(x)
            .flat_map(move |x2| self.copies(y).map(move |y2| (x2, y2)))
    }
}

impl<C: Adjacency> Surface<'_, C> {
    /// Classifies `v` into `p`'s ring and returns its class and decimation criterion:
    /// distance to the loop's average plane (simple), or to the line through its boundary /
    /// feature neighbours (boundary, interior edge), or for a complex vertex that may go
    /// through its fans (`sheets`), to the line its fans close on (the largest of them at a
    /// bowtie). `None` for vertices that are never removed.
    pub fn evaluate(&self, v: u32, p: &mut Planning) -> Option<(VertexClass, f64)> {
        let seam_side = self.seams.is_some_and(|s| s.twin(v).is_some());
        let mut class = classify(
            self.conn,
            self.positions,
            v,
            self.cos_feature,
            seam_side,
            &mut p.ring,
            &mut p.geometry,
        );
        p.corner = class == VertexClass::Corner;
        p.junction = None;
        if self.close_at_junction(v, p) {
            let (closed, ring) = (RingShape::Closed, &p.ring);
            class = classify_ring(
                self.positions,
                v,
                self.cos_feature,
                false,
                closed,
                ring,
                &mut p.geometry,
            );
        }
        // A folded ring cannot be filled in one piece: a crease along its sharpest turns.
        if class == VertexClass::Simple && self.unfold {
            if let Some((first, second)) = fold_line(&p.geometry) {
                class = VertexClass::InteriorEdge { first, second };
            }
        }
        let at = self.position(v);
        let verts = &p.ring.verts;
        let distance = match class {
            VertexClass::Simple => {
                let all = 0..p.geometry.crosses.len();
                let (normal, centre) = self.average_plane(p, at, all)?;
                normal.dot(at - centre).abs()
            }
            VertexClass::Boundary => self.line_distance(at, verts[0], verts[verts.len() - 1]),
            VertexClass::InteriorEdge { first, second } => {
                self.line_distance(at, verts[first], verts[second])
            }
            VertexClass::Complex => self.sheets_distance(v, p)?,
            // A dangling flap's apex goes like a boundary vertex of one triangle.
            VertexClass::Corner => {
                let (a, b) = sheets::flap_apex(self.conn, v)?;
                return Some((VertexClass::Boundary, self.line_distance(at, a, b)))
                    .filter(|(_, d)| d.is_finite());
            }
            _ => return None,
        };
        distance.is_finite().then_some((class, distance))
    }

    /// Closes `v`'s open ring when its two ends are copies of one seam junction (a
    /// textured sphere's pole, a cone's apex; `v` has no twin and is not pinned): welded,
    /// `v` is an interior vertex. The first end is left out of the ring, the last stands
    /// for both, so the fill uses it and the other copy loses its triangle with `v`
    /// (docs/design.md#texture-seams).
    fn close_at_junction(&self, v: u32, p: &mut Planning) -> bool {
        let Some(seams) = self.seams else {
            return false;
        };
        let pinned = |x: u32| seams.pinned.get(x as usize).copied().unwrap_or(false);
        let r = &p.ring;
        if seams.twin(v).is_some()
            || pinned(v)
            || r.verts.len() != r.triangles.len() + 1
            || r.triangles.len() < 3
        {
            return false;
        }
        let (first, last) = (r.verts[0], r.verts[r.verts.len() - 1]);
        let key = |x: u32| position_key(self.positions[x as usize]);
        if first == last || !pinned(first) || !pinned(last) || key(first) != key(last) {
            return false;
        }
        p.ring.verts.remove(0);
        p.ring.triangles.rotate_left(1);
        p.junction = Some(first);
        true
    }

    /// A complex vertex's criterion when it may go through its fans, each by the rules of
    /// a manifold vertex: an open fan has no feature edge inside and does not turn sharply
    /// at `v` (boundary), a closed one has at most one feature edge (simple). The largest
    /// of the fans' distances: to the line an open fan closes on, to a closed fan's average
    /// plane.
    fn sheets_distance(&self, v: u32, p: &mut Planning) -> Option<f64> {
        p.sheets.split(self.conn, v)?;
        let at = self.position(v);
        let mut distance = 0.0f64;
        for i in 0..p.sheets.count() {
            if p.sheets.is_fin_flap(i) {
                // Dropped: its corners stay on the surface but `v`, whose distance the
                // closed fan beside it measures.
                continue;
            }
            let (first, last, closed) = self.take_fan(v, i, p);
            let RingGeometry { crosses, lengths } = &p.geometry;
            let k = crosses.len();
            let is_feature = |j: usize, l: usize| {
                let len = lengths[j] * lengths[l];
                len > 0.0 && crosses[j].dot(crosses[l]) < self.cos_feature * len
            };
            let fan_distance = if closed {
                if (0..k).filter(|&j| is_feature(j, (j + 1) % k)).count() > 1 {
                    return None;
                }
                let (normal, centre) = self.average_plane(p, at, 0..k)?;
                normal.dot(at - centre).abs()
            } else {
                if (1..k).any(|j| is_feature(j - 1, j)) || self.sharp_turn(at, first, last) {
                    return None;
                }
                // On a crease line every fan closes on the same line.
                self.line_distance(at, first, last)
            };
            distance = distance.max(fan_distance);
        }
        Some(distance)
    }

    /// Puts fan `i` of `v` (`p.sheets`) in `p`'s ring and geometry, as a manifold ring:
    /// its ends and whether it is closed (then its path's repeated end is dropped).
    fn take_fan(&self, v: u32, i: usize, p: &mut Planning) -> (u32, u32, bool) {
        let (path, triangles) = p.sheets.fan(i);
        let (first, last) = (path[0], path[path.len() - 1]);
        let closed = first == last;
        fan_geometry(self.positions, v, path, &mut p.geometry);
        p.ring.verts.clear();
        p.ring
            .verts
            .extend_from_slice(&path[..path.len() - usize::from(closed)]);
        p.ring.triangles.clear();
        p.ring.triangles.extend_from_slice(triangles);
        (first, last, closed)
    }

    /// Whether the line `a`–`at`–`b` turns by more than the feature angle at `at`.
    fn sharp_turn(&self, at: DVec3, a: u32, b: u32) -> bool {
        let d1 = (at - self.position(a)).normalize_or_zero();
        let d2 = (self.position(b) - at).normalize_or_zero();
        d1.dot(d2) < self.cos_feature
    }

    /// Plans the removal of `v` into `p` (its ring and the fill): its class and criterion
    /// distance when the hole can be filled validly.
    pub fn plan_removal(&self, v: u32, p: &mut Planning) -> Option<(VertexClass, f64)> {
        let (class, distance) = self.evaluate(v, p)?;
        p.fill.clear();
        p.regions.clear();
        let ok = match class {
            VertexClass::Simple => self.fill_closed(v, p) && self.fill_is_valid(v, p),
            VertexClass::Boundary => self.fill_open(v, p) && self.fill_is_valid(v, p),
            VertexClass::InteriorEdge { first, second } => {
                self.fill_crease(v, first, second, p) && self.fill_is_valid(v, p)
            }
            VertexClass::Complex => self.fill_sheets(v, p),
            _ => false,
        };
        ok.then_some((class, distance))
    }

    /// Complex vertex: each fan filled and checked on its own, an open one as a boundary
    /// vertex's ring closed by the edge between its ends (on a crease line the same edge
    /// for every fan, which must not exist yet), a closed one as a simple vertex's. Leaves
    /// in `p` the whole removal: every neighbour, every triangle, every fan's fill.
    fn fill_sheets(&self, v: u32, p: &mut Planning) -> bool {
        let mut fill = std::mem::take(&mut p.sheets.fill);
        fill.clear();
        let mut input = std::mem::take(&mut p.sheets_input);
        input.clear();
        let mut ok = true;
        let (mut filled_across, mut flaps) = (0, 0);
        for i in 0..p.sheets.count() {
            let (_, _, closed) = self.take_fan(v, i, p);
            p.fill.clear();
            p.regions.clear();
            if p.sheets.is_fin_flap(i) {
                // A fin's flap `(v, a, x)`: dropped, its edge a–x keeps a triangle each way.
                let r = &p.ring.verts;
                if !sheets::keeps_both_sides(self.conn, r[0], r[1], v) {
                    ok = false;
                    break;
                }
                continue;
            }
            if p.ring.triangles.len() == 1 {
                flaps += 1; // a crease line's flap `(v, a, b)`: dropped, the others close on a–b
                continue;
            }
            filled_across += usize::from(!closed);
            let filled = if closed {
                self.fill_closed(v, p)
            } else {
                self.fill_open(v, p)
            };
            if !(filled && self.fill_is_valid(v, p)) {
                ok = false;
                break;
            }
            fill.extend_from_slice(&p.fill);
            input.extend_from_slice(&p.fill_input);
        }
        // Dropping a flap leaves its edge a–b to the other fans: two or more, or it would
        // open a border.
        ok &= flaps == 0 || filled_across >= 2;
        std::mem::swap(&mut p.fill, &mut fill);
        p.sheets.fill = fill;
        std::mem::swap(&mut p.fill_input, &mut input);
        p.sheets_input = input;
        p.regions.clear();
        p.ring.verts.clear();
        p.ring.verts.extend(p.sheets.neighbours());
        p.ring.triangles.clear();
        p.ring.triangles.extend_from_slice(p.sheets.all_triangles());
        ok
    }

    fn position(&self, v: u32) -> DVec3 {
        self.positions[v as usize].as_dvec3()
    }

    /// Interior vertex: triangulate the whole closed loop over its average plane.
    fn fill_closed(&self, v: u32, p: &mut Planning) -> bool {
        let all = 0..p.geometry.crosses.len();
        let Some((normal, _)) = self.average_plane(p, self.position(v), all) else {
            return false;
        };
        let r = &p.ring.verts;
        // Closed at a junction, its last vertex stands for all the junction's copies.
        let at_junction = |c: u32| self.conn.has_triangle(c, r[0], r[1]);
        let doubled =
            || p.junction.is_some() && self.seams.is_some_and(|s| s.copies(r[2]).any(at_junction));
        if r.len() == 3 && (self.conn.has_triangle(r[0], r[1], r[2]) || doubled()) {
            return false; // would duplicate a face: the last step before a tetrahedron
        }
        self.fill_whole_ring(normal, p)
    }

    /// Triangulates the whole ring over the plane of `normal`, as one region.
    fn fill_whole_ring(&self, normal: DVec3, p: &mut Planning) -> bool {
        let filled = loop_split::triangulate(
            self.positions,
            &p.ring.verts,
            normal,
            &mut p.fill,
            &mut p.triangulation,
        );
        p.regions.push(FillRegion {
            end: p.fill.len(),
            from: 0,
            to: p.ring.triangles.len(),
        });
        filled
    }

    /// Boundary vertex: the open path plus the closing edge between its ends.
    fn fill_open(&self, v: u32, p: &mut Planning) -> bool {
        let r = &p.ring.verts;
        let (first, last) = (r[0], r[r.len() - 1]);
        if r.len() == 2 {
            // A lone triangle: removing it leaves its far edge on the boundary, which must
            // then still belong to another triangle.
            return self.conn.has_edge_avoiding(first, last, v);
        }
        if self.conn.has_edge_avoiding(first, last, v) {
            return false;
        }
        let all = 0..p.geometry.crosses.len();
        let Some((normal, _)) = self.average_plane(p, self.position(v), all) else {
            return false;
        };
        self.fill_whole_ring(normal, p)
    }

    /// Interior-edge vertex: split along the crease first, then fill each side on its own
    /// average plane, so the crease line survives.
    fn fill_crease(&self, v: u32, first: usize, second: usize, p: &mut Planning) -> bool {
        let r = &p.ring.verts;
        let k = r.len();
        if second - first < 2 || k - second + first < 2 {
            return false; // one side is a single triangle: no room to split
        }
        if self.conn.has_edge_avoiding(r[first], r[second], v) {
            return false;
        }
        let at = self.position(v);
        let sides = [(first, second), (second, first + k)];
        for (from, to) in sides {
            let Some((normal, _)) = self.average_plane(p, at, (from..to).map(|i| i % k)) else {
                return false;
            };
            let Planning {
                ring,
                fill,
                loop_buf,
                triangulation,
                ..
            } = p;
            loop_buf.clear();
            loop_buf.extend((from..=to).map(|i| ring.verts[i % k]));
            if !loop_split::triangulate(self.positions, loop_buf, normal, fill, triangulation) {
                return false;
            }
            p.regions.push(FillRegion {
                end: p.fill.len(),
                from,
                to,
            });
        }
        true
    }

    /// The fill must not flip or degenerate a triangle (against the old triangles and the
    /// input surface they stand for) and must not create an edge that already exists
    /// elsewhere (the result would be non-manifold); each new triangle's share of the input
    /// surface goes to `p.fill_input`. A new triangle is
    /// compared with the old triangles of its own region only: across a crease the two sides
    /// may face apart by up to 180°.
    fn fill_is_valid(&self, v: u32, p: &mut Planning) -> bool {
        let mut fill_input = std::mem::take(&mut p.fill_input);
        let mut old_input = std::mem::take(&mut p.old_input);
        fill_input.clear();
        let valid = self.fill_checks(v, p, &mut fill_input, &mut old_input);
        p.fill_input = fill_input;
        p.old_input = old_input;
        valid
    }

    /// [`Self::fill_is_valid`]'s checks; each fill triangle's input surface into `fill_input`
    /// (`old_input` is scratch).
    fn fill_checks(
        &self,
        v: u32,
        p: &Planning,
        fill_input: &mut Vec<Vec3>,
        old_input: &mut Vec<DVec3>,
    ) -> bool {
        let k = p.ring.verts.len();
        let crosses = &p.geometry.crosses;
        let slots = &p.ring.triangles;
        let mut start = 0;
        for &region in &p.regions {
            // Normal of the old region: the sum of its ring triangles' area vectors; and
            // the input surface they stand for.
            let old: DVec3 = (region.from..region.to).map(|i| crosses[wrap(i, k)]).sum();
            old_input.clear();
            old_input.extend((region.from..region.to).map(|i| self.input.of(slots[wrap(i, k)])));
            let input: DVec3 = old_input.iter().sum();
            if !self.fill_keeps_texture(v, p, region, &p.fill[start..region.end]) {
                return false;
            }
            let mut area = 0.0;
            for tri in &p.fill[start..region.end] {
                let [a, b, c] = tri.map(|i| self.position(i));
                let cross = (b - a).cross(c - a);
                let longest = (b - a)
                    .length_squared()
                    .max((c - b).length_squared())
                    .max((a - c).length_squared());
                if cross.length() <= MIN_RELATIVE_AREA * longest {
                    return false;
                }
                // Flip test against the old triangles this one covers: it must face the same
                // way as at least the region as a whole and as the nearest old triangle.
                if cross.dot(old) <= 0.0
                    || !faces_like_old(p, cross, tri, region, self.unfold.then_some(old))
                {
                    return false;
                }
                // Nor against the input surface (what the region stands for, and some
                // input triangle at a corner): checks against the current triangles alone
                // let turns add up over removals in a row.
                if cross.dot(input) <= 0.0 || !self.corners.faces(cross, tri) {
                    return false;
                }
                area += cross.length();
                fill_input.push(Vec3::splat(cross.length() as f32));
                // A junction never moves: a triangle at one faces the way it faced.
                if !self.faces_like_junction(cross, tri) {
                    return false;
                }
                if !self.diagonals_allowed(v, tri, p) {
                    return false;
                }
            }
            share_input(
                p,
                region,
                &p.fill[start..region.end],
                old_input,
                area,
                &mut fill_input[start..region.end],
            );
            start = region.end;
        }
        true
    }

    /// Whether fill triangle `tri`'s new edges (the hole's diagonals) may be made: none is
    /// an edge already, joins a seam's two sides or joins copies joined elsewhere. A diagonal
    /// is in two fill triangles, once each way: looked up once. (The edge closing an open
    /// ring and a crease's split edge, in one triangle, were looked up before the fill was
    /// made.)
    fn diagonals_allowed(&self, v: u32, tri: &[u32; 3], p: &Planning) -> bool {
        let r = &p.ring.verts;
        let k = r.len();
        let closed = k == p.ring.triangles.len();
        let is_ring_edge = |a: u32, b: u32| {
            let (Some(i), Some(j)) = (
                r.iter().position(|&x| x == a),
                r.iter().position(|&x| x == b),
            ) else {
                return false;
            };
            let d = i.abs_diff(j);
            d == 1 || (closed && d == k - 1)
        };
        for (x, y) in [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])] {
            if x > y || is_ring_edge(x, y) {
                continue;
            }
            if self.conn.has_edge_avoiding(x, y, v) {
                return false;
            }
            // An open ring's closing edge lies on the outline: on a seam, the other side's
            // removal closes its hole with the same edge.
            let closing = !closed && is_ring_end(r, x) && is_ring_end(r, y);
            if !closing && self.joins_seam_sides(x, y) {
                return false;
            }
            // Welded, no other copies of the two may be joined already (at a junction, its
            // copies are joined to much of the ring).
            if !closing && self.joined_elsewhere(v, x, y) {
                return false;
            }
        }
        true
    }

    /// Whether a new edge `x`–`y` inside one side of a texture seam would meet an edge of
    /// its ends' other copies (their twins, a junction's other copies): welded, as a viewer
    /// shows the model, that edge would have four triangles or more.
    pub fn joins_seam_sides(&self, x: u32, y: u32) -> bool {
        let Some(seams) = self.seams else {
            return false;
        };
        if !(seams.on_seam(x) && seams.on_seam(y)) {
            return false;
        }
        seams
            .copy_pairs(x, y)
            .any(|(x2, y2)| (x2, y2) != (x, y) && self.conn.has_edge_avoiding(x2, y2, u32::MAX))
    }

    /// Whether a triangle of normal `cross` at the corners `tri` faces, at each junction
    /// copy among them, the way the junction faced at the start (docs/design.md#texture-seams).
    fn faces_like_junction(&self, cross: DVec3, tri: &[u32; 3]) -> bool {
        self.seams.is_none_or(|seams| {
            tri.iter().all(|&c| {
                seams.copies.get(c as usize).is_none_or(|&n| n == u32::MAX)
                    || seams
                        .facing
                        .get(c as usize)
                        .is_none_or(|f| cross.dot(f.as_dvec3()) > 0.0)
            })
        })
    }

    /// Whether a copy of `x` (its twin, a junction's copies) and a copy of `y` other than
    /// the two are joined by an edge of a triangle without `v`.
    fn joined_elsewhere(&self, v: u32, x: u32, y: u32) -> bool {
        self.seams.is_some_and(|seams| {
            (seams.on_seam(x) || seams.on_seam(y))
                && seams
                    .copy_pairs(x, y)
                    .any(|(x2, y2)| (x2, y2) != (x, y) && self.conn.has_edge_avoiding(x2, y2, v))
        })
    }

    /// With texture coordinates, the `fill` of `region` faces in the texture the way the
    /// old triangles it replaces did together, each new triangle with some area there:
    /// otherwise the image would show mirrored or smeared across it. A region with no area
    /// in the texture already is left alone.
    fn fill_keeps_texture(
        &self,
        v: u32,
        p: &Planning,
        region: FillRegion,
        fill: &[[u32; 3]],
    ) -> bool {
        let Some(t) = self.texcoords else {
            return true;
        };
        let uv = |x: u32| {
            let [u, v] = t[x as usize];
            DVec2::new(f64::from(u), f64::from(v))
        };
        let area = |[a, b, c]: [u32; 3]| (uv(b) - uv(a)).perp_dot(uv(c) - uv(a));
        let r = &p.ring.verts;
        let k = r.len();
        let old: f64 = (region.from..region.to)
            .map(|i| area([v, r[i % k], r[(i + 1) % k]]))
            .sum();
        old == 0.0
            || fill
                .iter()
                .all(|&tri| area(tri) * old.signum() > MIN_TEXTURE_AREA * old.abs())
    }

    /// Area-weighted unit normal and centre of the ring triangles `indices` (of the ring in
    /// `p`) around the vertex at `at`.
    fn average_plane(
        &self,
        p: &Planning,
        at: DVec3,
        indices: impl Iterator<Item = usize>,
    ) -> Option<(DVec3, DVec3)> {
        let verts = &p.ring.verts;
        let mut normal = DVec3::ZERO;
        let mut centre = DVec3::ZERO;
        let mut area = 0.0;
        for i in indices {
            let a = p.geometry.lengths[i];
            normal += p.geometry.crosses[i];
            let pa = self.position(verts[i]);
            let next = verts.get(i + 1).unwrap_or(&verts[0]);
            let pb = self.position(*next);
            centre += a * (at + pa + pb);
            area += a;
        }
        let centre = centre / 3.0;
        let len = normal.length();
        if area <= 0.0 || len <= 1e-12 * area {
            return None;
        }
        Some((normal / len, centre / area))
    }

    /// Distance from `at` to the line through vertices `a` and `b`.
    fn line_distance(&self, at: DVec3, a: u32, b: u32) -> f64 {
        let (a, b) = (self.position(a), self.position(b));
        let dir = b - a;
        let len2 = dir.length_squared();
        if len2 <= 0.0 {
            return (at - a).length();
        }
        (at - a).cross(dir).length() / len2.sqrt()
    }
}

/// Gives each new triangle of `region` (`fill`, the lengths of whose area vectors are in
/// `shares`, `area` in all) its share of the input surface the region's old slots stand
/// for (`old_input`, in region order): half by area, half the input of the old triangles
/// whose outer edge it takes (each old triangle's outer edge is in one new triangle), so the
/// total is kept and stays local (docs/design.md#schroeder-input-surface).
fn share_input(
    p: &Planning,
    region: FillRegion,
    fill: &[[u32; 3]],
    old_input: &[DVec3],
    area: f64,
    shares: &mut [Vec3],
) {
    let r = &p.ring.verts;
    let k = r.len();
    let input: DVec3 = old_input.iter().sum();
    for (tri, share) in fill.iter().zip(shares) {
        // Old triangle i's outer edge runs from ring vertex i to i + 1: each vertex is
        // looked up in `tri` once, as the end of one edge and the start of the next.
        let corner = |i: usize| {
            let x = r[wrap(i, k)];
            (tri[0] == x) | (tri[1] == x) | (tri[2] == x)
        };
        let mut near = DVec3::ZERO;
        let mut starts_in = corner(region.from);
        for (i, &old) in (region.from..region.to).zip(old_input) {
            let ends_in = corner(i + 1);
            if starts_in & ends_in {
                near += old;
            }
            starts_in = ends_in;
        }
        *share = (input * (0.5 * f64::from(share.x) / area) + 0.5 * near).as_vec3();
    }
}

/// Ring position `i` of a ring of `k` (`i < 2k`: a region runs at most once around).
fn wrap(i: usize, k: usize) -> usize {
    debug_assert!(i < 2 * k);
    if i >= k {
        i - k
    } else {
        i
    }
}

/// The area vectors of the open fan `path` around `v` (triangle `i` is `(v, path[i],
/// path[i + 1])`) into `geometry`, as `classify` gives them for a manifold ring.
fn fan_geometry(positions: &[Vec3], v: u32, path: &[u32], geometry: &mut RingGeometry) {
    let p = |u: u32| positions[u as usize].as_dvec3();
    let at = p(v);
    geometry.crosses.clear();
    geometry.lengths.clear();
    for w in path.windows(2) {
        let c = (p(w[0]) - at).cross(p(w[1]) - at);
        geometry.crosses.push(c);
        geometry.lengths.push(c.length());
    }
}

/// Whether `x` is the first or last of the open ring `r`.
pub(super) fn is_ring_end(r: &[u32], x: u32) -> bool {
    r.first() == Some(&x) || r.last() == Some(&x)
}

/// A new triangle faces like the old ring triangles of its region that share one of its
/// vertices; given the region's summed normal `unfold`, those folded back against it (more
/// than 120° away) aside: the fill removes such a fold, and no fill could face like both
/// sides of it (docs/design.md#schroeder-folds).
fn faces_like_old(
    p: &Planning,
    cross: DVec3,
    tri: &[u32; 3],
    region: FillRegion,
    unfold: Option<DVec3>,
) -> bool {
    let r = &p.ring.verts;
    let k = r.len();
    let crosses = &p.geometry.crosses;
    let apart = |a: DVec3, b: DVec3| a.dot(b) <= FOLD_COS * a.length() * b.length();
    (region.from..region.to).all(|i| {
        let i = wrap(i, k);
        let c = crosses[i];
        let next = if i + 1 == k { r[0] } else { r[i + 1] };
        let touches = tri.contains(&r[i]) || tri.contains(&next);
        !touches || unfold.is_some_and(|old| apart(c, old)) || !apart(cross, c)
    })
}

/// Two ring triangles facing more than 120° apart: the bound of the fill's flip check
/// (`faces_like_old`), past which no single fill can face like both.
const FOLD_COS: f64 = -0.5;

/// When the closed ring in `geometry` folds (two of its triangles face more than 120°
/// apart), its two sharpest turns (ring positions, ascending) when each side keeps two
/// triangles or more: filled side by side as a crease's, as no single fill of the whole
/// ring could be (docs/design.md#schroeder-folds).
fn fold_line(geometry: &RingGeometry) -> Option<(usize, usize)> {
    let RingGeometry { crosses, lengths } = geometry;
    let k = crosses.len();
    let cos = |i: usize, j: usize| {
        let len = lengths[i] * lengths[j];
        if len > 0.0 {
            crosses[i].dot(crosses[j]) / len
        } else {
            1.0
        }
    };
    if !(0..k).any(|i| (i + 1..k).any(|j| cos(i, j) < FOLD_COS)) {
        return None;
    }
    // The turn at ring vertex i lies between triangles i - 1 and i.
    let mut best = [(f64::INFINITY, 0usize); 2];
    for i in 0..k {
        let turn = cos((i + k - 1) % k, i);
        if turn < best[0].0 {
            best = [(turn, i), best[0]];
        } else if turn < best[1].0 {
            best[1] = (turn, i);
        }
    }
    let (first, second) = (best[0].1.min(best[1].1), best[0].1.max(best[1].1));
    (second - first >= 2 && k - second + first >= 2).then_some((first, second))
}

#[cfg(test)]
mod tests {
    use super::super::input_surface::area_vectors;
    use super::*;
    use crate::mesh::topology::Connectivity;

    /// Vertex 0 pulled over its hexagonal ring's edge 1–2 (in the plane z = 0): its
    /// triangle 0-1-2 faces down, folded back under the five others.
    fn folded_hexagon() -> (Vec<Vec3>, Connectivity) {
        let positions = [
            (0.8, 0.6),
            (0.75, 0.5),
            (0.75, 0.75),
            (0.5, 0.75),
            (0.25, 0.5),
            (0.25, 0.25),
            (0.5, 0.25),
        ]
        .map(|(x, y)| Vec3::new(x, y, 0.0))
        .to_vec();
        let tris: Vec<[u32; 3]> = (1..=6).map(|i| [0, i, i % 6 + 1]).collect();
        (positions, Connectivity::new(7, &tris))
    }

    #[test]
    fn a_vertex_pulled_over_its_ring_is_filled_flat_once_folds_may_go() {
        let (positions, conn) = folded_hexagon();
        let areas = area_vectors(&positions, conn.triangles());
        let corners = InputCorners::new(positions.len(), conn.triangles(), areas.clone());
        let mut surface = Surface {
            conn: &conn,
            positions: &positions,
            texcoords: None,
            cos_feature: -1.0, // 180°: no feature edge
            unfold: false,
            seams: None,
            input: InputSurface {
                t0: 0,
                vectors: &areas,
            },
            corners: &corners,
        };
        let mut p = Planning::default();
        assert_eq!(surface.plan_removal(0, &mut p), None);
        surface.unfold = true;
        let (class, distance) = surface.plan_removal(0, &mut p).expect("filled");
        assert_eq!((class, distance), (VertexClass::Simple, 0.0));
        // Four triangles over the hexagon, every one facing up: the fold is gone.
        assert_eq!(p.fill.len(), 4);
        let mut area = 0.0;
        for t in &p.fill {
            let [a, b, c] = t.map(|v| positions[v as usize].as_dvec3());
            let cross = (b - a).cross(c - a);
            assert!(cross.z > 0.0, "{t:?} faces down");
            area += cross.z / 2.0;
        }
        assert!((area - 0.1875).abs() < 1e-6, "{area}");
    }

    /// Vertex 0 just above the centre of a flat regular hexagon (z = 0), its six triangles
    /// facing up.
    fn raised_hexagon() -> (Vec<Vec3>, Connectivity) {
        let mut positions = vec![Vec3::new(0.0, 0.0, 0.05)];
        positions.extend((0..6).map(|i| {
            let a = std::f32::consts::TAU * i as f32 / 6.0;
            Vec3::new(a.cos(), a.sin(), 0.0)
        }));
        let tris: Vec<[u32; 3]> = (1..=6).map(|i| [0, i, i % 6 + 1]).collect();
        (positions, Connectivity::new(7, &tris))
    }

    /// Plans vertex 0's removal from `raised_hexagon` where its triangle slots stand for
    /// the input `slots` and its vertices' input triangles face as `corners`.
    fn plan_on_hexagon(slots: &[Vec3], corners: Vec<Vec3>) -> Option<(VertexClass, f64)> {
        let (positions, conn) = raised_hexagon();
        let corners = InputCorners::new(positions.len(), conn.triangles(), corners);
        let surface = Surface {
            conn: &conn,
            positions: &positions,
            texcoords: None,
            cos_feature: -1.0,
            unfold: false,
            seams: None,
            input: InputSurface {
                t0: 0,
                vectors: slots,
            },
            corners: &corners,
        };
        surface.plan_removal(0, &mut Planning::default())
    }

    #[test]
    fn a_fill_facing_its_old_triangles_but_away_from_their_input_is_refused() {
        // Earlier fills may have turned the current triangles: here each stands for input
        // turned 100° about the x axis, so the flat fill faces like the current triangles
        // but away from what they stand for, and must be refused; it would drift on.
        let (positions, conn) = raised_hexagon();
        let areas = area_vectors(&positions, conn.triangles());
        let turned: Vec<Vec3> = areas
            .iter()
            .map(|&a| glam::Quat::from_rotation_x(100f32.to_radians()) * a)
            .collect();
        assert!(plan_on_hexagon(&areas, areas.clone()).is_some(), "control");
        // Away from the input the region stands for, though facing some input at a corner.
        assert_eq!(plan_on_hexagon(&turned, areas.clone()), None);
        // Facing the region's input as a whole, but away from every input triangle at
        // every corner (a thin spike's side).
        assert_eq!(plan_on_hexagon(&areas, turned), None);
    }

    #[test]
    fn a_ring_folded_in_two_halves_is_split_along_its_sharpest_turns() {
        let geometry = |zs: &[f64]| RingGeometry {
            crosses: zs.iter().map(|&z| DVec3::new(0.0, 0.1, z)).collect(),
            lengths: zs
                .iter()
                .map(|&z| DVec3::new(0.0, 0.1, z).length())
                .collect(),
        };
        // Three triangles up, three down (a blade's edge): split where they turn.
        assert_eq!(
            fold_line(&geometry(&[1.0, 1.0, 1.0, -1.0, -1.0, -1.0])),
            Some((0, 3))
        );
        // One triangle folded back: its two turns leave it alone on one side.
        assert_eq!(fold_line(&geometry(&[1.0, -1.0, 1.0, 1.0, 1.0])), None);
        // Curved but not folded.
        assert_eq!(fold_line(&geometry(&[1.0, 0.5, 0.0, 0.5, 1.0])), None);
    }
}

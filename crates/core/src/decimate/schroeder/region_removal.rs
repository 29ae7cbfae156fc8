//! Vertex removal in regions on all cores (`decimate::regions`): each region plans and
//! makes, in key order, the removals of the round's candidates whose whole neighbourhood it
//! owns — the vertex, its ring, and every triangle of them both, the triangles that
//! planning's checks read and removal rewrites. The others are left to the caller: a
//! second, shifted cut, then the whole mesh. Their neighbours in the region wait for the
//! next pass, as they would had the candidate gone in its turn; letting them go first costs
//! accuracy (docs/design.md#schroeder-regions).
//!
//! A seam vertex with a twin (the other side of a texture seam, removed only together with
//! it) is left to the whole mesh like a border candidate, its neighbours held the same way;
//! the rest of a textured model goes in regions.
//!
//! On the whole mesh the removals are planned on all cores but made on one, in order; here
//! a region plans and makes its own, so both run on all cores and no plan goes stale.
//! Regions are a fixed cut of the vertex ids, so the result does not depend on the number
//! of cores.

use std::collections::HashMap;

use glam::Vec3;
use rayon::prelude::*;

use super::input_surface::{InputCorners, InputSurface};
use super::plan::{Planning, SeamSides, Surface};
use super::{volume_change, waits, Decimator, HELD};
use crate::decimate::candidates::Candidate;
use crate::decimate::closed::ClosedView;
use crate::decimate::regions::Regions;
use crate::decimate::Outcome;
use crate::mesh::topology::{split_mut, ConnectivityPart};

/// Candidates whose data is asked for ahead of their turn, per stage of
/// [`Region::prefetch_ahead`].
const AHEAD: usize = 2;

/// One region's share of a decimation: its part of the connectivity and of the per-vertex
/// state, indexed from `v0`.
struct Region<'a> {
    v0: u32,
    conn: ConnectivityPart<'a>,
    /// All of them: a removal moves no vertex.
    positions: &'a [Vec3],
    /// All of them, when the model has texture coordinates.
    texcoords: Option<&'a [[f32; 2]]>,
    /// Texture-seam twins and pinned vertices by vertex id, all of them (no twins when the
    /// model has no seams).
    seams: SeamSides<'a>,
    cos_feature: f64,
    /// The input surface of the region's triangle slots, from slot `t0`.
    input: &'a mut [Vec3],
    t0: u32,
    /// The input triangles at each vertex, all of them.
    corners: &'a InputCorners,
    /// Whether folds may be removed (`Surface::unfold`).
    unfold: bool,
    keys: &'a mut [f64],
    accumulated: &'a mut [f64],
    changed_in: &'a mut [u32],
    pass: u32,
    planning: Planning,
    /// Closed components' volumes as the round started, and this region's changes.
    closed: ClosedView<'a>,
    /// Scratch for [`Region::hold_neighbours`].
    held: Vec<u32>,
    done: Done,
}

/// What a region did.
#[derive(Debug, Default)]
struct Done {
    removed: usize,
    max_key: f64,
    /// Candidates whose neighbourhood reaches outside the region, in the order met.
    border: Vec<Candidate>,
    /// Vertices whose ring changed, each once (re-ranked at the pass's end).
    changed: Vec<u32>,
    /// Slots killed.
    freed: Vec<u32>,
    /// Changes of closed components' volumes (see `ClosedView`).
    volumes: HashMap<u32, f64>,
}

impl Decimator {
    /// Removes what it can of `candidates` (in key order) in `regions`, on all cores,
    /// adding to `outcome`; returns the candidates on borders, in key order.
    pub(super) fn remove_in_regions(
        &mut self,
        regions: &Regions,
        candidates: &[Candidate],
        outcome: &mut Outcome,
    ) -> Vec<Candidate> {
        let per_region = regions.distribute(candidates);
        let starts: Vec<usize> = regions.vertex_starts.iter().map(|&v| v as usize).collect();
        let mut keys = split_mut(&mut self.keys, &starts).into_iter();
        let mut accumulated = split_mut(&mut self.accumulated, &starts).into_iter();
        let mut changed_in = split_mut(&mut self.changed_in, &starts).into_iter();
        let slot_starts: Vec<usize> = regions.slot_starts.iter().map(|&t| t as usize).collect();
        let mut input = split_mut(&mut self.input, &slot_starts).into_iter();
        let (positions, cos_feature, pass) = (&self.positions[..], self.cos_feature, self.pass);
        let unfold = self.unfold;
        let texcoords = self.texcoords.as_deref();
        let seams = SeamSides {
            twins: &self.twins,
            pinned: &self.pinned,
            copies: &self.copies,
            facing: &self.facing,
        };
        let closed = &self.closed;
        let corners = &self.corners;
        let parts: Vec<Region<'_>> = self
            .conn
            .split(&regions.vertex_starts, &regions.slot_starts)
            .into_iter()
            .zip(regions.vertex_starts.iter().zip(&regions.slot_starts))
            .filter_map(|(conn, (&v0, &t0))| {
                Some(Region {
                    v0,
                    conn,
                    positions,
                    texcoords,
                    seams,
                    cos_feature,
                    input: input.next()?,
                    t0,
                    corners,
                    unfold,
                    keys: keys.next()?,
                    accumulated: accumulated.next()?,
                    changed_in: changed_in.next()?,
                    pass,
                    planning: Planning::default(),
                    closed: ClosedView::Part(closed, HashMap::new()),
                    held: Vec::new(),
                    done: Done::default(),
                })
            })
            .collect();
        let done: Vec<Done> = parts
            .into_par_iter()
            .zip(per_region)
            .map(|(region, mine)| region.remove_in_order(&mine))
            .collect();
        let mut border = Vec::new();
        for region in done {
            outcome.removed += region.removed;
            outcome.max_error = outcome.max_error.max(region.max_key);
            border.extend(region.border);
            self.changed.extend(region.changed);
            self.conn.absorb(region.freed);
            self.closed.absorb(region.volumes);
        }
        border.sort_unstable();
        border
    }
}

impl Region<'_> {
    fn at(&self, v: u32) -> usize {
        (v - self.v0) as usize
    }

    /// Tries `candidates` in order: each still current one whose neighbourhood the region
    /// owns is removed, or kept until a neighbour goes when its hole cannot be filled.
    fn remove_in_order(mut self, candidates: &[Candidate]) -> Done {
        for (n, &c) in candidates.iter().enumerate() {
            self.prefetch_ahead(candidates, n);
            let v = c.vertex();
            if waits(self.changed_in[self.at(v)], self.pass) {
                continue; // its key is stale (re-ranked at the pass's end), or held back
            }
            // Next to a seam, a fill is checked against the other side: on the whole mesh.
            if self.seams.twin(v).is_some() || !self.owns_neighbourhood(v) || self.near_seam(v) {
                self.done.border.push(c);
                self.hold_neighbours(v);
                continue;
            }
            let surface = Surface {
                conn: &self.conn,
                positions: self.positions,
                texcoords: self.texcoords,
                cos_feature: self.cos_feature,
                unfold: self.unfold,
                seams: None,
                input: InputSurface {
                    t0: self.t0,
                    vectors: self.input,
                },
                corners: self.corners,
            };
            let i = self.at(v);
            if surface.plan_removal(v, &mut self.planning).is_some() && self.keeps_closed_volume(v)
            {
                let key = self.keys[i];
                self.apply(v, key);
                self.done.removed += 1;
                self.done.max_key = self.done.max_key.max(key);
            } else {
                self.keys[i] = f64::NAN;
            }
        }
        self.done.freed = self.conn.finish();
        self.done.volumes = self.closed.into_changes();
        self.done
    }

    /// Asks for the data of the candidates ahead of candidate `n`, in three stages as each
    /// becomes addressable: a candidate's incident list and per-vertex state, then its
    /// triangles and their input surface, then its ring vertices' incident lists, input
    /// corners and per-vertex state (which the ownership check, the fill's checks and the
    /// removal read).
    fn prefetch_ahead(&self, candidates: &[Candidate], n: usize) {
        let conn = &self.conn;
        let listed = |k: usize| {
            candidates
                .get(n + k)
                .map(|c| c.vertex())
                .filter(|&v| conn.has_room(v, 0))
        };
        if let Some(c) = candidates.get(n + 3 * AHEAD) {
            let v = c.vertex();
            conn.prefetch_incident(v);
            self.closed.prefetch(v);
            let i = v.wrapping_sub(self.v0) as usize;
            if let (Some(mark), Some(key)) = (self.changed_in.get(i), self.keys.get(i)) {
                crate::mesh::prefetch(mark);
                crate::mesh::prefetch(key);
            }
        }
        if let Some(v) = listed(2 * AHEAD) {
            for &t in conn.incident(v) {
                conn.prefetch_triangle(t);
                if let Some(input) = self.input.get(t.wrapping_sub(self.t0) as usize) {
                    crate::mesh::prefetch(input);
                }
            }
        }
        if let Some(v) = listed(AHEAD) {
            for &t in conn.incident(v) {
                if conn.owns_slot(t) {
                    for u in conn.triangle(t) {
                        conn.prefetch_incident(u);
                        self.corners.prefetch(u);
                        let i = u.wrapping_sub(self.v0) as usize;
                        if let (Some(mark), Some(acc)) =
                            (self.changed_in.get(i), self.accumulated.get(i))
                        {
                            crate::mesh::prefetch(mark);
                            crate::mesh::prefetch(acc);
                        }
                    }
                }
            }
        }
    }

    /// True when the region owns `v`, its ring, and every triangle of them all (none of
    /// their incident lists spilled), and each ring vertex has room for what a fill can add
    /// to it: a ring vertex is in at least one of `v`'s `k` triangles and in at most all
    /// `k - 1` triangles of a fill, so it gains at most `k - 2`.
    fn owns_neighbourhood(&self, v: u32) -> bool {
        let conn = &self.conn;
        if !conn.owns_vertex(v) || !conn.has_room(v, 0) {
            return false;
        }
        let incident = conn.incident(v);
        let extra = incident.len().saturating_sub(2);
        incident.iter().all(|&t| {
            conn.owns_slot(t)
                && conn.triangle(t).iter().all(|&u| {
                    u == v
                        || (conn.owns_vertex(u)
                            && conn.has_room(u, extra)
                            && conn.incident(u).iter().all(|&s| conn.owns_slot(s)))
                })
        })
    }

    /// Whether filling the owned `v`'s hole could join two seam vertices (with a twin or
    /// pinned) by a new edge, when the model has seams: two of its neighbours are on a seam
    /// and are not already joined through one of its triangles; or it touches a junction's
    /// copy, whose fill must keep the junction's facing (checked on the whole mesh).
    fn near_seam(&self, v: u32) -> bool {
        if self.seams.twins.is_empty() && self.seams.copies.is_empty() {
            return false;
        }
        let mut seam = [u32::MAX; 2];
        for &t in self.conn.incident(v) {
            for u in self.conn.triangle(t) {
                if u == v || !self.seams.on_seam(u) || seam.contains(&u) {
                    continue;
                }
                if self
                    .seams
                    .copies
                    .get(u as usize)
                    .is_some_and(|&c| c != u32::MAX)
                {
                    return true; // a fill at a junction keeps its facing: on the whole mesh
                }
                if seam[0] != u32::MAX && seam[1] != u32::MAX {
                    return true; // a third
                }
                seam[usize::from(seam[0] != u32::MAX)] = u;
            }
        }
        seam[1] != u32::MAX
            && !self.conn.incident(v).iter().any(|&t| {
                let tri = self.conn.triangle(t);
                tri.contains(&seam[0]) && tri.contains(&seam[1])
            })
    }

    /// Keeps the neighbours of `v`, a candidate left to the whole mesh, from going before
    /// it: those the region owns are held, so they wait for the next pass, as `v`'s removal
    /// would make them wait. Held is not changed: a held vertex keeps its key and is not
    /// re-ranked. (Were it re-ranked, two such candidates that cannot go could free each
    /// other's key pass after pass, and the passes would never end.)
    fn hold_neighbours(&mut self, v: u32) {
        if !self.conn.owns_vertex(v) || !self.conn.has_room(v, 0) {
            return;
        }
        let mut ring = std::mem::take(&mut self.held);
        ring.clear();
        for &t in self.conn.incident(v) {
            if self.conn.owns_slot(t) {
                ring.extend(
                    self.conn
                        .triangle(t)
                        .into_iter()
                        .filter(|&u| u != v && self.conn.owns_vertex(u)),
                );
            }
        }
        for &u in &ring {
            let i = self.at(u);
            if !waits(self.changed_in[i], self.pass) {
                self.changed_in[i] = self.pass | HELD;
            }
        }
        self.held = ring;
    }

    /// Whether removing `v` as planned keeps its closed component (if any) beyond its floor
    /// (see `Decimator::keeps_closed_volume`).
    fn keeps_closed_volume(&self, v: u32) -> bool {
        self.closed
            .component(v)
            .is_none_or(|c| self.closed.allows(c, self.volume_change(v)))
    }

    /// Six times the change of signed volume that the planned removal of `v` makes.
    fn volume_change(&self, v: u32) -> f64 {
        let p = &self.planning;
        let old = p.ring.triangles.iter().map(|&t| self.conn.triangle(t));
        volume_change(self.positions, v, old, &p.fill)
    }

    /// Removes `v` as planned: its triangles replaced by the fill, `key` accumulated
    /// around the ring, and `v` and its ring noted as changed.
    fn apply(&mut self, v: u32, key: f64) {
        if let Some(c) = self.closed.component(v) {
            let change = self.volume_change(v);
            self.closed.apply(c, change);
        }
        let planning = std::mem::take(&mut self.planning);
        self.conn
            .replace_triangles(&planning.ring.triangles, &planning.fill);
        // As `replace_triangles` reuses the slots: fill[i] in old[old.len() - 1 - i].
        debug_assert_eq!(planning.fill.len(), planning.fill_input.len());
        let old = planning.ring.triangles.iter().rev();
        for (&t, &input) in old.zip(&planning.fill_input) {
            if let Some(slot) = self.input.get_mut(t.wrapping_sub(self.t0) as usize) {
                *slot = input;
            }
        }
        self.mark_changed(v);
        for &u in &planning.ring.verts {
            let i = self.at(u);
            self.accumulated[i] = self.accumulated[i].max(key);
            self.mark_changed(u);
        }
        self.planning = planning;
    }

    fn mark_changed(&mut self, v: u32) {
        let i = self.at(v);
        if self.changed_in[i] != self.pass {
            self.changed_in[i] = self.pass;
            self.done.changed.push(v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{measure, shapes, Model};

    /// A bumpy sphere (poles of valence 240, whose lists spill) loaded as a decimation
    /// loads it, ranked, with its candidates in key order.
    fn ranked() -> (Decimator, Vec<Candidate>) {
        let model = shapes::bumpy_sphere(120, 240);
        let (_, positions, triangles) = super::super::load(&model);
        let mut d = Decimator::new(positions, triangles, 30.0);
        d.rank_all();
        let mut candidates: Vec<Candidate> = d
            .keys
            .iter()
            .enumerate()
            .filter(|(_, k)| k.is_finite())
            .map(|(v, &k)| Candidate::new(k as f32, v as u32))
            .collect();
        candidates.sort_unstable();
        (d, candidates)
    }

    /// An outcome before anything is removed (features from 30°, as [`ranked`] ranks).
    fn nothing_yet() -> Outcome {
        Outcome::nothing_removed(30.0, 0)
    }

    /// Removes `candidates` in order on the whole mesh, as the passes do there (those whose
    /// ring changed in this pass wait); returns how many went.
    fn one_by_one(d: &mut Decimator, candidates: &[Candidate]) -> usize {
        let mut removed = 0;
        for c in candidates {
            let v = c.vertex();
            if !d.changed_now(v) && d.try_remove(v, d.keys[v as usize]) {
                removed += 1;
            }
        }
        removed
    }

    /// The decimator's live triangles as a model over its positions.
    fn live(d: &Decimator) -> Model {
        Model {
            positions: d.positions.clone(),
            triangles: d.conn.alive_ids().map(|t| d.conn.triangle(t)).collect(),
            ..Model::default()
        }
    }

    #[test]
    fn a_candidate_left_to_the_whole_mesh_holds_its_neighbours_without_re_ranking_them() {
        // Each region holds back the neighbours of a candidate it leaves to the whole mesh.
        // Holding once re-ranked them as if changed: two such candidates that could not go
        // then gave each other a fresh key pass after pass, and a 250k-vertex sphere in 64
        // texture charts decimated by 99 % never finished.
        let (mut d, candidates) = ranked();
        let regions = Regions::new(d.positions.len(), d.conn.triangles(), false);
        let starts = &regions.vertex_starts;
        let region_of = |v: u32| starts.partition_point(|&s| s <= v);
        // Candidates with a neighbour in another region: none is removed in regions.
        let straddling: Vec<Candidate> = candidates
            .iter()
            .copied()
            .filter(|c| {
                let v = c.vertex();
                d.conn.incident(v).iter().any(|&t| {
                    d.conn
                        .triangle(t)
                        .iter()
                        .any(|&u| region_of(u) != region_of(v))
                })
            })
            .collect();
        assert!(straddling.len() > 100, "{} straddle", straddling.len());
        let keys = d.keys.clone();
        let mut outcome = nothing_yet();
        let border = d.remove_in_regions(&regions, &straddling, &mut outcome);
        // Left to the whole mesh, or held back by one left before.
        assert_eq!(outcome.removed, 0);
        assert!(border.len() > 100, "{} left", border.len());
        // Their neighbours wait for the next pass, keys as they were, and nothing is to be
        // re-ranked: nothing changed.
        let held: Vec<u32> = (0..d.positions.len() as u32)
            .filter(|&v| d.changed_now(v))
            .collect();
        assert!(held.len() > straddling.len(), "{} held", held.len());
        assert!(d.changed.is_empty(), "{} to re-rank", d.changed.len());
        assert!(keys
            .iter()
            .zip(&d.keys)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        // A held vertex whose ring then changes is listed for re-ranking after all.
        let v = straddling[0].vertex();
        let planned = d.try_remove(v, d.keys[v as usize]);
        assert!(planned, "a bumpy sphere's vertex {v} can go");
        assert!(d.changed.len() >= 4, "{:?}", d.changed);
        assert!(d.changed.iter().all(|&u| d.changed_now(u)));
    }

    #[test]
    fn regions_remove_most_of_a_round_and_leave_a_valid_mesh() {
        let (mut d, candidates) = ranked();
        let regions = Regions::new(d.positions.len(), d.conn.triangles(), false);
        assert!(regions.count() >= 4, "{} regions", regions.count());
        let before = live(&d);
        let round = &candidates[..candidates.len() / 4];
        let mut outcome = nothing_yet();
        // The same round on the whole mesh, one candidate at a time, for comparison.
        let (mut serial, _) = ranked();
        serial.pass = d.pass;
        let serial_removed = one_by_one(&mut serial, round);

        let border = d.remove_in_regions(&regions, round, &mut outcome);
        let in_regions = outcome.removed;
        // Each removal takes one vertex and two triangles of a closed surface.
        let after = live(&d);
        assert_eq!(
            after.triangles.len(),
            before.triangles.len() - 2 * in_regions
        );
        assert!(
            border.len() * 5 < round.len(),
            "{} on borders",
            border.len()
        );
        // The border candidates on the whole mesh afterwards: about what the whole mesh
        // removes alone (the order differs: border candidates come last).
        let total = in_regions + one_by_one(&mut d, &border);
        assert!(
            total.abs_diff(serial_removed) * 50 < serial_removed,
            "{in_regions} in regions + border = {total}, against {serial_removed} one by one"
        );
        assert!(
            in_regions * 10 > total * 8,
            "{in_regions} of {total} in regions"
        );
        let after = live(&d);
        assert!(
            border.windows(2).all(|w| w[0] <= w[1]),
            "border in key order"
        );
        let broken = measure::invariant_violations(&before, &after);
        assert!(broken.is_empty(), "{broken:?}");
        // Every changed vertex is listed once, for re-ranking.
        let mut changed = d.changed.clone();
        changed.sort_unstable();
        changed.dedup();
        assert_eq!(changed.len(), d.changed.len());
        assert!(changed.len() >= outcome.removed * 4);
        // The whole mesh's connectivity agrees with the parts' edits.
        for v in 0..d.positions.len() as u32 {
            for &t in d.conn.incident(v) {
                assert!(d.conn.is_alive(t) && d.conn.triangle(t).contains(&v));
            }
        }
    }
}

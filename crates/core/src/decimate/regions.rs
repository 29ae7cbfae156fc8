//! Cutting a mesh into regions that decimate on all cores at once: ranges of vertex ids
//! (spatial blocks, as ids follow a Morton curve, `layout::load`) with the triangle slots
//! whose smallest corner lies in each. An operation whose whole neighbourhood one region
//! owns runs there, and operations in different regions touch disjoint data, so they
//! commute: the result depends neither on the threads' timing nor on how many there are.
//! The rest (candidates on borders) is left to a second cut, shifted, and then to the
//! whole mesh. Quadric edge collapse (`qem::collapse_passes`) and vertex removal
//! (`schroeder::region_removal`) both run their passes this way.

use super::candidates::Candidate;

/// Regions a pass is cut into when it runs on all cores: a fixed number, so that the result
/// is the same on any machine; more balance the cores but put more candidates on borders
/// (docs/design.md#regions).
const REGIONS: usize = 16;

/// The border candidates' second round runs in this many times fewer regions (at least
/// two), shifted by half a region: Morton-range borders lie on the same octree planes however
/// shifted, so only larger regions take many of them in (docs/design.md#regions).
const BORDER_MERGE: usize = 8;

/// Fewer vertices per region than this and the passes run on one core.
const MIN_REGION: usize = 4096;

/// A pass in regions goes in this many rounds of its cheapest candidates, each round's
/// border candidates on the whole mesh before the next round: a border candidate then waits
/// for at most a round's more expensive ones (docs/design.md#regions).
const ROUNDS: usize = 4;

/// Fewer candidates than this are not worth a round in regions.
const MIN_ROUND: usize = 1024;

/// The vertex and slot ranges of the regions.
pub(crate) struct Regions {
    pub vertex_starts: Vec<u32>,
    pub slot_starts: Vec<u32>,
}

impl Regions {
    /// `REGIONS` equal ranges of the `n` vertex ids (fewer on a small mesh; `shifted`:
    /// `BORDER_MERGE` times fewer, shifted by half an unshifted range, the first one longer
    /// and the last shorter), each with the slots of `triangles` whose smallest corner is
    /// in its range — all of them while nothing changed yet, as `layout::load` orders
    /// triangles by their smallest vertex. (Were they in another order, only more
    /// candidates would end up on borders.)
    pub fn new(n: usize, triangles: &[[u32; 3]], shifted: bool) -> Self {
        let count = (n / MIN_REGION).clamp(1, REGIONS);
        let shift = if shifted { n / count / 2 } else { 0 };
        let count = if shifted {
            (count / BORDER_MERGE).max(2).min(count)
        } else {
            count
        };
        let vertex_starts: Vec<u32> = (0..count)
            .map(|i| {
                if i == 0 {
                    0
                } else {
                    (i * n / count - shift) as u32
                }
            })
            .collect();
        let mut slot_starts: Vec<u32> = Vec::with_capacity(count);
        for &v0 in &vertex_starts {
            let at = triangles.partition_point(|tri| tri.iter().min().is_some_and(|&m| m < v0));
            let previous = slot_starts.last().copied().unwrap_or(0);
            slot_starts.push((at as u32).max(previous));
        }
        Self {
            vertex_starts,
            slot_starts,
        }
    }

    pub fn count(&self) -> usize {
        self.vertex_starts.len()
    }

    /// The region vertex `v` belongs to.
    pub fn of_vertex(&self, v: u32) -> usize {
        self.vertex_starts
            .partition_point(|&s| s <= v)
            .saturating_sub(1)
    }

    /// `candidates` by the region of their vertex, each region's in the given order.
    pub fn distribute(&self, candidates: &[Candidate]) -> Vec<Vec<Candidate>> {
        let mut per_region: Vec<Vec<Candidate>> = vec![Vec::new(); self.count()];
        for &c in candidates {
            per_region[self.of_vertex(c.vertex())].push(c);
        }
        per_region
    }
}

/// How many of `candidates` (the rest of a pass, in cost order) the next round in regions
/// takes: a round's share of the pass (`pass` candidates), never reaching `budget` (the
/// operations the count targets still allow), and none (0) when that is fewer than
/// [`MIN_ROUND`].
pub(crate) fn round_size(pass: usize, rest: usize, budget: usize) -> usize {
    let round = pass.div_ceil(ROUNDS).max(MIN_ROUND);
    let size = round.min(rest).min(budget.saturating_sub(1));
    if size < MIN_ROUND {
        0
    } else {
        size
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decimate::layout;
    use crate::mesh::shapes;

    #[test]
    fn regions_cover_the_vertices_and_own_the_slots_of_their_triangles() {
        let model = shapes::uv_sphere(100, 200);
        let loaded = layout::load(&model);
        let triangles = loaded.triangles(&model);
        let n = loaded.order.len();
        for shifted in [false, true] {
            let regions = Regions::new(n, &triangles, shifted);
            let count = n / MIN_REGION;
            let expected = if shifted { count.min(2) } else { count };
            assert_eq!(regions.count(), expected);
            assert_eq!(regions.vertex_starts[0], 0);
            assert_eq!(regions.slot_starts[0], 0);
            assert!(regions.vertex_starts.windows(2).all(|w| w[0] < w[1]));
            assert!(regions.slot_starts.windows(2).all(|w| w[0] <= w[1]));
            // Every triangle lies in the slot range of the region of its smallest corner.
            let slot_region =
                |t: usize| regions.slot_starts.partition_point(|&s| s as usize <= t) - 1;
            for (t, tri) in triangles.iter().enumerate() {
                let first = tri.iter().copied().min().unwrap_or(0);
                assert_eq!(slot_region(t), regions.of_vertex(first), "triangle {t}");
            }
            assert_eq!(regions.of_vertex(n as u32 - 1), regions.count() - 1);
            // Candidates keep their order within a region.
            let candidates: Vec<Candidate> = (0..n as u32)
                .rev()
                .map(|v| Candidate::new(v as f32, v))
                .collect();
            let per_region = regions.distribute(&candidates);
            assert_eq!(per_region.iter().map(Vec::len).sum::<usize>(), n);
            for (r, mine) in per_region.iter().enumerate() {
                assert!(mine.iter().all(|c| regions.of_vertex(c.vertex()) == r));
                assert!(mine.windows(2).all(|w| w[0].vertex() > w[1].vertex()));
            }
        }
    }

    #[test]
    fn a_round_never_reaches_the_budget_and_is_worth_its_cost() {
        assert_eq!(round_size(100_000, 100_000, usize::MAX), 25_000);
        assert_eq!(round_size(100_000, 10_000, usize::MAX), 10_000);
        assert_eq!(round_size(100_000, 100_000, 5_000), 4_999);
        assert_eq!(round_size(100_000, 100_000, MIN_ROUND), 0);
        assert_eq!(round_size(2_000, 2_000, usize::MAX), MIN_ROUND);
        assert_eq!(round_size(100_000, 500, usize::MAX), 0);
    }
}

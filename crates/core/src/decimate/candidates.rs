//! The candidates of a pass, shared by both algorithms' pass loops: a cost and a vertex
//! packed in one integer, and the selection of the cheapest of them on all cores.

use rayon::prelude::*;

/// A candidate: its cost (a qem vertex's best edge, a Schroeder vertex's removal) and the
/// vertex, packed so that comparing the packed
/// integers orders by cost (as `f32::total_cmp` does), then by vertex: selecting and sorting
/// plain integers is several times faster than through a comparison closure.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Candidate(pub(crate) u64);

impl Candidate {
    pub fn new(cost: f32, v: u32) -> Self {
        let bits = cost.to_bits();
        // Negative floats reversed, positive ones above them: the total order as integers.
        let key = if bits >> 31 == 1 {
            !bits
        } else {
            bits | 1 << 31
        };
        Self(u64::from(key) << 32 | u64::from(v))
    }

    pub fn vertex(self) -> u32 {
        self.0 as u32
    }

    pub fn cost(self) -> f32 {
        let key = (self.0 >> 32) as u32;
        f32::from_bits(if key >> 31 == 1 {
            key & !(1 << 31)
        } else {
            !key
        })
    }
}

/// Bits of a candidate's key that pick its bucket in [`cheapest`]: the sign, the exponent
/// and three bits of the mantissa of its cost, so that a bucket spans under 10 % of it (a
/// few thousand candidates of a scan of a million triangles), and the histogram stays small.
const BUCKET_BITS: u32 = 12;

/// Moves the candidates `first` picks to the front of `candidates`, in order (the rest is
/// left in any order); returns how many. The pass loops' "one triangle over a count" takes
/// only those whose removal or collapse takes one triangle.
pub(crate) fn move_to_front(
    candidates: &mut [Candidate],
    mut first: impl FnMut(Candidate) -> bool,
) -> usize {
    let mut front = 0;
    for i in 0..candidates.len() {
        if first(candidates[i]) {
            candidates.swap(front, i);
            front += 1;
        }
    }
    front
}

/// The `take` cheapest of `candidates` (distinct), sorted, into `out` (`tied` is scratch):
/// a histogram of the keys' top bits, on all cores, gives the bucket the last of them falls
/// in; the buckets below it are taken whole and that one is selected in. The same set as a
/// `select_nth_unstable`, so a pass is the same on any number of cores.
pub(crate) fn cheapest(
    candidates: &[Candidate],
    take: usize,
    out: &mut Vec<Candidate>,
    tied: &mut Vec<Candidate>,
) {
    let bucket = |c: &Candidate| (c.0 >> (64 - BUCKET_BITS)) as usize;
    out.clear();
    if take >= candidates.len() {
        out.extend_from_slice(candidates);
    } else {
        let per_thread = candidates
            .len()
            .div_ceil(rayon::current_num_threads().max(1));
        let histograms: Vec<Vec<u32>> = candidates
            .par_chunks(per_thread.max(1))
            .map(|chunk| {
                let mut histogram = vec![0u32; 1 << BUCKET_BITS];
                for c in chunk {
                    histogram[bucket(c)] += 1;
                }
                histogram
            })
            .collect();
        let mut below = 0;
        let mut last = 0;
        for b in 0..1 << BUCKET_BITS {
            let count: usize = histograms.iter().map(|h| h[b] as usize).sum();
            if below + count >= take {
                last = b;
                break;
            }
            below += count;
        }
        // The buckets below `last` are the keys below its first; compacted without a
        // branch (which would go either way at random): every key is written, and the end
        // moves on past those that stay.
        let lo = (last as u64) << (64 - BUCKET_BITS);
        out.resize(below + 1, Candidate(0));
        let mut end = 0;
        tied.clear();
        for &c in candidates {
            out[end] = c;
            end += usize::from(c.0 < lo);
            if bucket(&c) == last {
                tied.push(c);
            }
        }
        out.truncate(end);
        let rest = take - below;
        if rest < tied.len() {
            tied.select_nth_unstable(rest - 1);
            tied.truncate(rest);
        }
        out.append(tied);
    }
    out.par_sort_unstable();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn candidates_order_by_cost_then_vertex() {
        let costs = [-1.5f32, -0.0, 0.0, 1e-30, 0.25, 3.0, f32::MAX];
        let mut all: Vec<(f32, u32)> = costs.iter().flat_map(|&c| [(c, 7), (c, 2)]).rev().collect();
        let mut packed: Vec<Candidate> = all.iter().map(|&(c, v)| Candidate::new(c, v)).collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        packed.sort();
        let unpacked: Vec<(u32, u32)> = packed
            .iter()
            .map(|c| (c.cost().to_bits(), c.vertex()))
            .collect();
        let expected: Vec<(u32, u32)> = all.iter().map(|&(c, v)| (c.to_bits(), v)).collect();
        assert_eq!(unpacked, expected);
    }

    #[test]
    fn cheapest_takes_the_same_candidates_as_a_serial_selection() {
        // Costs from a few values (many in one bucket) and spread over many octaves.
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let candidates: Vec<Candidate> = (0..20_000u32)
            .map(|v| {
                let r = next();
                let cost = match r % 4 {
                    0 => 0.0,
                    1 => 1.0 + (r >> 40) as f32 * 1e-9,
                    _ => f32::from_bits(0x2000_0000 + (r >> 35) as u32),
                };
                Candidate::new(cost, v)
            })
            .collect();
        for take in [1, 2, 4_999, 5_000, 5_001, 10_000, 19_999, 20_000] {
            let mut expected = candidates.clone();
            expected.sort_unstable();
            expected.truncate(take);
            let (mut out, mut tied) = (vec![Candidate::new(5.0, 0)], Vec::new());
            cheapest(&candidates, take, &mut out, &mut tied);
            assert_eq!(out, expected, "take {take}");
        }
    }
}

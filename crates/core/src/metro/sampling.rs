//! Sampling one surface and measuring each sample's distance to the other, after Metro
//! (Cignoni, Rocchini, Scopigno, "Metro: measuring error on simplified surfaces", Computer
//! Graphics Forum 17(2), 1998, section 3.1: vertex, edge and face sampling).
//!
//! Owns: the deterministic generator ([`SplitMix64`]), the placement of samples (every vertex;
//! edge points spread by length; face points spread by area with systematic sampling and
//! placed uniformly inside each face), and the parallel, order-independent reduction of their
//! distances into a [`DirectionStats`].
//!
//! Determinism: each face and edge draws from its own generator, seeded from the user's seed
//! and its index, and the work is cut into fixed chunks whose partial results are combined in
//! order, so the numbers do not depend on the thread count or on scheduling.

use glam::DVec3;
use rayon::prelude::*;

use super::bvh::Bvh;
use super::{DirectionStats, Surface};
use crate::cancel::Cancel;

/// Items (faces, edges or vertices) per unit of parallel work.
const CHUNK: usize = 2048;

/// Salts that give faces, edges and the systematic-sampling offsets independent streams.
const SALT_FACE: u64 = 0x6a09_e667_f3bc_c908;
const SALT_EDGE: u64 = 0xbb67_ae85_84ca_a73b;
const SALT_OFFSET: u64 = 0x3c6e_f372_fe94_f82b;

/// Steele, Lea and Flood's SplitMix64 (2014): a tiny, fast, well-mixed 64-bit generator.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    #[cfg(test)]
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// A generator for stream `index` of `salt` under `seed`, decorrelated by one mixing step.
    pub fn stream(seed: u64, salt: u64, index: u64) -> Self {
        let mut g = Self(seed ^ salt ^ index.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        g.next_u64();
        g
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Running statistics of one chunk of samples.
#[derive(Debug, Clone, Copy)]
struct Partial {
    max: f64,
    max_at: DVec3,
    sum: f64,
    sum2: f64,
    count: u64,
}

impl Partial {
    const EMPTY: Self = Self {
        max: f64::NEG_INFINITY,
        max_at: DVec3::ZERO,
        sum: 0.0,
        sum2: 0.0,
        count: 0,
    };

    #[inline]
    fn add(&mut self, d: f64, at: DVec3) {
        if d > self.max {
            self.max = d;
            self.max_at = at;
        }
        self.sum += d;
        self.sum2 += d * d;
        self.count += 1;
    }

    /// Combines in order; on equal maxima the earlier location wins.
    fn merge(mut self, other: &Self) -> Self {
        if other.max > self.max {
            self.max = other.max;
            self.max_at = other.max_at;
        }
        self.sum += other.sum;
        self.sum2 += other.sum2;
        self.count += other.count;
        self
    }
}

/// Splits `weights` (areas or lengths) into `n` sample counts proportional to them by
/// systematic sampling: a stratified comb of `n` teeth with a random offset laid over the
/// cumulative weight, so every item gets its share rounded down or up and the total is `n`.
fn allocate(weights: &[f64], n: usize, offset: f64) -> Vec<u64> {
    let total: f64 = weights.iter().sum();
    if total.is_nan() || total <= 0.0 || n == 0 {
        return vec![0; weights.len()];
    }
    let scale = n as f64 / total;
    let mut cumulative = 0.0;
    let mut previous = 0i64; // the comb starts at `offset` in [0, 1)
    let mut counts = Vec::with_capacity(weights.len());
    for (i, &w) in weights.iter().enumerate() {
        cumulative += w;
        // The last item closes the comb exactly, whatever rounding the running sum met.
        let reach = if i + 1 == weights.len() {
            n as i64
        } else {
            ((cumulative * scale + offset).floor() as i64).min(n as i64)
        };
        counts.push((reach - previous).max(0) as u64);
        previous = previous.max(reach);
    }
    counts
}

/// Distance of `p` from the target surface, with values under `floor` (the rounding noise of
/// the closest-point arithmetic) reported as exactly zero.
#[inline]
fn distance(
    target: &Bvh,
    p: DVec3,
    hint: &mut Option<u32>,
    stack: &mut Vec<(u32, f64)>,
    floor: f64,
) -> f64 {
    match target.nearest(p, *hint, stack) {
        Some(hit) => {
            *hint = Some(hit.triangle);
            let d = hit.dist2.sqrt();
            if d <= floor {
                0.0
            } else {
                d
            }
        }
        None => f64::INFINITY,
    }
}

/// Runs `work` over `0..n` in fixed chunks in parallel and folds the partials in order; once
/// `cancel` is requested the chunks not yet started are skipped.
fn chunked<F>(n: usize, cancel: &Cancel, work: F) -> Partial
where
    F: Fn(std::ops::Range<usize>, &mut Partial) + Sync,
{
    let chunks = n.div_ceil(CHUNK);
    let partials: Vec<Partial> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut acc = Partial::EMPTY;
            if !cancel.requested() {
                work(c * CHUNK..((c + 1) * CHUNK).min(n), &mut acc);
            }
            acc
        })
        .collect();
    partials.iter().fold(Partial::EMPTY, |a, b| a.merge(b))
}

/// Samples `from` (`face_samples` points by area, a tenth as many along edges by length, and
/// every vertex) and measures each sample's distance to `to`. Max is over all samples; mean
/// and RMS are over the face samples, which estimate the area integral without bias. Once
/// `cancel` is requested the rest is skipped and the stats are partial.
pub fn measure(
    from: &Surface,
    to: &Bvh,
    face_samples: usize,
    seed: u64,
    floor: f64,
    cancel: &Cancel,
) -> DirectionStats {
    let probe = Probe {
        to,
        seed,
        floor,
        cancel,
    };
    let mut offsets = SplitMix64::stream(seed, SALT_OFFSET, 0);
    let faces = sample_faces(from, &probe, face_samples, offsets.next_f64());
    let edge_total = if from.edges.is_empty() {
        0
    } else {
        (face_samples / 10).max(1)
    };
    let edges = sample_edges(from, &probe, edge_total, offsets.next_f64());
    let vertices = sample_vertices(from, &probe);
    let all = faces.merge(&edges).merge(&vertices);
    let n = faces.count.max(1) as f64;
    DirectionStats {
        face_samples: faces.count as usize,
        edge_samples: edges.count as usize,
        vertex_samples: vertices.count as usize,
        max: all.max.max(0.0),
        max_at: all.max_at,
        mean: faces.sum / n,
        rms: (faces.sum2 / n).sqrt(),
    }
}

/// What every sample is measured against, and how.
struct Probe<'a> {
    to: &'a Bvh,
    seed: u64,
    floor: f64,
    cancel: &'a Cancel,
}

/// Faces: counts by area, points uniform in each face (Turk's square-root mapping).
fn sample_faces(from: &Surface, probe: &Probe<'_>, total: usize, offset: f64) -> Partial {
    let positions = &from.positions;
    let face_counts = allocate(&from.areas, total, offset);
    chunked(from.triangles.len(), probe.cancel, |range, acc| {
        let mut stack = Vec::with_capacity(64);
        let mut hint = None;
        for f in range {
            let k = face_counts[f];
            if k == 0 {
                continue;
            }
            let [a, b, c] = from.triangles[f].map(|v| positions[v as usize]);
            let mut rng = SplitMix64::stream(probe.seed, SALT_FACE, f as u64);
            for _ in 0..k {
                let s = rng.next_f64().sqrt();
                let t = rng.next_f64();
                let p = a * (1.0 - s) + b * (s * (1.0 - t)) + c * (s * t);
                let d = distance(probe.to, p, &mut hint, &mut stack, probe.floor);
                acc.add(d, p);
            }
        }
    })
}

/// Edges: counts by length, points stratified along each edge.
fn sample_edges(from: &Surface, probe: &Probe<'_>, total: usize, offset: f64) -> Partial {
    let positions = &from.positions;
    let lengths: Vec<f64> = from
        .edges
        .iter()
        .map(|&[u, v]| positions[u as usize].distance(positions[v as usize]))
        .collect();
    let edge_counts = allocate(&lengths, total, offset);
    chunked(from.edges.len(), probe.cancel, |range, acc| {
        let mut stack = Vec::with_capacity(64);
        let mut hint = None;
        for e in range {
            let k = edge_counts[e];
            if k == 0 {
                continue;
            }
            let [u, v] = from.edges[e];
            let (a, b) = (positions[u as usize], positions[v as usize]);
            let mut rng = SplitMix64::stream(probe.seed, SALT_EDGE, e as u64);
            for j in 0..k {
                let t = (j as f64 + rng.next_f64()) / k as f64;
                let p = a + (b - a) * t;
                let d = distance(probe.to, p, &mut hint, &mut stack, probe.floor);
                acc.add(d, p);
            }
        }
    })
}

/// Vertices: every one that a triangle uses.
fn sample_vertices(from: &Surface, probe: &Probe<'_>) -> Partial {
    chunked(from.used_vertices.len(), probe.cancel, |range, acc| {
        let mut stack = Vec::with_capacity(64);
        let mut hint = None;
        for i in range {
            let p = from.positions[from.used_vertices[i] as usize];
            let d = distance(probe.to, p, &mut hint, &mut stack, probe.floor);
            acc.add(d, p);
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allocation_is_proportional_and_exact() {
        let weights = [1.0, 3.0, 0.0, 6.0];
        for offset in [0.0, 0.3, 0.999] {
            let counts = allocate(&weights, 1000, offset);
            assert_eq!(counts, vec![100, 300, 0, 600]);
        }
        let counts = allocate(&[1.0; 7], 10, 0.5);
        assert_eq!(counts.iter().sum::<u64>(), 10);
        assert!(counts.iter().all(|&c| c == 1 || c == 2));
    }

    #[test]
    fn splitmix_reference_values() {
        // First outputs of SplitMix64 seeded with 0 (Vigna's reference implementation).
        let mut g = SplitMix64::new(0);
        assert_eq!(g.next_u64(), 0xe220_a839_7b1d_cdaf);
        assert_eq!(g.next_u64(), 0x6e78_9e6a_a1b9_65f4);
    }
}

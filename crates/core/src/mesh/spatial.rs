//! Spatial ordering for memory locality: vertices sorted along a Morton (Z-order) curve, so
//! that vertices close in space are close in memory. Local operations over a one-ring then
//! touch a few cache lines instead of scattered ones — the dominant cost of decimating a
//! large scan whose file order is arbitrary.

use glam::Vec3;
use rayon::prelude::*;

/// Spreads the low 21 bits of `x` so that there are two zero bits between each.
fn spread(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// The Morton code of `p` within the box `lo`..`lo + size` (21 bits per axis).
fn morton(p: Vec3, lo: Vec3, inv_size: Vec3) -> u64 {
    let q = ((p - lo) * inv_size).clamp(Vec3::ZERO, Vec3::ONE) * 2_097_151.0;
    spread(q.x as u64) | spread(q.y as u64) << 1 | spread(q.z as u64) << 2
}

/// Vertex ids sorted along the Morton curve of their positions (ties keep file order).
/// Non-finite coordinates sort as the box's low corner.
pub fn morton_order(positions: &[Vec3]) -> Vec<u32> {
    let finite = positions.iter().filter(|p| p.is_finite());
    let (lo, hi) = finite.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    });
    let size = (hi - lo).max(Vec3::splat(f32::MIN_POSITIVE));
    let inv = if lo.is_finite() {
        size.recip()
    } else {
        Vec3::ZERO
    };
    let lo = if lo.is_finite() { lo } else { Vec3::ZERO };
    let mut keyed: Vec<(u64, u32)> = positions
        .par_iter()
        .enumerate()
        .map(|(i, &p)| {
            let code = if p.is_finite() { morton(p, lo, inv) } else { 0 };
            (code, i as u32)
        })
        .collect();
    radix_sort(&mut keyed);
    keyed.into_par_iter().map(|(_, i)| i).collect()
}

/// Bits of the key one pass of [`radix_sort`] sorts on.
const DIGIT_BITS: u32 = 11;

/// Sorts `keyed` by code, ties in the order they come: least significant digit first,
/// each pass a stable counting sort, skipping the digits every code shares (the high bits
/// of a flat model's): linear in the vertices. Given the ids ascending, the same order as
/// sorting the pairs.
fn radix_sort(keyed: &mut Vec<(u64, u32)>) {
    let digits = u64::BITS.div_ceil(DIGIT_BITS);
    let buckets = 1usize << DIGIT_BITS;
    let digit = |code: u64, d: u32| ((code >> (d * DIGIT_BITS)) as usize) & (buckets - 1);
    let mut counts = vec![vec![0u32; buckets]; digits as usize];
    for &(code, _) in keyed.iter() {
        for (d, count) in counts.iter_mut().enumerate() {
            count[digit(code, d as u32)] += 1;
        }
    }
    let mut other = vec![(0u64, 0u32); keyed.len()];
    for (d, count) in counts.iter_mut().enumerate() {
        if count.iter().any(|&c| c as usize == keyed.len()) {
            continue;
        }
        let mut next = 0u32;
        for c in count.iter_mut() {
            (*c, next) = (next, next + *c);
        }
        for &(code, i) in keyed.iter() {
            let slot = &mut count[digit(code, d as u32)];
            other[*slot as usize] = (code, i);
            *slot += 1;
        }
        std::mem::swap(keyed, &mut other);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_radix_sort_orders_as_sorting_the_pairs() {
        // Codes spread over every digit, many repeated (ties keep their ids' order), and
        // codes equal in their high digits (the passes skipped).
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for shift in [0, 20, 40, 60] {
            let mut keyed: Vec<(u64, u32)> = (0..5000u32).map(|i| (next() >> shift, i)).collect();
            let repeats: Vec<(u64, u32)> = (5000..6000u32)
                .map(|i| (keyed[(i % 97) as usize].0, i))
                .collect();
            keyed.extend(repeats);
            let mut expected = keyed.clone();
            expected.sort_unstable();
            radix_sort(&mut keyed);
            assert_eq!(keyed, expected, "codes shifted by {shift}");
        }
    }

    #[test]
    fn octants_come_in_z_order_and_every_vertex_once() {
        let p: Vec<Vec3> = (0..8)
            .rev()
            .map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2 & 1) as f32))
            .collect();
        // p[k] is corner 7 - k; Z-order visits corners 0..8 in order.
        assert_eq!(morton_order(&p), vec![7, 6, 5, 4, 3, 2, 1, 0]);
        let q = vec![Vec3::NAN, Vec3::ONE, Vec3::ZERO];
        let mut o = morton_order(&q);
        o.sort_unstable();
        assert_eq!(o, vec![0, 1, 2]);
    }
}

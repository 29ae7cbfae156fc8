//! Filtering the passes' vertex lists on all cores, in order, into buffers kept from pass to
//! pass. A filtered `collect` on rayon gathers pieces in fresh vectors and joins them, which
//! costs more than the filtering here; instead each chunk compacts into its own stretch of
//! the buffer and the stretches close up.

use rayon::prelude::*;

/// Items per chunk: big enough that a chunk's task outweighs its scheduling, small enough
/// that the cores share a few hundred thousand items evenly.
const CHUNK: usize = 8192;

/// Writes `f(x)` for every `x` of `src` that gives one to the start of `buf`, in `src`'s
/// order, on all cores; returns how many. `buf` is grown to `src.len()` when shorter and
/// never shrunk: what follows the count is stale.
pub(crate) fn filter_map_into<T, U>(
    src: &[T],
    buf: &mut Vec<U>,
    f: impl Fn(&T) -> Option<U> + Sync,
) -> usize
where
    T: Sync,
    U: Copy + Default + Send,
{
    if buf.len() < src.len() {
        buf.resize(src.len(), U::default());
    }
    let counts: Vec<usize> = src
        .par_chunks(CHUNK)
        .zip(buf[..src.len()].par_chunks_mut(CHUNK))
        .map(|(from, to)| {
            let mut n = 0;
            for y in from.iter().filter_map(&f) {
                to[n] = y;
                n += 1;
            }
            n
        })
        .collect();
    close_up(buf, &counts)
}

/// Keeps the items of `list` for which `keep`, in order, on all cores.
pub(crate) fn retain(list: &mut Vec<u32>, keep: impl Fn(u32) -> bool + Sync) {
    let counts: Vec<usize> = list
        .par_chunks_mut(CHUNK)
        .map(|chunk| {
            let mut n = 0;
            for i in 0..chunk.len() {
                let x = chunk[i];
                if keep(x) {
                    chunk[n] = x;
                    n += 1;
                }
            }
            n
        })
        .collect();
    let len = close_up(list, &counts);
    list.truncate(len);
}

/// Moves the first `counts[i]` items of every chunk `i` of `buf` to follow those of the
/// chunk before; returns their total.
fn close_up<U: Copy>(buf: &mut [U], counts: &[usize]) -> usize {
    let mut end = 0;
    for (i, &n) in counts.iter().enumerate() {
        let start = i * CHUNK;
        buf.copy_within(start..start + n, end);
        end += n;
    }
    end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filtering_keeps_the_order_across_chunks() {
        // Several chunks, the last one short, some chunks emptied entirely.
        let src: Vec<u32> = (0..5 * CHUNK as u32 + 123).collect();
        let pick = |&x: &u32| x % 7 == 3 && !(CHUNK as u32..2 * CHUNK as u32).contains(&x);
        let expected: Vec<u64> = src
            .iter()
            .filter(|x| pick(x))
            .map(|&x| 2 * u64::from(x))
            .collect();
        let mut buf = vec![9u64; 3];
        let n = filter_map_into(&src, &mut buf, |x| pick(x).then(|| 2 * u64::from(*x)));
        assert_eq!(&buf[..n], &expected[..]);
        // The buffer is reused: a second, shorter filtering writes over the first's.
        let n = filter_map_into(&src[..CHUNK + 5], &mut buf, |&x| {
            (x % 1000 == 0).then_some(u64::from(x))
        });
        assert_eq!(
            &buf[..n],
            &[0, 1000, 2000, 3000, 4000, 5000, 6000, 7000, 8000]
        );

        let mut list = src.clone();
        retain(&mut list, |x| pick(&x));
        let expected: Vec<u32> = src.iter().copied().filter(|x| pick(x)).collect();
        assert_eq!(list, expected);
        retain(&mut list, |_| false);
        assert!(list.is_empty());
    }
}

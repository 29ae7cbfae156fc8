//! The rayon pool the binaries decimate on: the calling thread joins it as one of its
//! workers, and how many threads it has (`--threads`, [`with_threads`]).
//!
//! By default rayon keeps a pool beside the thread that calls into it: every parallel step
//! from that thread queues its work in the pool, wakes a worker and sleeps until the step is
//! done, and the serial code between steps runs on a thread of its own. The collapse loop
//! takes a few hundred such steps on a large scan, so on a machine with few cores that
//! hand-over is a visible share of the run. As a worker, the calling thread starts each
//! step's work itself and the other workers steal from it; the pool keeps the same number
//! of threads (`RAYON_NUM_THREADS` or one per core), the calling one included. With one
//! thread the pool is the calling thread alone: every parallel step runs on it in order.
//! The result is the same for every number of threads.

/// Makes the calling thread a worker of rayon's global pool. Call it before anything runs
/// in parallel; later calls, or a pool that already exists, leave the pool as it is.
pub fn join_pool() {
    join_pool_of(None);
}

/// As [`join_pool`], with a pool of `threads` threads, the calling one included (`None`:
/// `RAYON_NUM_THREADS` or one per core).
pub fn join_pool_of(threads: Option<usize>) {
    let mut builder = rayon::ThreadPoolBuilder::new().use_current_thread();
    if let Some(n) = threads {
        builder = builder.num_threads(n.max(1));
    }
    // Fails only when the global pool was already built: then it stays as it was.
    let _ = builder.build_global();
}

/// Runs `f` on a pool of `threads` threads of its own (at least one), the calling thread
/// one of them, so that everything `f` runs in parallel (a [`crate::api::simplify`]) uses
/// that many threads and no more. Where no such pool can be made (the calling thread is
/// already a worker of another pool, or no thread can be started), `f` runs on the pool
/// the calling thread would use anyway.
pub fn with_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    let n = threads.max(1);
    let own = rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .use_current_thread()
        .build();
    match own {
        Ok(pool) => pool.install(f),
        Err(_) => match rayon::ThreadPoolBuilder::new().num_threads(n).build() {
            Ok(pool) => pool.install(f),
            Err(_) => f(),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_inside_with_threads_sees_that_many_threads() {
        assert_eq!(with_threads(1, rayon::current_num_threads), 1);
        assert_eq!(with_threads(3, rayon::current_num_threads), 3);
        assert_eq!(with_threads(0, rayon::current_num_threads), 1);
    }
}

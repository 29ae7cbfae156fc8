//! The rayon pool the binaries decimate on: the calling thread joins it as one of its
//! workers.
//!
//! By default rayon keeps a pool beside the thread that calls into it: every parallel step
//! from that thread queues its work in the pool, wakes a worker and sleeps until the step is
//! done, and the serial code between steps runs on a thread of its own. The collapse loop
//! takes a few hundred such steps on a large scan, so on a machine with few cores that
//! hand-over is a visible share of the run. As a worker, the calling thread starts each
//! step's work itself and the other workers steal from it; the pool keeps the same number
//! of threads (`RAYON_NUM_THREADS` or one per core), the calling one included.

/// Makes the calling thread a worker of rayon's global pool. Call it before anything runs
/// in parallel; later calls, or a pool that already exists, leave the pool as it is.
pub fn join_pool() {
    // Fails only when the global pool was already built: then it stays as it was.
    let _ = rayon::ThreadPoolBuilder::new()
        .use_current_thread()
        .build_global();
}

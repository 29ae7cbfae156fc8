//! `Job`: one of the viewer's long computations — a decimation, a progressive mesh, a metro
//! measurement — run on a thread of its own, so that the window keeps drawing while it
//! runs. The job reports the fraction done (the status line's bar) and is asked to stop
//! with [`Job::cancel`] (`Esc`); its result is taken by [`Job::poll`], never waited for by a
//! frame.

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{self, Receiver, TryRecvError};
use std::sync::Arc;
use std::time::{Duration, Instant};

use decimate_core::decimate::Cancel;

/// A computation running on its own thread, with its own rayon pool (see [`spawn`]).
pub struct Job<T> {
    /// What the job does, in words ("decimating viewport 2: 90 %").
    pub what: String,
    started: Instant,
    /// The fraction done, as `f32` bits; written by the job, read by the frames.
    progress: Arc<AtomicU32>,
    cancel: Cancel,
    result: Receiver<Option<T>>,
}

/// Where a job stands.
#[derive(Debug)]
pub enum Poll<T> {
    Running,
    Done(T),
    /// It stopped on a cancel request, or was cancelled after it ended.
    Cancelled,
    /// Its thread panicked or could not start (the message says which).
    Failed(String),
}

/// Starts `work` on a new thread, which gets a rayon pool of its own (the thread one of its
/// workers): the parallel steps of a decimation never queue behind the window's, nor the
/// window's behind them; the pool's threads run at the window's priority. `work`
/// gets a progress callback (0..=1) and the cancel flag, and returns `None` when it stopped
/// on that flag.
pub fn spawn<T, F>(what: String, work: F) -> Job<T>
where
    T: Send + 'static,
    F: FnOnce(&mut dyn FnMut(f32), &Cancel) -> Option<T> + Send + 'static,
{
    let progress = Arc::new(AtomicU32::new(0.0f32.to_bits()));
    let cancel = Cancel::new();
    let (send, result) = mpsc::channel();
    let (shared, flag) = (progress.clone(), cancel.clone());
    let body = move || {
        let mut report = |fraction: f32| shared.store(fraction.to_bits(), Ordering::Relaxed);
        let run = || work(&mut report, &flag);
        let out = match rayon::ThreadPoolBuilder::new().use_current_thread().build() {
            Ok(pool) => pool.install(run),
            // No pool of its own: the job runs on the global one.
            Err(_) => run(),
        };
        // The receiver is gone when the viewer forgot the job (cancelled, or quit).
        let _ = send.send(out);
    };
    let job = Job {
        what,
        started: Instant::now(),
        progress,
        cancel,
        result,
    };
    if let Err(e) = std::thread::Builder::new()
        .name("decimate-job".into())
        .spawn(body)
    {
        // The sender went with the closure: `poll` reports the job as failed.
        eprintln!("decimate: cannot start a worker thread: {e}");
    }
    job
}

impl<T> Job<T> {
    /// The fraction done, 0 to 1.
    pub fn progress(&self) -> f32 {
        f32::from_bits(self.progress.load(Ordering::Relaxed)).clamp(0.0, 1.0)
    }

    pub fn elapsed(&self) -> Duration {
        self.started.elapsed()
    }

    /// Asks the job to stop at its next check; its result, if it still ends with one, is
    /// reported as [`Poll::Cancelled`].
    pub fn cancel(&self) {
        self.cancel.request();
    }

    /// The job's result once it has ended; never blocks.
    pub fn poll(&self) -> Poll<T> {
        match self.result.try_recv() {
            Err(TryRecvError::Empty) => Poll::Running,
            Err(TryRecvError::Disconnected) => {
                Poll::Failed(format!("{}: the worker thread stopped", self.what))
            }
            Ok(_) if self.cancel.requested() => Poll::Cancelled,
            Ok(Some(out)) => Poll::Done(out),
            Ok(None) => Poll::Cancelled,
        }
    }

    /// Blocks until the job ends (tests, and `shot`, which has no frames to keep drawing).
    pub fn wait(&self) -> Poll<T> {
        match self.result.recv() {
            Err(_) => Poll::Failed(format!("{}: the worker thread stopped", self.what)),
            Ok(_) if self.cancel.requested() => Poll::Cancelled,
            Ok(Some(out)) => Poll::Done(out),
            Ok(None) => Poll::Cancelled,
        }
    }

    /// The status line's words while the job runs: what, a bar, the share done, how to stop.
    pub fn status(&self) -> String {
        let fraction = self.progress();
        // Until the first progress report the job prepares (welding, ranking, building its
        // queue): said so, rather than a bar stuck at 0 % that reads as a hang.
        let phase = if fraction > 0.0 { "" } else { " preparing…" };
        format!(
            "{} {} {:.0} %{phase} ({:.1} s) — Esc cancels",
            self.what,
            bar(fraction),
            100.0 * fraction,
            self.elapsed().as_secs_f64()
        )
    }
}

/// Cells of the status line's progress bar.
const BAR_CELLS: usize = 20;

/// A text progress bar of `fraction` (0 to 1).
pub fn bar(fraction: f32) -> String {
    let full = ((fraction.clamp(0.0, 1.0) * BAR_CELLS as f32).round() as usize).min(BAR_CELLS);
    format!("[{}{}]", "#".repeat(full), "-".repeat(BAR_CELLS - full))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_job_reports_its_progress_and_result() {
        let (go, gate) = mpsc::channel::<()>();
        let job = spawn("counting".into(), move |progress, _| {
            progress(0.5);
            gate.recv().ok()?;
            Some(42)
        });
        let start = Instant::now();
        while job.progress() < 0.5 {
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "no progress seen"
            );
            std::thread::yield_now();
        }
        assert!(matches!(job.poll(), Poll::Running));
        assert!(job
            .status()
            .starts_with("counting [##########----------] 50 %"));
        go.send(()).unwrap_or_else(|e| panic!("{e}"));
        assert!(matches!(job.wait(), Poll::Done(42)));
    }

    #[test]
    fn a_cancelled_job_stops_and_says_so() {
        let job = spawn("spinning".into(), |_, cancel: &Cancel| {
            while !cancel.requested() {
                std::thread::sleep(Duration::from_millis(1));
            }
            None::<()>
        });
        assert!(matches!(job.poll(), Poll::Running));
        job.cancel();
        assert!(matches!(job.wait(), Poll::Cancelled));
        // A result that arrives after the cancel is not shown either.
        let job = spawn("quick".into(), |_, _| Some(1));
        job.cancel();
        assert!(matches!(job.wait(), Poll::Cancelled));
    }

    #[test]
    fn a_panicking_job_is_a_failure_not_a_hang() {
        let job = spawn("failing".into(), |_, _| -> Option<()> {
            panic!("on purpose")
        });
        assert!(matches!(job.wait(), Poll::Failed(_)));
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_jobs_threads_run_at_the_windows_priority() {
        use rayon::prelude::*;
        // SAFETY: gettid and getpriority only read their integer arguments.
        let nice =
            || unsafe { libc::getpriority(libc::PRIO_PROCESS, libc::gettid() as libc::id_t) };
        let window = nice();
        let job = spawn("nice".into(), move |_, _| {
            let workers: Vec<i32> = (0..64).into_par_iter().map(|_| nice()).collect();
            Some((nice(), workers))
        });
        let Poll::Done((own, workers)) = job.wait() else {
            panic!("the job did not end");
        };
        assert_eq!(own, window, "the job's thread is nicer than the window");
        assert!(workers.iter().all(|&n| n == window), "{workers:?}");
    }

    #[test]
    fn the_bar_fills_with_the_fraction() {
        assert_eq!(bar(0.0), format!("[{}]", "-".repeat(20)));
        assert_eq!(bar(1.0), format!("[{}]", "#".repeat(20)));
        assert_eq!(bar(0.25), "[#####---------------]");
        assert_eq!(bar(7.0), bar(1.0));
    }
}

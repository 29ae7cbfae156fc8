//! Running core work with the GIL released and Ctrl-C honoured: the work runs on a scoped
//! thread while the calling thread waits for it in short slices, checking Python's signal
//! handlers between them (only the main thread sees Ctrl-C). A pending KeyboardInterrupt
//! requests the run's cancel flag, waits for the core to stop at its next check, and is
//! raised.

use std::sync::mpsc;
use std::time::Duration;

use decimate_core::cancel::Cancel;
use pyo3::prelude::*;

/// How long the caller waits between two looks at Python's signals.
/// Runs `work` on `threads` threads (the calling one included), or on the shared pool
/// when `None`: the result is the same for every count.
pub fn on_threads<T: Send>(threads: Option<usize>, work: impl FnOnce() -> T + Send) -> T {
    match threads {
        Some(n) => decimate_core::api::with_threads(n, work),
        None => work(),
    }
}

const SLICE: Duration = Duration::from_millis(50);

/// Runs `work` off the GIL; `cancel` is requested when a signal handler raises.
pub fn interruptible<T, F>(py: Python<'_>, cancel: &Cancel, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> T + Send,
{
    std::thread::scope(|s| {
        let (tx, rx) = mpsc::channel();
        s.spawn(move || {
            // A panic in the core comes back as an error, not a crash of the interpreter.
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
            // The receiver only goes away once this thread is joined: nothing to report.
            let _ = tx.send(result);
        });
        let mut interrupt = None;
        let mut rx = rx;
        loop {
            // The receiver travels into the GIL-free closure and back (it is not Sync).
            let (got, back) = py.detach(move || (rx.recv_timeout(SLICE), rx));
            rx = back;
            match got {
                Ok(result) => {
                    return match (interrupt, result) {
                        (Some(e), _) => Err(e),
                        (None, Ok(value)) => Ok(value),
                        (None, Err(_)) => Err(pyo3::exceptions::PyRuntimeError::new_err(
                            "internal error in decimate-core (a bug: please report it)",
                        )),
                    }
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    return Err(pyo3::exceptions::PyRuntimeError::new_err(
                        "the decimation thread stopped without a result",
                    ))
                }
            }
            if interrupt.is_none() {
                if let Err(e) = py.check_signals() {
                    cancel.request();
                    interrupt = Some(e);
                }
            }
        }
    })
}

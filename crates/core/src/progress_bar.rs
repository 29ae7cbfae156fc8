//! What a long command-line run says as it goes (a decimation, a tiled run), shared by the
//! threads that do the work: step messages (one line each) and, on a terminal, a one-line
//! progress bar over the whole run that the messages are printed above.

use std::io::Write;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Messages and the progress bar of one run; `Sync`, so tile threads report through it.
pub struct Progress {
    state: Mutex<State>,
}

struct State {
    /// What the bar says it is doing.
    label: &'static str,
    messages: bool,
    bar: bool,
    start: Instant,
    last: Option<Instant>,
    /// Whether the bar is on screen (a message clears it first).
    shown: bool,
    fraction: f32,
}

impl Progress {
    /// A tiled run's: `messages`: print step lines on stderr; `bar`: draw the bar (a
    /// terminal only).
    pub fn new(messages: bool, bar: bool) -> Self {
        Self::labelled("decimating in tiles", messages, bar)
    }

    /// The same with the bar saying `label`.
    pub fn labelled(label: &'static str, messages: bool, bar: bool) -> Self {
        Self {
            state: Mutex::new(State {
                label,
                messages,
                bar,
                start: Instant::now(),
                last: None,
                shown: false,
                fraction: 0.0,
            }),
        }
    }

    /// Nothing printed: for library callers and tests.
    pub fn silent() -> Self {
        Self::new(false, false)
    }

    /// One step line, above the bar.
    pub fn say(&self, message: &str) {
        let mut s = self.lock();
        if !s.messages {
            return;
        }
        let clear = if s.shown { "\r\x1b[K" } else { "" };
        eprintln!("{clear}{message}");
        s.shown = false;
        s.last = None;
        s.draw();
    }

    /// The whole run's fraction done, 0 to 1 (never goes back).
    pub fn set(&self, fraction: f32) {
        let mut s = self.lock();
        s.fraction = s.fraction.max(fraction.clamp(0.0, 1.0));
        s.draw();
    }

    /// Takes the bar off the screen at the end of the run.
    pub fn finish(&self) {
        let mut s = self.lock();
        if s.shown {
            eprint!("\r\x1b[K");
            s.shown = false;
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        // A thread that panicked while printing leaves nothing half-done worth refusing.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl State {
    /// Redraws the bar, once the run has lasted a second and at most ten times a second.
    fn draw(&mut self) {
        if !self.bar || self.start.elapsed() < Duration::from_secs(1) {
            return;
        }
        if self
            .last
            .is_some_and(|t| t.elapsed() < Duration::from_millis(100))
        {
            return;
        }
        self.last = Some(Instant::now());
        self.shown = true;
        let width = 40;
        let done = ((self.fraction * width as f32) as usize).min(width);
        eprint!(
            "\r{} [{}{}] {:>3.0}%",
            self.label,
            "#".repeat(done),
            " ".repeat(width - done),
            self.fraction * 100.0
        );
        let _ = std::io::stderr().flush();
    }
}

//! [`Cancel`]: a stop request shared between the thread that asks (the viewer's `Esc`) and
//! the long computations that look at it (decimation passes, metro's sampling chunks).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A request to stop, made from another thread (the viewer's `Esc`). Both algorithms look
/// at it at the head of each pass and each batch, and stop there: the model is left valid,
/// short of its target; metro looks before each chunk of samples. Clones share the flag;
/// the default is never set.
#[derive(Debug, Clone, Default)]
pub struct Cancel(Option<Arc<AtomicBool>>);

impl Cancel {
    /// A flag that [`Self::request`] on this or any clone sets.
    pub fn new() -> Self {
        Self(Some(Arc::new(AtomicBool::new(false))))
    }

    /// Asks the work holding this flag (or a clone) to stop.
    pub fn request(&self) {
        if let Some(flag) = &self.0 {
            flag.store(true, Ordering::Relaxed);
        }
    }

    /// Whether a stop was asked for.
    pub fn requested(&self) -> bool {
        self.0.as_ref().is_some_and(|f| f.load(Ordering::Relaxed))
    }
}

/// Two handles are equal when they share one flag (or neither has one).
impl PartialEq for Cancel {
    fn eq(&self, other: &Self) -> bool {
        match (&self.0, &other.0) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        }
    }
}

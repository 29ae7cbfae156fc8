//! `Settle`: whether the window's view is moving or at rest, and so how many samples per
//! pixel the next frame is drawn with — single-sampled while the camera moves (drag, keys,
//! wheel, slider, geomorph), the chosen multisampling once it has rested a moment, as CAD
//! viewers do (docs/design.md#msaa).

use std::time::{Duration, Instant};

/// How long after the last camera input the view still counts as moving: long enough to
/// bridge the gaps between a drag's events, short enough that the sharp frame follows the
/// release at once (docs/design.md#msaa).
pub const SETTLE: Duration = Duration::from_millis(150);

/// The view's motion state: the last input that moved it, and whether a drag or geomorph
/// is in progress.
#[derive(Debug, Default, Clone, Copy)]
pub struct Settle {
    last_input: Option<Instant>,
}

impl Settle {
    /// The camera or the level shown was moved at `now`.
    pub fn moved(&mut self, now: Instant) {
        self.last_input = Some(now);
    }

    /// True while the view moves: `held` (a button drags, a geomorph plays) or an input
    /// came less than [`SETTLE`] ago.
    pub fn moving(&self, held: bool, now: Instant) -> bool {
        held || self
            .last_input
            .is_some_and(|t| now.saturating_duration_since(t) < SETTLE)
    }

    /// When the view comes to rest if nothing moves it again (for the frame drawn then).
    pub fn rests_at(&self) -> Option<Instant> {
        self.last_input.map(|t| t + SETTLE)
    }

    /// Samples per pixel of the frame drawn at `now`: 1 while moving, `msaa` at rest.
    pub fn samples(&self, msaa: u32, held: bool, now: Instant) -> u32 {
        if self.moving(held, now) {
            1
        } else {
            msaa
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_sampled_while_moving_multisampled_once_at_rest() {
        let start = Instant::now();
        let mut settle = Settle::default();
        assert_eq!(settle.samples(4, false, start), 4, "never moved: at rest");
        assert_eq!(settle.samples(4, true, start), 1, "a drag in progress");
        settle.moved(start);
        let soon = start + SETTLE / 2;
        assert_eq!(settle.samples(4, false, soon), 1, "just moved");
        assert_eq!(settle.rests_at(), Some(start + SETTLE));
        let later = start + SETTLE;
        assert_eq!(settle.samples(4, false, later), 4, "rested");
        assert_eq!(settle.samples(4, true, later), 1, "a geomorph still plays");
        assert_eq!(settle.samples(1, false, later), 1, "MSAA off stays off");
        // Each input restarts the wait.
        settle.moved(later);
        assert_eq!(settle.samples(4, false, later + SETTLE / 2), 1);
        assert_eq!(settle.samples(4, false, later + SETTLE * 2), 4);
    }
}

//! When a count target loosens the rules that hold vertices back: the feature angle (a
//! corner is never removed, a crease only along itself) and folded rings (never filled
//! until the candidates run out on a manifold mesh). See docs/design.md#schroeder-loosen.
//!
//! Before the first removal the angle is raised while corners would crowd the result
//! ([`relax_early`]); before a pass short of candidates for the removals still needed,
//! the rules are loosened a step ([`when_short`]). Running out of candidates loosens them
//! too (`removal_passes`).

use super::{Decimator, RELAX_STEP_DEG};
use crate::decimate::{Limits, Outcome};

/// Before the first removal the feature angle is raised while its corners are more than
/// this share of the vertices the count target leaves (docs/design.md#schroeder-relax-early).
const MAX_CORNER_SHARE: f64 = 0.5;

/// The early relaxation stops at a right angle; past it only [`when_short`] and running
/// out of candidates relax further (docs/design.md#schroeder-relax-early).
const MAX_EARLY_ANGLE_DEG: f64 = 90.0;

/// Folded rings may be filled once the candidates are fewer than this many times the
/// removals still needed: a pass takes the cheapest half (`removal_passes::PASS_SHARE`),
/// and would otherwise reach into the dear half.
const SHORT_SHARE: usize = 2;

/// Whether a count target is short of candidates from the start: it needs more than half
/// of the live vertices. Folded rings are then filled from the first ranking on, rather
/// than re-ranked for at the first pass ([`when_short`]).
/// `live`: [`live_count`].
pub(super) fn short_from_start(
    d: &Decimator,
    limits: &Limits,
    outcome: &Outcome,
    live: usize,
) -> bool {
    live < SHORT_SHARE * d.removals_allowed(limits, outcome)
}

/// Vertices with a triangle.
pub(super) fn live_count(d: &Decimator) -> usize {
    (0..d.positions.len() as u32)
        .filter(|&v| !d.conn.incident(v).is_empty())
        .count()
}

/// Ranks every vertex, raising the feature angle in `RELAX_STEP_DEG` steps before any
/// removal while the corners it makes (counted by the ranking) are more than
/// `MAX_CORNER_SHARE` of the vertices the count target leaves: kept whatever their error,
/// they would crowd the result, and be relaxed in bulk at the end. `live`: [`live_count`].
pub(super) fn relax_early(d: &mut Decimator, limits: &Limits, outcome: &mut Outcome, live: usize) {
    // About two triangles per vertex on a triangle mesh (Euler's formula).
    let by_triangles = if (1..d.conn.triangle_count()).contains(&limits.keep_triangles) {
        limits.keep_triangles.div_ceil(2)
    } else {
        live
    };
    // `remove` at or above the live count: no vertex target.
    let by_vertices = live.checked_sub(limits.remove).unwrap_or(live);
    let left = by_vertices.min(by_triangles);
    while d.rank_all() as f64 > MAX_CORNER_SHARE * left as f64
        && outcome.feature_angle_deg < MAX_EARLY_ANGLE_DEG
    {
        raise_feature_angle(d, outcome);
    }
}

/// Before a pass short of candidates, loosens the rules one step: when the `candidates`
/// are fewer than `SHORT_SHARE` times the removals `needed`, folded rings may be filled;
/// when they are fewer than the removals needed, the feature angle goes up
/// `RELAX_STEP_DEG` (not under `--keep-features`, `--max-error`, `-p 100`). True when it
/// loosened them and re-ranked every vertex.
///
/// Otherwise the pass would take every candidate left, dear or not, and the next ones too,
/// one or two at a time, until none is left: on a scan cut far down, whose noise makes
/// corners and folds everywhere, those last dear removals cut the surface.
pub(super) fn when_short(
    d: &mut Decimator,
    limits: &Limits,
    outcome: &mut Outcome,
    candidates: usize,
    needed: usize,
) -> bool {
    if !d.unfold && candidates < SHORT_SHARE * needed {
        d.unfold = true;
    } else if candidates < needed && limits.relax_features && outcome.feature_angle_deg < 180.0 {
        raise_feature_angle(d, outcome);
    } else {
        return false;
    }
    d.rank_all();
    true
}

/// Raises the feature angle one `RELAX_STEP_DEG` step, up to 180° (the keys are not
/// re-ranked).
pub(super) fn raise_feature_angle(d: &mut Decimator, outcome: &mut Outcome) {
    outcome.feature_angle_deg = (outcome.feature_angle_deg + RELAX_STEP_DEG).min(180.0);
    d.cos_feature = outcome.feature_angle_deg.to_radians().cos();
}

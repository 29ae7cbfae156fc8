//! What both algorithms take and give for one model: the [`Limits`] a model is decimated
//! within (its share of the scene's target, the error bound, the feature angle, a
//! [`Cancel`] flag) and the [`Outcome`] of doing so.

pub use crate::cancel::Cancel;

/// A decimated model left with fewer vertices than this is dropped from the scene (the
/// original program's rule); a count never takes a model below it.
pub const MIN_VERTICES: usize = 4;

/// How far one model may be decimated.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// Most vertices to remove, counted as positions: a texture seam's two sides removed
    /// together count once (`decimate::point_counts`).
    pub remove: usize,
    /// The model's used vertices beyond the first at each position (texture-seam copies):
    /// its used vertices less these are the positions the four-vertex floor counts.
    pub seam_copies: usize,
    /// Stop once this many triangles or fewer are left.
    pub keep_triangles: usize,
    /// Never make a removal whose error exceeds this (model units).
    pub max_error: f64,
    /// Dihedral angle in degrees above which an edge is a feature edge.
    pub feature_angle_deg: f64,
    /// When no candidate is left before `remove`/`keep_triangles` is reached, raise the
    /// feature angle in `schroeder::RELAX_STEP_DEG` steps (up to 180°) and go on.
    pub relax_features: bool,
    /// qem: feature vertices never leave their features (`Params::keep_features`;
    /// vertex removal keeps them by never relaxing the feature angle).
    pub keep_features: bool,
    /// qem: scale fold angles to the mesh's sampling before the feature test
    /// ([`super::Params::scale_folds`]).
    pub scale_folds: bool,
    /// qem: what a collapse costs and where its kept vertex goes (`--cost`).
    pub cost: Cost,
    /// Stop early when this is set (checked between passes and batches).
    pub cancel: Cancel,
}

/// qem's cost and placement of a collapse.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Cost {
    /// Garland–Heckbert: the accumulated quadrics' error at their optimum.
    #[default]
    Quadric,
    /// Lindström–Turk, memoryless: volume and boundary change against the current mesh
    /// around the edge, placement by their constraints (`qem::lt_placement`).
    LindstromTurk,
}

/// What decimating one model did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// Vertices removed.
    pub removed: usize,
    /// Largest key of a removal made (accumulated distance, model units).
    pub max_error: f64,
    /// True when no candidate was left: nothing more can be removed.
    pub exhausted: bool,
    /// The feature angle in force at the end (larger than asked when relaxed).
    pub feature_angle_deg: f64,
    /// Vertices never removed because they were pinned (texture seams, `mesh::seams`, and
    /// borders shared with another model, `mesh::stitches`).
    pub pinned: usize,
    /// Of a fully decimated model (`exhausted`), the vertices whose removal only the
    /// closed-volume guard refuses (`decimate::closed`); 0 otherwise.
    pub closed_kept: usize,
}

impl Outcome {
    /// The outcome before any removal, with features from `feature_angle_deg` and `pinned`
    /// vertices held.
    pub(crate) fn nothing_removed(feature_angle_deg: f64, pinned: usize) -> Self {
        Self {
            removed: 0,
            max_error: 0.0,
            exhausted: false,
            feature_angle_deg,
            pinned,
            closed_kept: 0,
        }
    }
}

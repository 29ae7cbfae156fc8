//! What planning a collapse decides, shared by everything that plans, checks or makes one:
//! a vertex's [`Kind`] (where it may go) and a [`Plan`] (which end goes, where the other
//! moves, at what cost).

use glam::DVec3;

use crate::mesh::topology::corner_of;

/// What a vertex's one-ring says about where it may go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Interior,
    Boundary,
    /// Pinned (a texture seam's junction of three or more sides, a border shared with
    /// another model): never moves and never goes, but takes in a neighbour where it
    /// stands — an interior one, or one along a boundary edge (on a seam, with the other
    /// side's, into its copy there).
    Anchored,
    /// Non-manifold: on an edge of three or more triangles, or where several fans meet
    /// (a "bowtie"). Never moves; takes in a neighbour where it stands (an interior one,
    /// or one along a boundary edge), and goes only along a non-manifold edge into a
    /// complex vertex (see `Part::plan`), so that no collapse adds a non-manifold edge.
    Complex,
    /// Unused, on a degenerate triangle, or removed: never moved.
    Fixed,
}

/// A planned collapse: `remove` goes, `keep` moves to `position`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plan {
    pub remove: u32,
    pub keep: u32,
    pub position: DVec3,
    /// Squared geometric error of the placement.
    pub error2: f64,
    /// Cost that orders the collapses: the quadric plus the colour term.
    pub cost: f64,
    /// On a texture seam, the other side's edge (its removed end, its kept end): it
    /// collapses in the same step, to the same position (see `Part::plan`).
    pub twin: Option<[u32; 2]>,
    /// The kept vertex's texture coordinates, when the texture's quadric gives them (an
    /// interior collapse of a textured model); otherwise they are interpolated along the
    /// edge.
    pub texcoords: Option<[f32; 2]>,
    /// Into a junction copy (`keep`) from a vertex whose other outline edge runs to another
    /// copy at the same point: that copy, whose triangle with the removed end goes too
    /// (see `Part::join_junction`).
    pub junction: Option<u32>,
}

impl Plan {
    /// The other side's collapse of a seam plan: its own ends, the same position and cost.
    pub fn other_side(&self) -> Option<Self> {
        self.twin.map(|[remove, keep]| Self {
            remove,
            keep,
            twin: None,
            texcoords: None,
            junction: None,
            ..*self
        })
    }
}

/// The two corners of `tri` other than `v`, in the triangle's cyclic order after `v`.
pub(super) fn others(tri: [u32; 3], v: u32) -> [u32; 2] {
    let (_, next, prev) = corner_of(tri, v);
    [next, prev]
}

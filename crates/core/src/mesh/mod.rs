//! The data model shared by every reader, writer, algorithm and the viewer: a `Scene` of
//! `Model`s over flat arrays, plus topology (adjacency, vertex classification), normals and
//! welding built on top of them.

pub mod build;
pub(crate) mod classify;
pub(crate) mod face_colour_seams;
pub mod measure;
pub mod progressive;
pub mod repair;
pub mod rgba_image;
pub(crate) mod scene;
pub mod seams;
pub mod shapes;
pub(crate) mod spatial;
pub(crate) mod stitches;
pub(crate) mod topology;
pub(crate) mod union_find;
pub mod weld;

pub use scene::{Attribute, CopiedThrough, Instance, LocalTransform, Model, Node, NodeTree, Scene};

/// Asks the CPU to start loading the cache line holding `value`: a hint that hides memory
/// latency in loops that visit vertices in a data-dependent order; no effect on results.
#[inline]
pub fn prefetch<T>(value: &T) {
    prefetch_address(std::ptr::from_ref(value).cast::<u8>());
}

/// As [`prefetch`], for every cache line `value` spans (an 88-byte record at an 8-byte
/// offset can span three): one hint every 64 bytes from its start, and one at its last byte.
#[inline]
pub fn prefetch_all<T>(value: &T) {
    let start = std::ptr::from_ref(value).cast::<u8>();
    let size = size_of::<T>().max(1);
    for offset in (0..size).step_by(64) {
        prefetch_address(start.wrapping_add(offset));
    }
    prefetch_address(start.wrapping_add(size - 1));
}

#[inline]
fn prefetch_address(address: *const u8) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: SSE is in every x86_64 CPU, and a prefetch never faults or reads into Rust.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(address.cast::<i8>()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}

//! The data model shared by every reader, writer, algorithm and the viewer: a `Scene` of
//! `Model`s over flat arrays, plus topology (adjacency, vertex classification), normals and
//! welding built on top of them.

pub mod build;
pub mod classify;
pub mod measure;
pub mod scene;
pub mod shapes;
pub mod spatial;
pub mod topology;
pub mod weld;

pub use scene::{Attribute, Model, Scene};

/// Asks the CPU to start loading the cache line holding `value`: a hint that hides memory
/// latency in loops that visit vertices in a data-dependent order; no effect on results.
#[inline]
pub fn prefetch<T>(value: &T) {
    prefetch_address(std::ptr::from_ref(value).cast::<u8>());
}

/// As [`prefetch`], for every cache line `value` spans (an 88-byte record at an 8-byte
/// offset can span three).
#[inline]
pub fn prefetch_all<T>(value: &T) {
    const LINE: usize = 64;
    let start = std::ptr::from_ref(value).cast::<u8>();
    let first = start as usize / LINE;
    let last = (start as usize + size_of::<T>().max(1) - 1) / LINE;
    for line in 0..=last - first {
        // Addresses inside `value` (the first byte of each later line it reaches).
        let offset = (line * LINE).saturating_sub(start as usize % LINE);
        prefetch_address(start.wrapping_add(offset));
    }
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

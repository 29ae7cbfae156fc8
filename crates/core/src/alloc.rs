//! The binaries' global allocator: the system's, asking the kernel to back large blocks
//! (the mesh arrays: tens of MB for a million-triangle scan) with transparent huge pages.
//!
//! Decimation and metro visit those arrays in a data-dependent order: with 4 KiB pages
//! nearly every cache miss also misses the TLB (docs/design.md#huge-pages). Linux's default
//! `madvise` mode gives huge pages only to memory that asks, hence the advice; elsewhere it
//! is a no-op and allocation is the system's.

use std::alloc::{GlobalAlloc, Layout, System};

/// Blocks from this size on are advised to use huge pages.
const MIN_HUGE: usize = 4 << 20;

/// The huge page size the advice is aligned to (x86-64 and most arm64 kernels).
#[cfg(target_os = "linux")]
const HUGE_PAGE: usize = 2 << 20;

/// The system allocator, with huge-page advice for large blocks.
#[derive(Debug, Default, Clone, Copy)]
pub struct HugePages;

// SAFETY: every block comes from, and goes back to, `System` with the caller's layout
// unchanged; the advice touches no memory and never moves a block.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded unchanged, under the caller's contract for `alloc`.
        let block = unsafe { System.alloc(layout) };
        advise(block, layout.size());
        block
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded unchanged, under the caller's contract for `alloc_zeroed`.
        let block = unsafe { System.alloc_zeroed(layout) };
        advise(block, layout.size());
        block
    }

    unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
        // SAFETY: `block` came from `System` with this layout (see `alloc`).
        unsafe { System.dealloc(block, layout) }
    }

    unsafe fn realloc(&self, block: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: forwarded unchanged, under the caller's contract for `realloc`.
        let moved = unsafe { System.realloc(block, layout, new_size) };
        advise(moved, new_size);
        moved
    }
}

/// Makes the C allocator map every block from `MIN_HUGE` on by itself and unmap it when it
/// is freed, so that a freed mesh array goes back to the system at once. By default glibc
/// raises that threshold to the size of each such block freed (up to 32 MiB), and later
/// arrays below it then come from the heap, where freeing them leaves holes the process
/// keeps (docs/design.md#in-core-memory). Called once, first thing in a binary's `main`.
pub fn return_large_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        // SAFETY: mallopt only sets a tuning parameter of the C allocator, before any
        // thread is started.
        unsafe { libc::mallopt(libc::M_MMAP_THRESHOLD, MIN_HUGE as libc::c_int) };
    }
}

/// Advises the kernel to back the whole huge pages inside `block..block + size` with huge
/// pages (large blocks only). Errors are ignored: the advice is only a hint.
fn advise(block: *mut u8, size: usize) {
    #[cfg(target_os = "linux")]
    if size >= MIN_HUGE && !block.is_null() {
        let first = block as usize;
        let start = first.next_multiple_of(HUGE_PAGE);
        let end = (first + size) / HUGE_PAGE * HUGE_PAGE;
        if end > start {
            // SAFETY: madvise(MADV_HUGEPAGE) on whole pages of a block this allocator owns
            // changes neither its contents nor its mapping, only how the kernel backs it.
            unsafe {
                libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (block, size);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_and_small_blocks_keep_their_contents() {
        let a = HugePages;
        for size in [64, MIN_HUGE + 12_345] {
            let layout = Layout::from_size_align(size, 64).unwrap_or(Layout::new::<u64>());
            // SAFETY: a non-zero layout; the block is written within its size, grown with
            // `realloc` under the same alignment and freed with its final layout.
            unsafe {
                let p = a.alloc_zeroed(layout);
                assert!(!p.is_null());
                assert_eq!(*p.add(size - 1), 0);
                *p.add(size - 1) = 7;
                let q = a.realloc(p, layout, 2 * size);
                assert!(!q.is_null());
                assert_eq!(*q.add(size - 1), 7);
                a.dealloc(q, Layout::from_size_align_unchecked(2 * size, 64));
            }
        }
    }
}

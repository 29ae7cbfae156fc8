//! Damaged files of every format, read, decimated and written again, one test per reader,
//! and the seed corpus the coverage-guided fuzzer starts from replayed. A crate of its own:
//! the tests silence the process's panic hook while they run, count every allocation and
//! exit the process on a hang, which would hide or cut short tests running beside them.

#[path = "../support/mod.rs"]
mod support;

mod alloc_cap;
mod corpus;
mod damaged_files;
mod seeds;

#[global_allocator]
static ALLOCATOR: alloc_cap::Counting = alloc_cap::Counting;

//! Damaged files of every format, read, decimated and written again. A crate of its own:
//! the test silences the process's panic hook while it runs and exits the process on a
//! hang, which would hide or cut short tests running beside it.

#[path = "../support/mod.rs"]
mod support;

mod damaged_files;
mod seeds;

//! Tiled decimation as a user and a scheduler run it: `decimate tile plan/run/status/merge`,
//! `nogui --tiles`, and the GNU parallel job script of tools/.

mod common;
mod errors;
mod memory;
mod pipeline;
mod scheduler;
mod slurm;

//! The `metro` error tool: distances against answers known in closed form, and its command
//! line.

mod cli;
mod exact;

//! Front-end tests: literals, ST, IL, SFC, declarations, configurations,
//! diagnostics and robustness.

mod common;
mod errors;
mod il;
mod literals;
mod programs;
mod sfc;
mod st;

//! The typed intermediate representation all three languages lower into.

pub mod chart;
pub mod fuse;
pub mod image;
pub mod op;
pub mod operands;
pub mod types;
pub mod verify;

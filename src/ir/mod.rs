//! The typed intermediate representation all three languages lower into.

pub mod byte_layout;
pub mod chart;
pub mod exception_codes;
pub mod fuse;
pub mod handler;
pub mod image;
pub mod index;
pub mod name_index;
pub mod op;
mod op_list;
pub mod operands;
pub mod refs;
pub mod retained;
pub mod type_table;
pub mod verify;

//! Values below every stage: numbers encoded into slots, IEC literal text
//! decoded (with or without the lexer) and printed back as IEC literals
//! and JSON. The
//! lexer, the checker, the executor and the runtime all use these, and
//! this module uses none of them.

pub mod convert;
pub mod encode;
pub mod format;
pub mod literal;
pub mod text;

//! Values below every stage: IEC literal text decoded into numbers and
//! printed back, and slot values formatted as IEC literals and JSON. The
//! lexer, the checker, the executor and the runtime all use these, and
//! this module uses none of them.

pub mod format;
pub mod literal;

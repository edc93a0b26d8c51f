//! Front-end: lexing and parsing of IL, ST and SFC source into the AST.

pub mod ast;
pub mod literal;

//! Renaming a symbol: every declaration and use of it, in every file,
//! and nothing else of the same name.

use super::Analysis;
use super::symbol::SymbolKind;
use crate::source::{FileId, Span};
use std::fmt;

/// Why a rename is refused.
#[derive(Debug, Clone, PartialEq)]
pub enum RenameError {
    /// No declared name at the cursor.
    NothingHere,
    /// The name is plcrun's own (a standard block or its pin).
    BuiltIn(String),
    /// The new name is not an identifier, or is a keyword.
    BadName(String),
    /// Something in the same scope already has the new name.
    Taken {
        /// The new name.
        name: String,
        /// Where that other declaration is.
        other: Span,
    },
}

impl fmt::Display for RenameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenameError::NothingHere => write!(f, "there is no declared name here to rename"),
            RenameError::BuiltIn(name) => {
                write!(
                    f,
                    "`{name}` is part of plcrun's standard library and cannot be renamed"
                )
            }
            RenameError::BadName(name) => write!(
                f,
                "`{name}` is not a valid IEC 61131-3 identifier (letters, digits and single underscores, not starting with a digit, not a keyword)"
            ),
            RenameError::Taken { name, .. } => {
                write!(f, "`{name}` is already declared in the same scope")
            }
        }
    }
}

impl std::error::Error for RenameError {}

/// Words that cannot name anything.
const RESERVED: &[&str] = &[
    "ABSTRACT",
    "ACTION",
    "AND",
    "ARRAY",
    "AT",
    "BY",
    "CASE",
    "CLASS",
    "CONFIGURATION",
    "CONSTANT",
    "CONTINUE",
    "DO",
    "ELSE",
    "ELSIF",
    "END_ACTION",
    "END_CASE",
    "END_CLASS",
    "END_CONFIGURATION",
    "END_FOR",
    "END_FUNCTION",
    "END_FUNCTION_BLOCK",
    "END_IF",
    "END_INTERFACE",
    "END_METHOD",
    "END_PROGRAM",
    "END_REPEAT",
    "END_RESOURCE",
    "END_STEP",
    "END_STRUCT",
    "END_TRANSITION",
    "END_TYPE",
    "END_VAR",
    "END_WHILE",
    "EXIT",
    "EXTENDS",
    "FALSE",
    "FINAL",
    "FOR",
    "FROM",
    "FUNCTION",
    "FUNCTION_BLOCK",
    "IF",
    "IMPLEMENTS",
    "INITIAL_STEP",
    "INTERFACE",
    "METHOD",
    "MOD",
    "NOT",
    "OF",
    "ON",
    "OR",
    "OVERLAP",
    "PRIORITY",
    "PRIVATE",
    "PROGRAM",
    "PROTECTED",
    "PUBLIC",
    "READ_ONLY",
    "READ_WRITE",
    "REF_TO",
    "REPEAT",
    "RESOURCE",
    "RETAIN",
    "RETURN",
    "STEP",
    "STRUCT",
    "SUPER",
    "TASK",
    "THEN",
    "THIS",
    "TO",
    "TRANSITION",
    "TRUE",
    "TYPE",
    "UNTIL",
    "VAR",
    "VAR_ACCESS",
    "VAR_CONFIG",
    "VAR_EXTERNAL",
    "VAR_GLOBAL",
    "VAR_INPUT",
    "VAR_IN_OUT",
    "VAR_OUTPUT",
    "VAR_TEMP",
    "WHILE",
    "WITH",
    "XOR",
];

/// True if `name` can be declared: an IEC identifier that is no keyword
/// and no elementary type name.
pub fn is_identifier(name: &str) -> bool {
    let bytes = name.as_bytes();
    let well_formed = !bytes.is_empty()
        && !bytes[0].is_ascii_digit()
        && bytes
            .iter()
            .all(|b| b.is_ascii_alphanumeric() || *b == b'_')
        && !name.contains("__")
        && !name.ends_with('_');
    let upper = name.to_ascii_uppercase();
    well_formed
        && !RESERVED.contains(&upper.as_str())
        && crate::elementary::ElemType::from_name(&upper).is_none()
}

impl Analysis {
    /// The name at `offset` and where it is, if it can be renamed.
    pub fn prepare_rename(&self, file: FileId, offset: u32) -> Result<Span, RenameError> {
        let o = self
            .occurrence_at(file, offset)
            .ok_or(RenameError::NothingHere)?;
        let symbol = self.symbol(o.symbol);
        if symbol.location.is_none() {
            return Err(RenameError::BuiltIn(symbol.name.clone()));
        }
        Ok(o.span)
    }

    /// Every span to replace by `new_name` to rename the name at
    /// `offset`: its declaration and each use, in every file.
    pub fn rename(
        &self,
        file: FileId,
        offset: u32,
        new_name: &str,
    ) -> Result<Vec<Span>, RenameError> {
        self.prepare_rename(file, offset)?;
        let id = self
            .symbol_at(file, offset)
            .ok_or(RenameError::NothingHere)?;
        if !is_identifier(new_name) {
            return Err(RenameError::BadName(new_name.to_string()));
        }
        let symbol = self.symbol(id);
        let key = new_name.to_ascii_uppercase();
        let clash = match symbol.parent {
            Some(parent) => self.table.member(parent, &key),
            None if symbol.kind == SymbolKind::Global => self.table.globals.get(&key).copied(),
            None => self.table.units.get(&key).copied(),
        };
        if let Some(other) = clash.filter(|&c| c != id)
            && let Some(span) = self.symbol(other).location
        {
            return Err(RenameError::Taken {
                name: new_name.to_string(),
                other: span,
            });
        }
        Ok(self.references(id).into_iter().map(|o| o.span).collect())
    }
}

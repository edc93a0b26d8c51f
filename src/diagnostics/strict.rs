//! Strict mode: every compatibility-extension warning becomes an error.
//!
//! A construct beyond IEC 61131-3 edition 3 that plcrun accepts for code
//! written for CODESYS, matiec or TwinCAT is reported with a warning code
//! `W300`-`W399` (for the CODESYS / TwinCAT dialect also `W485`-`W493`),
//! whichever stage finds it. `--strict` asks for pure IEC:
//! the rule below upgrades each of them to an error with the same code, so
//! the program is refused and the message stays the one documented.

use super::{Diagnostics, Severity};

/// True for the codes of compatibility-extension warnings, `W300`-`W399`,
/// and the CODESYS / TwinCAT dialect's `W485`-`W493`.
///
/// ```
/// use plcrun::is_compatibility_code;
/// assert!(is_compatibility_code("W360"));
/// assert!(is_compatibility_code("W485"));
/// assert!(!is_compatibility_code("W484"));
/// assert!(!is_compatibility_code("W020"));
/// assert!(!is_compatibility_code("E011"));
/// ```
pub fn is_compatibility_code(code: &str) -> bool {
    let number = code
        .strip_prefix('W')
        .filter(|n| n.len() == 3 && n.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|n| n.parse::<u16>().ok());
    matches!(number, Some(300..=399 | 485..=493))
}

/// The note added to a warning that strict mode made an error.
pub const STRICT_NOTE: &str =
    "an error because of --strict: this is an extension beyond IEC 61131-3 edition 3";

impl Diagnostics {
    /// Makes every compatibility-extension warning (see
    /// [`is_compatibility_code`]) an error with the same code and a note
    /// saying why; returns how many were changed.
    pub fn make_strict(&mut self) -> usize {
        let mut changed = 0;
        for d in &mut self.items {
            if d.severity == Severity::Warning && is_compatibility_code(d.code) {
                d.severity = Severity::Error;
                d.notes.push(STRICT_NOTE.to_string());
                changed += 1;
            }
        }
        changed
    }
}

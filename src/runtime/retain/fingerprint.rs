//! The fingerprint of a set of retained variables (their names and types)
//! and, when two sets differ, what differs.

use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use std::collections::HashMap;
use std::fmt;

/// The type of a retained value as the file spells it: `DINT`,
/// `STRING[80]`, `WSTRING[10]`, `INT(0..100)`, `ENUM(Red,Green)`.
pub(crate) fn type_text(types: &TypeTable, ty: TypeId) -> String {
    match &types.get(ty).kind {
        TypeKind::Elem(e) => e.name().to_string(),
        TypeKind::Str { wide, max } => {
            format!("{}[{max}]", if *wide { "WSTRING" } else { "STRING" })
        }
        TypeKind::Subrange { base, lo, hi } => format!("{}({lo}..{hi})", base.name()),
        TypeKind::Enum { values, .. } => {
            let names: Vec<&str> = values.iter().map(|(n, _)| n.as_str()).collect();
            format!("ENUM({})", names.join(","))
        }
        _ => types.name(ty).to_string(),
    }
}

/// 64-bit FNV-1a: small, stable across builds and platforms (the standard
/// library's hasher is not promised to be).
fn fnv1a(bytes: impl Iterator<Item = u8>, mut hash: u64) -> u64 {
    for b in bytes {
        hash ^= b as u64;
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    hash
}

/// The fingerprint of `(name, type)` pairs: 16 hex digits of a hash over
/// the pairs sorted by name, names case-folded (IEC names are not case
/// sensitive), so that reordering declarations does not change it.
pub(crate) fn fingerprint<'a>(pairs: impl Iterator<Item = (&'a str, &'a str)>) -> String {
    let mut lines: Vec<String> = pairs
        .map(|(n, t)| format!("{}:{}\n", n.to_ascii_lowercase(), t))
        .collect();
    lines.sort_unstable();
    let hash = lines
        .iter()
        .fold(0xcbf2_9ce4_8422_2325, |h, l| fnv1a(l.bytes(), h));
    format!("{hash:016x}")
}

/// A retained variable whose type differs between the file and the program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TypeChange {
    /// The variable.
    pub name: String,
    /// Its type in the file.
    pub file: String,
    /// Its type in the program.
    pub program: String,
}

/// How the retained variables of a file and of a program differ.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RetainDiff {
    /// Retained by the program but not in the file (they keep their
    /// initial values).
    pub not_in_file: Vec<String>,
    /// In the file but not retained by the program (their values are not
    /// used).
    pub not_in_program: Vec<String>,
    /// In both, with another type (not restored).
    pub changed_type: Vec<TypeChange>,
}

impl RetainDiff {
    /// The differences between the file's `(name, type)` pairs and the
    /// program's; names compare case-insensitively.
    pub(crate) fn between<'a>(
        file: impl Iterator<Item = (&'a str, &'a str)>,
        program: impl Iterator<Item = (&'a str, &'a str)>,
    ) -> RetainDiff {
        let mut diff = RetainDiff::default();
        let file: Vec<(&str, &str)> = file.collect();
        let in_file: HashMap<String, &str> = file
            .iter()
            .map(|(n, t)| (n.to_ascii_lowercase(), *t))
            .collect();
        let mut in_program = HashMap::new();
        for (name, ty) in program {
            in_program.insert(name.to_ascii_lowercase(), ());
            match in_file.get(&name.to_ascii_lowercase()) {
                None => diff.not_in_file.push(name.to_string()),
                Some(t) if *t != ty => diff.changed_type.push(TypeChange {
                    name: name.to_string(),
                    file: t.to_string(),
                    program: ty.to_string(),
                }),
                Some(_) => {}
            }
        }
        for (name, _) in file {
            if !in_program.contains_key(&name.to_ascii_lowercase()) {
                diff.not_in_program.push(name.to_string());
            }
        }
        diff
    }

    /// True when nothing differs.
    pub fn is_empty(&self) -> bool {
        self.not_in_file.is_empty()
            && self.not_in_program.is_empty()
            && self.changed_type.is_empty()
    }
}

/// At most this many names are listed per kind of difference.
const LISTED: usize = 10;

fn list(f: &mut fmt::Formatter<'_>, names: &[String]) -> fmt::Result {
    for (i, n) in names.iter().take(LISTED).enumerate() {
        write!(f, "{}{n}", if i == 0 { "" } else { ", " })?;
    }
    if names.len() > LISTED {
        write!(f, " and {} more", names.len() - LISTED)?;
    }
    Ok(())
}

impl fmt::Display for RetainDiff {
    /// One clause per kind of difference, separated by `; `.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut sep = "";
        if !self.not_in_file.is_empty() {
            write!(f, "retained by the program but not in the file: ")?;
            list(f, &self.not_in_file)?;
            sep = "; ";
        }
        if !self.not_in_program.is_empty() {
            write!(
                f,
                "{sep}in the file but no longer retained by the program: "
            )?;
            list(f, &self.not_in_program)?;
            sep = "; ";
        }
        if !self.changed_type.is_empty() {
            write!(f, "{sep}changed type: ")?;
            let texts: Vec<String> = (self.changed_type.iter())
                .map(|c| format!("{} (file {}, program {})", c.name, c.file, c.program))
                .collect();
            list(f, &texts)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fingerprint_ignores_order_and_case_of_names_but_not_types() {
        let a = fingerprint([("P.x", "INT"), ("P.y", "BOOL")].into_iter());
        let b = fingerprint([("p.Y", "BOOL"), ("P.X", "INT")].into_iter());
        let c = fingerprint([("P.x", "DINT"), ("P.y", "BOOL")].into_iter());
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_eq!(a.len(), 16);
    }

    #[test]
    fn diff_names_each_kind_of_difference() {
        let file = [("P.a", "INT"), ("P.b", "INT"), ("P.old", "BOOL")];
        let prog = [("P.a", "INT"), ("P.B", "DINT"), ("P.new", "TIME")];
        let d = RetainDiff::between(file.into_iter(), prog.into_iter());
        assert_eq!(d.not_in_file, vec!["P.new"]);
        assert_eq!(d.not_in_program, vec!["P.old"]);
        assert_eq!(d.changed_type.len(), 1);
        assert_eq!(
            d.to_string(),
            "retained by the program but not in the file: P.new; \
             in the file but no longer retained by the program: P.old; \
             changed type: P.B (file INT, program DINT)"
        );
    }
}

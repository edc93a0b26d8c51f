//! Other spellings of the standard functions, beyond edition 3: the typed
//! names matiec's library declares (`ADD_INT`, `GT_DINT`, `SEL_INT`,
//! `MOVE_REAL`, ..., `<generic>_<type>`) and the edition-1 names
//! `MULTIME`/`DIVTIME` (`MUL_TIME`/`DIV_TIME` since edition 2). Each is
//! the generic function with its overloaded inputs fixed to one type, so
//! they are derived here from the generic names instead of being listed.

use crate::elementary::ElemType;

/// The generic (overloaded) standard functions that have typed names.
const TYPED_GENERICS: &[&str] = &[
    "ADD", "SUB", "MUL", "DIV", "MOD", "EXPT", "AND", "OR", "XOR", "NOT", "MOVE", "ABS", "SQRT",
    "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SEL", "MAX", "MIN", "LIMIT",
    "MUX", "GT", "GE", "EQ", "LE", "LT", "NE", "SHL", "SHR", "ROL", "ROR",
];

/// A compatibility spelling of a standard function.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Alias {
    /// `<generic>_<type>`: the generic function with its overloaded
    /// inputs (and an overloaded result) of type `ty`.
    Typed {
        /// The generic name (`ADD`).
        generic: &'static str,
        /// The type named after it.
        ty: ElemType,
    },
    /// An edition-1 name of an edition-2/3 function.
    Legacy {
        /// The current name.
        current: &'static str,
    },
}

impl Alias {
    /// The name the function has in edition 3.
    pub(super) fn target(self) -> &'static str {
        match self {
            Alias::Typed { generic, .. } => generic,
            Alias::Legacy { current } => current,
        }
    }
}

/// The compatibility spelling `upper` (an upper-case name) stands for, if
/// it is one. A name that is a standard function of its own (`ADD_TIME`,
/// `TRUNC_INT`) is classified before this is asked.
pub(super) fn alias(upper: &str) -> Option<Alias> {
    match upper {
        "MULTIME" => {
            return Some(Alias::Legacy {
                current: "MUL_TIME",
            });
        }
        "DIVTIME" => {
            return Some(Alias::Legacy {
                current: "DIV_TIME",
            });
        }
        _ => {}
    }
    let (generic, ty) = upper.split_once('_')?;
    let generic = TYPED_GENERICS.iter().find(|g| **g == generic)?;
    let ty = ElemType::from_name(ty)?;
    Some(Alias::Typed { generic, ty })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typed_names_split_at_the_first_underscore() {
        assert_eq!(
            alias("ADD_INT"),
            Some(Alias::Typed {
                generic: "ADD",
                ty: ElemType::Int
            })
        );
        assert_eq!(
            alias("GT_TIME_OF_DAY"),
            Some(Alias::Typed {
                generic: "GT",
                ty: ElemType::Tod
            })
        );
        assert_eq!(alias("ADD_FOO"), None);
        assert_eq!(alias("FOO_INT"), None);
        assert_eq!(alias("LEN_STRING"), None);
    }

    #[test]
    fn legacy_time_names() {
        assert_eq!(alias("MULTIME").map(Alias::target), Some("MUL_TIME"));
        assert_eq!(alias("DIVTIME").map(Alias::target), Some("DIV_TIME"));
    }
}

//! Access specifiers on variable sections (IEC 61131-3 edition 3):
//! `VAR PUBLIC`, `VAR PRIVATE`, `VAR PROTECTED`, `VAR INTERNAL` in a
//! FUNCTION_BLOCK or CLASS. The grammar records each such section in the
//! parser state; [`attach`] hands them to the FB's [`crate::syntax::oop::PouOop`]
//! and `src/sema/oop/var_access.rs` checks every access from outside.

use crate::syntax::ast::{CompilationUnit, Item, PouKind, Retain, VarBlock, VarDecl, VarKind};
use crate::syntax::construct::State;
use crate::syntax::oop::{Access, PouOop};

/// A `VAR <access> ... END_VAR` section.
pub fn var_block(
    st: &State,
    kind: VarKind,
    access: Access,
    quals: Vec<Option<Retain>>,
    decls: Vec<VarDecl>,
    l: usize,
    r: usize,
) -> VarBlock {
    let b = crate::syntax::construct::var_block(st, kind, quals, decls, l, r);
    if kind == VarKind::Local {
        st.var_access.borrow_mut().push((b.span, access));
    } else {
        st.error(
            "E928",
            b.span,
            "an access specifier (PUBLIC, PRIVATE, PROTECTED, INTERNAL) applies to a VAR section only: inputs and outputs are public",
        );
    }
    b
}

/// Gives each FUNCTION_BLOCK or CLASS its sections with an access
/// specifier; one anywhere else (a PROGRAM, a FUNCTION, a METHOD) is E928.
pub fn attach(st: &State, unit: &mut CompilationUnit) {
    let mut todo = std::mem::take(&mut *st.var_access.borrow_mut());
    if todo.is_empty() {
        return;
    }
    for item in &mut unit.items {
        let Item::Pou(p) = item else { continue };
        if p.kind != PouKind::FunctionBlock {
            continue;
        }
        let mine: Vec<(crate::source::Span, Access)> = todo
            .iter()
            .filter(|(s, _)| p.var_blocks.iter().any(|b| b.span == *s))
            .copied()
            .collect();
        if mine.is_empty() {
            continue;
        }
        todo.retain(|x| !mine.contains(x));
        p.oop
            .get_or_insert_with(|| Box::new(PouOop::default()))
            .var_access
            .extend(mine);
    }
    for (span, _) in todo {
        st.error(
            "E928",
            span,
            "an access specifier on variables belongs to the VAR section of a FUNCTION_BLOCK or CLASS",
        );
    }
}

//! `trig : R_TRIG();` — a declaration that calls the block's `FB_init`
//! with no arguments, as CODESYS and TwinCAT allow: with nothing to pass
//! it declares the instance like `trig : R_TRIG;`, so a token pass drops
//! the empty parentheses. (`fb : FB_X(arg := 1)`, FB_init with arguments,
//! is [`super::init_arguments`]'s.)

use super::lexer::Spanned;
use super::token::{Kw, Tok};

/// True for the keyword that opens a block of variable declarations.
pub(super) fn opens_declarations(t: &Tok) -> bool {
    matches!(
        t,
        Tok::Kw(
            Kw::Var
                | Kw::VarInput
                | Kw::VarOutput
                | Kw::VarInOut
                | Kw::VarExternal
                | Kw::VarGlobal
                | Kw::VarTemp
                | Kw::VarInst
        )
    )
}

/// Drops `()` after the type name of a declaration (`: Name ( )` followed
/// by `;` or `:=`, between a `VAR...` keyword and `END_VAR`). Only there:
/// `1: Reset();` in a CASE is a call and keeps its parentheses.
pub fn drop_empty_init_calls(tokens: Vec<Spanned>) -> Vec<Spanned> {
    let hit = |t: &[Spanned], i: usize| {
        i >= 2
            && t[i - 2].1 == Tok::Colon
            && matches!(t[i - 1].1, Tok::Ident(_))
            && t[i].1 == Tok::LParen
            && t.get(i + 1).is_some_and(|x| x.1 == Tok::RParen)
            && t.get(i + 2)
                .is_some_and(|x| matches!(x.1, Tok::Semi | Tok::Assign))
    };
    if !(0..tokens.len()).any(|i| hit(&tokens, i)) {
        return tokens;
    }
    let mut drop = vec![false; tokens.len()];
    let mut in_declarations = false;
    for i in 0..tokens.len() {
        if opens_declarations(&tokens[i].1) {
            in_declarations = true;
        } else if tokens[i].1 == Tok::Kw(Kw::EndVar) {
            in_declarations = false;
        } else if in_declarations && hit(&tokens, i) {
            drop[i] = true;
            drop[i + 1] = true;
        }
    }
    super::lexer::without_marked(tokens, drop)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::Diagnostics;
    use crate::source::FileId;

    fn count(src: &str) -> usize {
        let toks = crate::syntax::lexer::lex(FileId(0), src, &mut Diagnostics::new());
        drop_empty_init_calls(toks)
            .iter()
            .filter(|t| matches!(t.1, Tok::LParen | Tok::RParen))
            .count()
    }

    #[test]
    fn only_the_empty_parentheses_of_a_declaration_go() {
        assert_eq!(
            count("VAR t : R_TRIG(); u : TON() := (PT := T#1s); END_VAR"),
            2
        );
        assert_eq!(count("VAR s : STRING(80); END_VAR x := f();"), 4);
        // A CASE arm calling a block or method is not a declaration.
        assert_eq!(count("CASE n OF 1: Reset(); 2: x := 1; END_CASE"), 2);
    }
}

//! `fb : FB_X(a := 1);` — an instance declared with the arguments of its
//! block's `FB_init` (CODESYS V3, TwinCAT 3). The grammar already reads
//! `Name ( ... )` after a declaration's colon as a subrange (`INT(0..9)`)
//! or an enumeration with a base type (`BYTE(red, green)`); this pass
//! retags the `(` of the third reading, so that the grammar needs no
//! look-ahead to tell them apart: the type's name is not an elementary
//! type, and no `..` stands at the parentheses' own depth.

use super::lexer::Spanned;
use super::token::{Kw, Tok};
use crate::elementary::ElemType;

/// True for the keyword that opens a block of variable declarations.
fn opens_declarations(t: &Tok) -> bool {
    matches!(
        t,
        Tok::Kw(Kw::Var | Kw::VarInput | Kw::VarOutput | Kw::VarTemp | Kw::VarGlobal | Kw::VarInst)
    )
}

/// Where the parentheses opening at `open` close, if they do, and whether
/// a `..` stands directly inside them.
fn closing(tokens: &[Spanned], open: usize) -> Option<(usize, bool)> {
    let mut depth = 0usize;
    let mut range = false;
    for (k, t) in tokens.iter().enumerate().skip(open) {
        match t.1 {
            Tok::LParen | Tok::LBracket => depth += 1,
            Tok::RParen | Tok::RBracket => {
                depth -= 1;
                if depth == 0 {
                    return Some((k, range));
                }
            }
            Tok::DotDot if depth == 1 => range = true,
            Tok::Semi | Tok::Kw(Kw::EndVar) => return None,
            _ => {}
        }
    }
    None
}

/// Whether the `(` or `[` at `i` follows `: Name` or `: Ns.Name` (`OF
/// Name` when `after_of`), where `Name` is not an elementary type.
fn after_block_type(tokens: &[Spanned], i: usize, after_of: bool) -> bool {
    let Some(Tok::Ident(name)) = tokens.get(i.wrapping_sub(1)).map(|t| &t.1) else {
        return false;
    };
    if ElemType::from_name(&name.to_ascii_uppercase()).is_some() {
        return false;
    }
    let mut k = i - 1;
    while k >= 2 && tokens[k - 1].1 == Tok::Dot && matches!(tokens[k - 2].1, Tok::Ident(_)) {
        k -= 2;
    }
    k >= 1
        && match tokens[k - 1].1 {
            Tok::Colon => !after_of,
            Tok::Kw(Kw::Of) => after_of,
            _ => false,
        }
}

/// Retags the `(` of every declaration's FB_init arguments as
/// [`Tok::InitArgsOpen`] (between a `VAR...` keyword and `END_VAR`,
/// followed after its `)` by `;` or `:=`). Line ends (kept at this stage
/// for Instruction List) may stand between the tokens.
pub fn mark_init_arguments(mut tokens: Vec<Spanned>) -> Vec<Spanned> {
    let mut in_declarations = false;
    for i in 0..tokens.len() {
        match &tokens[i].1 {
            t if opens_declarations(t) => in_declarations = true,
            Tok::Kw(Kw::EndVar) => in_declarations = false,
            // `OF FB_X[(...), ...]`: one argument list per element.
            Tok::LBracket
                if in_declarations
                    && after_block_type(&tokens, i, true)
                    && tokens[i + 1..]
                        .iter()
                        .find(|t| t.1 != Tok::Eol)
                        .is_some_and(|t| t.1 == Tok::LParen) =>
            {
                tokens[i].1 = Tok::InitArgsArray;
            }
            Tok::LParen if in_declarations && after_block_type(&tokens, i, false) => {
                let Some((close, range)) = closing(&tokens, i) else {
                    continue;
                };
                let ends = tokens[close + 1..]
                    .iter()
                    .find(|t| t.1 != Tok::Eol)
                    .is_some_and(|t| matches!(t.1, Tok::Semi | Tok::Assign));
                if !range && ends && close > i + 1 {
                    tokens[i].1 = Tok::InitArgsOpen;
                }
            }
            _ => {}
        }
    }
    tokens
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::Diagnostics;
    use crate::source::FileId;

    fn marked(src: &str) -> usize {
        let toks = crate::syntax::lexer::lex(FileId(0), src, &mut Diagnostics::new());
        mark_init_arguments(toks)
            .iter()
            .filter(|t| matches!(t.1, Tok::InitArgsOpen | Tok::InitArgsArray))
            .count()
    }

    #[test]
    fn only_the_arguments_of_a_block_instance_are_retagged() {
        assert_eq!(marked("VAR a : FB_Arbiter(1); END_VAR"), 1);
        assert_eq!(
            marked("VAR m : Lib.FB_M(Axis := ax[2], sName := 'Y'); END_VAR"),
            1
        );
        assert_eq!(marked("VAR t : FB_T(x) := (PT := T#1s); END_VAR"), 1);
        assert_eq!(
            marked("VAR a : ARRAY[1..2] OF FB_T[(1), (x := 2)]; END_VAR"),
            1
        );
        assert_eq!(marked("VAR a : ARRAY[1..2] OF FB_T; END_VAR"), 0);
        // Subranges, enumerations with a base type, strings: not arguments.
        assert_eq!(marked("VAR n : UINT(1..GVL.Max); END_VAR"), 0);
        assert_eq!(marked("VAR n : MyRange(0..N); END_VAR"), 0);
        assert_eq!(marked("VAR e : BYTE(red, green); END_VAR"), 0);
        assert_eq!(marked("VAR s : STRING(80); END_VAR"), 0);
        // Outside declarations a call keeps its parenthesis.
        assert_eq!(marked("PROGRAM P x := f(1); END_PROGRAM"), 0);
    }
}

//! Whether a body mentions the name `ENO`: only FUNCTIONs and
//! FUNCTION_BLOCKs whose body reads or writes their own ENO get the
//! implicit ENO output (eno_body.rs), so every other POU keeps its layout
//! and code unchanged. `ENO =>` in a call names the callee's output and is
//! not a mention; its target is.

use crate::syntax::ast::Body;

/// True when `body` mentions `ENO` as a variable.
pub(super) fn body_mentions_eno(body: &Body) -> bool {
    super::body_names::any_name(body, &mut is_eno)
}

fn is_eno(name: &str) -> bool {
    name.eq_ignore_ascii_case("ENO")
}

#[cfg(test)]
mod tests {
    use super::body_mentions_eno;
    use crate::syntax::ast::{Item, Pou};

    fn first_pou(src: &str) -> Pou {
        let mut diags = crate::diagnostics::Diagnostics::new();
        let unit = crate::syntax::parse(crate::source::FileId(0), src, &mut diags);
        assert!(!diags.has_errors(), "the test source parses");
        unit.items
            .into_iter()
            .find_map(|i| match i {
                Item::Pou(p) => Some(p),
                _ => None,
            })
            .expect("one POU")
    }

    #[test]
    fn st_and_il_mentions_are_found() {
        let st = first_pou(
            "FUNCTION f : INT VAR_INPUT a : INT; END_VAR IF a < 0 THEN ENO := FALSE; END_IF; f := a; END_FUNCTION",
        );
        assert!(body_mentions_eno(&st.body));
        let il = first_pou(
            "FUNCTION_BLOCK fb VAR_INPUT a : BOOL; END_VAR\nLD a\nST ENO\nEND_FUNCTION_BLOCK",
        );
        assert!(body_mentions_eno(&il.body));
    }

    #[test]
    fn eno_of_a_callee_is_not_a_mention() {
        let p = first_pou(
            "FUNCTION_BLOCK fb VAR t : TON; ok : BOOL; END_VAR t(IN := TRUE, ENO => ok); ok := t.ENO; END_FUNCTION_BLOCK",
        );
        assert!(!body_mentions_eno(&p.body));
    }
}

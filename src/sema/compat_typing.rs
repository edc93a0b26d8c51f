//! Typing rules that follow the context beyond what edition 3 says, for
//! code written for CODESYS 2.3 and matiec (edition 2):
//! - an untyped `0` or `1` as the selector G of `SEL` is FALSE or TRUE
//!   (W342);
//! - `BCD_TO_INT` is the edition-2 overloaded conversion from a BCD bit
//!   string to ANY_INT: its result takes the integer type the context
//!   expects (`u := BCD_TO_INT(b)` with `u : USINT`), W344 when that is not
//!   INT. (`TRUNC`, ANY_REAL to ANY_INT, takes the expected type in edition
//!   3 as well, without a warning.)

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Ty, Val};
use crate::elementary::ElemType;
use crate::ir::type_table::{TypeId, TypeTable};
use crate::source::Span;

impl BodyBuilder<'_> {
    /// The selector of `SEL` as a BOOL: an untyped literal 0 or 1 becomes
    /// FALSE or TRUE with warning W342; anything else is returned as is.
    pub(super) fn sel_selector(&mut self, g: Val, span: Span) -> Val {
        match g {
            Val::Const(Const::Int(n @ (0 | 1)), Ty::AnyInt) => {
                self.diags.warning(
                    "W342",
                    span,
                    format!(
                        "SEL: the selector G is BOOL; the literal {n} is read as {} (CODESYS, matiec)",
                        if n == 1 { "TRUE" } else { "FALSE" }
                    ),
                );
                Val::Const(
                    Const::Bits(n as u64),
                    Ty::T(TypeTable::elem(ElemType::Bool)),
                )
            }
            other => other,
        }
    }

    /// The result type of `BCD_TO_<to>`: for the edition-2 overloaded
    /// `BCD_TO_INT`, the integer type the context expects (W344 when that
    /// is not INT); otherwise `to`.
    pub(super) fn bcd_result_type(
        &mut self,
        fname: &str,
        to: ElemType,
        expect: Option<TypeId>,
        span: Span,
    ) -> ElemType {
        if fname != "BCD_TO_INT" {
            return to;
        }
        match expect.and_then(|t| self.scalar(t)).filter(|e| e.is_int()) {
            Some(want) if want != to => {
                self.diags.warning(
                    "W344",
                    span,
                    format!(
                        "BCD_TO_INT gives the {want} the context expects (edition 2: BCD_TO_INT converts to any integer type); edition 3 writes BCD_TO_{want}"
                    ),
                );
                want
            }
            _ => to,
        }
    }
}

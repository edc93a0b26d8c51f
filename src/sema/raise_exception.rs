//! `F_RaiseException(ExceptionCode)` (Tc2_System, TwinCAT 3): raises the
//! exception with that code where it is called, as a runtime fault would —
//! the enclosing `__TRY`'s `__CATCH` receives the code; outside any, the
//! PLC stops (R082) at the call. Emitted in place (not a library body) so
//! that the fault points at the caller's line.

use super::body::BodyBuilder;
use super::emit::Val;
use crate::ir::op::Op;
use crate::ir::type_table::{TypeKind, TypeTable};
use crate::syntax::ast::{Arg, Call, ExprKind};

/// The function's name, case-folded.
const NAME: &str = "F_RAISEEXCEPTION";

impl BodyBuilder<'_> {
    /// True when `call` is `F_RaiseException(...)` (and no POU or variable
    /// of the program takes the name): the fault is emitted, or its
    /// argument refused (E251, E301).
    pub(super) fn raise_exception_call(&mut self, call: &Call) -> bool {
        let ExprKind::Name(id) = &call.callee.kind else {
            return false;
        };
        let key = id.key();
        if key != NAME || self.model.pou_index.contains_key(&key) || self.lookup_var(&key).is_some()
        {
            return false;
        }
        let value = match call.args.as_slice() {
            [Arg::Positional(v)] => v,
            [Arg::Input { name, value }] if name.key() == "EXCEPTIONCODE" => value,
            _ => {
                self.diags.error(
                    "E251",
                    call.span,
                    "F_RaiseException takes one input, ExceptionCode (a __SYSTEM.ExceptionCode or UDINT)",
                );
                return true;
            }
        };
        let udint = TypeTable::elem(crate::elementary::ElemType::Udint);
        let v = self.expr(value, Some(udint));
        // A value of __SYSTEM.ExceptionCode is its number, a UDINT.
        let is_code = matches!(
            v.ty().id().map(|t| &self.types.get(t).kind),
            Some(TypeKind::Enum { base, .. }) if *base == crate::elementary::ElemType::Udint
        );
        let v = if is_code {
            v
        } else {
            self.coerce(v, udint, value.span, "F_RaiseException's ExceptionCode")
        };
        if v.is_error() {
            return true;
        }
        let c = self.materialize(&v);
        self.block.emit(Op::FaultRaise { c });
        true
    }

    /// `F_RaiseException` used as a value: E415 (it returns nothing).
    pub(super) fn raise_exception_value(&mut self, call: &Call) -> Option<Val> {
        let ExprKind::Name(id) = &call.callee.kind else {
            return None;
        };
        let key = id.key();
        if key != NAME || self.model.pou_index.contains_key(&key) || self.lookup_var(&key).is_some()
        {
            return None;
        }
        self.diags.error(
            "E415",
            call.span,
            "F_RaiseException returns no value: call it as a statement",
        );
        Some(Val::error())
    }
}

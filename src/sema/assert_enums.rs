//! `AssertEquals` of two values of one enumeration (TcUnit compares
//! enumerations too): the values are compared as the integers they are
//! stored as, by the runner's enumeration host function, which reports a
//! failure with the values' names (`E_Mode#Run`). A bare value (`Run`) is
//! read as a value of the other argument's enumeration, as in `m = Run`.
//! Values of two different enumerations, or an enumeration and a number,
//! are still E480.

use super::assert_calls::{ASSERT_EQ_ENUM_HOST, E_TYPES};
use super::body::BodyBuilder;
use super::emit::{Ty, Val};
use crate::elementary::ElemType;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::Expr;

/// Longest text of value names handed to the runner (a STRING input).
const MAX_NAMES: usize = 254;

impl BodyBuilder<'_> {
    /// Lowers `AssertEquals(e, a, message)` when either value is of an
    /// enumeration type; `None` when neither is (the elementary types
    /// decide).
    pub(super) fn enum_equals(
        &mut self,
        e: &Expr,
        a: &Expr,
        message: &Expr,
        loc: &Expr,
        span: Span,
        want: bool,
    ) -> Option<Val> {
        let target = self.assert_enum_type(e, a)?;
        let same = |s: &mut Self, x: &Expr| s.probe_in(x, false, Some(target)) == Ty::T(target);
        if !same(self, e) || !same(self, a) {
            return None;
        }
        let TypeKind::Enum { base, values } = self.types.get(target).kind.clone() else {
            return None;
        };
        // A bit-string base (`(a, b) BYTE`, TwinCAT) holds its value
        // zero-extended: read as LINT as it is.
        let bits = base.is_bit() && base != ElemType::Bool;
        if !(base == ElemType::Lint || base.widens_to(ElemType::Lint) || bits) {
            self.diags.error(
                E_TYPES,
                span,
                format!(
                    "AssertEquals compares enumerations stored as integers up to LINT or as bit strings; `{}` is stored as {}",
                    self.types.name(target),
                    base.name()
                ),
            );
            return Some(Val::error());
        }
        let &p = self.model.pou_index.get(ASSERT_EQ_ENUM_HOST)?;
        let base_ty = TypeTable::elem(if bits { ElemType::Lint } else { base });
        let ve = self.enum_as_base(e, target, base_ty);
        let va = self.enum_as_base(a, target, base_ty);
        if ve.is_error() || va.is_error() {
            return Some(Val::error());
        }
        let names = names_text(self.types.name(target), &values);
        let names = super::assert_calls::string_literal(&names, span);
        let vals = vec![
            ("Expected", ve, e.span),
            ("Actual", va, a.span),
            ("Message", self.expr(message, None), message.span),
            ("Loc", self.expr(loc, None), span),
            ("Names", self.expr(&names, None), span),
        ];
        Some(self.function_call_with_values(p, vals, span, want))
    }

    /// The enumeration an assertion compares: the type of `a` or `e` that
    /// is an enumeration, a named one before the anonymous type of a bare
    /// value.
    fn assert_enum_type(&mut self, e: &Expr, a: &Expr) -> Option<TypeId> {
        let types: Vec<TypeId> = [a, e]
            .into_iter()
            .filter_map(|x| self.probe_in(x, false, None).id())
            .collect();
        let mut found: Vec<TypeId> = types.into_iter().filter(|&t| self.is_enum(t)).collect();
        found.sort_by_key(|&t| self.types.name(t).starts_with('('));
        found.first().copied()
    }

    /// `x`, a value of enumeration `target`, as the integer it is stored as.
    fn enum_as_base(&mut self, x: &Expr, target: TypeId, base_ty: TypeId) -> Val {
        let v = self.expr(x, Some(target));
        match self.coerce(v, target, x.span, "AssertEquals") {
            Val::Slot(s, _) => Val::Slot(s, base_ty),
            Val::Const(c, _) => Val::Const(c, Ty::T(base_ty)),
            other => other,
        }
    }
}

/// `Type;name=value;...` for the runner, cut at a whole entry to fit a
/// STRING (a value whose name is cut off is reported as its number).
fn names_text(type_name: &str, values: &[(String, i64)]) -> String {
    let mut out = type_name.to_string();
    for (name, v) in values {
        let entry = format!(";{name}={v}");
        if out.len() + entry.len() > MAX_NAMES {
            break;
        }
        out.push_str(&entry);
    }
    out
}

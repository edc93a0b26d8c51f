//! CODESYS's POUs for implicit checks: FUNCTIONs a project declares under
//! fixed names (`CheckBounds`, `CheckDivDInt`, `CheckRangeSigned`...;
//! TwinCAT puts them in `ImplicitChecks`) that the compiler calls where
//! an array is indexed, a value divides, or a subrange variable is
//! assigned. This file says where one applies and whether it is declared
//! as CODESYS declares it; the calls are in implicit_bounds.rs,
//! implicit_div.rs and implicit_range.rs.

use super::body::BodyBuilder;
use super::emit::Val;
use super::implicit_int::wrap;
use super::model::Model;
use crate::diagnostics::Diagnostics;
use crate::elementary::ElemType;
use crate::ir::op::Slot;
use crate::ir::type_table::{MemberKind, TypeId, TypeTable};
use crate::source::Span;
use crate::syntax::ast::PouKind;

/// The array-index check, case-folded.
pub(super) const CHECK_BOUNDS: &str = "CHECKBOUNDS";
/// The division checks for DINT (and every narrower integer), LINT,
/// REAL and LREAL divisors.
pub(super) const CHECK_DIV_DINT: &str = "CHECKDIVDINT";
pub(super) const CHECK_DIV_LINT: &str = "CHECKDIVLINT";
pub(super) const CHECK_DIV_REAL: &str = "CHECKDIVREAL";
pub(super) const CHECK_DIV_LREAL: &str = "CHECKDIVLREAL";
/// The subrange checks: signed and unsigned up to 32 bits, then 64.
pub(super) const CHECK_RANGE_SIGNED: &str = "CHECKRANGESIGNED";
pub(super) const CHECK_RANGE_UNSIGNED: &str = "CHECKRANGEUNSIGNED";
pub(super) const CHECK_LRANGE_SIGNED: &str = "CHECKLRANGESIGNED";
pub(super) const CHECK_LRANGE_UNSIGNED: &str = "CHECKLRANGEUNSIGNED";

/// Each check plcrun calls, with the type of its inputs (all of one type)
/// and their number; the result is of the same type.
const SIGNATURES: [(&str, ElemType, usize); 9] = [
    (CHECK_BOUNDS, ElemType::Dint, 3),
    (CHECK_DIV_DINT, ElemType::Dint, 1),
    (CHECK_DIV_LINT, ElemType::Lint, 1),
    (CHECK_DIV_REAL, ElemType::Real, 1),
    (CHECK_DIV_LREAL, ElemType::Lreal, 1),
    (CHECK_RANGE_SIGNED, ElemType::Dint, 3),
    (CHECK_RANGE_UNSIGNED, ElemType::Udint, 3),
    (CHECK_LRANGE_SIGNED, ElemType::Lint, 3),
    (CHECK_LRANGE_UNSIGNED, ElemType::Ulint, 3),
];

/// The case-folded names of the checks plcrun calls (laid out before any
/// body, as a body's calls of them are not written in it).
pub(super) fn names() -> impl Iterator<Item = &'static str> {
    SIGNATURES.iter().map(|(name, _, _)| *name)
}

/// Whether POU `p` is a FUNCTION with `count` inputs of type `input` (and
/// nothing else in its interface) returning that type.
fn declared_as_codesys(model: &Model, p: usize, input: ElemType, count: usize) -> bool {
    let pou = &model.pous[p];
    let ty: TypeId = TypeTable::elem(input);
    pou.kind == PouKind::Function
        && pou.ret == ty
        && pou.params.len() == count
        && pou
            .params
            .iter()
            .filter_map(|k| pou.vars.get(k))
            .all(|v| v.kind == MemberKind::Input && v.ty == ty)
}

/// W494 for each check a CODESYS-dialect file declares with another
/// interface than CODESYS gives it: plcrun does not call it (CODESYS
/// requires the generated declaration to be left as it is).
pub(super) fn warn_other_signatures(model: &Model, diags: &mut Diagnostics) {
    for (name, input, count) in SIGNATURES {
        let Some(&p) = model.pou_index.get(name) else {
            continue;
        };
        let pou = &model.pous[p];
        if !model.checked_files.contains(&pou.span.file)
            || model.library_files.contains(&pou.span.file)
            || declared_as_codesys(model, p, input, count)
        {
            continue;
        }
        let inputs = vec![input.name(); count].join(", ");
        diags.warning(
            "W494",
            pou.span,
            format!(
                "`{}` is not declared as CODESYS's implicit check (FUNCTION {} : {} with the \
                 inputs {inputs}): plcrun does not call it",
                pou.name,
                pou.name,
                input.name()
            ),
        );
    }
}

impl BodyBuilder<'_> {
    /// The POU of the project's implicit check `name` (case-folded) when
    /// it applies to code at `at`: declared as CODESYS declares it and
    /// laid out, not the POU being built (a check does not check itself)
    /// nor a POU declared `{attribute 'no_check'}`, and `at` in a file of
    /// the CODESYS dialect other than a library's (plcrun's TwinCAT
    /// library, a library project loaded with the application).
    pub(super) fn implicit_check(&self, name: &str, at: Span) -> Option<usize> {
        let &p = self.model.pou_index.get(name)?;
        let &(_, input, count) = SIGNATURES.iter().find(|(n, _, _)| *n == name)?;
        // A body emitted while the types are resolved comes before the
        // function is laid out: it keeps plcrun's own checks.
        let laid_out = self.model.pous[p].code != crate::ir::op::CodeIdx::new(u32::MAX);
        let applies = laid_out
            && p != self.block.pou
            && !self.model.pous[self.block.pou].no_check
            && !self.in_no_check_method()
            && self.model.checked_files.contains(&at.file)
            && !self.model.library_files.contains(&at.file)
            && declared_as_codesys(self.model, p, input, count);
        applies.then_some(p)
    }

    /// Whether the code being emitted is a METHOD (or an inherited body)
    /// declared `{attribute 'no_check'}`.
    fn in_no_check_method(&self) -> bool {
        let Some(scope) = &self.oop else {
            return false;
        };
        let version = scope
            .version
            .and_then(|v| self.model.oop.fbs.get(&scope.fb)?.versions.get(v));
        version.is_some_and(|v| v.no_check)
    }

    /// The value `s` of type `from` passed through check `p` (its first
    /// input, of type `input`, `more` the others): converted to `input`
    /// and what the check returns back to `from`.
    pub(super) fn through_check(
        &mut self,
        p: usize,
        (s, from, input): (Slot, ElemType, ElemType),
        more: Vec<Val>,
        span: Span,
    ) -> Slot {
        let first = self.quietly_as(Val::Slot(s, TypeTable::elem(from)), from, input, span);
        let mut values = vec![first];
        values.extend(more);
        let result = self.call_implicit_check(p, values, span);
        let back = self.quietly_as(result, input, from, span);
        self.materialize(&back)
    }

    /// `v` of type `from` as a `to`: the same slot when every value fits,
    /// else its low bits (the implicit conversion CODESYS makes, without
    /// its warning: the compiler wrote it, not the user).
    fn quietly_as(&mut self, v: Val, from: ElemType, to: ElemType, span: Span) -> Val {
        match (v, wrap(from, to)) {
            (v, Some(conv)) => self.apply_conv(v, conv, to, span),
            (Val::Slot(s, _), None) => Val::Slot(s, TypeTable::elem(to)),
            (other, None) => other,
        }
    }

    /// Calls check `p` with `values` (already of its input type, in the
    /// order of its inputs): its result.
    fn call_implicit_check(&mut self, p: usize, values: Vec<Val>, span: Span) -> Val {
        let pou = &self.model.pous[p];
        let names: Vec<String> = pou
            .params
            .iter()
            .filter_map(|k| pou.vars.get(k))
            .map(|v| v.name.clone())
            .collect();
        let args = names
            .iter()
            .zip(values)
            .map(|(n, v)| (n.as_str(), v, span))
            .collect();
        self.function_call_with_values(p, args, span, true)
    }
}

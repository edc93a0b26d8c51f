//! Implicit conversion between an enumeration and integers, as CODESYS
//! allows it (without `{attribute 'strict'}`): an enumeration value is
//! its base type's integer where an integer is expected or combined with
//! one (W485; also an integer type narrower than the base type that holds
//! every one of its values: CODESYS's default base type is INT, plcrun's
//! DINT), and an integer may be stored in an enumeration variable
//! (W486: the value is not checked against the named ones). Both are
//! compatibility warnings: `--strict` refuses them. An enumeration
//! declared after `{attribute 'strict'}` takes part in no arithmetic and
//! takes no integer, as TwinCAT's manual lists; it still converts to an
//! integer where one is expected (TcUnit's own examples pass such values
//! to `AssertEquals_USINT`) and is compared with integers.

use super::body::BodyBuilder;
use super::emit::{Ty, Val};
use crate::elementary::ElemType;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::BinaryOp;

impl BodyBuilder<'_> {
    /// The base type of enumeration `t`, unless it is declared strict.
    fn enum_base(&self, t: TypeId) -> Option<ElemType> {
        self.any_enum_base(t)
            .filter(|_| !self.model.strict_enums.contains(&t))
    }

    /// The base type of enumeration `t`, strict or not.
    fn any_enum_base(&self, t: TypeId) -> Option<ElemType> {
        match self.types.get(t).kind {
            TypeKind::Enum { base, .. } => Some(base),
            _ => None,
        }
    }

    /// Whether a value of `from` converts to `to` across an enumeration
    /// (one side an enumeration, the other an integer or bit string the
    /// base type widens to, or that widens to the base type); warns then.
    pub(super) fn enum_int_conversion(&mut self, from: TypeId, to: TypeId, span: Span) -> bool {
        match (self.any_enum_base(from), self.enum_base(to)) {
            // Two enumerations mix only in CODESYS files, neither strict,
            // through their integers.
            (Some(_), Some(base)) if from != to && self.mixes_enums(from, span) => {
                self.enum_to_int_warning(from, base, span);
                self.int_to_enum_warning(base.name(), to, span);
                true
            }
            (Some(_), _) if self.is_enum(to) => false,
            (Some(base), None) => {
                let Some(t) = self.types.scalar(to).filter(|t| t.is_int() || t.is_bit()) else {
                    return false;
                };
                if base != t && !base.widens_to(t) && !self.values_fit(from, t) {
                    return false;
                }
                self.enum_to_int_warning(from, t, span);
                true
            }
            (None, Some(base)) => {
                let Some(f) = self.types.scalar(from).filter(|f| f.is_int() || f.is_bit()) else {
                    return false;
                };
                if f != base && !f.widens_to(base) {
                    return false;
                }
                self.int_to_enum_warning(f.name(), to, span);
                true
            }
            _ => false,
        }
    }

    /// A variable of an enumeration connected to a VAR_IN_OUT of its base
    /// type (a strict one too: TwinCAT connects `eState : E_State` with
    /// `{attribute 'strict'}` to a `VAR_IN_OUT nState : UINT`), or an
    /// integer variable of that type to a VAR_IN_OUT of a non-strict
    /// enumeration: the same memory, which CODESYS connects (W485 / W486).
    pub(super) fn enum_in_out(&mut self, arg: TypeId, param: TypeId, span: Span) -> bool {
        match (self.any_enum_base(arg), self.enum_base(param)) {
            (Some(base), None)
                if !self.is_enum(param) && self.types.scalar(param) == Some(base) =>
            {
                self.enum_to_int_warning(arg, base, span);
                true
            }
            (None, Some(base)) if !self.is_enum(arg) && self.types.scalar(arg) == Some(base) => {
                self.int_to_enum_warning(base.name(), param, span);
                true
            }
            _ => false,
        }
    }

    /// Whether every value of enumeration `t` is a value of integer type
    /// `to`: an enumeration of the default base type (DINT here, INT in
    /// CODESYS) whose values are small goes into an INT as in CODESYS.
    fn values_fit(&self, t: TypeId, to: ElemType) -> bool {
        let (TypeKind::Enum { values, .. }, Some((lo, hi))) =
            (&self.types.get(t).kind, to.int_range())
        else {
            return false;
        };
        values
            .iter()
            .all(|&(_, v)| (lo..=hi).contains(&i128::from(v)))
    }

    /// An enumeration value as an array index: its base type's integer
    /// (W485; strict enumerations too, as where an integer is expected).
    pub(super) fn enum_index(&mut self, v: &Val, span: Span) -> bool {
        let Ty::T(t) = v.ty() else { return false };
        let Some(base) = self.any_enum_base(t).filter(|b| b.is_int()) else {
            return false;
        };
        self.enum_to_int_warning(t, base, span);
        true
    }

    /// An untyped integer literal (`value`) stored in an enumeration: W486,
    /// or refused (false) for a strict one — unless, in a CODESYS-dialect
    /// file, it is one of the strict enumeration's values, which TwinCAT
    /// accepts (`{attribute 'strict'}` refuses constants that are no value
    /// of the type: `eSetPos := 2` with `TARGET1 := 2`).
    pub(super) fn literal_to_enum(
        &mut self,
        from: Ty,
        value: Option<i128>,
        to: TypeId,
        span: Span,
    ) -> bool {
        if from != Ty::AnyInt || !self.is_enum(to) {
            return true;
        }
        if self.enum_base(to).is_none() {
            let TypeKind::Enum { values, .. } = &self.types.get(to).kind else {
                return false;
            };
            let named = value.is_some_and(|n| values.iter().any(|&(_, v)| i128::from(v) == n));
            if !(named && self.model.codesys_files.contains(&span.file)) {
                return false;
            }
        }
        self.int_to_enum_warning("an integer literal", to, span);
        true
    }

    /// Operands of a binary operator where one is an enumeration and the
    /// other an integer: the enumeration taken as its base type (W485). A
    /// strict enumeration only in a comparison: `{attribute 'strict'}`
    /// forbids arithmetic, not `nCommand = E_Cmd.HOME`.
    pub(super) fn enum_operands(
        &mut self,
        op: BinaryOp,
        va: Val,
        vb: Val,
        span: Span,
    ) -> (Val, Val) {
        let strict_too = op.is_comparison();
        let (ea, eb) = (
            self.val_enum(&va, strict_too),
            self.val_enum(&vb, strict_too),
        );
        match (ea, eb) {
            (Some(t), None) if self.is_integer(&vb) => (self.as_base(va, t, span), vb),
            (None, Some(t)) if self.is_integer(&va) => (va, self.as_base(vb, t, span)),
            (Some(ta), Some(tb))
                if ta != tb && self.mixes_enums(ta, span) && self.mixes_enums(tb, span) =>
            {
                (self.as_base(va, ta, span), self.as_base(vb, tb, span))
            }
            _ => (va, vb),
        }
    }

    /// The arguments of MIN, MAX or LIMIT where enumerations meet
    /// integers in a CODESYS-dialect file (`MIN(nCode,
    /// E_Type.HIGH_RESERVED)`): each enumeration that is not strict taken
    /// as its base type (W485), so the call is over integers.
    pub(super) fn enum_args_as_ints(&mut self, vals: Vec<(Val, Span)>) -> Vec<(Val, Span)> {
        if !vals.iter().any(|(v, _)| self.is_integer(v)) {
            return vals;
        }
        vals.into_iter()
            .map(|(v, s)| match self.val_enum(&v, false) {
                Some(t) if self.mixes_enums(t, s) => (self.as_base(v, t, s), s),
                _ => (v, s),
            })
            .collect()
    }

    /// Whether enumeration `t`'s values may meet another enumeration's at
    /// `span`: in a CODESYS-dialect file, where an enumeration that is not
    /// strict is an integer (FB_VCN compares `E_ValvePositionState` with
    /// `E_VCN`).
    fn mixes_enums(&self, t: TypeId, span: Span) -> bool {
        self.enum_base(t).is_some() && self.model.codesys_files.contains(&span.file)
    }

    /// The enumeration type of `v`, if it has one (and is not strict,
    /// unless `strict_too`).
    fn val_enum(&self, v: &Val, strict_too: bool) -> Option<TypeId> {
        v.ty().id().filter(|t| {
            if strict_too {
                self.any_enum_base(*t).is_some()
            } else {
                self.enum_base(*t).is_some()
            }
        })
    }

    /// Whether `v` is an integer or bit string (typed or a literal).
    fn is_integer(&self, v: &Val) -> bool {
        match v.ty() {
            Ty::AnyInt => true,
            Ty::AnyReal => false,
            Ty::T(t) => {
                !self.is_enum(t)
                    && self
                        .types
                        .scalar(t)
                        .is_some_and(|e| e.is_int() || e.is_bit())
            }
        }
    }

    /// Enumeration value `v`, of enumeration `t`, retyped as its base
    /// type, with W485.
    fn as_base(&mut self, v: Val, t: TypeId, span: Span) -> Val {
        let Some(base) = self.any_enum_base(t) else {
            return v;
        };
        self.enum_to_int_warning(t, base, span);
        let b = TypeTable::elem(base);
        match v {
            Val::Const(c, _) => Val::Const(c, Ty::T(b)),
            Val::Slot(s, _) => Val::Slot(s, b),
            other => other,
        }
    }

    pub(super) fn enum_to_int_warning(&mut self, from: TypeId, to: ElemType, span: Span) {
        let from = self.types.name(from).to_string();
        self.diags.warning(
            "W485",
            span,
            format!(
                "enumeration {from} used as an integer of its base type {} (a CODESYS extension)",
                to.name()
            ),
        );
    }

    fn int_to_enum_warning(&mut self, from: &str, to: TypeId, span: Span) {
        let to = self.types.name(to).to_string();
        self.diags.warning(
            "W486",
            span,
            format!(
                "{from} stored in enumeration {to} (CODESYS): the value is not checked against {to}'s values"
            ),
        );
    }
}

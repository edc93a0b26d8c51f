//! Typing rules: unifying operand types with IEC implicit widening,
//! converting values between types, and choosing the typed instruction for
//! an operator.

use super::body::BodyBuilder;
use super::consts::{Const, int_to_slot, real_to_slot, slot_to_int, slot_to_real};
use super::emit::{Ty, Val};
use crate::elementary::{ElemType, Family};
use crate::ir::op::{Cmp, Conv, Op, Slot};
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;

/// `64 - bits` of an integer-like type (0 for 64-bit and time types).
pub fn shift_of(e: ElemType) -> u8 {
    match e.bits() {
        8 => 56,
        16 => 48,
        32 => 32,
        _ => 0,
    }
}

/// True when values of `e` compare as signed 64-bit integers.
pub fn compares_signed(e: ElemType) -> bool {
    !matches!(e, ElemType::Ulint | ElemType::Lword) && !e.is_real() && !e.is_string()
}

impl BodyBuilder<'_> {
    /// The common type of two operands, or `None` if they do not mix.
    pub(super) fn unify(&self, a: Ty, b: Ty) -> Option<Ty> {
        match (a, b) {
            (Ty::AnyInt, Ty::AnyInt) => Some(Ty::AnyInt),
            (Ty::AnyInt, Ty::AnyReal) | (Ty::AnyReal, Ty::AnyInt) | (Ty::AnyReal, Ty::AnyReal) => {
                Some(Ty::AnyReal)
            }
            (Ty::T(x), Ty::AnyInt) | (Ty::AnyInt, Ty::T(x)) => {
                let e = self.types.scalar(x)?;
                if self.is_enum(x) {
                    return None;
                }
                (e.is_num() || e.is_bit()).then(|| Ty::T(self.plain(x)))
            }
            (Ty::T(x), Ty::AnyReal) | (Ty::AnyReal, Ty::T(x)) => {
                let e = self.types.scalar(x)?;
                if e.is_real() {
                    Some(Ty::T(x))
                } else if e.is_int() {
                    if e.widens_to(ElemType::Real) {
                        Some(Ty::T(TypeTable::elem(ElemType::Real)))
                    } else {
                        Some(Ty::T(TypeTable::elem(ElemType::Lreal)))
                    }
                } else {
                    None
                }
            }
            (Ty::T(x), Ty::T(y)) => {
                if x == y {
                    return Some(Ty::T(x));
                }
                if self.is_enum(x) || self.is_enum(y) {
                    return None;
                }
                let (ex, ey) = (self.types.scalar(x)?, self.types.scalar(y)?);
                if ex == ey {
                    if ex.is_string() {
                        return Some(Ty::T(x));
                    }
                    return Some(Ty::T(TypeTable::elem(ex)));
                }
                if ex.widens_to(ey) {
                    Some(Ty::T(TypeTable::elem(ey)))
                } else if ey.widens_to(ex) {
                    Some(Ty::T(TypeTable::elem(ex)))
                } else {
                    None
                }
            }
        }
    }

    /// True for enumeration types.
    pub(super) fn is_enum(&self, t: TypeId) -> bool {
        matches!(self.types.get(t).kind, TypeKind::Enum { .. })
    }

    /// Subranges compute in their base type.
    pub(super) fn plain(&self, t: TypeId) -> TypeId {
        match self.types.get(t).kind {
            TypeKind::Subrange { base, .. } => TypeTable::elem(base),
            _ => t,
        }
    }

    /// The type an untyped constant takes when nothing else decides.
    pub(super) fn default_type(&self, ty: Ty, c: Option<&Const>) -> TypeId {
        match ty {
            Ty::T(t) => t,
            Ty::AnyInt => match c {
                Some(Const::Int(v)) if i32::try_from(*v).is_err() => {
                    TypeTable::elem(ElemType::Lint)
                }
                _ => TypeTable::elem(ElemType::Dint),
            },
            Ty::AnyReal => TypeTable::elem(ElemType::Lreal),
        }
    }

    /// Display name of an expression type.
    pub(super) fn ty_name(&self, t: Ty) -> String {
        match t {
            Ty::T(t) => self.types.name(t).to_string(),
            Ty::AnyInt => "an integer literal".into(),
            Ty::AnyReal => "a real literal".into(),
        }
    }

    /// Encodes a constant as type `to`, or says why it does not fit.
    pub(super) fn const_as(&self, c: &Const, from: Ty, to: TypeId) -> Result<Const, String> {
        let Some(e) = self.types.scalar(to) else {
            return Err(format!("a constant cannot be a {}", self.types.name(to)));
        };
        let r = match (c, from) {
            (Const::Int(v), _) => {
                if e == ElemType::Bool {
                    matches!(v, 0 | 1).then_some(Const::Bits(*v as u64))
                } else if e.is_num() || e.is_bit() || e.family() == Family::Duration {
                    int_to_slot(*v, e).map(Const::Bits)
                } else {
                    return Err(format!("an integer is not a {}", self.types.name(to)));
                }
            }
            (Const::Real(v), _) => {
                if !e.is_real() {
                    return Err(format!("a real number is not a {}", self.types.name(to)));
                }
                real_to_slot(*v, e).map(Const::Bits)
            }
            (Const::Str(s), _) => {
                if e.is_string() {
                    Some(Const::Str(s.clone()))
                } else {
                    return Err(format!("a string is not a {}", self.types.name(to)));
                }
            }
            (Const::Bits(b), Ty::T(ft)) => {
                let fe = self.types.scalar(ft).unwrap_or(e);
                if fe == e {
                    Some(Const::Bits(*b))
                } else if fe.is_int() && e.is_real() {
                    real_to_slot(slot_to_int(*b, fe) as f64, e).map(Const::Bits)
                } else if fe.is_real() && e.is_real() {
                    real_to_slot(slot_to_real(*b, fe), e).map(Const::Bits)
                } else {
                    Some(Const::Bits(*b))
                }
            }
            (Const::Bits(b), _) => Some(Const::Bits(*b)),
        };
        let r = r.ok_or_else(|| format!("constant does not fit in {}", self.types.name(to)))?;
        if let (TypeKind::Subrange { lo, hi, .. }, Const::Bits(b)) = (&self.types.get(to).kind, &r)
        {
            let v = slot_to_int(*b, e);
            if v < *lo as i128 || v > *hi as i128 {
                return Err(format!("{v} is outside {}", self.types.name(to)));
            }
        }
        Ok(r)
    }

    /// Converts `v` to type `to` with implicit widening only; reports E301
    /// and returns an error value otherwise. `what` names the context.
    pub(super) fn coerce(&mut self, v: Val, to: TypeId, span: Span, what: &str) -> Val {
        if v.is_error() || to == TypeTable::error() {
            return Val::error();
        }
        if let Some(c) = self.pointer_coerce(&v, to, span) {
            return c;
        }
        if let Some(c) = self.const_as_ref(&v, to, span, what) {
            return c;
        }
        match &v {
            Val::Const(c, from) => {
                if let Ty::T(ft) = from
                    && !self.assignable(*ft, to)
                    && !self.codesys_widening(*ft, to, span)
                {
                    self.mismatch(span, *from, to, what);
                    return Val::error();
                }
                let literal = match c {
                    crate::sema::consts::Const::Int(n) => Some(*n),
                    _ => None,
                };
                if !self.literal_to_enum(*from, literal, to, span) {
                    self.mismatch(span, *from, to, what);
                    return Val::error();
                }
                match self.const_as(c, *from, to) {
                    Ok(c) => Val::Const(c, Ty::T(to)),
                    Err(msg) => {
                        self.diags.error("E304", span, format!("{what}: {msg}"));
                        Val::error()
                    }
                }
            }
            Val::Slot(s, from) => {
                if *from == to {
                    return v;
                }
                if !self.assignable(*from, to) && !self.codesys_widening(*from, to, span) {
                    self.mismatch(span, Ty::T(*from), to, what);
                    return Val::error();
                }
                let (fe, te) = (self.types.scalar(*from), self.types.scalar(to));
                match (fe, te) {
                    (Some(fe), Some(te)) => {
                        let conv = match (fe.family(), te) {
                            (Family::Signed, ElemType::Real) => Some(Conv::SToF32),
                            (Family::Signed, ElemType::Lreal) => Some(Conv::SToF64),
                            (Family::Unsigned, ElemType::Real) => Some(Conv::UToF32),
                            (Family::Unsigned, ElemType::Lreal) => Some(Conv::UToF64),
                            (Family::Real, ElemType::Lreal) if fe == ElemType::Real => {
                                Some(Conv::F32ToF64)
                            }
                            // CODESYS's implicit LREAL into REAL (W491).
                            (Family::Real, ElemType::Real) if fe == ElemType::Lreal => {
                                Some(Conv::F64ToF32)
                            }
                            _ => super::implicit_int::wrap(fe, te),
                        };
                        let slot = match conv {
                            Some(conv) => {
                                let d = self.block.temp();
                                self.block.emit(Op::Convert { d, a: *s, conv });
                                d
                            }
                            None => *s,
                        };
                        if let TypeKind::Subrange { .. } = self.types.get(to).kind {
                            let slot = self.range_checked(slot, to, span);
                            return Val::Slot(self.check_subrange(slot, to), to);
                        }
                        Val::Slot(slot, to)
                    }
                    _ => Val::Slot(*s, to),
                }
            }
            Val::None(t) => {
                if *t == TypeTable::void() {
                    self.diags
                        .error("E301", span, format!("{what}: this call returns no value"));
                }
                Val::error()
            }
        }
    }

    /// Range check for values stored into a subrange variable.
    fn check_subrange(&mut self, s: Slot, to: TypeId) -> Slot {
        let TypeKind::Subrange { lo, hi, .. } = self.types.get(to).kind else {
            return s;
        };
        let desc = self.out.array_desc(crate::ir::image::ArrayDesc {
            offset: 0,
            lo,
            len: (hi - lo + 1) as u64,
            stride: 0,
            span: self.block.span,
        });
        let d = self.block.temp();
        // An element load with stride 0 checks the range and reads slot 0 of
        // a dummy; instead use IndexStep on a zeroed accumulator.
        self.block.emit(Op::LoadI { d, imm: 0 });
        self.block.emit(Op::IndexStep {
            acc: d,
            idx: s,
            desc,
        });
        s
    }

    /// May a value of `from` be stored where `to` is expected?
    pub(super) fn assignable(&self, from: TypeId, to: TypeId) -> bool {
        if from == to || from == TypeTable::error() || to == TypeTable::error() {
            return true;
        }
        let (fk, tk) = (&self.types.get(from).kind, &self.types.get(to).kind);
        match (fk, tk) {
            (TypeKind::Ref { .. }, _) | (_, TypeKind::Ref { .. }) => self.ref_assignable(from, to),
            (TypeKind::Enum { .. }, _) | (_, TypeKind::Enum { .. }) => false,
            (TypeKind::Str { wide: a, .. }, TypeKind::Str { wide: b, .. }) => a == b,
            (TypeKind::Array { dims: d1, elem: e1 }, TypeKind::Array { dims: d2, elem: e2 }) => {
                d1 == d2 && e1 == e2
            }
            _ => match (self.types.scalar(from), self.types.scalar(to)) {
                (Some(a), Some(b)) => a == b || a.widens_to(b),
                _ => false,
            },
        }
    }

    /// Whether CODESYS converts `from` to `to` implicitly where IEC does
    /// not (see `bits_arith`); warns W351 when it does.
    fn codesys_widening(&mut self, from: TypeId, to: TypeId, span: Span) -> bool {
        if self.is_enum(from) || self.is_enum(to) {
            return self.enum_int_conversion(from, to, span);
        }
        let (Some(f), Some(t)) = (self.types.scalar(from), self.types.scalar(to)) else {
            return false;
        };
        if !super::bits_arith::codesys_widens(f, t) {
            return self.implicit_int_conversion(f, t, span)
                || self.implicit_real_conversion(f, t, span);
        }
        self.diags.warning(
            "W351",
            span,
            format!(
                "implicit conversion of {} to {} is a CODESYS extension",
                f.name(),
                t.name()
            ),
        );
        true
    }

    /// Reports a type mismatch, unless one side is the error type (its
    /// cause was reported where the type was refused).
    pub(super) fn mismatch(&mut self, span: Span, from: Ty, to: TypeId, what: &str) {
        if to == TypeTable::error() || from == Ty::T(TypeTable::error()) {
            return;
        }
        let fname = self.ty_name(from);
        let tname = self.types.name(to).to_string();
        let mut d = crate::diagnostics::Diagnostic::error(
            "E301",
            span,
            format!("{what}: expected {tname}, found {fname}"),
        );
        if let (Ty::T(ft), Some(te)) = (from, self.types.scalar(to))
            && let Some(fe) = self.types.scalar(ft)
            && !self.is_enum(ft)
            && !self.is_enum(to)
        {
            d = d.with_note(format!(
                "IEC converts only without loss implicitly; write {}_TO_{}(...) to convert",
                fe.name(),
                te.name()
            ));
        }
        self.diags.push(d);
    }

    /// Emits a comparison of two slots of elementary type `e`.
    pub(super) fn emit_cmp(&mut self, e: ElemType, a: Slot, b: Slot, cmp: Cmp) -> Slot {
        let d = self.block.temp();
        let op = if e.is_string() {
            Op::CmpStr { d, a, b, cmp }
        } else if e == ElemType::Real {
            Op::CmpF32 { d, a, b, cmp }
        } else if e == ElemType::Lreal {
            Op::CmpF64 { d, a, b, cmp }
        } else if compares_signed(e) {
            Op::CmpS { d, a, b, cmp }
        } else {
            Op::CmpU { d, a, b, cmp }
        };
        self.block.emit(op);
        d
    }
}

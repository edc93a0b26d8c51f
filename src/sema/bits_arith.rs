//! CODESYS arithmetic on bit strings, beyond IEC 61131-3: `+ - * / MOD` on
//! BYTE..LWORD compute as the unsigned integer of the same width (so they
//! wrap like it), a bit string mixes with unsigned integers and integer
//! literals, and a bit string widens implicitly into an integer type that
//! holds all its values (BYTE into INT, WORD into UINT). Each use gets a
//! compatibility warning (W350, W351) that `--strict` makes an error.

use super::body::BodyBuilder;
use super::emit::{Ty, Val};
use crate::elementary::{ElemType, Family};
use crate::ir::type_table::{TypeId, TypeTable};
use crate::source::Span;
use crate::syntax::ast::BinaryOp;

/// The unsigned integer type of a bit string's width.
pub(super) fn unsigned_of(e: ElemType) -> Option<ElemType> {
    Some(match e {
        ElemType::Byte => ElemType::Usint,
        ElemType::Word => ElemType::Uint,
        ElemType::Dword => ElemType::Udint,
        ElemType::Lword => ElemType::Ulint,
        _ => return None,
    })
}

/// The bit string of an unsigned integer's width.
fn bits_of(e: ElemType) -> Option<ElemType> {
    Some(match e {
        ElemType::Usint => ElemType::Byte,
        ElemType::Uint => ElemType::Word,
        ElemType::Udint => ElemType::Dword,
        ElemType::Ulint => ElemType::Lword,
        _ => return None,
    })
}

/// Whether CODESYS converts a `from` value to `to` implicitly where IEC
/// does not: a bit string (BYTE..LWORD) into an integer type that holds
/// every value of it, and an unsigned integer into a bit string at least
/// as wide. Both keep the value (slots hold them zero-extended), so no
/// instruction is needed.
pub(super) fn codesys_widens(from: ElemType, to: ElemType) -> bool {
    if let Some(u) = unsigned_of(from) {
        return u.widens_to(to) && to.is_int();
    }
    if from.family() == Family::Unsigned
        && let Some(b) = bits_of(from)
    {
        return b.widens_to(to) && to.family() == Family::Bits;
    }
    false
}

impl BodyBuilder<'_> {
    /// The element type of `t` when it is a bit string BYTE..LWORD.
    fn bit_string(&self, t: Ty) -> Option<ElemType> {
        let id = t.id()?;
        if self.is_enum(id) {
            return None;
        }
        self.scalar(id).filter(|e| unsigned_of(*e).is_some())
    }

    /// `a op b` for an arithmetic operator with a bit-string operand, the
    /// CODESYS way; `None` when the operands are not such a case (the IEC
    /// rules then apply and report).
    pub(super) fn bit_string_arith(
        &mut self,
        op: BinaryOp,
        va: &Val,
        vb: &Val,
        span: Span,
    ) -> Option<Val> {
        if !matches!(
            op,
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Div | BinaryOp::Mod
        ) {
            return None;
        }
        let (ba, bb) = (self.bit_string(va.ty()), self.bit_string(vb.ty()));
        if ba.is_none() && bb.is_none() {
            return None;
        }
        let a = self.as_integer(va, ba, vb.ty())?;
        let b = self.as_integer(vb, bb, va.ty())?;
        self.diags.warning(
            "W350",
            span,
            "arithmetic on a bit string (BYTE..LWORD) is a CODESYS extension: \
             it computes as the unsigned integer of the same width",
        );
        let r = self.binary_vals(op, a, b, span);
        // Two bit strings (or one and a literal) give a bit string.
        let keep_bits = ba.is_some() && bb.is_some()
            || matches!(va.ty(), Ty::AnyInt)
            || matches!(vb.ty(), Ty::AnyInt);
        if !keep_bits {
            return Some(r);
        }
        let back = |e: Option<ElemType>| e.and_then(bits_of).map(TypeTable::elem);
        Some(match r {
            Val::Slot(s, t) => Val::Slot(s, back(self.scalar(t)).unwrap_or(t)),
            Val::Const(c, Ty::T(t)) => Val::Const(c, Ty::T(back(self.scalar(t)).unwrap_or(t))),
            other => other,
        })
    }

    /// `a op b` for a comparison of a bit string with an integer of no
    /// common IEC type (`dw <> udi`), the CODESYS way: the bit string
    /// compares as the unsigned integer of its width (W350). `None` when
    /// the operands are not such a case.
    pub(super) fn bit_string_compare(
        &mut self,
        op: BinaryOp,
        va: &Val,
        vb: &Val,
        span: Span,
    ) -> Option<Val> {
        if !op.is_comparison() {
            return None;
        }
        let (ba, bb) = (self.bit_string(va.ty()), self.bit_string(vb.ty()));
        if ba.is_some() == bb.is_some() {
            return None;
        }
        let a = self.as_integer(va, ba, vb.ty())?;
        let b = self.as_integer(vb, bb, va.ty())?;
        self.diags.warning(
            "W350",
            span,
            "comparing a bit string (BYTE..LWORD) with an integer is a CODESYS extension: \
             it compares as the unsigned integer of the same width",
        );
        Some(self.binary_vals(op, a, b, span))
    }

    /// CODESYS indexes arrays with a bit string (BYTE..LWORD) too; warns
    /// W358 when `v` is one.
    pub(super) fn codesys_bit_string_index(&mut self, v: &Val, span: Span) -> bool {
        if self.bit_string(v.ty()).is_none() {
            return false;
        }
        self.diags.warning(
            "W358",
            span,
            "a bit string (BYTE..LWORD) as an array index is a CODESYS extension",
        );
        true
    }

    /// An operand retyped for integer arithmetic: a bit string as the
    /// unsigned integer of its width, or (beside a wider signed integer)
    /// as that signed type. `None` when the pair does not mix.
    fn as_integer(&self, v: &Val, bits: Option<ElemType>, other: Ty) -> Option<Val> {
        let Some(bits) = bits else {
            // The other operand: an integer, a real, a literal, or a bit
            // string.
            return match v.ty() {
                Ty::AnyInt | Ty::AnyReal => Some(v.clone()),
                Ty::T(t) => {
                    let e = self.scalar(t)?;
                    (e.is_num() || unsigned_of(e).is_some()).then(|| v.clone())
                }
            };
        };
        let unsigned = unsigned_of(bits)?;
        let target = match other.id().and_then(|t| self.scalar(t)) {
            Some(o) if o.is_signed_int() => {
                if !unsigned.widens_to(o) {
                    return None;
                }
                o
            }
            _ => unsigned,
        };
        Some(retype(v, TypeTable::elem(target)))
    }
}

/// `v` seen as type `t` (same slot, same bits).
fn retype(v: &Val, t: TypeId) -> Val {
    match v {
        Val::Slot(s, _) => Val::Slot(*s, t),
        Val::Const(c, _) => Val::Const(c.clone(), Ty::T(t)),
        other => other.clone(),
    }
}

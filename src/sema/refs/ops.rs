//! `NULL`, assignment compatibility, comparison and pointer arithmetic.

use super::{null_type, ref_parts, size_bytes};
use crate::elementary::ElemType;
use crate::ir::op::{Cmp, Op};
use crate::ir::type_table::{RefFlavor, TypeId, TypeTable};
use crate::sema::body::BodyBuilder;
use crate::sema::consts::Const;
use crate::sema::emit::{Ty, Val};
use crate::source::Span;
use crate::syntax::ast::BinaryOp;

impl BodyBuilder<'_> {
    /// The value `NULL`.
    pub(in crate::sema) fn null_value(&mut self) -> Val {
        let t = null_type(self.types);
        Val::Const(Const::Bits(crate::ir::refs::NULL), Ty::T(t))
    }

    /// A constant stored where the reference type `to` is expected: `NULL`
    /// converts, any other constant is E301 (`None` when `v` is not a
    /// constant or `to` is not a reference: the ordinary rules apply).
    pub(in crate::sema) fn const_as_ref(
        &mut self,
        v: &Val,
        to: TypeId,
        span: Span,
        what: &str,
    ) -> Option<Val> {
        let Val::Const(_, from) = v else {
            return None;
        };
        ref_parts(self.types, to)?;
        let is_null = from
            .id()
            .and_then(|t| ref_parts(self.types, t))
            .is_some_and(|(_, f)| f == RefFlavor::Null);
        if is_null {
            return Some(Val::Const(Const::Bits(crate::ir::refs::NULL), Ty::T(to)));
        }
        self.mismatch(span, *from, to, what);
        Some(Val::error())
    }

    /// May a reference of type `from` be stored where `to` is expected?
    /// `NULL` goes anywhere; `REF_TO` needs the same target type; a
    /// `POINTER TO` also accepts a pointer to an array of its elements or
    /// to a longer or shorter array of the same elements (each access is
    /// checked against the object anyway).
    pub(in crate::sema) fn ref_assignable(&self, from: TypeId, to: TypeId) -> bool {
        let (Some((ft, ff)), Some((tt, tf))) =
            (ref_parts(self.types, from), ref_parts(self.types, to))
        else {
            return false;
        };
        if ff == RefFlavor::Null {
            return true;
        }
        if ft == tt {
            return true;
        }
        let pointers = tf == RefFlavor::Pointer && ff == RefFlavor::Pointer;
        pointers && self.types.innermost(ft) == self.types.innermost(tt)
    }

    /// `=` / `<>` on references and `pointer + n`, `pointer - n`; `None`
    /// when neither operand is a reference.
    pub(in crate::sema) fn ref_binary(
        &mut self,
        op: BinaryOp,
        va: &Val,
        vb: &Val,
        span: Span,
    ) -> Option<Val> {
        let ra = va.ty().id().and_then(|t| ref_parts(self.types, t));
        let rb = vb.ty().id().and_then(|t| ref_parts(self.types, t));
        if ra.is_none() && rb.is_none() {
            return None;
        }
        if let Some(v) = self.pointer_compare(op, va, vb, span) {
            return Some(v);
        }
        Some(match (op, ra, rb) {
            (BinaryOp::Eq | BinaryOp::Ne, Some(_), Some(_)) => {
                let (a, b) = (self.materialize(va), self.materialize(vb));
                let cmp = if op == BinaryOp::Eq { Cmp::Eq } else { Cmp::Ne };
                let d = self.block.temp();
                self.block.emit(Op::CmpU { d, a, b, cmp });
                Val::Slot(d, TypeTable::elem(ElemType::Bool))
            }
            (BinaryOp::Add | BinaryOp::Sub, Some((target, RefFlavor::Pointer)), None) => {
                self.pointer_add(op, va, vb, target, span)
            }
            (BinaryOp::Sub, Some((ta, RefFlavor::Pointer)), Some((tb, RefFlavor::Pointer))) => {
                self.pointer_distance(va, vb, ta, tb, span)
            }
            (BinaryOp::Add | BinaryOp::Sub, Some((_, RefFlavor::RefTo)), None) => {
                self.diags.error(
                    "E252",
                    span,
                    "no arithmetic on REF_TO (edition 3); declare a POINTER TO to move it",
                );
                Val::error()
            }
            _ => {
                let (x, y) = (self.ty_name(va.ty()), self.ty_name(vb.ty()));
                self.diags.error(
                    "E252",
                    span,
                    format!(
                        "operator {} cannot combine {x} and {y}: references compare with `=` and `<>`, pointers move with `+` and `-` an integer",
                        crate::sema::binary::binary_name(op)
                    ),
                );
                Val::error()
            }
        })
    }

    /// `p + n` / `p - n` with `n` in bytes (CODESYS): whole elements only.
    fn pointer_add(&mut self, op: BinaryOp, p: &Val, n: &Val, target: TypeId, span: Span) -> Val {
        let int = match n.ty() {
            Ty::AnyInt => true,
            Ty::T(t) => {
                self.scalar(t)
                    .is_some_and(|e| e.is_int() || (e.is_bit() && e != ElemType::Bool))
                    && !self.is_enum(t)
            }
            Ty::AnyReal => false,
        };
        if !int {
            let name = self.ty_name(n.ty());
            self.diags.error(
                "E252",
                span,
                format!("a pointer moves by an integer number of bytes, found {name}"),
            );
            return Val::error();
        }
        let unit = size_bytes(self.types, target).and_then(|b| u16::try_from(b).ok());
        let slots = u16::try_from(self.types.size(target)).ok();
        let (Some(unit), Some(slots)) = (unit, slots) else {
            self.diags.error(
                "E252",
                span,
                format!(
                    "pointer arithmetic needs elements of at most 65535 bytes and slots, not {}",
                    self.types.name(target)
                ),
            );
            return Val::error();
        };
        self.diags.warning(
            "W303",
            span,
            "pointer arithmetic is a CODESYS extension (IEC 61131-3 has none)",
        );
        let ty = p.ty().id().unwrap_or(TypeTable::error());
        let pa = self.materialize(p);
        let mut b = self.materialize(n);
        if op == BinaryOp::Sub {
            let neg = self.block.temp();
            self.block.emit(Op::NegS {
                d: neg,
                a: b,
                shift: 0,
            });
            b = neg;
        }
        let d = self.block.temp();
        self.block.emit(Op::Mov { d, s: pa });
        self.block.emit(Op::PtrAdd { d, b, unit, slots });
        self.block.last_def = None;
        Val::Slot(d, ty)
    }
}

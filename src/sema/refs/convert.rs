//! The pointer conversions CODESYS makes without a word and OSCAT relies
//! on: a pointer of another element type over the same object (a *byte
//! view*, W306), a pointer kept in an integer and back (W307, W308), and
//! pointers ordered and compared with integers (W307). Each stays checked:
//! a byte view reads the object's bytes only (`vm::byte_view`), and an
//! integer turns back into a pointer only to the object a pointer gave it.

use super::{ref_parts, view_unit, viewable};
use crate::elementary::ElemType;
use crate::ir::op::{Cmp, Op};
use crate::ir::type_table::{RefFlavor, TypeId, TypeTable};
use crate::sema::body::BodyBuilder;
use crate::sema::consts::Const;
use crate::sema::emit::{Ty, Val};
use crate::source::Span;
use crate::syntax::ast::BinaryOp;

impl BodyBuilder<'_> {
    /// `v` stored where `to` is expected when one side is a `POINTER TO`
    /// and the ordinary rules refuse it: a byte view, a pointer into an
    /// integer, an integer into a pointer. `None` when none applies.
    pub(in crate::sema) fn pointer_coerce(
        &mut self,
        v: &Val,
        to: TypeId,
        span: Span,
    ) -> Option<Val> {
        let to_ref = ref_parts(self.types, to);
        let from = v.ty().id();
        let from_ref = from.and_then(|t| ref_parts(self.types, t));
        match (from_ref, to_ref) {
            (Some((ft, RefFlavor::Pointer)), Some((tt, RefFlavor::Pointer))) => {
                if from.is_some_and(|f| self.ref_assignable(f, to)) {
                    return None;
                }
                if self.types.same_width_strings(ft, tt) {
                    // `POINTER TO STRING` over a `STRING(10000)` (CODESYS):
                    // the same string, whose buffer keeps its own length.
                    return Some(Val::Slot(self.materialize(v), to));
                }
                Some(self.byte_view(v, ft, tt, to, span))
            }
            (Some((ft, RefFlavor::Pointer)), None) => {
                let e = self.scalar(to).filter(|e| e.is_int() || e.is_bit())?;
                if self.is_enum(to) || e.bits() < 32 {
                    return None;
                }
                self.diags.warning(
                    "W307",
                    span,
                    format!(
                        "a pointer kept in {}: CODESYS's address is here the pointer's object number and byte offset (a CODESYS extension)",
                        self.types.name(to)
                    ),
                );
                let s = self.pointer_image(v, ft);
                Some(Val::Slot(s, to))
            }
            (None, Some((target, RefFlavor::Pointer))) => {
                let int = match v.ty() {
                    Ty::AnyInt => true,
                    Ty::T(t) => {
                        !self.is_enum(t)
                            && self
                                .scalar(t)
                                .is_some_and(|e| (e.is_int() || e.is_bit()) && e.bits() >= 32)
                    }
                    Ty::AnyReal => false,
                };
                if !int {
                    return None;
                }
                if let Val::Const(c, _) = v
                    && matches!(c, Const::Int(0) | Const::Bits(0))
                {
                    return Some(Val::Const(Const::Bits(crate::ir::refs::NULL), Ty::T(to)));
                }
                self.diags.warning(
                    "W308",
                    span,
                    "an integer made into a pointer (a CODESYS extension): it designates the object of the pointer it came from, or faults (R035)",
                );
                let s = self.materialize(v);
                let d = self.block.temp();
                self.block.emit(Op::Mov { d, s });
                // Elementary values are read through the byte view; a
                // structure or a STRING only as a value of its type found
                // at the address (vm::type_at).
                let ty = match viewable(self.types, self.types.innermost(target)) {
                    Some(_) => crate::ir::refs::NO_TYPE,
                    None => target.0,
                };
                self.block.emit(Op::IntToPtr { d, ty });
                self.block.last_def = None;
                Some(Val::Slot(d, to))
            }
            _ => None,
        }
    }

    /// `pt := ps` where the element types differ: a byte view (W306), or
    /// E256 when either side has no byte layout.
    fn byte_view(&mut self, v: &Val, ft: TypeId, tt: TypeId, to: TypeId, span: Span) -> Val {
        let target = self.types.innermost(tt);
        if self.object_layout(ft) == 0 || viewable(self.types, target).is_none() {
            let (a, b) = (self.ty_name(v.ty()), self.types.name(to).to_string());
            self.diags.error(
                "E256",
                span,
                format!(
                    "{a} cannot be viewed as {b}: a byte view needs an object of elementary values, strings or structures of them, read as elementary values"
                ),
            );
            return Val::error();
        }
        self.diags.warning(
            "W306",
            span,
            format!(
                "a {} over a {}: its bytes are read as CODESYS lays them out (a CODESYS extension)",
                self.types.name(to),
                self.types.name(ft)
            ),
        );
        let s = self.materialize(v);
        let d = self.block.temp();
        self.block.emit(Op::Mov { d, s });
        self.block.emit(Op::RefView {
            d,
            unit: view_unit(self.types, ft),
        });
        self.block.last_def = None;
        Val::Slot(d, to)
    }

    /// The integer image of pointer `v` to `target`, in a new slot.
    fn pointer_image(&mut self, v: &Val, target: TypeId) -> crate::ir::op::Slot {
        let s = self.materialize(v);
        let d = self.block.temp();
        self.block.emit(Op::Mov { d, s });
        self.block.emit(Op::PtrToInt {
            d,
            unit: view_unit(self.types, target),
        });
        self.block.last_def = None;
        d
    }

    /// `p1 - p2` between two pointers to elementary values (CODESYS): the
    /// distance in bytes, a DINT, as the difference of their integer
    /// images (W307). Within one object it is the byte distance CODESYS
    /// gives (`ADR(a[1]) - ADR(a[0])` is `SIZEOF(a[0])`); between two
    /// objects it is a number of no use, as an address difference is.
    pub(in crate::sema) fn pointer_distance(
        &mut self,
        va: &Val,
        vb: &Val,
        ta: TypeId,
        tb: TypeId,
        span: Span,
    ) -> Val {
        let elementary = |me: &Self, t: TypeId| viewable(me.types, me.types.innermost(t));
        if elementary(self, ta).is_none() || elementary(self, tb).is_none() {
            let (a, b) = (self.ty_name(va.ty()), self.ty_name(vb.ty()));
            self.diags.error(
                "E252",
                span,
                format!(
                    "the distance between two pointers is measured between pointers to elementary values (and arrays of them), not {a} and {b}"
                ),
            );
            return Val::error();
        }
        self.diags.warning(
            "W307",
            span,
            "the distance between two pointers, in bytes (a CODESYS extension): their objects' numbers and byte offsets subtracted",
        );
        let a = self.pointer_image(va, ta);
        let b = self.pointer_image(vb, tb);
        let d = self.block.temp();
        self.block.emit(Op::SubS { d, a, b, shift: 32 });
        Val::Slot(d, TypeTable::elem(ElemType::Dint))
    }

    /// `p1 < p2`, `p = q`, `pt < end` and `p = 0` between pointers, or a
    /// pointer and an integer: their integer images compared (W307 for
    /// an order or an integer). `None` when this is not such a comparison
    /// (`p = NULL` compares the slots: NULL is 0 either way).
    pub(in crate::sema) fn pointer_compare(
        &mut self,
        op: BinaryOp,
        va: &Val,
        vb: &Val,
        span: Span,
    ) -> Option<Val> {
        let cmp = match op {
            BinaryOp::Eq => Cmp::Eq,
            BinaryOp::Ne => Cmp::Ne,
            BinaryOp::Lt => Cmp::Lt,
            BinaryOp::Le => Cmp::Le,
            BinaryOp::Gt => Cmp::Gt,
            BinaryOp::Ge => Cmp::Ge,
            _ => return None,
        };
        let side = |me: &Self, v: &Val| -> Option<Option<TypeId>> {
            match v.ty() {
                Ty::AnyInt => Some(None),
                Ty::AnyReal => None,
                Ty::T(t) => match ref_parts(me.types, t) {
                    Some((target, RefFlavor::Pointer)) => Some(Some(target)),
                    Some((_, RefFlavor::Null)) => Some(Some(TypeTable::void())),
                    Some(_) => None,
                    None => {
                        let e = me.scalar(t)?;
                        ((e.is_int() || e.is_bit()) && !me.is_enum(t)).then_some(None)
                    }
                },
            }
        };
        let (a, b) = (side(self, va)?, side(self, vb)?);
        let null = TypeTable::void();
        if a.is_none() && b.is_none() || a == Some(null) || b == Some(null) {
            // Integers, or `NULL` on a side: the ordinary rules.
            return None;
        }
        let pointers = a.is_some() && b.is_some();
        if !(pointers && matches!(cmp, Cmp::Eq | Cmp::Ne)) {
            self.diags.warning(
                "W307",
                span,
                "pointers ordered or compared with an integer by their integer images (a CODESYS extension)",
            );
        }
        // Two pointers are equal when they designate the same byte, typed
        // or viewed: their images are compared, not their slots.
        let sa = match a {
            Some(t) => self.pointer_image(va, t),
            None => self.materialize(va),
        };
        let sb = match b {
            Some(t) => self.pointer_image(vb, t),
            None => self.materialize(vb),
        };
        let d = self.block.temp();
        self.block.emit(Op::CmpU {
            d,
            a: sa,
            b: sb,
            cmp,
        });
        Some(Val::Slot(d, TypeTable::elem(ElemType::Bool)))
    }
}

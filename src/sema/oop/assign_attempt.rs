//! The assignment attempt `itf ?= value;` (edition 3): `value` is an
//! interface value (of any interface), an FB instance or `THIS^`; the
//! target interface gets it when the instance's type implements the
//! target's interface, else the empty value (0). The instance's type id
//! is compared with each implementing FB's at run time (one compare and
//! branch per implementing FB, as a call through an interface does).

use super::calls::{is_this, place_ref};
use super::itf_values::field;
use crate::elementary::ElemType;
use crate::ir::op::{Cmp, Op, Slot, Target};
use crate::ir::type_table::TypeTable;
use crate::sema::body::BodyBuilder;
use crate::sema::consts::Const;
use crate::sema::emit::{Place, PlaceRef, Ty, Val};
use crate::syntax::ast::{Expr, ExprKind, LiteralValue};

impl BodyBuilder<'_> {
    /// `target ?= value;`.
    pub(super) fn assign_attempt(&mut self, target: &Expr, value: &Expr) {
        let Some(dst) = self.place(target) else {
            return;
        };
        if !self.check_writable(&dst, target.span) {
            return;
        }
        let Some(itf) = self.interface_of(dst.ty) else {
            let found = self.types.name(dst.ty).to_string();
            self.diags.error(
                "E941",
                target.span,
                format!(
                    "`?=` assigns to a variable of an interface type, not to one of type {found} (an attempt into a REF_TO is not supported by plcrun)"
                ),
            );
            return;
        };
        let Some((addr, tid)) = self.attempt_source(value) else {
            return;
        };
        let (ulint, udint) = (
            TypeTable::elem(ElemType::Ulint),
            TypeTable::elem(ElemType::Udint),
        );
        let (Some(dst_addr), Some(dst_tid)) = (field(&dst, 0, ulint), field(&dst, 1, udint)) else {
            return;
        };
        let mut tids: Vec<u32> = self
            .model
            .oop
            .fbs
            .values()
            .filter(|f| !f.is_abstract && f.interfaces.contains(&itf))
            .map(|f| f.tid)
            .collect();
        tids.sort_unstable();
        // A matching type id jumps to the copy; none leaves the empty value.
        let mut hits = Vec::new();
        for t in tids {
            hits.push(self.block.emit(Op::JnCmpSI {
                a: tid,
                imm: t as i32,
                cmp: Cmp::Ne,
                t: Target::UNPATCHED,
            }));
        }
        let zero = self.materialize(&Val::Const(Const::Bits(0), Ty::T(ulint)));
        self.write_place(&dst_addr, zero);
        self.write_place(&dst_tid, zero);
        let end = self.block.emit(Op::Jmp {
            t: Target::UNPATCHED,
        });
        let here = self.block.here();
        for h in hits {
            self.block.patch(h, here);
        }
        self.write_place(&dst_addr, addr);
        self.write_place(&dst_tid, tid);
        let here = self.block.here();
        self.block.patch(end, here);
        self.block.last_def = None;
    }

    /// The instance address and type id of the value tried, each in a
    /// temporary the writes to the target cannot change.
    fn attempt_source(&mut self, value: &Expr) -> Option<(Slot, Slot)> {
        let (ulint, udint) = (
            TypeTable::elem(ElemType::Ulint),
            TypeTable::elem(ElemType::Udint),
        );
        if let ExprKind::Literal(l) = &value.kind
            && matches!(l.value, LiteralValue::Int(0))
        {
            let z = self.materialize(&Val::Const(Const::Bits(0), Ty::T(ulint)));
            return Some((z, z));
        }
        let (addr, tid) = if is_this(value) {
            if !self.this_allowed(value.span) {
                return None;
            }
            let fb = self.oop.as_ref()?.fb.clone();
            let this = place_ref(Place::Frame(Slot::new(0)), ulint);
            let a = self.address_of(&this);
            (a, self.model.oop.fbs[&fb].tid)
        } else {
            let src = self.place(value)?;
            if self.interface_of(src.ty).is_some() {
                let a = self.read_field(&src, 0, ulint)?;
                let t = self.read_field(&src, 1, udint)?;
                return Some((a, t));
            }
            let Some(fb) = self.oop_fb_of(src.ty) else {
                let found = self.types.name(src.ty).to_string();
                self.diags.error(
                    "E942",
                    value.span,
                    format!("`?=` tries an interface value or a function block instance, not a value of type {found}"),
                );
                return None;
            };
            let a = self.address_of(&src);
            (a, self.model.oop.fbs[&fb].tid)
        };
        let a = self.kept(addr);
        let t = self.materialize(&Val::Const(Const::Bits(tid as u64), Ty::T(udint)));
        Some((a, self.kept(t)))
    }

    /// Field `off` of the interface value at `p`, read into a temporary.
    fn read_field(
        &mut self,
        p: &PlaceRef,
        off: u32,
        ty: crate::ir::type_table::TypeId,
    ) -> Option<Slot> {
        let f = field(p, off, ty)?;
        let Val::Slot(s, _) = self.read_place(&f) else {
            return None;
        };
        Some(self.kept(s))
    }

    /// `s`, or a temporary copy of it when it is a variable's slot.
    fn kept(&mut self, s: Slot) -> Slot {
        if self.block.is_temp(s) {
            return s;
        }
        let t = self.block.temp();
        self.block.mov(t, s);
        self.block.last_def = None;
        t
    }
}

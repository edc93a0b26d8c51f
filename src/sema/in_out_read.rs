//! Reading a VAR_IN_OUT of a function block instance from outside:
//! `x := inst.io;` (CoDeSys 2.3 and matiec accept it; OSCAT relies on it
//! in about twenty blocks: `RMP.RMP`, `INTEGRATE.Y`, `ONTIME.CYCLES`).
//!
//! IEC 61131-3 shows only inputs and outputs outside a block. CODESYS
//! implements an in-out as a hidden pointer in the instance that each call
//! sets to the variable passed, so reading `inst.io` reads *that
//! variable*, the one the last call bound. plcrun gives it the same
//! meaning: the instance's slot holds the bound variable's address, and
//! the read goes through it. Before the first call nothing is bound: the
//! hidden pointer holds no address (`NOT_CONNECTED`, outside memory), and
//! the read is the runtime fault R030 (a
//! dereference of NULL), as CODESYS, whose runtime stops on the access
//! violation, never an arbitrary value. Each read warns W325 (`--strict`
//! makes it an error); writing through it from outside is refused (E422):
//! the block's caller owns that variable.

use super::body::BodyBuilder;
use super::emit::{Place, PlaceRef, Val};
use crate::elementary::ElemType;
use crate::ir::image::NOT_CONNECTED;
use crate::ir::op::{Cmp, Op, Slot, Target};
use crate::ir::type_table::{Member, MemberKind, TypeDef, TypeTable};
use crate::syntax::ast::Ident;

/// The read-only reason given to an in-out seen from outside;
/// `write_refusal_code` reports writes through it as E422.
pub(super) const IN_OUT_OUTSIDE: &str = "it is a VAR_IN_OUT of the block: from outside it can be read (it reads the variable the \
     last call bound), not written";

impl BodyBuilder<'_> {
    /// `inst.io` where `io` is a VAR_IN_OUT of the POU instance at `b`:
    /// the variable the last call bound. `None` when `name` is not an
    /// in-out of `members` (the other rules apply).
    pub(super) fn in_out_from_outside(
        &mut self,
        def: &TypeDef,
        members: &[Member],
        name: &Ident,
        b: &PlaceRef,
    ) -> Option<PlaceRef> {
        let m = members
            .iter()
            .find(|m| m.kind == MemberKind::InOut && m.name.eq_ignore_ascii_case(&name.name))?;
        self.diags.warning(
            "W325",
            name.span,
            format!(
                "`{}` is a VAR_IN_OUT of {}: reading it from outside reads the variable its last \
                 call bound (a CoDeSys/matiec extension; before the first call it is the fault R030)",
                m.name, def.name
            ),
        );
        let (ty, offset) = (m.ty, m.offset);
        let holder = PlaceRef {
            place: self.offset_place(b.place, offset),
            ty: TypeTable::elem(ElemType::Udint),
            writable: false,
            readonly_reason: None,
            input_image: b.input_image,
        };
        let Val::Slot(addr, _) = self.read_place(&holder) else {
            return None;
        };
        // Not bound yet (NOT_CONNECTED, whose object number is 0): fault
        // R030 by dereferencing it as a reference, NULL.
        let connected = self.in_out_connected(addr);
        let bound = self.block.emit(Op::Jnz {
            c: connected,
            t: Target::UNPATCHED,
        });
        let scratch = self.block.temp();
        self.block.emit(Op::RefAddr {
            d: scratch,
            r: addr,
            width: 1,
        });
        let here = self.block.here();
        self.block.patch(bound, here);
        Some(PlaceRef {
            place: Place::Ind { p: addr, off: 0 },
            ty,
            writable: false,
            readonly_reason: Some(IN_OUT_OUTSIDE),
            input_image: false,
        })
    }

    /// A BOOL slot: TRUE when the VAR_IN_OUT whose address slot is `addr`
    /// has been connected by a call (it holds an address, not
    /// `NOT_CONNECTED`).
    pub(super) fn in_out_connected(&mut self, addr: Slot) -> Slot {
        let (d, none) = (self.block.temp(), self.block.const_slot(NOT_CONNECTED));
        self.block.emit(Op::CmpU {
            d,
            a: addr,
            b: none,
            cmp: Cmp::Ne,
        });
        d
    }
}

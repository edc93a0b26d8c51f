//! `r^` and `r^[i]` as places.

use super::{ref_parts, size_bytes, viewable};
use crate::ir::image::ArrayDesc;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{RefFlavor, TypeId};
use crate::sema::body::BodyBuilder;
use crate::sema::emit::{Place, PlaceRef, Val};
use crate::syntax::ast::Expr;

impl BodyBuilder<'_> {
    /// The reference `r` evaluates to, in a slot, with its target type;
    /// E250 when `r` is not a reference.
    fn reference_operand(&mut self, r: &Expr) -> Option<(Slot, TypeId, RefFlavor)> {
        let v = self.expr(r, None);
        if v.is_error() {
            return None;
        }
        let Some(t) = v.ty().id() else {
            self.not_a_reference(r, &v);
            return None;
        };
        match ref_parts(self.types, t) {
            Some((_, RefFlavor::Null)) => {
                self.diags
                    .error("E250", r.span, "`NULL` cannot be dereferenced");
                None
            }
            Some((target, flavor)) => Some((self.materialize(&v), target, flavor)),
            None => {
                self.not_a_reference(r, &v);
                None
            }
        }
    }

    fn not_a_reference(&mut self, r: &Expr, v: &Val) {
        let name = self.ty_name(v.ty());
        self.diags.error(
            "E250",
            r.span,
            format!("`^` needs a reference or pointer, found {name}"),
        );
    }

    /// The checked address of the `width` slots reference `r` designates.
    pub(super) fn checked_address(&mut self, r: Slot, width: u32) -> Slot {
        let d = self.block.temp();
        self.block.emit(Op::RefAddr { d, r, width });
        self.block.last_def = None;
        d
    }

    fn deref_place(p: Slot, ty: TypeId) -> PlaceRef {
        PlaceRef {
            place: Place::Ind { p, off: 0 },
            ty,
            writable: true,
            readonly_reason: None,
            input_image: false,
        }
    }

    /// The place of an elementary value a `POINTER TO` designates: read
    /// and written by `RefLoad`/`RefStore`, which also serve byte views.
    pub(super) fn view_place(&self, r: Slot, ty: TypeId, flavor: RefFlavor) -> Option<PlaceRef> {
        if flavor != RefFlavor::Pointer {
            return None;
        }
        let e = viewable(self.types, ty)?;
        let elem = crate::ir::refs::elem_code(e);
        Some(PlaceRef {
            place: Place::View { r, elem },
            ..Self::deref_place(r, ty)
        })
    }

    /// `r^`: the whole target, checked against the object.
    pub(in crate::sema) fn place_deref(&mut self, r: &Expr) -> Option<PlaceRef> {
        let (slot, target, flavor) = self.reference_operand(r)?;
        if let Some(p) = self.view_place(slot, target, flavor) {
            return Some(p);
        }
        let width = self.types.size(target).max(1);
        let p = self.checked_address(slot, width);
        Some(Self::deref_place(p, target))
    }

    /// `r^[i, ...]`: the element only is checked against the object, so a
    /// pointer to a long array may walk a shorter one.
    pub(in crate::sema) fn place_deref_index(
        &mut self,
        e: &Expr,
        r: &Expr,
        indexes: &[Expr],
    ) -> Option<PlaceRef> {
        let (slot, target, flavor) = self.reference_operand(r)?;
        self.reference_element(e, slot, target, flavor, indexes)
    }

    /// Element `indexes` of the array of type `target` reference `slot`
    /// designates.
    pub(in crate::sema) fn reference_element(
        &mut self,
        e: &Expr,
        slot: Slot,
        target: TypeId,
        flavor: RefFlavor,
        indexes: &[Expr],
    ) -> Option<PlaceRef> {
        let (moved, elem, stride) = self.element_reference(e, slot, target, indexes)?;
        if let Some(p) = self.view_place(moved, elem, flavor) {
            return Some(p);
        }
        let p = self.checked_address(moved, stride);
        Some(Self::deref_place(p, elem))
    }

    /// A new reference to element `indexes` of the array of type `target`
    /// reference `slot` designates, in the same object (the index checked
    /// against the declared bounds): the reference, the element type and
    /// its size in slots.
    pub(in crate::sema) fn element_reference(
        &mut self,
        e: &Expr,
        slot: Slot,
        target: TypeId,
        indexes: &[Expr],
    ) -> Option<(Slot, TypeId, u32)> {
        let (dims, elem) = self.array_shape(e, target, indexes.len())?;
        let vals = self.index_values(indexes)?;
        let idx = self.dynamic_index(&vals, &dims);
        let stride = self.types.size(elem).max(1);
        let desc = self.out.array_desc(ArrayDesc {
            offset: 0,
            lo: if dims.len() == 1 { dims[0].lo } else { 0 },
            len: dims.iter().map(|d| d.len()).product(),
            stride,
            span: e.span,
        });
        let moved = self.block.temp();
        self.block.emit(Op::Mov { d: moved, s: slot });
        let unit = size_bytes(self.types, elem)
            .and_then(|b| u16::try_from(b).ok())
            .unwrap_or(0);
        self.block.emit(Op::RefIndex {
            d: moved,
            idx,
            desc,
            unit,
        });
        self.block.last_def = None;
        Some((moved, elem, stride))
    }
}

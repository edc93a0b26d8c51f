//! `s[i]` on a STRING (CODESYS, TwinCAT): the BYTE at offset `i` of the
//! string's characters (`s[0]` the first), read and written in place, as
//! a byte view of the string through a pointer would (W306 semantics,
//! docs/semantics.md "Byte views through pointers"): an offset outside
//! the string's buffer (its length plus the closing NUL) stops the PLC
//! (R031). A WSTRING's element is a WORD, its `i`-th character.

use super::{RefFlavor, layout_code, view_unit};
use crate::elementary::ElemType;
use crate::ir::op::Op;
use crate::ir::type_table::{TypeKind, TypeTable};
use crate::sema::body::BodyBuilder;
use crate::sema::consts::Const;
use crate::sema::emit::{PlaceRef, Ty, Val};
use crate::syntax::ast::{BinaryOp, Expr};

impl BodyBuilder<'_> {
    /// The place of `base[index]` when `base` is a STRING or WSTRING of a
    /// CODESYS or TwinCAT file; `None` (nothing reported) otherwise.
    pub(in crate::sema) fn string_byte(
        &mut self,
        base: &PlaceRef,
        indexes: &[Expr],
        e: &Expr,
    ) -> Option<Option<PlaceRef>> {
        let TypeKind::Str { wide, .. } = self.types.get(base.ty).kind else {
            return None;
        };
        if !self.model.codesys_files.contains(&e.span.file) {
            return None;
        }
        let [index] = indexes else {
            self.diags.error(
                "E404",
                e.span,
                "a STRING is indexed by one offset (`s[i]`, its i-th byte from 0)",
            );
            return Some(None);
        };
        let (elem, bytes) = if wide {
            (ElemType::Word, 2u16)
        } else {
            (ElemType::Byte, 1u16)
        };
        let v = self.expr(index, Some(TypeTable::elem(ElemType::Dint)));
        let mut v = self.coerce(
            v,
            TypeTable::elem(ElemType::Dint),
            index.span,
            "a STRING offset",
        );
        if wide {
            // The pointer moves by bytes: two a character.
            let two = Val::Const(Const::Int(2), Ty::AnyInt);
            v = self.binary_vals(BinaryOp::Mul, v, two, index.span);
        }
        if v.is_error() || layout_code(self.types, base.ty) == 0 {
            return Some(None);
        }
        // A reference to the whole string, viewed as bytes, moved by the
        // offset (in characters: bytes of the element).
        let r = self.reference_value(base);
        let d = self.block.temp();
        self.block.emit(Op::Mov { d, s: r });
        self.block.emit(Op::RefView {
            d,
            unit: view_unit(self.types, base.ty),
        });
        let n = self.materialize(&v);
        self.block.emit(Op::PtrAdd {
            d,
            b: n,
            unit: bytes,
            slots: 1,
        });
        self.block.last_def = None;
        let ty = TypeTable::elem(elem);
        Some(
            self.view_place(d, ty, RefFlavor::Pointer)
                .map(|p| PlaceRef {
                    writable: base.writable,
                    readonly_reason: base.readonly_reason,
                    ..p
                }),
        )
    }
}

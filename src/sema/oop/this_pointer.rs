//! `THIS` without `^` (CODESYS / TwinCAT): a `POINTER TO` the instance the
//! code runs on, as in `addresses[n] := THIS;` (TcUnit's test suites
//! register themselves so).

use super::calls::place_ref;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::RefFlavor;
use crate::sema::body::BodyBuilder;
use crate::sema::emit::{Place, Val};
use crate::sema::refs::intern_ref;
use crate::source::Span;
use crate::syntax::ast::PouKind;

impl BodyBuilder<'_> {
    /// The value of `THIS` at `span` when no variable of that name is
    /// declared; E918 outside a FUNCTION_BLOCK and its methods.
    pub(in crate::sema) fn this_pointer(&mut self, span: Span) -> Val {
        let fb = match &self.oop {
            Some(scope) => self.model.pou_index.get(&scope.fb).copied(),
            None => self
                .model
                .pous
                .get(self.block.pou)
                .filter(|p| p.kind == PouKind::FunctionBlock)
                .map(|_| self.block.pou),
        };
        let Some(ty) = fb.map(|p| self.model.pous[p].ty) else {
            self.diags
                .error("E918", span, "`THIS` can only be used in a FUNCTION_BLOCK");
            return Val::error();
        };
        // The FB's body and its methods run on the instance's own frame.
        let this = place_ref(Place::Frame(Slot::new(0)), ty);
        let addr = self.address_of(&this);
        let d = self.block.temp();
        // The instance's size (its frame) is known once the body and its
        // methods are emitted: `patch_this_lengths` writes it over the 0.
        self.block.emit(Op::RefMake {
            d,
            p: addr,
            len: 0,
            layout: 0,
        });
        Val::Slot(d, intern_ref(self.types, ty, RefFlavor::Pointer))
    }
}

/// Gives every `THIS` of a function block's code (the `RefMake` of length
/// 0 that `this_pointer` emits; any other has a length of at least 1) the
/// instance's size, `frame_size`.
pub(in crate::sema) fn patch_this_lengths(ops: &mut [Op], frame_size: u32) {
    for op in ops {
        if let Op::RefMake { len, .. } = op
            && *len == 0
        {
            *len = frame_size;
        }
    }
}

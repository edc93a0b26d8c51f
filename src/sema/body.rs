//! The body phase: one [`BodyBuilder`] per POU emits its body (ST, IL or
//! SFC) into code blocks. It reads the declarations ([`Model`]) without
//! changing them, appends to the program's shared tables ([`Program`]), and
//! owns everything that only this body needs: the emission context of the
//! code block being emitted ([`Fcx`]: instructions, temporaries, constant
//! and pinned slots, fixups; an SFC condition or action swaps in a fresh
//! one for its own block) and the SFC blocks waiting for their constant
//! slots.

use super::emit::{Fcx, place_tagged};
use super::model::Model;
use super::program::Program;
use crate::diagnostics::Diagnostics;
use crate::ir::op::{CodeIdx, Op, Slot};
use crate::ir::type_table::TypeTable;
use crate::syntax::ast::{Body, Pou};
use indexmap::IndexSet;

/// Emits the body of one POU.
pub(super) struct BodyBuilder<'a> {
    /// The declarations (read-only).
    pub(super) model: &'a Model,
    /// All types; bodies only intern new ones (string function results).
    pub(super) types: &'a mut TypeTable,
    /// The shared output tables.
    pub(super) out: &'a mut Program,
    /// Where errors go.
    pub(super) diags: &'a mut Diagnostics,
    /// The code block being emitted: the body, or one of its SFC blocks.
    pub(super) block: Fcx,
    /// SFC blocks of this POU whose constant and pinned slots still need
    /// placing: (code block, constants, pin count).
    pub(super) pending_blocks: Vec<(CodeIdx, IndexSet<u64>, u32)>,
    /// SFC blocks of this POU (they share its frame size).
    pub(super) owned_blocks: Vec<CodeIdx>,
}

/// What an emitted body tells the declarations: its frame.
pub(super) struct BuiltBody {
    /// Frame size: variables, temporaries, constant and pinned slots.
    pub(super) frame_size: u32,
    /// The frame's constant slots: `(slot, value)`.
    pub(super) consts: Vec<(Slot, u64)>,
}

impl<'a> BodyBuilder<'a> {
    /// A builder of POU `p`'s body over the model as it stands.
    pub(super) fn new(
        model: &'a Model,
        types: &'a mut TypeTable,
        out: &'a mut Program,
        diags: &'a mut Diagnostics,
        p: usize,
    ) -> BodyBuilder<'a> {
        BodyBuilder {
            model,
            types,
            out,
            diags,
            block: Fcx::new(p, model.pous[p].vars_size),
            pending_blocks: Vec::new(),
            owned_blocks: Vec::new(),
        }
    }

    /// Emits the body of the POU into its code block (and SFC blocks).
    pub(super) fn build(mut self, pou: &Pou) -> BuiltBody {
        let p = self.block.pou;
        match &pou.body {
            Body::St(stmts) => self.stmts(stmts),
            Body::Il(lines) => {
                self.il_body(lines);
            }
            Body::Sfc(elems) => self.emit_chart(pou, elems),
        }
        let mut f = std::mem::replace(&mut self.block, Fcx::new(p, 0));
        let end = f.here();
        for j in std::mem::take(&mut f.returns) {
            f.patch(j, end);
        }
        f.span = pou.span;
        f.emit(Op::Ret);
        let code = self.model.pous[p].code;
        // The body and its SFC blocks share the frame: temporaries first
        // (each block's start at the same base), then one region of
        // constants and pinned slots per block.
        let first = f.temp_max;
        let (mut frame_size, mut consts) = f.place_consts(first);
        for (block, block_consts, pins) in std::mem::take(&mut self.pending_blocks) {
            let ops = &mut self.out.codes[block.index()].ops;
            let (end, list) = place_tagged(ops, &block_consts, pins, frame_size);
            consts.extend(list);
            frame_size = end;
        }
        for c in std::mem::take(&mut self.owned_blocks) {
            self.out.codes[c.index()].frame_size = frame_size;
        }
        for (at, callee) in std::mem::take(&mut f.fixups) {
            self.out.fixups.push((code, at, callee));
        }
        let block = &mut self.out.codes[code.index()];
        block.ops = f.ops;
        block.spans = f.spans;
        block.frame_size = frame_size;
        BuiltBody { frame_size, consts }
    }
}

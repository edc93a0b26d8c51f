//! Edge-qualified inputs (edition 3): `clk : BOOL R_EDGE;` in a
//! FUNCTION_BLOCK's VAR_INPUT reads TRUE inside the body only on a rising
//! (R_EDGE) or falling (F_EDGE) edge of the value the caller passes.
//!
//! The caller writes the input's slot as for any input (the raw value). Two
//! hidden slots follow it in the instance: the value the body sees under
//! the input's name, and the raw value of the previous call (FALSE at the
//! start, as R_TRIG's and F_TRIG's memory). At the start of every call the
//! body computes `seen := raw AND NOT previous` (rising) or
//! `seen := previous AND NOT raw` (falling), then `previous := raw`.

use super::body::BodyBuilder;
use super::declare::Declarer;
use super::model::Storage;
use crate::elementary::ElemType;
use crate::ir::op::{Op, Slot};
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::syntax::ast::{EdgeQualifier, Pou, PouKind, VarBlock, VarDecl, VarKind};

impl Declarer<'_> {
    /// Whether declaration `decl` may carry its edge qualifier: a BOOL
    /// (E427) VAR_INPUT of a FUNCTION_BLOCK (E426). False without one.
    pub(super) fn edge_input_ok(
        &mut self,
        pou: &Pou,
        block: &VarBlock,
        decl: &VarDecl,
        ty: TypeId,
    ) -> bool {
        if decl.edge.is_none() {
            return false;
        }
        if block.kind != VarKind::Input || pou.kind != PouKind::FunctionBlock {
            self.diags.error(
                "E426",
                decl.span,
                "R_EDGE and F_EDGE qualify only a VAR_INPUT of a FUNCTION_BLOCK (the edge \
                 needs memory that outlives the call)",
            );
            return false;
        }
        if ty != TypeTable::elem(ElemType::Bool) {
            if ty != TypeTable::error() {
                self.diags.error(
                    "E427",
                    decl.ty.span(),
                    format!(
                        "R_EDGE and F_EDGE need a BOOL input, found {}",
                        self.types.name(ty)
                    ),
                );
            }
            return false;
        }
        true
    }
}

impl BodyBuilder<'_> {
    /// Emits, at the start of an FB body, the edge detection of each of its
    /// edge-qualified inputs.
    pub(super) fn emit_edge_inputs(&mut self, pou: &Pou) {
        let edges = pou
            .var_blocks
            .iter()
            .filter(|b| b.kind == VarKind::Input)
            .flat_map(|b| &b.decls)
            .filter_map(|d| d.edge.map(|e| (d, e)));
        let mut work = Vec::new();
        for (decl, edge) in edges {
            for name in &decl.names {
                if let Some((raw, seen)) = self.edge_slots(&name.name) {
                    work.push((raw, seen, edge));
                }
            }
        }
        for (raw, seen, edge) in work {
            let previous = seen.offset(1);
            let (a, b) = match edge {
                EdgeQualifier::Rising => (raw, previous),
                EdgeQualifier::Falling => (previous, raw),
            };
            self.block.emit(Op::AndN { d: seen, a, b });
            self.block.emit(Op::Mov {
                d: previous,
                s: raw,
            });
        }
    }

    /// The caller's slot of input `name` and the slot the body reads it
    /// from, when they differ (the input was laid out with an edge).
    fn edge_slots(&self, name: &str) -> Option<(Slot, Slot)> {
        let var = self.lookup_var(&name.to_ascii_uppercase())?;
        let Storage::Frame(seen) = var.storage else {
            return None;
        };
        let pou = self.model.pous.get(self.block.pou)?;
        let TypeKind::Pou { members, .. } = &self.types.get(pou.ty).kind else {
            return None;
        };
        let raw = members
            .iter()
            .find(|m| m.name.eq_ignore_ascii_case(name))?
            .offset;
        (raw != seen).then(|| (Slot::new(raw), Slot::new(seen)))
    }
}

//! Where the runtime finds the `FB_init` calls it makes before the first
//! cycle: the hidden function of the global lists and the hidden method of
//! each program instance (`src/sema/fb_init_calls.rs`).

use super::Linker;
use crate::ir::image::{ProgramInstance, StartCall};
use crate::sema::fb_init_calls::{GLOBALS, MEMBERS, RETAINS};
use crate::sema::model::Storage;
use crate::syntax::ast::PouKind;

impl Linker<'_> {
    /// The start calls: the global lists' first, then each program
    /// instance's, in execution order.
    pub(super) fn start_calls(&self, instances: &[ProgramInstance]) -> Vec<StartCall> {
        let mut out = Vec::new();
        let globals = GLOBALS.to_ascii_uppercase();
        let function = self
            .model
            .pous
            .iter()
            .find(|p| p.kind == PouKind::Function && p.name.to_ascii_uppercase() == globals);
        if let Some(f) = function
            && let Some(Storage::Frame(o)) =
                f.vars.get(&RETAINS.to_ascii_uppercase()).map(|v| v.storage)
        {
            let base = self.out.codes[f.code.index()].frame;
            out.push(StartCall {
                code: f.code,
                base,
                retains: base + o,
            });
        }
        for inst in instances {
            if let Some(call) = self.program_start(inst) {
                out.push(call);
            }
        }
        out
    }

    /// The start call of a program instance whose PROGRAM has the hidden
    /// method.
    fn program_start(&self, inst: &ProgramInstance) -> Option<StartCall> {
        let key = inst.type_name.to_ascii_uppercase();
        let fb = self.model.oop.fbs.get(&key)?;
        let v = *fb.dispatch.get(&MEMBERS.to_ascii_uppercase())?;
        let hidden = &fb.versions[v].params.first()?.hidden;
        let pou = self
            .model
            .pous
            .iter()
            .find(|p| p.kind == PouKind::Program && p.name.to_ascii_uppercase() == key)?;
        let Storage::Frame(o) = pou.vars.get(hidden)?.storage else {
            return None;
        };
        Some(StartCall {
            code: fb.codes[v],
            base: inst.base,
            retains: inst.base + o,
        })
    }
}

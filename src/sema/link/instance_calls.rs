//! Where the runtime finds the `FB_init` and `FB_exit` calls it makes
//! outside the cycles: the hidden function of the global lists and the
//! hidden method of each program instance (`src/sema/instance_calls/`).

use super::Linker;
use crate::ir::image::{CopyCalls, InstanceCall, ProgramInstance};
use crate::sema::instance_calls::{EXIT, INIT, Phase};
use crate::sema::model::Storage;
use crate::syntax::ast::PouKind;

/// The key of the method an online change calls after copying an instance.
const REINIT: &str = "FB_REINIT";

impl Linker<'_> {
    /// The calls of `phase`: at start the global lists' first, then each
    /// program instance's in execution order; at exit the reverse.
    pub(super) fn instance_calls(
        &self,
        instances: &[ProgramInstance],
        phase: Phase,
    ) -> Vec<InstanceCall> {
        let mut out: Vec<InstanceCall> = instances
            .iter()
            .filter_map(|inst| self.program_call(inst, phase))
            .collect();
        let globals = phase.globals.to_ascii_uppercase();
        let function = self
            .model
            .pous
            .iter()
            .find(|p| p.kind == PouKind::Function && p.name.to_ascii_uppercase() == globals);
        let flag = phase.flag.to_ascii_uppercase();
        let global_call = function.and_then(|f| match f.vars.get(&flag)?.storage {
            Storage::Frame(o) => {
                let base = self.out.codes[f.code.index()].frame;
                Some(InstanceCall {
                    code: f.code,
                    base,
                    flag: base + o,
                })
            }
            _ => None,
        });
        if phase == INIT {
            out.splice(0..0, global_call);
        } else {
            out.reverse();
            out.extend(global_call);
        }
        out
    }

    /// The `FB_exit` and `FB_reinit` of every user FB that has one of them
    /// (its own or inherited), for the instances an online change copies.
    pub(super) fn copy_calls(&self) -> Vec<CopyCalls> {
        let mut out = Vec::new();
        for pou in self.model.pous.iter() {
            if pou.kind != PouKind::FunctionBlock {
                continue;
            }
            let Some(fb) = self.model.oop.fbs.get(&pou.name.to_ascii_uppercase()) else {
                continue;
            };
            let exit = fb.dispatch.get(EXIT.key).and_then(|&v| {
                let hidden = &fb.versions[v].params.first()?.hidden;
                match pou.vars.get(hidden)?.storage {
                    Storage::Frame(o) => Some((fb.codes[v], o)),
                    _ => None,
                }
            });
            let reinit = fb.dispatch.get(REINIT).map(|&v| fb.codes[v]);
            if exit.is_some() || reinit.is_some() {
                out.push(CopyCalls {
                    ty: pou.ty,
                    exit,
                    reinit,
                });
            }
        }
        out
    }

    /// The call of a program instance whose PROGRAM has the phase's hidden
    /// method.
    fn program_call(&self, inst: &ProgramInstance, phase: Phase) -> Option<InstanceCall> {
        let key = inst.type_name.to_ascii_uppercase();
        let fb = self.model.oop.fbs.get(&key)?;
        let v = *fb.dispatch.get(&phase.members.to_ascii_uppercase())?;
        let hidden = &fb.versions[v].params.first()?.hidden;
        let pou = self
            .model
            .pous
            .iter()
            .find(|p| p.kind == PouKind::Program && p.name.to_ascii_uppercase() == key)?;
        let Storage::Frame(o) = pou.vars.get(hidden)?.storage else {
            return None;
        };
        Some(InstanceCall {
            code: fb.codes[v],
            base: inst.base,
            flag: inst.base + o,
        })
    }
}

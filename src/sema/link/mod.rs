//! The link stage: after every body is emitted, places function frames
//! and program instances in memory, writes initial values, relocates
//! function-frame addresses, checks for recursion, builds the tasks and
//! the [`Image`]. Reads the declarations; consumes the output tables.

mod auto_address;
mod call_depth;
mod config_elements;
mod cycle_depth;
mod init;
mod instance_calls;
mod located_overlap;
mod oop_resets;
mod recursion;
mod retained;
mod schedule;
mod var_config;

use super::CompileOptions;
use super::decl_consts::DeclConsts;
use super::declare::Declared;
use super::instance_calls::{EXIT, INIT};
use super::model::{Model, Storage};
use super::program::Program;
use crate::diagnostics::Diagnostics;
use crate::ir::image::{Image, ProgramInstance, RootVar};
use crate::ir::op::{Op, Slot, StrConstIdx};
use crate::ir::type_table::{MemberKind, TypeId, TypeTable};
use crate::ir::verify::VerifiedImage;
use crate::source::Span;
use crate::syntax::ast::{CompilationUnit, PouKind};
use std::collections::HashSet;

/// Links the declared and emitted program (or, after errors, only reports
/// call cycles and configuration problems).
///
/// Also returns the methods a cycle of calls reaches that were compiled
/// without a re-entry guard (`guarded` names those that have one): the
/// program must be compiled again with them guarded (`link::recursion`).
pub(super) fn link(
    units: &[CompilationUnit],
    declared: Declared,
    options: &CompileOptions,
    guarded: &HashSet<String>,
    diags: &mut Diagnostics,
) -> (Option<VerifiedImage>, HashSet<String>) {
    let frame_abs = vec![0; declared.model.pous.len()];
    let mut linker = Linker {
        units,
        diags,
        model: &declared.model,
        types: &declared.types,
        out: declared.out,
        frame_abs,
        guarded,
        guard_request: HashSet::new(),
    };
    let image = linker.link(options);
    (image, linker.guard_request)
}

/// State of the link stage.
pub(super) struct Linker<'a> {
    /// The parsed files (for configurations).
    pub(super) units: &'a [CompilationUnit],
    /// Where errors go.
    pub(super) diags: &'a mut Diagnostics,
    /// The declarations (read-only).
    pub(super) model: &'a Model,
    /// All types.
    pub(super) types: &'a TypeTable,
    /// The output tables, completed here.
    pub(super) out: Program,
    /// Absolute address of each function's static frame.
    pub(super) frame_abs: Vec<u32>,
    /// Methods (`ORIGIN.METHOD`) compiled with a re-entry guard.
    pub(super) guarded: &'a HashSet<String>,
    /// Methods in a cycle of calls that need one (`recursion`).
    pub(super) guard_request: HashSet<String>,
}

/// A program instance chosen to run: (instance name, POU, task, connections).
pub(super) type Scheduled = (String, usize, usize, Vec<Connection>);

/// One connection of a program instance's parameter to a global (or a
/// constant, held in a slot of its own).
pub(super) struct Connection {
    /// Copy the global into the program before it runs (VAR_INPUT), or the
    /// program's output into the global after it ran (VAR_OUTPUT).
    pub(super) input: bool,
    /// Slot offset of the parameter in the program instance.
    pub(super) offset: u32,
    /// Absolute address of the global or constant.
    pub(super) global: u32,
}

/// Slots and strings a code block resets on entry: `(slot, value)` and
/// `(slot, constant string)`.
pub(super) type EntryResets = (Vec<(Slot, u64)>, Vec<(Slot, StrConstIdx)>);

impl Linker<'_> {
    /// The folder of declaration constants (for constant connections).
    pub(super) fn consts(&mut self) -> DeclConsts<'_> {
        DeclConsts {
            types: self.types,
            model: self.model,
            diags: self.diags,
            same_block: &[],
            globals_at_start: true,
        }
    }

    /// Places everything in memory and builds the image.
    pub(super) fn link(&mut self, options: &CompileOptions) -> Option<VerifiedImage> {
        if self.diags.has_errors() {
            // Still report call cycles and configuration problems, but do
            // not build memory for a program that cannot run.
            self.check_recursion();
            self.schedule(options);
            self.warn_overlapping_addresses(options.addressing);
            return None;
        }
        self.place_function_frames();
        self.set_entry_resets();
        self.fill_oop_offsets();
        self.relocate_frame_addresses();
        self.check_recursion();
        if !self.diags.has_errors() {
            self.check_call_depth();
        }
        self.initialise_globals();
        let scheduled = self.schedule(options);
        // After scheduling: program connections to direct addresses are
        // located too.
        self.warn_overlapping_addresses(options.addressing);
        let (tasks, programs) = scheduled?;
        let instances = self.instantiate_programs(programs);
        let mut roots = self.root_vars(&instances)?;
        let configured = self.apply_var_config(
            options.program.is_none(),
            &instances,
            &roots,
            options.addressing,
        );
        roots.extend(configured);
        let retained = self.retained_vars(&instances);
        let start = self.instance_calls(&instances, INIT);
        let exit = self.instance_calls(&instances, EXIT);
        let copy_calls = self.copy_calls();
        if !options.unoptimized {
            for c in &mut self.out.codes {
                crate::ir::fuse::fuse_loops(&mut c.ops);
            }
        }
        let image = Image {
            codes: std::mem::take(&mut self.out.codes),
            consts: std::mem::take(&mut self.out.consts).into_iter().collect(),
            str_consts: std::mem::take(&mut self.out.str_consts)
                .into_iter()
                .collect(),
            arrays: std::mem::take(&mut self.out.arrays),
            memory: std::mem::take(&mut self.out.memory),
            strings: std::mem::take(&mut self.out.strings),
            types: self.types.clone(),
            scalar_types: std::mem::take(&mut self.out.scalar_types)
                .into_iter()
                .collect(),
            byte_layouts: std::mem::take(&mut self.out.byte_layouts)
                .into_values()
                .collect(),
            globals: roots,
            programs: instances,
            tasks,
            charts: std::mem::take(&mut self.out.charts),
            hosts: options.host_pous.clone(),
            retained,
            start,
            exit,
            copy_calls,
            names: Default::default(),
        };
        if self.diags.has_errors() {
            return None;
        }
        match crate::ir::verify::verify(image) {
            Ok(verified) => Some(verified),
            Err(e) => {
                self.diags.error(
                    "E999",
                    Span::default(),
                    format!(
                        "internal compiler error: the generated code failed verification ({e})"
                    ),
                );
                None
            }
        }
    }

    /// Gives every emitted function its static frame, initialised.
    fn place_function_frames(&mut self) {
        for p in 0..self.model.pous.len() {
            if self.model.pous[p].kind != PouKind::Function || !self.model.emitted[p] {
                continue;
            }
            let code = self.model.pous[p].code.index();
            let size = self.out.codes[code].frame_size.max(1);
            let at = self.out.alloc_abs(self.diags, size);
            self.frame_abs[p] = at;
            self.out.codes[code].frame = at;
            let ty = self.model.pous[p].ty;
            self.instantiate(at, ty, None);
        }
    }

    /// What each code block resets on entry.
    fn set_entry_resets(&mut self) {
        for p in 0..self.model.pous.len() {
            if !self.model.emitted[p] {
                continue;
            }
            let (init, strings) = self.entry_resets(p);
            let code = self.model.pous[p].code.index();
            self.out.codes[code].entry_init = init;
            self.out.codes[code].entry_strings = strings;
        }
        self.set_method_resets();
    }

    /// Adds the callee's frame address to instructions addressing a
    /// function's frame.
    fn relocate_frame_addresses(&mut self) {
        for (code, at, callee) in std::mem::take(&mut self.out.fixups) {
            let base = self.frame_abs[callee];
            match &mut self.out.codes[code.index()].ops[at] {
                Op::StoreAbs { abs, .. } | Op::LoadAbs { abs, .. } => *abs += base,
                Op::LoadI { imm, .. } => *imm += base as i32,
                _ => {}
            }
        }
    }

    /// Initial values of globals, of located variables of programs and of
    /// every POU's VAR_STAT variables.
    fn initialise_globals(&mut self) {
        let statics: Vec<_> = self
            .model
            .pous
            .iter()
            .flat_map(|p| p.vars.values())
            .filter(|v| v.kind == MemberKind::Local && v.location.is_none())
            .filter_map(|v| match v.storage {
                Storage::Abs(a) => Some((a, v.ty, v.init.clone())),
                _ => None,
            })
            .collect();
        for (a, ty, init) in statics {
            self.instantiate(a, ty, init.as_ref());
        }
        let globals: Vec<_> = self.model.globals.values().cloned().collect();
        for g in &globals {
            if let Storage::Abs(a) = g.storage {
                self.instantiate(a, g.ty, g.init.as_ref());
            }
        }
        for p in 0..self.model.pous.len() {
            if self.model.pous[p].kind != PouKind::Program {
                continue;
            }
            let vars: Vec<_> = self.model.pous[p].vars.values().cloned().collect();
            for v in vars {
                if let (Storage::Abs(a), Some(_), Some(init)) = (v.storage, &v.location, &v.init) {
                    self.instantiate(a, v.ty, Some(init));
                }
            }
        }
    }

    /// Places and initialises each scheduled program instance.
    fn instantiate_programs(&mut self, programs: Vec<Scheduled>) -> Vec<ProgramInstance> {
        let mut instances = Vec::new();
        for (name, p, task, conns) in programs {
            let ty = self.model.pous[p].ty;
            let size = self.types.size(ty).max(1);
            let base = self.out.alloc_abs(self.diags, size);
            self.instantiate(base, ty, None);
            let (mut inputs, mut outputs) = (Vec::new(), Vec::new());
            for c in conns {
                if c.input {
                    inputs.push((c.global, base + c.offset));
                } else {
                    outputs.push((base + c.offset, c.global));
                }
            }
            instances.push(ProgramInstance {
                name,
                type_name: self.model.pous[p].name.clone(),
                code: self.model.pous[p].code,
                base,
                ty,
                task,
                inputs,
                outputs,
            });
        }
        instances
    }

    /// The variables visible from outside: globals, located addresses,
    /// and located variables of the program instances (named by them).
    fn root_vars(&self, instances: &[ProgramInstance]) -> Option<Vec<RootVar>> {
        let mut roots: Vec<RootVar> = self
            .model
            .globals
            .values()
            .filter_map(|g| match g.storage {
                Storage::Abs(a) => Some(RootVar {
                    name: g.name.clone(),
                    ty: g.ty,
                    addr: a,
                    kind: MemberKind::Local,
                    location: g.location.clone(),
                    constant: g.constant,
                }),
                _ => None,
            })
            .collect();
        let mut located: Vec<(&String, &(u32, TypeId))> = self.out.located.iter().collect();
        located.sort_by_key(|(_, (a, _))| *a);
        for (text, (addr, ty)) in located {
            if !roots.iter().any(|r| r.addr == *addr) {
                roots.push(RootVar {
                    name: text.clone(),
                    ty: *ty,
                    addr: *addr,
                    kind: MemberKind::Local,
                    location: Some(text.clone()),
                    constant: false,
                });
            }
        }
        // Located variables declared inside programs are named by the program.
        for inst in instances {
            let p = self.model.pous.iter().position(|x| x.code == inst.code)?;
            for v in self.model.pous[p].vars.values() {
                if let (Storage::Abs(a), Some(loc)) = (v.storage, &v.location) {
                    roots.push(RootVar {
                        name: v.name.clone(),
                        ty: v.ty,
                        addr: a,
                        kind: v.kind,
                        location: Some(loc.clone()),
                        constant: v.constant,
                    });
                }
            }
        }
        Some(roots)
    }
}

//! The link stage: after every body is emitted, places function frames
//! and program instances in memory, writes initial values, relocates
//! function-frame addresses, checks for recursion, builds the tasks and
//! the [`Image`]. Reads the declarations; consumes the output tables.

use super::CompileOptions;
use super::decl_consts::DeclConsts;
use super::declare::Declared;
use super::model::{ConstInit, Model, Storage};
use super::program::Program;
use crate::diagnostics::Diagnostics;
use crate::ir::image::{Image, ProgramInstance, RootVar, StringInit, Task};
use crate::ir::op::Op;
use crate::ir::types::{MemberKind, TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::ProgramInstance as ProgramDecl;
use crate::syntax::ast::{
    CompilationUnit, Configuration, ExprKind, Item, LiteralValue, PouKind, TaskDecl,
};
use crate::types::ElemType;

/// Links the declared and emitted program (or, after errors, only reports
/// call cycles and configuration problems).
pub(super) fn link(
    units: &[CompilationUnit],
    declared: Declared,
    options: &CompileOptions,
    diags: &mut Diagnostics,
) -> Option<Image> {
    let frame_abs = vec![0; declared.model.pous.len()];
    let mut linker = Linker {
        units,
        diags,
        model: &declared.model,
        types: &declared.types,
        out: declared.out,
        frame_abs,
    };
    linker.link(options)
}

/// State of the link stage.
struct Linker<'a> {
    /// The parsed files (for configurations).
    units: &'a [CompilationUnit],
    /// Where errors go.
    diags: &'a mut Diagnostics,
    /// The declarations (read-only).
    model: &'a Model,
    /// All types.
    types: &'a TypeTable,
    /// The output tables, completed here.
    out: Program,
    /// Absolute address of each function's static frame.
    frame_abs: Vec<u32>,
}

/// A program instance chosen to run: (instance name, POU, task, connections).
type Scheduled = (String, usize, usize, Vec<Connection>);

/// One connection of a program instance's parameter to a global (or a
/// constant, held in a slot of its own).
struct Connection {
    /// Copy the global into the program before it runs (VAR_INPUT), or the
    /// program's output into the global after it ran (VAR_OUTPUT).
    input: bool,
    /// Slot offset of the parameter in the program instance.
    offset: u32,
    /// Absolute address of the global or constant.
    global: u32,
}

/// Slots and strings a code block resets on entry: `(slot, value)` and
/// `(slot, constant string)`.
type EntryResets = (Vec<(u32, u64)>, Vec<(u32, u32)>);

impl Linker<'_> {
    /// The folder of declaration constants (for constant connections).
    fn consts(&mut self) -> DeclConsts<'_> {
        DeclConsts {
            types: self.types,
            model: self.model,
            diags: self.diags,
        }
    }

    /// Writes the initial value of a `ty` at `at` in `buf`, collecting string slots.
    fn write_init(
        &self,
        buf: &mut [u64],
        at: usize,
        ty: TypeId,
        init: Option<&ConstInit>,
        strs: &mut Vec<(usize, StringInit)>,
    ) {
        let default;
        let init = match init {
            Some(i) => Some(i),
            None => {
                default = self.model.type_inits.get(&ty).cloned();
                default.as_ref()
            }
        };
        match &self.types.get(ty).kind {
            TypeKind::Elem(_) | TypeKind::Enum { .. } | TypeKind::Subrange { .. } => {
                let Some(slot) = buf.get_mut(at) else { return };
                *slot = match init {
                    Some(ConstInit::Scalar(b)) => *b,
                    _ => match self.model.default_init(self.types, ty) {
                        ConstInit::Scalar(b) => b,
                        _ => 0,
                    },
                };
            }
            TypeKind::Str { max, wide } => {
                let text = match init {
                    Some(ConstInit::Str(s)) => s.clone(),
                    _ => String::new(),
                };
                strs.push((
                    at,
                    StringInit {
                        max: *max,
                        wide: *wide,
                        init: text,
                    },
                ));
            }
            TypeKind::Array { dims, elem } => {
                let n: u64 = dims.iter().map(|d| d.len()).product();
                let stride = self.types.size(*elem) as usize;
                let items = match init {
                    Some(ConstInit::Array(v)) => v.as_slice(),
                    _ => &[],
                };
                for k in 0..n as usize {
                    self.write_init(buf, at + k * stride, *elem, items.get(k), strs);
                }
            }
            TypeKind::Struct { fields } => {
                let overrides = match init {
                    Some(ConstInit::Struct(v)) => v.as_slice(),
                    _ => &[],
                };
                let type_defaults = match self.model.type_inits.get(&ty) {
                    Some(ConstInit::Struct(v)) => v.clone(),
                    _ => Vec::new(),
                };
                for (k, m) in fields.iter().enumerate() {
                    let fi = overrides
                        .iter()
                        .find(|(i, _)| *i == k)
                        .or_else(|| type_defaults.iter().find(|(i, _)| *i == k))
                        .map(|(_, c)| c);
                    self.write_init(buf, at + m.offset as usize, m.ty, fi, strs);
                }
            }
            TypeKind::NativeFb(fb) => {
                for (k, p) in crate::stdlib::interface(*fb).iter().enumerate() {
                    if let Some(slot) = buf.get_mut(at + k) {
                        *slot = p.init;
                    }
                }
            }
            TypeKind::Pou { code, .. } => {
                let Some(p) = self.model.pous.iter().position(|p| p.code == *code) else {
                    return;
                };
                for var in self.model.pous[p].vars.values() {
                    if let Storage::Frame(o) = var.storage {
                        self.write_init(buf, at + o as usize, var.ty, var.init.as_ref(), strs);
                    }
                }
                for &(slot, value) in &self.model.pous[p].consts {
                    if let Some(s) = buf.get_mut(at + slot as usize) {
                        *s = value;
                    }
                }
            }
            TypeKind::Step | TypeKind::Void | TypeKind::Error => {}
        }
    }

    /// Writes initial values into absolute memory and allocates string ids.
    fn instantiate(&mut self, addr: u32, ty: TypeId, init: Option<&ConstInit>) {
        let mut strs = Vec::new();
        let mut buf = std::mem::take(&mut self.out.memory);
        self.write_init(&mut buf, addr as usize, ty, init, &mut strs);
        for (slot, s) in strs {
            if let Some(s) = buf.get_mut(slot) {
                *s = self.out.strings.len() as u64;
            }
            self.out.strings.push(s);
        }
        self.out.memory = buf;
    }

    /// Entry resets of a POU's VAR_TEMP (FBs, programs) or of all its
    /// non-input variables (functions).
    fn entry_resets(&mut self, p: usize) -> EntryResets {
        let kind = self.model.pous[p].kind;
        let size = self.model.pous[p].vars_size as usize;
        let mut buf = vec![0u64; size];
        let mut strs = Vec::new();
        let mut slots = Vec::new();
        let vars: Vec<_> = self.model.pous[p].vars.values().cloned().collect();
        for var in vars {
            let reset = match kind {
                PouKind::Function => !matches!(var.kind, MemberKind::Input | MemberKind::InOut),
                _ => var.kind == MemberKind::Temp,
            };
            let Storage::Frame(o) = var.storage else {
                continue;
            };
            if !reset {
                continue;
            }
            let before = strs.len();
            self.write_init(&mut buf, o as usize, var.ty, var.init.as_ref(), &mut strs);
            let n = self.types.size(var.ty) as usize;
            let string_slots: Vec<usize> = strs[before..].iter().map(|(s, _)| *s).collect();
            for (k, value) in buf.iter().enumerate().skip(o as usize).take(n) {
                if !string_slots.contains(&k) {
                    slots.push((k as u32, *value));
                }
            }
        }
        let strings = strs
            .into_iter()
            .map(|(slot, s)| (slot as u32, self.out.str_const(&s.init)))
            .collect();
        (slots, strings)
    }

    /// Places everything in memory and builds the image.
    pub(super) fn link(&mut self, options: &CompileOptions) -> Option<Image> {
        if self.diags.has_errors() {
            // Still report call cycles and configuration problems, but do
            // not build memory for a program that cannot run.
            self.check_recursion();
            self.schedule(options);
            return None;
        }
        self.place_function_frames();
        self.set_entry_resets();
        self.relocate_frame_addresses();
        self.check_recursion();
        self.initialise_globals();
        let (tasks, programs) = self.schedule(options)?;
        let instances = self.instantiate_programs(programs);
        let roots = self.root_vars(&instances)?;
        for c in &mut self.out.codes {
            crate::ir::fuse::fuse_loops(&mut c.ops);
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
            globals: roots,
            programs: instances,
            tasks,
            charts: std::mem::take(&mut self.out.charts),
        };
        if self.diags.has_errors() {
            return None;
        }
        if let Err(e) = crate::ir::verify::verify(&image) {
            self.diags.error(
                "E999",
                Span::default(),
                format!("internal compiler error: the generated code failed verification ({e})"),
            );
            return None;
        }
        Some(image)
    }

    /// Gives every emitted function its static frame, initialised.
    fn place_function_frames(&mut self) {
        for p in 0..self.model.pous.len() {
            if self.model.pous[p].kind != PouKind::Function || !self.model.emitted[p] {
                continue;
            }
            let code = self.model.pous[p].code as usize;
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
            let code = self.model.pous[p].code as usize;
            self.out.codes[code].entry_init = init;
            self.out.codes[code].entry_strings = strings;
        }
    }

    /// Adds the callee's frame address to instructions addressing a
    /// function's frame.
    fn relocate_frame_addresses(&mut self) {
        for (code, at, callee) in std::mem::take(&mut self.out.fixups) {
            let base = self.frame_abs[callee];
            match &mut self.out.codes[code as usize].ops[at] {
                Op::StoreAbs { abs, .. } | Op::LoadAbs { abs, .. } => *abs += base,
                Op::LoadI { imm, .. } => *imm += base as i32,
                _ => {}
            }
        }
    }

    /// Initial values of globals and of located variables of programs.
    fn initialise_globals(&mut self) {
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
                    });
                }
            }
        }
        Some(roots)
    }

    /// Reports calls that form a cycle (IEC forbids recursion).
    fn check_recursion(&mut self) {
        let n = self.out.codes.len();
        let mut adj: Vec<Vec<(u32, Span)>> = vec![Vec::new(); n];
        for &(a, b, s) in &self.out.calls {
            if (a as usize) < n {
                adj[a as usize].push((b, s));
            }
        }
        // 0 = unvisited, 1 = on stack, 2 = done
        let mut state = vec![0u8; n];
        let mut reported = false;
        for start in 0..n {
            if state[start] != 0 {
                continue;
            }
            let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
            state[start] = 1;
            while let Some(&mut (node, ref mut next)) = stack.last_mut() {
                if *next < adj[node].len() {
                    let (to, span) = adj[node][*next];
                    *next += 1;
                    match state[to as usize] {
                        0 => {
                            state[to as usize] = 1;
                            stack.push((to as usize, 0));
                        }
                        1 if !reported => {
                            reported = true;
                            let name = self.out.codes[to as usize].name.clone();
                            self.diags.error(
                                "E409",
                                span,
                                format!(
                                    "recursive call of `{name}`: IEC 61131-3 forbids recursion"
                                ),
                            );
                        }
                        _ => {}
                    }
                } else {
                    state[node] = 2;
                    stack.pop();
                }
            }
        }
    }

    /// Tasks and the program instances to run: (instance name, POU, task index).
    #[allow(clippy::type_complexity)]
    fn schedule(&mut self, options: &CompileOptions) -> Option<(Vec<Task>, Vec<Scheduled>)> {
        let implicit = Task {
            name: "default".into(),
            interval: options.cycle_time,
            priority: 0,
            single: None,
        };
        let configs: Vec<&Configuration> = self
            .units
            .iter()
            .flat_map(|u| u.items.iter())
            .filter_map(|i| match i {
                Item::Configuration(c) => Some(c),
                _ => None,
            })
            .collect();
        if configs.len() > 1 {
            self.diags.error(
                "E701",
                configs[1].name.span,
                "only one CONFIGURATION can be run at a time",
            );
            return None;
        }
        if let Some(cfg) = configs
            .first()
            .copied()
            .filter(|_| options.program.is_none())
        {
            return Some(self.configured_schedule(cfg, options, implicit));
        }
        self.implicit_schedule(options, implicit)
    }

    /// The tasks and program instances of the CONFIGURATION (the implicit
    /// task added for instances without one).
    fn configured_schedule(
        &mut self,
        cfg: &Configuration,
        options: &CompileOptions,
        implicit: Task,
    ) -> (Vec<Task>, Vec<Scheduled>) {
        let mut tasks: Vec<Task> = Vec::new();
        for res in &cfg.resources {
            for t in &res.tasks {
                let task = self.configured_task(t);
                tasks.push(task);
            }
        }
        let mut progs = Vec::new();
        for res in &cfg.resources {
            for pi in &res.programs {
                if let Some(s) = self.configured_program(pi, &mut tasks, &progs, &implicit) {
                    progs.push(s);
                }
            }
        }
        if progs.is_empty() && !options.check_only {
            self.diags
                .error("E208", cfg.name.span, "the CONFIGURATION runs no PROGRAM");
        }
        (tasks, progs)
    }

    /// A TASK with its settings checked.
    fn configured_task(&mut self, t: &TaskDecl) -> Task {
        let mut task = Task {
            name: t.name.name.clone(),
            interval: 0,
            priority: 0,
            single: None,
        };
        for (k, v) in &t.settings {
            match (k.key().as_str(), &v.kind) {
                ("INTERVAL", ExprKind::Literal(l)) => match l.value {
                    LiteralValue::Duration { nanos, .. } if nanos > 0 => task.interval = nanos,
                    _ => self.diags.error(
                        "E702",
                        v.span,
                        "INTERVAL must be a positive duration literal",
                    ),
                },
                ("PRIORITY", ExprKind::Literal(l)) => match l.value {
                    LiteralValue::Int(n) if n >= 0 => task.priority = n as i64,
                    _ => {
                        self.diags
                            .error("E702", v.span, "PRIORITY must be a non-negative integer")
                    }
                },
                ("SINGLE", ExprKind::Name(id)) => match self.model.globals.get(&id.key()) {
                    Some(g) if self.types.scalar(g.ty) == Some(ElemType::Bool) => {
                        if let Storage::Abs(a) = g.storage {
                            task.single = Some(a);
                        }
                    }
                    _ => {
                        self.diags
                            .error("E702", v.span, "SINGLE must name a global BOOL variable")
                    }
                },
                _ => self.diags.error(
                    "E702",
                    k.span,
                    format!("unknown or invalid task setting `{}`", k.name),
                ),
            }
        }
        if task.interval == 0 && task.single.is_none() {
            self.diags.error(
                "E702",
                t.name.span,
                "a TASK needs an INTERVAL or a SINGLE trigger",
            );
        }
        task
    }

    /// A program instance of the CONFIGURATION: its PROGRAM, connections
    /// and task.
    fn configured_program(
        &mut self,
        pi: &ProgramDecl,
        tasks: &mut Vec<Task>,
        progs: &[Scheduled],
        implicit: &Task,
    ) -> Option<Scheduled> {
        let Some(&p) = self.model.pou_index.get(&pi.type_name.key()) else {
            self.diags.error(
                "E208",
                pi.type_name.span,
                format!("unknown PROGRAM `{}`", pi.type_name.name),
            );
            return None;
        };
        if self.model.pous[p].kind != PouKind::Program {
            self.diags.error(
                "E208",
                pi.type_name.span,
                format!("`{}` is not a PROGRAM", pi.type_name.name),
            );
            return None;
        }
        let conns: Vec<Connection> = pi
            .args
            .iter()
            .filter_map(|a| self.connection(p, a))
            .collect();
        let task = match &pi.task {
            Some(t) => match tasks
                .iter()
                .position(|x| x.name.eq_ignore_ascii_case(&t.name))
            {
                Some(i) => i,
                None => {
                    self.diags
                        .error("E702", t.span, format!("unknown TASK `{}`", t.name));
                    return None;
                }
            },
            None => {
                if !tasks.iter().any(|t| t.name == implicit.name) {
                    tasks.push(implicit.clone());
                }
                tasks
                    .iter()
                    .position(|t| t.name == implicit.name)
                    .unwrap_or(0)
            }
        };
        if progs
            .iter()
            .any(|(n, ..): &Scheduled| n.eq_ignore_ascii_case(&pi.name.name))
        {
            self.diags.error(
                "E202",
                pi.name.span,
                format!("program instance `{}` is declared twice", pi.name.name),
            );
            return None;
        }
        Some((pi.name.name.clone(), p, task, conns))
    }

    /// Without a CONFIGURATION (or with `--program`): the one PROGRAM (or
    /// the one named) on the implicit task.
    fn implicit_schedule(
        &mut self,
        options: &CompileOptions,
        implicit: Task,
    ) -> Option<(Vec<Task>, Vec<Scheduled>)> {
        let programs: Vec<usize> = (0..self.model.pous.len())
            .filter(|&p| self.model.pous[p].kind == PouKind::Program)
            .collect();
        let chosen = match &options.program {
            Some(name) => match programs
                .iter()
                .find(|&&p| self.model.pous[p].name.eq_ignore_ascii_case(name))
            {
                Some(&p) => Some(p),
                None => {
                    self.diags.error(
                        "E208",
                        Span::default(),
                        format!(
                            "no PROGRAM named `{name}` (use --program with one of: {})",
                            self.program_names(&programs)
                        ),
                    );
                    return None;
                }
            },
            None => match programs.len() {
                1 => Some(programs[0]),
                0 => None,
                _ => None,
            },
        };
        match chosen {
            Some(p) => Some((
                vec![implicit],
                vec![(self.model.pous[p].name.clone(), p, 0, Vec::new())],
            )),
            None if options.check_only => Some((vec![implicit], Vec::new())),
            // After other errors the missing PROGRAM is usually their
            // consequence (a POU dropped by syntax recovery): say nothing.
            None if self.diags.has_errors() => None,
            None => {
                let span = self
                    .units
                    .iter()
                    .flat_map(|u| u.items.first())
                    .next()
                    .map(item_span)
                    .unwrap_or_default();
                if programs.is_empty() {
                    self.diags.error("E208", span, "there is no PROGRAM to run");
                } else {
                    self.diags.error(
                        "E208",
                        span,
                        format!(
                            "several PROGRAMs ({}): choose one with --program",
                            self.program_names(&programs)
                        ),
                    );
                }
                None
            }
        }
    }

    /// Checks one `x := global`, `x := constant` or `y => global` argument
    /// of a program instance in a configuration.
    fn connection(&mut self, p: usize, arg: &crate::syntax::ast::Arg) -> Option<Connection> {
        use crate::syntax::ast::Arg;
        let (name, expr, input) = match arg {
            Arg::Input { name, value } => (name, value, true),
            Arg::Output {
                name,
                negated: false,
                target,
            } => (name, target, false),
            Arg::Output { name, .. } => {
                self.diags.error(
                    "E703",
                    name.span,
                    "`NOT ... =>` cannot connect a program output",
                );
                return None;
            }
            Arg::Positional(e) => {
                self.diags.error(
                    "E703",
                    e.span,
                    "program parameters are connected by name: `PROGRAM p WITH t : P(x := g)`",
                );
                return None;
            }
        };
        let program = self.model.pous[p].name.clone();
        let wanted = if input {
            MemberKind::Input
        } else {
            MemberKind::Output
        };
        let Some(var) = self.model.pous[p]
            .vars
            .get(&name.key())
            .filter(|v| v.kind == wanted)
            .cloned()
        else {
            let what = if input { "VAR_INPUT" } else { "VAR_OUTPUT" };
            self.diags.error(
                "E703",
                name.span,
                format!("PROGRAM {program} has no {what} `{}`", name.name),
            );
            return None;
        };
        let Storage::Frame(offset) = var.storage else {
            return None;
        };
        let Some(elem) = self.types.scalar(var.ty).filter(|e| !e.is_string()) else {
            self.diags.error(
                "E703",
                name.span,
                format!(
                    "only elementary parameters (not {}) can be connected",
                    self.types.name(var.ty)
                ),
            );
            return None;
        };
        // The other side: a global of the same type, or (for inputs) a constant.
        if let ExprKind::Name(g) = &expr.kind
            && let Some(global) = self.model.globals.get(&g.key()).cloned()
        {
            let Storage::Abs(addr) = global.storage else {
                return None;
            };
            if global.ty != var.ty && self.types.scalar(global.ty) != Some(elem) {
                self.diags.error(
                    "E703",
                    expr.span,
                    format!(
                        "`{}` is {} but `{}` is {}: connections need the same type",
                        g.name,
                        self.types.name(global.ty),
                        name.name,
                        self.types.name(var.ty)
                    ),
                );
                return None;
            }
            if !input && global.constant {
                self.diags.error(
                    "E401",
                    expr.span,
                    format!("global `{}` is CONSTANT", g.name),
                );
                return None;
            }
            return Some(Connection {
                input,
                offset,
                global: addr,
            });
        }
        if input
            && let Some(crate::sema::consts::Const::Bits(bits)) =
                self.consts().const_value(expr, var.ty, None)
        {
            let addr = self.out.alloc_abs(self.diags, 1);
            if let Some(slot) = self.out.memory.get_mut(addr as usize) {
                *slot = bits;
            }
            return Some(Connection {
                input,
                offset,
                global: addr,
            });
        }
        if !input {
            self.diags.error(
                "E703",
                expr.span,
                "a program output connects to a VAR_GLOBAL variable",
            );
        }
        None
    }

    fn program_names(&self, programs: &[usize]) -> String {
        programs
            .iter()
            .map(|&p| self.model.pous[p].name.clone())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

fn item_span(i: &Item) -> Span {
    match i {
        Item::Pou(p) => p.name.span,
        Item::Types(t) => t.first().map(|d| d.name.span).unwrap_or_default(),
        Item::Configuration(c) => c.name.span,
        Item::Globals(b) => b.span,
    }
}

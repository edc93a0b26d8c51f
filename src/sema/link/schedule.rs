//! Tasks and program instances: from the CONFIGURATION (tasks, program
//! instances, connections to globals) or the one PROGRAM on the implicit
//! task.

use super::{Connection, Linker, Scheduled};
use crate::elementary::ElemType;
use crate::ir::image::Task;
use crate::ir::type_table::MemberKind;
use crate::sema::CompileOptions;
use crate::sema::model::Storage;
use crate::source::Span;
use crate::syntax::ast::ProgramInstance as ProgramDecl;
use crate::syntax::ast::{Configuration, ExprKind, Item, LiteralValue, PouKind, TaskDecl};

impl Linker<'_> {
    /// Tasks and the program instances to run: (instance name, POU, task index).
    #[allow(clippy::type_complexity)]
    pub(super) fn schedule(
        &mut self,
        options: &CompileOptions,
    ) -> Option<(Vec<Task>, Vec<Scheduled>)> {
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
        if let ExprKind::Direct(a) = &expr.kind {
            return self.direct_connection(a, input, offset, var.ty);
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
                "a program output connects to a VAR_GLOBAL variable or a %Q or %M address",
            );
        }
        None
    }

    /// `x := %IX0.0` or `y => %QX0.1`: the parameter is connected to the
    /// located slot of the address (the one every other use of the address
    /// shares), which the process image fills and reads like any located
    /// variable. The address must fit the parameter's type (E207); an
    /// output cannot go to a `%I` input.
    fn direct_connection(
        &mut self,
        a: &crate::syntax::ast::DirectAddress,
        input: bool,
        offset: u32,
        ty: crate::ir::type_table::TypeId,
    ) -> Option<Connection> {
        let key = crate::sema::declare::normalize_address(a);
        if !input && key.starts_with("%I") {
            self.diags.error(
                "E703",
                a.span,
                format!(
                    "a program output cannot go to the input address `{}`: connect it to a %Q or %M address or a VAR_GLOBAL",
                    a.text
                ),
            );
            return None;
        }
        let global = self.out.located_slot(self.types, self.diags, a, ty)?;
        Some(Connection {
            input,
            offset,
            global,
        })
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
        Item::Interface(x) => x.name.span,
    }
}

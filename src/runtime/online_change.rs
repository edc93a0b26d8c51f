//! Online change: a new version of the program takes over a running PLC
//! between two cycles, keeping the state of everything that did not change.
//!
//! The new version is compiled on its own (its memory holds its initial
//! values), then the old state is carried into it, walking both versions'
//! variables by path:
//!
//! - a variable whose path and type are the same in both keeps its value:
//!   scalars slot by slot, strings by content (a slot holds a string's id,
//!   which may differ), arrays element by element (same bounds and element
//!   type), standard FB instances with their hidden state (a TON keeps its
//!   start time, so it keeps timing; an R_TRIG keeps its memory);
//! - a structure or FB instance of the same type name whose definition
//!   changed is walked member by member, so its unchanged members keep
//!   their values;
//! - a path that is new keeps its initial value, one that is gone is
//!   dropped, one whose type changed is re-initialised;
//! - an SFC chart keeps its state (active steps, step times, action
//!   control) when its shape is the same: the same steps in the same order
//!   with the same action associations, the same transitions between the
//!   same steps, the same actions. Conditions and action bodies may
//!   change. Otherwise the chart starts again at its initial steps.
//!
//! VAR_TEMP (reset at each call), VAR_IN_OUT (bound at each call) and
//! VAR_EXTERNAL (the global is carried by its own name) are not carried.
//! The clock and the cycle counter continue. Tasks cannot change: the
//! change is refused (restart to change the schedule).

use super::change_report::{ChangeReport, OnlineChangeError, Retyped};
use super::engine::{Options, Plc};
use super::forcing::Forces;
use super::process_image::ProcessImage;
use crate::ir::chart::{Chart, action_layout, header};
use crate::ir::image::{Image, Task};
use crate::ir::op::Op;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind, step_layout};
use crate::vm::Machine;

impl Plc {
    /// Replaces the running program by `new` between two cycles, carrying
    /// over the state of every variable whose path and type did not change
    /// (see `docs/runtime.md`, "Online change"). On error nothing changes.
    ///
    /// The clock and the cycle counter continue; warnings and sources
    /// become the new version's. Variable handles ([`crate::VarRef`])
    /// resolved before the change are refused afterwards: resolve them
    /// again, since addresses move.
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// let v1 = "PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM";
    /// let v2 = "PROGRAM P VAR n : INT; m : INT := 7; END_VAR n := n + 10; END_PROGRAM";
    /// let mut plc = Plc::compile_files(&[("p.st", v1)], &Options::default())?;
    /// plc.run_cycle()?;
    /// plc.run_cycle()?;
    /// let new = Plc::compile_files(&[("p.st", v2)], &Options::default())?;
    /// let report = plc.online_change(new)?;
    /// assert_eq!(report.kept, ["P.n"]);
    /// assert_eq!(report.initialised, ["P.m"]);
    /// plc.run_cycle()?;
    /// assert_eq!(plc.read("P.n")?.to_literal(), "12");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn online_change(&mut self, mut new: Plc) -> Result<ChangeReport, OnlineChangeError> {
        check_tasks(&self.image.tasks, &new.image.tasks)?;
        if self.scheduler.base_tick() != new.scheduler.base_tick() {
            return Err(OnlineChangeError::CycleTimeChanged {
                old: self.scheduler.base_tick(),
                new: new.scheduler.base_tick(),
            });
        }
        let forces = self.forces.rebind(&new).map_err(|(path, error)| {
            OnlineChangeError::ForceDoesNotFit {
                path,
                error: Box::new(error),
            }
        })?;
        let (report, host_moves, copied) = self.carry_into(&mut new);
        // Copied instances get FB_exit(bInCopyCode := TRUE) before the
        // copy, which then carries what it wrote.
        let exited = self.exit_copied(&copied).map_err(fault)?;
        let (report, host_moves, copied) = if exited {
            self.carry_into(&mut new)
        } else {
            (report, host_moves, copied)
        };
        if let (Some(old), Some(code)) = (&self.host_code, &new.host_code) {
            let mut old = old.lock().unwrap_or_else(|p| p.into_inner());
            let mut code = code.lock().unwrap_or_else(|p| p.into_inner());
            code.adopt(&mut old, &host_moves);
        }
        new.machine.now = self.machine.now;
        new.scheduler.carry_over(&self.scheduler);
        self.take_over(new, forces);
        self.reinit_copied(&copied).map_err(fault)?;
        Ok(report)
    }

    /// Carries the running state into `new`: the report, the host
    /// blocks' moves and the instances copied into a changed layout.
    fn carry_into(&self, new: &mut Plc) -> (ChangeReport, HostMoves, Vec<Copied>) {
        let mut carry = Carry {
            old: &self.image,
            old_m: &self.machine,
            new: &new.image,
            new_m: &mut new.machine,
            entries: Vec::new(),
            host_moves: Vec::new(),
            copied: Vec::new(),
        };
        carry.programs();
        carry.globals();
        let host_moves = std::mem::take(&mut carry.host_moves);
        let copied = std::mem::take(&mut carry.copied);
        let mut report = carry.report();
        report.copied = copied.iter().map(|c| c.path.clone()).collect();
        (report, host_moves, copied)
    }

    /// Compiles `files` with `options` and applies them with
    /// [`Plc::online_change`]. Sources that do not compile are refused
    /// with their diagnostics ([`OnlineChangeError::Compile`]) and the
    /// running program goes on unchanged.
    pub fn online_change_files(
        &mut self,
        files: &[(&str, &str)],
        options: &Options,
    ) -> Result<ChangeReport, OnlineChangeError> {
        let new = Plc::compile_files(files, options)?;
        self.online_change(new)
    }
}

impl Plc {
    /// Makes `new` (whose memory already holds the carried state) the
    /// running program. The cycle counter, the clock, the stop handle and
    /// the watchdog (the tasks are the same) stay, and so does the
    /// machine's interrupt word, which stop handles already given out and
    /// the watchdog thread hold; the process image is rebuilt for the new
    /// located variables under the new version's addressing convention,
    /// the forces are `forces` (rebound to the new version).
    fn take_over(&mut self, mut new: Plc, forces: Forces) {
        std::mem::swap(&mut self.image, &mut new.image);
        std::mem::swap(&mut self.machine.mem, &mut new.machine.mem);
        std::mem::swap(&mut self.machine.strings, &mut new.machine.strings);
        std::mem::swap(&mut self.machine.host, &mut new.machine.host);
        // References are not carried (they start NULL): the objects the
        // old ones designated belong to the old layout.
        std::mem::swap(&mut self.machine.refs, &mut new.machine.refs);
        // The new version's native code goes with its image.
        #[cfg(feature = "native")]
        self.machine.swap_native(&mut new.machine);
        std::mem::swap(&mut self.native_report, &mut new.native_report);
        self.machine.now = new.machine.now;
        std::mem::swap(&mut self.scheduler, &mut new.scheduler);
        if let (Some(info), Some(old)) = (&mut new.task_info, &self.task_info) {
            info.carry_over(old);
        }
        std::mem::swap(&mut self.task_info, &mut new.task_info);
        std::mem::swap(&mut self.sources, &mut new.sources);
        std::mem::swap(&mut self.warnings, &mut new.warnings);
        self.id = new.id;
        self.host_code = new.host_code.take();
        // The new version's addressing convention, under which its
        // warnings (W204) were judged.
        self.io = ProcessImage::new(&self.image, &self.machine.mem, new.io.addressing());
        self.forces = forces;
    }
}

/// The error of a fault in `FB_exit` or `FB_reinit` of a copied instance.
fn fault(f: super::engine::RuntimeFault) -> OnlineChangeError {
    OnlineChangeError::Fault(Box::new(f))
}

/// Tasks as the refusal message shows them.
fn describe(tasks: &[Task]) -> Vec<String> {
    tasks
        .iter()
        .map(|t| {
            let single = if t.single.is_some() { ", SINGLE" } else { "" };
            format!(
                "{}({} ns, priority {}{single})",
                t.name, t.interval, t.priority
            )
        })
        .collect()
}

/// The tasks must be the same: same names, intervals, priorities, and a
/// SINGLE trigger where there was one (its address may move).
fn check_tasks(old: &[Task], new: &[Task]) -> Result<(), OnlineChangeError> {
    let same = old.len() == new.len()
        && old.iter().zip(new).all(|(a, b)| {
            a.name.eq_ignore_ascii_case(&b.name)
                && a.interval == b.interval
                && a.priority == b.priority
                && a.single.is_some() == b.single.is_some()
        });
    if same {
        Ok(())
    } else {
        Err(OnlineChangeError::TasksChanged {
            old: describe(old),
            new: describe(new),
        })
    }
}

/// One line of the report, in walk order.
enum Entry {
    Kept(String),
    Initialised(String),
    Dropped(String),
    Retyped(Retyped),
    ChartRestarted(String),
}

/// The walk over both versions' variables.
struct Carry<'a> {
    old: &'a Image,
    old_m: &'a Machine,
    new: &'a Image,
    new_m: &'a mut Machine,
    entries: Vec<Entry>,
    /// Host FUNCTION_BLOCK instances carried: `(block, old base, new base)`.
    host_moves: Vec<(String, usize, usize)>,
    /// Instances of a user FB whose declaration changed, in walk order.
    copied: Vec<Copied>,
}

/// A variable seen in one version: its type and absolute address.
pub(super) type At = (TypeId, u32);

/// Host FUNCTION_BLOCK instances carried: `(block, old base, new base)`.
type HostMoves = Vec<(String, usize, usize)>;

/// An instance of a user FB whose declaration changed: the online change
/// copies it into the new layout (`super::copy_calls`).
pub(super) struct Copied {
    /// Its path, as the report gives it.
    pub path: String,
    /// Where it was.
    pub old: At,
    /// Where it is in the new version.
    pub new: At,
}

impl Carry<'_> {
    fn report(self) -> ChangeReport {
        let mut r = ChangeReport::default();
        for e in self.entries {
            match e {
                Entry::Kept(p) => r.kept.push(p),
                Entry::Initialised(p) => r.initialised.push(p),
                Entry::Dropped(p) => r.dropped.push(p),
                Entry::Retyped(t) => r.retyped.push(t),
                Entry::ChartRestarted(p) => r.charts_restarted.push(p),
            }
        }
        r
    }

    /// Program instances, matched by instance name.
    fn programs(&mut self) {
        let (old, new) = (self.old, self.new);
        for np in &new.programs {
            match old
                .programs
                .iter()
                .find(|op| op.name.eq_ignore_ascii_case(&np.name))
            {
                Some(op) => self.variable(&np.name, (op.ty, op.base), (np.ty, np.base)),
                None => self.entries.push(Entry::Initialised(np.name.clone())),
            }
        }
        for op in &old.programs {
            if !new
                .programs
                .iter()
                .any(|np| np.name.eq_ignore_ascii_case(&op.name))
            {
                self.entries.push(Entry::Dropped(op.name.clone()));
            }
        }
    }

    /// Global and located variables, matched by name.
    fn globals(&mut self) {
        let (old, new) = (self.old, self.new);
        for ng in &new.globals {
            match old
                .globals
                .iter()
                .find(|og| og.name.eq_ignore_ascii_case(&ng.name))
            {
                Some(og) => self.variable(&ng.name, (og.ty, og.addr), (ng.ty, ng.addr)),
                None => self.entries.push(Entry::Initialised(ng.name.clone())),
            }
        }
        for og in &old.globals {
            if !new
                .globals
                .iter()
                .any(|ng| ng.name.eq_ignore_ascii_case(&og.name))
            {
                self.entries.push(Entry::Dropped(og.name.clone()));
            }
        }
    }

    /// Carries one variable and reports it as a whole when it was kept
    /// whole, member by member otherwise.
    fn variable(&mut self, path: &str, o: At, n: At) {
        let mark = self.entries.len();
        if self.carry(path, o, n) {
            self.entries.truncate(mark);
            self.entries.push(Entry::Kept(path.to_string()));
        }
    }

    /// Carries the value at `o` into `n`; true when all of it was kept.
    fn carry(&mut self, path: &str, o: At, n: At) -> bool {
        let (od, nd) = (self.old.types.get(o.0), self.new.types.get(n.0));
        match (&od.kind, &nd.kind) {
            (TypeKind::Str { .. }, TypeKind::Str { .. })
                if same_type(self.old, o.0, self.new, n.0) =>
            {
                self.copy_string(o.1, n.1);
                true
            }
            (TypeKind::Array { dims, elem }, TypeKind::Array { elem: ne, .. })
                if same_type(self.old, o.0, self.new, n.0) =>
            {
                let count: u64 = dims.iter().map(|d| d.len()).product();
                let (os, ns) = (self.old.types.size(*elem), self.new.types.size(*ne));
                let mark = self.entries.len();
                for i in 0..count as u32 {
                    self.carry(path, (*elem, o.1 + i * os), (*ne, n.1 + i * ns));
                }
                // Same element type: every element was kept whole.
                self.entries.truncate(mark);
                true
            }
            (TypeKind::Struct { .. }, TypeKind::Struct { .. })
            | (TypeKind::Pou { .. }, TypeKind::Pou { .. })
                if od.name.eq_ignore_ascii_case(&nd.name) =>
            {
                let is_fb = matches!(nd.kind, TypeKind::Pou { program: false, .. });
                if is_fb && !same_type(self.old, o.0, self.new, n.0) {
                    self.copied.push(Copied {
                        path: path.to_string(),
                        old: o,
                        new: n,
                    });
                }
                if self
                    .new
                    .hosts
                    .iter()
                    .any(|h| h.eq_ignore_ascii_case(&nd.name))
                {
                    let (from, to) = (o.1 as usize, n.1 as usize);
                    self.host_moves.push((nd.name.clone(), from, to));
                }
                self.members(path, o, n)
            }
            (TypeKind::Step, TypeKind::Step) => {
                self.copy_slots(o.1, n.1, step_layout::SIZE);
                true
            }
            // A reference designates an object of the old layout: it
            // starts again from NULL (docs/semantics.md §16).
            (TypeKind::Ref { .. }, TypeKind::Ref { .. }) => {
                self.entries.push(Entry::Initialised(path.to_string()));
                false
            }
            _ if same_type(self.old, o.0, self.new, n.0) => {
                // Scalars, enumerations, subranges and standard FB
                // instances (pins and hidden state) are plain slots.
                self.copy_slots(o.1, n.1, nd.size);
                true
            }
            _ => {
                self.entries.push(Entry::Retyped(Retyped {
                    path: path.to_string(),
                    old_type: od.name.clone(),
                    new_type: nd.name.clone(),
                }));
                false
            }
        }
    }

    /// The members of a structure or POU instance of the same type name,
    /// matched by name, and its chart; true when all of it was kept.
    fn members(&mut self, path: &str, o: At, n: At) -> bool {
        let (old, new) = (self.old, self.new);
        let carried = |k: MemberKind| {
            !matches!(
                k,
                MemberKind::Temp | MemberKind::InOut | MemberKind::External
            )
        };
        let chart_kept = self.chart(path, o, n);
        let chart_part = |k: MemberKind| matches!(k, MemberKind::Step | MemberKind::Action);
        let mut whole = chart_kept;
        for nm in new.types.members(n.0).iter().filter(|m| carried(m.kind)) {
            let sub = format!("{path}.{}", nm.name);
            let om = old
                .types
                .members(o.0)
                .iter()
                .find(|m| carried(m.kind) && m.name.eq_ignore_ascii_case(&nm.name));
            match om {
                // The chart copied its steps and actions, or restarts.
                Some(om) if chart_part(nm.kind) && chart_part(om.kind) => {}
                Some(om) => {
                    let mark = self.entries.len();
                    if self.carry(&sub, (om.ty, o.1 + om.offset), (nm.ty, n.1 + nm.offset)) {
                        self.entries.truncate(mark);
                        self.entries.push(Entry::Kept(sub));
                    } else {
                        whole = false;
                    }
                }
                None => {
                    whole = false;
                    self.entries.push(Entry::Initialised(sub));
                }
            }
        }
        for om in old.types.members(o.0).iter().filter(|m| carried(m.kind)) {
            let gone = !new
                .types
                .members(n.0)
                .iter()
                .any(|m| carried(m.kind) && m.name.eq_ignore_ascii_case(&om.name));
            if gone {
                whole = false;
                self.entries
                    .push(Entry::Dropped(format!("{path}.{}", om.name)));
            }
        }
        whole
    }

    /// Carries the chart state of a POU instance when both versions have
    /// a chart of the same shape; true when there is nothing to restart.
    fn chart(&mut self, path: &str, o: At, n: At) -> bool {
        let (oc, nc) = (chart_of(self.old, o.0), chart_of(self.new, n.0));
        match (oc, nc) {
            (None, None) => true,
            (Some(oc), Some(nc)) if same_shape(oc, nc) => {
                self.copy_chart(oc, o.1, nc, n.1);
                true
            }
            (_, Some(_)) => {
                self.entries.push(Entry::ChartRestarted(path.to_string()));
                false
            }
            // A chart removed from the body: its steps are dropped members.
            (Some(_), None) => false,
        }
    }

    /// Copies every piece of a chart's run-time state (the regions listed
    /// in `ir::chart`), each at its own offset in the two layouts.
    fn copy_chart(&mut self, oc: &Chart, ob: u32, nc: &Chart, nb: u32) {
        self.copy_slots(ob + oc.header, nb + nc.header, header::SIZE);
        self.copy_slots(ob + oc.active, nb + nc.active, nc.steps.len() as u32);
        self.copy_slots(ob + oc.live, nb + nc.live, nc.actions.len() as u32);
        let transitions = nc.transitions.len() as u32;
        self.copy_slots(ob + oc.cache, nb + nc.cache, transitions);
        for (os, ns) in oc.steps.iter().zip(&nc.steps) {
            self.copy_slots(ob + os.rec, nb + ns.rec, step_layout::SIZE);
            self.copy_slots(ob + os.scratch, nb + ns.scratch, 1);
        }
        for (oa, na) in oc.actions.iter().zip(&nc.actions) {
            self.copy_slots(ob + oa.rec, nb + na.rec, action_layout::SIZE);
        }
    }

    fn copy_slots(&mut self, from: u32, to: u32, n: u32) {
        let (from, to, n) = (from as usize, to as usize, n as usize);
        let (Some(src), Some(dst)) = (
            self.old_m.mem.get(from..from + n),
            self.new_m.mem.get_mut(to..to + n),
        ) else {
            return;
        };
        dst.copy_from_slice(src);
    }

    /// A string's slot holds its id in each version: copy the text.
    fn copy_string(&mut self, from: u32, to: u32) {
        let old_id = self.old_m.mem.get(from as usize).copied();
        let new_id = self.new_m.mem.get(to as usize).copied();
        let (Some(old_id), Some(new_id)) = (old_id, new_id) else {
            return;
        };
        let text = self
            .old_m
            .strings
            .get(old_id as usize)
            .map(|s| s.text.as_str());
        if let (Some(text), Some(dst)) = (text, self.new_m.strings.get_mut(new_id as usize)) {
            dst.set(text);
        }
    }
}

/// The chart of a POU type's body, if it has one.
fn chart_of(image: &Image, ty: TypeId) -> Option<&Chart> {
    let TypeKind::Pou { code, .. } = &image.types.get(ty).kind else {
        return None;
    };
    image
        .codes
        .get(code.index())?
        .ops
        .iter()
        .find_map(|op| match op {
            Op::Sfc { chart } => image.charts.get(chart.index()),
            _ => None,
        })
}

/// Two charts have the same shape: same steps in the same order with the
/// same associations, same transitions between the same steps, same
/// actions in the same order. (Conditions and bodies may differ.)
fn same_shape(a: &Chart, b: &Chart) -> bool {
    let steps = a.steps.len() == b.steps.len()
        && a.steps.iter().zip(&b.steps).all(|(x, y)| {
            x.name.eq_ignore_ascii_case(&y.name)
                && x.out == y.out
                && x.assocs.len() == y.assocs.len()
                && x.assocs
                    .iter()
                    .zip(&y.assocs)
                    .all(|(p, q)| p.action == q.action && p.qualifier == q.qualifier)
        });
    let transitions = a.transitions.len() == b.transitions.len()
        && a.transitions
            .iter()
            .zip(&b.transitions)
            .all(|(x, y)| x.from == y.from && x.to == y.to);
    let actions = a.actions.len() == b.actions.len()
        && a.actions
            .iter()
            .zip(&b.actions)
            .all(|(x, y)| x.name.eq_ignore_ascii_case(&y.name));
    steps && transitions && actions && a.initial == b.initial
}

/// Two types (each in its own version's table) are the same type: same
/// kind, same name, and for aggregates the same layout down to the leaves.
fn same_type(a_img: &Image, a: TypeId, b_img: &Image, b: TypeId) -> bool {
    let (ad, bd) = (a_img.types.get(a), b_img.types.get(b));
    if !ad.name.eq_ignore_ascii_case(&bd.name) || ad.size != bd.size {
        return false;
    }
    let same_members = |x: &[crate::ir::type_table::Member],
                        y: &[crate::ir::type_table::Member]| {
        x.len() == y.len()
            && x.iter().zip(y).all(|(p, q)| {
                p.name.eq_ignore_ascii_case(&q.name)
                    && p.kind == q.kind
                    && p.offset == q.offset
                    && same_type(a_img, p.ty, b_img, q.ty)
            })
    };
    match (&ad.kind, &bd.kind) {
        (TypeKind::Elem(x), TypeKind::Elem(y)) => x == y,
        (TypeKind::Str { wide: w1, max: m1 }, TypeKind::Str { wide: w2, max: m2 }) => {
            w1 == w2 && m1 == m2
        }
        (TypeKind::Array { dims: d1, elem: e1 }, TypeKind::Array { dims: d2, elem: e2 }) => {
            d1 == d2 && same_type(a_img, *e1, b_img, *e2)
        }
        (TypeKind::Struct { fields: f1 }, TypeKind::Struct { fields: f2 }) => same_members(f1, f2),
        (TypeKind::Pou { members: m1, .. }, TypeKind::Pou { members: m2, .. }) => {
            same_members(m1, m2)
                && match (chart_of(a_img, a), chart_of(b_img, b)) {
                    (None, None) => true,
                    (Some(x), Some(y)) => same_shape(x, y),
                    _ => false,
                }
        }
        (
            TypeKind::Enum {
                base: b1,
                values: v1,
            },
            TypeKind::Enum {
                base: b2,
                values: v2,
            },
        ) => b1 == b2 && v1 == v2,
        (
            TypeKind::Subrange {
                base: b1,
                lo: l1,
                hi: h1,
            },
            TypeKind::Subrange {
                base: b2,
                lo: l2,
                hi: h2,
            },
        ) => b1 == b2 && l1 == l2 && h1 == h2,
        (TypeKind::NativeFb(x), TypeKind::NativeFb(y)) => x == y,
        (TypeKind::Step, TypeKind::Step) => true,
        _ => false,
    }
}

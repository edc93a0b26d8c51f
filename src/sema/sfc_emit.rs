//! Emission of textual SFC bodies: checks the chart, builds its step
//! table ([`crate::ir::chart`]), emits the transition conditions and action
//! bodies into code blocks of their own, then `Op::Sfc` followed by the
//! body's plain statements.

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Fcx, Ty, Val};
use super::model::{Storage, VarInfo};
use super::sfc::{HIDDEN, Hidden, Names, hidden_layout, names};
use crate::elementary::ElemType;
use crate::ir::chart::{
    self, Action, ActionKind, Association, Chart, Condition, Duration, Qualifier, action_layout,
    header,
};
use crate::ir::image::{CodeBlock, CodeKind};
use crate::ir::op::{ChartIdx, CodeIdx, Op, Slot};
use crate::ir::type_table::{MemberKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Body, Expr, Ident, Pou, SfcElement, TransitionCondition};
use std::collections::HashMap;

/// The chart of the POU being emitted: where its state lives.
struct ChartFrame<'a> {
    /// The POU.
    p: usize,
    /// Its declaration.
    pou: &'a Pou,
    /// Start of the hidden chart-state region in the frame.
    hbase: u32,
    /// Parts of that region.
    lay: Hidden,
    /// First temporary of the code blocks (after the variables).
    temp_base: u32,
    /// Highest temporary used by the condition and action blocks.
    temp_max: u32,
}

impl BodyBuilder<'_> {
    /// Checks a chart body, builds its table, and emits `Op::Sfc` followed
    /// by the plain statements into the current code block.
    pub(super) fn emit_chart(&mut self, pou: &Pou, elems: &[SfcElement]) {
        let p = self.block.pou;
        let Some(hidden) = self.model.pous[p].vars.get(HIDDEN).map(|v| v.storage) else {
            // A FUNCTION (already reported).
            return;
        };
        let Storage::Frame(hbase) = hidden else {
            return;
        };
        let n = names(elems);
        let lay = hidden_layout(
            n.steps.len() as u32,
            (n.actions.len() + n.var_actions.len()) as u32,
            n.transitions.len() as u32,
            n.var_actions.len() as u32,
        );
        let mut cf = ChartFrame {
            p,
            pou,
            hbase,
            lay,
            temp_base: self.model.pous[p].vars_size,
            temp_max: self.block.temp_max,
        };
        let (step_index, mut steps, step_src) = self.chart_steps(&cf, &n);
        let initial: Vec<u32> = step_src
            .iter()
            .enumerate()
            .filter(|(_, s)| s.initial)
            .map(|(i, _)| i as u32)
            .collect();
        let (action_index, actions) = self.chart_actions(&mut cf, &n);
        self.chart_associations(&n, &step_src, &action_index, &mut steps);
        let transitions = self.chart_transitions(&mut cf, &n, &step_index, &mut steps);
        let temp_max = cf.temp_max;
        self.chart_structure(pou, &step_src, &transitions, &initial);
        let forcings = self.chart_forcings(&n, &step_index);
        let evolution = if self.model.grafcet {
            chart::Evolution::Grafcet
        } else {
            chart::Evolution::Sfc
        };

        if self.diags.has_errors() {
            // Keep going for more diagnostics, but emit nothing runnable.
            self.block.temp_max = temp_max;
            self.stmts(&n.statements);
            return;
        }
        let chart = Chart {
            name: pou.name.name.clone(),
            header: hbase,
            active: hbase + cf.lay.active,
            live: hbase + cf.lay.live,
            cache: hbase + cf.lay.cache,
            initial,
            steps,
            transitions,
            actions,
            evolution,
            forcings,
        };
        let index = ChartIdx::new(self.out.charts.len() as u32);
        self.out.charts.push(chart);
        self.block.span = pou.name.span;
        self.block.emit(Op::Sfc { chart: index });
        self.block.temp_max = self.block.temp_max.max(temp_max);
        self.stmts(&n.statements);
    }

    /// The steps of the chart (the first declaration of a name wins;
    /// duplicates are reported by the layout), with their source.
    #[allow(clippy::type_complexity)]
    fn chart_steps<'n>(
        &mut self,
        cf: &ChartFrame,
        n: &Names<'n>,
    ) -> (
        HashMap<String, u32>,
        Vec<chart::Step>,
        Vec<&'n crate::syntax::ast::Step>,
    ) {
        let (p, hbase) = (cf.p, cf.hbase);
        let mut step_index: HashMap<String, u32> = HashMap::new();
        let mut steps: Vec<chart::Step> = Vec::new();
        let mut step_src: Vec<&crate::syntax::ast::Step> = Vec::new();
        for s in &n.steps {
            let key = s.name.key();
            if step_index.contains_key(&key) {
                continue;
            }
            let Some(VarInfo {
                storage: Storage::Frame(rec),
                kind: MemberKind::Step,
                ..
            }) = self.model.pous[p].vars.get(&key).cloned()
            else {
                continue;
            };
            step_index.insert(key, steps.len() as u32);
            steps.push(chart::Step {
                name: s.name.name.clone(),
                rec,
                scratch: hbase + cf.lay.scratch + steps.len() as u32,
                out: Vec::new(),
                assocs: Vec::new(),
            });
            step_src.push(s);
        }
        (step_index, steps, step_src)
    }

    /// The actions in execution order: by the position of their declaration
    /// (an ACTION block, or a BOOL variable's first association). ACTION
    /// bodies become code blocks.
    fn chart_actions(
        &mut self,
        cf: &mut ChartFrame,
        n: &Names,
    ) -> (HashMap<String, u32>, Vec<Action>) {
        let mut order: Vec<(u32, usize, bool)> = Vec::new();
        let mut seen_action: HashMap<String, ()> = HashMap::new();
        for (k, a) in n.actions.iter().enumerate() {
            if seen_action.insert(a.name.key(), ()).is_none() {
                order.push((a.span.start, k, true));
            }
        }
        for (k, (_, (_, span))) in n.var_actions.iter().enumerate() {
            order.push((span.start, k, false));
        }
        order.sort_by_key(|o| o.0);
        let mut action_index: HashMap<String, u32> = HashMap::new();
        let mut actions: Vec<Action> = Vec::new();
        for &(_, k, declared) in &order {
            let found = if declared {
                self.declared_action(cf, n, k)
            } else {
                self.variable_action(cf, n, k)
            };
            if let Some((key, action)) = found {
                action_index.insert(key, actions.len() as u32);
                actions.push(action);
            }
        }
        (action_index, actions)
    }

    /// ACTION `k` of the chart, its body emitted into a code block.
    fn declared_action(
        &mut self,
        cf: &mut ChartFrame,
        n: &Names,
        k: usize,
    ) -> Option<(String, Action)> {
        let (p, pou, temp_base) = (cf.p, cf.pou, cf.temp_base);
        let a = n.actions[k];
        let key = a.name.key();
        let Some(VarInfo {
            storage: Storage::Frame(rec),
            kind: MemberKind::Action,
            ..
        }) = self.model.pous[p].vars.get(&key).cloned()
        else {
            return None;
        };
        let name = format!("{}.{}", pou.name.name, a.name.name);
        let (code, max) = self.sub_block(p, name, a.span, temp_base, |c| match &a.body {
            Body::St(stmts) => c.stmts(stmts),
            Body::Il(lines) => {
                c.il_body(lines);
            }
            Body::Sfc(_) => {}
        });
        cf.temp_max = cf.temp_max.max(max);
        let action = Action {
            name: a.name.name.clone(),
            rec,
            kind: ActionKind::Body(code),
        };
        Some((key, action))
    }

    /// A BOOL variable used as action `k` of the chart's variable actions.
    fn variable_action(
        &mut self,
        cf: &ChartFrame,
        n: &Names,
        k: usize,
    ) -> Option<(String, Action)> {
        let hbase = cf.hbase;
        let (key, (id, _)) = n.var_actions.get_index(k)?;
        let rec = hbase + cf.lay.records + k as u32 * action_layout::SIZE;
        let kind = match self.lookup_var(key).cloned() {
            None => {
                self.diags.error(
                    "E610",
                    id.span,
                    format!(
                        "unknown action `{}`: declare an ACTION or a BOOL variable with this name",
                        id.name
                    ),
                );
                return None;
            }
            Some(v) => {
                let is_bool = self.types.scalar(v.ty) == Some(ElemType::Bool);
                match (v.storage, v.kind) {
                    (_, MemberKind::Step | MemberKind::Hidden) => None,
                    _ if v.constant || !is_bool => None,
                    (Storage::Frame(o), _) => Some(ActionKind::Frame(o)),
                    (Storage::Abs(a), _) => Some(ActionKind::Abs(a)),
                    (Storage::Ref(_), _) => None,
                }
            }
        };
        let Some(kind) = kind else {
            self.diags.error(
                "E615",
                id.span,
                format!(
                    "`{}` cannot be used as an action: only ACTIONs and writable BOOL variables (not VAR_IN_OUT) can",
                    id.name
                ),
            );
            return None;
        };
        let action = Action {
            name: id.name.clone(),
            rec,
            kind,
        };
        Some((key.clone(), action))
    }

    /// The action associations of every step (unknown actions were
    /// reported with the actions), and a warning for unused ACTIONs.
    fn chart_associations(
        &mut self,
        n: &Names,
        step_src: &[&crate::syntax::ast::Step],
        action_index: &HashMap<String, u32>,
        steps: &mut [chart::Step],
    ) {
        let mut used_actions: HashMap<String, ()> = HashMap::new();
        for (i, s) in step_src.iter().enumerate() {
            for a in &s.actions {
                used_actions.insert(a.action.key(), ());
                let Some(&action) = action_index.get(&a.action.key()) else {
                    continue;
                };
                if let Some(assoc) = self.association(a, action) {
                    steps[i].assocs.push(assoc);
                }
            }
        }
        for a in &n.actions {
            if !used_actions.contains_key(&a.name.key()) {
                self.diags.warning(
                    "W602",
                    a.name.span,
                    format!("action `{}` is not associated with any step", a.name.name),
                );
            }
        }
    }

    /// One association: its qualifier, its duration (timed qualifiers
    /// only), its indicator variables.
    fn association(
        &mut self,
        a: &crate::syntax::ast::ActionAssociation,
        action: u32,
    ) -> Option<Association> {
        let qualifier = match &a.qualifier {
            None => Qualifier::N,
            Some(q) => match Qualifier::parse(&q.key()) {
                Some(q) => q,
                None => {
                    self.diags.error(
                        "E609",
                        q.span,
                        format!(
                            "unknown action qualifier `{}` (expected N, R, S, L, D, P, P0, P1, SD, DS or SL)",
                            q.name
                        ),
                    );
                    return None;
                }
            },
        };
        let duration = match (&a.duration, qualifier.timed()) {
            (None, true) => {
                self.diags.error(
                    "E608",
                    a.span,
                    format!(
                        "qualifier {qualifier:?} needs a duration, e.g. `{}({qualifier:?}, T#5s)`",
                        a.action.name
                    ),
                );
                return None;
            }
            (Some(e), true) => self.duration(e)?,
            (Some(e), false) => {
                self.diags.error(
                    "E608",
                    e.span,
                    format!("qualifier {qualifier:?} takes no duration"),
                );
                return None;
            }
            (None, false) => Duration::None,
        };
        for ind in &a.indicators {
            if self.lookup_var(&ind.key()).is_none() {
                self.diags.error(
                    "E613",
                    ind.span,
                    format!("unknown indicator variable `{}`", ind.name),
                );
            }
        }
        Some(Association {
            action,
            qualifier,
            duration,
        })
    }

    /// The transitions, their conditions emitted into code blocks; each
    /// step's outgoing transitions ordered by priority.
    fn chart_transitions(
        &mut self,
        cf: &mut ChartFrame,
        n: &Names,
        step_index: &HashMap<String, u32>,
        steps: &mut [chart::Step],
    ) -> Vec<chart::Transition> {
        let (p, pou, hbase, temp_base) = (cf.p, cf.pou, cf.hbase, cf.temp_base);
        let mut transitions: Vec<chart::Transition> = Vec::new();
        let mut ranks: Vec<(u64, usize)> = Vec::new();
        let mut names_seen: HashMap<String, Span> = HashMap::new();
        let cond_slot = hbase + header::COND;
        for (k, t) in n.transitions.iter().enumerate() {
            if let Some(name) = &t.name
                && names_seen.insert(name.key(), name.span).is_some()
            {
                self.diags.error(
                    "E614",
                    name.span,
                    format!("transition `{}` is declared twice", name.name),
                );
            }
            let resolve = |c: &mut BodyBuilder, ids: &[Ident]| -> Option<Vec<u32>> {
                let mut out = Vec::new();
                let mut ok = true;
                for id in ids {
                    match step_index.get(&id.key()) {
                        Some(&s) => {
                            if !out.contains(&s) {
                                out.push(s)
                            }
                        }
                        None => {
                            c.diags.error(
                                "E602",
                                id.span,
                                format!("unknown step `{}` in transition", id.name),
                            );
                            ok = false;
                        }
                    }
                }
                ok.then_some(out)
            };
            let from = resolve(self, &t.from);
            let to = resolve(self, &t.to);
            let rank = match &t.priority {
                None => u64::MAX,
                Some(e) => self.priority(e),
            };
            let label = match &t.name {
                Some(nm) => format!("{}.{}", pou.name.name, nm.name),
                None => format!("{}.transition{}", pou.name.name, k + 1),
            };
            let cond = self.condition(p, label, t, temp_base, cond_slot, &mut cf.temp_max);
            let (Some(from), Some(to)) = (from, to) else {
                continue;
            };
            ranks.push((rank, transitions.len()));
            transitions.push(chart::Transition { from, to, cond });
        }
        ranks.sort();
        for &(_, t) in &ranks {
            let from = transitions[t].from.clone();
            for s in from {
                steps[s as usize].out.push(t as u32);
            }
        }
        transitions
    }

    /// Initial steps per connected chart, and steps no transition reaches.
    fn chart_structure(
        &mut self,
        pou: &Pou,
        steps: &[&crate::syntax::ast::Step],
        transitions: &[chart::Transition],
        initial: &[u32],
    ) {
        if steps.is_empty() {
            return;
        }
        if initial.is_empty() {
            self.diags.error(
                "E605",
                pou.name.span,
                format!("the chart of `{}` has no INITIAL_STEP", pou.name.name),
            );
            return;
        }
        // Union-find over the steps linked by transitions.
        let mut parent: Vec<usize> = (0..steps.len()).collect();
        fn find(parent: &mut [usize], mut x: usize) -> usize {
            while parent[x] != x {
                parent[x] = parent[parent[x]];
                x = parent[x];
            }
            x
        }
        let mut reached = vec![false; steps.len()];
        for t in transitions {
            let all: Vec<u32> = t.from.iter().chain(t.to.iter()).copied().collect();
            for w in all.windows(2) {
                let (a, b) = (
                    find(&mut parent, w[0] as usize),
                    find(&mut parent, w[1] as usize),
                );
                parent[a] = b;
            }
            for &s in &t.to {
                reached[s as usize] = true;
            }
        }
        let mut has_initial = vec![false; steps.len()];
        for &s in initial {
            let r = find(&mut parent, s as usize);
            has_initial[r] = true;
        }
        let mut reported = vec![false; steps.len()];
        for (i, s) in steps.iter().enumerate() {
            let r = find(&mut parent, i);
            if !has_initial[r] {
                if !reported[r] {
                    reported[r] = true;
                    self.diags.error(
                        "E605",
                        s.name.span,
                        format!(
                            "step `{}` belongs to a chart without an INITIAL_STEP",
                            s.name.name
                        ),
                    );
                }
            } else if !s.initial && !reached[i] {
                self.diags.warning(
                    "W601",
                    s.name.span,
                    format!(
                        "no transition leads to step `{}`: it can never become active",
                        s.name.name
                    ),
                );
            }
        }
    }

    /// Compiles a transition condition.
    fn condition(
        &mut self,
        p: usize,
        label: String,
        t: &crate::syntax::ast::Transition,
        temp_base: u32,
        cond_slot: u32,
        temp_max: &mut u32,
    ) -> Condition {
        let bool_ty = TypeTable::elem(ElemType::Bool);
        let mut folded: Option<Condition> = None;
        let (code, max) = self.sub_block(p, label, t.span, temp_base, |c| {
            let (slot, ty, span) = match &t.condition {
                TransitionCondition::Expr(e) => {
                    let v = c.expr(e, Some(bool_ty));
                    if v.is_error() {
                        return;
                    }
                    if v.ty() != Ty::T(bool_ty) {
                        let name = c.ty_name(v.ty());
                        c.diags.error(
                            "E607",
                            e.span,
                            format!("a transition condition must be BOOL, found {name}"),
                        );
                        return;
                    }
                    match v {
                        Val::Const(Const::Bits(b), _) => {
                            folded = Some(Condition::Const(b != 0));
                            return;
                        }
                        Val::Slot(s, _) if c.block.ops.is_empty() => {
                            folded = Some(Condition::Frame(s.get()));
                            return;
                        }
                        _ => {}
                    }
                    let s = c.materialize(&v);
                    (s, Some(bool_ty), e.span)
                }
                TransitionCondition::Il(lines) => {
                    let (cr, ty) = c.il_body(lines);
                    let end = c.block.here();
                    for j in std::mem::take(&mut c.block.returns) {
                        c.block.patch(j, end);
                    }
                    (cr, ty, t.span)
                }
            };
            if ty != Some(bool_ty) {
                let found = ty
                    .map(|t| c.types.name(t).to_string())
                    .unwrap_or("nothing".into());
                c.diags.error(
                    "E607",
                    span,
                    format!("a transition condition must be BOOL, found {found}"),
                );
                return;
            }
            c.block.mov(Slot::new(cond_slot), slot);
        });
        match folded {
            Some(c) => {
                // The block is unused; keep it (empty) so code indexes stay stable.
                c
            }
            None => {
                *temp_max = (*temp_max).max(max);
                Condition::Code(code)
            }
        }
    }

    /// Emits a code block of kind `Block` for POU `p` built by `build`;
    /// returns its index and its frame high-water mark.
    fn sub_block(
        &mut self,
        p: usize,
        name: String,
        span: Span,
        temp_base: u32,
        build: impl FnOnce(&mut BodyBuilder),
    ) -> (CodeIdx, u32) {
        let mut sub = Fcx::new(p, temp_base);
        sub.span = span;
        let outer = std::mem::replace(&mut self.block, sub);
        build(self);
        let mut sub = std::mem::replace(&mut self.block, outer);
        let end = sub.here();
        for j in std::mem::take(&mut sub.returns) {
            sub.patch(j, end);
        }
        sub.span = span;
        sub.emit(Op::Ret);
        let code = CodeIdx::new(self.out.codes.len() as u32);
        for (at, callee) in std::mem::take(&mut sub.fixups) {
            self.out.fixups.push((code, at, callee));
        }
        let (consts, pins) = sub.take_tagged();
        self.pending_blocks.push((code, consts, pins));
        self.owned_blocks.push(code);
        self.out.codes.push(CodeBlock {
            name,
            kind: CodeKind::Block,
            ops: sub.ops,
            spans: sub.spans,
            entry_init: Vec::new(),
            entry_strings: Vec::new(),
            frame: 0,
            frame_size: sub.temp_max,
            handlers: sub.handlers,
        });
        (code, sub.temp_max)
    }

    /// Checks `e` in a scratch code block whose instructions are discarded
    /// (only a constant or a plain variable is accepted); returns its value
    /// and those instructions.
    fn scratch_expr(
        &mut self,
        e: &Expr,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> (Val, Vec<Op>) {
        let scratch = Fcx::new(self.block.pou, self.block.temp_base);
        let outer = std::mem::replace(&mut self.block, scratch);
        let v = self.expr(e, expect);
        let scratch = std::mem::replace(&mut self.block, outer);
        (v, scratch.ops)
    }

    /// A duration: a constant TIME expression or a TIME variable.
    fn duration(&mut self, e: &Expr) -> Option<Duration> {
        let time = TypeTable::elem(ElemType::Time);
        let (v, ops) = self.scratch_expr(e, Some(time));
        if v.is_error() {
            return None;
        }
        if v.ty() != Ty::T(time) {
            let name = self.ty_name(v.ty());
            self.diags.error(
                "E611",
                e.span,
                format!("an action duration must be TIME, found {name}"),
            );
            return None;
        }
        match (&v, ops.as_slice()) {
            (Val::Const(Const::Bits(b), _), _) => Some(Duration::Const(*b as i64)),
            (Val::Slot(s, _), []) => Some(Duration::Frame(s.get())),
            (Val::Slot(s, _), [Op::LoadAbs { d, abs }]) if d == s => Some(Duration::Abs(*abs)),
            _ => {
                self.diags.error(
                    "E611",
                    e.span,
                    "an action duration must be a TIME literal, a constant or a TIME variable",
                );
                None
            }
        }
    }

    /// A transition priority: a non-negative constant integer.
    fn priority(&mut self, e: &Expr) -> u64 {
        let (v, _) = self.scratch_expr(e, None);
        match v {
            Val::Const(Const::Int(i), _) if (0..i64::MAX as i128).contains(&i) => i as u64,
            Val::Const(Const::Bits(b), Ty::T(t))
                if self.types.scalar(t).is_some_and(|x| x.is_int()) && (b as i64) >= 0 =>
            {
                b
            }
            _ => {
                if !v.is_error() {
                    self.diags.error(
                        "E612",
                        e.span,
                        "a transition PRIORITY must be a non-negative constant integer",
                    );
                }
                u64::MAX
            }
        }
    }
}

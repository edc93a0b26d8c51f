//! Lowering of textual SFC bodies into a step table ([`crate::ir::chart`])
//! plus code blocks for conditions and action bodies.
//!
//! Layout (called from `layout_pou`) gives every step a step record and
//! every ACTION a control record as members of the POU, and reserves one
//! hidden region for the rest of the chart state. Emission checks the
//! chart, builds the table, and emits `Op::Sfc` followed by the body's
//! plain statements.

use super::body::BodyBuilder;
use super::consts::Const;
use super::declare::Declarer;
use super::emit::{Fcx, Ty, Val};
use super::model::{Storage, VarInfo};
use crate::ir::chart::{
    self, Action, ActionKind, Association, Chart, Condition, Duration, Qualifier, action_layout,
    header,
};
use crate::ir::image::{CodeBlock, CodeKind};
use crate::ir::op::Op;
use crate::ir::types::{Member, MemberKind, TypeDef, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Body, Expr, Ident, Pou, SfcElement, Stmt, TransitionCondition};
use crate::types::ElemType;
use indexmap::IndexMap;
use std::collections::HashMap;

/// Key of the hidden chart-state variable (not a valid identifier).
const HIDDEN: &str = "$SFC";

/// Names of a chart body, in the order the layout and the emission agree on.
struct Names<'a> {
    steps: Vec<&'a crate::syntax::ast::Step>,
    actions: Vec<&'a crate::syntax::ast::Action>,
    transitions: Vec<&'a crate::syntax::ast::Transition>,
    statements: Vec<Stmt>,
    /// Names associated with steps that are not ACTIONs (candidate BOOL
    /// variables), by key, with the first association's span.
    var_actions: IndexMap<String, (Ident, Span)>,
}

fn names(elems: &[SfcElement]) -> Names<'_> {
    let mut n = Names {
        steps: Vec::new(),
        actions: Vec::new(),
        transitions: Vec::new(),
        statements: Vec::new(),
        var_actions: IndexMap::new(),
    };
    for e in elems {
        match e {
            SfcElement::Step(s) => n.steps.push(s),
            SfcElement::Action(a) => n.actions.push(a),
            SfcElement::Transition(t) => n.transitions.push(t),
            SfcElement::Statement(s) => n.statements.push(s.clone()),
        }
    }
    let action_keys: std::collections::HashSet<String> =
        n.actions.iter().map(|a| a.name.key()).collect();
    for s in &n.steps {
        for a in &s.actions {
            let key = a.action.key();
            if !action_keys.contains(&key) {
                n.var_actions
                    .entry(key)
                    .or_insert((a.action.clone(), a.span));
            }
        }
    }
    n
}

/// Offsets of the parts of the hidden region, relative to its start.
struct Hidden {
    active: u32,
    live: u32,
    cache: u32,
    scratch: u32,
    records: u32,
    size: u32,
}

fn hidden_layout(steps: u32, actions: u32, transitions: u32, var_actions: u32) -> Hidden {
    let active = header::SIZE;
    let live = active + steps;
    let cache = live + actions;
    // The cache is followed by the list of transitions fired in a call.
    let scratch = cache + 2 * transitions;
    let records = scratch + steps;
    Hidden {
        active,
        live,
        cache,
        scratch,
        records,
        size: records + var_actions * action_layout::SIZE,
    }
}

impl Declarer<'_> {
    /// Adds the chart members of POU `pou` (steps, actions, hidden state)
    /// after its variables.
    pub(super) fn layout_chart(
        &mut self,
        pou: &Pou,
        elems: &[SfcElement],
        vars: &mut IndexMap<String, VarInfo>,
        members: &mut Vec<Member>,
        offset: &mut u32,
    ) {
        if pou.kind == crate::syntax::ast::PouKind::Function {
            self.diags.error(
                "E601",
                pou.name.span,
                "a FUNCTION cannot contain a Sequential Function Chart (it has no state)",
            );
            return;
        }
        let n = names(elems);
        let step_ty = TypeTable::step();
        let action_ty = self.types.add(TypeDef {
            name: "ACTION".into(),
            kind: TypeKind::Struct {
                fields: vec![
                    Member {
                        name: "Q".into(),
                        ty: TypeTable::elem(ElemType::Bool),
                        offset: action_layout::Q,
                        kind: MemberKind::Field,
                        constant: false,
                    },
                    Member {
                        name: "A".into(),
                        ty: TypeTable::elem(ElemType::Bool),
                        offset: action_layout::A,
                        kind: MemberKind::Field,
                        constant: false,
                    },
                ],
            },
            size: action_layout::SIZE,
        });
        let mut add = |c: &mut Declarer, id: &Ident, ty, kind: MemberKind, what: &str| {
            let key = id.key();
            if let Some(prev) = vars.get(&key) {
                let code = if kind == MemberKind::Step {
                    "E603"
                } else {
                    "E604"
                };
                let prior = match prev.kind {
                    MemberKind::Step => "a step",
                    MemberKind::Action => "an action",
                    _ => "a variable",
                };
                c.diags.error(
                    code,
                    id.span,
                    format!(
                        "{what} `{}` has the same name as {prior} of `{}`",
                        id.name, pou.name.name
                    ),
                );
                return;
            }
            let at = *offset;
            *offset += c.types.size(ty);
            members.push(Member {
                name: id.name.clone(),
                ty,
                offset: at,
                kind,
                constant: false,
            });
            vars.insert(
                key,
                VarInfo {
                    name: id.name.clone(),
                    ty,
                    kind,
                    storage: Storage::Frame(at),
                    constant: false,
                    value: None,
                    init: None,
                    location: None,
                    span: id.span,
                },
            );
        };
        for s in &n.steps {
            add(self, &s.name, step_ty, MemberKind::Step, "step");
        }
        for a in &n.actions {
            add(self, &a.name, action_ty, MemberKind::Action, "action");
        }
        let h = hidden_layout(
            n.steps.len() as u32,
            (n.actions.len() + n.var_actions.len()) as u32,
            n.transitions.len() as u32,
            n.var_actions.len() as u32,
        );
        let hidden_ty = self.types.add(TypeDef {
            name: "SFC_STATE".into(),
            kind: TypeKind::Struct { fields: Vec::new() },
            size: h.size,
        });
        vars.insert(
            HIDDEN.into(),
            VarInfo {
                name: HIDDEN.into(),
                ty: hidden_ty,
                kind: MemberKind::Hidden,
                storage: Storage::Frame(*offset),
                constant: false,
                value: None,
                init: None,
                location: None,
                span: pou.name.span,
            },
        );
        *offset += h.size;
    }
}

impl BodyBuilder<'_> {
    /// Checks a chart body, builds its table, and emits `Op::Sfc` followed
    /// by the plain statements into `f`.
    pub(super) fn emit_chart(&mut self, f: &mut Fcx, pou: &Pou, elems: &[SfcElement]) {
        let p = f.pou;
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
        let temp_base = self.model.pous[p].vars_size;
        let mut temp_max = f.temp_max;

        // Steps: the first declaration of a name wins (duplicates reported).
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
                scratch: hbase + lay.scratch + steps.len() as u32,
                out: Vec::new(),
                assocs: Vec::new(),
            });
            step_src.push(s);
        }
        let initial: Vec<u32> = step_src
            .iter()
            .enumerate()
            .filter(|(_, s)| s.initial)
            .map(|(i, _)| i as u32)
            .collect();

        // Actions in execution order: by the position of their declaration
        // (an ACTION block, or a BOOL variable's first association).
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
            if declared {
                let a = n.actions[k];
                let key = a.name.key();
                let Some(VarInfo {
                    storage: Storage::Frame(rec),
                    kind: MemberKind::Action,
                    ..
                }) = self.model.pous[p].vars.get(&key).cloned()
                else {
                    continue;
                };
                let name = format!("{}.{}", pou.name.name, a.name.name);
                let (code, max) =
                    self.sub_block(p, name, a.span, temp_base, |c, sub| match &a.body {
                        Body::St(stmts) => c.stmts(sub, stmts),
                        Body::Il(lines) => {
                            c.il_body(sub, lines);
                        }
                        Body::Sfc(_) => {}
                    });
                temp_max = temp_max.max(max);
                action_index.insert(key, actions.len() as u32);
                actions.push(Action {
                    name: a.name.name.clone(),
                    rec,
                    kind: ActionKind::Body(code),
                });
            } else {
                let Some((key, (id, _))) = n.var_actions.get_index(k) else {
                    continue;
                };
                let rec = hbase + lay.records + k as u32 * action_layout::SIZE;
                let kind = match self.lookup_var(f, key).cloned() {
                    None => {
                        self.diags.error(
                            "E610",
                            id.span,
                            format!(
                                "unknown action `{}`: declare an ACTION or a BOOL variable with this name",
                                id.name
                            ),
                        );
                        continue;
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
                    continue;
                };
                action_index.insert(key.clone(), actions.len() as u32);
                actions.push(Action {
                    name: id.name.clone(),
                    rec,
                    kind,
                });
            }
        }

        // Associations.
        let mut used_actions: HashMap<String, ()> = HashMap::new();
        for (i, s) in step_src.iter().enumerate() {
            for a in &s.actions {
                used_actions.insert(a.action.key(), ());
                let Some(&action) = action_index.get(&a.action.key()) else {
                    continue;
                };
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
                            continue;
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
                        continue;
                    }
                    (Some(e), true) => match self.duration(f, e) {
                        Some(d) => d,
                        None => continue,
                    },
                    (Some(e), false) => {
                        self.diags.error(
                            "E608",
                            e.span,
                            format!("qualifier {qualifier:?} takes no duration"),
                        );
                        continue;
                    }
                    (None, false) => Duration::None,
                };
                for ind in &a.indicators {
                    if self.lookup_var(f, &ind.key()).is_none() {
                        self.diags.error(
                            "E613",
                            ind.span,
                            format!("unknown indicator variable `{}`", ind.name),
                        );
                    }
                }
                steps[i].assocs.push(Association {
                    action,
                    qualifier,
                    duration,
                });
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

        // Transitions.
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
                Some(e) => self.priority(f, e),
            };
            let label = match &t.name {
                Some(nm) => format!("{}.{}", pou.name.name, nm.name),
                None => format!("{}.transition{}", pou.name.name, k + 1),
            };
            let cond = self.condition(p, label, t, temp_base, cond_slot, &mut temp_max);
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

        self.chart_structure(pou, &step_src, &transitions, &initial);

        if self.diags.has_errors() {
            // Keep going for more diagnostics, but emit nothing runnable.
            f.temp_max = temp_max;
            self.stmts(f, &n.statements);
            return;
        }
        let chart = Chart {
            name: pou.name.name.clone(),
            header: hbase,
            active: hbase + lay.active,
            live: hbase + lay.live,
            cache: hbase + lay.cache,
            initial,
            steps,
            transitions,
            actions,
        };
        let index = self.out.charts.len() as u32;
        self.out.charts.push(chart);
        f.span = pou.name.span;
        f.emit(Op::Sfc { chart: index });
        f.temp_max = f.temp_max.max(temp_max);
        self.stmts(f, &n.statements);
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
        let (code, max) = self.sub_block(p, label, t.span, temp_base, |c, sub| {
            let (slot, ty, span) = match &t.condition {
                TransitionCondition::Expr(e) => {
                    let v = c.expr(sub, e, Some(bool_ty));
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
                        Val::Slot(s, _) if sub.ops.is_empty() => {
                            folded = Some(Condition::Frame(s));
                            return;
                        }
                        _ => {}
                    }
                    let s = c.materialize(sub, &v);
                    (s, Some(bool_ty), e.span)
                }
                TransitionCondition::Il(lines) => {
                    let (cr, ty) = c.il_body(sub, lines);
                    let end = sub.here();
                    for j in std::mem::take(&mut sub.returns) {
                        sub.patch(j, end);
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
            sub.mov(cond_slot, slot);
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
        build: impl FnOnce(&mut BodyBuilder, &mut Fcx),
    ) -> (u32, u32) {
        let mut sub = Fcx::new(p, temp_base);
        sub.span = span;
        build(self, &mut sub);
        let end = sub.here();
        for j in std::mem::take(&mut sub.returns) {
            sub.patch(j, end);
        }
        sub.span = span;
        sub.emit(Op::Ret);
        let code = self.out.codes.len() as u32;
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
        });
        (code, sub.temp_max)
    }

    /// A duration: a constant TIME expression or a TIME variable.
    fn duration(&mut self, f: &Fcx, e: &Expr) -> Option<Duration> {
        let time = TypeTable::elem(ElemType::Time);
        let mut scratch = Fcx::new(f.pou, f.temp_base);
        let v = self.expr(&mut scratch, e, Some(time));
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
        match (&v, scratch.ops.as_slice()) {
            (Val::Const(Const::Bits(b), _), _) => Some(Duration::Const(*b as i64)),
            (Val::Slot(s, _), []) => Some(Duration::Frame(*s)),
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
    fn priority(&mut self, f: &Fcx, e: &Expr) -> u64 {
        let mut scratch = Fcx::new(f.pou, f.temp_base);
        let v = self.expr(&mut scratch, e, None);
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

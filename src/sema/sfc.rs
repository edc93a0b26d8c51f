//! Textual SFC bodies in the declaration phase, and what the layout and
//! the emission (`sfc_emit`) share: the chart's names in the order both
//! agree on, and the layout of the hidden chart-state region.
//!
//! Layout (called from `layout_pou`) gives every step a step record and
//! every ACTION a control record as members of the POU, and reserves one
//! hidden region for the rest of the chart state.

use super::declare::Declarer;
use super::model::{Storage, VarInfo};
use crate::elementary::ElemType;
use crate::ir::chart::{action_layout, header};
use crate::ir::type_table::{Member, MemberKind, Retention, TypeDef, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Ident, Pou, SfcElement, Stmt};
use indexmap::IndexMap;

/// Key of the hidden chart-state variable (not a valid identifier).
pub(super) const HIDDEN: &str = "$SFC";

/// Names of a chart body, in the order the layout and the emission agree on.
pub(super) struct Names<'a> {
    pub(super) steps: Vec<&'a crate::syntax::ast::Step>,
    pub(super) actions: Vec<&'a crate::syntax::ast::Action>,
    pub(super) transitions: Vec<&'a crate::syntax::ast::Transition>,
    pub(super) statements: Vec<Stmt>,
    /// Names associated with steps that are not ACTIONs (candidate BOOL
    /// variables), by key, with the first association's span.
    pub(super) var_actions: IndexMap<String, (Ident, Span)>,
    /// Forcing orders of partial grafcets (`G1(F, X8)`, `G1(FREEZE)`),
    /// with the step that holds each (see `grafcet_forcing`).
    pub(super) forcings: Vec<(&'a Ident, &'a crate::syntax::ast::ActionAssociation)>,
}

/// Sorts the elements of a chart body by kind.
pub(super) fn names(elems: &[SfcElement]) -> Names<'_> {
    let mut n = Names {
        steps: Vec::new(),
        actions: Vec::new(),
        transitions: Vec::new(),
        statements: Vec::new(),
        var_actions: IndexMap::new(),
        forcings: Vec::new(),
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
            if super::grafcet_forcing::is_forcing(a) {
                n.forcings.push((&s.name, a));
            } else if !action_keys.contains(&key) {
                n.var_actions
                    .entry(key)
                    .or_insert((a.action.clone(), a.span));
            }
        }
    }
    n
}

/// Offsets of the parts of the hidden region, relative to its start.
pub(super) struct Hidden {
    pub(super) active: u32,
    pub(super) live: u32,
    pub(super) cache: u32,
    pub(super) scratch: u32,
    pub(super) records: u32,
    pub(super) size: u32,
}

/// Lays out the hidden chart-state region.
pub(super) fn hidden_layout(
    steps: u32,
    actions: u32,
    transitions: u32,
    var_actions: u32,
) -> Hidden {
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
                        retain: Retention::Inherit,
                    },
                    Member {
                        name: "A".into(),
                        ty: TypeTable::elem(ElemType::Bool),
                        offset: action_layout::A,
                        kind: MemberKind::Field,
                        constant: false,
                        retain: Retention::Inherit,
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
                retain: Retention::Inherit,
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
            },
        );
        *offset += h.size;
    }
}

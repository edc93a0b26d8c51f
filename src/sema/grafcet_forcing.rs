//! Forcing orders of partial grafcets (IEC 60848), written as step
//! associations: `G1(F, X8)` is `F/G1:{X8}`, `G1(F)` is `F/G1:{}` and
//! `G1(FREEZE)` is `F/G1:{*}`, where `G1` is a FUNCTION_BLOCK instance of
//! the POU whose body is a chart (the partial grafcet) and `X8` one of its
//! steps. Only under IEC 60848 evolution (`--grafcet`); see docs/grafcet.md.

use super::body::BodyBuilder;
use super::model::{Storage, VarInfo};
use super::sfc::{HIDDEN, Names};
use crate::ir::chart::{Forcing, ForcingOrder, InstanceAt};
use crate::ir::type_table::{MemberKind, TypeKind};
use crate::syntax::ast::ActionAssociation;
use std::collections::HashMap;

/// Qualifier of a forcing order into a given situation.
const FORCE: &str = "F";
/// Qualifier of a freezing order (forcing into the current situation).
const FREEZE: &str = "FREEZE";

/// Is this association a forcing order (qualifier `F` or `FREEZE`)?
pub(super) fn is_forcing(a: &ActionAssociation) -> bool {
    a.qualifier
        .as_ref()
        .is_some_and(|q| matches!(q.key().as_str(), FORCE | FREEZE))
}

/// What the checker knows of a forced instance.
struct Target {
    instance: InstanceAt,
    header: u32,
    /// Step keys of the forced chart, in its step order, with their records.
    steps: Vec<(String, u32)>,
    /// The forced POU's name.
    pou: String,
}

impl BodyBuilder<'_> {
    /// The forcing orders of the chart, checked (E630-E634).
    pub(super) fn chart_forcings(
        &mut self,
        n: &Names,
        step_index: &HashMap<String, u32>,
    ) -> Vec<Forcing> {
        let mut out = Vec::new();
        for &(step, a) in &n.forcings {
            if !self.model.grafcet {
                self.diags.error(
                    "E630",
                    a.span,
                    format!(
                        "`{}` is a forcing order of a partial grafcet: forcing orders need IEC 60848 evolution (`--grafcet`)",
                        a.action.name
                    ),
                );
                continue;
            }
            let Some(&step) = step_index.get(&step.key()) else {
                continue;
            };
            if let Some(f) = self.forcing(step, a) {
                out.push(f);
            }
        }
        out
    }

    /// One forcing order held by step `step`.
    fn forcing(&mut self, step: u32, a: &ActionAssociation) -> Option<Forcing> {
        let freeze = a.qualifier.as_ref().is_some_and(|q| q.key() == FREEZE);
        if let Some(d) = &a.duration {
            self.diags.error(
                "E633",
                d.span,
                "a forcing order takes step names only (`G(F, X1, X2)`, `G(F)` or `G(FREEZE)`)",
            );
            return None;
        }
        if freeze && !a.indicators.is_empty() {
            self.diags.error(
                "E633",
                a.indicators[0].span,
                "`FREEZE` keeps the current situation and takes no steps (`G(FREEZE)`)",
            );
            return None;
        }
        let target = self.forced_target(a)?;
        let order = if freeze {
            ForcingOrder::Freeze
        } else {
            let mut situation = Vec::new();
            for id in &a.indicators {
                match target.steps.iter().position(|(k, _)| *k == id.key()) {
                    Some(i) => situation.push(i as u32),
                    None => {
                        self.diags.error(
                            "E632",
                            id.span,
                            format!(
                                "the partial grafcet `{}` (a `{}`) has no step `{}`",
                                a.action.name, target.pou, id.name
                            ),
                        );
                        return None;
                    }
                }
            }
            situation.sort_unstable();
            situation.dedup();
            ForcingOrder::Situation(situation)
        };
        Some(Forcing {
            step,
            instance: target.instance,
            header: target.header,
            steps: target.steps.into_iter().map(|(_, rec)| rec).collect(),
            order,
        })
    }

    /// The FUNCTION_BLOCK instance named by a forcing order, whose body
    /// must be a chart (E631 otherwise; E634 for a VAR_IN_OUT).
    fn forced_target(&mut self, a: &ActionAssociation) -> Option<Target> {
        let id = &a.action;
        let Some(var) = self.lookup_var(&id.key()).cloned() else {
            self.diags.error(
                "E631",
                id.span,
                format!(
                    "unknown partial grafcet `{}`: declare an instance of a FUNCTION_BLOCK whose body is a chart",
                    id.name
                ),
            );
            return None;
        };
        let VarInfo { ty, storage, .. } = var;
        let target = self.model.pous.iter().position(|p| p.ty == ty).filter(|_| {
            matches!(
                self.types.get(ty).kind,
                TypeKind::Pou { program: false, .. }
            )
        });
        let chart = target.and_then(|t| {
            let pou = &self.model.pous[t];
            match pou.vars.get(HIDDEN).map(|v| v.storage) {
                Some(Storage::Frame(h)) => Some((t, h)),
                _ => None,
            }
        });
        let Some((t, header)) = chart else {
            self.diags.error(
                "E631",
                id.span,
                format!(
                    "`{}` is not a partial grafcet: only an instance of a FUNCTION_BLOCK whose body is a chart can be forced",
                    id.name
                ),
            );
            return None;
        };
        let instance = match storage {
            Storage::Frame(o) => InstanceAt::Frame(o),
            Storage::Abs(at) => InstanceAt::Abs(at),
            Storage::Ref(_) => {
                self.diags.error(
                    "E634",
                    id.span,
                    format!(
                        "`{}` is a VAR_IN_OUT: a forced partial grafcet must be an instance declared in VAR or VAR_GLOBAL",
                        id.name
                    ),
                );
                return None;
            }
        };
        let pou = &self.model.pous[t];
        let steps = pou
            .vars
            .iter()
            .filter_map(|(k, v)| match (v.kind, v.storage) {
                (MemberKind::Step, Storage::Frame(rec)) => Some((k.clone(), rec)),
                _ => None,
            })
            .collect();
        Some(Target {
            instance,
            header,
            steps,
            pou: pou.name.clone(),
        })
    }
}

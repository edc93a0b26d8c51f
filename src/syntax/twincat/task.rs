//! A `.TcTTO` task: `<Task Name>` with `<CycleTime>` (microseconds),
//! `<Priority>` and a `<PouCall>` per program it runs. It becomes
//! `CONFIGURATION PLC TASK name (INTERVAL := T#<n>us, PRIORITY := p);
//! PROGRAM prog WITH name : prog; ... END_CONFIGURATION`, each word placed
//! at the element it comes from; the program instance takes the program's
//! own name, as TwinCAT's online view names it.

use super::codes;
use crate::syntax::plcopen::emit::{Emitter, Range, child, elements, is_identifier};
use crate::syntax::plcopen::raw::content_range;
use roxmltree::Node;

/// Longest cycle accepted, in microseconds (an hour; TwinCAT's own limit is
/// far below).
const MAX_CYCLE_US: u64 = 3_600_000_000;

/// The trimmed text of element `name` under `node`, with its range.
fn setting<'a>(node: Node<'a, '_>, name: &str) -> Option<(&'a str, Range)> {
    let c = child(node, name)?;
    let text = c.text()?;
    let (s, e) = content_range(node.document().input_text(), c.range())?;
    let lead = text.len() - text.trim_start().len();
    let trimmed = text.trim();
    Some((trimmed, (s + lead, (s + lead + trimmed.len()).min(e))))
}

/// Emits the configuration a `<Task>` stands for.
pub(super) fn task(em: &mut Emitter, node: Node) {
    let at = em.at(node);
    let Some(name) = em.required_name(node, "Name") else {
        return;
    };
    let Some((cycle, cycle_at)) = setting(node, "CycleTime") else {
        em.error(
            codes::MISSING,
            at,
            format!("task `{name}` has no `<CycleTime>`: plcrun runs cyclic tasks"),
        );
        return;
    };
    let cycle_us = match cycle.parse::<u64>() {
        Ok(n) if (1..=MAX_CYCLE_US).contains(&n) => n,
        _ => {
            em.error(
                codes::BAD_TASK_SETTING,
                cycle_at,
                format!(
                    "the cycle time of task `{name}` is `{cycle}`: a whole number of microseconds from 1 to {MAX_CYCLE_US} is expected"
                ),
            );
            return;
        }
    };
    let priority = match setting(node, "Priority") {
        None => None,
        Some((p, p_at)) => match p.parse::<u16>() {
            Ok(n) => Some((n, p_at)),
            Err(_) => {
                em.error(
                    codes::BAD_TASK_SETTING,
                    p_at,
                    format!(
                        "the priority of task `{name}` is `{p}`: a whole number from 0 to 65535 is expected"
                    ),
                );
                return;
            }
        },
    };
    let name_at = em.attr_range(node, "Name").unwrap_or(at);
    em.synth("CONFIGURATION PLC TASK", at);
    em.ident(name, name_at);
    em.synth(&format!("( INTERVAL := T#{cycle_us}us"), cycle_at);
    if let Some((p, p_at)) = priority {
        em.synth(&format!(", PRIORITY := {p}"), p_at);
    }
    em.synth(");", at);
    for call in elements(node).filter(|c| c.tag_name().name() == "PouCall") {
        let Some((program, program_at)) = setting(call, "Name") else {
            em.error(
                codes::MISSING,
                em.at(call),
                "a `<PouCall>` names its program in `<Name>`",
            );
            continue;
        };
        if !is_identifier(program) {
            em.error(
                codes::BAD_TASK_SETTING,
                program_at,
                format!("`{program}` is not the name of a PROGRAM"),
            );
            continue;
        }
        em.synth("PROGRAM", em.at(call));
        em.ident(program, program_at);
        em.synth("WITH", em.at(call));
        em.ident(name, name_at);
        em.synth(":", em.at(call));
        em.ident(program, program_at);
        em.synth(";", em.end_of(call));
    }
    em.synth("END_CONFIGURATION", em.end_of(node));
}

//! Reads an SFC POU as drawn: the chart's elements (steps, transitions
//! with their conditions, divergences, convergences, jumps, action
//! blocks with their associations) among the FBD/LD elements of the same
//! `<SFC>`, and the POU's named actions and transitions with their
//! bodies.

use super::model::{
    ActionTarget, Association, ChartBody, Condition, ConditionKind, ElementKind, NamedBody,
};
use super::read::{named, point, point_in, point_out, read_body, read_diagram};
use crate::syntax::plcopen::body::SFC_STATEMENTS_DATA;
use crate::syntax::plcopen::emit::{child, elements, is_true};
use roxmltree::Node;

/// The kind of a chart element; `None` for what is not one.
pub fn chart_kind(node: Node) -> Result<Option<ElementKind>, String> {
    let attr = |a: &str| node.attribute(a).unwrap_or("").trim().to_string();
    Ok(Some(match node.tag_name().name() {
        "step" => ElementKind::Step {
            name: attr("name"),
            initial: is_true(node.attribute("initialStep")),
        },
        "transition" => ElementKind::Transition {
            priority: node.attribute("priority").map(|p| p.trim().to_string()),
            condition: condition(child(node, "condition"))?,
        },
        "selectionDivergence" => ElementKind::SelectionDivergence,
        "selectionConvergence" => ElementKind::SelectionConvergence,
        "simultaneousDivergence" => ElementKind::SimultaneousDivergence,
        "simultaneousConvergence" => ElementKind::SimultaneousConvergence,
        "jumpStep" => ElementKind::JumpStep(attr("targetName")),
        "actionBlock" => ElementKind::ActionBlock(
            named(node, "action")
                .map(association)
                .collect::<Result<_, _>>()?,
        ),
        _ => return Ok(None),
    }))
}

/// The first element child that is not documentation.
fn content<'a, 'i>(node: Node<'a, 'i>) -> Option<Node<'a, 'i>> {
    elements(node).find(|c| !matches!(c.tag_name().name(), "documentation" | "addData"))
}

/// A transition's `<condition>`.
fn condition(node: Option<Node>) -> Result<Condition, String> {
    let Some(node) = node else {
        return Ok(Condition {
            negated: false,
            kind: ConditionKind::Missing,
        });
    };
    let kind = match content(node) {
        None => ConditionKind::Missing,
        Some(c) => match c.tag_name().name() {
            "reference" => {
                ConditionKind::Reference(c.attribute("name").unwrap_or("").trim().to_string())
            }
            "inline" => ConditionKind::Inline {
                name: c.attribute("name").unwrap_or("").to_string(),
                body: inline_body(c)?,
            },
            "connectionPointIn" => ConditionKind::Wired(point_in(c)),
            other => return Err(format!("`<{other}>` in a `<condition>`")),
        },
    };
    Ok(Condition {
        negated: is_true(node.attribute("negated")),
        kind,
    })
}

/// The body of an `<inline>` element.
fn inline_body(inline: Node) -> Result<super::model::BodyModel, String> {
    let lang = content(inline).ok_or("an empty `<inline>` body")?;
    read_body(lang)
}

/// One `<action>` of an action block.
fn association(node: Node) -> Result<Association, String> {
    let text = |a: &str| node.attribute(a).map(str::to_string);
    let action = if let Some(r) = child(node, "reference") {
        ActionTarget::Reference(r.attribute("name").unwrap_or("").trim().to_string())
    } else if let Some(i) = child(node, "inline") {
        ActionTarget::Inline(inline_body(i)?)
    } else {
        ActionTarget::Missing
    };
    Ok(Association {
        id: text("localId"),
        qualifier: text("qualifier"),
        duration: text("duration"),
        indicator: text("indicator"),
        rel: child(node, "relPosition").map(point),
        action,
        output: child(node, "connectionPointOut").map(point_out),
    })
}

/// The `<action>`s or `<transition>`s (`item`) of a POU's list `list`.
fn named_bodies(
    pou: Node,
    list: &'static str,
    item: &'static str,
) -> Result<Vec<NamedBody>, String> {
    let mut out = Vec::new();
    for l in named(pou, list) {
        for c in named(l, item) {
            let body = match child(c, "body").and_then(content) {
                Some(lang) => Some(read_body(lang)?),
                None => None,
            };
            out.push(NamedBody {
                name: c.attribute("name").unwrap_or("").trim().to_string(),
                body,
            });
        }
    }
    Ok(out)
}

/// The SFC POU `pou` whose `<body>` is `body` and chart `sfc`.
pub fn read_chart(pou: Node, body: Node, sfc: Node) -> Result<ChartBody, String> {
    let statements = named(body, "addData")
        .flat_map(|a| named(a, "data"))
        .filter(|d| d.attribute("name") == Some(SFC_STATEMENTS_DATA))
        .find_map(content)
        .map(super::read::body_text);
    Ok(ChartBody {
        chart: read_diagram(sfc)?,
        actions: named_bodies(pou, "actions", "action")?,
        transitions: named_bodies(pou, "transitions", "transition")?,
        statements,
    })
}

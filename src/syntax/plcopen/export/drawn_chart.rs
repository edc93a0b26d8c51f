//! Export of an SFC POU read from PLCopen XML, as drawn ([`ChartBody`]):
//! its named actions and transitions with their bodies, then the
//! `<SFC>` body (chart elements with their conditions and action blocks,
//! among the FBD/LD elements wired to them) and plcrun's plain statements.

use super::super::body::SFC_STATEMENTS_DATA;
use super::super::diagram::{
    ActionTarget, Association, BodyModel, ChartBody, Condition, ConditionKind, NamedBody,
};
use super::graphic::{body_model, diagram, empty_owned, open_owned, point_attrs, point_in};
use super::writer::Writer;

/// `<actions>`, `<transitions>` and the `<body>` of a chart POU.
pub fn chart_pou(w: &mut Writer, c: &ChartBody) {
    named_list(w, "actions", "action", &c.actions);
    named_list(w, "transitions", "transition", &c.transitions);
    w.open("body", &[]);
    diagram(w, &c.chart);
    if let Some(text) = &c.statements {
        w.open("addData", &[]);
        w.open(
            "data",
            &[
                ("name", SFC_STATEMENTS_DATA),
                ("handleUnknown", "implementation"),
            ],
        );
        w.text_body("ST", text);
        w.close("data");
        w.close("addData");
    }
    w.close("body");
}

/// A list of named actions or transitions (nothing when empty).
fn named_list(w: &mut Writer, list: &str, item: &str, bodies: &[NamedBody]) {
    if bodies.is_empty() {
        return;
    }
    w.open(list, &[]);
    for b in bodies {
        w.open(item, &[("name", &b.name)]);
        if let Some(body) = &b.body {
            w.open("body", &[]);
            body_model(w, body);
            w.close("body");
        }
        w.close(item);
    }
    w.close(list);
}

/// A transition's `<condition>`.
pub fn condition(w: &mut Writer, c: &Condition) {
    let attrs: &[(&str, &str)] = if c.negated {
        &[("negated", "true")]
    } else {
        &[]
    };
    match &c.kind {
        ConditionKind::Missing => return,
        ConditionKind::Reference(name) => {
            w.open("condition", attrs);
            w.empty("reference", &[("name", name)]);
        }
        ConditionKind::Inline { name, body } => {
            w.open("condition", attrs);
            inline(w, Some(name), body);
        }
        ConditionKind::Wired(p) => {
            w.open("condition", attrs);
            point_in(w, p);
        }
    }
    w.close("condition");
}

/// `<inline [name]>` with its body.
fn inline(w: &mut Writer, name: Option<&str>, body: &BodyModel) {
    match name {
        Some(n) => w.open("inline", &[("name", n)]),
        None => w.open("inline", &[]),
    }
    body_model(w, body);
    w.close("inline");
}

/// The `<action>`s of an action block.
pub fn associations(w: &mut Writer, list: &[Association]) {
    for a in list {
        let mut attrs: Vec<(&'static str, String)> = Vec::new();
        for (name, value) in [
            ("localId", &a.id),
            ("qualifier", &a.qualifier),
            ("duration", &a.duration),
            ("indicator", &a.indicator),
        ] {
            if let Some(v) = value {
                attrs.push((name, v.clone()));
            }
        }
        open_owned(w, "action", &attrs);
        if let Some(rel) = a.rel {
            empty_owned(w, "relPosition", &point_attrs(rel));
        }
        match &a.action {
            ActionTarget::Reference(name) => w.empty("reference", &[("name", name)]),
            ActionTarget::Inline(body) => inline(w, None, body),
            ActionTarget::Missing => {}
        }
        if let Some(p) = &a.output {
            super::graphic::point_out(w, p);
        }
        w.close("action");
    }
}

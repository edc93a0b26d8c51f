//! `<instances><configurations>`: configurations, resources, tasks and
//! program instances.

use super::body::add_data;
use super::emit::{Emitter, elements};
use super::interface::var_section;
use roxmltree::Node;

/// `<instances>`: each `<configuration>` as `CONFIGURATION ... END_CONFIGURATION`.
pub fn instances(em: &mut Emitter, node: Node) {
    for c in elements(node) {
        match c.tag_name().name() {
            "configurations" => {
                for conf in elements(c) {
                    match conf.tag_name().name() {
                        "configuration" => configuration(em, conf),
                        "documentation" => {}
                        "addData" => add_data(em, conf),
                        _ => em.unknown(conf, "configurations"),
                    }
                }
            }
            "documentation" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, "instances"),
        }
    }
}

/// `<configuration name>`: globals first, then resources.
fn configuration(em: &mut Emitter, node: Node) {
    em.synth("CONFIGURATION", em.at(node));
    em.name(node, "name");
    for c in elements(node) {
        match c.tag_name().name() {
            "globalVars" => var_section(em, c),
            "resource" | "documentation" => {}
            "addData" => add_data(em, c),
            "accessVars" => em.refuse(c, "VAR_ACCESS is not supported"),
            "configVars" => {}
            _ => em.unknown(c, "configuration"),
        }
    }
    for r in elements(node).filter(|c| c.tag_name().name() == "resource") {
        resource(em, r);
    }
    // After the resources: its paths name their program instances.
    for v in elements(node).filter(|c| c.tag_name().name() == "configVars") {
        super::config_vars::config_vars(em, v);
    }
    em.synth("END_CONFIGURATION", em.end_of(node));
}

/// `<resource name>`: globals, tasks, then program instances (with and
/// without a task).
fn resource(em: &mut Emitter, node: Node) {
    em.synth("RESOURCE", em.at(node));
    em.name(node, "name");
    for c in elements(node) {
        match c.tag_name().name() {
            "globalVars" => var_section(em, c),
            "task" | "pouInstance" | "documentation" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, "resource"),
        }
    }
    let tasks: Vec<Node> = elements(node)
        .filter(|c| c.tag_name().name() == "task")
        .collect();
    for &t in &tasks {
        task(em, t);
    }
    for &t in &tasks {
        for p in elements(t) {
            match p.tag_name().name() {
                "pouInstance" => pou_instance(em, p, Some(t)),
                "documentation" => {}
                "addData" => add_data(em, p),
                _ => em.unknown(p, "task"),
            }
        }
    }
    for p in elements(node).filter(|c| c.tag_name().name() == "pouInstance") {
        pou_instance(em, p, None);
    }
    em.synth("END_RESOURCE", em.end_of(node));
}

/// `TASK name (INTERVAL := ..., PRIORITY := ..., SINGLE := ...);`.
fn task(em: &mut Emitter, node: Node) {
    let at = em.at(node);
    em.synth("TASK", at);
    em.name(node, "name");
    em.synth("(", at);
    let mut first = true;
    for (attr, key) in [
        ("single", "SINGLE"),
        ("interval", "INTERVAL"),
        ("priority", "PRIORITY"),
    ] {
        if node.attribute(attr).is_some() {
            if !first {
                em.synth(",", at);
            }
            first = false;
            em.synth(key, at);
            em.synth(":=", at);
            em.lex_attr(node, attr);
        }
    }
    em.synth(");", at);
}

/// `PROGRAM name [WITH task] : Type;`.
fn pou_instance(em: &mut Emitter, node: Node, task: Option<Node>) {
    let at = em.at(node);
    em.synth("PROGRAM", at);
    em.name(node, "name");
    if let Some(t) = task
        && let Some(name) = em.required_name(t, "name")
    {
        em.synth("WITH", at);
        em.ident(name, at);
    }
    em.synth(":", at);
    em.name(node, "typeName");
    em.synth(";", em.end_of(node));
}

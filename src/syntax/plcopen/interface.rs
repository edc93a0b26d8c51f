//! A POU's `<interface>`: the variable sections and their variables.

use super::body::add_data;
use super::emit::{Emitter, elements, is_true};
use super::types::{initial_value, missing_child, type_of};
use roxmltree::Node;

/// The keyword of a TC6 variable section.
fn section_keyword(name: &str) -> Option<&'static str> {
    Some(match name {
        "inputVars" => "VAR_INPUT",
        "outputVars" => "VAR_OUTPUT",
        "inOutVars" => "VAR_IN_OUT",
        "externalVars" => "VAR_EXTERNAL",
        "globalVars" => "VAR_GLOBAL",
        "localVars" => "VAR",
        "tempVars" => "VAR_TEMP",
        _ => return None,
    })
}

/// Every variable section of `<interface>` (the return type is read by
/// the POU).
pub fn interface(em: &mut Emitter, node: Node) {
    for c in elements(node) {
        match c.tag_name().name() {
            "returnType" | "documentation" => {}
            // CODESYS's EXTENDS/IMPLEMENTS there are read with the header.
            "addData" => super::codesys_members::other_data(em, c),
            "accessVars" => em.refuse(c, "VAR_ACCESS is not supported"),
            name if section_keyword(name).is_some() => var_section(em, c),
            _ => em.unknown(c, "interface"),
        }
    }
}

/// One section: `VAR_INPUT [CONSTANT] [RETAIN|NON_RETAIN|PERSISTENT] ... END_VAR`.
pub fn var_section(em: &mut Emitter, node: Node) {
    let at = em.at(node);
    let Some(keyword) = section_keyword(node.tag_name().name()) else {
        em.unknown(node, "interface");
        return;
    };
    em.synth(keyword, at);
    if is_true(node.attribute("constant")) {
        em.synth("CONSTANT", at);
    }
    if is_true(node.attribute("persistent")) {
        em.synth("PERSISTENT", at);
    } else if is_true(node.attribute("retain")) {
        em.synth("RETAIN", at);
    } else if is_true(node.attribute("nonretain")) {
        em.synth("NON_RETAIN", at);
    }
    for v in elements(node) {
        match v.tag_name().name() {
            "variable" => variable(em, v),
            "documentation" => {}
            "addData" => add_data(em, v),
            _ => em.unknown(v, node.tag_name().name()),
        }
    }
    em.synth("END_VAR", em.end_of(node));
}

/// `<variable name address><type/><initialValue/></variable>`:
/// `name [AT address] : type [:= value];`.
pub fn variable(em: &mut Emitter, node: Node) {
    em.name(node, "name");
    declaration_tail(em, node, "variable");
}

/// What follows a declared name in a `<variable>` or `<configVariable>`:
/// `[AT address] : type [:= value];` (`what` names the element in the
/// message about an unknown child).
pub fn declaration_tail(em: &mut Emitter, node: Node, what: &str) {
    if node.attribute("address").is_some() {
        em.synth("AT", em.at(node));
        em.lex_attr(node, "address");
    }
    em.synth(":", em.at(node));
    let mut typed = false;
    let mut init = None;
    for c in elements(node) {
        match c.tag_name().name() {
            "type" => {
                type_of(em, c);
                typed = true;
            }
            "initialValue" => init = Some(c),
            "documentation" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, what),
        }
    }
    if !typed {
        missing_child(em, node, "type");
    }
    if let Some(init) = init {
        em.synth(":=", em.at(init));
        initial_value(em, init);
    }
    em.synth(";", em.end_of(node));
}

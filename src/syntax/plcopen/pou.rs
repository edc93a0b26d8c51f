//! One `<pou>`: header, interface, body, and the actions and named
//! transitions an SFC body refers to.

use super::body;
use super::codes;
use super::codesys_members;
use super::emit::{Emitter, child, elements};
use super::interface::interface;
use super::types::{missing_child, type_of};
use roxmltree::Node;

/// `<pou name pouType>` as `PROGRAM name ... END_PROGRAM` (or FUNCTION,
/// FUNCTION_BLOCK).
pub fn pou(em: &mut Emitter, node: Node) {
    let at = em.at(node);
    let (open, close) = match node.attribute("pouType") {
        Some("program") => ("PROGRAM", "END_PROGRAM"),
        Some("function") => ("FUNCTION", "END_FUNCTION"),
        Some("functionBlock") => ("FUNCTION_BLOCK", "END_FUNCTION_BLOCK"),
        Some(other) => {
            let range = em.attr_range(node, "pouType").unwrap_or(at);
            em.error(
                codes::REFUSED,
                range,
                format!("pouType `{other}` is not supported: expected program, function or functionBlock"),
            );
            return;
        }
        None => {
            em.missing(node, "pouType");
            return;
        }
    };
    em.synth(open, at);
    em.name(node, "name");
    let iface = child(node, "interface");
    if let Some(i) = iface {
        codesys_members::inheritance(em, i);
    }
    if let Some(ret) = iface.and_then(|i| child(i, "returnType")) {
        em.synth(":", em.at(ret));
        type_of(em, ret);
    }
    let mut bodies = Vec::new();
    let mut members = Vec::new();
    for c in elements(node) {
        match c.tag_name().name() {
            "interface" => interface(em, c),
            "body" => bodies.push(c),
            "actions" | "transitions" | "documentation" => {}
            "addData" => {
                members.extend(elements(c).filter(|d| codesys_members::is_member(*d)));
                codesys_members::other_data(em, c);
            }
            _ => em.unknown(c, "pou"),
        }
    }
    // CODESYS V3's methods and properties, between the variables and the
    // body as in ST; a FUNCTION has none.
    for data in members {
        if open == "FUNCTION" {
            em.refuse(data, "a method or property of a FUNCTION");
        } else {
            codesys_members::member(em, data);
        }
    }
    match bodies.as_slice() {
        [body] => body::pou_body(em, node, *body),
        [] => missing_child(em, node, "body"),
        [_, extra, ..] => em.refuse(*extra, "a POU with several bodies"),
    }
    em.synth(close, em.end_of(node));
}

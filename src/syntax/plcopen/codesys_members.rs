//! CODESYS V3's methods and properties in a PLCopen export. TC6 XML has
//! no place for them, so CODESYS writes each one in the `<addData>` of its
//! POU: `<data name=".../plcopenxml/method">` holding a `<Method>` with its
//! own `<interface>` and `<body>`, and `<data name=".../plcopenxml/property">`
//! holding a `<Property>` with a `<GetAccessor>` and a `<SetAccessor>`.
//! They are emitted as the textual `METHOD ... END_METHOD` and
//! `PROPERTY ... END_PROPERTY` of the block, before its body, so the ST
//! parser and the checker treat them as in a `.st` file.

use super::body::{add_data_except, text_body};
use super::emit::{Emitter, child, elements, is_true};
use super::interface::interface;
use super::types::{missing_child, type_of};
use crate::syntax::token::{Kw, Tok};
use roxmltree::Node;

/// The `<data>` name of a method.
const METHOD_DATA: &str = "http://www.3s-software.com/plcopenxml/method";
/// The `<data>` name of a property.
const PROPERTY_DATA: &str = "http://www.3s-software.com/plcopenxml/property";
/// The `<data>` name of a block's `EXTENDS` and `IMPLEMENTS`.
const INHERITANCE_DATA: &str = "http://www.3s-software.com/plcopenxml/pouinheritance";
/// The `<data>` name of a member's access modifiers.
const ACCESS_DATA: &str = "http://www.3s-software.com/plcopenxml/accessmodifiers";

/// True for a `<data>` holding a method or a property.
pub fn is_member(data: Node) -> bool {
    data.tag_name().name() == "data"
        && matches!(data.attribute("name"), Some(METHOD_DATA | PROPERTY_DATA))
}

/// `EXTENDS base` and `IMPLEMENTS i, j` of a block, from the
/// `<Inheritance>` CODESYS writes in the `<addData>` of its `<interface>`
/// (emitted right after the block's name, where the header has them).
pub fn inheritance(em: &mut Emitter, iface: Node) {
    let Some(add) = child(iface, "addData") else {
        return;
    };
    let found = elements(add)
        .filter(|d| d.attribute("name") == Some(INHERITANCE_DATA))
        .flat_map(elements)
        .filter(|i| i.tag_name().name() == "Inheritance");
    for inh in found {
        let mut implements = 0;
        for c in elements(inh) {
            let keyword = match c.tag_name().name() {
                "Extends" => "EXTENDS",
                "Implements" if implements == 0 => "IMPLEMENTS",
                "Implements" => ",",
                _ => {
                    em.unknown(c, "Inheritance");
                    continue;
                }
            };
            implements += usize::from(keyword != "EXTENDS");
            em.synth(keyword, em.at(c));
            let name = c.text().unwrap_or("").trim();
            if name.is_empty() {
                missing_child(em, c, "name");
            } else {
                em.ident(name, em.at(c));
            }
        }
    }
}

/// True for a `<data>` this module reads (members, inheritance), which
/// the generic `<addData>` reader must leave alone.
fn is_codesys_object(data: Node) -> bool {
    is_member(data) || data.attribute("name") == Some(INHERITANCE_DATA)
}

/// Emits the method or property of one `<data>` ([`is_member`]).
pub fn member(em: &mut Emitter, data: Node) {
    for c in elements(data) {
        match c.tag_name().name() {
            "Method" => method(em, c),
            "Property" => property(em, c),
            _ => em.unknown(c, "data"),
        }
    }
}

/// `<Method name>`: `METHOD [modifiers] name [: type] sections body END_METHOD`.
fn method(em: &mut Emitter, node: Node) {
    em.synth("METHOD", em.at(node));
    modifiers(em, node);
    em.name(node, "name");
    let iface = child(node, "interface");
    if let Some(ret) = iface.and_then(|i| child(i, "returnType")) {
        em.synth(":", em.at(ret));
        type_of(em, ret);
    }
    if let Some(i) = iface {
        interface(em, i);
    }
    member_body(em, node);
    em.synth("END_METHOD", em.end_of(node));
}

/// `<Property name>`: `PROPERTY [modifiers] name : type`, then a `GET` and
/// a `SET` section for the accessors present, `END_PROPERTY`.
fn property(em: &mut Emitter, node: Node) {
    em.synth("PROPERTY", em.at(node));
    modifiers(em, node);
    em.name(node, "name");
    match child(node, "interface").and_then(|i| child(i, "returnType")) {
        Some(ret) => {
            em.synth(":", em.at(ret));
            type_of(em, ret);
        }
        None => missing_child(em, node, "interface><returnType"),
    }
    for c in elements(node) {
        let (open, close) = match c.tag_name().name() {
            "GetAccessor" => (Kw::Get, "END_GET"),
            "SetAccessor" => (Kw::Set, "END_SET"),
            "interface" | "documentation" => continue,
            "addData" => {
                access_free_add_data(em, c);
                continue;
            }
            _ => {
                em.unknown(c, "Property");
                continue;
            }
        };
        // `GET` and `SET` are keywords only where they open an accessor,
        // which the textual lexer decides from context: say it here.
        let span = em.span(em.at(c));
        em.toks
            .push((span.start as usize, Tok::Kw(open), span.end as usize));
        modifiers(em, c);
        if let Some(i) = child(c, "interface") {
            interface(em, i);
        }
        member_body(em, c);
        em.synth(close, em.end_of(c));
    }
    em.synth("END_PROPERTY", em.end_of(node));
}

/// The `<body>` of a method or accessor: ST or IL text. Its other
/// children (`<addData>` aside, read by [`modifiers`]) are unknown.
fn member_body(em: &mut Emitter, node: Node) {
    for c in elements(node) {
        match c.tag_name().name() {
            "interface" | "documentation" => {}
            "addData" => access_free_add_data(em, c),
            "body" => match elements(c).find(|l| matches!(l.tag_name().name(), "ST" | "IL")) {
                Some(lang) => text_body(em, lang),
                None => em.refuse(c, "a method or accessor body that is not ST or IL"),
            },
            _ => em.unknown(c, node.tag_name().name()),
        }
    }
    if child(node, "body").is_none() {
        missing_child(em, node, "body");
    }
}

/// The access modifiers CODESYS writes in a member's `<addData>`
/// (`<AccessModifiers Private="true"/>`), as keywords.
fn modifiers(em: &mut Emitter, node: Node) {
    let Some(add) = child(node, "addData") else {
        return;
    };
    for data in elements(add).filter(|d| d.attribute("name") == Some(ACCESS_DATA)) {
        for m in elements(data).filter(|m| m.tag_name().name() == "AccessModifiers") {
            for (attr, keyword) in [
                ("Private", "PRIVATE"),
                ("Protected", "PROTECTED"),
                ("Internal", "INTERNAL"),
                ("Public", "PUBLIC"),
            ] {
                if is_true(m.attribute(attr)) {
                    em.synth(keyword, em.at(m));
                }
            }
        }
    }
}

/// A member's `<addData>` without its access modifiers (read by
/// [`modifiers`]).
fn access_free_add_data(em: &mut Emitter, add: Node) {
    add_data_except(em, add, |d| d.attribute("name") == Some(ACCESS_DATA));
}

/// A POU's or interface's `<addData>` without the methods, properties and
/// inheritance this module emits.
pub fn other_data(em: &mut Emitter, add: Node) {
    add_data_except(em, add, is_codesys_object);
}

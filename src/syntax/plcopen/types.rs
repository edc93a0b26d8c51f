//! Data types: `<dataTypes>` declarations, the type of a variable
//! (`<type>`, `<baseType>`, `<returnType>`) and initial values.

use super::body::add_data;
use super::codes;
use super::emit::{Emitter, child, elements};
use roxmltree::Node;

/// Elementary type elements of TC6 (plus the edition-3 long types), written
/// as the type name of the same spelling.
const ELEMENTARY: [&str; 25] = [
    "BOOL", "BYTE", "WORD", "DWORD", "LWORD", "SINT", "INT", "DINT", "LINT", "USINT", "UINT",
    "UDINT", "ULINT", "REAL", "LREAL", "TIME", "DATE", "DT", "TOD", "LTIME", "LDATE", "LTOD",
    "LDT", "CHAR", "WCHAR",
];

/// Generic type elements of TC6 (`<ANY_NUM/>`): the type of a generic
/// input of a FUNCTION, FUNCTION_BLOCK or METHOD (CODESYS V3), written as
/// the type name of the same spelling.
const GENERIC: [&str; 9] = [
    "ANY",
    "ANY_ELEMENTARY",
    "ANY_MAGNITUDE",
    "ANY_NUM",
    "ANY_REAL",
    "ANY_INT",
    "ANY_BIT",
    "ANY_STRING",
    "ANY_DATE",
];

/// `<dataTypes>`: one `TYPE ... END_TYPE` holding every `<dataType>`.
pub fn data_types(em: &mut Emitter, node: Node) {
    let decls: Vec<Node> = elements(node).collect();
    if !decls.iter().any(|d| d.tag_name().name() == "dataType") {
        return;
    }
    em.synth("TYPE", em.at(node));
    for decl in decls {
        match decl.tag_name().name() {
            "dataType" => data_type(em, decl),
            "documentation" => {}
            "addData" => add_data(em, decl),
            _ => em.unknown(decl, "dataTypes"),
        }
    }
    em.synth("END_TYPE", em.end_of(node));
}

/// `<dataType name="T"><baseType>...</baseType><initialValue/></dataType>`.
fn data_type(em: &mut Emitter, node: Node) {
    em.name(node, "name");
    em.synth(":", em.at(node));
    let mut typed = false;
    let mut init = None;
    for c in elements(node) {
        match c.tag_name().name() {
            "baseType" => {
                type_of(em, c);
                typed = true;
            }
            "initialValue" => init = Some(c),
            "documentation" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, "dataType"),
        }
    }
    if !typed {
        missing_child(em, node, "baseType");
    }
    if let Some(init) = init {
        em.synth(":=", em.at(init));
        initial_value(em, init);
    }
    em.synth(";", em.end_of(node));
}

/// Reports a missing required child element.
pub fn missing_child(em: &mut Emitter, node: Node, name: &str) {
    em.error(
        codes::MISSING_CHILD,
        em.at(node),
        format!("`<{}>` needs a `<{name}>`", node.tag_name().name()),
    );
}

/// A wrapper (`<type>`, `<baseType>`, `<returnType>`) holding one type
/// element.
pub fn type_of(em: &mut Emitter, wrapper: Node) {
    let mut found = false;
    for c in elements(wrapper) {
        match c.tag_name().name() {
            "documentation" => {}
            "addData" => add_data(em, c),
            _ if found => em.unknown(c, wrapper.tag_name().name()),
            _ => {
                found = true;
                type_element(em, c);
            }
        }
    }
    if !found {
        em.error(
            codes::MISSING_CHILD,
            em.at(wrapper),
            format!("`<{}>` holds no type", wrapper.tag_name().name()),
        );
    }
}

/// One type element: elementary, `string`, `array`, `derived`, `enum`,
/// `struct`, `subrangeSigned`/`subrangeUnsigned`.
fn type_element(em: &mut Emitter, node: Node) {
    if em.too_deep(node) {
        return;
    }
    let at = em.at(node);
    let name = node.tag_name().name();
    match name {
        _ if ELEMENTARY.contains(&name) || GENERIC.contains(&name) => em.synth(name, at),
        "string" | "wstring" => {
            em.synth(
                if name == "string" {
                    "STRING"
                } else {
                    "WSTRING"
                },
                at,
            );
            if node.attribute("length").is_some() {
                em.synth("[", at);
                em.lex_attr(node, "length");
                em.synth("]", at);
            }
        }
        "derived" => {
            em.name(node, "name");
        }
        "array" => array(em, node),
        "enum" => enumeration(em, node),
        "struct" => {
            em.synth("STRUCT", at);
            for c in elements(node) {
                match c.tag_name().name() {
                    "variable" => super::interface::variable(em, c),
                    "documentation" => {}
                    "addData" => add_data(em, c),
                    _ => em.unknown(c, "struct"),
                }
            }
            em.synth("END_STRUCT", em.end_of(node));
        }
        "subrangeSigned" | "subrangeUnsigned" => subrange(em, node),
        "pointer" | "reference" => em.refuse(node, "plcrun has no pointer or reference types"),
        _ => em.refuse(node, "not a data type plcrun knows"),
    }
}

/// `<array><dimension lower upper/>...<baseType/></array>`.
fn array(em: &mut Emitter, node: Node) {
    let at = em.at(node);
    em.synth("ARRAY [", at);
    let mut first = true;
    for dim in elements(node).filter(|c| c.tag_name().name() == "dimension") {
        if !first {
            em.synth(",", em.at(dim));
        }
        first = false;
        if dim.attribute("lower") == Some("*") {
            // `ARRAY[*]`: a VAR_IN_OUT taking the argument's bounds.
            em.synth("*", em.at(dim));
            continue;
        }
        em.lex_attr(dim, "lower");
        em.synth("..", em.at(dim));
        em.lex_attr(dim, "upper");
    }
    if first {
        missing_child(em, node, "dimension");
    }
    em.synth("] OF", at);
    for c in elements(node) {
        match c.tag_name().name() {
            "dimension" | "documentation" => {}
            "baseType" => type_of(em, c),
            "addData" => add_data(em, c),
            _ => em.unknown(c, "array"),
        }
    }
    if child(node, "baseType").is_none() {
        missing_child(em, node, "baseType");
    }
}

/// `<enum><values><value name="Red" value="1"/></values><baseType/></enum>`.
fn enumeration(em: &mut Emitter, node: Node) {
    if let Some(base) = child(node, "baseType") {
        type_of(em, base);
    }
    em.synth("(", em.at(node));
    let mut first = true;
    for c in elements(node) {
        match c.tag_name().name() {
            "values" => {
                for v in elements(c) {
                    if v.tag_name().name() != "value" {
                        em.unknown(v, "values");
                        continue;
                    }
                    if !first {
                        em.synth(",", em.at(v));
                    }
                    first = false;
                    em.name(v, "name");
                    if v.attribute("value").is_some() {
                        em.synth(":=", em.at(v));
                        em.lex_attr(v, "value");
                    }
                }
            }
            "baseType" | "documentation" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, "enum"),
        }
    }
    if first {
        missing_child(em, node, "values");
    }
    em.synth(")", em.end_of(node));
}

/// `<subrangeSigned><range lower upper/><baseType/></subrangeSigned>`.
fn subrange(em: &mut Emitter, node: Node) {
    match child(node, "baseType") {
        Some(base) => type_of(em, base),
        None => missing_child(em, node, "baseType"),
    }
    em.synth("(", em.at(node));
    match child(node, "range") {
        Some(range) => {
            em.lex_attr(range, "lower");
            em.synth("..", em.at(range));
            em.lex_attr(range, "upper");
        }
        None => missing_child(em, node, "range"),
    }
    em.synth(")", em.end_of(node));
    for c in elements(node) {
        match c.tag_name().name() {
            "range" | "baseType" | "documentation" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, node.tag_name().name()),
        }
    }
}

/// `<initialValue>` (or a `<value>` inside an array or struct value):
/// `simpleValue`, `arrayValue` or `structValue`.
pub fn initial_value(em: &mut Emitter, node: Node) {
    if em.too_deep(node) {
        return;
    }
    let mut found = false;
    for c in elements(node) {
        match c.tag_name().name() {
            "documentation" => continue,
            "addData" => {
                add_data(em, c);
                continue;
            }
            _ if found => {
                em.unknown(c, node.tag_name().name());
                continue;
            }
            "simpleValue" => {
                em.lex_attr(c, "value");
            }
            "arrayValue" => array_value(em, c),
            "structValue" => struct_value(em, c),
            _ => em.unknown(c, node.tag_name().name()),
        }
        found = true;
    }
    if !found {
        em.error(
            codes::MISSING_CHILD,
            em.at(node),
            format!("`<{}>` holds no value", node.tag_name().name()),
        );
    }
}

/// `[v, n(v), ...]`.
fn array_value(em: &mut Emitter, node: Node) {
    em.synth("[", em.at(node));
    let mut first = true;
    for v in elements(node) {
        if v.tag_name().name() != "value" {
            em.unknown(v, "arrayValue");
            continue;
        }
        if !first {
            em.synth(",", em.at(v));
        }
        first = false;
        if v.attribute("repetitionValue").is_some() {
            em.lex_attr(v, "repetitionValue");
            em.synth("(", em.at(v));
            initial_value(em, v);
            em.synth(")", em.end_of(v));
        } else {
            initial_value(em, v);
        }
    }
    em.synth("]", em.end_of(node));
}

/// `(member := v, ...)`.
fn struct_value(em: &mut Emitter, node: Node) {
    em.synth("(", em.at(node));
    let mut first = true;
    for v in elements(node) {
        if v.tag_name().name() != "value" {
            em.unknown(v, "structValue");
            continue;
        }
        if !first {
            em.synth(",", em.at(v));
        }
        first = false;
        em.name(v, "member");
        em.synth(":=", em.at(v));
        initial_value(em, v);
    }
    em.synth(")", em.end_of(node));
}

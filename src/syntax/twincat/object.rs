//! The objects of a TwinCAT file: a POU with its methods, properties and
//! actions, a DUT or GVL (a declaration and nothing else), an interface.

use super::codes;
use crate::syntax::lexer::Spanned;
use crate::syntax::plcopen::emit::{Emitter, Range, child, elements};
use crate::syntax::plcopen::raw::content_range;
use crate::syntax::token::{Kw, Tok};
use roxmltree::Node;

/// The text range inside an element (its CDATA), if it has content.
fn inner(node: Node) -> Option<Range> {
    content_range(node.document().input_text(), node.range())
}

/// Emits the ST of an element's content (a `<Declaration>` or `<ST>`),
/// between line breaks so that line-oriented passes see its lines.
fn text(em: &mut Emitter, node: Node) {
    em.eol(em.at(node));
    if let Some(range) = inner(node) {
        em.lex_range(range, true);
    }
    em.eol(em.end_of(node));
}

/// Emits the `<Declaration>` child of `node`; reports when there is none.
fn declaration(em: &mut Emitter, node: Node) -> bool {
    match child(node, "Declaration") {
        Some(decl) => {
            text(em, decl);
            true
        }
        None => {
            em.error(
                codes::MISSING,
                em.at(node),
                format!(
                    "`<{}>` has no `<Declaration>`: it declares nothing",
                    node.tag_name().name()
                ),
            );
            false
        }
    }
}

/// Elements that carry no code: TwinCAT's line maps, folders, object
/// properties.
fn is_bookkeeping(name: &str) -> bool {
    matches!(
        name,
        "LineIds" | "Folder" | "ObjectProperties" | "Documentation"
    )
}

/// The POU keyword its declaration starts with (after pragmas and line
/// breaks), if it is one.
fn pou_kind(tokens: &[Spanned]) -> Option<Kw> {
    let (_, first, _) = tokens.iter().find(|(_, t, _)| *t != Tok::Eol)?;
    match first {
        Tok::Kw(k @ (Kw::Program | Kw::FunctionBlock | Kw::Function)) => Some(*k),
        _ => None,
    }
}

/// A `<POU>`: its declaration, then its methods, properties and actions
/// (which the textual grammar places before the body), then its body and
/// the closing keyword.
pub(super) fn pou(em: &mut Emitter, node: Node) {
    let before = em.toks.len();
    if !declaration(em, node) {
        return;
    }
    let kind = pou_kind(&em.toks[before..]);
    let end = match kind {
        Some(Kw::Program) => "END_PROGRAM",
        Some(Kw::FunctionBlock) => "END_FUNCTION_BLOCK",
        Some(Kw::Function) => "END_FUNCTION",
        _ => {
            em.error(
                codes::MISSING,
                em.at(node),
                "the declaration of a `<POU>` starts with PROGRAM, FUNCTION_BLOCK or FUNCTION",
            );
            return;
        }
    };
    let mut body = None;
    for c in elements(node) {
        match c.tag_name().name() {
            "Declaration" => {}
            "Implementation" => body = Some(c),
            "Method" => method(em, c),
            "Property" => property(em, c, true),
            "Action" => action(em, c),
            "Transition" => em.error(
                codes::REFUSED,
                em.at(c),
                "`<Transition>` refused: transitions belong to an SFC body, which plcrun does not read from TwinCAT files",
            ),
            name if is_bookkeeping(name) => {}
            name => unknown(em, c, name, "POU"),
        }
    }
    if let Some(b) = body {
        implementation(em, b);
    }
    em.synth(end, em.end_of(node));
}

/// A `<Method>`: declaration, body, `END_METHOD`. In an interface there is
/// no body.
fn method(em: &mut Emitter, node: Node) {
    if !declaration(em, node) {
        return;
    }
    body_of(em, node, "Method");
    em.synth("END_METHOD", em.end_of(node));
}

/// A `<Property>`: its declaration, a `GET ... END_GET` and `SET ...
/// END_SET` for each accessor it has (each with its own declaration and,
/// outside an interface, body), `END_PROPERTY`.
fn property(em: &mut Emitter, node: Node, with_bodies: bool) {
    if !declaration(em, node) {
        return;
    }
    for c in elements(node) {
        let (open, close) = match c.tag_name().name() {
            "Get" => ("GET", "END_GET"),
            "Set" => ("SET", "END_SET"),
            "Declaration" => continue,
            name if is_bookkeeping(name) => continue,
            name => {
                unknown(em, c, name, "Property");
                continue;
            }
        };
        em.synth(open, em.at(c));
        if let Some(decl) = child(c, "Declaration") {
            text(em, decl);
        }
        if with_bodies {
            body_of(em, c, c.tag_name().name());
        }
        em.synth(close, em.end_of(c));
    }
    em.synth("END_PROPERTY", em.end_of(node));
}

/// An `<Action>`: CODESYS and TwinCAT call it like a method of its POU
/// without variables of its own (`fb.Reset();`, `Reset();` inside), which
/// is what it becomes.
fn action(em: &mut Emitter, node: Node) {
    let Some(name) = em.required_name(node, "Name") else {
        return;
    };
    let at = em.attr_range(node, "Name").unwrap_or(em.at(node));
    em.synth("METHOD", em.at(node));
    em.ident(name, at);
    em.eol(at);
    body_of(em, node, "Action");
    em.synth("END_METHOD", em.end_of(node));
}

/// Emits the `<Implementation>` of `node`, if it has one.
fn body_of(em: &mut Emitter, node: Node, what: &str) {
    for c in elements(node) {
        match c.tag_name().name() {
            "Implementation" => implementation(em, c),
            "Declaration" | "Get" | "Set" => {}
            name if is_bookkeeping(name) => {}
            name => unknown(em, c, name, what),
        }
    }
}

/// An `<Implementation>`: ST is read; the graphical languages are refused
/// by name.
fn implementation(em: &mut Emitter, node: Node) {
    for lang in elements(node) {
        match lang.tag_name().name() {
            "ST" => text(em, lang),
            name => {
                let what = match name {
                    "SFC" => "a sequential function chart",
                    "NWL" => "a network list (TwinCAT's IL, LD and FBD)",
                    "CFC" => "a continuous function chart",
                    "FBD" => "a function block diagram",
                    "LD" => "a ladder diagram",
                    "UML" => "a UML diagram",
                    _ => "a body in a language plcrun does not know",
                };
                em.error(
                    codes::REFUSED,
                    em.at(lang),
                    format!(
                        "`<{name}>` body refused: it is {what}; plcrun reads TwinCAT bodies written in ST"
                    ),
                );
            }
        }
    }
}

/// A `<DUT>` or `<GVL>`: its declaration is the whole text (`TYPE ...
/// END_TYPE`, `VAR_GLOBAL ... END_VAR`).
pub(super) fn declaration_only(em: &mut Emitter, node: Node) {
    declaration(em, node);
    for c in elements(node) {
        let name = c.tag_name().name();
        if name != "Declaration" && !is_bookkeeping(name) {
            unknown(em, c, name, node.tag_name().name());
        }
    }
}

/// An `<Itf>`: `INTERFACE` declaration, its method and property
/// prototypes, `END_INTERFACE`.
pub(super) fn interface(em: &mut Emitter, node: Node) {
    if !declaration(em, node) {
        return;
    }
    for c in elements(node) {
        match c.tag_name().name() {
            "Declaration" => {}
            "Method" => {
                if declaration(em, c) {
                    em.synth("END_METHOD", em.end_of(c));
                }
            }
            "Property" => property(em, c, false),
            name if is_bookkeeping(name) => {}
            name => unknown(em, c, name, "Itf"),
        }
    }
    em.synth("END_INTERFACE", em.end_of(node));
}

/// Objects of a TwinCAT project that hold no code plcrun can run
/// (visualisations, text lists, type systems...): refused by name.
pub(super) fn refuse_object(em: &mut Emitter, node: Node, name: &str) {
    em.error(
        codes::REFUSED,
        em.at(node),
        format!(
            "`<{name}>` refused: plcrun reads POUs, DUTs, GVLs, interfaces and tasks from TwinCAT files"
        ),
    );
}

/// Warns about an element that has no meaning where it stands.
fn unknown(em: &mut Emitter, node: Node, name: &str, parent: &str) {
    em.warning(
        codes::UNKNOWN_ELEMENT,
        em.at(node),
        format!("unknown element `<{name}>` in `<{parent}>` skipped"),
    );
}

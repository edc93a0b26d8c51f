//! TwinCAT 3 PLC project files (`.TcPOU`, `.TcDUT`, `.TcGVL`, `.TcIO`,
//! `.TcTTO`): XML files (`<TcPlcObject>`) that hold ST in CDATA sections,
//! a POU's declaration apart from its body and from each of its methods,
//! properties and actions.
//!
//! Like the PLCopen reader, this one does not build the AST by hand: it
//! writes the tokens of the equivalent textual source, each lexed at its
//! own position in the XML file, adds the words the XML structure stands
//! for (`END_METHOD`, `GET`, `END_FUNCTION_BLOCK`...) at the element they
//! come from, and runs the textual parser. Every diagnostic therefore
//! points at line:column of the ST text inside the XML file. A task file
//! becomes a `CONFIGURATION` with one `TASK` and its program calls;
//! [`merge_task_configurations`] joins those of a project into one.
//! `docs/twincat.md` says what maps to what.

pub mod codes;
mod object;
mod task;
pub mod type_description;

use crate::diagnostics::Diagnostics;
use crate::source::FileId;
use crate::syntax::ast::{CompilationUnit, Item};
use crate::syntax::construct::State;
use crate::syntax::il_lines::keep_il_lines;
use crate::syntax::parser;
use crate::syntax::plcopen::emit::{Emitter, elements, open_xml};
use std::collections::HashSet;

/// True when `text` is a TwinCAT object file: after an optional byte-order
/// mark, white space and an XML declaration, its root is `<TcPlcObject`.
pub fn is_twincat(text: &str) -> bool {
    root_name(text) == Some("TcPlcObject")
}

/// True when `text` is a TwinCAT task file (a `<TcPlcObject>` holding a
/// `<Task>`).
pub fn is_task_file(text: &str) -> bool {
    is_twincat(text) && text.contains("<Task")
}

/// The name of the object a TwinCAT object file declares (`<POU
/// Name="FB_X"`, `<DUT ...>`, `<GVL ...>`, `<Itf ...>`), read without
/// parsing the file; `None` for a task or an unreadable file.
pub fn object_name(text: &str) -> Option<&str> {
    if !is_twincat(text) {
        return None;
    }
    let at = ["<POU ", "<DUT ", "<GVL ", "<Itf "]
        .iter()
        .filter_map(|tag| text.find(tag))
        .min()?;
    let rest = &text[at..];
    let rest = &rest[rest.find("Name=\"")? + 6..];
    Some(&rest[..rest.find('"')?])
}

/// The identifiers of `text`, upper case: every `[A-Za-z_][A-Za-z0-9_]*`
/// run (in comments and XML markup too, which only adds names).
pub fn identifiers(text: &str, into: &mut HashSet<String>) {
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_alphabetic() || bytes[i] == b'_' {
            let start = i;
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                i += 1;
            }
            into.insert(text[start..i].to_ascii_uppercase());
        } else {
            i += 1;
        }
    }
}

/// The name of the first element of an XML text (skipping the
/// declaration, comments and white space), read without parsing it all.
fn root_name(text: &str) -> Option<&str> {
    let mut rest = text.trim_start_matches('\u{FEFF}').trim_start();
    loop {
        if let Some(after) = rest.strip_prefix("<?") {
            rest = after.split_once("?>")?.1.trim_start();
        } else if let Some(after) = rest.strip_prefix("<!--") {
            rest = after.split_once("-->")?.1.trim_start();
        } else {
            break;
        }
    }
    let name = rest.strip_prefix('<')?;
    let end = name
        .find(|c: char| c.is_whitespace() || c == '>' || c == '/')
        .unwrap_or(name.len());
    Some(&name[..end])
}

/// Parses a TwinCAT object file into the AST. Never panics, on any input;
/// every problem is a diagnostic pointing into `text`.
pub fn parse(file: FileId, text: &str, diags: &mut Diagnostics) -> CompilationUnit {
    let (mut em, doc) = open_xml(file, text, codes::MALFORMED_XML);
    em.nested_comments = true;
    let Some(doc) = doc else {
        diags.extend(em.diags);
        return CompilationUnit::default();
    };
    let root = doc.root_element();
    for node in elements(root) {
        match node.tag_name().name() {
            "POU" => object::pou(&mut em, node),
            "DUT" | "GVL" => object::declaration_only(&mut em, node),
            "Itf" => object::interface(&mut em, node),
            "Task" => task::task(&mut em, node),
            other => object::refuse_object(&mut em, node, other),
        }
    }
    let Emitter {
        toks, diags: found, ..
    } = em;
    let structural = found.iter().any(|d| {
        d.severity == crate::diagnostics::Severity::Error
            && (d.code == codes::MALFORMED_XML || d.code == codes::MISSING)
    });
    diags.extend(found);
    if structural {
        return CompilationUnit::default();
    }
    let toks = crate::syntax::textual_passes(file, text, toks, diags);
    parser::parse_tokens(State::new(file, text), keep_il_lines(toks), diags)
}

/// Joins the configurations that task files became into one, since a
/// TwinCAT project's tasks are one file each and plcrun runs one
/// configuration: the tasks and program calls of every unit for which
/// `is_task_unit` is true go into the first such unit's resource.
pub fn merge_task_configurations(
    units: &mut [CompilationUnit],
    is_task_unit: impl Fn(usize) -> bool,
) {
    let mut first: Option<usize> = None;
    for i in 0..units.len() {
        if !is_task_unit(i) {
            continue;
        }
        let Some(target) = first else {
            first = Some(i);
            continue;
        };
        let moved: Vec<Item> = std::mem::take(&mut units[i].items);
        let mut kept = Vec::new();
        for item in moved {
            match item {
                Item::Configuration(cfg) => {
                    let into = units[target].items.iter_mut().find_map(|it| match it {
                        Item::Configuration(c) => c.resources.first_mut(),
                        _ => None,
                    });
                    match into {
                        Some(res) => {
                            for r in cfg.resources {
                                res.tasks.extend(r.tasks);
                                res.programs.extend(r.programs);
                            }
                        }
                        None => kept.push(Item::Configuration(cfg)),
                    }
                }
                other => kept.push(other),
            }
        }
        units[i].items = kept;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const COUNTER: &str = include_str!("../../../tests/twincat/conveyor/POUs/FB_Counter.TcPOU");

    #[test]
    fn the_root_element_decides_and_a_byte_order_mark_or_comment_is_skipped() {
        assert!(is_twincat(
            "\u{FEFF}<?xml version=\"1.0\"?>\r\n<!-- x --><TcPlcObject>"
        ));
        assert!(!is_twincat("<?xml version=\"1.0\"?><project/>"));
        assert!(!is_twincat("PROGRAM P END_PROGRAM"));
        assert!(is_task_file(
            "<TcPlcObject><Task Name=\"t\"/></TcPlcObject>"
        ));
    }

    #[test]
    fn every_prefix_of_a_file_parses_without_panicking() {
        for end in (0..COUNTER.len()).filter(|&e| COUNTER.is_char_boundary(e)) {
            let mut diags = Diagnostics::new();
            parse(FileId(0), &COUNTER[..end], &mut diags);
        }
        let mut diags = Diagnostics::new();
        let unit = parse(FileId(0), COUNTER, &mut diags);
        assert!(!diags.has_errors(), "{diags:?}");
        assert_eq!(unit.items.len(), 1);
    }
}

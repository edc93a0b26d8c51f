//! PLCopen TC6 XML (`http://www.plcopen.org/xml/tc6_0201`, and `tc6_0200`):
//! import into the AST and export from it.
//!
//! Import ([`parse`]) turns a `<project>` into the token stream of the
//! equivalent textual source ([`emit`]) and runs the textual parser on it,
//! so the result is the same [`CompilationUnit`] a `.st`/`.il`/`.sfc` file
//! gives, and every diagnostic points into the XML file. What plcrun cannot
//! represent (macro steps, graphical conditions...) is refused by name
//! with an `E8xx` code, never skipped. FBD and LD bodies are lowered to ST
//! statements ([`graphic`]). Export
//! ([`export::export_plcopen`]) writes parsed sources back as a PLCopen
//! project; the bodies of PLCopen files as drawn ([`diagram`]). See
//! `docs/plcopen.md`.

pub mod body;
pub mod codes;
pub mod codesys_members;
pub mod config;
pub mod config_vars;
pub mod diagram;
pub mod emit;
pub mod export;
pub mod fbd;
pub mod graphic;
pub mod infer;
pub mod interface;
pub mod ld;
pub mod network;
pub mod order;
pub mod origin;
pub mod pou;
pub mod raw;
pub mod sfc;
pub mod types;
pub mod values;

use crate::diagnostics::Diagnostics;
use crate::source::FileId;
use crate::syntax::ast::CompilationUnit;
use crate::syntax::construct::State;
use crate::syntax::{il_lines, parser};
use emit::{Emitter, elements, open_xml};

/// The namespace of TC6 XML 2.01 (written by the OpenPLC Editor and Beremiz).
pub const NAMESPACE_0201: &str = "http://www.plcopen.org/xml/tc6_0201";
/// The namespace of TC6 XML 2.0, read as well.
pub const NAMESPACE_0200: &str = "http://www.plcopen.org/xml/tc6_0200";

/// True when `text` is a PLCopen XML file rather than IL/ST/SFC source:
/// after an optional byte-order mark and white space it starts with
/// `<?xml` or `<project`.
pub fn is_plcopen(text: &str) -> bool {
    let rest = text.trim_start_matches('\u{FEFF}').trim_start();
    rest.starts_with("<?xml") || rest.starts_with("<project")
}

/// Parses `xml` as the importers read XML files (no DTD: nothing can make
/// the reader fetch or expand anything); on failure, the byte offset where
/// the reader stopped and its message.
pub(crate) fn read_xml(xml: &str) -> Result<roxmltree::Document<'_>, (usize, String)> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: false,
        ..roxmltree::ParsingOptions::default()
    };
    roxmltree::Document::parse_with_options(xml, options)
        .map_err(|e| (offset_of(xml, e.pos()), e.to_string()))
}

/// Parses a PLCopen project into the AST. Never panics, on any input;
/// every problem is a diagnostic pointing into `text`.
pub fn parse(file: FileId, text: &str, diags: &mut Diagnostics) -> CompilationUnit {
    let (mut em, doc) = open_xml(file, text, codes::MALFORMED_XML);
    em.nested_comments = origin::written_by_codesys(text);
    let Some(doc) = doc else {
        diags.extend(em.diags);
        return CompilationUnit::default();
    };
    project(&mut em, doc.root_element());
    let Emitter {
        toks, diags: found, ..
    } = em;
    // After a structural error (E8xx) the token stream would only add
    // consequent syntax errors: the checker sees an empty unit. Lexical
    // errors inside bodies (E0xx) do not stop the parse.
    let structural = found
        .iter()
        .any(|d| d.severity == crate::diagnostics::Severity::Error && d.code.starts_with("E8"));
    diags.extend(found);
    if structural {
        return CompilationUnit::default();
    }
    let toks = il_lines::keep_il_lines(toks);
    parser::parse_tokens(State::new(file, text), toks, diags)
}

/// Parses PLCopen XML given as bytes (as a fuzzer gives them): never
/// panics; invalid UTF-8 is an error diagnostic. Returns the unit and the
/// diagnostics.
///
/// ```
/// use plcrun::syntax::plcopen::parse_bytes;
/// let (_, diags) = parse_bytes(b"<project><types><pous/></types>");
/// assert!(diags.has_errors());
/// ```
pub fn parse_bytes(bytes: &[u8]) -> (CompilationUnit, Diagnostics) {
    let mut diags = Diagnostics::new();
    let text = String::from_utf8_lossy(bytes);
    if let std::borrow::Cow::Owned(_) = text {
        diags.error(
            codes::MALFORMED_XML,
            crate::source::Span::default(),
            "the file is not valid UTF-8",
        );
    }
    let unit = parse(FileId(0), &text, &mut diags);
    (unit, diags)
}

/// The byte offset of a 1-based row/column (in characters).
fn offset_of(xml: &str, pos: roxmltree::TextPos) -> usize {
    let mut offset = 0;
    for (i, line) in xml.split_inclusive('\n').enumerate() {
        if i + 1 == pos.row as usize {
            let col = (pos.col as usize).saturating_sub(1);
            return offset + line.char_indices().nth(col).map_or(line.len(), |(b, _)| b);
        }
        offset += line.len();
    }
    xml.len()
}

/// `<project>`: headers, `<types>`, `<instances>`.
fn project(em: &mut Emitter, root: roxmltree::Node) {
    if root.tag_name().name() != "project" {
        em.error(
            codes::NOT_A_PROJECT,
            em.at(root),
            format!(
                "a PLCopen file holds a `<project>`, not a `<{}>`",
                root.tag_name().name()
            ),
        );
        return;
    }
    match root.tag_name().namespace() {
        Some(NAMESPACE_0201 | NAMESPACE_0200) => {}
        other => em.warning(
            codes::UNKNOWN_NAMESPACE,
            em.at(root),
            format!(
                "namespace `{}` is not TC6 XML 2.01 (`{NAMESPACE_0201}`); reading it as 2.01",
                other.unwrap_or("")
            ),
        ),
    }
    for node in elements(root) {
        match node.tag_name().name() {
            "fileHeader" | "contentHeader" | "documentation" => {}
            "addData" => body::add_data(em, node),
            "types" => types_section(em, node),
            "instances" => config::instances(em, node),
            _ => em.unknown(node, "project"),
        }
    }
}

/// `<types>`: `<dataTypes>` and `<pous>`.
fn types_section(em: &mut Emitter, node: roxmltree::Node) {
    for child in elements(node) {
        match child.tag_name().name() {
            "dataTypes" => types::data_types(em, child),
            "pous" => {
                for p in elements(child) {
                    match p.tag_name().name() {
                        "pou" => pou::pou(em, p),
                        "documentation" => {}
                        "addData" => body::add_data(em, p),
                        _ => em.unknown(p, "pous"),
                    }
                }
            }
            "documentation" => {}
            "addData" => body::add_data(em, child),
            _ => em.unknown(child, "types"),
        }
    }
}

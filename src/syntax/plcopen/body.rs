//! Bodies: the language element of a `<body>`, textual bodies in ST and IL
//! (plain or wrapped in XHTML, as the OpenPLC Editor and Beremiz write
//! them), and `<addData>`.

use super::codes;
use super::emit::{Emitter, Range, elements};
use super::raw::content_range;
use super::sfc;
use roxmltree::Node;

/// The `<data name>` under which plcrun stores an SFC body's plain
/// statements (a plcrun extension of textual SFC that TC6 has no element
/// for). Its `handleUnknown` is `implementation`: another tool must not
/// drop it silently.
pub const SFC_STATEMENTS_DATA: &str = "urn:plcrun:sfc-statements";

/// A POU's `<body>`.
pub fn pou_body(em: &mut Emitter, pou: Node, body: Node) {
    let Some(lang) =
        elements(body).find(|c| matches!(c.tag_name().name(), "IL" | "ST" | "FBD" | "LD" | "SFC"))
    else {
        super::types::missing_child(em, body, "ST>, <IL>, <FBD>, <LD> or <SFC");
        return;
    };
    for c in elements(body) {
        match c.tag_name().name() {
            "IL" | "ST" | "FBD" | "LD" | "SFC" if c == lang => {}
            "documentation" => {}
            "addData" if lang.tag_name().name() == "SFC" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, "body"),
        }
    }
    match lang.tag_name().name() {
        "SFC" => sfc::chart(em, pou, body, lang),
        "ST" | "IL" => {
            refuse_actions(em, pou);
            text_body(em, lang);
        }
        _ => {
            refuse_actions(em, pou);
            super::graphic::body(em, pou, lang);
        }
    }
}

/// Refuses `<actions>`/`<transitions>` in a POU whose body is not SFC.
fn refuse_actions(em: &mut Emitter, pou: Node) {
    for name in ["actions", "transitions"] {
        if let Some(list) = elements(pou).find(|c| c.tag_name().name() == name)
            && elements(list).next().is_some()
        {
            em.refuse(list, "actions and named transitions belong to an SFC body");
        }
    }
}

/// Emits a textual body (`<ST>` or `<IL>`) as its tokens, between line
/// breaks so that an IL body is recognised line by line.
pub fn text_body(em: &mut Emitter, lang: Node) {
    let at = em.at(lang);
    em.eol(at);
    for range in text_ranges(em, lang) {
        em.lex_range(range, true);
        em.eol(range_end(range));
    }
    em.eol(em.end_of(lang));
}

/// The empty range at the end of `range`.
fn range_end((_, e): Range) -> Range {
    (e, e)
}

/// The ranges of text of a textual body: the content of each
/// `<xhtml:p>` (or of `<xhtml>`), or the element's own content.
pub fn text_ranges(em: &mut Emitter, lang: Node) -> Vec<Range> {
    let xml = lang.document().input_text();
    let kids: Vec<Node> = elements(lang).collect();
    if kids.is_empty() {
        return content_range(xml, lang.range()).into_iter().collect();
    }
    let mut ranges = Vec::new();
    for k in kids {
        match k.tag_name().name() {
            "p" | "xhtml" | "div" | "body" => {
                if let Some(r) = content_range(xml, k.range()) {
                    ranges.push(r);
                }
            }
            _ => em.error(
                codes::MARKUP_IN_TEXT,
                em.at(k),
                format!(
                    "`<{}>` inside a `<{}>` body: only text (or an XHTML paragraph) is allowed",
                    k.tag_name().name(),
                    lang.tag_name().name()
                ),
            ),
        }
    }
    ranges
}

/// `<addData>`: ignored, unless a `<data>` says with
/// `handleUnknown="implementation"` that dropping it changes the program.
pub fn add_data(em: &mut Emitter, node: Node) {
    add_data_except(em, node, |_| false);
}

/// [`add_data`] for the `<data>` that `skip` does not take (those another
/// reader handles: CODESYS's methods, for instance).
pub fn add_data_except(em: &mut Emitter, node: Node, skip: impl Fn(Node) -> bool) {
    for data in elements(node).filter(|d| !skip(*d)) {
        if data.tag_name().name() == "data" {
            data_element(em, data);
        } else {
            em.unknown(data, "addData");
        }
    }
}

/// One `<data>` of an `<addData>`: refused when it changes meaning.
pub fn data_element(em: &mut Emitter, data: Node) {
    if data.attribute("handleUnknown") == Some("implementation") {
        let name = data.attribute("name").unwrap_or("");
        let where_ = if name == SFC_STATEMENTS_DATA {
            " (it belongs in the <body> of an SFC POU)"
        } else {
            ""
        };
        em.error(
            codes::MEANINGFUL_ADD_DATA,
            em.at(data),
            format!(
                "`<data name=\"{name}\">` says it changes the implementation, and plcrun does not know it{where_}"
            ),
        );
    }
}

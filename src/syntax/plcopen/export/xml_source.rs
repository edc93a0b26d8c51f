//! PLCopen files given to export. Their declarations, types and
//! configurations come from the AST as for textual sources; their bodies
//! do not (the AST holds a graphical body lowered to ST): a graphical
//! body is read as drawn ([`Diagram`]), a textual one as its decoded text.

use super::super::body::text_ranges;
use super::super::diagram::{Diagram, body_language, pou_bodies, read_diagram};
use super::super::emit::Emitter;
use super::super::raw::decode;
use crate::source::FileId;
use std::collections::HashMap;
use std::ops::Range;

/// The body of a POU of a PLCopen file.
#[derive(Debug, Clone)]
pub(super) enum XmlBody {
    /// An FBD or LD body as drawn.
    Graphic(Diagram),
    /// An ST or IL body's text.
    Text {
        /// `ST` or `IL`.
        language: &'static str,
        /// The decoded text.
        text: String,
    },
}

/// A POU body of a PLCopen file and where its language element lies.
#[derive(Debug, Clone)]
pub(super) struct XmlPou {
    /// Its body.
    pub body: XmlBody,
    /// The byte range of its language element in the file: declarations
    /// placed there are the lowering's hidden variables, not the user's.
    pub range: Range<usize>,
}

/// The bodies of file `file`'s POUs by upper-case name (SFC bodies are
/// left to the AST); an error names what cannot be read.
pub(super) fn xml_bodies(
    file: FileId,
    text: &str,
) -> Result<HashMap<(FileId, String), XmlPou>, String> {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let xml = &text[base..];
    let doc = super::super::read_xml(xml).map_err(|(_, e)| format!("malformed XML: {e}"))?;
    let mut out = HashMap::new();
    for (pou, body) in pou_bodies(doc.root_element()) {
        let Some(lang) = body_language(body) else {
            continue;
        };
        let name = pou.attribute("name").unwrap_or("").trim();
        let body = match lang.tag_name().name() {
            "FBD" | "LD" => {
                XmlBody::Graphic(read_diagram(lang).map_err(|e| format!("POU `{name}`: {e}"))?)
            }
            "ST" => XmlBody::Text {
                language: "ST",
                text: body_text(xml, lang),
            },
            "IL" => XmlBody::Text {
                language: "IL",
                text: body_text(xml, lang),
            },
            _ => continue,
        };
        let r = lang.range();
        out.insert(
            (file, name.to_ascii_uppercase()),
            XmlPou {
                body,
                range: r.start + base..r.end + base,
            },
        );
    }
    Ok(out)
}

/// The decoded text of a textual body, its paragraphs one after another.
fn body_text(xml: &str, lang: roxmltree::Node) -> String {
    // The importer has reported what is wrong with the body already.
    let mut scratch = Emitter::new(FileId(0), xml, 0);
    let mut text = String::new();
    for (s, e) in text_ranges(&mut scratch, lang) {
        if let Ok(d) = decode(xml, s, e) {
            text.push_str(d.text.trim_matches('\n'));
            text.push('\n');
        }
    }
    text
}

//! The graphical bodies of a PLCopen project as drawn: the [`Diagram`]
//! of every POU whose body is `<FBD>` or `<LD>`, read from the XML with
//! positions, sizes and routes kept. Export writes these back
//! ([`crate::export_plcopen`]); `plcrun draw` draws them.

pub mod model;
pub mod read;

pub use model::{
    BlockPin, Connection, Diagram, DiagramElement, ElementKind, Language, Modifiers, PinList,
    Point, PointIn, PointOut,
};
pub use read::read_diagram;

use super::emit::{child, elements};
use roxmltree::Node;

/// A POU with a graphical body.
#[derive(Debug, Clone, PartialEq)]
pub struct GraphicalPou {
    /// The POU's name.
    pub name: String,
    /// Its body as drawn.
    pub diagram: Diagram,
    /// The byte range of the `<FBD>`/`<LD>` element in the file (after a
    /// byte-order mark, counted as in the file).
    pub range: std::ops::Range<usize>,
}

/// The POUs of a project with their `<body>` elements, in document order.
pub fn pou_bodies<'a, 'i>(root: Node<'a, 'i>) -> Vec<(Node<'a, 'i>, Node<'a, 'i>)> {
    let pous = child(root, "types").and_then(|t| child(t, "pous"));
    pous.into_iter()
        .flat_map(elements)
        .filter(|p| p.tag_name().name() == "pou")
        .filter_map(|p| child(p, "body").map(|b| (p, b)))
        .collect()
}

/// The language element of a `<body>` (`<ST>`, `<FBD>`, ...).
pub fn body_language<'a, 'i>(body: Node<'a, 'i>) -> Option<Node<'a, 'i>> {
    elements(body).find(|c| matches!(c.tag_name().name(), "IL" | "ST" | "FBD" | "LD" | "SFC"))
}

/// Every POU of the PLCopen file `text` whose body is FBD or LD, in
/// document order; an error when the XML cannot be read.
pub fn graphical_pous(text: &str) -> Result<Vec<GraphicalPou>, String> {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let doc = super::read_xml(&text[base..]).map_err(|(_, e)| format!("malformed XML: {e}"))?;
    let mut out = Vec::new();
    for (pou, body) in pou_bodies(doc.root_element()) {
        let Some(lang) = body_language(body) else {
            continue;
        };
        if !matches!(lang.tag_name().name(), "FBD" | "LD") {
            continue;
        }
        let name = pou.attribute("name").unwrap_or("").trim().to_string();
        let diagram = read_diagram(lang).map_err(|e| format!("POU `{name}`: {e}"))?;
        let r = lang.range();
        out.push(GraphicalPou {
            name,
            diagram,
            range: r.start + base..r.end + base,
        });
    }
    Ok(out)
}

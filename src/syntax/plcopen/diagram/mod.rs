//! The bodies of a PLCopen project as drawn: the [`Diagram`] of every
//! POU whose body is `<FBD>` or `<LD>`, the [`ChartBody`] of every SFC
//! POU, read from the XML with positions, sizes and routes kept. Export
//! writes these back ([`crate::export_plcopen`]); `plcrun draw` draws the
//! FBD and LD ones.

pub mod model;
pub mod read;
pub mod read_chart;

pub use model::{
    ActionTarget, Association, BlockPin, BodyModel, ChartBody, Condition, ConditionKind,
    Connection, Diagram, DiagramElement, ElementKind, Language, Modifiers, NamedBody, PinList,
    Point, PointIn, PointOut,
};
pub use read::{read_body, read_diagram};
pub use read_chart::read_chart;

use super::emit::{child, elements};
use roxmltree::Node;

/// A POU with a graphical (FBD or LD) body.
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

/// The body of a POU of a PLCopen project, as written.
#[derive(Debug, Clone, PartialEq)]
pub enum PouBody {
    /// ST or IL text, or an FBD or LD drawing.
    Plain(BodyModel),
    /// An SFC chart with its actions and transitions.
    Chart(ChartBody),
}

/// A POU of a PLCopen project with its body as written.
#[derive(Debug, Clone, PartialEq)]
pub struct ProjectPou {
    /// The POU's name.
    pub name: String,
    /// Its body.
    pub body: PouBody,
    /// The byte range of its language element (`<ST>`, `<FBD>`, `<SFC>`...)
    /// in the file (after a byte-order mark, counted as in the file).
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

/// Every POU of the PLCopen file `text` with a body, in document order;
/// an error when the XML cannot be read or a body has no form plcrun
/// writes back.
pub fn project_pous(text: &str) -> Result<Vec<ProjectPou>, String> {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let doc = super::read_xml(&text[base..]).map_err(|(_, e)| format!("malformed XML: {e}"))?;
    let mut out = Vec::new();
    for (pou, body) in pou_bodies(doc.root_element()) {
        let Some(lang) = body_language(body) else {
            continue;
        };
        let name = pou.attribute("name").unwrap_or("").trim().to_string();
        let read = match lang.tag_name().name() {
            "SFC" => read_chart(pou, body, lang).map(PouBody::Chart),
            _ => read_body(lang).map(PouBody::Plain),
        };
        let r = lang.range();
        out.push(ProjectPou {
            body: read.map_err(|e| format!("POU `{name}`: {e}"))?,
            name,
            range: r.start + base..r.end + base,
        });
    }
    Ok(out)
}

/// Every POU of the PLCopen file `text` whose body is FBD or LD, in
/// document order (whatever the other bodies hold); an error when the
/// XML cannot be read.
pub fn graphical_pous(text: &str) -> Result<Vec<GraphicalPou>, String> {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let doc = super::read_xml(&text[base..]).map_err(|(_, e)| format!("malformed XML: {e}"))?;
    let mut out = Vec::new();
    for (pou, body) in pou_bodies(doc.root_element()) {
        let Some(lang) =
            body_language(body).filter(|l| matches!(l.tag_name().name(), "FBD" | "LD"))
        else {
            continue;
        };
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

//! Reads a [`Diagram`] from the XML of an `<FBD>`, `<LD>` or `<SFC>`
//! body: every element as written, nothing resolved. The body is expected to have
//! passed the importer (which reports what is wrong with a coded
//! diagnostic); what this reader still cannot take is an error naming the
//! element.

use super::model::{
    BlockPin, BodyModel, Connection, Diagram, DiagramElement, Edge, ElementKind, Language,
    Modifiers, PinList, Point, PointIn, PointOut, Storage,
};
use crate::source::FileId;
use crate::syntax::plcopen::body::text_ranges;
use crate::syntax::plcopen::emit::{Emitter, child, elements, is_true};
use crate::syntax::plcopen::raw::decode;
use roxmltree::Node;

/// Reads the body `lang` (an `<FBD>`, `<LD>` or `<SFC>` element).
pub fn read_diagram(lang: Node) -> Result<Diagram, String> {
    let language = match lang.tag_name().name() {
        "LD" => Language::Ld,
        "FBD" => Language::Fbd,
        "SFC" => Language::Sfc,
        other => return Err(format!("`<{other}>` is not an FBD, LD or SFC body")),
    };
    let mut out = Vec::new();
    for node in elements(lang) {
        if let Some(el) = read_element(node)? {
            out.push(el);
        }
    }
    Ok(Diagram {
        language,
        elements: out,
    })
}

/// One element; `None` for what carries no drawing (`<addData>`,
/// `<documentation>`).
fn read_element(node: Node) -> Result<Option<DiagramElement>, String> {
    let name = node.tag_name().name();
    let attr = |a: &str| node.attribute(a).unwrap_or("").trim().to_string();
    let kind = match name {
        "inVariable" => ElementKind::InVariable,
        "outVariable" => ElementKind::OutVariable,
        "inOutVariable" => ElementKind::InOutVariable,
        "block" => ElementKind::Block {
            type_name: attr("typeName"),
            instance: Some(attr("instanceName")).filter(|i| !i.is_empty()),
        },
        "connector" => ElementKind::Connector(attr("name")),
        "continuation" => ElementKind::Continuation(attr("name")),
        "jump" => ElementKind::Jump(attr("label")),
        "label" => ElementKind::Label(attr("label")),
        "return" => ElementKind::Return,
        "leftPowerRail" => ElementKind::LeftRail,
        "rightPowerRail" => ElementKind::RightRail,
        "contact" => ElementKind::Contact,
        "coil" => ElementKind::Coil,
        "comment" => ElementKind::Comment,
        "addData" | "documentation" => return Ok(None),
        other => match super::read_chart::chart_kind(node)? {
            Some(kind) => kind,
            None => return Err(format!("`<{other}>` has no place in a graphical body")),
        },
    };
    let Some(id) = node.attribute("localId").map(str::trim) else {
        return Err(format!("`<{name}>` has no localId"));
    };
    let position = child(node, "position").map(point).unwrap_or_default();
    let mut el = DiagramElement::new(kind, id, position);
    el.size = match (number(node, "width"), number(node, "height")) {
        (None, None) => None,
        (w, h) => Some(Point {
            x: w.unwrap_or(0.0),
            y: h.unwrap_or(0.0),
        }),
    };
    el.order = node
        .attribute("executionOrderId")
        .and_then(|v| v.trim().parse().ok());
    if el.kind == ElementKind::InOutVariable {
        el.modifiers = modifiers(node, "negatedIn", "edgeIn", "storageIn");
        el.out_modifiers = modifiers(node, "negatedOut", "edgeOut", "storageOut");
    } else {
        el.modifiers = modifiers(node, "negated", "edge", "storage");
    }
    el.text = match el.kind {
        ElementKind::Contact | ElementKind::Coil => text_of(child(node, "variable")),
        ElementKind::Comment => content_text(node),
        _ => text_of(child(node, "expression")),
    };
    if let ElementKind::Block { .. } = el.kind {
        el.pins = block_pins(node);
    } else {
        el.inputs = named(node, "connectionPointIn").map(point_in).collect();
        el.outputs = named(node, "connectionPointOut").map(point_out).collect();
        el.action_point = child(node, "connectionPointOutAction").map(point_out);
    }
    Ok(Some(el))
}

/// Reads a body written in `lang` (`<ST>`, `<IL>`, `<FBD>` or `<LD>`).
pub fn read_body(lang: Node) -> Result<BodyModel, String> {
    match lang.tag_name().name() {
        "ST" | "IL" => Ok(BodyModel::Text {
            language: lang.tag_name().name().to_string(),
            text: body_text(lang),
        }),
        "FBD" | "LD" => Ok(BodyModel::Diagram(read_diagram(lang)?)),
        other => Err(format!(
            "a `<{other}>` body here has no form plcrun writes back"
        )),
    }
}

/// The decoded text of a textual body, its paragraphs one after another,
/// each ending with one line break.
pub fn body_text(lang: Node) -> String {
    let xml = lang.document().input_text();
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

/// The children of `node` named `name`.
pub(super) fn named<'a, 'i>(
    node: Node<'a, 'i>,
    name: &'static str,
) -> impl Iterator<Item = Node<'a, 'i>> {
    elements(node).filter(move |c| c.tag_name().name() == name)
}

/// A numeric attribute.
pub(super) fn number(node: Node, name: &str) -> Option<f64> {
    node.attribute(name)?.trim().parse().ok()
}

/// A `<position>` or `<relPosition>` (0 for a missing coordinate).
pub(super) fn point(node: Node) -> Point {
    Point {
        x: number(node, "x").unwrap_or(0.0),
        y: number(node, "y").unwrap_or(0.0),
    }
}

/// The text of an `<expression>` or `<variable>` child.
fn text_of(node: Option<Node>) -> String {
    node.and_then(|n| n.text()).unwrap_or("").to_string()
}

/// The text of a comment's `<content>` (plain, or in XHTML paragraphs).
fn content_text(node: Node) -> String {
    let Some(content) = child(node, "content") else {
        return String::new();
    };
    let paragraphs: Vec<Node> = elements(content).collect();
    if paragraphs.is_empty() {
        return content.text().unwrap_or("").to_string();
    }
    // The white space between paragraphs is layout, not text.
    paragraphs
        .iter()
        .flat_map(|p| p.descendants())
        .filter(|d| d.is_text())
        .filter_map(|d| d.text())
        .collect()
}

/// Negation, edge and storage from the three attributes named.
fn modifiers(node: Node, negated: &str, edge: &str, storage: &str) -> Modifiers {
    Modifiers {
        negated: is_true(node.attribute(negated)),
        edge: match node.attribute(edge).map(str::trim) {
            Some("rising") => Edge::Rising,
            Some("falling") => Edge::Falling,
            _ => Edge::None,
        },
        storage: match node.attribute(storage).map(str::trim) {
            Some("set") => Storage::Set,
            Some("reset") => Storage::Reset,
            _ => Storage::None,
        },
    }
}

/// A `<connectionPointIn>` with its connections.
pub(super) fn point_in(node: Node) -> PointIn {
    PointIn {
        rel: child(node, "relPosition").map(point),
        connections: named(node, "connection")
            .map(|c| Connection {
                from: c.attribute("refLocalId").unwrap_or("").trim().to_string(),
                pin: c.attribute("formalParameter").map(|p| p.trim().to_string()),
                route: named(c, "position").map(point).collect(),
            })
            .collect(),
    }
}

/// A `<connectionPointOut>`.
pub(super) fn point_out(node: Node) -> PointOut {
    PointOut {
        name: node
            .attribute("formalParameter")
            .map(|p| p.trim().to_string()),
        rel: child(node, "relPosition").map(point),
    }
}

/// The `<variable>`s of a block's three lists.
fn block_pins(node: Node) -> Vec<BlockPin> {
    let lists = [
        ("inputVariables", PinList::Input),
        ("inOutVariables", PinList::InOut),
        ("outputVariables", PinList::Output),
    ];
    let mut pins = Vec::new();
    for (tag, list) in lists {
        for v in child(node, tag)
            .into_iter()
            .flat_map(|l| named(l, "variable"))
        {
            pins.push(BlockPin {
                list,
                name: v
                    .attribute("formalParameter")
                    .unwrap_or("")
                    .trim()
                    .to_string(),
                modifiers: modifiers(v, "negated", "edge", "storage"),
                hidden: is_true(v.attribute("hidden")),
                input: child(v, "connectionPointIn").map(point_in),
                output: child(v, "connectionPointOut").map(point_out),
            });
        }
    }
    pins
}

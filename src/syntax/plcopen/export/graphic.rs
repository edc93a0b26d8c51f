//! Export of a graphical body: a [`Diagram`] written back as `<FBD>`,
//! `<LD>` or `<SFC>` with every element, its localId, position, size, pins,
//! connection points and connection routes, so that reading the output
//! gives the same diagram.

use super::super::diagram::{
    BlockPin, BodyModel, Connection, Diagram, DiagramElement, ElementKind, Modifiers, PinList,
    Point, PointIn, PointOut,
};
use super::super::network::{Edge, Storage};
use super::drawn_chart::{associations, condition};
use super::writer::Writer;

/// A body: ST or IL text, or a drawing.
pub fn body_model(w: &mut Writer, b: &BodyModel) {
    match b {
        BodyModel::Text { language, text } => w.text_body(language, text),
        BodyModel::Diagram(d) => diagram(w, d),
    }
}

/// Writes `<FBD>`/`<LD>`/`<SFC>` with the diagram's elements.
pub fn diagram(w: &mut Writer, d: &Diagram) {
    let tag = d.language.tag();
    if d.elements.is_empty() {
        w.empty(tag, &[]);
        return;
    }
    w.open(tag, &[]);
    for el in &d.elements {
        element(w, el);
    }
    w.close(tag);
}

/// A coordinate as written: the shortest text that reads back the same.
fn coordinate(v: f64) -> String {
    format!("{v}")
}

/// `x="..." y="..."` of a point.
pub(super) fn point_attrs(p: Point) -> [(&'static str, String); 2] {
    [("x", coordinate(p.x)), ("y", coordinate(p.y))]
}

/// Writes an element with only attributes made of owned strings.
pub(super) fn empty_owned(w: &mut Writer, name: &str, attrs: &[(&'static str, String)]) {
    let borrowed: Vec<(&str, &str)> = attrs.iter().map(|(k, v)| (*k, v.as_str())).collect();
    w.empty(name, &borrowed);
}

/// Opens an element with attributes made of owned strings.
pub(super) fn open_owned(w: &mut Writer, name: &str, attrs: &[(&'static str, String)]) {
    let borrowed: Vec<(&str, &str)> = attrs.iter().map(|(k, v)| (*k, v.as_str())).collect();
    w.open(name, &borrowed);
}

/// The attributes of an element's start tag, in the order TC6 lists them.
fn element_attrs(el: &DiagramElement) -> Vec<(&'static str, String)> {
    let mut a: Vec<(&'static str, String)> = vec![("localId", el.id.clone())];
    match &el.kind {
        ElementKind::Block {
            type_name,
            instance,
        } => {
            a.push(("typeName", type_name.clone()));
            if let Some(i) = instance {
                a.push(("instanceName", i.clone()));
            }
        }
        ElementKind::Connector(n) | ElementKind::Continuation(n) => a.push(("name", n.clone())),
        ElementKind::Jump(l) | ElementKind::Label(l) => a.push(("label", l.clone())),
        ElementKind::Step { name, .. } => a.push(("name", name.clone())),
        ElementKind::JumpStep(target) => a.push(("targetName", target.clone())),
        _ => {}
    }
    if let Some(size) = el.size {
        a.push(("height", coordinate(size.y)));
        a.push(("width", coordinate(size.x)));
    }
    if let Some(order) = el.order {
        a.push(("executionOrderId", order.to_string()));
    }
    match &el.kind {
        ElementKind::Step { initial: true, .. } => a.push(("initialStep", "true".to_string())),
        ElementKind::Transition {
            priority: Some(p), ..
        } => a.push(("priority", p.clone())),
        _ => {}
    }
    if el.kind == ElementKind::InOutVariable {
        modifier_attrs(&mut a, el.modifiers, ["negatedIn", "edgeIn", "storageIn"]);
        modifier_attrs(
            &mut a,
            el.out_modifiers,
            ["negatedOut", "edgeOut", "storageOut"],
        );
    } else {
        modifier_attrs(&mut a, el.modifiers, ["negated", "edge", "storage"]);
    }
    a
}

/// The modifiers that differ from the default, under the names given.
fn modifier_attrs(a: &mut Vec<(&'static str, String)>, m: Modifiers, names: [&'static str; 3]) {
    if m.negated {
        a.push((names[0], "true".to_string()));
    }
    match m.edge {
        Edge::Rising => a.push((names[1], "rising".to_string())),
        Edge::Falling => a.push((names[1], "falling".to_string())),
        Edge::None => {}
    }
    match m.storage {
        Storage::Set => a.push((names[2], "set".to_string())),
        Storage::Reset => a.push((names[2], "reset".to_string())),
        Storage::None => {}
    }
}

/// One element with its children in the order of the TC6 schema:
/// position, input points, output points, then its text.
fn element(w: &mut Writer, el: &DiagramElement) {
    let tag = el.kind.tag();
    open_owned(w, tag, &element_attrs(el));
    empty_owned(w, "position", &point_attrs(el.position));
    if let ElementKind::Block { .. } = el.kind {
        for (list, tag) in [
            (PinList::Input, "inputVariables"),
            (PinList::InOut, "inOutVariables"),
            (PinList::Output, "outputVariables"),
        ] {
            w.open(tag, &[]);
            for pin in el.pins.iter().filter(|p| p.list == list) {
                block_pin(w, pin);
            }
            w.close(tag);
        }
    }
    for p in &el.inputs {
        point_in(w, p);
    }
    for p in &el.outputs {
        point_out(w, p);
    }
    if let Some(p) = &el.action_point {
        write_action_point(w, p);
    }
    match &el.kind {
        ElementKind::Contact | ElementKind::Coil => w.text_element("variable", &[], &el.text),
        ElementKind::InVariable | ElementKind::OutVariable | ElementKind::InOutVariable => {
            w.text_element("expression", &[], &el.text)
        }
        ElementKind::Comment => w.text_body("content", &el.text),
        ElementKind::Transition { condition: c, .. } => condition(w, c),
        ElementKind::ActionBlock(list) => associations(w, list),
        _ => {}
    }
    w.close(tag);
}

/// A block's `<variable>`.
fn block_pin(w: &mut Writer, pin: &BlockPin) {
    let mut a: Vec<(&'static str, String)> = vec![("formalParameter", pin.name.clone())];
    modifier_attrs(&mut a, pin.modifiers, ["negated", "edge", "storage"]);
    if pin.hidden {
        a.push(("hidden", "true".to_string()));
    }
    if pin.input.is_none() && pin.output.is_none() {
        empty_owned(w, "variable", &a);
        return;
    }
    open_owned(w, "variable", &a);
    if let Some(p) = &pin.input {
        point_in(w, p);
    }
    if let Some(p) = &pin.output {
        point_out(w, p);
    }
    w.close("variable");
}

/// A `<connectionPointIn>` with its connections.
pub(super) fn point_in(w: &mut Writer, p: &PointIn) {
    if p.rel.is_none() && p.connections.is_empty() {
        w.empty("connectionPointIn", &[]);
        return;
    }
    w.open("connectionPointIn", &[]);
    if let Some(rel) = p.rel {
        empty_owned(w, "relPosition", &point_attrs(rel));
    }
    for c in &p.connections {
        connection(w, c);
    }
    w.close("connectionPointIn");
}

/// A `<connection>` with its route.
fn connection(w: &mut Writer, c: &Connection) {
    let mut a: Vec<(&'static str, String)> = vec![("refLocalId", c.from.clone())];
    if let Some(pin) = &c.pin {
        a.push(("formalParameter", pin.clone()));
    }
    if c.route.is_empty() {
        empty_owned(w, "connection", &a);
        return;
    }
    open_owned(w, "connection", &a);
    for p in &c.route {
        empty_owned(w, "position", &point_attrs(*p));
    }
    w.close("connection");
}

/// A step's `<connectionPointOutAction>`.
fn write_action_point(w: &mut Writer, p: &PointOut) {
    out_point(w, "connectionPointOutAction", p);
}

/// A `<connectionPointOut>`.
pub(super) fn point_out(w: &mut Writer, p: &PointOut) {
    out_point(w, "connectionPointOut", p);
}

/// An output point written as `tag`.
fn out_point(w: &mut Writer, tag: &str, p: &PointOut) {
    let a: Vec<(&'static str, String)> = p
        .name
        .iter()
        .map(|n| ("formalParameter", n.clone()))
        .collect();
    match p.rel {
        None => empty_owned(w, tag, &a),
        Some(rel) => {
            open_owned(w, tag, &a);
            empty_owned(w, "relPosition", &point_attrs(rel));
            w.close(tag);
        }
    }
}

//! Where things are on an FBD/LD drawing: the editor's positions and
//! sizes, with defaults for what a file leaves out, the absolute places
//! of connection points, and the route of every connection as an
//! orthogonal polyline (the editor's own route when the file gives one).

use crate::syntax::plcopen::diagram::{BlockPin, Diagram, DiagramElement, ElementKind, Point};

/// Vertical distance between two pins of a block drawn without positions.
const PIN_STEP: f64 = 20.0;
/// Where the first pin of such a block sits below its top.
const FIRST_PIN: f64 = 30.0;

/// A connection line, from the output it comes from to the input it feeds.
#[derive(Debug, Clone, PartialEq)]
pub struct Wire {
    /// The polyline's points.
    pub points: Vec<(f64, f64)>,
}

/// An element's width and height: the file's, else a default for its kind.
pub fn size(el: &DiagramElement) -> (f64, f64) {
    if let Some(s) = el.size.filter(|s| s.x > 0.0 && s.y > 0.0) {
        return (s.x, s.y);
    }
    match &el.kind {
        ElementKind::Contact | ElementKind::Coil => (21.0, 15.0),
        ElementKind::LeftRail | ElementKind::RightRail => (3.0, 40.0),
        ElementKind::Block { type_name, .. } => {
            let ins = el.pins.iter().filter(|p| p.input.is_some()).count();
            let outs = el.pins.iter().filter(|p| p.output.is_some()).count();
            let longest = |input: bool| {
                el.pins
                    .iter()
                    .filter(|p| (p.input.is_some() && input) || (p.output.is_some() && !input))
                    .map(|p| p.name.chars().count())
                    .max()
                    .unwrap_or(0)
            };
            let chars = (longest(true) + longest(false) + 2).max(type_name.chars().count() + 2);
            let rows = ins.max(outs).max(1) as f64;
            (
                chars as f64 * 7.2 + 16.0,
                FIRST_PIN + (rows - 0.5) * PIN_STEP,
            )
        }
        ElementKind::Comment => (160.0, 40.0),
        _ => {
            let chars = el.text.chars().count().max(4) as f64;
            (chars * 7.2 + 16.0, 24.0)
        }
    }
}

/// The absolute place of a point given relative to `el` (`rel`), or the
/// default: the left middle for an input, the right middle for an output.
fn place(el: &DiagramElement, rel: Option<Point>, input: bool) -> (f64, f64) {
    let (w, h) = size(el);
    let r = rel.unwrap_or(Point {
        x: if input { 0.0 } else { w },
        y: h / 2.0,
    });
    (el.position.x + r.x, el.position.y + r.y)
}

/// The place of a block's pin on its `input` side (its input point, or
/// its output point): the file's, else one row per pin down the side.
pub fn pin_place(el: &DiagramElement, pin: &BlockPin, input: bool) -> (f64, f64) {
    let rel = if input {
        pin.input.as_ref().and_then(|p| p.rel)
    } else {
        pin.output.as_ref().and_then(|p| p.rel)
    };
    if rel.is_some() {
        return place(el, rel, input);
    }
    let row = el
        .pins
        .iter()
        .filter(|p| {
            if input {
                p.input.is_some()
            } else {
                p.output.is_some()
            }
        })
        .position(|p| std::ptr::eq(p, pin))
        .unwrap_or(0);
    let (w, _) = size(el);
    let x = if input { 0.0 } else { w };
    (
        el.position.x + x,
        el.position.y + FIRST_PIN + row as f64 * PIN_STEP,
    )
}

/// The place of output `pin` of `el` (its only output when `pin` names
/// none of them).
pub fn output_place(el: &DiagramElement, pin: Option<&str>) -> (f64, f64) {
    if let ElementKind::Block { .. } = el.kind {
        let outs: Vec<_> = el.pins.iter().filter(|p| p.output.is_some()).collect();
        let chosen = pin
            .and_then(|n| outs.iter().find(|p| p.name.eq_ignore_ascii_case(n)))
            .or(outs.first());
        return match chosen {
            Some(p) => pin_place(el, p, false),
            None => place(el, None, false),
        };
    }
    let chosen = pin
        .and_then(|n| {
            el.outputs
                .iter()
                .find(|o| o.name.as_deref().is_some_and(|m| m.eq_ignore_ascii_case(n)))
        })
        .or(el.outputs.first());
    place(el, chosen.and_then(|o| o.rel), false)
}

/// The place of an element's input point given by `rel`.
pub fn input_place(el: &DiagramElement, rel: Option<Point>) -> (f64, f64) {
    place(el, rel, true)
}

/// The place of an output point given by `rel`.
pub fn out_place(el: &DiagramElement, rel: Option<Point>) -> (f64, f64) {
    place(el, rel, false)
}

/// Every connection of the diagram as a wire (connections from an element
/// the diagram does not have are left out: the importer reports them).
pub fn wires(d: &Diagram) -> Vec<Wire> {
    let mut out = Vec::new();
    for el in &d.elements {
        let block_inputs = el
            .pins
            .iter()
            .filter_map(|p| p.input.as_ref().map(|i| (i, pin_place(el, p, true))));
        let own = el.inputs.iter().map(|i| (i, input_place(el, i.rel)));
        for (point, to) in own.chain(block_inputs) {
            for c in &point.connections {
                let Some(src) = d.element(&c.from) else {
                    continue;
                };
                let points = if c.route.len() >= 2 {
                    c.route.iter().rev().map(|p| (p.x, p.y)).collect()
                } else if src.kind == ElementKind::LeftRail && c.pin.is_none() {
                    // A rail's points are alike: the wire leaves the
                    // one level with the input, else the nearest.
                    orthogonal(nearest_rail_point(src, to.1), to)
                } else {
                    orthogonal(output_place(src, c.pin.as_deref()), to)
                };
                out.push(Wire { points });
            }
        }
    }
    out
}

/// The point of left rail `rail` nearest to height `y` (level with it
/// when the rail has no points of its own).
fn nearest_rail_point(rail: &DiagramElement, y: f64) -> (f64, f64) {
    let (w, _) = size(rail);
    let mut best = (rail.position.x + w, y);
    let mut distance = f64::INFINITY;
    for o in &rail.outputs {
        let p = out_place(rail, o.rel);
        if o.rel.is_some() && (p.1 - y).abs() < distance {
            distance = (p.1 - y).abs();
            best = p;
        }
    }
    best
}

/// A route from `a` to `b` in horizontal and vertical segments, turning
/// half way across.
fn orthogonal(a: (f64, f64), b: (f64, f64)) -> Vec<(f64, f64)> {
    if (a.1 - b.1).abs() < f64::EPSILON {
        return vec![a, b];
    }
    let mid = (a.0 + b.0) / 2.0;
    vec![a, (mid, a.1), (mid, b.1), b]
}

/// The smallest and largest coordinates the drawing covers (elements,
/// wires), as `(min_x, min_y, max_x, max_y)`; `None` when empty.
pub fn bounds(d: &Diagram, wires: &[Wire]) -> Option<(f64, f64, f64, f64)> {
    let mut b: Option<(f64, f64, f64, f64)> = None;
    let mut add = |x: f64, y: f64| {
        b = Some(match b {
            None => (x, y, x, y),
            Some((a, c, e, f)) => (a.min(x), c.min(y), e.max(x), f.max(y)),
        });
    };
    for el in &d.elements {
        let (w, h) = size(el);
        // Names written above contacts, coils and blocks.
        add(el.position.x, el.position.y - 18.0);
        add(el.position.x + w, el.position.y + h);
        if matches!(el.kind, ElementKind::Contact | ElementKind::Coil) {
            let half = el.text.chars().count() as f64 * 3.6;
            add(el.position.x + w / 2.0 - half, el.position.y);
            add(el.position.x + w / 2.0 + half, el.position.y);
        }
    }
    for wire in wires {
        for &(x, y) in &wire.points {
            add(x, y);
        }
    }
    b
}

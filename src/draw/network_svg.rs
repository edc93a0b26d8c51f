//! Draws FBD networks and LD rungs ([`Diagram`]) as SVG at the editor's
//! positions, so the picture looks like the editor's (the LD symbols are
//! drawn by `ld_svg`).
//!
//! Conventions (IEC 61131-3): a block is a box with its type name inside
//! at the top, its instance name above, its formal parameters inside at
//! their pins; a negated pin has a small circle; a variable is a rounded
//! box with its expression; a contact is `-| |-` (`/`, `P`, `N` inside
//! when negated or edge-triggered), a coil `-( )-` (`/`, `S`, `R`, `P`,
//! `N`), with its variable above; power rails are thick vertical lines;
//! connections are orthogonal polylines; connectors and continuations
//! are arrow boxes with their name; a jump is `>>label`, a label
//! `label:`, a return `<RETURN>`; a comment is a pale box with its text.
//!
//! Every element carries a `class` (`block`, `variable`, `contact`,
//! `coil`, `rail`, `wire`, `connector`, `continuation`, `jump`, `label`,
//! `return`, `comment`, `negation`) and a `data-id` (its localId), so
//! tests and style sheets can find them.

use super::chart_svg;
use super::ld_svg;
use super::network_geometry::{Wire, bounds, input_place, out_place, pin_place, size, wires};
use super::svg_writer::{Element, SvgWriter, num};
use crate::syntax::plcopen::diagram::{Diagram, DiagramElement, ElementKind, Modifiers, PinList};
use crate::syntax::plcopen::network::Edge;

/// Width of one character of the 12 px monospace font.
const CHAR_W: f64 = 7.2;
/// Space around each network and above it for its title.
const MARGIN: f64 = 20.0;
/// Height of a network's title line.
const TITLE_H: f64 = 24.0;
/// Radius of a negation circle.
const NEG_R: f64 = 3.5;

/// One network to draw: its title and its diagram.
pub struct Network<'a> {
    /// The POU it is the body of.
    pub pou: &'a str,
    /// Its diagram.
    pub diagram: &'a Diagram,
}

/// The SVG document of `networks`, one under the other.
pub fn networks_svg(networks: &[Network]) -> String {
    let mut placed = Vec::new();
    let (mut width, mut height) = (0.0f64, 0.0f64);
    for n in networks {
        let wires = wires(n.diagram);
        let (x0, y0, x1, y1) = bounds(n.diagram, &wires).unwrap_or((0.0, 0.0, 0.0, 0.0));
        let title_w = (n.pou.chars().count() + 6) as f64 * CHAR_W;
        let w = (x1 - x0).max(title_w) + 2.0 * MARGIN;
        let dx = MARGIN - x0;
        let dy = height + TITLE_H + MARGIN - y0;
        placed.push((n, wires, dx, dy, height));
        height += TITLE_H + (y1 - y0) + 2.0 * MARGIN;
        width = width.max(w);
    }
    let mut svg = SvgWriter::new(width.max(1.0), height.max(1.0));
    for (n, wires, dx, dy, top) in &placed {
        network(&mut svg, n, wires, (*dx, *dy), *top);
    }
    svg.finish()
}

/// One network: its title, its wires, then its elements on top.
fn network(svg: &mut SvgWriter, n: &Network, wires: &[Wire], (dx, dy): (f64, f64), top: f64) {
    let lang = n.diagram.language.tag();
    svg.open(
        Element::new("g")
            .attr("class", format!("network {}", lang.to_ascii_lowercase()))
            .attr("data-pou", n.pou),
    );
    svg.text(
        Element::new("text")
            .attr("class", "title")
            .num("x", MARGIN)
            .num("y", top + MARGIN)
            .attr("font-weight", "bold"),
        &format!("{} ({lang})", n.pou),
    );
    svg.open(Element::new("g").attr("transform", format!("translate({} {})", num(dx), num(dy))));
    for w in wires {
        svg.empty(
            Element::new("polyline")
                .attr("class", "wire")
                .points(&w.points)
                .attr("fill", "none")
                .attr("stroke", "black"),
        );
    }
    for el in &n.diagram.elements {
        element(svg, el);
    }
    svg.close();
    svg.close();
}

/// A group for element `el` with its class and localId.
pub(super) fn group(el: &DiagramElement, class: &str) -> Element {
    Element::new("g")
        .attr("class", class.to_string())
        .attr("data-id", el.id.clone())
}

/// A text at `(x, y)` anchored as `anchor` (`start`, `middle`, `end`).
pub(super) fn label(
    svg: &mut SvgWriter,
    class: &str,
    (x, y): (f64, f64),
    anchor: &str,
    text: &str,
) {
    svg.text(
        Element::new("text")
            .attr("class", class.to_string())
            .num("x", x)
            .num("y", y)
            .attr("text-anchor", anchor.to_string()),
        text,
    );
}

/// A plain black line.
pub(super) fn line(svg: &mut SvgWriter, (x1, y1): (f64, f64), (x2, y2): (f64, f64), width: f64) {
    svg.empty(chart_svg::line(x1, y1, x2, y2).num("stroke-width", width));
}

/// The `<rect>` of an element's box, at its place and size; the caller
/// adds fill and stroke.
fn frame(el: &DiagramElement) -> Element {
    let (w, h) = size(el);
    Element::new("rect")
        .num("x", el.position.x)
        .num("y", el.position.y)
        .num("width", w)
        .num("height", h)
}

/// A negation circle whose edge touches the point `(x, y)` on the side
/// `toward` (-1: left of it, 1: right of it).
fn negation(svg: &mut SvgWriter, (x, y): (f64, f64), toward: f64) {
    svg.empty(
        Element::new("circle")
            .attr("class", "negation")
            .num("cx", x + toward * NEG_R)
            .num("cy", y)
            .num("r", NEG_R)
            .attr("fill", "white")
            .attr("stroke", "black"),
    );
}

/// One element.
fn element(svg: &mut SvgWriter, el: &DiagramElement) {
    match &el.kind {
        ElementKind::Block {
            type_name,
            instance,
        } => block(svg, el, type_name, instance.as_deref()),
        ElementKind::InVariable | ElementKind::OutVariable | ElementKind::InOutVariable => {
            variable(svg, el)
        }
        ElementKind::Contact => ld_svg::contact_or_coil(svg, el, true),
        ElementKind::Coil => ld_svg::contact_or_coil(svg, el, false),
        ElementKind::LeftRail | ElementKind::RightRail => ld_svg::rail(svg, el),
        ElementKind::Connector(name) => named_arrow(svg, el, "connector", name, false),
        ElementKind::Continuation(name) => named_arrow(svg, el, "continuation", name, true),
        ElementKind::Jump(target) => jump(svg, el, target),
        ElementKind::Label(name) => {
            svg.open(group(el, "label"));
            let (_, h) = size(el);
            let at = (el.position.x, el.position.y + h / 2.0 + 4.0);
            label(svg, "name", at, "start", &format!("{name}:"));
            svg.close();
        }
        ElementKind::Return => {
            svg.open(group(el, "return"));
            let (_, h) = size(el);
            let at = (el.position.x, el.position.y + h / 2.0 + 4.0);
            label(svg, "name", at, "start", "<RETURN>");
            svg.close();
        }
        ElementKind::Comment => comment(svg, el),
        // Charts are drawn from the parsed chart (`chart_svg`), never here.
        ElementKind::Step { .. }
        | ElementKind::Transition { .. }
        | ElementKind::SelectionDivergence
        | ElementKind::SelectionConvergence
        | ElementKind::SimultaneousDivergence
        | ElementKind::SimultaneousConvergence
        | ElementKind::JumpStep(_)
        | ElementKind::ActionBlock(_) => {}
    }
}

/// A block: box, type name, instance name above, pins.
fn block(svg: &mut SvgWriter, el: &DiagramElement, type_name: &str, instance: Option<&str>) {
    let (w, _) = size(el);
    let (x, y) = (el.position.x, el.position.y);
    svg.open(group(el, "block").attr("data-type", type_name.to_string()));
    svg.empty(frame(el).attr("fill", "white").attr("stroke", "black"));
    label(svg, "type", (x + w / 2.0, y + 14.0), "middle", type_name);
    if let Some(i) = instance {
        label(svg, "instance", (x + w / 2.0, y - 5.0), "middle", i);
    }
    for pin in el.pins.iter().filter(|p| !p.hidden) {
        if pin.input.is_some() {
            let at = pin_place(el, pin, true);
            label(svg, "pin", (x + 4.0, at.1 + 4.0), "start", &pin.name);
            pin_marks(svg, at, pin.modifiers, -1.0);
        }
        if pin.output.is_some() {
            let at = pin_place(el, pin, false);
            if pin.list != PinList::InOut || pin.input.is_none() {
                label(svg, "pin", (x + w - 4.0, at.1 + 4.0), "end", &pin.name);
            }
            pin_marks(svg, at, pin.modifiers, 1.0);
        }
    }
    svg.close();
}

/// A pin's negation circle or edge wedge, outside the box on side `side`.
fn pin_marks(svg: &mut SvgWriter, at: (f64, f64), m: Modifiers, side: f64) {
    if m.negated {
        negation(svg, at, side);
    }
    if m.edge != Edge::None {
        // The edge symbol: a wedge inside the box, pointing in (rising)
        // or with an `N` beside it (falling).
        let inner = at.0 - side * 6.0;
        svg.empty(
            Element::new("polyline")
                .attr("class", "edge")
                .points(&[(at.0, at.1 - 4.0), (inner, at.1), (at.0, at.1 + 4.0)])
                .attr("fill", "none")
                .attr("stroke", "black"),
        );
        if m.edge == Edge::Falling {
            label(svg, "edge", (inner - side * 2.0, at.1 - 5.0), "middle", "N");
        }
    }
}

/// A variable: a rounded box with its expression.
fn variable(svg: &mut SvgWriter, el: &DiagramElement) {
    let (w, h) = size(el);
    let (x, y) = (el.position.x, el.position.y);
    svg.open(group(el, "variable").attr("data-kind", el.kind.tag()));
    svg.empty(
        frame(el)
            .num("rx", 6.0)
            .attr("fill", "white")
            .attr("stroke", "black"),
    );
    label(
        svg,
        "expression",
        (x + w / 2.0, y + h / 2.0 + 4.0),
        "middle",
        el.text.trim(),
    );
    if el.modifiers.negated
        && let Some(p) = el.inputs.first()
    {
        negation(svg, input_place(el, p.rel), -1.0);
    }
    let out_negated = match el.kind {
        ElementKind::InOutVariable => el.out_modifiers.negated,
        _ => el.modifiers.negated,
    };
    if out_negated && let Some(p) = el.outputs.first() {
        negation(svg, out_place(el, p.rel), 1.0);
    }
    svg.close();
}

/// A connector (arrow box pointing right) or a continuation (the same,
/// notched on its left), with its name.
fn named_arrow(svg: &mut SvgWriter, el: &DiagramElement, class: &str, name: &str, notch: bool) {
    let (w, h) = size(el);
    let (x, y) = (el.position.x, el.position.y);
    let tip = (h / 2.0).min(w / 3.0);
    let mut pts = vec![
        (x, y),
        (x + w - tip, y),
        (x + w, y + h / 2.0),
        (x + w - tip, y + h),
        (x, y + h),
    ];
    if notch {
        pts.push((x + tip, y + h / 2.0));
    }
    svg.open(group(el, class));
    svg.empty(
        Element::new("polygon")
            .points(&pts)
            .attr("fill", "white")
            .attr("stroke", "black"),
    );
    let text_x = x + if notch { tip } else { 0.0 } + (w - tip) / 2.0;
    label(svg, "name", (text_x, y + h / 2.0 + 4.0), "middle", name);
    svg.close();
}

/// A jump: `>>` and its label.
fn jump(svg: &mut SvgWriter, el: &DiagramElement, target: &str) {
    let (_, h) = size(el);
    let (x, mid) = (el.position.x, el.position.y + h / 2.0);
    svg.open(group(el, "jump"));
    for dx in [0.0, 6.0] {
        svg.empty(
            Element::new("polyline")
                .points(&[
                    (x + dx, mid - 5.0),
                    (x + dx + 6.0, mid),
                    (x + dx, mid + 5.0),
                ])
                .attr("fill", "none")
                .attr("stroke", "black"),
        );
    }
    label(svg, "name", (x + 16.0, mid + 4.0), "start", target);
    svg.close();
}

/// A comment: a pale box with its lines.
fn comment(svg: &mut SvgWriter, el: &DiagramElement) {
    let (_, h) = size(el);
    let (x, y) = (el.position.x, el.position.y);
    svg.open(group(el, "comment"));
    svg.empty(frame(el).attr("fill", "#fffbe6").attr("stroke", "#b0a060"));
    for (i, text) in el.text.lines().enumerate() {
        let ty = y + 16.0 + i as f64 * 14.0;
        if ty > y + h {
            break;
        }
        label(svg, "text", (x + 6.0, ty), "start", text);
    }
    svg.close();
}

//! The symbols of LD: contacts `-| |-`, coils `-( )-` (with the letter
//! of their negation, edge or storage inside and their variable above),
//! and power rails.

use super::network_geometry::size;
use super::network_svg::{group, label, line};
use super::svg_writer::{Element, SvgWriter};
use crate::syntax::plcopen::diagram::{DiagramElement, Modifiers};
use crate::syntax::plcopen::network::{Edge, Storage};

/// The letter inside a contact or coil, if any.
fn symbol_letter(m: Modifiers, coil: bool) -> &'static str {
    match (m.edge, m.storage, m.negated) {
        (Edge::Rising, _, _) => "P",
        (Edge::Falling, _, _) => "N",
        (_, Storage::Set, _) if coil => "S",
        (_, Storage::Reset, _) if coil => "R",
        (_, _, true) => "/",
        _ => "",
    }
}

/// A contact `-| |-` or a coil `-( )-` with its variable above.
pub(super) fn contact_or_coil(svg: &mut SvgWriter, el: &DiagramElement, contact: bool) {
    let (w, h) = size(el);
    let (x, y) = (el.position.x, el.position.y);
    let mid = y + h / 2.0;
    let letter = symbol_letter(el.modifiers, !contact);
    let class = if contact { "contact" } else { "coil" };
    svg.open(group(el, class).attr("data-symbol", letter));
    if contact {
        line(svg, (x + 2.0, y), (x + 2.0, y + h), 2.0);
        line(svg, (x + w - 2.0, y), (x + w - 2.0, y + h), 2.0);
    } else {
        let r = h / 2.0;
        let d = format!(
            "M {} {} A {r} {r} 0 0 0 {} {} M {} {} A {r} {r} 0 0 1 {} {}",
            x + r * 0.6,
            y,
            x + r * 0.6,
            y + h,
            x + w - r * 0.6,
            y,
            x + w - r * 0.6,
            y + h,
        );
        svg.empty(
            Element::new("path")
                .attr("d", d)
                .attr("fill", "none")
                .attr("stroke", "black")
                .num("stroke-width", 1.5),
        );
    }
    line(svg, (x, mid), (x + 2.0, mid), 1.0);
    line(svg, (x + w - 2.0, mid), (x + w, mid), 1.0);
    if !letter.is_empty() {
        label(svg, "symbol", (x + w / 2.0, mid + 4.0), "middle", letter);
    }
    label(
        svg,
        "name",
        (x + w / 2.0, y - 4.0),
        "middle",
        el.text.trim(),
    );
    svg.close();
}

/// A power rail: a thick vertical line.
pub(super) fn rail(svg: &mut SvgWriter, el: &DiagramElement) {
    let (w, h) = size(el);
    svg.open(group(el, "rail"));
    svg.empty(
        Element::new("rect")
            .num("x", el.position.x)
            .num("y", el.position.y)
            .num("width", w.min(4.0))
            .num("height", h)
            .attr("fill", "black"),
    );
    svg.close();
}

//! SFC breakpoints in a chart drawn in PLCopen XML (graphical SFC): the
//! lines of its `<step>` elements (the step becoming active), of the
//! `<action>` elements of its action blocks (the action running) and of
//! its `<transition>` elements (the transition firing), found in the XML
//! of the POU whose body the chart is. A transition is found when it goes
//! from one step to one step (or to a `<jumpStep>`); one behind a
//! divergence or convergence has no breakpoint place.

use super::debug_lines::SfcElement;
use crate::ir::chart::Chart;
use roxmltree::{Document, Node};
use std::collections::HashMap;

/// A breakpoint place of the chart: what it watches, its 1-based line and
/// the name the stack shows.
pub(super) type XmlPlace = (SfcElement, u32, String);

/// The places of `chart`, drawn in the XML `text`, whose POU holds byte
/// offset `at` (where the chart's instruction points); empty when the text
/// is no XML or holds no chart there.
pub(super) fn xml_places(chart: &Chart, text: &str, at: usize) -> Vec<XmlPlace> {
    let Ok(doc) = Document::parse(text) else {
        return Vec::new();
    };
    let Some(pou) = doc
        .descendants()
        .rfind(|n| n.has_tag_name("pou") && n.range().contains(&at))
    else {
        return Vec::new();
    };
    let line = |n: Node| doc.text_pos_at(n.range().start).row;
    let step_of = |name: &str| {
        chart
            .steps
            .iter()
            .position(|s| s.name.eq_ignore_ascii_case(name))
    };
    let mut places = Vec::new();
    // localId -> step index, for the transitions.
    let mut steps: HashMap<&str, usize> = HashMap::new();
    let sfc = pou.descendants().filter(|n| n.has_tag_name("SFC"));
    for node in sfc.flat_map(|s| s.children()).filter(Node::is_element) {
        match node.tag_name().name() {
            "step" => {
                let Some(s) = node.attribute("name").and_then(step_of) else {
                    continue;
                };
                if let Some(id) = node.attribute("localId") {
                    steps.insert(id, s);
                }
                let name = chart.steps[s].name.clone();
                places.push((SfcElement::Step(s as u32), line(node), name));
            }
            "actionBlock" => {
                for action in node.children().filter(|n| n.has_tag_name("action")) {
                    let named = action
                        .children()
                        .find(|n| n.has_tag_name("reference"))
                        .and_then(|r| r.attribute("name"));
                    let found = named.and_then(|n| {
                        chart
                            .actions
                            .iter()
                            .position(|a| a.name.eq_ignore_ascii_case(n))
                    });
                    if let Some(a) = found {
                        let name = chart.actions[a].name.clone();
                        places.push((SfcElement::Action(a as u32), line(action), name));
                    }
                }
            }
            _ => {}
        }
    }
    let sfc = pou.descendants().filter(|n| n.has_tag_name("SFC"));
    let elements: Vec<Node> = sfc
        .flat_map(|s| s.children())
        .filter(Node::is_element)
        .collect();
    for t in elements.iter().filter(|n| n.has_tag_name("transition")) {
        if let Some(place) = transition_place(chart, &elements, &steps, *t, &step_of) {
            places.push((place.0, line(*t), place.1));
        }
    }
    places
}

/// The transition `t` goes from one step to one step (or jump): its index
/// in the chart and its `FROM -> TO` name.
fn transition_place(
    chart: &Chart,
    elements: &[Node],
    steps: &HashMap<&str, usize>,
    t: Node,
    step_of: &dyn Fn(&str) -> Option<usize>,
) -> Option<(SfcElement, String)> {
    let from = *steps.get(incoming(t)?)?;
    let id = t.attribute("localId")?;
    let next = elements.iter().find(|n| incoming(**n) == Some(id))?;
    let to = match next.tag_name().name() {
        "step" => step_of(next.attribute("name")?)?,
        "jumpStep" => step_of(next.attribute("targetName")?)?,
        _ => return None,
    };
    let k = chart
        .transitions
        .iter()
        .position(|tr| tr.from == [from as u32] && tr.to == [to as u32])?;
    let name = format!("{} -> {}", chart.steps[from].name, chart.steps[to].name);
    Some((SfcElement::Transition(k as u32), name))
}

/// The `localId` the element's (first) input is connected to.
fn incoming<'a>(n: Node<'a, 'a>) -> Option<&'a str> {
    n.children()
        .find(|c| c.has_tag_name("connectionPointIn"))?
        .children()
        .find(|c| c.has_tag_name("connection"))?
        .attribute("refLocalId")
}

//! An `<SFC>` body: the network of steps, transitions, divergences,
//! convergences, jumps and action blocks, connected by `refLocalId`,
//! becomes textual SFC: `STEP`s with their action associations,
//! `TRANSITION FROM ... TO ...` in document order, and `ACTION`s.

use super::body::{SFC_STATEMENTS_DATA, add_data, data_element, text_body};
use super::codes;
use super::emit::{Emitter, child, elements, is_identifier, is_true};
use super::graphic::{self, Lowering};
use roxmltree::Node;
use std::collections::HashMap;

/// What a network element is.
#[derive(Debug, Clone, PartialEq)]
enum Kind {
    Step { name: String, initial: bool },
    Transition,
    SelectionDivergence,
    SelectionConvergence,
    SimultaneousDivergence,
    SimultaneousConvergence,
    Jump { target: String },
    ActionBlock,
}

/// One element of the network with the elements it is connected from.
struct Element<'a, 'i> {
    kind: Kind,
    node: Node<'a, 'i>,
    /// Indices of the elements its `connectionPointIn`s name.
    inputs: Vec<usize>,
}

/// The network of one chart.
struct Network<'a, 'i> {
    elements: Vec<Element<'a, 'i>>,
    /// For each element, the elements connected from it (action blocks excluded).
    outputs: Vec<Vec<usize>>,
    /// Step name (upper case) to element index.
    steps: HashMap<String, usize>,
}

/// Emits the chart of `pou` whose body is `body` with language element `sfc`.
pub fn chart(em: &mut Emitter, pou: Node, body: Node, sfc: Node) {
    let Some(net) = network(em, sfc) else {
        return;
    };
    // The graphical elements of the chart (conditions wired to them) and
    // the actions written in FBD or LD: their hidden variables first.
    let Some(wired) = graphic::prepare(em, pou, sfc, true, "") else {
        return;
    };
    let actions = named_bodies(em, pou, "actions", "action");
    let mut graphical_actions = Vec::new();
    for (k, (name, action)) in actions.iter().enumerate() {
        let lang = child(*action, "body")
            .and_then(|b| elements(b).find(|c| matches!(c.tag_name().name(), "FBD" | "LD")));
        if let Some(lang) = lang {
            let prefix = format!("_A{}", k + 1);
            match graphic::prepare(em, pou, lang, false, &prefix) {
                Some(lw) => graphical_actions.push((name.clone(), lw)),
                None => return,
            }
        }
    }
    // Inline actions of action blocks written in FBD or LD.
    let mut graphical_inline = Vec::new();
    let inlines = elements(sfc)
        .filter(|b| b.tag_name().name() == "actionBlock")
        .flat_map(elements)
        .filter_map(|a| child(a, "inline"));
    for (k, inline) in inlines.enumerate() {
        if let Some(lang) = elements(inline).find(|c| matches!(c.tag_name().name(), "FBD" | "LD")) {
            match graphic::prepare(em, pou, lang, false, &format!("_I{}", k + 1)) {
                Some(lw) => graphical_inline.push((inline, lw)),
                None => return,
            }
        }
    }
    wired.declarations(em, em.at(sfc));
    for (_, lw) in &graphical_actions {
        lw.declarations(em, em.at(sfc));
    }
    for (_, lw) in &graphical_inline {
        lw.declarations(em, em.at(sfc));
    }
    let named_transitions = named_bodies(em, pou, "transitions", "transition");
    let mut inline_actions = Vec::new();
    for (i, el) in net.elements.iter().enumerate() {
        if let Kind::Step { name, initial } = &el.kind {
            step(em, &net, i, name, *initial, &mut inline_actions);
        }
    }
    for (i, el) in net.elements.iter().enumerate() {
        if el.kind == Kind::Transition {
            transition(em, &net, i, &named_transitions, &wired, pou);
        }
    }
    for (name, action) in actions {
        match graphical_actions
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(&name))
        {
            Some((_, lw)) => graphical_action(em, &name, action, lw),
            None => action_decl(em, &name, action, child(action, "body")),
        }
    }
    for (name, inline) in inline_actions {
        match graphical_inline.iter().find(|(n, _)| *n == inline) {
            Some((_, lw)) => graphical_action(em, &name, inline, lw),
            None => action_decl(em, &name, inline, Some(inline)),
        }
    }
    // The chart's blocks run as its plain statements, after the actions
    // of every call.
    if !wired.is_empty() {
        wired.statements(em, em.at(sfc));
    }
    for add in elements(body).filter(|c| c.tag_name().name() == "addData") {
        statements(em, add);
    }
}

/// `ACTION name : <lowered network> END_ACTION` for an action (named, or
/// inline in an action block) written in FBD or LD.
fn graphical_action(em: &mut Emitter, name: &str, node: Node, lw: &Lowering) {
    let at = em.at(node);
    em.synth("ACTION", at);
    em.ident(name, em.attr_range(node, "name").unwrap_or(at));
    em.synth(":", at);
    lw.statements(em, at);
    em.synth("END_ACTION", em.end_of(node));
}

/// Reads the elements and their connections; `None` after a reported
/// structural error.
fn network<'a, 'i>(em: &mut Emitter, sfc: Node<'a, 'i>) -> Option<Network<'a, 'i>> {
    let mut elements_ = Vec::new();
    let mut ids: HashMap<&str, usize> = HashMap::new();
    let mut ok = true;
    for node in elements(sfc) {
        let Some(kind) = kind_of(em, node) else {
            ok &= matches!(
                node.tag_name().name(),
                "comment" | "documentation" | "addData"
            ) || GRAPHICAL.contains(&node.tag_name().name());
            continue;
        };
        match node.attribute("localId") {
            Some(id) => {
                if ids.insert(id.trim(), elements_.len()).is_some() {
                    let range = em.attr_range(node, "localId").unwrap_or(em.at(node));
                    em.error(
                        codes::DUPLICATE_ID,
                        range,
                        format!("localId {id} is used twice in this chart"),
                    );
                    ok = false;
                }
            }
            None => {
                em.missing(node, "localId");
                ok = false;
            }
        }
        elements_.push(Element {
            kind,
            node,
            inputs: Vec::new(),
        });
    }
    for el in &mut elements_ {
        let points = elements(el.node).filter(|c| c.tag_name().name() == "connectionPointIn");
        for conn in points
            .flat_map(elements)
            .filter(|c| c.tag_name().name() == "connection")
        {
            let target = conn.attribute("refLocalId").map(str::trim);
            match target.and_then(|t| ids.get(t)) {
                Some(&i) => el.inputs.push(i),
                None => {
                    let range = em.attr_range(conn, "refLocalId").unwrap_or(em.at(conn));
                    em.error(
                        codes::DANGLING_REF,
                        range,
                        format!(
                            "refLocalId `{}` names no element of this chart",
                            target.unwrap_or("")
                        ),
                    );
                    ok = false;
                }
            }
        }
    }
    let mut outputs = vec![Vec::new(); elements_.len()];
    let mut steps = HashMap::new();
    for (i, el) in elements_.iter().enumerate() {
        if el.kind != Kind::ActionBlock {
            for &from in &el.inputs {
                outputs[from].push(i);
            }
        }
        if let Kind::Step { name, .. } = &el.kind
            && steps.insert(name.to_ascii_uppercase(), i).is_some()
        {
            em.error(
                codes::SFC_STRUCTURE,
                em.at(el.node),
                format!("step `{name}` is declared twice"),
            );
            ok = false;
        }
    }
    ok.then_some(Network {
        elements: elements_,
        outputs,
        steps,
    })
}

/// FBD and LD elements, which an SFC body may hold to compute its
/// transitions' conditions.
const GRAPHICAL: [&str; 13] = [
    "inVariable",
    "outVariable",
    "inOutVariable",
    "block",
    "connector",
    "continuation",
    "contact",
    "coil",
    "leftPowerRail",
    "rightPowerRail",
    "label",
    "jump",
    "return",
];

/// The kind of a chart element; `None` (reported unless it is a comment)
/// for anything plcrun cannot run.
fn kind_of(em: &mut Emitter, node: Node) -> Option<Kind> {
    Some(match node.tag_name().name() {
        "step" => Kind::Step {
            name: em.required_name(node, "name")?.to_string(),
            initial: is_true(node.attribute("initialStep")),
        },
        "transition" => Kind::Transition,
        "selectionDivergence" => Kind::SelectionDivergence,
        "selectionConvergence" => Kind::SelectionConvergence,
        "simultaneousDivergence" => Kind::SimultaneousDivergence,
        "simultaneousConvergence" => Kind::SimultaneousConvergence,
        "jumpStep" => Kind::Jump {
            target: em.required_name(node, "targetName")?.to_string(),
        },
        "actionBlock" => Kind::ActionBlock,
        "comment" | "documentation" => return None,
        "addData" => {
            add_data(em, node);
            return None;
        }
        "macroStep" => {
            em.refuse(node, "macro steps have no textual SFC form");
            return None;
        }
        // Read by the graphical network of the chart.
        name if GRAPHICAL.contains(&name) => return None,
        _ => {
            em.unknown(node, "SFC");
            return None;
        }
    })
}

/// `<actions>`/`<transitions>` of a POU: name to element.
fn named_bodies<'a, 'i>(
    em: &mut Emitter,
    pou: Node<'a, 'i>,
    list: &str,
    item: &str,
) -> Vec<(String, Node<'a, 'i>)> {
    let mut out = Vec::new();
    for l in elements(pou).filter(|c| c.tag_name().name() == list) {
        for c in elements(l) {
            if c.tag_name().name() == item {
                if let Some(name) = em.required_name(c, "name") {
                    out.push((name.to_string(), c));
                }
            } else if !matches!(c.tag_name().name(), "documentation" | "addData") {
                em.unknown(c, list);
            }
        }
    }
    out
}

/// `[INITIAL_]STEP name : associations END_STEP`.
fn step<'a, 'i>(
    em: &mut Emitter,
    net: &Network<'a, 'i>,
    index: usize,
    name: &str,
    initial: bool,
    inline_actions: &mut Vec<(String, Node<'a, 'i>)>,
) {
    let node = net.elements[index].node;
    let at = em.at(node);
    em.synth(if initial { "INITIAL_STEP" } else { "STEP" }, at);
    em.name(node, "name");
    em.synth(":", at);
    for block in net
        .elements
        .iter()
        .filter(|b| b.kind == Kind::ActionBlock && b.inputs.contains(&index))
    {
        for action in elements(block.node).filter(|a| a.tag_name().name() == "action") {
            association(em, name, action, inline_actions);
        }
    }
    em.synth("END_STEP", em.end_of(node));
}

/// One `<action qualifier duration indicator>` of an action block:
/// `name(Q[, duration][, indicator]);`.
fn association<'a, 'i>(
    em: &mut Emitter,
    step: &str,
    action: Node<'a, 'i>,
    inline_actions: &mut Vec<(String, Node<'a, 'i>)>,
) {
    let at = em.at(action);
    if let Some(reference) = child(action, "reference") {
        if em.name(reference, "name").is_none() {
            return;
        }
    } else if let Some(inline) = child(action, "inline") {
        // Named after its step and its rank among the chart's inline actions.
        let name = format!("{step}_INLINE{}", inline_actions.len());
        em.ident(&name, at);
        inline_actions.push((name, inline));
    } else {
        em.error(
            codes::MISSING_CHILD,
            at,
            "`<action>` needs a `<reference>` or an `<inline>` body",
        );
        return;
    }
    em.synth("(", at);
    match em.attr_range(action, "qualifier") {
        Some(_) => {
            em.lex_attr(action, "qualifier");
        }
        None => em.synth("N", at),
    }
    for attr in ["duration", "indicator"] {
        if action.attribute(attr).is_some_and(|v| !v.trim().is_empty()) {
            em.synth(",", at);
            em.lex_attr(action, attr);
        }
    }
    em.synth(");", at);
}

/// `TRANSITION [name] [(PRIORITY := p)] FROM steps TO steps condition END_TRANSITION`.
fn transition(
    em: &mut Emitter,
    net: &Network,
    index: usize,
    named: &[(String, Node)],
    wired: &Lowering,
    pou: Node,
) {
    let node = net.elements[index].node;
    let at = em.at(node);
    let mut from = Vec::new();
    let mut to = Vec::new();
    let mut ok = true;
    let mut seen = vec![false; net.elements.len()];
    for &i in &net.elements[index].inputs {
        ok &= preceding(em, net, i, &mut from, &mut seen);
    }
    let mut seen = vec![false; net.elements.len()];
    for &i in &net.outputs[index] {
        ok &= following(em, net, i, &mut to, &mut seen);
    }
    if !ok {
        return;
    }
    if from.is_empty() || to.is_empty() {
        let which = if from.is_empty() {
            "no step before it"
        } else {
            "no step after it"
        };
        em.error(
            codes::SFC_STRUCTURE,
            at,
            format!("this transition has {which}"),
        );
        return;
    }
    em.synth("TRANSITION", at);
    let condition = child(node, "condition");
    if let Some(name) = condition
        .and_then(|c| child(c, "inline"))
        .and_then(|i| i.attribute("name"))
        && is_identifier(name)
    {
        em.ident(name, at);
    }
    if node.attribute("priority").is_some() {
        em.synth("(PRIORITY :=", at);
        em.lex_attr(node, "priority");
        em.synth(")", at);
    }
    em.synth("FROM", at);
    step_set(em, &from, at);
    em.synth("TO", at);
    step_set(em, &to, at);
    match condition {
        Some(c) => transition_condition(em, c, named, (wired, pou), node),
        None => em.error(
            codes::MISSING_CHILD,
            at,
            "`<transition>` needs a `<condition>`",
        ),
    }
    em.synth("END_TRANSITION", em.end_of(node));
}

/// `a` or `(a, b)`.
fn step_set(em: &mut Emitter, names: &[String], at: (usize, usize)) {
    if names.len() > 1 {
        em.synth("(", at);
    }
    for (k, n) in names.iter().enumerate() {
        if k > 0 {
            em.synth(",", at);
        }
        em.ident(n, at);
    }
    if names.len() > 1 {
        em.synth(")", at);
    }
}

/// The steps a transition's input comes from, through selection
/// divergences and simultaneous convergences.
fn preceding(
    em: &mut Emitter,
    net: &Network,
    i: usize,
    out: &mut Vec<String>,
    seen: &mut [bool],
) -> bool {
    // Each element is visited once per transition, so a cycle of bars or a
    // dense mesh of them ends, in linear time.
    if std::mem::replace(&mut seen[i], true) {
        return true;
    }
    let el = &net.elements[i];
    match &el.kind {
        Kind::Step { name, .. } => {
            if !out.contains(name) {
                out.push(name.clone());
            }
            true
        }
        Kind::SelectionDivergence | Kind::SimultaneousConvergence => {
            el.inputs.iter().all(|&j| preceding(em, net, j, out, seen))
        }
        _ => {
            wrong_link(
                em,
                el.node,
                "a transition must be connected from a step, a selection divergence or a simultaneous convergence",
            );
            false
        }
    }
}

/// The steps a transition leads to, through simultaneous divergences,
/// selection convergences and jumps.
fn following(
    em: &mut Emitter,
    net: &Network,
    i: usize,
    out: &mut Vec<String>,
    seen: &mut [bool],
) -> bool {
    // Each element is visited once per transition, so a cycle of bars or a
    // dense mesh of them ends, in linear time.
    if std::mem::replace(&mut seen[i], true) {
        return true;
    }
    let el = &net.elements[i];
    match &el.kind {
        Kind::Step { name, .. } => {
            if !out.contains(name) {
                out.push(name.clone());
            }
            true
        }
        Kind::Jump { target } => match net.steps.get(&target.to_ascii_uppercase()) {
            Some(&s) => following(em, net, s, out, seen),
            None => {
                let range = em
                    .attr_range(el.node, "targetName")
                    .unwrap_or(em.at(el.node));
                em.error(
                    codes::UNKNOWN_JUMP_TARGET,
                    range,
                    format!("jump to `{target}`, a step this chart does not have"),
                );
                false
            }
        },
        Kind::SimultaneousDivergence | Kind::SelectionConvergence => net.outputs[i]
            .iter()
            .all(|&j| following(em, net, j, out, seen)),
        _ => {
            wrong_link(
                em,
                el.node,
                "a transition must lead to a step, a jump, a simultaneous divergence or a selection convergence",
            );
            false
        }
    }
}

/// Reports a connection the textual SFC cannot express.
fn wrong_link(em: &mut Emitter, node: Node, why: &str) {
    em.error(
        codes::SFC_STRUCTURE,
        em.at(node),
        format!("`<{}>` here: {why}", node.tag_name().name()),
    );
}

/// `<condition>`: inline ST/IL, or a reference to a named transition.
fn transition_condition(
    em: &mut Emitter,
    cond: Node,
    named: &[(String, Node)],
    (wired, pou): (&Lowering, Node),
    transition: Node,
) {
    let mut reference = "";
    let negated = is_true(cond.attribute("negated"));
    let Some(kind) = elements(cond)
        .find(|c| c.tag_name().name() != "documentation" && c.tag_name().name() != "addData")
    else {
        em.error(codes::MISSING_CHILD, em.at(cond), "`<condition>` is empty");
        return;
    };
    let lang = match kind.tag_name().name() {
        "inline" => {
            elements(kind).find(|c| matches!(c.tag_name().name(), "ST" | "IL" | "FBD" | "LD"))
        }
        "reference" => {
            let Some(name) = em.required_name(kind, "name") else {
                return;
            };
            reference = name;
            match named.iter().find(|(n, _)| n.eq_ignore_ascii_case(name)) {
                Some((_, t)) => child(*t, "body").and_then(|b| {
                    elements(b)
                        .find(|c| matches!(c.tag_name().name(), "ST" | "IL" | "FBD" | "LD" | "SFC"))
                }),
                None => {
                    let range = em.attr_range(kind, "name").unwrap_or(em.at(kind));
                    em.error(
                        codes::UNKNOWN_REFERENCE,
                        range,
                        format!("no transition `{name}` in this POU's `<transitions>`"),
                    );
                    return;
                }
            }
        }
        "connectionPointIn" => {
            em.synth(":=", em.at(kind));
            if negated {
                em.synth("NOT (", em.at(cond));
            }
            wired.condition(em, transition);
            if negated {
                em.synth(")", em.at(cond));
            }
            em.synth(";", em.end_of(cond));
            return;
        }
        _ => {
            em.unknown(kind, "condition");
            return;
        }
    };
    let Some(lang) = lang else {
        em.error(
            codes::MISSING_CHILD,
            em.at(kind),
            "the condition has no ST or IL body",
        );
        return;
    };
    match lang.tag_name().name() {
        "ST" => st_condition(em, lang, negated),
        "IL" if negated => em.refuse(cond, "a negated IL condition"),
        "IL" => {
            em.synth(":", em.at(lang));
            text_body(em, lang);
        }
        "FBD" | "LD" => {
            if let Some(lw) = graphic::prepare(em, pou, lang, false, "_X") {
                em.synth(":=", em.at(lang));
                if negated {
                    em.synth("NOT (", em.at(cond));
                }
                if let Err(why) = lw.transition_value(em, reference) {
                    em.refuse(lang, &why);
                }
                if negated {
                    em.synth(")", em.at(cond));
                }
                em.synth(";", em.end_of(lang));
            }
        }
        _ => em.refuse(lang, "a transition written in SFC"),
    }
}

/// `:= expr;` from an ST condition, written as a bare expression (inline)
/// or as `:= expr;` (a named transition's body).
fn st_condition(em: &mut Emitter, lang: Node, negated: bool) {
    let at = em.at(lang);
    let start = em.toks.len();
    text_body(em, lang);
    let mut body: Vec<_> = em
        .toks
        .drain(start..)
        .filter(|t| t.1 != crate::syntax::token::Tok::Eol)
        .collect();
    if body
        .first()
        .is_some_and(|t| t.1 == crate::syntax::token::Tok::Assign)
    {
        body.remove(0);
    }
    while body
        .last()
        .is_some_and(|t| t.1 == crate::syntax::token::Tok::Semi)
    {
        body.pop();
    }
    em.synth(":=", at);
    if negated {
        em.synth("NOT (", at);
    }
    em.toks.extend(body);
    if negated {
        em.synth(")", em.end_of(lang));
    }
    em.synth(";", em.end_of(lang));
}

/// `ACTION name : body END_ACTION` from a named `<action>` (its `<body>`)
/// or an inline one.
fn action_decl(em: &mut Emitter, name: &str, node: Node, body: Option<Node>) {
    let at = em.at(node);
    let lang = body.and_then(|b| {
        elements(b).find(|c| matches!(c.tag_name().name(), "ST" | "IL" | "FBD" | "LD" | "SFC"))
    });
    let Some(lang) = lang else {
        em.error(
            codes::MISSING_CHILD,
            at,
            format!("action `{name}` has no ST or IL body"),
        );
        return;
    };
    match lang.tag_name().name() {
        "ST" | "IL" => {
            em.synth("ACTION", at);
            em.ident(name, em.attr_range(node, "name").unwrap_or(at));
            em.synth(":", at);
            text_body(em, lang);
            em.synth("END_ACTION", em.end_of(node));
        }
        "SFC" => em.refuse(lang, "an action written in SFC"),
        _ => em.refuse(lang, "this action's FBD/LD body has no place here"),
    }
}

/// plcrun's plain statements of an SFC body, kept in `<addData>`.
fn statements(em: &mut Emitter, add: Node) {
    for data in elements(add) {
        if data.attribute("name") == Some(SFC_STATEMENTS_DATA) {
            for lang in elements(data) {
                match lang.tag_name().name() {
                    "ST" => text_body(em, lang),
                    _ => em.unknown(lang, "data"),
                }
            }
        } else if data.tag_name().name() == "data" {
            data_element(em, data);
        } else {
            em.unknown(data, "addData");
        }
    }
}

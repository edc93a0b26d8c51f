//! The network of an `<FBD>` or `<LD>` body, read from the XML: its
//! elements, their input pins with the connections feeding them, and their
//! output pins. Connections to a `<continuation>` are resolved to what
//! feeds the `<connector>` of the same name, so the rest of the lowering
//! sees direct connections only.

use super::codes;
use super::emit::{Emitter, child, elements, is_identifier, is_true};
use roxmltree::Node;
use std::collections::HashMap;

/// What a network element is.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// `<inVariable>`: an ST expression read.
    InVariable,
    /// `<outVariable>`: a variable written.
    OutVariable,
    /// `<inOutVariable>`: a variable written, then read.
    InOutVariable,
    /// `<block typeName instanceName>`: a function (no instance) or a
    /// function block instance.
    Block {
        /// The function or function block type.
        type_name: String,
        /// The instance of a function block.
        instance: Option<String>,
    },
    /// `<connector name>`: the entry of a named connection.
    Connector,
    /// `<continuation name>`: the exit of a named connection.
    Continuation,
    /// `<jump label>`.
    Jump(String),
    /// `<label label>`.
    Label(String),
    /// `<return>`.
    Return,
    /// `<leftPowerRail>`: TRUE.
    LeftRail,
    /// `<rightPowerRail>`: nothing.
    RightRail,
    /// `<contact>`: a Boolean variable in series with the power flow.
    Contact,
    /// `<coil>`: the power flow written to a Boolean variable.
    Coil,
    /// The `<condition>` of an SFC `<transition>` wired to the network:
    /// read by the chart, it writes nothing.
    Condition,
}

/// Edge detection of a pin, contact or coil (`edge="rising|falling"`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Edge {
    /// No edge detection.
    None,
    /// `R_TRIG`.
    Rising,
    /// `F_TRIG`.
    Falling,
}

/// Latching of a coil or output (`storage="set|reset"`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Storage {
    /// Plain assignment.
    None,
    /// Written TRUE when the power flow is TRUE.
    Set,
    /// Written FALSE when the power flow is TRUE.
    Reset,
}

/// Where a connection comes from: element `from`, output pin `pin`.
#[derive(Debug, Clone)]
pub struct Source<'a, 'i> {
    /// The index of the element.
    pub from: usize,
    /// The output pin's name (`formalParameter`; empty for elements with one output).
    pub pin: String,
    /// The `<connection>` element, where problems are reported.
    pub at: Node<'a, 'i>,
}

/// An input pin and what feeds it (several sources are ORed, as a ladder
/// rung joins parallel branches).
#[derive(Debug, Clone)]
pub struct Input<'a, 'i> {
    /// The formal parameter (empty for variables, contacts and coils).
    pub name: String,
    /// The element describing the pin (a block's `<variable>`, else the element).
    pub node: Node<'a, 'i>,
    /// `negated="true"`.
    pub negated: bool,
    /// `edge`.
    pub edge: Edge,
    /// An input-output pin of a block (`<inOutVariables>`).
    pub in_out: bool,
    /// The connections feeding it.
    pub sources: Vec<Source<'a, 'i>>,
}

/// An output pin of a block.
#[derive(Debug, Clone)]
pub struct Output {
    /// The formal parameter.
    pub name: String,
    /// `negated="true"`.
    pub negated: bool,
    /// An input-output pin (its value is the variable given to the input).
    pub in_out: bool,
}

/// One element of the network.
#[derive(Debug, Clone)]
pub struct Element<'a, 'i> {
    /// Its kind.
    pub kind: Kind,
    /// The XML element.
    pub node: Node<'a, 'i>,
    /// Its `localId`.
    pub id: String,
    /// Its input pins.
    pub inputs: Vec<Input<'a, 'i>>,
    /// Its output pins (blocks only).
    pub outputs: Vec<Output>,
    /// `executionOrderId`, 0 when absent.
    pub order: u64,
    /// `<position x y>` as (y, x).
    pub position: (i64, i64),
    /// `negated` (or `negatedOut` of an in-out variable: the value read).
    pub negated: bool,
    /// `negatedIn` of an in-out variable, `negated` of an out-variable or coil.
    pub negated_in: bool,
    /// `edge` (or `edgeIn`).
    pub edge: Edge,
    /// `storage` (or `storageIn`).
    pub storage: Storage,
}

/// The elements of one body, with their connections resolved.
pub struct Network<'a, 'i> {
    /// The elements, in document order.
    pub elements: Vec<Element<'a, 'i>>,
}

/// Reads a network; `None` after a reported error.
///
/// With `in_sfc`, `body` is an `<SFC>`: its chart elements are left to the
/// chart, and each `<transition>` whose `<condition>` holds a
/// `<connectionPointIn>` gives a [`Kind::Condition`] element.
pub fn read<'a, 'i>(em: &mut Emitter, body: Node<'a, 'i>, in_sfc: bool) -> Option<Network<'a, 'i>> {
    let mut out = Vec::new();
    let mut ids: HashMap<&str, usize> = HashMap::new();
    let mut ok = true;
    let mut conditions = Vec::new();
    let mut chart_ids = Vec::new();
    for node in elements(body) {
        if in_sfc && SFC_ELEMENTS.contains(&node.tag_name().name()) {
            if let Some(id) = node.attribute("localId") {
                chart_ids.push(id.trim());
            }
            if let Some(cond) = wired_condition(node) {
                conditions.push((node, cond));
            }
            continue;
        }
        let Some(kind) = kind_of(em, node, &mut ok) else {
            continue;
        };
        let Some(id) = node.attribute("localId").map(str::trim) else {
            em.missing(node, "localId");
            ok = false;
            continue;
        };
        if ids.insert(id, out.len()).is_some() {
            let range = em.attr_range(node, "localId").unwrap_or(em.at(node));
            em.error(
                codes::DUPLICATE_ID,
                range,
                format!("localId {id} is used twice in this body"),
            );
            ok = false;
        }
        out.push(element(node, kind, id));
    }
    for (transition, cond) in conditions {
        let id = transition.attribute("localId").unwrap_or("").trim();
        let mut el = element(transition, Kind::Condition, id);
        el.inputs = vec![Input {
            name: String::new(),
            node: cond,
            negated: false,
            edge: Edge::None,
            in_out: false,
            sources: Vec::new(),
        }];
        out.push(el);
    }
    let mut net = Network { elements: out };
    ok &= link(em, &mut net, &ids, &chart_ids);
    ok &= resolve_continuations(em, &mut net);
    ok.then_some(net)
}

/// The elements of an SFC chart, left to the chart when a network is read
/// from an `<SFC>`.
pub const SFC_ELEMENTS: [&str; 9] = [
    "step",
    "transition",
    "selectionDivergence",
    "selectionConvergence",
    "simultaneousDivergence",
    "simultaneousConvergence",
    "jumpStep",
    "actionBlock",
    "macroStep",
];

/// The `<condition>` of a `<transition>` when it is wired to the network.
fn wired_condition<'a, 'i>(node: Node<'a, 'i>) -> Option<Node<'a, 'i>> {
    if node.tag_name().name() != "transition" {
        return None;
    }
    let cond = child(node, "condition")?;
    child(cond, "connectionPointIn").map(|_| cond)
}

/// The kind of an element; `None` for comments, and (reported) for
/// anything that has no place in a graphical body.
fn kind_of(em: &mut Emitter, node: Node, ok: &mut bool) -> Option<Kind> {
    let name = node.tag_name().name();
    let mut named = |attr: &str| -> Option<String> {
        let v = em.required_name(node, attr).map(str::to_string);
        *ok &= v.is_some();
        v
    };
    Some(match name {
        "inVariable" => Kind::InVariable,
        "outVariable" => Kind::OutVariable,
        "inOutVariable" => Kind::InOutVariable,
        "block" => {
            let type_name = named("typeName")?;
            let instance = match node.attribute("instanceName").map(str::trim) {
                None | Some("") => None,
                Some(_) => Some(named("instanceName")?),
            };
            Kind::Block {
                type_name,
                instance,
            }
        }
        "connector" => {
            named("name")?;
            Kind::Connector
        }
        "continuation" => {
            named("name")?;
            Kind::Continuation
        }
        "jump" => Kind::Jump(named("label")?),
        "label" => Kind::Label(named("label")?),
        "return" => Kind::Return,
        "leftPowerRail" => Kind::LeftRail,
        "rightPowerRail" => Kind::RightRail,
        "contact" => Kind::Contact,
        "coil" => Kind::Coil,
        "comment" | "documentation" => return None,
        "addData" => {
            super::body::add_data(em, node);
            return None;
        }
        _ => {
            em.refuse(
                node,
                "this element has no place in an FBD or LD body (SFC elements belong in an <SFC> body)",
            );
            *ok = false;
            return None;
        }
    })
}

/// The element's attributes and pins, before its connections are linked.
fn element<'a, 'i>(node: Node<'a, 'i>, kind: Kind, id: &str) -> Element<'a, 'i> {
    let position = child(node, "position")
        .map(|p| (coordinate(p, "y"), coordinate(p, "x")))
        .unwrap_or((0, 0));
    let (negated, negated_in, edge, storage) = match kind {
        Kind::InOutVariable => (
            is_true(node.attribute("negatedOut")),
            is_true(node.attribute("negatedIn")),
            edge_of(node.attribute("edgeIn")),
            storage_of(node.attribute("storageIn")),
        ),
        _ => {
            let n = is_true(node.attribute("negated"));
            (
                n,
                n,
                edge_of(node.attribute("edge")),
                storage_of(node.attribute("storage")),
            )
        }
    };
    let (inputs, outputs) = pins(node, &kind);
    Element {
        kind,
        node,
        id: id.to_string(),
        inputs,
        outputs,
        order: node
            .attribute("executionOrderId")
            .and_then(|v| v.trim().parse().ok())
            .unwrap_or(0),
        position,
        negated,
        negated_in,
        edge,
        storage,
    }
}

/// An integer attribute of `<position>` (0 when absent or not a number).
fn coordinate(p: Node, name: &str) -> i64 {
    p.attribute(name)
        .and_then(|v| v.trim().parse::<f64>().ok())
        .map_or(0, |v| v as i64)
}

/// `edge="rising|falling"`.
fn edge_of(v: Option<&str>) -> Edge {
    match v.map(str::trim) {
        Some("rising") => Edge::Rising,
        Some("falling") => Edge::Falling,
        _ => Edge::None,
    }
}

/// `storage="set|reset"`.
fn storage_of(v: Option<&str>) -> Storage {
    match v.map(str::trim) {
        Some("set") => Storage::Set,
        Some("reset") => Storage::Reset,
        _ => Storage::None,
    }
}

/// The input and output pins of an element (connections not yet linked).
fn pins<'a, 'i>(node: Node<'a, 'i>, kind: &Kind) -> (Vec<Input<'a, 'i>>, Vec<Output>) {
    let mut inputs = Vec::new();
    let mut outputs = Vec::new();
    if let Kind::Block { .. } = kind {
        for (list, in_out) in [("inputVariables", false), ("inOutVariables", true)] {
            for v in child(node, list).into_iter().flat_map(elements) {
                if v.tag_name().name() == "variable" {
                    inputs.push(Input {
                        name: v
                            .attribute("formalParameter")
                            .unwrap_or("")
                            .trim()
                            .to_string(),
                        node: v,
                        negated: is_true(v.attribute("negated")),
                        edge: edge_of(v.attribute("edge")),
                        in_out,
                        sources: Vec::new(),
                    });
                }
            }
        }
        for (list, in_out) in [("outputVariables", false), ("inOutVariables", true)] {
            for v in child(node, list).into_iter().flat_map(elements) {
                if v.tag_name().name() == "variable" {
                    outputs.push(Output {
                        name: v
                            .attribute("formalParameter")
                            .unwrap_or("")
                            .trim()
                            .to_string(),
                        negated: is_true(v.attribute("negated")),
                        in_out,
                    });
                }
            }
        }
    } else if elements(node).any(|c| c.tag_name().name() == "connectionPointIn") {
        inputs.push(Input {
            name: String::new(),
            node,
            negated: false,
            edge: Edge::None,
            in_out: false,
            sources: Vec::new(),
        });
    }
    (inputs, outputs)
}

/// The `<connectionPointIn>`s of an input pin.
fn points<'a, 'i>(pin: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    elements(pin).filter(|c| c.tag_name().name() == "connectionPointIn")
}

/// Links every `<connection refLocalId formalParameter>` to its element.
fn link(
    em: &mut Emitter,
    net: &mut Network,
    ids: &HashMap<&str, usize>,
    chart_ids: &[&str],
) -> bool {
    let mut ok = true;
    let kinds: Vec<Kind> = net.elements.iter().map(|e| e.kind.clone()).collect();
    let outputs: Vec<Vec<Output>> = net.elements.iter().map(|e| e.outputs.clone()).collect();
    for el in &mut net.elements {
        for input in &mut el.inputs {
            let conns = points(input.node)
                .flat_map(elements)
                .filter(|c| c.tag_name().name() == "connection");
            for conn in conns {
                let target = conn.attribute("refLocalId").map(str::trim);
                let Some(&from) = target.and_then(|t| ids.get(t)) else {
                    if let Some(t) = target.filter(|t| chart_ids.contains(t)) {
                        em.error(
                            codes::BAD_CONNECTION,
                            em.at(conn),
                            format!("this connection comes from chart element {t} (a step, a transition...), which gives no value to an FBD/LD network"),
                        );
                        ok = false;
                        continue;
                    }
                    let range = em.attr_range(conn, "refLocalId").unwrap_or(em.at(conn));
                    em.error(
                        codes::DANGLING_REF,
                        range,
                        format!(
                            "refLocalId `{}` names no element of this body",
                            target.unwrap_or("")
                        ),
                    );
                    ok = false;
                    continue;
                };
                let pin = conn.attribute("formalParameter").unwrap_or("").trim();
                match output_pin(&kinds[from], &outputs[from], pin) {
                    Ok(pin) => input.sources.push(Source {
                        from,
                        pin,
                        at: conn,
                    }),
                    Err(why) => {
                        em.error(codes::BAD_CONNECTION, em.at(conn), why);
                        ok = false;
                    }
                }
            }
        }
    }
    ok
}

/// The output pin a connection names on an element of kind `kind`, or why
/// the element has no such output.
fn output_pin(kind: &Kind, outputs: &[Output], pin: &str) -> Result<String, String> {
    match kind {
        Kind::Block { type_name, .. } => {
            if let Some(o) = outputs.iter().find(|o| o.name.eq_ignore_ascii_case(pin)) {
                return Ok(o.name.clone());
            }
            match outputs {
                [only] if pin.is_empty() => Ok(only.name.clone()),
                [] => Err(format!(
                    "this connection comes from block `{type_name}`, which declares no output"
                )),
                _ if pin.is_empty() => Err(format!(
                    "this connection does not say which output of block `{type_name}` it comes from (formalParameter)"
                )),
                _ => Err(format!("block `{type_name}` has no output `{pin}`")),
            }
        }
        Kind::OutVariable
        | Kind::Jump(_)
        | Kind::Label(_)
        | Kind::Return
        | Kind::RightRail
        | Kind::Connector => Err(format!(
            "this connection comes from {}, which has no output",
            describe(kind)
        )),
        _ => Ok(String::new()),
    }
}

/// How an element kind is named in messages.
pub fn describe(kind: &Kind) -> &'static str {
    match kind {
        Kind::InVariable => "an <inVariable>",
        Kind::OutVariable => "an <outVariable>",
        Kind::InOutVariable => "an <inOutVariable>",
        Kind::Block { .. } => "a <block>",
        Kind::Connector => "a <connector>",
        Kind::Continuation => "a <continuation>",
        Kind::Jump(_) => "a <jump>",
        Kind::Label(_) => "a <label>",
        Kind::Return => "a <return>",
        Kind::LeftRail => "a <leftPowerRail>",
        Kind::RightRail => "a <rightPowerRail>",
        Kind::Contact => "a <contact>",
        Kind::Coil => "a <coil>",
        Kind::Condition => "a transition's <condition>",
    }
}

/// Replaces every connection to a `<continuation>` with the connections
/// feeding the `<connector>` of the same name (through chains of them).
fn resolve_continuations(em: &mut Emitter, net: &mut Network) -> bool {
    let mut connectors: HashMap<String, usize> = HashMap::new();
    let mut ok = true;
    for (i, el) in net.elements.iter().enumerate() {
        if el.kind == Kind::Connector {
            let name = el.node.attribute("name").unwrap_or("").to_ascii_uppercase();
            if connectors.insert(name.clone(), i).is_some() {
                em.error(
                    codes::CONNECTOR,
                    em.at(el.node),
                    format!("two connectors are named `{name}` in this body"),
                );
                ok = false;
            }
        }
    }
    // What each continuation stands for, following chains with a bound.
    let mut resolved: HashMap<usize, Vec<Source>> = HashMap::new();
    for (i, el) in net.elements.iter().enumerate() {
        if el.kind != Kind::Continuation {
            continue;
        }
        match follow(net, &connectors, i) {
            Ok(sources) => {
                resolved.insert(i, sources);
            }
            Err(why) => {
                em.error(codes::CONNECTOR, em.at(el.node), why);
                ok = false;
            }
        }
    }
    for el in &mut net.elements {
        for input in &mut el.inputs {
            let mut sources = Vec::new();
            for s in input.sources.drain(..) {
                match resolved.get(&s.from) {
                    Some(r) => sources.extend(r.iter().cloned()),
                    None => sources.push(s),
                }
            }
            input.sources = sources;
        }
    }
    ok
}

/// The sources a continuation stands for, or why it stands for none.
fn follow<'a, 'i>(
    net: &Network<'a, 'i>,
    connectors: &HashMap<String, usize>,
    start: usize,
) -> Result<Vec<Source<'a, 'i>>, String> {
    let mut current = start;
    for _ in 0..=net.elements.len() {
        let name = net.elements[current]
            .node
            .attribute("name")
            .unwrap_or("")
            .to_string();
        let Some(&c) = connectors.get(&name.to_ascii_uppercase()) else {
            return Err(format!(
                "continuation `{name}` has no connector of the same name in this body"
            ));
        };
        let sources: Vec<Source> = net.elements[c]
            .inputs
            .iter()
            .flat_map(|i| i.sources.iter().cloned())
            .collect();
        match sources.as_slice() {
            [] => return Err(format!("connector `{name}` is not connected to anything")),
            [one] if net.elements[one.from].kind == Kind::Continuation => current = one.from,
            many if many
                .iter()
                .any(|s| net.elements[s.from].kind == Kind::Continuation) =>
            {
                return Err(format!(
                    "connector `{name}` joins a continuation with other connections; plcrun follows a continuation only when it is the connector's one input"
                ));
            }
            _ => return Ok(sources),
        }
    }
    Err("this continuation leads back to itself through connectors".to_string())
}

/// True when `s` can name a hidden variable's part.
pub fn safe_part(s: &str) -> bool {
    is_identifier(s) && !s.contains("__")
}

//! The evaluation order of an FBD or LD network, and which values are
//! kept in hidden variables.
//!
//! The order (documented in `docs/plcopen.md`, "Evaluation order"):
//!
//! 1. elements with an `executionOrderId` greater than 0, by that number;
//! 2. then the elements that write something (`<outVariable>`,
//!    `<inOutVariable>`, `<coil>`, `<jump>`, `<label>`, `<return>`, and
//!    blocks none of whose outputs is connected), by position: top to
//!    bottom, then left to right, then document order;
//! 3. then any element not reached yet, by position.
//!
//! Before an element runs, every element feeding it runs (depth first),
//! unless it is numbered (1.) and its turn has not come, or it is already
//! running further up the walk: then the connection is a feedback path and
//! reads the value the source stored the last time it ran (the previous
//! cycle's, or the initial value).

use super::network::{Kind, Network};
use std::collections::HashMap;

/// Inline expressions deeper than this are kept in a hidden variable
/// instead, so that no expression (and no recursion) grows without bound.
const MAX_INLINE_DEPTH: usize = 32;

/// The result of ordering a network.
pub struct Plan {
    /// The elements that take part in evaluation, in evaluation order.
    pub order: Vec<usize>,
    /// For each element: its value is read before it runs in this cycle
    /// (a feedback path, or a numbered element read before its turn).
    pub early: Vec<bool>,
    /// For each element: how many inputs read each of its output pins
    /// (by upper-case pin name).
    pub uses: Vec<HashMap<String, usize>>,
    /// For each element: it runs as a statement of its own, its value
    /// kept in a hidden variable, rather than written inline where it is
    /// read.
    pub stored: Vec<bool>,
    /// For each element written inline: how deep its expression nests.
    pub depth: Vec<usize>,
}

impl Plan {
    /// How many inputs read any output of element `i`.
    pub fn total_uses(&self, i: usize) -> usize {
        self.uses[i].values().sum()
    }
}

/// True for elements that take part in the evaluation order (the others,
/// variables read, rails, connectors, are expressions or nothing).
pub fn is_evaluated(kind: &Kind) -> bool {
    !matches!(
        kind,
        Kind::InVariable | Kind::LeftRail | Kind::RightRail | Kind::Connector | Kind::Continuation
    )
}

/// True for elements that write something: the roots of step 2.
fn is_sink(net: &Network, uses: &[HashMap<String, usize>], i: usize) -> bool {
    match net.elements[i].kind {
        Kind::OutVariable
        | Kind::InOutVariable
        | Kind::Coil
        | Kind::Jump(_)
        | Kind::Label(_)
        | Kind::Return
        | Kind::Condition => true,
        Kind::Block { .. } => uses[i].is_empty(),
        _ => false,
    }
}

/// Orders `net`. `can_store(i)` says whether element `i`'s value may be
/// kept in a hidden variable (its type is known).
pub fn plan(net: &Network, can_store: &dyn Fn(usize) -> bool) -> Plan {
    let n = net.elements.len();
    let uses = count_uses(net);
    let numbered = |i: usize| net.elements[i].order > 0;
    let by_place = |list: &mut Vec<usize>| {
        list.sort_by_key(|&i| (net.elements[i].position, i));
    };
    let mut roots: Vec<usize> = (0..n)
        .filter(|&i| numbered(i) && is_evaluated(&net.elements[i].kind))
        .collect();
    roots.sort_by_key(|&i| (net.elements[i].order, net.elements[i].position, i));
    let mut sinks: Vec<usize> = (0..n)
        .filter(|&i| !numbered(i) && is_sink(net, &uses, i))
        .collect();
    by_place(&mut sinks);
    let mut rest: Vec<usize> = (0..n)
        .filter(|&i| !numbered(i) && is_evaluated(&net.elements[i].kind))
        .collect();
    by_place(&mut rest);
    roots.extend(sinks);
    roots.extend(rest);

    let mut walk = Walk {
        net,
        state: vec![State::New; n],
        early: vec![false; n],
        order: Vec::new(),
    };
    for r in roots {
        walk.visit(r);
    }
    let Walk { order, early, .. } = walk;
    let (stored, depth) = storage(net, &order, &early, &uses, can_store);
    Plan {
        order,
        early,
        uses,
        stored,
        depth,
    }
}

/// How many inputs read each output pin of each element (connectors and
/// the right rail are not readers: they evaluate nothing).
fn count_uses(net: &Network) -> Vec<HashMap<String, usize>> {
    let mut uses = vec![HashMap::new(); net.elements.len()];
    for el in &net.elements {
        if matches!(el.kind, Kind::Connector | Kind::RightRail) {
            continue;
        }
        for input in &el.inputs {
            for s in &input.sources {
                *uses[s.from].entry(s.pin.to_ascii_uppercase()).or_insert(0) += 1;
            }
        }
    }
    uses
}

#[derive(Clone, Copy, PartialEq)]
enum State {
    New,
    Running,
    Done,
}

/// The depth-first walk (iterative: networks may be long).
struct Walk<'n, 'a, 'i> {
    net: &'n Network<'a, 'i>,
    state: Vec<State>,
    early: Vec<bool>,
    order: Vec<usize>,
}

impl Walk<'_, '_, '_> {
    /// Runs `root` after everything feeding it.
    fn visit(&mut self, root: usize) {
        if self.state[root] != State::New || !is_evaluated(&self.net.elements[root].kind) {
            return;
        }
        // (element, index of the next source to look at)
        let mut stack = vec![(root, 0usize)];
        self.state[root] = State::Running;
        while let Some(&mut (el, ref mut next)) = stack.last_mut() {
            let sources: Vec<usize> = self.net.elements[el]
                .inputs
                .iter()
                .flat_map(|i| i.sources.iter().map(|s| s.from))
                .collect();
            if let Some(&s) = sources.get(*next) {
                *next += 1;
                if !is_evaluated(&self.net.elements[s].kind) {
                    continue;
                }
                match self.state[s] {
                    State::Done => {}
                    State::Running => self.early[s] = true,
                    State::New if self.net.elements[s].order > 0 => self.early[s] = true,
                    State::New => {
                        self.state[s] = State::Running;
                        stack.push((s, 0));
                    }
                }
            } else {
                stack.pop();
                self.state[el] = State::Done;
                self.order.push(el);
            }
        }
    }
}

/// Which elements keep their value in a hidden variable.
fn storage(
    net: &Network,
    order: &[usize],
    early: &[bool],
    uses: &[HashMap<String, usize>],
    can_store: &dyn Fn(usize) -> bool,
) -> (Vec<bool>, Vec<usize>) {
    let n = net.elements.len();
    let mut stored = vec![false; n];
    let mut depth = vec![0usize; n];
    for &i in order {
        let el = &net.elements[i];
        let total: usize = uses[i].values().sum();
        let inline_kind = matches!(
            el.kind,
            Kind::Block { instance: None, .. } | Kind::Contact | Kind::Coil
        );
        let d = 1 + el
            .inputs
            .iter()
            .flat_map(|p| p.sources.iter())
            .map(|s| depth[s.from])
            .max()
            .unwrap_or(0);
        let deep = d > MAX_INLINE_DEPTH;
        // `must`: only a statement of its own gives the right value;
        // `prefer`: one is better, when the value's type is known.
        let (must, prefer) = match &el.kind {
            Kind::Block { instance: None, .. } => {
                let out = return_uses(&uses[i]);
                let other = total - out;
                let enabled = el.inputs.iter().any(|p| p.name.eq_ignore_ascii_case("EN"));
                (early[i] || out != 1 || other > 0, enabled || deep)
            }
            Kind::Contact => (early[i] || total > 1, deep),
            Kind::Coil => (total > 0, false),
            _ => (false, false),
        };
        stored[i] = inline_kind && (must || (prefer && can_store(i)));
        depth[i] = if inline_kind && !stored[i] {
            d
        } else if let Kind::Block {
            instance: Some(_), ..
        } = el.kind
        {
            // An instance's in-out output is the variable given to the
            // in-out: written inline where it is read.
            el.inputs
                .iter()
                .filter(|p| p.in_out)
                .flat_map(|p| p.sources.iter())
                .map(|s| 1 + depth[s.from])
                .max()
                .unwrap_or(0)
        } else {
            0
        };
    }
    (stored, depth)
}

/// How many inputs read a function's result (its `OUT` pin, or its only
/// unnamed one).
pub fn return_uses(uses: &HashMap<String, usize>) -> usize {
    uses.get("OUT").copied().unwrap_or(0) + uses.get("").copied().unwrap_or(0)
}

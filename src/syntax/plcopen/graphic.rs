//! An `<FBD>` or `<LD>` body lowered to ST: the network is read
//! ([`super::network`]), ordered ([`super::order`]), and written as the
//! tokens of a `VAR ... END_VAR` block of hidden variables (values kept
//! between elements, edge memories, the jump state) followed by one ST
//! statement per element, each token placed at the XML element it comes
//! from. Values are written by [`super::values`], blocks and variables by
//! [`super::fbd`], contacts and coils by [`super::ld`].
//!
//! Labels and jumps: with `_JMP` holding the number of the label a jump
//! goes to (0: none), every run of statements is wrapped in
//! `IF _JMP = 0 THEN ... END_IF`, a label `k` is
//! `IF _JMP = k THEN _JMP := 0; END_IF`, and a jump `IF c THEN _JMP := k;
//! END_IF`; when a jump goes backwards the whole body is a
//! `REPEAT ... UNTIL _JMP = 0 END_REPEAT`, so it starts again from the top
//! and skips to the label.

use super::codes;
use super::emit::{Emitter, Range};
use super::infer::{Ty, Types};
use super::network::{self, Edge, Kind, Network};
use super::order::{self, Plan, return_uses};
use super::types::type_of;
use roxmltree::Node;
use std::collections::HashMap;

/// Inline expressions nested deeper than this (a chain of functions
/// whose types cannot be worked out) are refused.
const MAX_DEPTH: usize = 200;

/// The lowering of one body.
pub struct Lowering<'a, 'i> {
    /// The network.
    pub net: Network<'a, 'i>,
    /// Its order and storage.
    pub plan: Plan,
    /// Types of the names it uses.
    pub types: Types<'a, 'i>,
    /// Label name (upper case) to number.
    pub labels: HashMap<String, usize>,
    /// The start of its hidden variables' names (`_A1` for the first
    /// graphical action of a chart; empty for a POU's body).
    pub prefix: String,
}

/// Lowers the graphical body `lang` (`<FBD>` or `<LD>`) of `pou`.
pub fn body(em: &mut Emitter, pou: Node, lang: Node) {
    if let Some(lw) = prepare(em, pou, lang, false, "") {
        lw.declarations(em, em.at(lang));
        lw.statements(em, em.at(lang));
    }
}

/// Reads, orders and checks the network of `lang` (an `<FBD>`, an `<LD>`,
/// or, with `in_sfc`, the graphical elements of an `<SFC>` and the
/// conditions wired to them); `None` after a reported error.
pub fn prepare<'a, 'i>(
    em: &mut Emitter,
    pou: Node<'a, 'i>,
    lang: Node<'a, 'i>,
    in_sfc: bool,
    prefix: &str,
) -> Option<Lowering<'a, 'i>> {
    let net = network::read(em, lang, in_sfc)?;
    let types = Types::new(pou);
    let plan = order::plan(&net, &|i| can_store(&net, &types, i));
    let mut lw = Lowering {
        net,
        plan,
        types,
        labels: HashMap::new(),
        prefix: prefix.to_string(),
    };
    lw.check(em).then_some(lw)
}

/// Whether element `i`'s value can be kept in a hidden variable.
fn can_store<'a, 'i>(net: &Network<'a, 'i>, types: &Types<'a, 'i>, i: usize) -> bool {
    match net.elements[i].kind {
        Kind::Block { instance: None, .. } => types.output(net, i, "OUT").is_some(),
        _ => true,
    }
}

impl<'a, 'i> Lowering<'a, 'i> {
    /// True when nothing is connected to element `i`'s input.
    fn unwired(&self, i: usize) -> bool {
        self.net.elements[i]
            .inputs
            .iter()
            .all(|p| p.sources.is_empty())
    }

    /// True when the network has elements (an SFC body may have none).
    pub fn is_empty(&self) -> bool {
        self.net.elements.is_empty()
    }

    /// The value wired to the `<condition>` of SFC transition `transition`
    /// (false when the network has no such condition).
    pub fn condition(&self, em: &mut Emitter, transition: Node) -> bool {
        let Some(el) = self
            .net
            .elements
            .iter()
            .find(|e| e.kind == Kind::Condition && e.node == transition)
        else {
            return false;
        };
        let at = em.at(el.inputs[0].node);
        self.sources_value(em, &el.inputs[0].sources, at);
        true
    }

    /// The value a transition's FBD/LD body gives: what is written to the
    /// `<outVariable>` or `<coil>` named like the transition (`name`), or
    /// to the body's only one. A transition is an expression: a network
    /// that needs statements of its own (function block calls, edge
    /// memories, values read twice, other writes) is refused with why.
    pub fn transition_value(&self, em: &mut Emitter, name: &str) -> Result<(), String> {
        let writers: Vec<usize> = (0..self.net.elements.len())
            .filter(|&i| matches!(self.net.elements[i].kind, Kind::OutVariable | Kind::Coil))
            .collect();
        let named = writers.iter().copied().find(|&i| {
            self.expression_node(i)
                .and_then(|n| n.text())
                .is_some_and(|t| t.trim().eq_ignore_ascii_case(name))
        });
        let target = match (named, writers.as_slice()) {
            (Some(t), _) => t,
            (None, [only]) => *only,
            _ => {
                return Err(format!(
                    "a transition network gives its value to an <outVariable> or <coil> named `{name}`, and this one has none"
                ));
            }
        };
        for &i in &self.plan.order {
            let el = &self.net.elements[i];
            let quiet = match el.kind {
                Kind::Block { instance: None, .. } | Kind::Contact => {
                    !self.plan.stored[i]
                        && el.edge == Edge::None
                        && el.inputs.iter().all(|p| p.edge == Edge::None)
                }
                Kind::OutVariable | Kind::Coil => i == target,
                _ => false,
            };
            if !quiet {
                return Err(format!(
                    "{} in a transition's network would need a statement of its own; a transition is an expression (write it in ST, or move the element into an action)",
                    network::describe(&el.kind)
                ));
            }
        }
        let sources = &self.net.elements[target].inputs[0].sources;
        self.sources_value(em, sources, em.at(self.net.elements[target].node));
        Ok(())
    }

    /// The identifier part naming element `i` in hidden variables.
    pub fn tag(&self, i: usize) -> String {
        let id = &self.net.elements[i].id;
        if id.chars().all(|c| c.is_ascii_alphanumeric()) {
            id.clone()
        } else {
            format!("X{i}")
        }
    }

    /// The hidden variable holding output `pin` of element `i` (`_T12_OUT`;
    /// `_T12` for contacts and coils).
    pub fn temp(&self, i: usize, pin: &str) -> String {
        match self.net.elements[i].kind {
            Kind::Block { .. } => {
                let p = if pin.is_empty() { "OUT" } else { pin };
                format!(
                    "{}_T{}_{}",
                    self.prefix,
                    self.tag(i),
                    p.to_ascii_uppercase()
                )
            }
            _ => format!("{}_T{}", self.prefix, self.tag(i)),
        }
    }

    /// The hidden variable holding the number of the label a jump goes to.
    pub fn jump_state(&self) -> String {
        format!("{}_JMP", self.prefix)
    }

    /// The hidden edge memory of element `i` (`_E12`), or of its input `pin`.
    pub fn trigger(&self, i: usize, pin: &str) -> String {
        if pin.is_empty() {
            format!("{}_E{}", self.prefix, self.tag(i))
        } else {
            format!(
                "{}_E{}_{}",
                self.prefix,
                self.tag(i),
                pin.to_ascii_uppercase()
            )
        }
    }

    /// Reports what the network cannot be lowered with; false if anything.
    fn check(&mut self, em: &mut Emitter) -> bool {
        let mut ok = true;
        for el in &self.net.elements {
            if let Kind::Label(name) = &el.kind {
                let k = self.labels.len() + 1;
                if self.labels.insert(name.to_ascii_uppercase(), k).is_some() {
                    em.error(
                        codes::LABEL,
                        em.at(el.node),
                        format!("label `{name}` is placed twice in this body"),
                    );
                    ok = false;
                }
            }
        }
        for (i, el) in self.net.elements.iter().enumerate() {
            ok &= self.check_element(em, i, el);
        }
        ok
    }

    /// The checks of one element.
    fn check_element(&self, em: &mut Emitter, i: usize, el: &network::Element) -> bool {
        let at = em.at(el.node);
        if let Kind::Jump(name) = &el.kind
            && !self.labels.contains_key(&name.to_ascii_uppercase())
        {
            em.error(
                codes::LABEL,
                em.attr_range(el.node, "label").unwrap_or(at),
                format!("jump to `{name}`, a label this body does not have"),
            );
            return false;
        }
        let unconnected = el.inputs.iter().all(|p| p.sources.is_empty());
        if unconnected
            && matches!(
                el.kind,
                Kind::OutVariable | Kind::InOutVariable | Kind::Coil
            )
        {
            // Drawn but not wired: nothing to write (Beremiz skips it too).
            em.warning(
                codes::UNWIRED_WRITE,
                at,
                format!(
                    "{} whose input is not connected writes nothing; it is ignored",
                    network::describe(&el.kind)
                ),
            );
        }
        let needs_input = matches!(el.kind, Kind::Contact | Kind::Condition);
        if needs_input && unconnected {
            em.error(
                codes::UNCONNECTED,
                at,
                format!(
                    "{} whose input is not connected",
                    network::describe(&el.kind)
                ),
            );
            return false;
        }
        if matches!(
            el.kind,
            Kind::Contact | Kind::Coil | Kind::InVariable | Kind::OutVariable | Kind::InOutVariable
        ) && self.expression_node(i).is_none()
        {
            let what = if matches!(el.kind, Kind::Contact | Kind::Coil) {
                "variable"
            } else {
                "expression"
            };
            em.error(
                codes::MISSING_CHILD,
                at,
                format!(
                    "`<{}>` needs a non-empty `<{what}>`",
                    el.node.tag_name().name()
                ),
            );
            return false;
        }
        if let Kind::Block { type_name, .. } = &el.kind {
            for p in &el.inputs {
                if !network::safe_part(&p.name) {
                    em.error(
                        codes::BAD_CONNECTION,
                        em.at(p.node),
                        format!(
                            "an input of block `{type_name}` without a usable formalParameter (`{}`)",
                            p.name
                        ),
                    );
                    return false;
                }
                if p.in_out && p.sources.is_empty() {
                    em.error(
                        codes::UNCONNECTED,
                        em.at(p.node),
                        format!(
                            "in-out `{}` of block `{type_name}` is not connected to a variable",
                            p.name
                        ),
                    );
                    return false;
                }
            }
        }
        if !self.plan.stored[i] && self.plan.depth[i] > MAX_DEPTH {
            em.refuse(el.node, "this network nests expressions too deeply");
            return false;
        }
        true
    }

    /// The `<expression>` (variables) or `<variable>` (contacts, coils)
    /// of element `i`, when it has text.
    pub fn expression_node(&self, i: usize) -> Option<Node<'a, 'i>> {
        let el = &self.net.elements[i];
        let name = match el.kind {
            Kind::Contact | Kind::Coil => "variable",
            _ => "expression",
        };
        let node = super::emit::child(el.node, name)?;
        node.text()
            .is_some_and(|t| !t.trim().is_empty())
            .then_some(node)
    }

    /// Emits the text of element `i`'s expression at its own characters.
    pub fn expression(&self, em: &mut Emitter, i: usize) {
        if let Some(node) = self.expression_node(i) {
            let xml = node.document().input_text();
            if let Some(range) = super::raw::content_range(xml, node.range()) {
                em.lex_range(range, false);
            }
        }
    }

    /// `VAR ... END_VAR` with the hidden variables, if any.
    pub fn declarations(&self, em: &mut Emitter, at: Range) {
        let mut decls: Vec<(String, Range, Result<Ty<'a, 'i>, String>)> = Vec::new();
        let mut jumps = false;
        for (i, el) in self.net.elements.iter().enumerate() {
            let here = em.at(el.node);
            let word = |w: &str| Ok(Ty::Word(w.to_string()));
            let edge_fb = |e: Edge| match e {
                Edge::Rising => Some("R_TRIG"),
                Edge::Falling => Some("F_TRIG"),
                Edge::None => None,
            };
            match &el.kind {
                Kind::Block {
                    instance,
                    type_name,
                } => {
                    for p in &el.inputs {
                        if let Some(fb) = edge_fb(p.edge) {
                            decls.push((self.trigger(i, &p.name), em.at(p.node), word(fb)));
                        }
                    }
                    if instance.is_some() && self.plan.uses[i].contains_key("ENO") {
                        decls.push((self.temp(i, "ENO"), here, word("BOOL")));
                    }
                    if instance.is_none() && self.plan.stored[i] {
                        let uses = &self.plan.uses[i];
                        if return_uses(uses) > 0 || self.plan.early[i] {
                            decls.push((
                                self.temp(i, "OUT"),
                                here,
                                self.typed(i, "OUT", type_name),
                            ));
                        }
                        for o in &el.outputs {
                            let up = o.name.to_ascii_uppercase();
                            if up.is_empty() || up == "OUT" || !uses.contains_key(&up) || o.in_out {
                                continue;
                            }
                            decls.push((
                                self.temp(i, &o.name),
                                here,
                                self.typed(i, &o.name, type_name),
                            ));
                        }
                    }
                }
                Kind::Contact | Kind::Coil | Kind::OutVariable | Kind::InOutVariable => {
                    if let Some(fb) = edge_fb(el.edge) {
                        decls.push((self.trigger(i, ""), here, word(fb)));
                    }
                    if self.plan.stored[i] {
                        decls.push((self.temp(i, ""), here, word("BOOL")));
                    }
                }
                Kind::Jump(_) | Kind::Label(_) => jumps = true,
                _ => {}
            }
        }
        if jumps {
            decls.push((self.jump_state(), at, Ok(Ty::Word("INT".into()))));
        }
        if decls.is_empty() {
            return;
        }
        em.synth("VAR", at);
        for (name, range, ty) in decls {
            match ty {
                Ok(ty) => {
                    em.ident(&name, range);
                    em.synth(":", range);
                    match ty {
                        Ty::Word(w) => em.synth(&w, range),
                        Ty::Xml(node) => type_of(em, node),
                    }
                    em.synth(";", range);
                }
                Err(why) => em.error(codes::UNTYPED_VALUE, range, why),
            }
        }
        em.synth("END_VAR", at);
    }

    /// The type of output `pin` of function element `i`, or why it is unknown.
    fn typed(&self, i: usize, pin: &str, type_name: &str) -> Result<Ty<'a, 'i>, String> {
        self.types.output(&self.net, i, pin).ok_or_else(|| {
            format!(
                "output `{pin}` of function `{type_name}` is read twice, through a feedback path or after an EN, so it is kept in a variable, and its type cannot be worked out here; connect it to a declared variable (an <inOutVariable>) and read that"
            )
        })
    }

    /// The body's statements, with the jump machinery when it has jumps.
    pub fn statements(&self, em: &mut Emitter, at: Range) {
        // An empty statement first: a body starting with a call such as
        // `ADD(...)` must not be taken for IL (`ADD(` is an IL operator).
        em.synth(";", at);
        let order = self.plan.order.clone();
        if !self.labels.is_empty()
            || order
                .iter()
                .any(|&i| matches!(self.net.elements[i].kind, Kind::Jump(_)))
        {
            self.with_jumps(em, &order, at);
        } else {
            for &i in &order {
                self.statement(em, i);
            }
        }
    }

    /// The statements of `order` wrapped for jumps and labels.
    fn with_jumps(&self, em: &mut Emitter, order: &[usize], at: Range) {
        let position: HashMap<usize, usize> =
            order.iter().enumerate().map(|(k, &i)| (i, k)).collect();
        let label_at = |name: &str| -> Option<usize> {
            self.net
                .elements
                .iter()
                .enumerate()
                .find_map(|(i, e)| match &e.kind {
                    Kind::Label(l) if l.eq_ignore_ascii_case(name) => position.get(&i).copied(),
                    _ => None,
                })
        };
        let backwards = order
            .iter()
            .enumerate()
            .any(|(k, &i)| match &self.net.elements[i].kind {
                Kind::Jump(l) => label_at(l).is_some_and(|p| p <= k),
                _ => false,
            });
        let jmp = self.jump_state();
        em.synth(&format!("{jmp} := 0;"), at);
        if backwards {
            em.synth("REPEAT", at);
        }
        let mut open = false;
        for &i in order {
            let el = &self.net.elements[i];
            let here = em.at(el.node);
            if let Kind::Label(name) = &el.kind {
                if open {
                    em.synth("END_IF;", here);
                    open = false;
                }
                let k = self.labels[&name.to_ascii_uppercase()];
                em.synth(&format!("IF {jmp} = {k} THEN {jmp} := 0; END_IF;"), here);
                continue;
            }
            if !open {
                em.synth(&format!("IF {jmp} = 0 THEN"), here);
                open = true;
            }
            self.statement(em, i);
            if matches!(el.kind, Kind::Jump(_)) {
                em.synth("END_IF;", here);
                open = false;
            }
        }
        if open {
            em.synth("END_IF;", at);
        }
        if backwards {
            em.synth(&format!("UNTIL {jmp} = 0 END_REPEAT;"), at);
        }
    }

    /// The statement(s) of element `i`.
    fn statement(&self, em: &mut Emitter, i: usize) {
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        match &el.kind {
            Kind::Block {
                instance: Some(inst),
                ..
            } => self.fb_call(em, i, inst),
            Kind::Block { instance: None, .. } => self.function_statement(em, i),
            Kind::OutVariable | Kind::InOutVariable | Kind::Coil if self.unwired(i) => {}
            Kind::OutVariable | Kind::InOutVariable => self.variable_write(em, i),
            Kind::Contact => self.contact_statement(em, i),
            Kind::Coil => self.coil_statement(em, i),
            Kind::Jump(name) => {
                let k = self.labels[&name.to_ascii_uppercase()];
                self.conditional(em, i, &format!("{} := {k};", self.jump_state()), at);
            }
            Kind::Return => self.conditional(em, i, "RETURN;", at),
            _ => {}
        }
    }

    /// `IF <input> THEN stmt END_IF;`, or `stmt` when the element's input
    /// is not connected.
    fn conditional(&self, em: &mut Emitter, i: usize, stmt: &str, at: Range) {
        let sources = self.net.elements[i]
            .inputs
            .first()
            .map(|p| p.sources.as_slice())
            .unwrap_or(&[]);
        if sources.is_empty() {
            em.synth(stmt, at);
            return;
        }
        em.synth("IF", at);
        self.sources_value(em, sources, at);
        em.synth("THEN", at);
        em.synth(stmt, at);
        em.synth("END_IF;", at);
    }
}

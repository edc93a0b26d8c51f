//! FBD elements as ST statements: a function block instance is called
//! with its connected inputs (`inst(IN := ..., PT := ...);`, its outputs
//! read as `inst.Q`); a function is called inline where its result is
//! read once, or as a statement storing its outputs in hidden variables
//! (`_T12_OUT := ADD(IN1 := ..., IN2 := ...);`); an `<outVariable>` or
//! `<inOutVariable>` is an assignment. Negated pins wrap their value in
//! `NOT`; an edge on an input calls a hidden `R_TRIG`/`F_TRIG` and passes
//! its `Q`.

use super::emit::{Emitter, Range};
use super::graphic::Lowering;
use super::network::{Edge, Input, Storage};
use super::order::return_uses;

impl Lowering<'_, '_> {
    /// `inst(EN := ..., IN := ...);`.
    pub fn fb_call(&self, em: &mut Emitter, i: usize, inst: &str) {
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        self.input_triggers(em, i);
        let range = em.attr_range(el.node, "instanceName").unwrap_or(at);
        em.ident(inst, range);
        em.synth("(", at);
        let none = self.arguments(em, i, true);
        if self.plan.uses[i].contains_key("ENO") {
            if !none {
                em.synth(",", at);
            }
            em.synth("ENO =>", at);
            em.ident(&self.temp(i, "ENO"), at);
        }
        em.synth(");", em.end_of(el.node));
    }

    /// The statement of a function: its call, storing what is read of it.
    pub fn function_statement(&self, em: &mut Emitter, i: usize) {
        self.input_triggers(em, i);
        if !self.plan.stored[i] {
            return;
        }
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        let en = el
            .inputs
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case("EN") && !p.sources.is_empty());
        let eno_read = self.plan.uses[i].contains_key("ENO");
        let result = return_uses(&self.plan.uses[i]) > 0 || self.plan.early[i];
        if let Some(en) = en {
            // Not enabled: nothing runs, the outputs keep their values and
            // ENO is FALSE.
            em.synth("IF", at);
            self.pin_value(em, i, en);
            em.synth("THEN", at);
        }
        if result {
            em.ident(&self.temp(i, "OUT"), at);
            em.synth(":=", at);
        }
        self.function_call(em, i, false);
        em.synth(";", at);
        if eno_read && !self.user_function(i) {
            // A standard function that ran sets ENO.
            em.ident(&self.temp(i, "ENO"), at);
            em.synth(":= TRUE;", at);
        }
        if en.is_some() {
            if eno_read {
                em.synth("ELSE", at);
                em.ident(&self.temp(i, "ENO"), at);
                em.synth(":= FALSE;", at);
            }
            em.synth("END_IF;", at);
        }
    }

    /// `F(IN1 := ..., ...)`, with `EN` when `with_en`, and the outputs
    /// read bound to their hidden variables when the call is stored.
    pub fn function_call(&self, em: &mut Emitter, i: usize, with_en: bool) {
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        let range = em.attr_range(el.node, "typeName").unwrap_or(at);
        if let super::network::Kind::Block { type_name, .. } = &el.kind {
            em.ident(type_name, range);
        }
        em.synth("(", at);
        let mut first = self.arguments(em, i, with_en);
        if self.plan.stored[i] {
            for o in &el.outputs {
                let up = o.name.to_ascii_uppercase();
                if up.is_empty()
                    || up == "OUT"
                    || o.in_out
                    || !self.plan.uses[i].contains_key(&up)
                    || (up == "ENO" && !self.user_function(i))
                {
                    continue;
                }
                if !first {
                    em.synth(",", at);
                }
                first = false;
                em.ident(&o.name, at);
                em.synth("=>", at);
                em.ident(&self.temp(i, &o.name), at);
            }
        }
        em.synth(")", em.end_of(el.node));
    }

    /// True when block `i` calls a function the project declares (not a
    /// standard one, whose ENO is TRUE whenever it runs).
    fn user_function(&self, i: usize) -> bool {
        match &self.net.elements[i].kind {
            super::network::Kind::Block { type_name, .. } => self.types.declares(type_name),
            _ => false,
        }
    }

    /// The connected inputs as `name := value` (in-outs too); returns
    /// whether none was written. `EN` is left out unless `with_en`.
    fn arguments(&self, em: &mut Emitter, i: usize, with_en: bool) -> bool {
        let el = &self.net.elements[i];
        let mut first = true;
        for p in &el.inputs {
            if p.sources.is_empty() || (!with_en && p.name.eq_ignore_ascii_case("EN")) {
                continue;
            }
            let at = em.at(p.node);
            if !first {
                em.synth(",", at);
            }
            first = false;
            em.ident(&p.name, at);
            em.synth(":=", at);
            self.pin_value(em, i, p);
        }
        first
    }

    /// The value an input pin receives: its sources, through its edge
    /// memory and its negation.
    fn pin_value(&self, em: &mut Emitter, i: usize, p: &Input) {
        let at = em.at(p.node);
        if p.negated {
            em.synth("NOT (", at);
        }
        if p.edge == Edge::None {
            self.sources_value(em, &p.sources, at);
        } else {
            em.ident(&self.trigger(i, &p.name), at);
            em.synth(".Q", at);
        }
        if p.negated {
            em.synth(")", at);
        }
    }

    /// The edge memories of a block's inputs, called with the input's value.
    fn input_triggers(&self, em: &mut Emitter, i: usize) {
        for p in &self.net.elements[i].inputs {
            if p.edge != Edge::None && !p.sources.is_empty() {
                let at = em.at(p.node);
                self.trigger_call(em, &self.trigger(i, &p.name), at, |em| {
                    self.sources_value(em, &p.sources, at)
                });
            }
        }
    }

    /// `name(CLK := <value>);`.
    pub fn trigger_call(
        &self,
        em: &mut Emitter,
        name: &str,
        at: Range,
        value: impl FnOnce(&mut Emitter),
    ) {
        em.ident(name, at);
        em.synth("(CLK :=", at);
        value(em);
        em.synth(");", at);
    }

    /// An `<outVariable>` or `<inOutVariable>`: its expression written
    /// with the value of its input.
    pub fn variable_write(&self, em: &mut Emitter, i: usize) {
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        let sources = &el.inputs[0].sources;
        self.write(
            em,
            i,
            at,
            |em| self.sources_value(em, sources, at),
            |em| self.expression(em, i),
        );
    }

    /// `target := value;` with the element's negation, edge and storage:
    /// `IF value THEN target := TRUE; END_IF;` (set), `FALSE` (reset),
    /// `_E12(CLK := value); target := _E12.Q;` (edge).
    pub fn write(
        &self,
        em: &mut Emitter,
        i: usize,
        at: Range,
        value: impl Fn(&mut Emitter),
        target: impl Fn(&mut Emitter),
    ) {
        let el = &self.net.elements[i];
        let edge = el.edge != Edge::None;
        let memory = self.trigger(i, "");
        if edge {
            self.trigger_call(em, &memory, at, &value);
        }
        let condition = |em: &mut Emitter| {
            if el.negated_in {
                em.synth("NOT", at);
            }
            em.synth("(", at);
            if edge {
                em.ident(&memory, at);
                em.synth(".Q", at);
            } else {
                value(em);
            }
            em.synth(")", at);
        };
        match el.storage {
            Storage::Set | Storage::Reset => {
                em.synth("IF", at);
                condition(em);
                em.synth("THEN", at);
                target(em);
                let v = if el.storage == Storage::Set {
                    ":= TRUE;"
                } else {
                    ":= FALSE;"
                };
                em.synth(v, at);
                em.synth("END_IF;", at);
            }
            Storage::None => {
                target(em);
                em.synth(":=", at);
                condition(em);
                em.synth(";", at);
            }
        }
    }
}

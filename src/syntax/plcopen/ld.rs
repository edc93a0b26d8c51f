//! LD elements as ST: a contact is its power flow ANDed with its variable
//! (`NOT` when negated; a rising or falling contact ANDs the `Q` of a
//! hidden `R_TRIG`/`F_TRIG` called with the variable every cycle); a coil
//! writes its power flow to its variable (negated, set, reset, or through
//! a hidden edge memory). Parallel branches are the OR of the connections
//! into one input ([`super::values`]); a contact or coil read by several
//! elements keeps its power flow in a hidden BOOL so it is worked out once.

use super::emit::Emitter;
use super::graphic::Lowering;
use super::network::{Edge, Kind};

impl Lowering<'_, '_> {
    /// `(<power> AND <variable>)`.
    pub fn contact_value(&self, em: &mut Emitter, i: usize) {
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        let sources = &el.inputs[0].sources;
        let from_rail =
            matches!(sources.as_slice(), [s] if self.net.elements[s.from].kind == Kind::LeftRail);
        em.synth("(", at);
        if !from_rail {
            em.synth("(", at);
            self.sources_value(em, sources, at);
            em.synth(") AND", at);
        }
        if el.negated {
            em.synth("NOT", at);
        }
        if el.edge == Edge::None {
            em.synth("(", at);
            self.expression(em, i);
            em.synth(")", at);
        } else {
            em.ident(&self.trigger(i, ""), at);
            em.synth(".Q", at);
        }
        em.synth(")", at);
    }

    /// A contact's statements: its edge memory's call, and its stored
    /// power flow.
    pub fn contact_statement(&self, em: &mut Emitter, i: usize) {
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        if el.edge != Edge::None {
            self.trigger_call(em, &self.trigger(i, ""), at, |em| {
                em.synth("(", at);
                self.expression(em, i);
                em.synth(")", at);
            });
        }
        if self.plan.stored[i] {
            em.ident(&self.temp(i, ""), at);
            em.synth(":=", at);
            self.contact_value(em, i);
            em.synth(";", at);
        }
    }

    /// A coil: its variable written from its power flow.
    pub fn coil_statement(&self, em: &mut Emitter, i: usize) {
        let el = &self.net.elements[i];
        let at = em.at(el.node);
        let sources = &el.inputs[0].sources;
        let stored = self.plan.stored[i];
        if stored {
            em.ident(&self.temp(i, ""), at);
            em.synth(":=", at);
            self.sources_value(em, sources, at);
            em.synth(";", at);
        }
        self.write(
            em,
            i,
            at,
            |em| {
                if stored {
                    em.ident(&self.temp(i, ""), at);
                } else {
                    self.sources_value(em, sources, at);
                }
            },
            |em| self.expression(em, i),
        );
    }
}

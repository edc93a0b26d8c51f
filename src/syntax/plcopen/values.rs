//! The value on a connection, written as an ST expression: a variable's
//! expression, `TRUE` for the left power rail, a function block
//! instance's output (`inst.Q`), a hidden variable holding a stored
//! value, or, for a value read once, the function call or the contact
//! written inline. Several connections into one input are ORed (parallel
//! branches of a rung); none is FALSE.

use super::emit::{Emitter, Range};
use super::graphic::Lowering;
use super::network::{Kind, Source};

impl Lowering<'_, '_> {
    /// The OR of `sources` (one source: its value).
    pub fn sources_value(&self, em: &mut Emitter, sources: &[Source], at: Range) {
        if sources.is_empty() {
            // No power (an unwired coil read further right).
            em.synth("FALSE", at);
            return;
        }
        if let [one] = sources {
            self.value(em, one);
            return;
        }
        em.synth("(", at);
        for (k, s) in sources.iter().enumerate() {
            if k > 0 {
                em.synth("OR", at);
            }
            self.value(em, s);
        }
        em.synth(")", at);
    }

    /// The value of one connection.
    pub fn value(&self, em: &mut Emitter, s: &Source) {
        let el = &self.net.elements[s.from];
        let at = em.at(el.node);
        match &el.kind {
            Kind::LeftRail => em.synth("TRUE", at),
            Kind::InVariable | Kind::InOutVariable => {
                if el.negated {
                    em.synth("NOT", at);
                }
                em.synth("(", at);
                self.expression(em, s.from);
                em.synth(")", at);
            }
            Kind::Block { instance, .. } => self.block_output(em, s, instance.as_deref()),
            Kind::Contact | Kind::Coil if self.plan.stored[s.from] => {
                em.ident(&self.temp(s.from, ""), at);
            }
            Kind::Contact => self.contact_value(em, s.from),
            Kind::Coil => {
                // A coil's value is its power flow; a coil read is stored.
                let sources = &el.inputs[0].sources;
                self.sources_value(em, sources, at);
            }
            _ => em.synth("FALSE", at),
        }
    }

    /// Output `s.pin` of a block.
    fn block_output(&self, em: &mut Emitter, s: &Source, instance: Option<&str>) {
        let el = &self.net.elements[s.from];
        let at = em.at(el.node);
        let Some(out) = el
            .outputs
            .iter()
            .find(|o| o.name.eq_ignore_ascii_case(&s.pin))
        else {
            return;
        };
        if out.negated {
            em.synth("NOT (", at);
        }
        if out.in_out {
            // The variable given to the in-out is the value that comes out.
            if let Some(p) = el
                .inputs
                .iter()
                .find(|p| p.in_out && p.name.eq_ignore_ascii_case(&out.name))
            {
                self.sources_value(em, &p.sources, at);
            }
        } else if instance.is_some() && out.name.eq_ignore_ascii_case("ENO") {
            // Bound by the call (`ENO => _T12_ENO`).
            em.ident(&self.temp(s.from, "ENO"), at);
        } else if let Some(inst) = instance {
            let range = em.attr_range(el.node, "instanceName").unwrap_or(at);
            em.ident(inst, range);
            em.synth(".", at);
            em.ident(&out.name, at);
        } else if self.plan.stored[s.from] {
            em.ident(&self.temp(s.from, &out.name), at);
        } else {
            self.function_call(em, s.from, true);
        }
        if out.negated {
            em.synth(")", at);
        }
    }
}

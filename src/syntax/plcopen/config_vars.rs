//! `<configVars>` of a `<configuration>` (PLCopen TC6 XML 2.01): each
//! `<configVariable instancePathAndName="R1.Prog.fb.x" address="%QX1.0">`
//! with its `<type>` and optional `<initialValue>` becomes one line of a
//! `VAR_CONFIG` block, `R1.Prog.fb.x AT %QX1.0 : BOOL := ...;`, so the
//! textual rules (completion of `AT %Q*`, per-instance initial values,
//! E710-E714) apply unchanged, with spans into the XML.

use super::body::add_data;
use super::emit::{Emitter, elements};
use super::interface::declaration_tail;
use roxmltree::Node;

/// `<configVars>`: `VAR_CONFIG ... END_VAR`.
pub fn config_vars(em: &mut Emitter, node: Node) {
    em.synth("VAR_CONFIG", em.at(node));
    for c in elements(node) {
        match c.tag_name().name() {
            "configVariable" => config_variable(em, c),
            "documentation" => {}
            "addData" => add_data(em, c),
            _ => em.unknown(c, "configVars"),
        }
    }
    em.synth("END_VAR", em.end_of(node));
}

/// One `<configVariable>`: `path [AT address] : type [:= value];`.
fn config_variable(em: &mut Emitter, node: Node) {
    if node.attribute("instancePathAndName").is_none() {
        em.refuse(
            node,
            "a configVariable needs the attribute instancePathAndName (the variable's path)",
        );
        return;
    }
    em.lex_attr(node, "instancePathAndName");
    declaration_tail(em, node, "configVariable");
}

//! The type of a value on a connection, where the lowering of a network
//! must keep it in a hidden variable (a function's result read twice or
//! through a feedback path): worked out from the XML alone, from the POU's
//! interface, the project's POUs and the standard functions' signatures.
//! When it cannot be worked out the importer says so (`E821`) and the user
//! connects the value through a variable.

use super::emit::{child, elements, is_identifier};
use super::network::{Kind, Network};
use roxmltree::Node;
use std::cell::RefCell;
use std::collections::HashMap;

/// A type, as a word or as a TC6 type wrapper (`<type>`, `<returnType>`).
#[derive(Debug, Clone)]
pub enum Ty<'a, 'i> {
    /// An elementary type name.
    Word(String),
    /// A wrapper element holding a type element.
    Xml(Node<'a, 'i>),
}

/// What is known about the names a network uses.
pub struct Types<'a, 'i> {
    /// The POU's variables (upper-case name to `<type>`).
    vars: HashMap<String, Node<'a, 'i>>,
    /// The project's POUs (upper-case name to `<pou>`).
    pous: HashMap<String, Node<'a, 'i>>,
    /// Types already worked out, by element and upper-case pin (a chain
    /// of blocks is walked once).
    known: RefCell<HashMap<(usize, String), Ty<'a, 'i>>>,
}

/// Inputs of standard functions that do not give the result's type.
const NOT_DATA: [&str; 6] = ["EN", "G", "K", "N", "L", "P"];

/// Standard function blocks' outputs.
fn std_fb_output(fb: &str, pin: &str) -> Option<&'static str> {
    Some(match (fb, pin) {
        ("TON" | "TOF" | "TP", "Q") => "BOOL",
        ("TON" | "TOF" | "TP", "ET") => "TIME",
        ("CTU" | "CTD" | "CTUD", "Q" | "QU" | "QD") => "BOOL",
        ("CTU" | "CTD" | "CTUD", "CV") => "INT",
        ("R_TRIG" | "F_TRIG", "Q") => "BOOL",
        ("SR" | "RS", "Q1") => "BOOL",
        ("RTC", "Q") => "BOOL",
        ("RTC", "CDT") => "DATE_AND_TIME",
        (_, "ENO") => "BOOL",
        _ => return None,
    })
}

impl<'a, 'i> Types<'a, 'i> {
    /// The names visible in `pou`'s body.
    pub fn new(pou: Node<'a, 'i>) -> Types<'a, 'i> {
        let mut vars = HashMap::new();
        for section in child(pou, "interface").into_iter().flat_map(elements) {
            for v in elements(section).filter(|v| v.tag_name().name() == "variable") {
                if let (Some(name), Some(ty)) = (v.attribute("name"), child(v, "type")) {
                    vars.insert(name.trim().to_ascii_uppercase(), ty);
                }
            }
        }
        let mut pous = HashMap::new();
        if let Some(list) = pou.parent_element() {
            for p in elements(list).filter(|p| p.tag_name().name() == "pou") {
                if let Some(name) = p.attribute("name") {
                    pous.insert(name.trim().to_ascii_uppercase(), p);
                }
            }
        }
        Types {
            vars,
            pous,
            known: RefCell::new(HashMap::new()),
        }
    }

    /// The type of output `pin` of element `i`, if it can be worked out.
    pub fn output(&self, net: &Network<'a, 'i>, i: usize, pin: &str) -> Option<Ty<'a, 'i>> {
        let mut budget = 64;
        self.of(net, i, pin, &mut budget)
            .or_else(|| self.written_to(net, i, pin))
    }

    /// The type of a POU's variable or of a literal `text`.
    pub fn of_text(&self, text: &str) -> Option<Ty<'a, 'i>> {
        let t = text.trim();
        let upper = t.to_ascii_uppercase();
        if is_identifier(t) {
            if upper == "TRUE" || upper == "FALSE" {
                return Some(Ty::Word("BOOL".into()));
            }
            return self.vars.get(&upper).map(|n| Ty::Xml(*n));
        }
        let (prefix, _) = upper.split_once('#')?;
        Some(Ty::Word(
            match prefix {
                "T" => "TIME",
                "D" => "DATE",
                "TOD" => "TIME_OF_DAY",
                "DT" => "DATE_AND_TIME",
                p if is_identifier(p) => p,
                _ => return None,
            }
            .into(),
        ))
    }

    /// True when the project declares a POU named `name` (a block of any
    /// other type is taken for a standard function or function block).
    pub fn declares(&self, name: &str) -> bool {
        self.pous.contains_key(&name.to_ascii_uppercase())
    }

    /// The declared type name of a POU variable (`<derived name>` or the
    /// elementary element), upper case.
    fn type_name(&self, var: &str) -> Option<String> {
        let ty = self.vars.get(&var.to_ascii_uppercase())?;
        let e = elements(*ty).next()?;
        Some(match e.tag_name().name() {
            "derived" => e.attribute("name")?.trim().to_ascii_uppercase(),
            other => other.to_ascii_uppercase(),
        })
    }

    /// The type of output `pin` of a POU `pou` (its result for `OUT`).
    fn pou_output(&self, pou: &str, pin: &str) -> Option<Ty<'a, 'i>> {
        let p = self.pous.get(&pou.to_ascii_uppercase())?;
        let iface = child(*p, "interface")?;
        let pin = pin.to_ascii_uppercase();
        if (pin.is_empty() || pin == "OUT")
            && p.attribute("pouType") == Some("function")
            && let Some(r) = child(iface, "returnType")
        {
            return Some(Ty::Xml(r));
        }
        elements(iface)
            .filter(|s| matches!(s.tag_name().name(), "outputVars" | "inOutVars"))
            .flat_map(elements)
            .find(|v| {
                v.attribute("name")
                    .is_some_and(|n| n.trim().eq_ignore_ascii_case(&pin))
            })
            .and_then(|v| child(v, "type"))
            .map(Ty::Xml)
    }

    fn of(
        &self,
        net: &Network<'a, 'i>,
        i: usize,
        pin: &str,
        budget: &mut u32,
    ) -> Option<Ty<'a, 'i>> {
        let key = (i, pin.to_ascii_uppercase());
        if let Some(t) = self.known.borrow().get(&key) {
            return Some(t.clone());
        }
        if *budget == 0 {
            return None;
        }
        *budget -= 1;
        let found = self.of_element(net, i, pin, budget)?;
        self.known.borrow_mut().insert(key, found.clone());
        Some(found)
    }

    fn of_element(
        &self,
        net: &Network<'a, 'i>,
        i: usize,
        pin: &str,
        budget: &mut u32,
    ) -> Option<Ty<'a, 'i>> {
        let el = &net.elements[i];
        match &el.kind {
            Kind::InVariable | Kind::InOutVariable => {
                let text = child(el.node, "expression").and_then(|e| e.text())?;
                self.of_text(text)
            }
            Kind::Contact | Kind::Coil | Kind::LeftRail => Some(Ty::Word("BOOL".into())),
            Kind::Block {
                instance: Some(inst),
                ..
            } => {
                let fb = self.type_name(inst)?;
                let pin = pin.to_ascii_uppercase();
                std_fb_output(&fb, &pin)
                    .map(|w| Ty::Word(w.into()))
                    .or_else(|| self.pou_output(&fb, &pin))
            }
            Kind::Block {
                type_name,
                instance: None,
            } => {
                let upper_pin = pin.to_ascii_uppercase();
                if upper_pin == "ENO" {
                    return Some(Ty::Word("BOOL".into()));
                }
                if let Some(t) = self.pou_output(type_name, pin) {
                    return Some(t);
                }
                if !(upper_pin.is_empty() || upper_pin == "OUT") {
                    return None;
                }
                if let Some(w) = std_result(type_name) {
                    return Some(Ty::Word(w));
                }
                if type_name.eq_ignore_ascii_case("SUB")
                    && let Some(duration) = self.difference_of_two_moments(net, el, budget)
                {
                    return Some(Ty::Word(duration.into()));
                }
                for input in &el.inputs {
                    if NOT_DATA.contains(&input.name.to_ascii_uppercase().as_str()) {
                        continue;
                    }
                    for s in &input.sources {
                        if let Some(t) = self.of(net, s.from, &s.pin, budget) {
                            return Some(t);
                        }
                    }
                }
                None
            }
            _ => None,
        }
    }

    /// The duration type a `SUB` of two moments of one kind gives (DT - DT,
    /// DATE - DATE, TOD - TOD: TIME; their long forms: LTIME), not the
    /// moment its first input is.
    fn difference_of_two_moments(
        &self,
        net: &Network<'a, 'i>,
        el: &super::network::Element<'a, 'i>,
        budget: &mut u32,
    ) -> Option<&'static str> {
        let mut kinds = el
            .inputs
            .iter()
            .filter(|input| !NOT_DATA.contains(&input.name.to_ascii_uppercase().as_str()))
            .map(|input| {
                let from = input.sources.first()?;
                let ty = self.of(net, from.from, &from.pin, budget)?;
                moment_kind(&ty)
            });
        match (kinds.next(), kinds.next(), kinds.next()) {
            (Some(Some((a, long))), Some(Some(b)), None) if (a, long) == b => {
                Some(if long { "LTIME" } else { "TIME" })
            }
            _ => None,
        }
    }

    /// The type of the variable an output is written to, when it is
    /// connected straight to an `<outVariable>` or `<inOutVariable>`.
    fn written_to(&self, net: &Network<'a, 'i>, i: usize, pin: &str) -> Option<Ty<'a, 'i>> {
        net.elements.iter().find_map(|el| {
            if !matches!(el.kind, Kind::OutVariable | Kind::InOutVariable) {
                return None;
            }
            let fed = el.inputs.iter().any(|p| {
                p.sources
                    .iter()
                    .any(|s| s.from == i && s.pin.eq_ignore_ascii_case(pin))
            });
            if !fed {
                return None;
            }
            self.of_text(child(el.node, "expression").and_then(|e| e.text())?)
        })
    }
}

/// The kind of moment a type is (`DT`, `DATE`, `TOD`) and whether it is
/// the long form; `None` for any other type.
fn moment_kind(ty: &Ty) -> Option<(&'static str, bool)> {
    let name = match ty {
        Ty::Word(w) => w.to_ascii_uppercase(),
        Ty::Xml(node) => elements(*node)
            .next()?
            .tag_name()
            .name()
            .to_ascii_uppercase(),
    };
    Some(match name.as_str() {
        "DT" | "DATE_AND_TIME" => ("DT", false),
        "LDT" | "LDATE_AND_TIME" => ("DT", true),
        "DATE" => ("DATE", false),
        "LDATE" => ("DATE", true),
        "TOD" | "TIME_OF_DAY" => ("TOD", false),
        "LTOD" | "LTIME_OF_DAY" => ("TOD", true),
        _ => return None,
    })
}

/// The result type of a standard function whose result type does not
/// depend on its inputs.
fn std_result(name: &str) -> Option<String> {
    let upper = name.to_ascii_uppercase();
    Some(match upper.as_str() {
        "GT" | "GE" | "EQ" | "LE" | "LT" | "NE" => "BOOL".into(),
        "LEN" | "FIND" => "INT".into(),
        "TRUNC" => "DINT".into(),
        _ => {
            let (_, to) = upper.rsplit_once("TO_")?;
            if !is_identifier(to) {
                return None;
            }
            to.to_string()
        }
    })
}

//! Pragmas that change a program's meaning in other tools, named in their
//! warning (W150-W154) instead of the generic "pragma ignored" (W001): a
//! CODESYS attribute or conditional compilation ignored by plcrun may make
//! the program behave differently here than there. Attributes only tools
//! around the program read are W155, which TwinCAT and CODESYS files do
//! not show (they are everywhere there, and change nothing).

/// The warning for pragma `text` (`{...}` as written), when it is one that
/// changes meaning elsewhere: `(code, message)`.
pub fn named(text: &str) -> Option<(&'static str, String)> {
    let inner = text.trim_start_matches('{').trim_end_matches('}').trim();
    let mut words = inner.split_whitespace();
    let first = words.next()?.to_ascii_lowercase();
    match first.as_str() {
        "attribute" => {
            let name = inner["attribute".len()..]
                .trim()
                .trim_matches(|c| c == '\'' || c == '"')
                .split(['\'', '"'])
                .next()
                .unwrap_or("")
                .trim()
                .to_string();
            attribute(&name)
        }
        "if" | "elsif" | "else" | "end_if" | "define" | "undefine" => Some((
            "W152",
            format!(
                "conditional compilation `{{{}}}` ignored: plcrun compiles every branch, \
                 CODESYS only the selected one",
                short(inner)
            ),
        )),
        "flow" | "noflow" => Some((
            "W155",
            format!(
                "pragma `{{{}}}` ignored: it switches CODESYS's flow control display; the \
                 program runs the same",
                short(inner)
            ),
        )),
        "error" | "warning" | "info" | "text" => Some((
            "W154",
            format!(
                "message pragma `{{{}}}` ignored (CODESYS reports it{})",
                short(inner),
                if first == "error" {
                    " as a compile error"
                } else {
                    ""
                }
            ),
        )),
        _ => None,
    }
}

/// The warning for `{attribute 'name'}`.
fn attribute(name: &str) -> Option<(&'static str, String)> {
    Some(match name.to_ascii_lowercase().as_str() {
        "qualified_only" => (
            "W150",
            "attribute 'qualified_only' ignored: plcrun does not require the names of this \
             list to be qualified"
                .to_string(),
        ),
        "call_after_init" => (
            "W151",
            format!(
                "attribute '{name}' ignored: plcrun honours it right before a METHOD or \
                 FUNCTION_BLOCK only (the method is then called after FB_init)"
            ),
        ),
        "call_after_online_change_slot" | "init_on_onlchange" => (
            "W151",
            format!(
                "attribute '{name}' ignored: plcrun's online change keeps instances in place and \
                 calls no method"
            ),
        ),
        "tcinitsymbol" => (
            "W151",
            format!(
                "attribute '{name}' ignored: TwinCAT initialises this variable from its symbol \
                 configuration, plcrun from its declaration"
            ),
        ),
        "instance-path" => (
            "W151",
            format!(
                "attribute '{name}' ignored: TwinCAT and CODESYS fill this STRING with the \
                 instance's path, plcrun leaves its declared initial value"
            ),
        ),
        other if LAYOUT_ATTRIBUTES.contains(&other) => (
            "W153",
            format!(
                "attribute '{name}' ignored: it changes layout, initialisation or access in CODESYS"
            ),
        ),
        other if TOOL_ATTRIBUTES.contains(&other) => (
            "W155",
            format!(
                "attribute '{name}' ignored: it tells tools about the program (symbols, \
                 monitoring, static analysis, generators); the program runs the same"
            ),
        ),
        _ => return None,
    })
}

/// Attributes read by tools around the program, not by the code it runs:
/// ADS symbols, online monitoring, the linker, static analysis, library
/// display, and generators such as SLAC's `pytmc` (EPICS records).
const TOOL_ATTRIBUTES: [&str; 12] = [
    "pytmc",
    "analysis",
    "symbol",
    "monitoring",
    "linkalways",
    "obsolete",
    "conditionalshow",
    "conditionalshow_all_locals",
    "displaymode",
    "naming",
    "reflection",
    "estimated-stack-usage",
];

/// Attributes that change layout, initialisation or access in CODESYS.
const LAYOUT_ATTRIBUTES: [&str; 8] = [
    "pack_mode",
    "no_init",
    "noinit",
    "no_copy",
    "no_assign",
    "global_init_slot",
    "init_namespace",
    "hide",
];

/// `text` cut to 40 characters.
fn short(text: &str) -> String {
    match text.char_indices().nth(40) {
        Some((cut, _)) => format!("{}...", &text[..cut]),
        None => text.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::named;

    #[test]
    fn meaningful_pragmas_are_named() {
        let code = |t: &str| named(t).map(|(c, _)| c);
        assert_eq!(code("{attribute 'qualified_only'}"), Some("W150"));
        assert_eq!(code("{ attribute 'call_after_init' }"), Some("W151"));
        assert_eq!(code("{attribute 'TcInitSymbol'}"), Some("W151"));
        assert_eq!(code("{IF defined(SIMULATION)}"), Some("W152"));
        assert_eq!(code("{END_IF}"), Some("W152"));
        assert_eq!(code("{attribute 'pack_mode' := '1'}"), Some("W153"));
        assert_eq!(code("{error 'not for this PLC'}"), Some("W154"));
        assert_eq!(code("{attribute 'pytmc' := 'pv: X'}"), Some("W155"));
        assert_eq!(code("{attribute 'instance-path'}"), Some("W151"));
        assert_eq!(code("{flow}"), Some("W155"));
        assert_eq!(code("{ a pragma }"), None);
        assert_eq!(
            code("{attribute 'x'}"),
            None,
            "an unknown attribute stays W001"
        );
        let (_, m) = named("{attribute 'pack_mode' := '1'}").unwrap();
        assert!(m.contains("'pack_mode'"), "{m}");
        let (_, m) = named("{IF defined(SIMULATION)}").unwrap();
        assert!(m.contains("IF defined(SIMULATION)"), "{m}");
    }
}

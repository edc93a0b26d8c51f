//! `{attribute 'qualified_only'}` and `{attribute 'strict'}` before a
//! `TYPE` (CODESYS / TwinCAT): the enumeration values of the types declared
//! there must be written with their type's name (`E_Mode.Run`), and a
//! strict enumeration never converts to or from an integer. The attribute
//! is found in the source text right before the `TYPE` keyword, with only
//! blanks and other pragmas between; the lexer uses the same rule to know
//! that the attribute is honoured (no W150, no W001) rather than ignored.

/// Whether pragma text `{...}` is `{attribute 'qualified_only'}`.
pub fn is_qualified_only(pragma: &str) -> bool {
    is_attribute(pragma, "qualified_only")
}

/// Whether pragma text `{...}` is `{attribute 'strict'}`.
pub fn is_strict(pragma: &str) -> bool {
    is_attribute(pragma, "strict")
}

/// Whether pragma text `{...}` is `{attribute 'no_check'}`.
pub fn is_no_check(pragma: &str) -> bool {
    is_attribute(pragma, "no_check")
}

/// Whether `FUNCTION`, `FUNCTION_BLOCK`, `PROGRAM` or `METHOD` (with
/// its modifiers) follows `rest`, with only blanks and pragmas before it:
/// where `no_check` is honoured.
pub fn pou_follows(rest: &str) -> bool {
    matches!(
        first_word(rest).as_str(),
        "FUNCTION" | "FUNCTION_BLOCK" | "FUNCTIONBLOCK" | "PROGRAM" | "METHOD"
    )
}

/// The first word of `rest` after blanks and pragmas, upper-cased.
fn first_word(rest: &str) -> String {
    let mut rest = rest.trim_start();
    while rest.starts_with('{') {
        match rest.find('}') {
            Some(close) => rest = rest[close + 1..].trim_start(),
            None => return String::new(),
        }
    }
    rest.chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect::<String>()
        .to_ascii_uppercase()
}

/// Whether pragma text `{...}` is `{attribute 'call_after_init'}`.
pub fn is_call_after_init(pragma: &str) -> bool {
    is_attribute(pragma, "call_after_init")
}

/// Whether `METHOD` or `FUNCTION_BLOCK` (with its modifiers) follows
/// `rest`, with only blanks and pragmas before it: where
/// `call_after_init` is honoured.
pub fn method_or_block_follows(rest: &str) -> bool {
    matches!(
        first_word(rest).as_str(),
        "METHOD" | "FUNCTION_BLOCK" | "FUNCTIONBLOCK"
    )
}

/// Whether pragma text `{...}` is `{attribute 'name'}`.
fn is_attribute(pragma: &str, name: &str) -> bool {
    let inner = pragma.trim_start_matches('{').trim_end_matches('}').trim();
    let Some(rest) = strip_word(inner, "attribute") else {
        return false;
    };
    rest.trim()
        .trim_matches(|c| c == '\'' || c == '"')
        .trim()
        .eq_ignore_ascii_case(name)
}

/// Whether the `TYPE` keyword at byte `at` of `text` is preceded by a
/// pragma `is` accepts, with only blanks and pragmas between.
pub fn before_type(text: &str, at: usize, is: fn(&str) -> bool) -> bool {
    let mut end = at.min(text.len());
    loop {
        let trimmed = text[..end].trim_end();
        if !trimmed.ends_with('}') {
            return false;
        }
        // Pragmas do not nest: the last `{` opens this one.
        let Some(open) = trimmed.rfind('{') else {
            return false;
        };
        if is(&trimmed[open..]) {
            return true;
        }
        end = open;
    }
}

/// Whether a `TYPE` keyword follows `rest` (the text after a pragma),
/// with only blanks and pragmas before it.
pub fn type_follows(rest: &str) -> bool {
    let mut rest = rest.trim_start();
    while rest.starts_with('{') {
        match rest.find('}') {
            Some(close) => rest = rest[close + 1..].trim_start(),
            None => return false,
        }
    }
    strip_word(rest, "TYPE").is_some()
}

/// `text` after its first word when that word is `word` (any case).
fn strip_word<'a>(text: &'a str, word: &str) -> Option<&'a str> {
    let head = text.get(..word.len())?;
    let rest = &text[word.len()..];
    let ends = !rest.starts_with(|c: char| c.is_ascii_alphanumeric() || c == '_');
    (head.eq_ignore_ascii_case(word) && ends).then_some(rest)
}

#[cfg(test)]
mod tests {
    use super::{before_type, is_qualified_only, is_strict, type_follows};

    #[test]
    fn the_attribute_is_found_next_to_its_type_keyword() {
        assert!(is_qualified_only("{attribute 'qualified_only'}"));
        assert!(is_qualified_only("{ attribute \"QUALIFIED_ONLY\" }"));
        assert!(!is_qualified_only("{attribute 'strict'}"));
        assert!(!is_qualified_only("{attributes 'qualified_only'}"));
        let text = "{attribute 'qualified_only'}\n{attribute 'strict'}\nTYPE E : (A); END_TYPE";
        let at = text.find("TYPE").unwrap();
        assert!(before_type(text, at, is_qualified_only));
        assert!(before_type(text, at, is_strict));
        assert!(!is_strict("{attribute 'strictly'}"));
        assert!(type_follows(&text["{attribute 'qualified_only'}".len()..]));
        let text =
            "{attribute 'qualified_only'}\nVAR_GLOBAL x : INT; END_VAR\nTYPE E : (A); END_TYPE";
        assert!(!before_type(
            text,
            text.find("TYPE").unwrap(),
            is_qualified_only
        ));
        assert!(!type_follows(&text["{attribute 'qualified_only'}".len()..]));
        assert!(!type_follows(" TYPES"));
    }
}

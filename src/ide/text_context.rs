//! What the text just before the cursor says, read without the parser: an
//! edit in progress (`motor.`, `f(a, `) does not parse yet, so completion
//! and signature help look at the characters instead.

/// One link of a member chain such as `line.motors[i]^.`.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Link {
    /// The name, as written.
    pub name: String,
    /// Subscripts follow the name (`[i]`), once per bracket pair.
    pub indexed: usize,
    /// A `^` follows the name (or its subscripts).
    pub deref: bool,
}

/// An unclosed call around the cursor.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CallSite {
    /// What is called: `f`, `inst`, `a.b.method`.
    pub callee: Vec<Link>,
    /// Which argument the cursor is in (0-based), by commas.
    pub argument: usize,
    /// The formal name written at the start of that argument (`PT :=`).
    pub named: Option<String>,
    /// Only blanks stand between the argument's start and the cursor.
    pub at_start: bool,
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// `text` with comments and string literals blanked (same length, line
/// breaks kept), so that brackets and dots inside them are not read.
pub(super) fn masked(text: &str) -> Vec<u8> {
    let bytes = text.as_bytes();
    let mut out = bytes.to_vec();
    let mut i = 0;
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for b in &mut out[from..to] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
    };
    while i < bytes.len() {
        let rest = &bytes[i..];
        let end = if rest.starts_with(b"(*") {
            find(bytes, i + 2, b"*)").map_or(bytes.len(), |e| e + 2)
        } else if rest.starts_with(b"/*") {
            find(bytes, i + 2, b"*/").map_or(bytes.len(), |e| e + 2)
        } else if rest.starts_with(b"//") {
            find(bytes, i, b"\n").unwrap_or(bytes.len())
        } else if rest[0] == b'\'' || rest[0] == b'"' {
            let quote = rest[0];
            let mut j = i + 1;
            while j < bytes.len() && bytes[j] != quote && bytes[j] != b'\n' {
                j += if bytes[j] == b'$' { 2 } else { 1 };
            }
            (j + 1).min(bytes.len())
        } else {
            i += 1;
            continue;
        };
        blank(&mut out, i, end);
        i = end;
    }
    out
}

fn find(bytes: &[u8], from: usize, what: &[u8]) -> Option<usize> {
    bytes
        .get(from..)?
        .windows(what.len())
        .position(|w| w == what)
        .map(|p| p + from)
}

/// The identifier at or just before `offset`: its start and text.
pub(super) fn word_at(text: &str, offset: usize) -> Option<(usize, &str)> {
    let bytes = text.as_bytes();
    let offset = offset.min(bytes.len());
    let mut start = offset;
    while start > 0 && is_ident(bytes[start - 1]) {
        start -= 1;
    }
    let mut end = offset;
    while end < bytes.len() && is_ident(bytes[end]) {
        end += 1;
    }
    (start < end).then(|| (start, &text[start..end]))
}

/// The start of the identifier being typed at `offset` (`offset` itself
/// when none is).
pub(super) fn typed_word_start(text: &[u8], offset: usize) -> usize {
    let mut start = offset.min(text.len());
    while start > 0 && is_ident(text[start - 1]) {
        start -= 1;
    }
    start
}

/// The chain ending at byte `end` of masked text (exclusive), read
/// backwards: `a.b[i]^.c` gives `a`, `b` (indexed, deref), `c`.
fn chain_before(text: &[u8], end: usize) -> Option<Vec<Link>> {
    let mut links = Vec::new();
    let mut i = end;
    loop {
        while i > 0 && text[i - 1] == b' ' {
            i -= 1;
        }
        let mut deref = false;
        if i > 0 && text[i - 1] == b'^' {
            deref = true;
            i -= 1;
        }
        let mut indexed = 0;
        while i > 0 && text[i - 1] == b']' {
            let mut depth = 0usize;
            loop {
                if i == 0 {
                    return None;
                }
                i -= 1;
                match text[i] {
                    b']' => depth += 1,
                    b'[' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
            }
            indexed += 1;
        }
        let name_end = i;
        while i > 0 && is_ident(text[i - 1]) {
            i -= 1;
        }
        if i == name_end || text[i].is_ascii_digit() {
            return None;
        }
        links.push(Link {
            name: String::from_utf8_lossy(&text[i..name_end]).into_owned(),
            indexed,
            deref,
        });
        if i > 0 && text[i - 1] == b'.' {
            i -= 1;
        } else {
            break;
        }
    }
    links.reverse();
    Some(links)
}

/// The chain before a `.` the cursor follows (a name may be partly typed
/// after it): `motor.` and `motor.sp` both give `[motor]`.
pub(super) fn member_chain(text: &str, offset: usize) -> Option<Vec<Link>> {
    let masked = masked(&text[..offset.min(text.len())]);
    let start = typed_word_start(&masked, masked.len());
    if start == 0 || masked[start - 1] != b'.' {
        return None;
    }
    chain_before(&masked, start - 1)
}

/// The call whose argument list the cursor is in, if any.
pub(super) fn call_site(text: &str, offset: usize) -> Option<CallSite> {
    let masked = masked(&text[..offset.min(text.len())]);
    let mut depth = 0usize;
    let mut commas = 0;
    let mut arg_start = masked.len();
    let mut i = masked.len();
    while i > 0 {
        i -= 1;
        match masked[i] {
            b')' | b']' => depth += 1,
            b'[' if depth > 0 => depth -= 1,
            b'(' if depth > 0 => depth -= 1,
            b'[' => return None,
            b'(' => break,
            b',' if depth == 0 => {
                if commas == 0 {
                    arg_start = i + 1;
                }
                commas += 1;
            }
            b';' if depth == 0 => return None,
            _ => {}
        }
        if i == 0 {
            return None;
        }
    }
    if commas == 0 {
        arg_start = i + 1;
    }
    let callee = chain_before(&masked, i)?;
    let arg = String::from_utf8_lossy(&masked[arg_start..]).into_owned();
    let named = arg
        .split_once(":=")
        .or_else(|| arg.split_once("=>"))
        .map(|(n, _)| n.trim().trim_start_matches("NOT ").trim().to_string())
        .filter(|n| !n.is_empty() && n.bytes().all(is_ident));
    Some(CallSite {
        callee,
        argument: commas,
        named,
        at_start: arg.trim().is_empty(),
    })
}

/// Where the cursor is in a declaration section: `None` outside one,
/// `Some(true)` after the `:` of a declaration (a type is expected),
/// `Some(false)` before it (a name is expected).
pub(super) fn in_declaration(text: &str, offset: usize) -> Option<bool> {
    let masked = masked(&text[..offset.min(text.len())]);
    let upper = String::from_utf8_lossy(&masked).to_ascii_uppercase();
    let words: Vec<(usize, &str)> = word_positions(&upper);
    let last_open = words
        .iter()
        .rev()
        .find(|(_, w)| w.starts_with("VAR") && !w.starts_with("VARIABLE"))
        .map(|(p, _)| *p);
    let last_close = words
        .iter()
        .rev()
        .find(|(_, w)| *w == "END_VAR" || *w == "END_STRUCT")
        .map(|(p, _)| *p);
    let last_struct = words
        .iter()
        .rev()
        .find(|(_, w)| *w == "STRUCT")
        .map(|(p, _)| *p);
    let open = last_open.max(last_struct)?;
    if last_close.is_some_and(|c| c > open) {
        return None;
    }
    let statement = upper.rfind(';').map_or(open, |s| s.max(open));
    let current = &upper[statement..];
    Some(current.contains(':') && !current.contains(":="))
}

fn word_positions(text: &str) -> Vec<(usize, &str)> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if is_ident(bytes[i]) {
            let start = i;
            while i < bytes.len() && is_ident(bytes[i]) {
                i += 1;
            }
            out.push((start, &text[start..i]));
        } else {
            i += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(links: &[Link]) -> Vec<&str> {
        links.iter().map(|l| l.name.as_str()).collect()
    }

    #[test]
    fn member_chains_through_subscripts_and_dereferences() {
        let text = "x := line.motors[i + 1]^.";
        let links = member_chain(text, text.len()).unwrap();
        assert_eq!(names(&links), ["line", "motors"]);
        assert_eq!(links[1].indexed, 1);
        assert!(links[1].deref);
        let text = "x := motor.sp";
        assert_eq!(names(&member_chain(text, text.len()).unwrap()), ["motor"]);
        assert_eq!(member_chain("x := 1.", 7), None);
        assert_eq!(member_chain("x := motor", 10), None);
    }

    #[test]
    fn call_sites_count_arguments_and_read_formal_names() {
        let text = "t1(IN := start, PT := ";
        let site = call_site(text, text.len()).unwrap();
        assert_eq!(names(&site.callee), ["t1"]);
        assert_eq!(site.argument, 1);
        assert_eq!(site.named.as_deref(), Some("PT"));
        let text = "y := LIMIT(0, f(a, b), ";
        let site = call_site(text, text.len()).unwrap();
        assert_eq!(names(&site.callee), ["LIMIT"]);
        assert_eq!(site.argument, 2);
        assert!(site.at_start);
        assert_eq!(call_site("x := a; y := (b", 15).map(|s| s.callee), None);
        assert_eq!(call_site("x := 'f(' + g", 13), None);
    }

    #[test]
    fn declaration_sections_expect_names_then_types() {
        let text = "VAR\n  speed : ";
        assert_eq!(in_declaration(text, text.len()), Some(true));
        let text = "VAR\n  a : INT;\n  sp";
        assert_eq!(in_declaration(text, text.len()), Some(false));
        let text = "VAR\n  a : INT;\nEND_VAR\n  a := ";
        assert_eq!(in_declaration(text, text.len()), None);
    }
}

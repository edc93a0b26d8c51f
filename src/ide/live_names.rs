//! Where an editor can show the value a running PLC has for a name: each
//! use of a program's variable or a global in a body, extended through
//! the `.member` names written after it (`p.a.count`), with the paths the
//! runtime may list it under (`p.a.count`, or `Main.p.a.count` when the
//! program's name prefixes its variables).

use super::Analysis;
use super::symbol::SymbolKind;
use crate::source::{FileId, Span};

/// A name an editor can show a live value beside.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LiveName {
    /// The whole access as written (`p.a.count`); the value goes after
    /// its end.
    pub span: Span,
    /// The variable paths it may have in a running PLC, the likeliest
    /// first; an editor shows the first one the PLC knows.
    pub paths: Vec<String>,
}

impl Analysis {
    /// The names of `file` that stand for variables a running PLC has,
    /// in position order: uses (not declarations) of a PROGRAM's variables
    /// and of global variables. Uses inside a FUNCTION_BLOCK or a METHOD
    /// are left out: their values depend on the instance.
    pub fn live_names(&self, file: FileId) -> Vec<LiveName> {
        let text = &self.sources().file(file).text;
        let mut out = Vec::new();
        for o in self.occurrences_in(file) {
            if o.declaration || follows_a_dot(text, o.span.start as usize) {
                continue;
            }
            let symbol = self.symbol(o.symbol);
            let program = match symbol.kind {
                SymbolKind::Global => None,
                SymbolKind::Variable(_) => match symbol.parent.map(|p| self.symbol(p)) {
                    Some(p) if p.kind == SymbolKind::Program => Some(p.name.clone()),
                    _ => continue,
                },
                _ => continue,
            };
            let end = member_chain_end(text, o.span.end as usize);
            // A call (`p.Method()`) or an element (`a[i]`) has no one value.
            if text[end..].starts_with(['(', '[']) {
                continue;
            }
            let written: String = text[o.span.start as usize..end]
                .chars()
                .filter(|c| !c.is_whitespace())
                .collect();
            let mut paths = vec![written.clone()];
            if let Some(p) = program {
                paths.push(format!("{p}.{written}"));
            }
            out.push(LiveName {
                span: Span::new(file, o.span.start as usize, end),
                paths,
            });
        }
        out
    }
}

/// Whether the name at byte `at` is a member (`x.name`).
fn follows_a_dot(text: &str, at: usize) -> bool {
    text[..at].trim_end().ends_with('.')
}

/// The end of `name.member.member...` whose first name ends at `end`.
fn member_chain_end(text: &str, mut end: usize) -> usize {
    let bytes = text.as_bytes();
    loop {
        let mut k = end;
        if bytes.get(k) != Some(&b'.') {
            return end;
        }
        k += 1;
        let start = k;
        while bytes
            .get(k)
            .is_some_and(|b| b.is_ascii_alphanumeric() || *b == b'_')
        {
            k += 1;
        }
        // `x.3` (a bit) and `x.%X3` are not member names.
        if k == start || bytes[start].is_ascii_digit() {
            return end;
        }
        end = k;
    }
}

#[cfg(test)]
mod tests {
    use crate::driver::CheckOptions;
    use crate::source::SourceMap;

    #[test]
    fn program_variables_and_globals_are_named_with_their_member_chains() {
        let src = "VAR_GLOBAL g : INT; END_VAR
FUNCTION_BLOCK FB VAR_OUTPUT q : INT; END_VAR VAR n : INT; END_VAR n := n + 1; q := n; END_FUNCTION_BLOCK
PROGRAM Main VAR fb : FB; arr : ARRAY[1..2] OF INT; x : INT; END_VAR
fb(); x := fb.q + g; arr[1] := x;
END_PROGRAM";
        let mut sources = SourceMap::new();
        let file = sources.add("m.st", src.to_string());
        let analysis = crate::Analysis::new(sources, &CheckOptions::default());
        let names: Vec<(String, Vec<String>)> = analysis
            .live_names(file)
            .into_iter()
            .map(|n| {
                (
                    src[n.span.start as usize..n.span.end as usize].to_string(),
                    n.paths,
                )
            })
            .collect();
        let p = |a: &str, b: &str| vec![a.to_string(), b.to_string()];
        assert_eq!(
            names,
            [
                ("x".to_string(), p("x", "Main.x")),
                ("fb.q".to_string(), p("fb.q", "Main.fb.q")),
                ("g".to_string(), vec!["g".to_string()]),
                ("x".to_string(), p("x", "Main.x")),
            ]
        );
    }
}

//! `--keep-going` inside a global variable list: a list whose only errors
//! are in the declarations of some of its variables (a TwinCAT GVL holding
//! one variable of a library plcrun does not have, `BP_jsonDoc :
//! SJsonValue;`) keeps its other variables. Those declarations are blanked
//! out (spaces, line breaks kept, so every other position in the file
//! stays the same) and the rest of the list is checked again; the code
//! that uses a variable left out then fails and is left out in turn.

use crate::diagnostics::Diagnostics;
use crate::source::{FileId, SourceFile, Span};
use crate::syntax::ast::Item;

/// A list with some of its declarations blanked out.
pub(super) struct Blanked {
    /// The file's new text.
    pub(super) text: String,
    /// The variables left out, as declared.
    pub(super) names: Vec<String>,
}

/// The text of `file` (id `id`) with the global declarations that hold the
/// errors at `errors` blanked out; `None` when an error lies outside every
/// declaration of a `VAR_GLOBAL` block (a body, a type, a POU's own
/// variable: the whole file is left out then).
pub(super) fn blank_global_declarations(
    id: FileId,
    file: &SourceFile,
    errors: &[Span],
) -> Option<Blanked> {
    let unit = crate::syntax::parse_source(id, file, &mut Diagnostics::new());
    let decls: Vec<_> = unit
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Globals(block) => Some(block.decls.iter()),
            _ => None,
        })
        .flatten()
        .collect();
    let mut chosen = Vec::new();
    for e in errors {
        let holder = decls
            .iter()
            .find(|d| d.span.start <= e.start && e.end <= d.span.end.max(e.start))?;
        if !chosen
            .iter()
            .any(|c: &&&crate::syntax::ast::VarDecl| c.span == holder.span)
        {
            chosen.push(holder);
        }
    }
    let mut names = Vec::new();
    let mut ranges = Vec::new();
    for d in chosen {
        let start = d.span.start as usize;
        let mut end = (d.span.end as usize).min(file.text.len());
        // The `;` that ends the declaration, if the span stops before it.
        let rest = &file.text[end..];
        if let Some(semi) = rest.find(|c: char| !c.is_whitespace())
            && rest[semi..].starts_with(';')
        {
            end += semi + 1;
        }
        ranges.push(start..end);
        names.extend(d.names.iter().map(|n| n.name.clone()));
    }
    let text = crate::source::blank_out(&file.text, ranges)?;
    Some(Blanked { text, names })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_declarations_holding_errors_are_blanked() {
        let text = "VAR_GLOBAL\n  a : INT := 1;\n  b : Unknown;\n  c : BOOL;\nEND_VAR\n";
        let file = SourceFile::new("g.st", text);
        let at = text.find("Unknown").unwrap() as u32;
        let error = Span::new(FileId(0), at as usize, at as usize + 7);
        let b = blank_global_declarations(FileId(0), &file, &[error]).unwrap();
        assert_eq!(b.names, ["b"]);
        assert_eq!(b.text.len(), text.len());
        assert!(b.text.contains("a : INT := 1;") && b.text.contains("c : BOOL;"));
        assert!(!b.text.contains("Unknown") && !b.text.contains(" b "));
        // An error in a program's body is not a global's.
        let prog = SourceFile::new(
            "p.st",
            "PROGRAM P\nVAR x : INT; END_VAR\nx := y;\nEND_PROGRAM\n",
        );
        let at = prog.text.find("y;").unwrap();
        let error = Span::new(FileId(0), at, at + 1);
        assert!(blank_global_declarations(FileId(0), &prog, &[error]).is_none());
    }
}

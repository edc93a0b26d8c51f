//! Splits an S7-200 STL text into lines of words: `NETWORK` headers (with
//! their titles), block headers of Micro/WIN's exported form
//! (`ORGANIZATION_BLOCK`, `SUBROUTINE_BLOCK SBR_0:SBR0`, `BEGIN`, `TITLE=`,
//! `END_…`), and instructions (a mnemonic and its operands, separated by
//! blanks or commas). `//` starts a comment to the end of the line; a
//! leading print address (`15 LD SM0.0`, as old listings show) is dropped.

use crate::source::{FileId, Span};

/// A word of a line and where it is.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Word {
    /// As written.
    pub text: String,
    /// Where.
    pub span: Span,
}

/// One meaningful line.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Line {
    /// `NETWORK [n] [title]`: a boundary with no code.
    Network,
    /// A block header or footer of the exported form, by its first word
    /// (upper case) and the rest of its words.
    Block(Word, Vec<Word>),
    /// An instruction.
    Instr {
        /// Its mnemonic.
        mnemonic: Word,
        /// Its operands.
        operands: Vec<Word>,
        /// The whole instruction.
        span: Span,
    },
}

/// The first words of the exported form's block lines.
const BLOCK_WORDS: &[&str] = &[
    "ORGANIZATION_BLOCK",
    "SUBROUTINE_BLOCK",
    "INTERRUPT_BLOCK",
    "END_ORGANIZATION_BLOCK",
    "END_SUBROUTINE_BLOCK",
    "END_INTERRUPT_BLOCK",
    "BEGIN",
    "VAR_INPUT",
    "VAR_OUTPUT",
    "VAR_IN_OUT",
    "VAR",
    "VAR_TEMP",
    "END_VAR",
];

/// Whether `word` (upper case) starts a NETWORK header: `NETWORK`,
/// `NETWORK12`.
pub(super) fn is_network(word: &str) -> bool {
    word.strip_prefix("NETWORK")
        .is_some_and(|rest| rest.bytes().all(|b| b.is_ascii_digit()))
}

/// The words of one line (comment removed), with absolute offsets.
fn words(file: FileId, line: &str, base: usize) -> Vec<Word> {
    let code = match line.find("//") {
        Some(i) => &line[..i],
        None => line,
    };
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in code
        .char_indices()
        .chain(std::iter::once((code.len(), ' ')))
    {
        let separator = c.is_whitespace() || c == ',';
        match (start, separator) {
            (None, false) => start = Some(i),
            (Some(s), true) => {
                out.push(Word {
                    text: code[s..i].to_string(),
                    span: Span::new(file, base + s, base + i),
                });
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// The meaningful lines of `text`.
pub(super) fn lines(file: FileId, text: &str) -> Vec<Line> {
    let mut out = Vec::new();
    let mut base = 0;
    for raw in text.split_inclusive('\n') {
        let line = raw.trim_end_matches(['\n', '\r']);
        let mut ws = words(file, line, base);
        base += raw.len();
        if ws.is_empty() {
            continue;
        }
        let first = ws[0].text.to_ascii_uppercase();
        if is_network(&first) {
            out.push(Line::Network);
            continue;
        }
        if first.starts_with("TITLE") {
            continue;
        }
        if BLOCK_WORDS.contains(&first.as_str()) {
            let head = ws.remove(0);
            out.push(Line::Block(
                Word {
                    text: first,
                    span: head.span,
                },
                ws,
            ));
            continue;
        }
        // A print address before the mnemonic.
        if ws.len() > 1 && ws[0].text.bytes().all(|b| b.is_ascii_digit()) {
            ws.remove(0);
        }
        let mnemonic = ws.remove(0);
        let end = ws.last().map_or(mnemonic.span, |w| w.span);
        out.push(Line::Instr {
            span: mnemonic.span.to(end),
            mnemonic,
            operands: ws,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn networks_comments_and_both_operand_styles() {
        let text = "NETWORK 1 // title\n// only a comment\n  15 LD SM0.0\nTON T37, +50\nS V72.0 K2\nNETWORK12\n";
        let ls = lines(FileId(0), text);
        assert_eq!(ls.len(), 5);
        assert_eq!(ls[0], Line::Network);
        let Line::Instr {
            mnemonic, operands, ..
        } = &ls[1]
        else {
            panic!("{:?}", ls[1]);
        };
        assert_eq!(mnemonic.text, "LD");
        assert_eq!(operands[0].text, "SM0.0");
        assert_eq!(
            &text[operands[0].span.start as usize..operands[0].span.end as usize],
            "SM0.0"
        );
        let Line::Instr { operands, .. } = &ls[2] else {
            panic!();
        };
        assert_eq!(operands.len(), 2);
        assert_eq!(operands[1].text, "+50");
        assert_eq!(ls[4], Line::Network);
    }
}

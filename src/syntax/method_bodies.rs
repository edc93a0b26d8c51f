//! Method bodies in the IL line-orientation pass: each METHOD of a POU is
//! classified (IL or not) on its own, between its header or last END_VAR
//! and its END_METHOD, and the POU's own body starts after the last
//! END_METHOD, so an FB can have an IL body next to ST methods and the
//! other way round.

use crate::syntax::lexer::Spanned;
use crate::syntax::token::{Kw, Tok};

/// One region classifier: `(start, end, regions)`.
type Classify<'a> = dyn FnMut(usize, usize, &mut Vec<(usize, usize)>) + 'a;

fn kw(tokens: &[Spanned], i: usize) -> Option<Kw> {
    match tokens.get(i) {
        Some((_, Tok::Kw(k), _)) => Some(*k),
        _ => None,
    }
}

/// Classifies the bodies of the methods of the POU at `pou` (ending at
/// `end`); the first token of the POU's own body, or `None` when it has no
/// methods.
pub(crate) fn classify_methods(
    tokens: &[Spanned],
    pou: usize,
    end: usize,
    classify: &mut Classify<'_>,
    regions: &mut Vec<(usize, usize)>,
) -> Option<usize> {
    let mut after = None;
    let mut i = pou + 1;
    while i < end {
        if kw(tokens, i) != Some(Kw::Method) {
            i += 1;
            continue;
        }
        let m_end = (i + 1..end)
            .find(|&j| kw(tokens, j) == Some(Kw::EndMethod))
            .unwrap_or(end);
        // The header's modifiers are skipped: the name follows the last one.
        let mut head = i;
        while matches!(
            kw(tokens, next_sig(tokens, head + 1)),
            Some(
                Kw::Public | Kw::Private | Kw::Protected | Kw::Internal | Kw::Abstract | Kw::Final
            )
        ) {
            head = next_sig(tokens, head + 1);
        }
        let start = crate::syntax::il_lines::body_start(tokens, head, m_end);
        classify(start, m_end, regions);
        after = Some(m_end + 1);
        i = m_end + 1;
    }
    after.map(|a| a.min(end))
}

fn next_sig(tokens: &[Spanned], mut i: usize) -> usize {
    while i < tokens.len() && tokens[i].1 == Tok::Eol {
        i += 1;
    }
    i
}

//! The token stream a PLCopen project becomes.
//!
//! The importer does not build the AST by hand: it writes the tokens of
//! the equivalent textual source and hands them to the textual parser, so
//! IL, ST and SFC keep one grammar. Tokens that stand for XML structure
//! (`PROGRAM`, `VAR_INPUT`, `:`...) carry the position of the element they
//! come from; tokens of a body or of an attribute value are lexed from the
//! decoded text and carry the exact position of their characters in the
//! file, so every diagnostic, from the parser or from the checker, points
//! into the XML file.

use super::codes;
use super::raw::{Decoded, RawProblem, decode};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, Span};
use crate::syntax::lexer::{self, Spanned};
use crate::syntax::token::Tok;
use roxmltree::Node;

/// A byte range in the XML file (relative to the parsed text).
pub type Range = (usize, usize);

/// Collects tokens and diagnostics for one XML file.
pub struct Emitter<'x> {
    file: FileId,
    /// The text given to the XML parser (the file after a byte-order mark).
    xml: &'x str,
    /// Offset of `xml` in the file (3 after a byte-order mark, else 0).
    base: usize,
    /// The tokens so far.
    pub toks: Vec<Spanned>,
    /// The diagnostics so far.
    pub diags: Diagnostics,
    /// Whether the ST text's `(* *)` comments nest (CODESYS and TwinCAT
    /// files: true; other PLCopen writers: false).
    pub nested_comments: bool,
}

impl<'x> Emitter<'x> {
    /// An emitter for `xml`, which starts at byte `base` of file `file`.
    pub fn new(file: FileId, xml: &'x str, base: usize) -> Emitter<'x> {
        Emitter {
            file,
            xml,
            base,
            toks: Vec::new(),
            diags: Diagnostics::new(),
            nested_comments: false,
        }
    }

    /// The span of `range` in the file.
    pub fn span(&self, (s, e): Range) -> Span {
        Span::new(self.file, s + self.base, e.max(s) + self.base)
    }

    /// The range of an element's start-tag name (`<pou`), where its
    /// diagnostics point.
    pub fn at(&self, node: Node) -> Range {
        let start = node.range().start;
        let len = 1 + node.tag_name().name().len();
        (start, (start + len).min(self.xml.len()))
    }

    /// The last byte of an element (its end tag's `>`).
    pub fn end_of(&self, node: Node) -> Range {
        let end = node.range().end;
        (end.saturating_sub(1), end)
    }

    /// Reports an error at `range`.
    pub fn error(&mut self, code: &'static str, range: Range, message: impl Into<String>) {
        let span = self.span(range);
        self.diags.push(Diagnostic::error(code, span, message));
    }

    /// Reports a warning at `range`.
    pub fn warning(&mut self, code: &'static str, range: Range, message: impl Into<String>) {
        let span = self.span(range);
        self.diags.push(Diagnostic::warning(code, span, message));
    }

    /// Refuses an element plcrun cannot represent, by name.
    pub fn refuse(&mut self, node: Node, why: &str) {
        let name = node.tag_name().name();
        self.error(
            codes::REFUSED,
            self.at(node),
            format!("`<{name}>` is not supported by plcrun: {why}"),
        );
    }

    /// Reports an element that has no place where it stands.
    pub fn unknown(&mut self, node: Node, parent: &str) {
        let name = node.tag_name().name();
        self.error(
            codes::UNKNOWN_ELEMENT,
            self.at(node),
            format!("unknown element `<{name}>` in `<{parent}>`"),
        );
    }

    /// Emits the tokens of `text` (fixed words such as `END_VAR`), all
    /// placed at `range`.
    pub fn synth(&mut self, text: &str, range: Range) {
        let span = self.span(range);
        let mut scratch = Diagnostics::new();
        for (_, tok, _) in lexer::lex(self.file, text, &mut scratch) {
            if tok != Tok::Eol {
                self.toks
                    .push((span.start as usize, tok, span.end as usize));
            }
        }
    }

    /// Emits an identifier token at `range`.
    pub fn ident(&mut self, name: &str, range: Range) {
        let span = self.span(range);
        self.toks.push((
            span.start as usize,
            Tok::Ident(name.to_string()),
            span.end as usize,
        ));
    }

    /// Emits a line break (IL bodies are line-oriented).
    pub fn eol(&mut self, range: Range) {
        let span = self.span(range);
        self.toks
            .push((span.start as usize, Tok::Eol, span.end as usize));
    }

    /// Decodes `range` of the file and emits its tokens at their own
    /// positions; line breaks are kept when `keep_eol`. Returns false (and
    /// reports) when the range holds markup.
    pub fn lex_range(&mut self, range: Range, keep_eol: bool) -> bool {
        let decoded = match decode(self.xml, range.0, range.1) {
            Ok(d) => d,
            Err(RawProblem::Markup(at)) => {
                self.error(
                    codes::MARKUP_IN_TEXT,
                    (at, at + 1),
                    "markup inside a textual body or value: only text, entities and CDATA are allowed here",
                );
                return false;
            }
        };
        self.lex_decoded(&decoded, keep_eol);
        true
    }

    /// Emits the tokens of decoded text, mapping positions to the file.
    fn lex_decoded(&mut self, decoded: &Decoded, keep_eol: bool) {
        let mut scratch = Diagnostics::new();
        let tokens = if self.nested_comments {
            lexer::lex_codesys(self.file, &decoded.text, &mut scratch)
        } else {
            lexer::lex(self.file, &decoded.text, &mut scratch)
        };
        for mut d in scratch.iter().cloned() {
            let (s, e) = decoded.file_range(d.span.start as usize, d.span.end as usize);
            d.span = self.span((s, e));
            self.diags.push(d);
        }
        for (l, mut tok, r) in tokens {
            if tok == Tok::Eol && !keep_eol {
                continue;
            }
            let (s, e) = decoded.file_range(l, r);
            let span = self.span((s, e));
            // A direct address carries its own span (a located variable's
            // diagnostics point with it): in the file, as the token's.
            if let Tok::Direct(d) = &mut tok {
                d.span = span;
            }
            self.toks
                .push((span.start as usize, tok, span.end as usize));
        }
    }

    /// The value of attribute `name`, if present.
    pub fn attr<'a>(&self, node: Node<'a, '_>, name: &str) -> Option<&'a str> {
        node.attribute(name)
    }

    /// The range of attribute `name`'s value.
    pub fn attr_range(&self, node: Node, name: &str) -> Option<Range> {
        node.attributes()
            .find(|a| a.name() == name)
            .map(|a| (a.range_value().start, a.range_value().end))
    }

    /// Emits the tokens of attribute `name`'s value; reports a missing one.
    pub fn lex_attr(&mut self, node: Node, name: &str) -> bool {
        match self.attr_range(node, name) {
            Some(range) => {
                let before = self.toks.len();
                let ok = self.lex_range(range, false);
                if ok && self.toks.len() == before {
                    self.error(
                        codes::MISSING_ATTRIBUTE,
                        range,
                        format!(
                            "attribute `{name}` of `<{}>` is empty",
                            node.tag_name().name()
                        ),
                    );
                    return false;
                }
                ok
            }
            None => {
                self.missing(node, name);
                false
            }
        }
    }

    /// Reports a missing required attribute.
    pub fn missing(&mut self, node: Node, name: &str) {
        self.error(
            codes::MISSING_ATTRIBUTE,
            self.at(node),
            format!("`<{}>` needs a `{name}` attribute", node.tag_name().name()),
        );
    }

    /// The IEC identifier in attribute `name`, emitted as a token at its
    /// position; `None` (reported) when missing or not an identifier.
    pub fn name<'a>(&mut self, node: Node<'a, '_>, name: &str) -> Option<&'a str> {
        let value = self.required_name(node, name)?;
        let range = self.attr_range(node, name).unwrap_or(self.at(node));
        self.lex_range(range, false);
        Some(value)
    }

    /// The IEC identifier in attribute `name`, checked but not emitted.
    pub fn required_name<'a>(&mut self, node: Node<'a, '_>, name: &str) -> Option<&'a str> {
        let Some(value) = node.attribute(name) else {
            self.missing(node, name);
            return None;
        };
        if !is_identifier(value) {
            let range = self.attr_range(node, name).unwrap_or(self.at(node));
            self.error(
                codes::BAD_NAME,
                range,
                format!("`{value}` is not an IEC 61131-3 identifier"),
            );
            return None;
        }
        Some(value)
    }
}

/// The XML document of `text` (after a byte-order mark) and an emitter
/// over it; `None` for malformed XML, reported in the emitter with code
/// `malformed` at the place the parser stopped.
pub fn open_xml<'x>(
    file: FileId,
    text: &'x str,
    malformed: &'static str,
) -> (Emitter<'x>, Option<roxmltree::Document<'x>>) {
    let base = text.len() - text.trim_start_matches('\u{FEFF}').len();
    let xml = &text[base..];
    let mut em = Emitter::new(file, xml, base);
    match crate::syntax::plcopen::read_xml(xml) {
        Ok(doc) => (em, Some(doc)),
        Err((at, e)) => {
            em.error(malformed, (at, at), format!("malformed XML: {e}"));
            (em, None)
        }
    }
}

/// Deepest element nesting the importer follows (types in types, values in
/// values): deeper input is refused instead of exhausting the stack.
const MAX_DEPTH: usize = 200;

impl Emitter<'_> {
    /// Reports (and returns true) when `node` is nested too deeply to follow.
    pub fn too_deep(&mut self, node: Node) -> bool {
        if node.ancestors().nth(MAX_DEPTH).is_none() {
            return false;
        }
        self.refuse(node, "nested too deeply");
        true
    }
}

/// True for `[A-Za-z_][A-Za-z0-9_]*`.
pub fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The element children of `node`.
pub fn elements<'a, 'i>(node: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(|n| n.is_element())
}

/// The first element child named `name`.
pub fn child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    elements(node).find(|n| n.tag_name().name() == name)
}

/// True for an XML boolean attribute value meaning true.
pub fn is_true(value: Option<&str>) -> bool {
    matches!(value.map(str::trim), Some("true" | "1"))
}

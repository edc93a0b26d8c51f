//! The lexer: runs the `logos` scanner, decodes literals, classifies
//! keywords, and reports malformed input as `E0xx` diagnostics (then keeps
//! going). Line breaks become [`Tok::Eol`]; [`crate::syntax::il_lines`] decides
//! where they matter.

use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::encoding::TextEncoding;
use crate::source::{FileId, Span};
use crate::syntax::ast::{AddrSize, Area, DirectAddress, Ident, Literal, LiteralValue};
use crate::syntax::literal::decode_typed_body;
use crate::syntax::token::{CommentNesting, Kw, PrefixKind, Raw, Tok, prefix_kind};
use crate::value::literal::{
    decode_string, parse_date_body, parse_dt_body, parse_duration_body, parse_int_text,
    parse_real_text, parse_tod_body,
};
use logos::Logos;

/// A token with its byte range, as the grammar wants it.
pub type Spanned = (usize, Tok, usize);

/// Lexes `text`. Never fails: bad input is reported into `diags` and either
/// skipped or turned into a harmless placeholder token.
pub fn lex(file: FileId, text: &str, diags: &mut Diagnostics) -> Vec<Spanned> {
    lex_in(file, text, TextEncoding::Utf8, diags)
}

/// [`lex`] of CODESYS / TwinCAT code, where `(* ... *)` comments nest.
pub fn lex_codesys(file: FileId, text: &str, diags: &mut Diagnostics) -> Vec<Spanned> {
    lex_with(
        file,
        text,
        TextEncoding::Utf8,
        CommentNesting::Nested,
        diags,
    )
}

/// [`lex`] of text read from a file in `encoding`: a STRING literal of a
/// Windows-1252 file keeps the file's bytes ([`TextEncoding::string_byte`]).
pub fn lex_in(
    file: FileId,
    text: &str,
    encoding: TextEncoding,
    diags: &mut Diagnostics,
) -> Vec<Spanned> {
    lex_with(file, text, encoding, CommentNesting::Flat, diags)
}

fn lex_with(
    file: FileId,
    text: &str,
    encoding: TextEncoding,
    nesting: CommentNesting,
    diags: &mut Diagnostics,
) -> Vec<Spanned> {
    let mut out = Vec::with_capacity(text.len() / 4);
    let mut lexer = Raw::lexer_with_extras(text, nesting);
    let mut bad_run: Option<(usize, usize)> = None;
    let span = |s: usize, e: usize| Span::new(file, s, e);
    while let Some(raw) = lexer.next() {
        let r = lexer.span();
        let slice = lexer.slice();
        let Ok(raw) = raw else {
            // Merge adjacent invalid characters into one diagnostic.
            match &mut bad_run {
                Some((_, e)) if *e == r.start => *e = r.end,
                _ => {
                    flush_bad(file, text, &mut bad_run, diags);
                    bad_run = Some((r.start, r.end));
                }
            }
            continue;
        };
        flush_bad(file, text, &mut bad_run, diags);
        let tok = match raw {
            Raw::Newline => Tok::Eol,
            Raw::BlockComment | Raw::SlashComment => {
                let (open, close) = if raw == Raw::BlockComment {
                    ("(*", "*)")
                } else {
                    ("/*", "*/")
                };
                if !slice.ends_with(close) || slice.len() < 4 {
                    diags.error(
                        "E002",
                        span(r.start, r.start + 2),
                        format!("unterminated comment: `{open}` has no closing `{close}`"),
                    );
                }
                // A comment spanning lines still ends an IL line.
                if slice.contains('\n') {
                    Tok::Eol
                } else {
                    continue;
                }
            }
            Raw::LineComment => continue,
            Raw::Pragma if pragma(span(r.start, r.end), slice, lexer.remainder(), diags) => {
                Tok::Eol
            }
            Raw::Pragma => continue,
            Raw::Word if library_list(&mut lexer, span(r.start, r.end), text, diags) => Tok::Eol,
            Raw::Word => word(slice),
            Raw::ThisDeref => Tok::Kw(Kw::ThisDeref),
            Raw::SuperDeref => Tok::Kw(Kw::SuperDeref),
            Raw::Typed => typed(
                file,
                slice,
                r.start,
                nesting == CommentNesting::Nested,
                diags,
            ),
            Raw::Int | Raw::Based => {
                let value = match parse_int_text(slice) {
                    Ok(v) => {
                        doubled_underscores(slice, span(r.start, r.end), diags);
                        v
                    }
                    Err(m) => {
                        diags.error("E005", span(r.start, r.end), m);
                        0
                    }
                };
                lit(LiteralValue::Int(value), None)
            }
            Raw::Real => {
                let value = parse_real_text(slice).unwrap_or_else(|m| {
                    diags.error("E005", span(r.start, r.end), m);
                    0.0
                });
                lit(LiteralValue::Real(value), None)
            }
            Raw::SString | Raw::DString => {
                let wide = raw == Raw::DString;
                let value =
                    as_file_bytes(string(file, slice, r.start, wide, diags), wide, encoding);
                lit(LiteralValue::String { value, wide }, None)
            }
            Raw::Direct => match direct(file, slice, r.start) {
                Ok(d) => Tok::Direct(Box::new(d)),
                // `w.%B1`: the member name `%B1`, decoded by sema (partial_access.rs).
                Err(_) if is_partial_access(text, r.start, slice) && is_part_number(slice) => {
                    Tok::Ident(slice.to_string())
                }
                Err(m) => {
                    let m = if is_partial_access(text, r.start, slice) {
                        format!(
                            "partial access `.{slice}` needs a size letter and a part number: \
                             `.%X3` (bit), `.%B1` (byte), `.%W0` (word), `.%D1` (double word), \
                             `.%L0` (long word)"
                        )
                    } else {
                        m
                    };
                    diags.error("E009", span(r.start, r.end), m);
                    Tok::Ident(String::from("_"))
                }
            },
            Raw::Assign => Tok::Assign,
            Raw::Arrow => Tok::Arrow,
            Raw::Colon => Tok::Colon,
            Raw::Semi => Tok::Semi,
            Raw::Comma => Tok::Comma,
            Raw::Dot => Tok::Dot,
            Raw::DotDot => Tok::DotDot,
            Raw::LParen => Tok::LParen,
            Raw::RParen => Tok::RParen,
            Raw::LBracket => Tok::LBracket,
            Raw::RBracket => Tok::RBracket,
            Raw::Plus => Tok::Plus,
            Raw::Minus => Tok::Minus,
            Raw::Star => Tok::Star,
            Raw::Power => Tok::Power,
            Raw::Slash => Tok::Slash,
            Raw::Amp => Tok::Amp,
            Raw::Eq => Tok::Eq,
            Raw::Ne => Tok::Ne,
            Raw::Lt => Tok::Lt,
            Raw::Le => Tok::Le,
            Raw::Gt => Tok::Gt,
            Raw::Ge => Tok::Ge,
            Raw::Bar => Tok::Bar,
            // Spanning lines, it ends an IL line as a comment does.
            Raw::EmbeddedC if embedded_c(span(r.start, r.end), slice, diags) => Tok::Eol,
            Raw::EmbeddedC => continue,
            Raw::Caret => Tok::Caret,
            Raw::AssignAttempt => Tok::AssignAttempt,
        };
        out.push((r.start, tok, r.end));
    }
    flush_bad(file, text, &mut bad_run, diags);
    crate::syntax::ref_words::merge(&mut out);
    // The guess above is low for dense code: give back what doubling
    // over-reserved (a large file's tokens live through the whole parse).
    out.shrink_to_fit();
    out
}

/// Reports a `{...}` pragma: named when other tools give it a meaning,
/// W001 otherwise, E010 when unterminated; nothing for one plcrun honours
/// (`qualified_only` or `strict` before a `TYPE`, `call_after_init` before
/// a METHOD or FUNCTION_BLOCK, `no_check` before a FUNCTION,
/// FUNCTION_BLOCK or PROGRAM, followed by `rest`). True when it
/// spans lines (it then ends an IL line, as a comment does).
fn pragma(at: Span, slice: &str, rest: &str, diags: &mut Diagnostics) -> bool {
    use super::qualified_only::{
        is_call_after_init, is_no_check, is_qualified_only, is_strict, method_or_block_follows,
        pou_follows, type_follows,
    };
    if (is_qualified_only(slice) || is_strict(slice)) && type_follows(rest) {
        // Honoured: the grammar finds it before the TYPE keyword.
    } else if is_call_after_init(slice) && method_or_block_follows(rest) {
        // Honoured: the method's constructor finds it before METHOD.
    } else if is_no_check(slice) && pou_follows(rest) {
        // Honoured: the POU's constructor finds it before its keyword.
    } else if slice.ends_with('}')
        && let Some((code, message)) = super::pragma_meaning::named(slice)
    {
        diags.warning(code, at, message);
    } else if slice.ends_with('}') {
        let shown: String = slice.chars().take(40).collect();
        let more = if shown.len() < slice.len() { "..." } else { "" };
        diags.warning("W001", at, format!("pragma `{shown}{more}` ignored"));
    } else {
        diags.error(
            "E010",
            Span::new(at.file, at.start as usize, at.start as usize + 1),
            "unterminated pragma: `{` has no closing `}`",
        );
    }
    slice.contains('\n')
}

/// Skips the `LIBRARY ... END_LIBRARY` list a CoDeSys 2.3 export ends
/// with (the libraries the project referenced, as free text) when `lexer`
/// has just read `LIBRARY` (at `word`) at the start of a line, with a W021
/// warning; true when it did.
fn library_list(
    lexer: &mut logos::Lexer<'_, Raw>,
    word: Span,
    text: &str,
    diags: &mut Diagnostics,
) -> bool {
    // Cheap tests first: this runs for every word.
    let start = word.start as usize;
    let rest = lexer.remainder();
    if lexer.slice() != "LIBRARY"
        || !(start == 0 || text[..start].ends_with('\n'))
        || !rest.starts_with(['\r', '\n'])
    {
        return false;
    }
    let Some(end) = rest.find("\nEND_LIBRARY") else {
        return false;
    };
    let end = end + "\nEND_LIBRARY".len();
    let first = rest
        .trim_start()
        .lines()
        .next()
        .unwrap_or("")
        .trim()
        .to_string();
    lexer.bump(end);
    diags.warning(
        "W021",
        word,
        format!("CoDeSys export's library list skipped (first: `{first}`): plcrun brings its own standard functions"),
    );
    true
}

/// Reports matiec's `{{ ... }}` at `span` (its text `slice`): a warning
/// that it is ignored, or an error when it has no closing `}}`. True when
/// it spans lines.
fn embedded_c(span: Span, slice: &str, diags: &mut Diagnostics) -> bool {
    if slice.len() >= 4 && slice.ends_with("}}") {
        let code = slice[2..slice.len() - 2].trim();
        let shown: String = code.chars().take(40).collect();
        let more = if shown.len() < code.len() { "..." } else { "" };
        diags.push(
            Diagnostic::warning(
                "W360",
                span,
                format!("embedded C code `{{{{ {shown}{more} }}}}` (a matiec pragma) ignored: it does not run"),
            )
            .with_note("plcrun runs IEC 61131-3 code only; write the effect in ST or as a host block"),
        );
    } else {
        let start = Span::new(span.file, span.start as usize, span.start as usize + 2);
        diags.error(
            "E020",
            start,
            "unterminated embedded-C pragma: `{{` has no closing `}}`",
        );
    }
    slice.contains('\n')
}

fn flush_bad(file: FileId, text: &str, run: &mut Option<(usize, usize)>, diags: &mut Diagnostics) {
    if let Some((s, e)) = run.take() {
        let shown: String = text.get(s..e).unwrap_or("?").chars().take(20).collect();
        diags.error(
            "E001",
            Span::new(file, s, e),
            format!("invalid character `{}` in source", shown.escape_debug()),
        );
    }
}

fn lit(value: LiteralValue, type_prefix: Option<Ident>) -> Tok {
    Tok::Lit(Box::new(Literal { value, type_prefix }))
}

/// A word: keyword, `TRUE`/`FALSE`, or identifier.
fn word(slice: &str) -> Tok {
    if slice.eq_ignore_ascii_case("TRUE") {
        return lit(LiteralValue::Bool(true), None);
    }
    if slice.eq_ignore_ascii_case("FALSE") {
        return lit(LiteralValue::Bool(false), None);
    }
    match Kw::lookup(slice) {
        Some(k) => Tok::Kw(k),
        None => Tok::Ident(slice.to_string()),
    }
}

/// Decodes a string literal token (with its quotes).
fn string(file: FileId, slice: &str, start: usize, wide: bool, diags: &mut Diagnostics) -> String {
    let quote = if wide { '"' } else { '\'' };
    let terminated = slice.len() >= 2 && slice.ends_with(quote) && closes(slice);
    let inner = if terminated {
        &slice[1..slice.len() - 1]
    } else {
        diags.error(
            "E003",
            Span::new(file, start, start + slice.len()),
            format!("unterminated string: missing closing {quote} before the end of the line"),
        );
        &slice[1..]
    };
    match decode_string(inner, wide) {
        Ok(s) => s,
        Err((s, e, m)) => {
            diags.error("E004", Span::new(file, start + 1 + s, start + 1 + e), m);
            String::new()
        }
    }
}

/// A STRING literal's characters as the bytes the file held: STRING is a
/// string of bytes, so `€` of a Windows-1252 file is byte 0x80 (as `'$80'`).
/// A WSTRING literal holds characters and is left as it is.
fn as_file_bytes(value: String, wide: bool, encoding: TextEncoding) -> String {
    if wide || encoding != TextEncoding::Windows1252 {
        return value;
    }
    value
        .chars()
        .map(|c| encoding.string_byte(c).map_or(c, char::from))
        .collect()
}

/// A TwinCAT LTIME literal beyond the signed range.
const UNSIGNED_LTIME: &str = "W022";

/// The 64 bits of an LTIME literal in 2^63 .. 2^64 - 1 ns, when `allowed`.
fn unsigned_ltime(body: &str, allowed: bool) -> Option<i64> {
    let wide = crate::value::literal::parse_duration_wide(body).ok()?;
    (allowed && (0..=u64::MAX as i128).contains(&wide)).then_some(wide as u64 as i64)
}

/// True when the final quote of `slice` is not escaped by `$` (counting
/// consecutive `$` signs).
fn closes(slice: &str) -> bool {
    let body = &slice.as_bytes()[1..slice.len() - 1];
    let dollars = body.iter().rev().take_while(|c| **c == b'$').count();
    dollars % 2 == 0
}

/// Decodes `PREFIX#body`.
///
/// `twincat`: the text is a TwinCAT object's (lexed with nested comments,
/// [`lex_codesys`]), where an LTIME reaches 2^64 - 1 ns.
fn typed(file: FileId, slice: &str, start: usize, twincat: bool, diags: &mut Diagnostics) -> Tok {
    let hash = slice.find('#').unwrap_or(slice.len());
    let prefix = &slice[..hash];
    let body = slice.get(hash + 1..).unwrap_or("");
    let whole = Span::new(file, start, start + slice.len());
    let prefix_ident = Ident {
        name: prefix.to_string(),
        span: Span::new(file, start, start + hash),
    };
    let fail = |diags: &mut Diagnostics, code, msg: String| {
        diags.error(code, whole, msg);
    };
    let result = match prefix_kind(prefix) {
        PrefixKind::Duration { long } => match parse_duration_body(body) {
            Ok(nanos) => Ok(LiteralValue::Duration { nanos, long }),
            Err(m) => match unsigned_ltime(body, long && twincat) {
                Some(nanos) => {
                    diags.warning(
                        UNSIGNED_LTIME,
                        whole,
                        "an LTIME beyond 2^63 - 1 ns (TwinCAT's LTIME is unsigned): plcrun's LTIME is signed, it holds these 64 bits, and compares and prints them as a negative duration",
                    );
                    Ok(LiteralValue::Duration { nanos, long })
                }
                None => Err(("E006", m)),
            },
        },
        PrefixKind::Date { long } => match parse_date_body(body) {
            Ok(nanos) => Ok(LiteralValue::Date { nanos, long }),
            Err(m) => Err(("E007", m)),
        },
        PrefixKind::TimeOfDay { long } => match parse_tod_body(body) {
            Ok(nanos) => Ok(LiteralValue::TimeOfDay { nanos, long }),
            Err(m) => Err(("E007", m)),
        },
        PrefixKind::DateTime { long } => match parse_dt_body(body) {
            Ok(nanos) => Ok(LiteralValue::DateTime { nanos, long }),
            Err(m) => Err(("E007", m)),
        },
        PrefixKind::Type => match decode_typed_body(prefix, body) {
            Ok(LiteralValue::EnumValue(mut id)) => {
                id.span = Span::new(file, start + hash + 1, start + slice.len());
                return lit(LiteralValue::EnumValue(id), Some(prefix_ident));
            }
            Ok(v) => return lit(v, Some(prefix_ident)),
            Err(m) => Err(("E008", m)),
        },
    };
    match result {
        Ok(v) => lit(v, None),
        Err((code, m)) => {
            let m = if body.is_empty() {
                format!("missing value after `{prefix}#`")
            } else {
                m
            };
            fail(diags, code, m);
            lit(LiteralValue::Int(0), None)
        }
    }
}

/// True when the direct-address text `slice` at `start` follows a `.` and
/// names a size (`b.%X3`, `w.%B1`): the edition-3 partial access form.
fn is_partial_access(text: &str, start: usize, slice: &str) -> bool {
    let size = slice[1..].chars().next().map(|c| c.to_ascii_uppercase());
    text[..start].ends_with('.') && matches!(size, Some('X' | 'B' | 'W' | 'D' | 'L'))
}

/// True for `%X3`, `%B1`, `%W0`, `%D1`, `%L0`: a size letter and a part
/// number, nothing else.
fn is_part_number(slice: &str) -> bool {
    let digits = &slice[2.min(slice.len())..];
    slice.len() > 2 && digits.bytes().all(|b| b.is_ascii_digit())
}

/// Decodes `%IX0.3`, `%QW4`, `%I0.0.0.0.1`, `%MD12`, `%I*`.
pub fn direct(file: FileId, slice: &str, start: usize) -> Result<DirectAddress, String> {
    let rest = &slice[1..];
    let letters: String = rest
        .chars()
        .take_while(|c| c.is_ascii_alphabetic())
        .collect::<String>()
        .to_ascii_uppercase();
    let tail = &rest[letters.len()..];
    let mut chars = letters.chars();
    let area = match chars.next() {
        Some('I') => Area::Input,
        Some('Q') => Area::Output,
        Some('M') => Area::Memory,
        _ => {
            return Err(format!(
                "direct address `{slice}` must start with %I, %Q or %M"
            ));
        }
    };
    let size = match chars.next() {
        None => None,
        Some('X') => Some(AddrSize::Bit),
        Some('B') => Some(AddrSize::Byte),
        Some('W') => Some(AddrSize::Word),
        Some('D') => Some(AddrSize::Dword),
        Some('L') => Some(AddrSize::Lword),
        Some(c) => {
            return Err(format!(
                "unknown size `{c}` in direct address `{slice}` (use X, B, W, D or L)"
            ));
        }
    };
    if chars.next().is_some() {
        return Err(format!("malformed direct address `{slice}`"));
    }
    let fields = if tail == "*" {
        Vec::new()
    } else if tail.is_empty() {
        return Err(format!("direct address `{slice}` has no address fields"));
    } else {
        tail.split('.')
            .map(|f| {
                let f: String = f.chars().filter(|c| *c != '_').collect();
                f.parse::<u64>()
                    .map_err(|_| format!("address field `{f}` of `{slice}` is not a valid number"))
            })
            .collect::<Result<Vec<u64>, String>>()?
    };
    Ok(DirectAddress {
        area,
        size: size.unwrap_or(AddrSize::Bit),
        explicit_size: size.is_some(),
        fields,
        text: slice.to_string(),
        span: Span::new(file, start, start + slice.len()),
    })
}

/// `tokens` without those whose flag in `drop` is set (the token passes
/// that remove CODESYS forms mark, then drop in one go).
pub fn without_marked(tokens: Vec<Spanned>, drop: Vec<bool>) -> Vec<Spanned> {
    tokens
        .into_iter()
        .zip(drop)
        .filter(|(_, d)| !d)
        .map(|(t, _)| t)
        .collect()
}

/// W349 for an integer literal with runs of underscores between its
/// digits (`16#7f_ff_ff_ff__ff_ff_ff_ff`): IEC allows single ones only,
/// CODESYS and TwinCAT accept more, and so does the literal reader
/// (`parse_int_text`); `--strict` refuses it.
fn doubled_underscores(slice: &str, at: Span, diags: &mut Diagnostics) {
    if slice.contains("__") {
        diags.warning(
            "W349",
            at,
            format!("consecutive `_` in `{slice}` (a CODESYS extension: IEC separates digits with single underscores)"),
        );
    }
}

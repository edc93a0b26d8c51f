//! Front-end: lexing and parsing of IL, ST and SFC source into the AST.
//!
//! Pipeline: [`lexer`] (logos scanner + literal decoding) → [`il_lines`] (IL
//! line orientation) → [`parser`] (lalrpop grammar, error recovery) → [`ast`].

pub mod assign_attempt;
pub mod ast;
pub mod chain_assign;
mod codesys_spellings;
pub mod config_path;
pub mod construct;
pub mod depth;
mod empty_args;
mod empty_declarations;
mod empty_init_call;
mod header_semicolon;
pub mod il_lines;
pub mod init_arguments;
pub mod lexer;
pub mod literal;
mod method_bodies;
mod method_names;
pub mod oop;
pub mod oop_class;
pub mod oop_property;
pub mod oop_var_access;
pub mod parser;
pub mod plcopen;
pub mod pragma_meaning;
pub mod qualified_only;
pub mod recovery;
pub mod ref_words;
pub mod repair;
pub mod s7;
mod set_reset_assign;
mod soft_keywords;
pub mod token;
pub mod try_stmt;
pub mod twincat;

use crate::diagnostics::{Diagnostics, Severity};
use crate::source::encoding::TextEncoding;
use crate::source::{FileId, SourceFile};
use ast::{Literal, LiteralValue};
use token::Tok;

/// Parses one file. Never panics, on any input. Reports every syntax error it can (recover, don't stop at the first).
pub fn parse(file: FileId, text: &str, diags: &mut Diagnostics) -> ast::CompilationUnit {
    parse_in(file, text, TextEncoding::Utf8, diags)
}

/// [`parse`] of text read from a file in `encoding` (which decides the
/// bytes of its STRING literals).
fn parse_in(
    file: FileId,
    text: &str,
    encoding: TextEncoding,
    diags: &mut Diagnostics,
) -> ast::CompilationUnit {
    if twincat::is_twincat(text) {
        return twincat::parse(file, text, diags);
    }
    if twincat::type_description::is_type_description(text) {
        return twincat::type_description::parse(file, text, diags);
    }
    if plcopen::is_plcopen(text) {
        return plcopen::parse(file, text, diags);
    }
    let tokens_of = |diags: &mut Diagnostics| {
        let tokens = lexer::lex_in(file, text, encoding, diags);
        textual_passes(file, text, tokens, diags)
    };
    repair::parse_repairing(file, text, &tokens_of, diags)
}

/// The token passes between the lexer and the grammar that make the
/// CODESYS spellings and soft keywords of textual sources parse (method
/// names that are keywords, `GET`/`SET` accessors, `FUNCTIONBLOCK`, a `;`
/// after a header); readers that emit tokens from another format run them
/// too.
pub(crate) fn textual_passes(
    file: FileId,
    text: &str,
    tokens: Vec<lexer::Spanned>,
    diags: &mut Diagnostics,
) -> Vec<lexer::Spanned> {
    let tokens = method_names::method_names(file, text, tokens, diags);
    let tokens = soft_keywords::names_from_keywords(file, text, tokens, diags);
    let tokens = oop_property::accessor_words(tokens);
    let tokens = codesys_spellings::iec_keywords(file, tokens, diags);
    let tokens = set_reset_assign::set_reset_assignments(tokens);
    let tokens = empty_args::drop_empty_arguments(tokens);
    let tokens = empty_init_call::drop_empty_init_calls(tokens);
    let tokens = empty_declarations::drop_empty_declarations(file, tokens, diags);
    let tokens = init_arguments::mark_init_arguments(tokens);
    header_semicolon::drop_header_semicolons(tokens)
}

/// Parses one file named `name`: S7-200 STL when [`s7::recognise`] says
/// so (a `.awl`/`.stl` file, or S7-200 content), IEC text otherwise.
pub fn parse_file(
    file: FileId,
    name: &str,
    text: &str,
    diags: &mut Diagnostics,
) -> ast::CompilationUnit {
    if s7::recognise(name, text) {
        return s7::parse(file, text, diags);
    }
    parse(file, text, diags)
}

/// [`parse_file`] of a loaded source file, in the encoding it was read in.
pub fn parse_source(
    file: FileId,
    source: &SourceFile,
    diags: &mut Diagnostics,
) -> ast::CompilationUnit {
    if s7::recognise(&source.name, &source.text) {
        return s7::parse(file, &source.text, diags);
    }
    parse_in(file, &source.text, source.encoding(), diags)
}

/// Parses one standalone IEC literal as written on a command line / stimulus cell:
/// `TRUE`, `FALSE`, `1`, `-5`, `16#FF`, `INT#-3`, `1.5`, `-2.5E3`, `T#1s500ms`, `TIME#-2ms`, `LT#1ns`, `D#2024-01-31`, `TOD#12:00:00.5`, `DT#2024-01-31-12:00:00`, `'text'`, `"wide"`, `Color#Red`.
pub fn parse_literal(text: &str) -> Result<ast::Literal, String> {
    let text = text.trim();
    let mut diags = Diagnostics::new();
    let tokens: Vec<Tok> = lexer::lex(FileId(0), text, &mut diags)
        .into_iter()
        .map(|t| t.1)
        .filter(|t| *t != Tok::Eol)
        .collect();
    if let Some(d) = diags.iter().find(|d| d.severity == Severity::Error) {
        return Err(d.message.clone());
    }
    let (sign, rest) = match tokens.split_first() {
        Some((Tok::Minus, rest)) => (-1, rest),
        Some((Tok::Plus, rest)) => (1, rest),
        _ => (0, tokens.as_slice()),
    };
    let lit = match rest {
        [Tok::Lit(lit)] => (**lit).clone(),
        [] => return Err(format!("`{text}` is not a literal: it is empty")),
        _ => return Err(format!("`{text}` is not a single IEC literal")),
    };
    if sign == 0 {
        return Ok(lit);
    }
    let negate = sign < 0;
    let value = match (lit.type_prefix.is_some(), lit.value) {
        (false, LiteralValue::Int(v)) => LiteralValue::Int(if negate { -v } else { v }),
        (false, LiteralValue::Real(v)) => LiteralValue::Real(if negate { -v } else { v }),
        _ => {
            return Err(format!(
                "`{text}`: a sign is only allowed before a plain number"
            ));
        }
    };
    Ok(Literal {
        value,
        type_prefix: None,
    })
}

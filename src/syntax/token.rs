//! Tokens: the raw token classes recognised by the `logos` scanner, and the
//! decoded [`Tok`] values the grammar consumes.
//!
//! The scanner ([`Raw`]) only delimits tokens; [`crate::syntax::lexer`]
//! decodes literals, classifies keywords and reports malformed input.

use crate::syntax::ast::{DirectAddress, IlOperator, Literal};
use crate::value::text::numeric_len;
use logos::{Lexer, Logos};
use std::fmt;

/// Raw token classes, as delimited by the scanner. Several classes have
/// callbacks that consume their body by hand (comments, strings, typed and
/// based literals, direct addresses) so that malformed text stays one token
/// and can be reported precisely.
#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq)]
#[logos(skip r"[ \t\r\u{0c}\u{feff}]+")]
#[logos(extras = CommentNesting)]
pub enum Raw {
    /// A line break.
    #[token("\n")]
    Newline,
    /// `(* ... *)`; the body is consumed by the callback.
    #[token("(*", block_comment)]
    BlockComment,
    /// `/* ... */` (edition 3); the body is consumed by the callback.
    #[token("/*", slash_comment)]
    SlashComment,
    /// `// ...` to the end of the line.
    #[regex(r"//[^\n]*", allow_greedy = true)]
    LineComment,
    /// `{ ... }` pragma.
    #[token("{", pragma)]
    Pragma,
    /// An identifier or keyword.
    #[regex("[A-Za-z_][A-Za-z0-9_]*")]
    Word,
    /// `PREFIX#body`: typed, time and date literals; body consumed by the callback.
    #[regex("[A-Za-z_][A-Za-z0-9_]*#", typed_body)]
    Typed,
    /// A decimal integer.
    #[regex("[0-9][0-9_]*")]
    Int,
    /// `16#FF`, `2#1010`, `8#17`.
    #[regex("[0-9][0-9_]*#", based_body)]
    Based,
    /// `1.5`, `1.5E-3`, `1e10`.
    #[regex(r"[0-9][0-9_]*\.[0-9][0-9_]*([eE][+-]?[0-9][0-9_]*)?")]
    #[regex(r"[0-9][0-9_]*[eE][+-]?[0-9][0-9_]*")]
    Real,
    /// `'...'` string (STRING); body consumed by the callback.
    #[token("'", single_quoted)]
    SString,
    /// `"..."` string (WSTRING); body consumed by the callback.
    #[token("\"", double_quoted)]
    DString,
    /// `%IX0.3` and friends; body consumed by the callback.
    #[token("%", direct_body)]
    Direct,
    /// `:=`
    #[token(":=")]
    Assign,
    /// `=>`
    #[token("=>")]
    Arrow,
    /// `:`
    #[token(":")]
    Colon,
    /// `;`
    #[token(";")]
    Semi,
    /// `,`
    #[token(",")]
    Comma,
    /// `.`
    #[token(".")]
    Dot,
    /// `..`
    #[token("..")]
    DotDot,
    /// `(`
    #[token("(")]
    LParen,
    /// `)`
    #[token(")")]
    RParen,
    /// `[`
    #[token("[")]
    LBracket,
    /// `]`
    #[token("]")]
    RBracket,
    /// `+`
    #[token("+")]
    Plus,
    /// `-`
    #[token("-")]
    Minus,
    /// `*`
    #[token("*")]
    Star,
    /// `**`
    #[token("**")]
    Power,
    /// `/`
    #[token("/")]
    Slash,
    /// `&`
    #[token("&")]
    Amp,
    /// `=`
    #[token("=")]
    Eq,
    /// `<>`
    #[token("<>")]
    Ne,
    /// `<`
    #[token("<")]
    Lt,
    /// `<=`
    #[token("<=")]
    Le,
    /// `>`
    #[token(">")]
    Gt,
    /// `>=`
    #[token(">=")]
    Ge,
    /// `|` (Moeller CAL output list separator).
    #[token("|")]
    Bar,
    // --- source: matiec's embedded C ---
    /// `{{ ... }}`: matiec's embedded-C pragma, up to the first `}}`; the
    /// body is consumed by the callback.
    #[token("{{", embedded_c)]
    EmbeddedC,
    /// `^` (postfix dereference).
    #[token("^")]
    Caret,
    /// `THIS^` (edition 3: the current instance), spaces allowed before `^`.
    #[regex(r"[Tt][Hh][Ii][Ss][ \t]*\^")]
    ThisDeref,
    /// `SUPER^` (edition 3: the parent FB's view of the current instance).
    #[regex(r"[Ss][Uu][Pp][Ee][Rr][ \t]*\^")]
    SuperDeref,
    /// `?=` (assignment attempt, edition 3)
    #[token("?=")]
    AssignAttempt,
}

/// Whether `(* ... *)` comments nest: not in IEC text (the first `*)`
/// ends the comment), but in CODESYS and TwinCAT code, where
/// `(* a (* b *) c *)` is one comment (code commented out with its own
/// comments inside).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum CommentNesting {
    /// The first `*)` closes the comment (IEC 61131-3).
    #[default]
    Flat,
    /// Each `(*` inside opens a level that its `*)` closes (CODESYS).
    Nested,
}

/// Consumes a block comment body up to and including the `*)` that closes
/// it (the first one, or the matching one when comments nest), or to the
/// end of input when unterminated.
fn block_comment(lex: &mut Lexer<Raw>) {
    let rest = lex.remainder();
    let n = match lex.extras {
        CommentNesting::Flat => rest.find("*)").map(|i| i + 2),
        CommentNesting::Nested => nested_comment_end(rest),
    };
    lex.bump(n.unwrap_or(rest.len()));
}

/// The length of a nested comment's body and closing `*)` in `rest` (the
/// text after the opening `(*`), or `None` when it is not closed.
fn nested_comment_end(rest: &str) -> Option<usize> {
    let bytes = rest.as_bytes();
    let mut depth = 1usize;
    let mut i = 0;
    while i + 1 < bytes.len() {
        match (bytes[i], bytes[i + 1]) {
            (b'(', b'*') => {
                depth += 1;
                i += 2;
            }
            (b'*', b')') => {
                depth -= 1;
                i += 2;
                if depth == 0 {
                    return Some(i);
                }
            }
            _ => i += 1,
        }
    }
    None
}

/// Consumes an edition-3 `/* ... */` comment body up to and including
/// `*/` (not nested, as in the standard).
fn slash_comment(lex: &mut Lexer<Raw>) {
    let rest = lex.remainder();
    let n = rest.find("*/").map(|i| i + 2).unwrap_or(rest.len());
    lex.bump(n);
}

/// Consumes a pragma body up to and including `}`.
fn pragma(lex: &mut Lexer<Raw>) {
    let rest = lex.remainder();
    let n = rest.find('}').map(|i| i + 1).unwrap_or(rest.len());
    lex.bump(n);
}

/// Consumes an embedded-C body up to and including `}}` (it may hold
/// anything else, single braces and line breaks included), or to the end
/// of input when unterminated.
fn embedded_c(lex: &mut Lexer<Raw>) {
    let rest = lex.remainder();
    let n = rest.find("}}").map(|i| i + 2).unwrap_or(rest.len());
    lex.bump(n);
}

/// Consumes a quoted string body up to the closing quote; stops before a
/// line break when unterminated. `$` escapes the next character.
fn quoted(lex: &mut Lexer<Raw>, quote: u8) {
    let rest = lex.remainder().as_bytes();
    let mut i = 0;
    while i < rest.len() {
        match rest[i] {
            b'\n' => break,
            b'$' if i + 1 < rest.len() && rest[i + 1] != b'\n' => i += 2,
            c if c == quote => {
                i += 1;
                break;
            }
            _ => i += 1,
        }
    }
    let i = i.min(rest.len());
    // Never split a UTF-8 sequence (a `$` followed by a multibyte char).
    let text = lex.remainder();
    let mut n = i;
    while !text.is_char_boundary(n) {
        n += 1;
    }
    lex.bump(n);
}

fn single_quoted(lex: &mut Lexer<Raw>) {
    quoted(lex, b'\'')
}

fn double_quoted(lex: &mut Lexer<Raw>) {
    quoted(lex, b'"')
}

/// Length of the run of bytes at the start of `s` satisfying `f`.
fn run(s: &[u8], f: impl Fn(u8) -> bool) -> usize {
    s.iter().position(|&c| !f(c)).unwrap_or(s.len())
}

fn is_word_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// Consumes the digits of a based integer (`16#` already matched).
fn based_body(lex: &mut Lexer<Raw>) {
    let n = run(lex.remainder().as_bytes(), is_word_byte);
    lex.bump(n);
}

/// Consumes characters from `allowed`, where the separators in `seps` are
/// only taken when a digit follows them.
fn date_like_len(s: &[u8], seps: &[u8]) -> usize {
    let mut i = 0;
    while i < s.len() {
        let c = s[i];
        let sep_then_digit = seps.contains(&c) && s.get(i + 1).is_some_and(u8::is_ascii_digit);
        if c.is_ascii_digit() || c == b'_' || sep_then_digit {
            i += 1;
        } else {
            break;
        }
    }
    i
}

/// What kind of body a literal prefix (`T`, `DATE`, `INT`, ...) takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PrefixKind {
    /// `T#`, `TIME#`, `LT#`, `LTIME#`.
    Duration {
        /// `LT`/`LTIME`.
        long: bool,
    },
    /// `D#`, `DATE#`, `LD#`, `LDATE#`.
    Date {
        /// `LD`/`LDATE`.
        long: bool,
    },
    /// `TOD#`, `TIME_OF_DAY#`, `LTOD#`, `LTIME_OF_DAY#`.
    TimeOfDay {
        /// `LTOD`.
        long: bool,
    },
    /// `DT#`, `DATE_AND_TIME#`, `LDT#`, `LDATE_AND_TIME#`.
    DateTime {
        /// `LDT`.
        long: bool,
    },
    /// Any other prefix: a type name (`INT#`, `REAL#`, `Color#`).
    Type,
}

/// Classifies a literal prefix (case-insensitive, without `#`).
pub fn prefix_kind(prefix: &str) -> PrefixKind {
    match prefix.to_ascii_uppercase().as_str() {
        "T" | "TIME" => PrefixKind::Duration { long: false },
        "LT" | "LTIME" => PrefixKind::Duration { long: true },
        "D" | "DATE" => PrefixKind::Date { long: false },
        "LD" | "LDATE" => PrefixKind::Date { long: true },
        "TOD" | "TIME_OF_DAY" => PrefixKind::TimeOfDay { long: false },
        "LTOD" | "LTIME_OF_DAY" => PrefixKind::TimeOfDay { long: true },
        "DT" | "DATE_AND_TIME" => PrefixKind::DateTime { long: false },
        "LDT" | "LDATE_AND_TIME" => PrefixKind::DateTime { long: true },
        _ => PrefixKind::Type,
    }
}

/// Consumes the body of a `PREFIX#` literal according to the prefix.
fn typed_body(lex: &mut Lexer<Raw>) {
    let prefix = lex.slice().trim_end_matches('#');
    let s = lex.remainder().as_bytes();
    let n = match prefix_kind(prefix) {
        PrefixKind::Duration { .. } => {
            let sign = usize::from(matches!(s.first(), Some(b'+' | b'-')));
            sign + run(&s[sign..], |c| is_word_byte(c) || c == b'.')
        }
        PrefixKind::Date { .. } => date_like_len(s, b"-"),
        PrefixKind::TimeOfDay { .. } => date_like_len(s, b":."),
        PrefixKind::DateTime { .. } => date_like_len(s, b"-:."),
        PrefixKind::Type => match s.first() {
            Some(b'\'') => {
                lex.bump(1);
                return quoted(lex, b'\'');
            }
            Some(b'"') => {
                lex.bump(1);
                return quoted(lex, b'"');
            }
            _ => numeric_len(s),
        },
    };
    lex.bump(n);
}

/// Consumes a direct address after `%`: area and size letters, then
/// dot-separated fields or `*`.
fn direct_body(lex: &mut Lexer<Raw>) {
    let s = lex.remainder().as_bytes();
    let mut i = run(s, |c| c.is_ascii_alphabetic());
    if s.get(i) == Some(&b'*') {
        i += 1;
    } else {
        i += date_like_len(&s[i..], b".");
    }
    lex.bump(i);
}

/// Reserved words (case-insensitive).
#[allow(missing_docs)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Kw {
    Program,
    EndProgram,
    Function,
    EndFunction,
    FunctionBlock,
    EndFunctionBlock,
    Var,
    VarInput,
    VarOutput,
    VarInOut,
    VarExternal,
    VarGlobal,
    VarTemp,
    VarStat,
    VarInst,
    EndVar,
    Constant,
    Retain,
    NonRetain,
    Persistent,
    At,
    Type,
    EndType,
    Struct,
    EndStruct,
    Union,
    EndUnion,
    Array,
    Of,
    String,
    WString,
    Configuration,
    EndConfiguration,
    Resource,
    EndResource,
    On,
    Task,
    With,
    If,
    Then,
    Elsif,
    Else,
    EndIf,
    Case,
    EndCase,
    For,
    To,
    By,
    Do,
    EndFor,
    While,
    EndWhile,
    Repeat,
    Until,
    EndRepeat,
    /// `__TRY` (CODESYS, TwinCAT 3: exception handling).
    Try,
    /// `__CATCH`.
    Catch,
    /// `__FINALLY`.
    Finally,
    /// `__ENDTRY`.
    EndTry,
    Exit,
    Continue,
    Return,
    Not,
    And,
    Or,
    /// `AND_THEN` (CODESYS: short-circuit AND).
    AndThen,
    /// `OR_ELSE` (CODESYS: short-circuit OR).
    OrElse,
    Xor,
    Mod,
    InitialStep,
    Step,
    EndStep,
    Transition,
    EndTransition,
    From,
    Action,
    EndAction,
    VarConfig,
    Method,
    EndMethod,
    Interface,
    EndInterface,
    Extends,
    Implements,
    Abstract,
    Final,
    Public,
    Private,
    Protected,
    Internal,
    /// `THIS^` (one token: the word and the caret).
    ThisDeref,
    /// `SUPER^` (one token: the word and the caret).
    SuperDeref,
    Property,
    EndProperty,
    /// `GET` of a property (a name elsewhere: see `syntax::oop_property`).
    Get,
    EndGet,
    /// `SET` of a property (a name elsewhere: see `syntax::oop_property`).
    Set,
    EndSet,
    Class,
    EndClass,
}

/// Every keyword with its spelling.
pub const KEYWORDS: [(&str, Kw); 98] = [
    ("PROGRAM", Kw::Program),
    ("END_PROGRAM", Kw::EndProgram),
    ("FUNCTION", Kw::Function),
    ("END_FUNCTION", Kw::EndFunction),
    ("FUNCTION_BLOCK", Kw::FunctionBlock),
    ("END_FUNCTION_BLOCK", Kw::EndFunctionBlock),
    ("VAR", Kw::Var),
    ("VAR_INPUT", Kw::VarInput),
    ("VAR_OUTPUT", Kw::VarOutput),
    ("VAR_IN_OUT", Kw::VarInOut),
    ("VAR_EXTERNAL", Kw::VarExternal),
    ("VAR_GLOBAL", Kw::VarGlobal),
    ("VAR_TEMP", Kw::VarTemp),
    ("VAR_INST", Kw::VarInst),
    ("VAR_STAT", Kw::VarStat),
    ("END_VAR", Kw::EndVar),
    ("CONSTANT", Kw::Constant),
    ("RETAIN", Kw::Retain),
    ("NON_RETAIN", Kw::NonRetain),
    ("PERSISTENT", Kw::Persistent),
    ("AT", Kw::At),
    ("TYPE", Kw::Type),
    ("END_TYPE", Kw::EndType),
    ("STRUCT", Kw::Struct),
    ("END_STRUCT", Kw::EndStruct),
    ("UNION", Kw::Union),
    ("END_UNION", Kw::EndUnion),
    ("ARRAY", Kw::Array),
    ("OF", Kw::Of),
    ("STRING", Kw::String),
    ("WSTRING", Kw::WString),
    ("CONFIGURATION", Kw::Configuration),
    ("END_CONFIGURATION", Kw::EndConfiguration),
    ("RESOURCE", Kw::Resource),
    ("END_RESOURCE", Kw::EndResource),
    ("ON", Kw::On),
    ("TASK", Kw::Task),
    ("WITH", Kw::With),
    ("IF", Kw::If),
    ("THEN", Kw::Then),
    ("ELSIF", Kw::Elsif),
    ("ELSE", Kw::Else),
    ("END_IF", Kw::EndIf),
    ("CASE", Kw::Case),
    ("END_CASE", Kw::EndCase),
    ("FOR", Kw::For),
    ("TO", Kw::To),
    ("BY", Kw::By),
    ("DO", Kw::Do),
    ("END_FOR", Kw::EndFor),
    ("WHILE", Kw::While),
    ("END_WHILE", Kw::EndWhile),
    ("REPEAT", Kw::Repeat),
    ("UNTIL", Kw::Until),
    ("END_REPEAT", Kw::EndRepeat),
    ("__TRY", Kw::Try),
    ("__CATCH", Kw::Catch),
    ("__FINALLY", Kw::Finally),
    ("__ENDTRY", Kw::EndTry),
    ("EXIT", Kw::Exit),
    ("CONTINUE", Kw::Continue),
    ("RETURN", Kw::Return),
    ("NOT", Kw::Not),
    ("AND", Kw::And),
    ("OR", Kw::Or),
    ("AND_THEN", Kw::AndThen),
    ("OR_ELSE", Kw::OrElse),
    ("XOR", Kw::Xor),
    ("MOD", Kw::Mod),
    ("INITIAL_STEP", Kw::InitialStep),
    ("STEP", Kw::Step),
    ("END_STEP", Kw::EndStep),
    ("TRANSITION", Kw::Transition),
    ("END_TRANSITION", Kw::EndTransition),
    ("FROM", Kw::From),
    ("ACTION", Kw::Action),
    ("END_ACTION", Kw::EndAction),
    ("VAR_CONFIG", Kw::VarConfig),
    ("METHOD", Kw::Method),
    ("END_METHOD", Kw::EndMethod),
    ("INTERFACE", Kw::Interface),
    ("END_INTERFACE", Kw::EndInterface),
    ("EXTENDS", Kw::Extends),
    ("IMPLEMENTS", Kw::Implements),
    ("ABSTRACT", Kw::Abstract),
    ("FINAL", Kw::Final),
    ("PUBLIC", Kw::Public),
    ("PRIVATE", Kw::Private),
    ("PROTECTED", Kw::Protected),
    ("INTERNAL", Kw::Internal),
    ("THIS^", Kw::ThisDeref),
    ("SUPER^", Kw::SuperDeref),
    ("PROPERTY", Kw::Property),
    ("END_PROPERTY", Kw::EndProperty),
    ("END_GET", Kw::EndGet),
    ("END_SET", Kw::EndSet),
    ("CLASS", Kw::Class),
    ("END_CLASS", Kw::EndClass),
];

impl Kw {
    /// Looks a word up case-insensitively.
    pub fn lookup(word: &str) -> Option<Kw> {
        if word.len() > 18 {
            return None;
        }
        let upper = word.to_ascii_uppercase();
        KEYWORDS.iter().find(|(s, _)| *s == upper).map(|(_, k)| *k)
    }

    /// The keyword as written in the standard.
    pub fn as_str(self) -> &'static str {
        // Not in the table: the lexer never makes them from a word.
        match self {
            Kw::Get => return "GET",
            Kw::Set => return "SET",
            _ => {}
        }
        KEYWORDS
            .iter()
            .find(|(_, k)| *k == self)
            .map(|(s, _)| *s)
            .unwrap_or("?")
    }
}

/// An IL operator with its `N` modifier (`ANDN` = `And`, negate).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IlOpCode {
    /// The operator.
    pub op: IlOperator,
    /// `N` modifier given.
    pub negate: bool,
}

/// A decoded token, as handed to the grammar. `Il*` variants only appear
/// inside Instruction List bodies, where [`crate::syntax::il_lines`] retags the
/// first word of each line.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq)]
pub enum Tok {
    /// An identifier (never a keyword).
    Ident(String),
    /// A keyword.
    Kw(Kw),
    /// A decoded literal.
    Lit(Box<Literal>),
    /// A direct address.
    Direct(Box<DirectAddress>),
    Assign,
    Arrow,
    Colon,
    Semi,
    Comma,
    Dot,
    DotDot,
    LParen,
    RParen,
    LBracket,
    RBracket,
    Plus,
    Minus,
    Star,
    Power,
    Slash,
    Amp,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Bar,
    Caret,
    /// `REF_TO` where a type is written.
    RefTo,
    /// `POINTER TO` where a type is written.
    PointerTo,
    /// `REFERENCE TO` where a type is written.
    ReferenceTo,
    /// `REF=` after a variable (CODESYS reference binding).
    RefAssign,
    /// End of an IL line.
    Eol,
    /// `name` of `name:` at the start of an IL line.
    IlLabel(String),
    /// `LD`, `ANDN`, `&`, `ST`...
    IlOp(IlOpCode),
    /// `JMP`, `JMPC`, `JMPCN` (condition as in [`crate::syntax::ast::IlInstrKind::Jump`]).
    IlJmp(Option<bool>),
    /// `CAL`, `CALC`, `CALCN`.
    IlCal(Option<bool>),
    /// `RET`, `RETC`, `RETCN`.
    IlRet(Option<bool>),
    /// FB input operator of IEC Table 53 (`S1`, `CLK`, `PT`...).
    IlFbIn(String),
    /// Any other word in operator position: a function call.
    IlFun(String),
    /// `?=`: the assignment attempt (edition 3).
    AssignAttempt,
    /// The `(` of an instance's FB_init arguments in a declaration
    /// (`fb : FB_X(a := 1);`), told from a subrange's or an enumeration's
    /// by [`crate::syntax::init_arguments`].
    InitArgsOpen,
    /// The `[` that opens one list of FB_init arguments per element of an
    /// array of instances (`a : ARRAY[1..2] OF FB_X[(1), (2)];`).
    InitArgsArray,
}

impl fmt::Display for Tok {
    /// Describes the token for messages: "`END_IF`", "identifier `x`".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = |f: &mut fmt::Formatter<'_>, s: &str| write!(f, "`{s}`");
        match self {
            Tok::Ident(s) => write!(f, "identifier `{s}`"),
            Tok::Kw(k) => p(f, k.as_str()),
            Tok::Lit(_) => write!(f, "a literal"),
            Tok::Direct(d) => write!(f, "direct address `{}`", d.text),
            Tok::Assign => p(f, ":="),
            Tok::Arrow => p(f, "=>"),
            Tok::Colon => p(f, ":"),
            Tok::Semi => p(f, ";"),
            Tok::Comma => p(f, ","),
            Tok::Dot => p(f, "."),
            Tok::DotDot => p(f, ".."),
            Tok::LParen | Tok::InitArgsOpen => p(f, "("),
            Tok::InitArgsArray => p(f, "["),
            Tok::RParen => p(f, ")"),
            Tok::LBracket => p(f, "["),
            Tok::RBracket => p(f, "]"),
            Tok::Plus => p(f, "+"),
            Tok::Minus => p(f, "-"),
            Tok::Star => p(f, "*"),
            Tok::Power => p(f, "**"),
            Tok::Slash => p(f, "/"),
            Tok::Amp => p(f, "&"),
            Tok::Eq => p(f, "="),
            Tok::Ne => p(f, "<>"),
            Tok::Lt => p(f, "<"),
            Tok::Le => p(f, "<="),
            Tok::Gt => p(f, ">"),
            Tok::Ge => p(f, ">="),
            Tok::Bar => p(f, "|"),
            Tok::Caret => p(f, "^"),
            Tok::RefTo => p(f, "REF_TO"),
            Tok::PointerTo => p(f, "POINTER TO"),
            Tok::ReferenceTo => p(f, "REFERENCE TO"),
            Tok::RefAssign => p(f, "REF="),
            Tok::AssignAttempt => p(f, "?="),
            Tok::Eol => write!(f, "end of line"),
            Tok::IlLabel(s) => write!(f, "label `{s}`"),
            Tok::IlOp(_) | Tok::IlJmp(_) | Tok::IlCal(_) | Tok::IlRet(_) => {
                write!(f, "an IL operator")
            }
            Tok::IlFbIn(s) | Tok::IlFun(s) => write!(f, "`{s}`"),
        }
    }
}

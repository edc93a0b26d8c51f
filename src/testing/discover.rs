//! Finding the tests in the sources: every PROGRAM and FUNCTION_BLOCK
//! whose name starts with `TEST_` (any case), with how long each runs
//! (`TEST_CYCLES`) and whether it says when it is done (`TEST_DONE`).

use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::{FileId, SourceMap, Span};
use crate::syntax::ast::{ExprKind, Initializer, Item, LiteralValue, Pou, PouKind};

/// The name prefix that makes a POU a test (compared ignoring case).
pub const TEST_PREFIX: &str = "TEST_";
/// Cycles a test runs when it declares no `TEST_CYCLES`: one, or up to
/// this many when it declares `TEST_DONE`.
pub(crate) const DEFAULT_DONE_LIMIT: u64 = 100_000;

/// A test found in the sources.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Found {
    /// The POU's name as written.
    pub(crate) name: String,
    /// The file it is declared in.
    pub(crate) file: String,
    /// A FUNCTION_BLOCK (run through a generated PROGRAM) or a PROGRAM.
    pub(crate) is_block: bool,
    /// `TEST_CYCLES`' initial value, if declared.
    pub(crate) cycles: Option<u64>,
    /// `TEST_DONE` is declared.
    pub(crate) has_done: bool,
}

impl Found {
    /// How many cycles the test runs at most.
    pub(crate) fn cycle_limit(&self) -> u64 {
        match (self.cycles, self.has_done) {
            (Some(n), _) => n,
            (None, true) => DEFAULT_DONE_LIMIT,
            (None, false) => 1,
        }
    }
}

/// True when `name` names a test.
pub(crate) fn is_test_name(name: &str) -> bool {
    name.get(..TEST_PREFIX.len())
        .is_some_and(|p| p.eq_ignore_ascii_case(TEST_PREFIX))
}

/// Diagnostic code of a `TEST_CYCLES` that is not set by an integer literal.
const CYCLES_NOT_LITERAL: &str = "E483";

/// The integer literal a declaration of `name` in `pou` starts with, and
/// where the name is declared.
fn declared(pou: &Pou, name: &str) -> Option<(Option<i128>, Span)> {
    for block in &pou.var_blocks {
        for decl in &block.decls {
            if let Some(ident) = decl
                .names
                .iter()
                .find(|n| n.name.eq_ignore_ascii_case(name))
            {
                let value = match &decl.init {
                    Some(Initializer::Expr(e)) => match &e.kind {
                        ExprKind::Literal(l) => match l.value {
                            LiteralValue::Int(v) => Some(v),
                            _ => None,
                        },
                        _ => None,
                    },
                    _ => None,
                };
                return Some((value, ident.span));
            }
        }
    }
    None
}

/// The diagnostics of [`find_tests`] that are the runner's own (E483),
/// not the parser's: the check of the sources reports those again.
pub(crate) fn runner_errors(diags: Diagnostics) -> Diagnostics {
    let mut out = Diagnostics::new();
    for d in diags.iter().filter(|d| d.code == CYCLES_NOT_LITERAL) {
        out.push(d.clone());
    }
    out
}

/// The tests of `sources`, in file and declaration order; parse errors go
/// into `diags`.
pub(crate) fn find_tests(sources: &SourceMap, diags: &mut Diagnostics) -> Vec<Found> {
    let mut found = Vec::new();
    for (i, file) in sources.files().iter().enumerate() {
        let unit = crate::syntax::parse_file(FileId(i as u32), &file.name, &file.text, diags);
        for item in &unit.items {
            let Item::Pou(pou) = item else { continue };
            if pou.kind == PouKind::Function || !is_test_name(&pou.name.name) {
                continue;
            }
            // The runner reads the cycle count before compiling: anything
            // but a literal would be ignored, so it is refused instead.
            let cycles = match declared(pou, "TEST_CYCLES") {
                Some((Some(v), _)) => Some(v.clamp(1, u64::MAX as i128) as u64),
                Some((None, span)) => {
                    diags.push(Diagnostic::error(
                        CYCLES_NOT_LITERAL,
                        span,
                        format!(
                            "`TEST_CYCLES` of test `{}` must be initialised with an integer \
                             literal (e.g. `TEST_CYCLES : INT := 50;`)",
                            pou.name.name
                        ),
                    ));
                    None
                }
                None => None,
            };
            found.push(Found {
                name: pou.name.name.clone(),
                file: file.name.clone(),
                is_block: pou.kind == PouKind::FunctionBlock,
                cycles,
                has_done: declared(pou, "TEST_DONE").is_some(),
            });
        }
    }
    found
}

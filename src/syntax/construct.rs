//! AST construction helpers called from the grammar actions: parser state
//! (file, diagnostics), nesting-depth guards, and the few constructs whose
//! shape is decided after parsing (CASE arms, SFC bodies, action
//! associations, configurations).
//!
//! Depth guard: every node with children is built here, and refuses to grow
//! deeper than the limits of [`crate::syntax::depth`] (reporting `E106`
//! once).

use crate::diagnostics::Diagnostic;
use crate::source::{FileId, Span};
use crate::syntax::ast::*;
use crate::syntax::depth::{
    MAX_EXPR_DEPTH, MAX_EXPR_TERMS, MAX_INIT_DEPTH, MAX_STMT_DEPTH, expr_depth, expr_height,
    init_depth, stmt_depth, type_depth,
};
use crate::syntax::parser::recovery_diagnostic;
use crate::syntax::token::Tok;
use lalrpop_util::ErrorRecovery;
use std::cell::{Cell, RefCell};
use std::rc::Rc;

/// Most syntax errors recorded per file; the rest are counted.
const MAX_SYNTAX_ERRORS: usize = 200;

/// The first place the parser could not go on from.
#[derive(Debug, Clone)]
pub struct Failure {
    /// Byte offset of the token it could not take.
    pub at: usize,
    /// The terminals it expected there, as the grammar names them.
    pub expected: Vec<String>,
    /// The syntax error reported for it.
    pub diagnostic: Diagnostic,
}

/// Mutable state shared by all grammar actions of one parse.
pub struct State<'t> {
    file: FileId,
    text: &'t str,
    line_starts: Rc<[usize]>,
    /// A repair trial ([`State::trial`]): only whether the parse failed
    /// matters, so failures are counted without building their messages.
    trial: bool,
    diags: RefCell<Vec<Diagnostic>>,
    depth_reported: Cell<bool>,
    last_error_line: Cell<Option<usize>>,
    suppressed: Cell<usize>,
    /// Lines holding an unsupported construct (E110): other syntax errors
    /// there are its consequence and are not reported.
    quiet_lines: RefCell<Vec<usize>>,
    /// Span and height of the binary node built last: the left operand of
    /// the next one in a chain.
    last_binary: Cell<Option<(Span, usize)>>,
    /// An overlong chain was cut (E106): later chains in the file are not
    /// built either.
    chain_cut: Cell<bool>,
    /// Byte ranges of the tokens parsed (for [`crate::syntax::recovery`]).
    token_spans: Vec<(usize, usize)>,
    /// `VAR PRIVATE`-style sections seen (for [`crate::syntax::oop_var_access`]).
    pub(crate) var_access: RefCell<Vec<(Span, crate::syntax::oop::Access)>>,
    /// Where the parser first had to recover, and what it expected there
    /// (for [`crate::syntax::repair`]); and how many times it recovered.
    first_failure: RefCell<Option<Failure>>,
    failures: Cell<usize>,
}

impl<'t> State<'t> {
    /// State for parsing `text` of `file`.
    pub fn new(file: FileId, text: &'t str) -> State<'t> {
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        State::with_lines(file, text, line_starts.into(), false)
    }

    /// State for one repair trial over the same text as `self`: it shares
    /// the line table (a trial must not rescan a large file) and does not
    /// word its failures.
    pub fn trial(&self) -> State<'t> {
        State::with_lines(self.file, self.text, self.line_starts.clone(), true)
    }

    fn with_lines(file: FileId, text: &'t str, line_starts: Rc<[usize]>, trial: bool) -> State<'t> {
        State {
            file,
            text,
            line_starts,
            trial,
            diags: RefCell::new(Vec::new()),
            depth_reported: Cell::new(false),
            last_error_line: Cell::new(None),
            suppressed: Cell::new(0),
            quiet_lines: RefCell::new(Vec::new()),
            last_binary: Cell::new(None),
            chain_cut: Cell::new(false),
            token_spans: Vec::new(),
            var_access: RefCell::new(Vec::new()),
            first_failure: RefCell::new(None),
            failures: Cell::new(0),
        }
    }

    /// Remembers the byte ranges of the tokens about to be parsed.
    pub fn set_token_spans(&mut self, spans: Vec<(usize, usize)>) {
        self.token_spans = spans;
    }

    /// The range of the last token that ends at or before byte `at`.
    pub fn token_before(&self, at: usize) -> Option<(usize, usize)> {
        let n = self.token_spans.partition_point(|&(_, r)| r <= at);
        n.checked_sub(1).map(|i| self.token_spans[i])
    }

    /// The span `l..r` in this file.
    pub fn span(&self, l: usize, r: usize) -> Span {
        Span::new(self.file, l, r.max(l))
    }

    /// The source text.
    pub fn text(&self) -> &'t str {
        self.text
    }

    /// The file being parsed.
    pub fn file(&self) -> FileId {
        self.file
    }

    /// Records an error.
    pub fn error(&self, code: &'static str, span: Span, message: impl Into<String>) {
        self.diags
            .borrow_mut()
            .push(Diagnostic::error(code, span, message));
    }

    /// Records a syntax error found by the parser, unless it is a cascade
    /// of the previous one (same line) or there are already too many.
    pub fn syntax_error(&self, d: Diagnostic) {
        let line = match self.line_starts.binary_search(&(d.span.start as usize)) {
            Ok(l) => l,
            Err(l) => l.saturating_sub(1),
        };
        if d.code == "E110" {
            if self.quiet_lines.borrow().contains(&line) {
                return;
            }
            self.quiet_lines.borrow_mut().push(line);
        } else if self.quiet_lines.borrow().contains(&line) {
            return;
        }
        if self.last_error_line.get() == Some(line) {
            return;
        }
        self.last_error_line.set(Some(line));
        let count = self.diags.borrow().len();
        if count >= MAX_SYNTAX_ERRORS {
            self.suppressed.set(self.suppressed.get() + 1);
            return;
        }
        self.diags.borrow_mut().push(d);
    }

    /// Records a recovered parse error.
    pub fn recover(&self, e: ErrorRecovery<usize, Tok, ()>) {
        let d = self.note_failure(e.error);
        self.syntax_error(d);
    }

    /// Counts a parse error, remembers the first one (place, expected
    /// tokens, message) and returns its diagnostic.
    pub fn note_failure(&self, e: lalrpop_util::ParseError<usize, Tok, ()>) -> Diagnostic {
        use lalrpop_util::ParseError as P;
        self.failures.set(self.failures.get() + 1);
        if self.trial {
            // The trial is abandoned at its first failure; nobody reads this.
            return Diagnostic::error("E101", self.span(self.text.len(), self.text.len()), "");
        }
        let place = match &e {
            P::UnrecognizedToken {
                token: (l, _, _),
                expected,
            } => (*l, expected.clone()),
            // Reported at the end of the text (see `recovery_diagnostic`).
            P::UnrecognizedEof { expected, .. } => (self.text.len(), expected.clone()),
            P::ExtraToken { token: (l, _, _) } => (*l, Vec::new()),
            P::InvalidToken { location } => (*location, Vec::new()),
            P::User { .. } => (self.text.len(), Vec::new()),
        };
        let d = recovery_diagnostic(self, e);
        if self.first_failure.borrow().is_none() {
            *self.first_failure.borrow_mut() = Some(Failure {
                at: place.0,
                expected: place.1,
                diagnostic: d.clone(),
            });
        }
        d
    }

    /// How many times the parser had to recover so far.
    pub fn failures(&self) -> usize {
        self.failures.get()
    }

    /// Where the parser first had to recover (byte offset of the token it
    /// could not take) and the terminals it expected there.
    pub fn first_failure(&self) -> Option<Failure> {
        self.first_failure.borrow().clone()
    }

    /// Takes the collected diagnostics.
    pub fn finish(self) -> Vec<Diagnostic> {
        let mut d = self.diags.into_inner();
        if self.suppressed.get() > 0 {
            let span = Span::new(self.file, self.text.len(), self.text.len());
            d.push(Diagnostic::error(
                "E101",
                span,
                format!(
                    "{} more syntax errors not shown; fix the ones above first",
                    self.suppressed.get()
                ),
            ));
        }
        d
    }

    /// E106 for a chain of more than [`MAX_EXPR_TERMS`] operands.
    fn too_long(&self, span: Span) {
        self.chain_cut.set(true);
        if !self.depth_reported.replace(true) {
            self.error(
                "E106",
                span,
                format!(
                    "expression too long (a chain of more than {MAX_EXPR_TERMS} operands); split it up"
                ),
            );
        }
    }

    fn too_deep(&self, span: Span, what: &str, limit: usize) {
        if !self.depth_reported.replace(true) {
            self.error(
                "E106",
                span,
                format!("{what} nested too deeply (more than {limit} levels); split it up"),
            );
        }
    }
}

/// Returns `node` if it is not too deep, else reports `E106` and returns
/// `fallback` (a shallower child).
fn guard(st: &State, node: Expr, fallback: impl FnOnce(Expr) -> Expr) -> Expr {
    if expr_depth(&node) > MAX_EXPR_DEPTH {
        st.too_deep(node.span, "expression", MAX_EXPR_DEPTH);
        fallback(node)
    } else {
        node
    }
}

/// Drops an expression tree of any height with a work list (the default
/// drop recurses once per level).
fn dismantle(e: Expr) {
    let mut work = vec![e];
    while let Some(mut node) = work.pop() {
        let span = node.span;
        let leaf = || Expr {
            kind: ExprKind::Literal(Literal {
                value: LiteralValue::Bool(false),
                type_prefix: None,
            }),
            span,
        };
        match &mut node.kind {
            ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => {
                work.push(std::mem::replace(a.as_mut(), leaf()));
                work.push(std::mem::replace(b.as_mut(), leaf()));
            }
            ExprKind::Member(b, _)
            | ExprKind::BitAccess(b, _)
            | ExprKind::Unary(_, b)
            | ExprKind::Paren(b)
            | ExprKind::Deref(b) => work.push(std::mem::replace(b.as_mut(), leaf())),
            ExprKind::Index(b, idx) => {
                work.push(std::mem::replace(b.as_mut(), leaf()));
                work.append(idx);
            }
            _ => {}
        }
    }
}

fn first_child(e: Expr) -> Expr {
    match e.kind {
        ExprKind::Member(b, _)
        | ExprKind::BitAccess(b, _)
        | ExprKind::Unary(_, b)
        | ExprKind::Paren(b)
        | ExprKind::Deref(b)
        | ExprKind::Index(b, _)
        | ExprKind::Binary(_, b, _)
        | ExprKind::Assign(_, b) => *b,
        ExprKind::Call(c) => *c.callee,
        _ => e,
    }
}

// ------------------------------------------------------------------ expressions

/// `l op r`. The left operand was checked when it was built, so only the
/// right one can make the node nest too deeply (a left-associative chain is
/// flat, see [`expr_depth`]). The chain's length is bounded separately by
/// [`MAX_EXPR_TERMS`]; the height of the left operand is remembered from the
/// previous reduction, so that checking a chain of n terms costs O(n).
pub fn binary(st: &State, op: BinaryOp, l: Expr, r: Expr) -> Expr {
    let span = l.span.to(r.span);
    if 1 + expr_depth(&r) > MAX_EXPR_DEPTH {
        st.too_deep(r.span, "expression", MAX_EXPR_DEPTH);
        return l;
    }
    let left_height = match st.last_binary.get() {
        Some((s, h)) if s == l.span && matches!(l.kind, ExprKind::Binary(..)) => h,
        _ => expr_height(&l),
    };
    let height = 1 + left_height.max(expr_height(&r));
    if height > MAX_EXPR_TERMS || (st.chain_cut.get() && left_height > 1) {
        st.too_long(span);
        // Keep only the right operand (the rest of an overlong chain then
        // costs constant time per term and builds nothing), and take the
        // long left operand apart without recursion.
        dismantle(l);
        return r;
    }
    st.last_binary.set(Some((span, height)));
    Expr {
        kind: ExprKind::Binary(op, Box::new(l), Box::new(r)),
        span,
    }
}

/// `op e`; a minus directly before an untyped number or duration literal is
/// folded into the literal (`-5` is the literal -5).
pub fn unary(st: &State, op: UnaryOp, e: Expr, l: usize, r: usize) -> Expr {
    let span = st.span(l, r);
    if op == UnaryOp::Neg
        && let ExprKind::Literal(lit) = &e.kind
        && lit.type_prefix.is_none()
    {
        let negated = match lit.value {
            LiteralValue::Int(v) => Some(LiteralValue::Int(-v)),
            LiteralValue::Real(v) => Some(LiteralValue::Real(-v)),
            LiteralValue::Duration { nanos, long } => nanos
                .checked_neg()
                .map(|nanos| LiteralValue::Duration { nanos, long }),
            _ => None,
        };
        if let Some(value) = negated {
            return Expr {
                kind: ExprKind::Literal(Literal {
                    value,
                    type_prefix: None,
                }),
                span,
            };
        }
    }
    let node = Expr {
        kind: ExprKind::Unary(op, Box::new(e)),
        span,
    };
    guard(st, node, first_child)
}

/// `( e )`.
pub fn paren(st: &State, e: Expr, l: usize, r: usize) -> Expr {
    let node = Expr {
        kind: ExprKind::Paren(Box::new(e)),
        span: st.span(l, r),
    };
    guard(st, node, first_child)
}

/// `(t := v)` inside an expression.
pub fn assign_expr(st: &State, t: Expr, v: Expr, l: usize, r: usize) -> Expr {
    let node = Expr {
        kind: ExprKind::Assign(Box::new(t), Box::new(v)),
        span: st.span(l, r),
    };
    guard(st, node, first_child)
}

/// A field name of a structure initialiser, read as an lvalue: anything
/// but a plain name is E113.
pub fn field_name(st: &State, e: Expr) -> Ident {
    match e.kind {
        ExprKind::Name(id) => id,
        _ => {
            st.error(
                "E113",
                e.span,
                "a structure initialiser names a field here: a plain name is expected",
            );
            Ident {
                name: String::new(),
                span: e.span,
            }
        }
    }
}

/// An initialiser written as an expression. `(f := v)` is an assignment
/// expression to the parser; in an initialiser it is the structure
/// initialiser of the one field `f` (nested ones too: `(a := (b := 1))`).
pub fn init_from_expr(st: &State, e: Expr) -> Initializer {
    match e.kind {
        ExprKind::Assign(target, value) => {
            let field = field_name(st, *target);
            let value = init_from_expr(st, *value);
            struct_init_span(st, vec![(field, value)], e.span)
        }
        _ => Initializer::Expr(e),
    }
}

/// `b.m`.
pub fn member(st: &State, b: Expr, m: Ident) -> Expr {
    let span = b.span.to(m.span);
    let node = Expr {
        kind: ExprKind::Member(Box::new(b), m),
        span,
    };
    guard(st, node, first_child)
}

/// `b.3`: bit access with an integer literal.
pub fn bit_access(st: &State, b: Expr, lit: Literal, l: usize, r: usize) -> Expr {
    let span = b.span.to(st.span(l, r));
    let bit = match lit {
        Literal {
            value: LiteralValue::Int(v),
            type_prefix: None,
        } if (0..=63).contains(&v) => v as u32,
        _ => {
            st.error(
                "E108",
                st.span(l, r),
                "expected a member name or a bit number 0..63 after `.`",
            );
            0
        }
    };
    let node = Expr {
        kind: ExprKind::BitAccess(Box::new(b), bit),
        span,
    };
    guard(st, node, first_child)
}

/// `b.%X3`: bit access written with a direct-address style suffix.
pub fn bit_access_direct(st: &State, b: Expr, d: DirectAddress) -> Expr {
    st.error(
        "E108",
        d.span,
        format!("`.{}` is not a valid member or bit number", d.text),
    );
    b
}

/// `b[i, j]`.
pub fn index(st: &State, b: Expr, idx: Vec<Expr>, r: usize) -> Expr {
    let span = b.span.to(st.span(r, r));
    let node = Expr {
        kind: ExprKind::Index(Box::new(b), idx),
        span,
    };
    guard(st, node, first_child)
}

/// `b(args)`.
pub fn call(st: &State, b: Expr, args: Vec<Arg>, r: usize) -> Expr {
    let span = b.span.to(st.span(r, r));
    let node = Expr {
        kind: ExprKind::Call(Call {
            callee: Box::new(b),
            args,
            span,
        }),
        span,
    };
    guard(st, node, first_child)
}

// ------------------------------------------------------------------ statements

/// Intermediate element of a CASE body: labels or a statement.
#[allow(clippy::large_enum_variant)]
pub enum CaseItem {
    /// `1, 2..5 :`
    Labels(Vec<CaseLabel>, Span),
    /// A statement of the current arm.
    Stmt(Stmt),
    /// The assignments of a chained assignment in the current arm.
    Chain(Vec<Stmt>),
}

/// The declarations of a `TYPE` block starting at byte `l`, marked
/// qualified-only and strict when `{attribute 'qualified_only'}` and
/// `{attribute 'strict'}` precede it.
pub fn type_block(st: &State, l: usize, decls: Vec<Option<TypeDecl>>) -> Vec<TypeDecl> {
    use crate::syntax::qualified_only::{before_type, is_qualified_only, is_strict};
    let qualified = before_type(st.text(), l, is_qualified_only);
    let strict = before_type(st.text(), l, is_strict);
    decls
        .into_iter()
        .flatten()
        .map(|d| TypeDecl {
            qualified_only: qualified,
            strict,
            ..d
        })
        .collect()
}

/// Adds `stmts` to the last arm; E107 when there is none yet.
fn arm_stmts(st: &State, arms: &mut [CaseArm], stmts: Vec<Stmt>) {
    match arms.last_mut() {
        Some(arm) => arm.body.extend(stmts),
        None => {
            if let Some(s) = stmts.first() {
                st.error(
                    "E107",
                    s.span,
                    "statement before the first CASE label: expected a label such as `1:`",
                );
            }
        }
    }
}

fn is_compound(s: &Stmt) -> bool {
    matches!(
        s.kind,
        StmtKind::If { .. }
            | StmtKind::Case { .. }
            | StmtKind::For { .. }
            | StmtKind::While { .. }
            | StmtKind::Repeat { .. }
            | StmtKind::Try { .. }
    )
}

/// Drops the `;` written after `END_IF`, `END_FOR`, ... (it terminates the
/// compound statement and is not an empty statement of its own).
pub fn stmt_list(mut stmts: Vec<Stmt>) -> Vec<Stmt> {
    // In place: a body of a million statements is not held twice.
    let mut absorb = false;
    stmts.retain(|s| {
        if absorb && s.kind == StmtKind::Empty {
            absorb = false;
            return false;
        }
        absorb = is_compound(s);
        true
    });
    stmts
}

/// A compound statement, replaced by an empty one if nested too deeply.
pub fn compound(st: &State, kind: StmtKind, l: usize, r: usize) -> Stmt {
    let s = Stmt {
        kind,
        span: st.span(l, r),
    };
    if stmt_depth(&s) > MAX_STMT_DEPTH {
        st.too_deep(s.span, "statement", MAX_STMT_DEPTH);
        return Stmt {
            kind: StmtKind::Empty,
            span: s.span,
        };
    }
    s
}

/// `IF ... END_IF`.
pub fn if_stmt(
    st: &State,
    cond: Expr,
    then: Vec<Stmt>,
    elsifs: Vec<(Expr, Vec<Stmt>)>,
    else_branch: Option<Vec<Stmt>>,
    l: usize,
    r: usize,
) -> Stmt {
    let mut branches = vec![(cond, then)];
    branches.extend(elsifs);
    compound(
        st,
        StmtKind::If {
            branches,
            else_branch,
        },
        l,
        r,
    )
}

/// `CASE ... END_CASE`: groups labels and statements into arms.
pub fn case_stmt(
    st: &State,
    selector: Expr,
    items: Vec<CaseItem>,
    else_branch: Option<Vec<Stmt>>,
    l: usize,
    r: usize,
) -> Stmt {
    let mut arms: Vec<CaseArm> = Vec::new();
    for item in items {
        match item {
            CaseItem::Labels(labels, span) => arms.push(CaseArm {
                labels,
                body: Vec::new(),
                span,
            }),
            CaseItem::Stmt(s) => arm_stmts(st, &mut arms, vec![s]),
            CaseItem::Chain(v) => arm_stmts(st, &mut arms, v),
        }
    }
    for arm in &mut arms {
        arm.body = stmt_list(std::mem::take(&mut arm.body));
    }
    compound(
        st,
        StmtKind::Case {
            selector,
            arms,
            else_branch,
        },
        l,
        r,
    )
}

/// `expr;` where `expr` contains a call: must be the call itself.
pub fn call_stmt(st: &State, e: Expr, l: usize, r: usize) -> Stmt {
    let span = st.span(l, r);
    match e.kind {
        ExprKind::Call(c) => Stmt {
            kind: StmtKind::Call(c),
            span,
        },
        _ => {
            st.error(
                "E103",
                e.span,
                "this expression is not a statement: expected an assignment `:=` or a call",
            );
            Stmt {
                kind: StmtKind::Empty,
                span,
            }
        }
    }
}

/// `x;`: a name alone.
pub fn bare_stmt(st: &State, e: Expr, l: usize, r: usize) -> Stmt {
    let shown = st
        .text()
        .get(e.span.start as usize..e.span.end as usize)
        .unwrap_or("?")
        .to_string();
    st.error(
        "E103",
        e.span,
        format!("`{shown}` alone is not a statement: expected `{shown} := ...` or `{shown}(...)`"),
    );
    Stmt {
        kind: StmtKind::Empty,
        span: st.span(l, r),
    }
}

// ------------------------------------------------------------------ declarations

/// A `VAR...END_VAR` block; `quals` holds `None` for CONSTANT.
pub fn var_block(
    st: &State,
    kind: VarKind,
    quals: Vec<Option<Retain>>,
    decls: Vec<VarDecl>,
    l: usize,
    r: usize,
) -> VarBlock {
    VarBlock {
        kind,
        constant: quals.iter().any(Option::is_none),
        // PERSISTENT wins over a RETAIN next to it; otherwise the last word.
        retain: if quals.contains(&Some(Retain::Persistent)) {
            Some(Retain::Persistent)
        } else {
            quals.iter().flatten().last().copied()
        },
        decls,
        span: st.span(l, r),
    }
}

/// A var block outside any POU: only VAR_GLOBAL is allowed.
pub fn top_level_globals(st: &State, vb: VarBlock) -> Option<Item> {
    if vb.kind == VarKind::Global {
        return Some(Item::Globals(vb));
    }
    let at = Span {
        end: vb.span.start,
        ..vb.span
    };
    st.error(
        "E111",
        at,
        "variable block outside a POU: only VAR_GLOBAL may appear at the top level \
         (is a `PROGRAM name` header missing?)",
    );
    None
}

/// `ARRAY [ranges] OF elem`.
pub fn array_type(
    st: &State,
    ranges: Vec<(Expr, Expr)>,
    elem: TypeSpec,
    l: usize,
    r: usize,
) -> TypeSpec {
    let span = st.span(l, r);
    if type_depth(&elem) >= MAX_INIT_DEPTH {
        st.too_deep(span, "array type", MAX_INIT_DEPTH);
        return elem;
    }
    TypeSpec::Array {
        ranges,
        elem: Box::new(elem),
        span,
    }
}

/// `ARRAY[*, ...] OF elem`.
pub fn open_array_type(st: &State, rank: usize, elem: TypeSpec, l: usize, r: usize) -> TypeSpec {
    let span = st.span(l, r);
    if type_depth(&elem) >= MAX_INIT_DEPTH {
        st.too_deep(span, "array type", MAX_INIT_DEPTH);
        return elem;
    }
    TypeSpec::OpenArray {
        rank,
        elem: Box::new(elem),
        span,
    }
}

fn guard_init(st: &State, init: Initializer, span: Span) -> Initializer {
    if init_depth(&init) > MAX_INIT_DEPTH {
        st.too_deep(span, "initializer", MAX_INIT_DEPTH);
        return Initializer::Array(Vec::new(), span);
    }
    init
}

/// `[a, n(b), m()]`.
pub fn array_init(st: &State, elems: Vec<ArrayInitElem>, l: usize, r: usize) -> Initializer {
    let span = st.span(l, r);
    guard_init(st, Initializer::Array(elems, span), span)
}

/// `1, 2, 3` as a declaration's initial value: CODESYS's array initial
/// value without brackets (W355).
pub fn bare_array_init(
    st: &State,
    first: ArrayInitElem,
    mut rest: Vec<ArrayInitElem>,
    l: usize,
    r: usize,
) -> Initializer {
    let span = st.span(l, r);
    st.diags.borrow_mut().push(Diagnostic::warning(
        "W355",
        span,
        "an array initial value without brackets is a CODESYS extension; IEC writes [1, 2, 3]",
    ));
    rest.insert(0, first);
    array_init(st, rest, l, r)
}

/// `(a := x, b := y)`.
pub fn struct_init(
    st: &State,
    fields: Vec<(Ident, Initializer)>,
    l: usize,
    r: usize,
) -> Initializer {
    struct_init_span(st, fields, st.span(l, r))
}

fn struct_init_span(st: &State, fields: Vec<(Ident, Initializer)>, span: Span) -> Initializer {
    guard_init(st, Initializer::Struct(fields, span), span)
}

/// A POU.
#[allow(clippy::too_many_arguments)]
pub fn pou(
    st: &State,
    kind: PouKind,
    name: Ident,
    return_type: Option<TypeSpec>,
    var_blocks: Vec<VarBlock>,
    body: Body,
    l: usize,
    r: usize,
) -> Pou {
    Pou {
        kind,
        name,
        return_type,
        var_blocks,
        body,
        span: st.span(l, r),
        oop: None,
        no_check: crate::syntax::qualified_only::before_type(
            st.text(),
            l,
            crate::syntax::qualified_only::is_no_check,
        ),
    }
}

// ------------------------------------------------------------------ SFC

/// Intermediate element of a POU body.
#[allow(clippy::large_enum_variant)]
pub enum BodyElem {
    /// A plain statement.
    Stmt(Stmt),
    /// The assignments of a chained assignment (`a := b := c;`).
    Chain(Vec<Stmt>),
    /// A step, transition or action.
    Sfc(SfcElement),
}

/// ST statements, or an SFC chart if any chart element is present.
pub fn body(elems: Vec<BodyElem>) -> Body {
    let elems = spell_out_chains(elems);
    if elems.iter().all(|e| matches!(e, BodyElem::Stmt(_))) {
        let stmts = elems
            .into_iter()
            .filter_map(|e| match e {
                BodyElem::Stmt(s) => Some(s),
                BodyElem::Sfc(_) | BodyElem::Chain(_) => None,
            })
            .collect();
        return Body::St(stmt_list(stmts));
    }
    let mut out = Vec::with_capacity(elems.len());
    let mut absorb = false;
    for e in elems {
        match e {
            BodyElem::Stmt(s) => {
                if absorb && s.kind == StmtKind::Empty {
                    absorb = false;
                    continue;
                }
                absorb = is_compound(&s);
                out.push(SfcElement::Statement(s));
            }
            BodyElem::Sfc(x) => {
                absorb = false;
                out.push(x);
            }
            // Spelt out by `spell_out_chains` above.
            BodyElem::Chain(_) => {}
        }
    }
    Body::Sfc(out)
}

/// `elems` with each chained assignment replaced by its statements.
fn spell_out_chains(elems: Vec<BodyElem>) -> Vec<BodyElem> {
    if !elems.iter().any(|e| matches!(e, BodyElem::Chain(_))) {
        return elems;
    }
    let mut out = Vec::with_capacity(elems.len());
    for e in elems {
        match e {
            BodyElem::Chain(v) => out.extend(v.into_iter().map(BodyElem::Stmt)),
            other => out.push(other),
        }
    }
    out
}

/// Qualifiers of IEC 61131-3 action associations.
const QUALIFIERS: [&str; 11] = ["N", "R", "S", "L", "D", "P", "P0", "P1", "SD", "DS", "SL"];
/// Qualifiers that take a duration.
const TIMED: [&str; 5] = ["L", "D", "SD", "DS", "SL"];

/// `A(qualifier, duration, indicators...)`: the first argument, when it is
/// a name, is the qualifier; a timed qualifier takes the next argument as
/// duration; the remaining arguments are indicator variables.
pub fn association(
    st: &State,
    action: Ident,
    args: Vec<Expr>,
    l: usize,
    r: usize,
) -> Option<ActionAssociation> {
    let mut args = args.into_iter().peekable();
    let mut qualifier = None;
    if let Some(Expr {
        kind: ExprKind::Name(id),
        ..
    }) = args.peek()
    {
        // The first name is always the qualifier; an unknown one is
        // reported by the checker (E609).
        qualifier = Some(id.clone());
        args.next();
    }
    let known = qualifier
        .as_ref()
        .is_some_and(|q| QUALIFIERS.contains(&q.key().as_str()));
    let timed = qualifier
        .as_ref()
        .is_some_and(|q| TIMED.contains(&q.key().as_str()));
    // A duration follows a timed qualifier; after an unknown qualifier, a
    // non-name argument is taken as its duration too.
    let duration = match args.peek() {
        Some(_) if timed => args.next(),
        Some(e) if !known && !matches!(e.kind, ExprKind::Name(_)) => args.next(),
        _ => None,
    };
    let mut indicators = Vec::new();
    for a in args {
        match a.kind {
            ExprKind::Name(id) => indicators.push(id),
            _ => {
                let why = match &qualifier {
                    Some(q) if !timed => {
                        format!(
                            "qualifier {} takes no duration; expected an indicator variable",
                            q.name
                        )
                    }
                    _ => "expected an indicator variable name".to_string(),
                };
                st.error("E104", a.span, why);
            }
        }
    }
    Some(ActionAssociation {
        action,
        qualifier,
        duration,
        indicators,
        span: st.span(l, r),
    })
}

/// `(PRIORITY := n)` of a transition.
pub fn priority(st: &State, key: Ident, e: Expr) -> Expr {
    if key.key() != "PRIORITY" {
        st.error(
            "E105",
            key.span,
            format!(
                "expected `PRIORITY := n` in transition, found `{}`",
                key.name
            ),
        );
    }
    e
}

// ------------------------------------------------------------------ configuration

/// Intermediate element of a CONFIGURATION or RESOURCE.
#[allow(clippy::large_enum_variant)]
pub enum ConfElem {
    /// VAR_GLOBAL block.
    Globals(VarBlock),
    /// RESOURCE (only directly in a configuration).
    Resource(Resource),
    /// TASK.
    Task(TaskDecl),
    /// PROGRAM instance.
    Program(ProgramInstance),
    /// A recovered syntax error.
    Error,
    /// `VAR_CONFIG ... END_VAR` (only directly in a configuration).
    VarConfig(Vec<ConfigInit>),
}

/// `CONFIGURATION`; tasks and programs given directly go to an implicit
/// resource named like the configuration.
pub fn configuration(
    st: &State,
    name: Ident,
    elems: Vec<ConfElem>,
    l: usize,
    r: usize,
) -> Configuration {
    let span = st.span(l, r);
    let mut globals = Vec::new();
    let mut resources = Vec::new();
    let mut var_config = Vec::new();
    let mut implicit = Resource {
        name: name.clone(),
        on: None,
        globals: Vec::new(),
        tasks: Vec::new(),
        programs: Vec::new(),
        span,
    };
    for e in elems {
        match e {
            ConfElem::Globals(g) => globals.push(g),
            ConfElem::Resource(res) => resources.push(res),
            ConfElem::Task(t) => implicit.tasks.push(t),
            ConfElem::Program(p) => implicit.programs.push(p),
            ConfElem::VarConfig(v) => var_config.extend(v),
            ConfElem::Error => {}
        }
    }
    if !implicit.tasks.is_empty() || !implicit.programs.is_empty() {
        resources.push(implicit);
    }
    Configuration {
        name,
        globals,
        resources,
        var_config,
        span,
    }
}

/// `RESOURCE name ON type ... END_RESOURCE`.
pub fn resource(
    st: &State,
    name: Ident,
    on: Option<Ident>,
    elems: Vec<ConfElem>,
    l: usize,
    r: usize,
) -> Resource {
    let mut res = Resource {
        name,
        on,
        globals: Vec::new(),
        tasks: Vec::new(),
        programs: Vec::new(),
        span: st.span(l, r),
    };
    for e in elems {
        match e {
            ConfElem::Globals(g) => res.globals.push(g),
            ConfElem::Task(t) => res.tasks.push(t),
            ConfElem::Program(p) => res.programs.push(p),
            ConfElem::Resource(_) | ConfElem::VarConfig(_) | ConfElem::Error => {}
        }
    }
    res
}

/// `a, b : BOOL R_EDGE`: a declaration with an edge qualifier (anything
/// else after the type is E425).
pub fn edge_decl(
    st: &State,
    names: Vec<Ident>,
    ty: TypeSpec,
    q: Ident,
    l: usize,
    r: usize,
) -> VarDecl {
    let edge = match q.key().as_str() {
        "R_EDGE" => Some(EdgeQualifier::Rising),
        "F_EDGE" => Some(EdgeQualifier::Falling),
        _ => {
            st.error(
                "E425",
                q.span,
                format!(
                    "`{}` after the type: only R_EDGE or F_EDGE may follow it",
                    q.name
                ),
            );
            None
        }
    };
    VarDecl {
        names,
        location: None,
        ty,
        init: None,
        span: st.span(l, r),
        edge,
        init_args: None,
    }
}

// --- refs: dereference and reference types ---

/// `b^`.
pub fn deref(st: &State, b: Expr, r: usize) -> Expr {
    let span = b.span.to(st.span(r, r));
    let node = Expr {
        kind: ExprKind::Deref(Box::new(b)),
        span,
    };
    guard(st, node, first_child)
}

/// `REF_TO T`, `POINTER TO T`, `REFERENCE TO T`.
pub fn ref_type(st: &State, kind: RefKind, target: TypeSpec, l: usize, r: usize) -> TypeSpec {
    TypeSpec::Ref {
        kind,
        target: Box::new(target),
        span: st.span(l, r),
    }
}

//! Small constructors of AST nodes, all carrying the span of the S7-200
//! instruction they come from, so that every diagnostic and runtime fault
//! of the generated code points into the `.awl` file.

use crate::source::Span;
use crate::syntax::ast::{
    Arg, BinaryOp, Call, Expr, ExprKind, Ident, Literal, LiteralValue, Stmt, StmtKind, UnaryOp,
};

/// Builds nodes at one span.
#[derive(Debug, Clone, Copy)]
pub(super) struct At(pub Span);

impl At {
    /// An identifier.
    pub fn ident(self, name: &str) -> Ident {
        Ident {
            name: name.to_string(),
            span: self.0,
        }
    }

    fn expr(self, kind: ExprKind) -> Expr {
        Expr { kind, span: self.0 }
    }

    /// A variable.
    pub fn name(self, name: &str) -> Expr {
        self.expr(ExprKind::Name(self.ident(name)))
    }

    /// An untyped integer literal.
    pub fn int(self, v: i64) -> Expr {
        self.expr(ExprKind::Literal(Literal {
            value: LiteralValue::Int(i128::from(v)),
            type_prefix: None,
        }))
    }

    /// A typed integer literal (`WORD#16#FF`).
    pub fn typed(self, ty: &str, v: i64) -> Expr {
        self.expr(ExprKind::Literal(Literal {
            value: LiteralValue::Int(i128::from(v)),
            type_prefix: Some(self.ident(ty)),
        }))
    }

    /// `TRUE` or `FALSE`.
    pub fn boolean(self, b: bool) -> Expr {
        self.expr(ExprKind::Literal(Literal {
            value: LiteralValue::Bool(b),
            type_prefix: None,
        }))
    }

    /// A duration literal.
    pub fn duration(self, nanos: i64) -> Expr {
        self.expr(ExprKind::Literal(Literal {
            value: LiteralValue::Duration { nanos, long: false },
            type_prefix: None,
        }))
    }

    /// `array[i]`.
    pub fn index(self, array: &str, i: u32) -> Expr {
        self.expr(ExprKind::Index(
            Box::new(self.name(array)),
            vec![self.int(i64::from(i))],
        ))
    }

    /// `base.n`.
    pub fn bit(self, base: Expr, n: u8) -> Expr {
        self.expr(ExprKind::BitAccess(Box::new(base), u32::from(n)))
    }

    /// `base.member`.
    pub fn member(self, base: Expr, member: &str) -> Expr {
        self.expr(ExprKind::Member(Box::new(base), self.ident(member)))
    }

    /// `f(args…)`.
    pub fn call(self, f: &str, args: Vec<Expr>) -> Expr {
        self.expr(ExprKind::Call(Call {
            callee: Box::new(self.name(f)),
            args: args.into_iter().map(Arg::Positional).collect(),
            span: self.0,
        }))
    }

    /// `a op b`.
    pub fn bin(self, op: BinaryOp, a: Expr, b: Expr) -> Expr {
        self.expr(ExprKind::Binary(op, Box::new(a), Box::new(b)))
    }

    /// `NOT e`.
    pub fn not(self, e: Expr) -> Expr {
        self.expr(ExprKind::Unary(UnaryOp::Not, Box::new(e)))
    }

    fn stmt(self, kind: StmtKind) -> Stmt {
        Stmt { kind, span: self.0 }
    }

    /// `target := value;`
    pub fn assign(self, target: Expr, value: Expr) -> Stmt {
        self.stmt(StmtKind::Assign { target, value })
    }

    /// `IF cond THEN body END_IF;`
    pub fn when(self, cond: Expr, body: Vec<Stmt>) -> Stmt {
        self.stmt(StmtKind::If {
            branches: vec![(cond, body)],
            else_branch: None,
        })
    }

    /// `REPEAT body UNTIL cond END_REPEAT;`
    pub fn repeat(self, body: Vec<Stmt>, until: Expr) -> Stmt {
        self.stmt(StmtKind::Repeat { body, until })
    }

    /// `callee(name := value, …);` (inputs and in-outs by name).
    pub fn call_stmt(self, callee: &str, args: Vec<(&str, Expr)>) -> Stmt {
        self.stmt(StmtKind::Call(Call {
            callee: Box::new(self.name(callee)),
            args: args
                .into_iter()
                .map(|(name, value)| Arg::Input {
                    name: self.ident(name),
                    value,
                })
                .collect(),
            span: self.0,
        }))
    }
}

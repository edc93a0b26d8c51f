//! `AssertArrayEquals` over multi-dimensional arrays and arrays of
//! structures (nested to any depth): the two values must have the same
//! type; their elementary leaves are compared in storage order (last index
//! fastest, fields in declaration order) and the first that differs is
//! reported, named by its path (`[2,3]`, `[1].pos.x`), with its expected
//! and actual values; the comparison stops there.

use super::assert_calls::{E_ARRAYS, MAX_ARRAY_ELEMENTS, formal, literal, string_literal};
use super::body::BodyBuilder;
use super::emit::Val;
use crate::elementary::ElemType;
use crate::ir::op::Target;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind, Ident, LiteralValue};

/// One step from a value to a part of it.
#[derive(Clone)]
enum Step {
    /// `[i, j, ...]`.
    Index(Vec<i64>),
    /// `.field`.
    Field(String),
}

/// An elementary part: the steps to it, and its type.
struct Leaf {
    steps: Vec<Step>,
    elem: ElemType,
}

impl BodyBuilder<'_> {
    /// True when `AssertArrayEquals` of a `x` and a `y` is a nested
    /// comparison: one array type (same bounds, same element type) that is
    /// multi-dimensional or holds structures.
    pub(super) fn nested_shape(&self, x: TypeId, y: TypeId) -> bool {
        let (TypeKind::Array { dims: d1, elem: e1 }, TypeKind::Array { dims: d2, elem: e2 }) =
            (&self.types.get(x).kind, &self.types.get(y).kind)
        else {
            return false;
        };
        d1 == d2 && e1 == e2 && (d1.len() > 1 || self.elementary(*e1).is_none())
    }

    /// Emits the comparison of `e` and `a` (both of type `ty`).
    pub(super) fn nested_array_equals(
        &mut self,
        ty: TypeId,
        (e, a): (Expr, Expr),
        message: Expr,
        loc: Expr,
        span: Span,
        want: bool,
    ) -> Val {
        if want {
            self.diags.error(
                E_ARRAYS,
                span,
                "AssertArrayEquals returns no value: call it as a statement",
            );
            return Val::error();
        }
        let mut leaves = Vec::new();
        if !self.leaves(ty, &mut Vec::new(), &mut leaves, span) {
            return Val::error();
        }
        let mut misses = Vec::new();
        for leaf in &leaves {
            let name = format!(
                "{}{}",
                super::assert_calls::ASSERT_EQ_PREFIX,
                leaf.elem.name()
            );
            let mut args = self.eq_args(
                at(&e, &leaf.steps),
                at(&a, &leaf.steps),
                message.clone(),
                loc.clone(),
                None,
            );
            if let Some(last) = args.last_mut() {
                *last = formal("Element", string_literal(&path_text(&leaf.steps), span));
            }
            let ok = self.host_assert(&name, args, span, true);
            if ok.is_error() {
                return ok;
            }
            let s = self.materialize(&ok);
            misses.push(self.branch_on_slot(s, false, Target::UNPATCHED));
        }
        let end = self.block.here();
        for j in misses {
            self.block.patch(j, end);
        }
        self.block.last_def = None;
        Val::None(TypeTable::void())
    }

    /// Collects the elementary leaves of a value of type `ty` reached by
    /// `steps`; E482 when there are too many or one is not elementary.
    fn leaves(
        &mut self,
        ty: TypeId,
        steps: &mut Vec<Step>,
        out: &mut Vec<Leaf>,
        span: Span,
    ) -> bool {
        if let Some(elem) = self.elementary(ty) {
            if out.len() as i64 >= MAX_ARRAY_ELEMENTS {
                self.diags.error(
                    E_ARRAYS,
                    span,
                    format!(
                        "AssertArrayEquals compares arrays of at most {MAX_ARRAY_ELEMENTS} elementary values"
                    ),
                );
                return false;
            }
            out.push(Leaf {
                steps: steps.clone(),
                elem,
            });
            return true;
        }
        match self.types.get(ty).kind.clone() {
            TypeKind::Array { dims, elem } => {
                let total: i64 = dims.iter().map(|d| d.hi - d.lo + 1).product();
                if total > MAX_ARRAY_ELEMENTS {
                    self.diags.error(
                        E_ARRAYS,
                        span,
                        format!(
                            "AssertArrayEquals compares arrays of at most {MAX_ARRAY_ELEMENTS} elements"
                        ),
                    );
                    return false;
                }
                let mut idx: Vec<i64> = dims.iter().map(|d| d.lo).collect();
                for _ in 0..total {
                    steps.push(Step::Index(idx.clone()));
                    let ok = self.leaves(elem, steps, out, span);
                    steps.pop();
                    if !ok {
                        return false;
                    }
                    // Next index, the last dimension fastest.
                    for k in (0..idx.len()).rev() {
                        if idx[k] < dims[k].hi {
                            idx[k] += 1;
                            break;
                        }
                        idx[k] = dims[k].lo;
                    }
                }
                true
            }
            TypeKind::Struct { fields } => {
                for f in fields {
                    steps.push(Step::Field(f.name.clone()));
                    let ok = self.leaves(f.ty, steps, out, span);
                    steps.pop();
                    if !ok {
                        return false;
                    }
                }
                true
            }
            _ => {
                let name = self.types.name(ty).to_string();
                self.diags.error(
                    E_ARRAYS,
                    span,
                    format!(
                        "AssertArrayEquals compares arrays of elementary values and of structures of them, not of {name}"
                    ),
                );
                false
            }
        }
    }
}

/// `x` followed by `steps`, as an expression.
fn at(x: &Expr, steps: &[Step]) -> Expr {
    let mut e = x.clone();
    for s in steps {
        let span = x.span;
        e = Expr {
            span,
            kind: match s {
                Step::Index(idx) => ExprKind::Index(
                    Box::new(e),
                    idx.iter()
                        .map(|i| literal(LiteralValue::Int(*i as i128), None, span))
                        .collect(),
                ),
                Step::Field(f) => ExprKind::Member(
                    Box::new(e),
                    Ident {
                        name: f.clone(),
                        span,
                    },
                ),
            },
        };
    }
    e
}

/// `[2,3].pos.x`.
fn path_text(steps: &[Step]) -> String {
    let mut s = String::new();
    for step in steps {
        match step {
            Step::Index(idx) => {
                let parts: Vec<String> = idx.iter().map(i64::to_string).collect();
                s.push('[');
                s.push_str(&parts.join(","));
                s.push(']');
            }
            Step::Field(f) => {
                s.push('.');
                s.push_str(f);
            }
        }
    }
    s
}

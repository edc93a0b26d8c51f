//! The unit-test assertions (`AssertEquals`, `AssertTrue`, ...), available
//! when the test runner registered its host functions. A call is checked
//! here (both values of one elementary type, arrays of the same shape) and
//! rewritten into a formal call of one of the runner's typed host functions
//! (`PLCRUN_ASSERT_EQ_INT`, ...), with the call's source position as a
//! hidden argument so a failure can say where it happened.

use super::body::BodyBuilder;
use super::emit::{Ty, Val};
use crate::elementary::ElemType;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Arg, Call, Expr, ExprKind, Ident, Literal, LiteralValue};

/// Host function every test-mode compile declares (its presence switches
/// the assertions on).
pub(crate) const ASSERT_TRUE_HOST: &str = "PLCRUN_ASSERT_TRUE";
/// Prefix of the typed equality host functions (`..._EQ_` + type name).
pub(crate) const ASSERT_EQ_PREFIX: &str = "PLCRUN_ASSERT_EQ_";
/// The equality host function for two values of one enumeration.
pub(crate) const ASSERT_EQ_ENUM_HOST: &str = "PLCRUN_ASSERT_EQ_ENUM";
/// Prefix of TcUnit's `AssertEquals(ANY, ANY)` of two strings (`..._STRING`,
/// `..._WSTRING`): strings of other lengths are reported by their lengths,
/// as TcUnit compares the sizes of ANY values first.
pub(crate) const ASSERT_EQ_ANY_PREFIX: &str = "PLCRUN_ASSERT_EQ_ANY_";
/// TcUnit's LTIME equality: TwinCAT's LTIME is unsigned, so a failure
/// shows the values as unsigned durations.
pub(crate) const TCUNIT_LTIME_HOST: &str = "PLCRUN_ASSERT_EQ_TCUNIT_LTIME";
/// Prefix of the REAL/LREAL with-delta host functions.
pub(crate) const ASSERT_NEAR_PREFIX: &str = "PLCRUN_ASSERT_NEAR_";
/// Called by a TcUnit array assertion before its element comparisons,
/// when the runner declares it (TcUnit's count of array assertions).
pub(crate) const TCUNIT_ARRAY_ASSERT: &str = "PLCRUN_TCUNIT_ARRAY_ASSERT";
/// Largest array `AssertArrayEquals` compares (it unrolls per element).
pub(super) const MAX_ARRAY_ELEMENTS: i64 = 4096;

/// Diagnostic: the two values of an assertion differ in type, or are not elementary.
pub(super) const E_TYPES: &str = "E480";
/// `AssertEquals` of two elementary types: it fails when it runs.
const W_TYPES: &str = "W480";
/// Diagnostic: missing, unknown or repeated assertion argument.
const E_ARGS: &str = "E481";
/// Diagnostic: arrays that `AssertArrayEquals` cannot compare.
pub(super) const E_ARRAYS: &str = "E482";

/// The assertion families.
#[derive(Clone, Copy, PartialEq)]
enum Family {
    Equals,
    Near(ElemType),
    Truth(bool),
    ArrayEquals,
    /// TcUnit's `AssertEquals_<TYPE>`.
    Typed(ElemType),
    /// TcUnit's `AssertArray[2d|3d]Equals_<TYPE>`: the element type and
    /// the number of dimensions.
    TypedArray(ElemType, usize),
}

impl Family {
    fn of(key: &str) -> Option<Family> {
        Some(match key {
            "ASSERTEQUALS" => Family::Equals,
            "ASSERTEQUALS_REAL" => Family::Near(ElemType::Real),
            "ASSERTEQUALS_LREAL" => Family::Near(ElemType::Lreal),
            "ASSERTTRUE" => Family::Truth(true),
            "ASSERTFALSE" => Family::Truth(false),
            "ASSERTARRAYEQUALS" => Family::ArrayEquals,
            _ => match super::assert_tcunit::tcunit_name(key)? {
                (t, None) => Family::Typed(t),
                (t, Some(rank)) => Family::TypedArray(t, rank),
            },
        })
    }

    /// The parameter names in positional order (`Message` is optional).
    fn params(self) -> &'static [&'static str] {
        match self {
            Family::Equals | Family::ArrayEquals | Family::Typed(_) => {
                &["EXPECTED", "ACTUAL", "MESSAGE"]
            }
            Family::Near(_) => &["EXPECTED", "ACTUAL", "DELTA", "MESSAGE"],
            Family::Truth(_) => &["CONDITION", "MESSAGE"],
            Family::TypedArray(t, _) if super::assert_tcunit::has_delta(t) => {
                &["EXPECTEDS", "ACTUALS", "DELTA", "MESSAGE"]
            }
            Family::TypedArray(..) => &["EXPECTEDS", "ACTUALS", "MESSAGE"],
        }
    }
}

/// True when `key` (upper case) names one of the assertions.
pub(super) fn is_assertion_name(key: &str) -> bool {
    Family::of(key).is_some()
}

/// Encodes a call's position for the runner: file in the high half,
/// byte offset in the low half.
pub(crate) fn encode_location(span: Span) -> i64 {
    ((span.file.0 as i64) << 32) | span.start as i64
}

pub(super) fn name_expr(name: &str, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Name(Ident {
            name: name.to_string(),
            span,
        }),
        span,
    }
}

pub(super) fn literal(value: LiteralValue, prefix: Option<&str>, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Literal(Literal {
            value,
            type_prefix: prefix.map(|p| Ident {
                name: p.to_string(),
                span,
            }),
        }),
        span,
    }
}

pub(super) fn formal(name: &str, value: Expr) -> Arg {
    Arg::Input {
        name: Ident {
            name: name.to_string(),
            span: value.span,
        },
        value,
    }
}

impl BodyBuilder<'_> {
    /// Lowers `call` when it is an assertion and test mode is on; `None`
    /// otherwise (the call is resolved as usual).
    pub(super) fn assert_call(&mut self, id: &Ident, call: &Call, want: bool) -> Option<Val> {
        if !self.model.pou_index.contains_key(ASSERT_TRUE_HOST) {
            return None;
        }
        let family = Family::of(&id.key())?;
        // An error is reported here; the call is not resolved again.
        Some(
            self.lower_assert(family, id, call, want)
                .unwrap_or_else(Val::error),
        )
    }

    /// Lowers assertion `call` of `family`; `None` after an error.
    fn lower_assert(&mut self, family: Family, id: &Ident, call: &Call, want: bool) -> Option<Val> {
        let args = self.assert_args(family, id, call)?;
        let span = call.span;
        let loc = literal(
            LiteralValue::Int(encode_location(span) as i128),
            Some("LINT"),
            span,
        );
        let message = args[family.params().len() - 1].clone().unwrap_or_else(|| {
            literal(
                LiteralValue::String {
                    value: String::new(),
                    wide: false,
                },
                None,
                span,
            )
        });
        let (e, a) = (args[0].clone()?, args.get(1).cloned().flatten());
        Some(match (family, a) {
            (Family::Truth(want_true), _) => {
                let expected = literal(LiteralValue::Bool(want_true), None, span);
                let args = vec![
                    formal("Expected", expected),
                    formal("Actual", e),
                    formal("Message", message),
                    formal("Loc", loc),
                ];
                self.host_assert(ASSERT_TRUE_HOST, args, span, want)
            }
            (Family::Near(t), Some(a)) => {
                let name = format!("{ASSERT_NEAR_PREFIX}{}", t.name());
                let delta = args[2].clone()?;
                let mut args = self.eq_args(e, a, message, loc, None);
                args.insert(2, formal("Delta", delta));
                self.host_assert(&name, args, span, want)
            }
            (Family::Typed(t), Some(a)) => {
                let name = self.equality_host(t);
                let args = self.eq_args(e, a, message, loc, None);
                self.host_assert(&name, args, span, want)
            }
            (Family::TypedArray(t, rank), Some(a)) => {
                let delta = if super::assert_tcunit::has_delta(t) {
                    Some(args[2].clone()?)
                } else {
                    None
                };
                self.tcunit_array_equals((t, rank), (e, a), delta, message, loc, span, want)
            }
            (Family::Equals, Some(a)) => {
                if let Some(v) = self.enum_equals(&e, &a, &message, &loc, span, want) {
                    return Some(v);
                }
                // TcUnit's AssertEquals(ANY, ANY) takes two types (plcrun's
                // own tests keep E480).
                let tcunit = self.in_tcunit_run();
                if let Some((x, y)) = self.differing_elementary(&e, &a).filter(|_| tcunit) {
                    return Some(self.differing_types((x, y), message, loc, span, want));
                }
                let t = self.common_elementary(&e, &a, span)?;
                let name = match tcunit && matches!(t, ElemType::String | ElemType::WString) {
                    true => format!("{ASSERT_EQ_ANY_PREFIX}{}", t.name()),
                    false => self.equality_host(t),
                };
                let args = self.eq_args(e, a, message, loc, None);
                self.host_assert(&name, args, span, want)
            }
            (Family::ArrayEquals, Some(a)) => self.array_equals(e, a, message, loc, span, want),
            (_, None) => return None,
        })
    }

    /// The assertion's arguments in parameter order (`None` for an
    /// omitted optional one); `None` after an error.
    fn assert_args(
        &mut self,
        family: Family,
        id: &Ident,
        call: &Call,
    ) -> Option<Vec<Option<Expr>>> {
        let params = family.params();
        let mut out: Vec<Option<Expr>> = vec![None; params.len()];
        for (i, arg) in call.args.iter().enumerate() {
            let (slot, value, span) = match arg {
                Arg::Positional(e) => (Some(i), e, e.span),
                Arg::Input { name, value } => (
                    params.iter().position(|p| *p == name.key()),
                    value,
                    name.span,
                ),
                Arg::Output { name, .. } => (None, &name_expr(&name.name, name.span), name.span),
            };
            match slot.filter(|&s| s < params.len() && out[s].is_none()) {
                Some(s) => out[s] = Some(value.clone()),
                None => {
                    self.diags.error(
                        E_ARGS,
                        span,
                        format!(
                            "`{}` takes ({}): this argument does not fit",
                            id.name,
                            params.join(", ")
                        ),
                    );
                    return None;
                }
            }
        }
        if let Some(missing) = (0..params.len() - 1).find(|&i| out[i].is_none()) {
            self.diags.error(
                E_ARGS,
                call.span,
                format!("`{}` needs its argument `{}`", id.name, params[missing]),
            );
            return None;
        }
        Some(out)
    }

    /// The formal arguments of an equality host function.
    pub(super) fn eq_args(
        &self,
        e: Expr,
        a: Expr,
        message: Expr,
        loc: Expr,
        index: Option<i64>,
    ) -> Vec<Arg> {
        let span = loc.span;
        vec![
            formal("Expected", e),
            formal("Actual", a),
            formal("Message", message),
            formal("Loc", loc),
            formal(
                "IsElement",
                literal(LiteralValue::Bool(index.is_some()), None, span),
            ),
            formal(
                "Index",
                literal(
                    LiteralValue::Int(index.unwrap_or(0) as i128),
                    Some("LINT"),
                    span,
                ),
            ),
            formal("Element", string_literal("", span)),
        ]
    }

    /// Calls host function `name` with `args`.
    pub(super) fn host_assert(
        &mut self,
        name: &str,
        args: Vec<Arg>,
        span: Span,
        want: bool,
    ) -> Val {
        let Some(&p) = self.model.pou_index.get(&name.to_ascii_uppercase()) else {
            self.diags
                .error(E_TYPES, span, format!("no assertion `{name}` is available"));
            return Val::error();
        };
        let call = Call {
            callee: Box::new(name_expr(name, span)),
            args,
            span,
        };
        self.user_function_call(p, &call, want)
    }

    /// The type `e` would have, without emitting its code (as a variable
    /// when `place`: arrays are not values).
    fn probe(&mut self, e: &Expr, place: bool) -> Ty {
        self.probe_in(e, place, None)
    }

    /// [`Self::probe`] where type `want` is expected (a bare enumeration
    /// value takes the enumeration it names a value of).
    pub(super) fn probe_in(&mut self, e: &Expr, place: bool, want: Option<TypeId>) -> Ty {
        let block = self.block.clone();
        let diags = self.diags.len();
        let calls = self.out.calls.len();
        let t = if place {
            self.place(e)
                .map_or(Ty::T(TypeTable::error()), |p| Ty::T(p.ty))
        } else {
            self.expr(e, want).ty()
        };
        self.block = block;
        self.diags.truncate(diags);
        self.out.calls.truncate(calls);
        t
    }

    /// The elementary type both values share (an untyped literal takes the
    /// other's type); reports E480 otherwise (a structure, an array...).
    fn common_elementary(&mut self, e: &Expr, a: &Expr, span: Span) -> Option<ElemType> {
        let (te, ta) = (self.probe(e, false), self.probe(a, false));
        let of = |s: &Self, t: Ty| t.id().map(|id| (id, s.elementary(id)));
        match (of(self, te), of(self, ta)) {
            (Some((_, Some(x))), Some((_, Some(y)))) if x == y => Some(x),
            (Some((_, Some(x))), None) | (None, Some((_, Some(x)))) => Some(x),
            (None, None) => Some(if te == Ty::AnyReal || ta == Ty::AnyReal {
                ElemType::Lreal
            } else {
                ElemType::Lint
            }),
            _ => {
                // Let the values' own errors show first.
                // (An array or a structure is no value, but a variable.)
                let broken = |s: &mut Self, t: Ty, x: &Expr| {
                    t.id().is_some_and(|id| s.is_error(id))
                        && s.probe(x, true).id().is_none_or(|id| s.is_error(id))
                };
                if broken(self, te, e) || broken(self, ta, a) {
                    self.expr(e, None);
                    self.expr(a, None);
                    return None;
                }
                let name = |s: &mut Self, t: Ty, x: &Expr| match t.id() {
                    Some(id) if s.is_error(id) => {
                        let id = s.probe(x, true).id().unwrap_or(id);
                        s.types.name(id).to_string()
                    }
                    Some(id) => s.types.name(id).to_string(),
                    None => "an untyped literal".to_string(),
                };
                let (ne, na) = (name(self, te, e), name(self, ta, a));
                self.diags.error(
                    E_TYPES,
                    span,
                    format!(
                        "AssertEquals compares two values of one elementary type; expected is {ne}, actual is {na}"
                    ),
                );
                None
            }
        }
    }

    /// The host function comparing two values of type `t`: TcUnit's for an
    /// LTIME in a TcUnit run, plcrun's otherwise.
    pub(super) fn equality_host(&self, t: ElemType) -> String {
        if t == ElemType::Ltime && self.in_tcunit_run() {
            return TCUNIT_LTIME_HOST.to_string();
        }
        format!("{ASSERT_EQ_PREFIX}{}", t.name())
    }

    /// True under a TcUnit run: its runner declares the hosts TcUnit's
    /// assertions report to.
    pub(super) fn in_tcunit_run(&self) -> bool {
        self.model.pou_index.contains_key(TCUNIT_ARRAY_ASSERT)
    }

    /// The two elementary types of `e` and `a` when they differ (both
    /// typed): TcUnit's `AssertEquals(ANY, ANY)` takes them, in a TcUnit
    /// suite.
    fn differing_elementary(&mut self, e: &Expr, a: &Expr) -> Option<(ElemType, ElemType)> {
        let (te, ta) = (self.probe(e, false), self.probe(a, false));
        let x = self.elementary(te.id()?)?;
        let y = self.elementary(ta.id()?)?;
        (x != y).then_some((x, y))
    }

    /// `AssertEquals` of values of two elementary types: never equal, so a
    /// failing assertion, as TcUnit's fails when it runs, naming the
    /// types' classes as it does (W480 says so when compiling).
    fn differing_types(
        &mut self,
        (x, y): (ElemType, ElemType),
        message: Expr,
        loc: Expr,
        span: Span,
        want: bool,
    ) -> Val {
        self.diags.warning(
            W_TYPES,
            span,
            format!(
                "AssertEquals of a {} and a {}: values of two types are never equal, so it fails when it runs (as in TcUnit)",
                x.name(),
                y.name()
            ),
        );
        let class = |t: ElemType| string_literal(&format!("(Type class = {})", t.name()), span);
        let args = self.eq_args(class(x), class(y), message, loc, None);
        self.host_assert(&format!("{ASSERT_EQ_PREFIX}STRING"), args, span, want)
    }

    fn is_error(&self, id: TypeId) -> bool {
        matches!(self.types.get(id).kind, TypeKind::Error)
    }

    /// The elementary type of `id` (any STRING length is STRING).
    pub(super) fn elementary(&self, id: TypeId) -> Option<ElemType> {
        match &self.types.get(id).kind {
            TypeKind::Elem(e) => Some(*e),
            TypeKind::Str { wide: false, .. } => Some(ElemType::String),
            TypeKind::Str { wide: true, .. } => Some(ElemType::WString),
            _ => None,
        }
    }

    /// `AssertArrayEquals`: one equality check per element (arrays of one
    /// elementary type with the same bounds).
    fn array_equals(
        &mut self,
        e: Expr,
        a: Expr,
        message: Expr,
        loc: Expr,
        span: Span,
        want: bool,
    ) -> Val {
        let shape = |s: &Self, t: Ty| {
            let id = t.id()?;
            match &s.types.get(id).kind {
                TypeKind::Array { dims, elem } => Some((dims.clone(), s.elementary(*elem))),
                _ => None,
            }
        };
        let (te, ta) = (self.probe(&e, true), self.probe(&a, true));
        let (se, sa) = (shape(self, te), shape(self, ta));
        if let (Some(x), Some(y)) = (te.id(), ta.id())
            && self.nested_shape(x, y)
        {
            return self.nested_array_equals(x, (e, a), message, loc, span, want);
        }
        let (dims, elem) = match (se, sa) {
            (Some((d1, Some(t1))), Some((d2, Some(t2)))) if d1 == d2 && t1 == t2 => (d1, t1),
            _ => {
                let name = |s: &Self, t: Ty| match t.id() {
                    Some(id) => s.types.name(id).to_string(),
                    None => "a literal".to_string(),
                };
                let (ne, na) = (name(self, te), name(self, ta));
                self.diags.error(
                    E_ARRAYS,
                    span,
                    format!(
                        "AssertArrayEquals compares two arrays of one elementary type with the same bounds; expected is {ne}, actual is {na}"
                    ),
                );
                return Val::error();
            }
        };
        let [dim] = dims.as_slice() else {
            self.diags.error(
                E_ARRAYS,
                span,
                "AssertArrayEquals compares one-dimensional arrays",
            );
            return Val::error();
        };
        if dim.hi - dim.lo + 1 > MAX_ARRAY_ELEMENTS {
            self.diags.error(
                E_ARRAYS,
                span,
                format!(
                    "AssertArrayEquals compares arrays of at most {MAX_ARRAY_ELEMENTS} elements"
                ),
            );
            return Val::error();
        }
        let name = format!("{ASSERT_EQ_PREFIX}{}", elem.name());
        for i in dim.lo..=dim.hi {
            let at = |x: &Expr| Expr {
                span: x.span,
                kind: ExprKind::Index(
                    Box::new(x.clone()),
                    vec![literal(LiteralValue::Int(i as i128), None, x.span)],
                ),
            };
            let args = self.eq_args(at(&e), at(&a), message.clone(), loc.clone(), Some(i));
            self.host_assert(&name, args, span, false);
        }
        if want {
            self.diags.error(
                E_ARRAYS,
                span,
                "AssertArrayEquals returns no value: call it as a statement",
            );
            return Val::error();
        }
        Val::None(TypeTable::void())
    }
}

/// A STRING literal `'text'`.
pub(super) fn string_literal(text: &str, span: Span) -> Expr {
    literal(
        LiteralValue::String {
            value: text.to_string(),
            wide: false,
        },
        None,
        span,
    )
}

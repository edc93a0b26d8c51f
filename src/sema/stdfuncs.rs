//! The IEC standard functions: arithmetic, selection, comparison, bit
//! strings, type conversions, time arithmetic and strings. They lower to
//! typed instructions directly (no call overhead).

use super::body::BodyBuilder;
use super::emit::Val;
use super::std_typed_names::Alias;
use crate::elementary::{ElemType, Family};
use crate::ir::op::{MathFn, Op, ShiftKind, StrFn};
use crate::ir::type_table::TypeTable;
use crate::source::Span;
use crate::syntax::ast::{Arg, BinaryOp, Ident};

/// The kinds of standard function.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Std {
    Binary(BinaryOp, bool),
    Move,
    Abs,
    Math(MathFn),
    Trunc(Option<ElemType>),
    Sel,
    MinMax(bool),
    Limit,
    Mux,
    Compare(BinaryOp),
    Shift(ShiftKind),
    Not,
    Convert(Option<ElemType>, ElemType),
    BcdTo(ElemType),
    ToBcd(Option<ElemType>),
    Time(BinaryOp),
    ConcatDateTod,
    Str(StrFn),
    Concat,
    Clock,
}

fn elem(name: &str) -> Option<ElemType> {
    ElemType::from_name(name)
}

fn classify(name: &str) -> Option<Std> {
    let n = name.to_ascii_uppercase();
    classify_own(&n).or_else(|| classify_own(super::std_typed_names::alias(&n)?.target()))
}

/// The compatibility spelling `name` is, when it is not a standard name of
/// its own.
fn compat_alias(name: &str) -> Option<Alias> {
    let n = name.to_ascii_uppercase();
    match classify_own(&n) {
        Some(_) => None,
        None => super::std_typed_names::alias(&n),
    }
}

/// True if argument `i` of typed function `std` is one of its overloaded
/// inputs (fixed to the type in the name): not SEL's G, MUX's K, a
/// shift's N, nor EXPT's exponent.
fn typed_input(std: Std, i: usize) -> bool {
    match std {
        Std::Sel | Std::Mux => i > 0,
        Std::Shift(_) | Std::Binary(BinaryOp::Pow, _) => i == 0,
        _ => true,
    }
}

/// Classifies an upper-case name that is a standard function of its own.
fn classify_own(n: &str) -> Option<Std> {
    use BinaryOp as B;
    let direct = match n {
        "ADD" => Some(Std::Binary(B::Add, true)),
        "MUL" => Some(Std::Binary(B::Mul, true)),
        "SUB" => Some(Std::Binary(B::Sub, false)),
        "DIV" => Some(Std::Binary(B::Div, false)),
        "MOD" => Some(Std::Binary(B::Mod, false)),
        "EXPT" => Some(Std::Binary(B::Pow, false)),
        "AND" => Some(Std::Binary(B::And, true)),
        "OR" => Some(Std::Binary(B::Or, true)),
        "XOR" => Some(Std::Binary(B::Xor, true)),
        "NOT" => Some(Std::Not),
        "MOVE" => Some(Std::Move),
        "ABS" => Some(Std::Abs),
        "SQRT" => Some(Std::Math(MathFn::Sqrt)),
        "LN" => Some(Std::Math(MathFn::Ln)),
        "LOG" => Some(Std::Math(MathFn::Log)),
        "EXP" => Some(Std::Math(MathFn::Exp)),
        "SIN" => Some(Std::Math(MathFn::Sin)),
        "COS" => Some(Std::Math(MathFn::Cos)),
        "TAN" => Some(Std::Math(MathFn::Tan)),
        "ASIN" => Some(Std::Math(MathFn::Asin)),
        "ACOS" => Some(Std::Math(MathFn::Acos)),
        "ATAN" => Some(Std::Math(MathFn::Atan)),
        "TRUNC" => Some(Std::Trunc(None)),
        "SEL" => Some(Std::Sel),
        "MAX" => Some(Std::MinMax(true)),
        "MIN" => Some(Std::MinMax(false)),
        "LIMIT" => Some(Std::Limit),
        "MUX" => Some(Std::Mux),
        "GT" => Some(Std::Compare(B::Gt)),
        "GE" => Some(Std::Compare(B::Ge)),
        "EQ" => Some(Std::Compare(B::Eq)),
        "LE" => Some(Std::Compare(B::Le)),
        "LT" => Some(Std::Compare(B::Lt)),
        "NE" => Some(Std::Compare(B::Ne)),
        "SHL" => Some(Std::Shift(ShiftKind::Shl)),
        "SHR" => Some(Std::Shift(ShiftKind::Shr)),
        "ROL" => Some(Std::Shift(ShiftKind::Rol)),
        "ROR" => Some(Std::Shift(ShiftKind::Ror)),
        "ADD_TIME" | "ADD_LTIME" | "ADD_TOD_TIME" | "ADD_DT_TIME" | "ADD_LTOD_LTIME"
        | "ADD_LDT_LTIME" => Some(Std::Time(B::Add)),
        "SUB_TIME" | "SUB_LTIME" | "SUB_DATE_DATE" | "SUB_TOD_TIME" | "SUB_TOD_TOD"
        | "SUB_DT_TIME" | "SUB_DT_DT" | "SUB_LDATE_LDATE" | "SUB_LTOD_LTIME" | "SUB_LTOD_LTOD"
        | "SUB_LDT_LTIME" | "SUB_LDT_LDT" => Some(Std::Time(B::Sub)),
        "MUL_TIME" | "MUL_LTIME" => Some(Std::Time(B::Mul)),
        "DIV_TIME" | "DIV_LTIME" => Some(Std::Time(B::Div)),
        "CONCAT_DATE_TOD" | "CONCAT_LDATE_LTOD" => Some(Std::ConcatDateTod),
        "LEN" => Some(Std::Str(StrFn::Len)),
        "LEFT" => Some(Std::Str(StrFn::Left)),
        "RIGHT" => Some(Std::Str(StrFn::Right)),
        "MID" => Some(Std::Str(StrFn::Mid)),
        "INSERT" => Some(Std::Str(StrFn::Insert)),
        "DELETE" => Some(Std::Str(StrFn::Delete)),
        "REPLACE" => Some(Std::Str(StrFn::Replace)),
        "FIND" => Some(Std::Str(StrFn::Find)),
        "__PLCRUN_JSON_OF_SYMBOL" => Some(Std::Str(StrFn::JsonOfSymbol)),
        "__PLCRUN_SYMBOL_FROM_JSON" => Some(Std::Str(StrFn::SymbolFromJson)),
        "CONCAT" => Some(Std::Concat),
        "PLC_CLOCK" => Some(Std::Clock),
        _ => None,
    };
    if direct.is_some() {
        return direct;
    }
    if let Some(to) = n.strip_prefix("TRUNC_").and_then(elem) {
        return to.is_int().then_some(Std::Trunc(Some(to)));
    }
    if let Some((from, to)) = n.split_once("_TRUNC_") {
        let (f, t) = (elem(from)?, elem(to)?);
        return (f.is_real() && t.is_int()).then_some(Std::Trunc(Some(t)));
    }
    if let Some(to) = n.strip_prefix("BCD_TO_").and_then(elem) {
        return to.is_int().then_some(Std::BcdTo(to));
    }
    if let Some((from, to)) = n.split_once("_BCD_TO_") {
        let (f, t) = (elem(from)?, elem(to)?);
        return (f.family() == Family::Bits && t.is_int()).then_some(Std::BcdTo(t));
    }
    if let Some(from) = n.strip_suffix("_TO_BCD") {
        return elem(from).filter(|e| e.is_int()).map(|_| Std::ToBcd(None));
    }
    if let Some((from, to)) = n.split_once("_TO_BCD_") {
        let (f, t) = (elem(from)?, elem(to)?);
        return (f.is_int() && t.family() == Family::Bits).then_some(Std::ToBcd(Some(t)));
    }
    if let Some(to) = n.strip_prefix("TO_").and_then(elem) {
        return Some(Std::Convert(None, to));
    }
    if let Some((from, to)) = n.split_once("_TO_") {
        return Some(Std::Convert(Some(elem(from)?), elem(to)?));
    }
    None
}

/// True if `name` is a standard function (or a plcrun extension function).
pub fn is_standard_function(name: &str) -> bool {
    classify(name).is_some()
}

/// Formal parameter names of a standard function, in positional order.
fn param_names(std: Std, n: usize) -> Vec<String> {
    let ins = |n: usize| (1..=n).map(|i| format!("IN{i}")).collect::<Vec<_>>();
    let v = |x: &[&str]| x.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    match std {
        Std::Binary(_, true) | Std::MinMax(_) | Std::Compare(_) | Std::Concat => ins(n.max(2)),
        Std::Binary(_, false) | Std::Time(_) | Std::ConcatDateTod => ins(2),
        Std::Sel => v(&["G", "IN0", "IN1"]),
        Std::Limit => v(&["MN", "IN", "MX"]),
        Std::Mux => {
            let mut p = v(&["K"]);
            p.extend((0..n.saturating_sub(1)).map(|i| format!("IN{i}")));
            p
        }
        Std::Shift(_) => v(&["IN", "N"]),
        Std::Str(StrFn::Len) => v(&["IN"]),
        Std::Str(StrFn::Left | StrFn::Right) => v(&["IN", "L"]),
        Std::Str(StrFn::Mid | StrFn::Delete) => v(&["IN", "L", "P"]),
        Std::Str(StrFn::Insert) => v(&["IN1", "IN2", "P"]),
        Std::Str(StrFn::Replace) => v(&["IN1", "IN2", "L", "P"]),
        Std::Str(StrFn::Find) => v(&["IN1", "IN2"]),
        Std::Str(StrFn::Concat) => ins(2),
        Std::Str(StrFn::JsonOfSymbol) => v(&["DATATYPE", "PDATA"]),
        Std::Str(StrFn::SymbolFromJson) => v(&["JSON", "DATATYPE", "PDATA"]),
        Std::Clock => Vec::new(),
        _ => v(&["IN"]),
    }
}

/// The names CODESYS and TwinCAT give the string functions' inputs
/// (`CONCAT(STR1, STR2)`, `MID(STR, LEN, POS)`...), position by position
/// as [`param_names`]; `None` for the other functions.
fn codesys_param_names(std: Std, n: usize) -> Option<Vec<String>> {
    let v = |x: &[&str]| x.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    Some(match std {
        Std::Concat | Std::Str(StrFn::Concat) => {
            (1..=n.max(2)).map(|i| format!("STR{i}")).collect()
        }
        Std::Str(StrFn::Len) => v(&["STR"]),
        Std::Str(StrFn::Left | StrFn::Right) => v(&["STR", "SIZE"]),
        Std::Str(StrFn::Mid | StrFn::Delete) => v(&["STR", "LEN", "POS"]),
        Std::Str(StrFn::Insert) => v(&["STR1", "STR2", "POS"]),
        Std::Str(StrFn::Replace) => v(&["STR1", "STR2", "L", "P"]),
        Std::Str(StrFn::Find) => v(&["STR1", "STR2"]),
        _ => return None,
    })
}

impl BodyBuilder<'_> {
    /// The position of formal input `name` of standard function `std`:
    /// its IEC name, or the name CODESYS gives it (W359).
    fn std_input_position(
        &mut self,
        std: Std,
        n: usize,
        names: &[String],
        name: &Ident,
    ) -> Option<usize> {
        if let Some(k) = names
            .iter()
            .position(|x| x.eq_ignore_ascii_case(&name.name))
        {
            return Some(k);
        }
        let k = codesys_param_names(std, n)?
            .iter()
            .position(|x| x.eq_ignore_ascii_case(&name.name))?;
        self.diags.warning(
            "W359",
            name.span,
            format!(
                "`{}` is CODESYS's name for this input; IEC 61131-3 calls it `{}`",
                name.name, names[k]
            ),
        );
        Some(k)
    }

    /// E404: the parameter at one position given twice (once by name,
    /// once by position).
    fn std_argument_twice(&mut self, fname: &str, param: Option<&String>, span: Span) {
        let which = param.map_or(String::new(), |p| format!(" `{p}`"));
        self.diags.error(
            "E404",
            span,
            format!("{fname}'s parameter{which} is given twice (by name and by position)"),
        );
    }

    /// Checks and emits a call of a standard function; `None` if `id` is not one.
    pub(super) fn std_call(
        &mut self,
        id: &Ident,
        args: &[Arg],
        span: Span,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Option<Val> {
        if args.is_empty() && id.name.eq_ignore_ascii_case("TIME") {
            return Some(self.codesys_time_call(span));
        }
        let std = classify(&id.name)?;
        let fname = id.name.to_ascii_uppercase();
        // Order the argument expressions by parameter.
        let names = param_names(std, args.len());
        let mut exprs: Vec<Option<&crate::syntax::ast::Expr>> = vec![None; names.len()];
        let formal = args.iter().any(|a| !matches!(a, Arg::Positional(_)));
        if formal && args.iter().any(|a| matches!(a, Arg::Positional(_))) {
            // TwinCAT accepts `FIND(STR1 := s, '.')` (TcUnit): a standard
            // function's parameters have a fixed order, so each positional
            // argument takes the parameter at its own position.
            self.diags.warning(
                "W487",
                span,
                format!("positional and formal arguments mixed in a call of `{fname}` (a CODESYS extension): each positional one goes to the parameter at its position"),
            );
        }
        for (i, a) in args.iter().enumerate() {
            match a {
                Arg::Positional(e) => {
                    if exprs.get(i).is_some_and(|x| x.is_some()) {
                        self.std_argument_twice(&fname, names.get(i), e.span);
                        return Some(Val::error());
                    }
                    if i < exprs.len() {
                        exprs[i] = Some(e);
                    } else {
                        exprs.push(Some(e));
                    }
                }
                Arg::Input { name, value } => {
                    match self.std_input_position(std, args.len(), &names, name) {
                        Some(k) if exprs[k].is_some() => {
                            self.std_argument_twice(&fname, names.get(k), name.span);
                            return Some(Val::error());
                        }
                        Some(k) => exprs[k] = Some(value),
                        None => {
                            self.diags.error(
                                "E403",
                                name.span,
                                format!("{fname} has no input `{}`", name.name),
                            );
                            return Some(Val::error());
                        }
                    }
                }
                Arg::Output { name, .. } => {
                    self.diags.error(
                        "E403",
                        name.span,
                        format!("{fname} has no output `{}`", name.name),
                    );
                    return Some(Val::error());
                }
            }
        }
        let extensible = matches!(
            std,
            Std::Binary(_, true) | Std::MinMax(_) | Std::Compare(_) | Std::Concat | Std::Mux
        );
        let min = match std {
            Std::Clock => 0,
            Std::Mux => 2,
            _ if extensible => 2,
            _ => names.len(),
        };
        let given: Vec<&crate::syntax::ast::Expr> = exprs.iter().flatten().copied().collect();
        if given.len() < min
            || (!extensible && given.len() != names.len())
            || given.len() != exprs.len()
        {
            let expected = if extensible {
                format!("at least {min}")
            } else {
                names.len().to_string()
            };
            self.diags.error(
                "E404",
                span,
                format!(
                    "{fname} takes {expected} argument(s), {} given",
                    given.len()
                ),
            );
            return Some(Val::error());
        }
        let typed = self.compat_name_warning(id, span);
        // Evaluate in order.
        let mut vals: Vec<(Val, Span)> = Vec::new();
        for (i, e) in given.iter().enumerate() {
            let fixed = typed.filter(|_| typed_input(std, i)).map(TypeTable::elem);
            let hint = match std {
                _ if fixed.is_some() => fixed,
                // SEL's G and MUX's K are not of the result's type.
                Std::Sel | Std::Mux if i == 0 => None,
                Std::Binary(..)
                | Std::MinMax(_)
                | Std::Move
                | Std::Sel
                | Std::Limit
                | Std::Mux
                | Std::Abs
                | Std::Not => expect,
                Std::Shift(_) if i == 0 => expect,
                // `INT_TO_WORD(TRUNC(x))`: the argument is an INT.
                Std::Convert(Some(from), _) => Some(TypeTable::elem(from)),
                _ => None,
            };
            let mut v = self.expr(e, hint);
            if let Some(t) = fixed {
                v = self.coerce(v, t, e.span, &fname);
            }
            if v.is_error() {
                return Some(Val::error());
            }
            vals.push((v, e.span));
        }
        let expect = match (typed, std) {
            (Some(_), Std::Compare(_)) | (None, _) => expect,
            (Some(t), _) => Some(TypeTable::elem(t)),
        };
        Some(self.std_emit(std, &fname, vals, span, expect))
    }

    /// Warns (W340 typed, W341 edition 1) about a compatibility spelling of a standard function
    /// and returns the type a typed name (`ADD_INT`) fixes.
    fn compat_name_warning(&mut self, id: &Ident, span: Span) -> Option<ElemType> {
        let alias = compat_alias(&id.name)?;
        let (code, msg, ty) = match alias {
            Alias::Typed { generic, ty } => (
                "W340",
                format!(
                    "`{}` is a typed name of the standard function {generic} (matiec); edition 3 writes {generic} with {ty} arguments",
                    id.name
                ),
                Some(ty),
            ),
            Alias::Legacy { current } => (
                "W341",
                format!(
                    "`{}` is the edition-1 name of the standard function {current}",
                    id.name
                ),
                None,
            ),
        };
        let at = if id.span.end > id.span.start {
            id.span
        } else {
            span
        };
        self.diags.warning(code, at, msg);
        ty
    }

    /// Emits standard function `std` on its evaluated arguments.
    fn std_emit(
        &mut self,
        std: Std,
        fname: &str,
        mut vals: Vec<(Val, Span)>,
        span: Span,
        expect: Option<crate::ir::type_table::TypeId>,
    ) -> Val {
        match std {
            Std::Binary(op, _) | Std::Time(op) => self.std_fold_binary(op, vals, span),
            Std::Move => vals.remove(0).0,
            Std::Not => self.std_not(vals),
            Std::Abs => self.std_abs(vals),
            Std::Math(m) => self.std_math(m, vals, fname),
            Std::Trunc(to) => self.std_trunc(to, vals, expect),
            Std::Sel => self.std_sel(vals, fname, span, expect),
            Std::MinMax(max) => self.std_min_max(max, vals, fname, span, expect),
            Std::Limit => self.std_limit(vals, fname, span, expect),
            Std::Mux => self.std_mux(vals, fname, span, expect),
            Std::Compare(op) => self.std_compare(op, vals, span),
            Std::Shift(kind) => self.std_shift(kind, vals, fname, span),
            Std::Convert(from, to) => self.std_convert(from, to, vals, fname),
            Std::BcdTo(to) => {
                let to = self.bcd_result_type(fname, to, expect, span);
                self.std_bcd_to(to, vals, fname)
            }
            Std::ToBcd(to) => {
                let bits = vals
                    .first()
                    .and_then(|(v, _)| v.ty().id())
                    .and_then(|t| self.scalar(t));
                let to = self.bcd_target_type(fname, to, bits.map(|e| e.bits()), expect, span);
                self.std_to_bcd(to, vals, fname)
            }
            Std::ConcatDateTod => self.std_concat_date_tod(vals, fname, span),
            Std::Clock => self.clock_value(),
            Std::Concat => self.std_concat(vals, fname),
            Std::Str(func) => self.string_fn(func, vals, fname),
        }
    }

    /// CODESYS's `TIME()`: the PLC's clock as TIME, the same value as
    /// PLC_CLOCK (in virtual time, the time the timers see).
    fn codesys_time_call(&mut self, span: Span) -> Val {
        self.diags.warning(
            "W354",
            span,
            "`TIME()` (the PLC's clock) is a CODESYS extension; PLC_CLOCK() is plcrun's name for it",
        );
        self.clock_value()
    }

    /// The task's clock now, as TIME.
    fn clock_value(&mut self) -> Val {
        let d = self.block.temp();
        self.block.emit(Op::Clock { d });
        Val::Slot(d, TypeTable::elem(ElemType::Time))
    }
}

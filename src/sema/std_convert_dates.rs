//! Conversions the edition-3 tables leave out but CODESYS and matiec code
//! uses (OSCAT: `DT_TO_DWORD`, `DWORD_TO_TOD`, `TOD_TO_TIME`, ...), and
//! REAL/LREAL to BOOL. A date or time of day converts to and from numbers
//! through a count: DATE and DT count seconds since 1970-01-01 (rounded
//! down), TOD counts milliseconds since midnight, and the long forms
//! LDATE, LDT and LTOD count nanoseconds. The count converts like a LINT.

use super::body::BodyBuilder;
use super::emit::{Ty, Val};
use crate::elementary::{ElemType as E, Family};
use crate::ir::op::Conv;
use crate::ir::type_table::TypeTable;
use crate::source::Span;

/// True for the types that convert like an integer (BOOL and CHAR by
/// their code).
fn int_like(t: E) -> bool {
    matches!(
        t.family(),
        Family::Signed | Family::Unsigned | Family::Bits | Family::Bool | Family::Char
    )
}

/// `v` with the same bits read as type `t`.
fn retyped(v: Val, t: E) -> Val {
    let rt = TypeTable::elem(t);
    match v {
        Val::Const(c, _) => Val::Const(c, Ty::T(rt)),
        Val::Slot(s, _) => Val::Slot(s, rt),
        other => other,
    }
}

/// What a date or time of day counts when converted to a number.
fn unit(t: E) -> &'static str {
    match t {
        E::Date | E::Dt => "seconds since 1970-01-01",
        E::Tod => "milliseconds since midnight",
        E::Ldate | E::Ldt => "nanoseconds since 1970-01-01",
        _ => "nanoseconds since midnight",
    }
}

impl BodyBuilder<'_> {
    /// `FROM_TO_TO` for the pairs beyond the edition-3 tables; `None` when
    /// (`from`, `to`) is not one of them. Warns W346 for the date and
    /// time ones.
    pub(super) fn extra_convert(
        &mut self,
        v: &Val,
        from: E,
        to: E,
        span: Span,
        fname: &str,
    ) -> Option<Val> {
        let (ff, tf) = (from.family(), to.family());
        if to == E::Bool && ff == Family::Real {
            let conv = if from == E::Real {
                Conv::F32ToBool
            } else {
                Conv::F64ToBool
            };
            return Some(self.apply_conv(v.clone(), conv, to, span));
        }
        let dated = |f: Family| f == Family::DateTime;
        let timed = |f: Family| f == Family::Duration;
        let to_number = (int_like(to) || tf == Family::Real) && to != E::Bool;
        let from_number = int_like(from) || ff == Family::Real;
        let tod = |t: E| matches!(t, E::Tod | E::Ltod);
        let out = if to == E::Bool && (dated(ff) || timed(ff)) {
            self.compat_conversion(fname, span, "a date or a time is TRUE unless it is zero");
            self.apply_conv(v.clone(), Conv::ToBool, to, span)
        } else if dated(ff) && to_number {
            self.compat_conversion(fname, span, &format!("{from} counts {}", unit(from)));
            let count = self.date_count(v.clone(), from, span);
            self.convert(count, E::Lint, to, span, fname)
        } else if from_number && dated(tf) {
            self.compat_conversion(fname, span, &format!("the number counts {}", unit(to)));
            let count = self.convert(v.clone(), from, E::Lint, span, fname);
            self.date_from_count(count, to, span)
        } else if tod(from) && timed(tf) {
            self.compat_conversion(fname, span, "the time since midnight");
            retyped(v.clone(), to)
        } else if timed(ff) && tod(to) {
            self.compat_conversion(
                fname,
                span,
                "the time of day the duration reaches from midnight, wrapped around midnight",
            );
            self.apply_conv(v.clone(), Conv::DtToTod, to, span)
        } else {
            return None;
        };
        Some(out)
    }

    /// W346: a conversion CODESYS defines and edition 3 does not.
    fn compat_conversion(&mut self, fname: &str, span: Span, meaning: &str) {
        self.diags.warning(
            "W346",
            span,
            format!("{fname} is a CODESYS conversion beyond IEC 61131-3 edition 3: {meaning}"),
        );
    }

    /// The count a date or time of day converts as (a LINT value).
    fn date_count(&mut self, v: Val, from: E, span: Span) -> Val {
        match from {
            E::Date | E::Dt => self.apply_conv(v, Conv::NsToSecs, E::Lint, span),
            E::Tod => self.apply_conv(v, Conv::NsToMsS(0), E::Lint, span),
            _ => retyped(v, E::Lint),
        }
    }

    /// The date or time of day `to` of LINT count `n` (a time of day wraps
    /// around midnight, a date is rounded down to its midnight).
    fn date_from_count(&mut self, n: Val, to: E, span: Span) -> Val {
        if n.is_error() {
            return n;
        }
        let ns = match to {
            E::Date | E::Dt => self.apply_conv(n, Conv::SecsToNs, to, span),
            E::Tod => self.apply_conv(n, Conv::MsToNsS, to, span),
            _ => retyped(n, to),
        };
        match to {
            E::Date | E::Ldate => self.apply_conv(ns, Conv::DtToDate, to, span),
            E::Tod | E::Ltod => self.apply_conv(ns, Conv::DtToTod, to, span),
            _ => ns,
        }
    }
}

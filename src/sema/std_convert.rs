//! The type conversion standard functions: `*_TO_*`, BCD, and the
//! conversion instructions they lower to (folded for constants).

use super::body::BodyBuilder;
use super::consts::Const;
use super::emit::{Ty, Val};
use crate::elementary::{ElemType, Family};
use crate::ir::op::{Conv, Op};
use crate::ir::type_table::TypeTable;
use crate::source::Span;

impl BodyBuilder<'_> {
    /// `*_TO_*` conversions (the source type from the name or the argument).
    pub(super) fn std_convert(
        &mut self,
        from: Option<ElemType>,
        to: ElemType,
        mut vals: Vec<(Val, Span)>,
        fname: &str,
    ) -> Val {
        let (v, s) = vals.remove(0);
        let actual = match v.ty() {
            Ty::T(t) => self.scalar(t),
            Ty::AnyInt => from.or(Some(ElemType::Lint)),
            Ty::AnyReal => from.or(Some(ElemType::Lreal)),
        };
        let Some(actual) = actual else {
            self.diags
                .error("E302", s, format!("{fname} cannot convert this value"));
            return Val::error();
        };
        let from = from.unwrap_or(actual);
        let v = self.coerce(v, TypeTable::elem(from), s, fname);
        if v.is_error() {
            return v;
        }
        self.convert(v, from, to, s, fname)
    }

    /// `BCD_TO_*`: a BCD bit string to an integer.
    pub(super) fn std_bcd_to(
        &mut self,
        to: ElemType,
        mut vals: Vec<(Val, Span)>,
        fname: &str,
    ) -> Val {
        let (v, s) = vals.remove(0);
        let is_bits = v
            .ty()
            .id()
            .and_then(|t| self.scalar(t))
            .is_some_and(|e| e.family() == Family::Bits);
        if !is_bits {
            self.diags.error(
                "E302",
                s,
                format!("{fname} needs a bit string (BYTE, WORD, ...)"),
            );
            return Val::error();
        }
        let x = self.apply_conv(v, Conv::FromBcd, ElemType::Ulint, s);
        self.convert(x, ElemType::Ulint, to, s, fname)
    }

    /// `*_TO_BCD`: an integer to a BCD bit string.
    pub(super) fn std_to_bcd(
        &mut self,
        to: Option<ElemType>,
        mut vals: Vec<(Val, Span)>,
        fname: &str,
    ) -> Val {
        let (v, s) = vals.remove(0);
        let Some(from) = v
            .ty()
            .id()
            .and_then(|t| self.scalar(t))
            .filter(|e| e.is_int())
            .or(if v.ty() == Ty::AnyInt {
                Some(ElemType::Lint)
            } else {
                None
            })
        else {
            self.diags
                .error("E302", s, format!("{fname} needs an integer"));
            return Val::error();
        };
        let to = to.unwrap_or(match from.bits() {
            8 => ElemType::Byte,
            16 => ElemType::Word,
            32 => ElemType::Dword,
            _ => ElemType::Lword,
        });
        let v = self.coerce(v, TypeTable::elem(from), s, fname);
        self.apply_conv(v, Conv::ToBcd(to.bits() as u8), to, s)
    }

    /// Applies a conversion instruction (folding constants at compile time).
    pub(super) fn apply_conv(&mut self, v: Val, conv: Conv, to: ElemType, span: Span) -> Val {
        let rt = TypeTable::elem(to);
        if let Val::Const(Const::Bits(b), _) = v {
            return match crate::value::convert::convert(conv, b) {
                Ok(r) => Val::Const(Const::Bits(r), Ty::T(rt)),
                Err(k) => {
                    self.diags
                        .error("E305", span, format!("constant conversion fails: {k}"));
                    Val::error()
                }
            };
        }
        let a = self.materialize(&v);
        let d = self.block.temp();
        self.block.emit(Op::Convert { d, a, conv });
        Val::Slot(d, rt)
    }

    /// `FROM_TO_TO` conversion of a value already of type `from`.
    pub(super) fn convert(
        &mut self,
        v: Val,
        from: ElemType,
        to: ElemType,
        span: Span,
        fname: &str,
    ) -> Val {
        use ElemType as E;
        let rt = TypeTable::elem(to);
        let shift = super::typeck::shift_of(to);
        let (ff, tf) = (from.family(), to.family());
        let int_like = |fam: Family| {
            matches!(
                fam,
                Family::Signed | Family::Unsigned | Family::Bits | Family::Bool | Family::Char
            )
        };
        if from == to {
            return match v {
                Val::Const(c, _) => Val::Const(c, Ty::T(rt)),
                Val::Slot(s, _) => Val::Slot(s, rt),
                other => other,
            };
        }
        if to.is_string() {
            if from.is_string() {
                let s = self.materialize(&v);
                let d = self.string_temp(254, to == E::WString);
                self.block.emit(Op::StrMov { d, s });
                return Val::Slot(d, rt);
            }
            let a = self.materialize(&v);
            let idx = self.out.scalar_index(from);
            let d = self.string_temp(254, to == E::WString);
            self.block.emit(Op::ToStr { d, a, ty: idx });
            return Val::Slot(d, rt);
        }
        if from.is_string() {
            let a = self.materialize(&v);
            let idx = self.out.scalar_index(to);
            let d = self.block.temp();
            self.block.emit(Op::FromStr { d, a, ty: idx });
            return Val::Slot(d, rt);
        }
        if let Some(v) = self.extra_convert(&v, from, to, span, fname) {
            return v;
        }
        let conv = match (ff, tf) {
            _ if to == E::Bool && int_like(ff) => Some(Conv::ToBool),
            (a, b) if int_like(a) && int_like(b) => {
                let binary = a == Family::Bits || b == Family::Bits;
                if from.widens_to(to) || (from == E::Bool) {
                    None
                } else if binary {
                    // Bit strings convert as bit patterns (IEC: binary transfer).
                    if to.is_signed_int() {
                        Some(Conv::WrapS(shift))
                    } else {
                        Some(Conv::WrapU(shift))
                    }
                } else if to.is_signed_int() {
                    // Between integers the value must fit (semantics §3).
                    if from == E::Ulint && !self.cut_like_codesys(span) {
                        // CheckS reads the slot as signed: a ULINT of 2^63
                        // or more must fail before it looks negative.
                        let v = self.apply_conv(v, Conv::CheckU(1), E::Lint, span);
                        return self.apply_conv(v, Conv::CheckS(shift), to, span);
                    }
                    Some(Conv::CheckS(shift))
                } else if from.is_signed_int() {
                    Some(Conv::CheckSToU(shift))
                } else {
                    Some(Conv::CheckU(shift))
                }
            }
            (a, Family::Real) if int_like(a) => Some(match (from.is_signed_int(), to) {
                (true, E::Real) => Conv::SToF32,
                (true, _) => Conv::SToF64,
                (false, E::Real) => Conv::UToF32,
                (false, _) => Conv::UToF64,
            }),
            (Family::Real, b) if int_like(b) && to != E::Bool => {
                Some(match (from, to.is_signed_int()) {
                    (E::Real, true) => Conv::F32ToS(shift),
                    (E::Real, false) => Conv::F32ToU(shift),
                    (_, true) => Conv::F64ToS(shift),
                    (_, false) => Conv::F64ToU(shift),
                })
            }
            (Family::Real, Family::Real) => Some(if from == E::Real {
                Conv::F32ToF64
            } else {
                Conv::F64ToF32
            }),
            (Family::Duration, Family::Duration) => None,
            (Family::Duration, b) if int_like(b) && to != E::Bool => Some(if to.is_signed_int() {
                Conv::NsToMsS(shift)
            } else {
                Conv::NsToMsU(shift)
            }),
            (a, Family::Duration) if int_like(a) => Some(if from.is_signed_int() {
                Conv::MsToNsS
            } else {
                Conv::MsToNsU
            }),
            (Family::Duration, Family::Real) => Some(if to == E::Real {
                Conv::NsToMsF32
            } else {
                Conv::NsToMsF64
            }),
            (Family::Real, Family::Duration) => Some(if from == E::Real {
                Conv::MsF32ToNs
            } else {
                Conv::MsF64ToNs
            }),
            (Family::DateTime, Family::DateTime) => match (from, to) {
                (E::Dt | E::Ldt, E::Date | E::Ldate) => Some(Conv::DtToDate),
                (E::Dt | E::Ldt, E::Tod | E::Ltod) => Some(Conv::DtToTod),
                (E::Date, E::Ldate)
                | (E::Ldate, E::Date)
                | (E::Tod, E::Ltod)
                | (E::Ltod, E::Tod)
                | (E::Dt, E::Ldt)
                | (E::Ldt, E::Dt)
                | (E::Date | E::Ldate, E::Dt | E::Ldt) => None,
                _ => {
                    self.diags
                        .error("E302", span, format!("{fname}: no such conversion"));
                    return Val::error();
                }
            },
            _ => {
                self.diags
                    .error("E302", span, format!("{fname}: no such conversion"));
                return Val::error();
            }
        };
        match conv {
            None => match v {
                Val::Const(c, _) => Val::Const(c, Ty::T(rt)),
                Val::Slot(s, _) => Val::Slot(s, rt),
                other => other,
            },
            Some(c) if self.cut_like_codesys(span) => self.cut_conversion(v, c, to, span),
            Some(c) => self.apply_conv(v, c, to, span),
        }
    }

    /// Conversion `c` of `v` to `to` as CODESYS makes it: an integer that
    /// does not fit keeps its low bits, so does a rounded REAL within
    /// LINT's range (`cut_like_codesys`).
    fn cut_conversion(&mut self, v: Val, c: Conv, to: ElemType, span: Span) -> Val {
        match c {
            Conv::CheckS(sh) => self.apply_conv(v, Conv::WrapS(sh), to, span),
            Conv::CheckU(sh) | Conv::CheckSToU(sh) => self.apply_conv(v, Conv::WrapU(sh), to, span),
            // A REAL rounded to a LINT first (beyond it still R004),
            // then cut to the target's width (`LREAL_TO_UDINT(-1.0)` is
            // 4294967295 on TwinCAT's x64 targets).
            Conv::F32ToS(sh) | Conv::F32ToU(sh) | Conv::F64ToS(sh) | Conv::F64ToU(sh)
                if sh != 0 =>
            {
                let wide = match c {
                    Conv::F32ToS(_) | Conv::F32ToU(_) => Conv::F32ToS(0),
                    _ => Conv::F64ToS(0),
                };
                let lint = self.apply_conv(v, wide, ElemType::Lint, span);
                let wrap = match c {
                    Conv::F32ToS(_) | Conv::F64ToS(_) => Conv::WrapS(sh),
                    _ => Conv::WrapU(sh),
                };
                self.apply_conv(lint, wrap, to, span)
            }
            Conv::NsToMsS(sh) | Conv::NsToMsU(sh) if sh != 0 => {
                let ms = self.apply_conv(v, Conv::NsToMsS(0), ElemType::Lint, span);
                let wrap = match c {
                    Conv::NsToMsS(_) => Conv::WrapS(sh),
                    _ => Conv::WrapU(sh),
                };
                self.apply_conv(ms, wrap, to, span)
            }
            _ => self.apply_conv(v, c, to, span),
        }
    }

    /// Whether an integer conversion written at `span` keeps the low bits
    /// of a value that does not fit, as CODESYS and TwinCAT do
    /// (`TIME_TO_INT(T#60S)` is -5536 there), instead of faulting (R004):
    /// in the files of that dialect (semantics.md §3).
    fn cut_like_codesys(&self, span: Span) -> bool {
        self.model.codesys_files.contains(&span.file)
    }
}

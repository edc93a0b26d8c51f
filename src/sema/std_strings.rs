//! The string standard functions: LEN, LEFT, CONCAT, FIND, ... lowered to
//! `StrCall` with a result of the capacity the arguments need.

use super::body::BodyBuilder;
use super::emit::Val;
use crate::elementary::ElemType;
use crate::ir::op::{Op, StrFn};
use crate::ir::type_table::{TypeKind, TypeTable};
use crate::source::Span;

impl BodyBuilder<'_> {
    /// CONCAT of two or more strings, left to right.
    pub(super) fn std_concat(&mut self, vals: Vec<(Val, Span)>, fname: &str) -> Val {
        let mut acc: Option<(Val, Span)> = None;
        for (v, s) in vals {
            acc = Some(match acc {
                None => (v, s),
                Some((a, _)) => (
                    self.string_fn(StrFn::Concat, vec![(a, s), (v, s)], fname),
                    s,
                ),
            });
        }
        acc.map(|a| a.0).unwrap_or_else(Val::error)
    }

    /// A string function with arguments in consecutive slots.
    pub(super) fn string_fn(&mut self, func: StrFn, vals: Vec<(Val, Span)>, fname: &str) -> Val {
        let is_str = |c: &BodyBuilder, v: &Val| {
            v.ty()
                .id()
                .and_then(|t| c.scalar(t))
                .is_some_and(|e| e.is_string())
        };
        // Which positions are strings.
        let string_pos: &[usize] = match func {
            StrFn::Len | StrFn::Left | StrFn::Right | StrFn::Mid | StrFn::Delete => &[0],
            StrFn::Concat
            | StrFn::Insert
            | StrFn::Replace
            | StrFn::Find
            | StrFn::SymbolFromJson => &[0, 1],
            StrFn::JsonOfSymbol => &[0],
        };
        // The other arguments are counts and positions; a pointer's
        // integer image takes 64 bits.
        let number = match func {
            StrFn::JsonOfSymbol | StrFn::SymbolFromJson => ElemType::Ulint,
            _ => ElemType::Dint,
        };
        let mut wide = false;
        let mut max = 0u32;
        let mut slots = Vec::new();
        for (i, (v, s)) in vals.into_iter().enumerate() {
            if string_pos.contains(&i) {
                if !is_str(self, &v) {
                    let n = self.ty_name(v.ty());
                    self.diags
                        .error("E301", s, format!("{fname}: expected a string, found {n}"));
                    return Val::error();
                }
                if let Some(TypeKind::Str { max: m, wide: w }) =
                    v.ty().id().map(|t| self.types.get(t).kind.clone())
                {
                    max = max.saturating_add(m);
                    wide |= w;
                }
                slots.push(self.materialize(&v));
            } else {
                let v = self.coerce(v, TypeTable::elem(number), s, fname);
                if v.is_error() {
                    return v;
                }
                slots.push(self.materialize(&v));
            }
        }
        let a = self.block.temps(4);
        for (i, s) in slots.into_iter().enumerate() {
            self.block.emit(Op::Mov {
                d: a.offset(i as u32),
                s,
            });
        }
        if matches!(func, StrFn::Len | StrFn::Find | StrFn::SymbolFromJson) {
            let d = self.block.temp();
            self.block.emit(Op::StrCall { d, a, f: func });
            return Val::Slot(d, TypeTable::elem(ElemType::Int));
        }
        let max = match func {
            StrFn::JsonOfSymbol => crate::ir::op::JSON_OF_SYMBOL_MAX,
            _ => max.clamp(1, 65535),
        };
        let d = self.string_temp(max, wide);
        self.block.emit(Op::StrCall { d, a, f: func });
        let t = self.types.intern(crate::ir::type_table::TypeDef {
            name: format!("{}[{max}]", if wide { "WSTRING" } else { "STRING" }),
            kind: TypeKind::Str { wide, max },
            size: 1,
        });
        Val::Slot(d, t)
    }
}

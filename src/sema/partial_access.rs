//! Partial access: a bit, byte, word or double word of a variable, read
//! and written in place (`w.%X3`, `d.%B1`, `l.%W0`, `l.%D1`, and the bit
//! written as a number, `w.3`).
//!
//! IEC 61131-3 edition 3 defines it on the bit strings BYTE..LWORD; CODESYS
//! also accepts it on the integer types, which plcrun does with a
//! compatibility warning (W322). Part `n` of width `w` is bits
//! `n*w .. n*w+w-1`, counted from the least significant bit; a part beyond
//! the variable's width is refused at compile time (E423). The lexer hands
//! `.%B1` over as the member name `%B1` (no identifier starts with `%`).
//!
//! A read is a shift and a mask; a write reads the variable, clears the
//! part, ORs the new value in and writes the whole variable back (signed
//! integers are sign-extended again so the slot stays canonical).

use super::body::BodyBuilder;
use super::consts::{Const, slot_to_int};
use super::emit::Val;
use crate::elementary::ElemType;
use crate::ir::op::{Op, ShiftKind};
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind};

/// The width of a part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PartSize {
    /// `%X`, or `.n`: one bit, a BOOL.
    Bit,
    /// `%B`: a BYTE.
    Byte,
    /// `%W`: a WORD.
    Word,
    /// `%D`: a DWORD.
    Dword,
    /// `%L`: an LWORD.
    Lword,
}

impl PartSize {
    /// Bits in one part.
    fn width(self) -> u32 {
        match self {
            PartSize::Bit => 1,
            PartSize::Byte => 8,
            PartSize::Word => 16,
            PartSize::Dword => 32,
            PartSize::Lword => 64,
        }
    }

    /// The type a part reads as.
    pub(super) fn elem(self) -> ElemType {
        match self {
            PartSize::Bit => ElemType::Bool,
            PartSize::Byte => ElemType::Byte,
            PartSize::Word => ElemType::Word,
            PartSize::Dword => ElemType::Dword,
            PartSize::Lword => ElemType::Lword,
        }
    }

    /// What a part is called in messages.
    fn noun(self) -> &'static str {
        match self {
            PartSize::Bit => "bit",
            PartSize::Byte => "byte",
            PartSize::Word => "word",
            PartSize::Dword => "double word",
            PartSize::Lword => "long word",
        }
    }
}

/// One partial access: which part, and where it is written.
#[derive(Debug, Clone, Copy)]
pub(super) struct PartSel {
    /// Width of the part.
    pub size: PartSize,
    /// Part number (0 = least significant).
    pub index: u64,
    /// The access as written (`w.%B1`).
    pub span: Span,
}

/// Decodes the member name the lexer gives an edition-3 partial access:
/// `%X3`, `%B1`, `%W0`, `%D1`, `%L0` (letters in either case).
pub(super) fn partial_name(name: &str) -> Option<(PartSize, u64)> {
    let rest = name.strip_prefix('%')?;
    let mut chars = rest.chars();
    let size = match chars.next()?.to_ascii_uppercase() {
        'X' => PartSize::Bit,
        'B' => PartSize::Byte,
        'W' => PartSize::Word,
        'D' => PartSize::Dword,
        'L' => PartSize::Lword,
        _ => return None,
    };
    let digits = chars.as_str();
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    // Too many digits to count is beyond every width: reported as such.
    Some((size, digits.parse().unwrap_or(u64::MAX)))
}

/// The variable and the part of a partial access expression (`w.3`,
/// `w.%B1`), or `None` for any other expression.
pub(super) fn part_target(e: &Expr) -> Option<(&Expr, PartSel)> {
    match &e.kind {
        ExprKind::BitAccess(base, bit) => Some((
            base,
            PartSel {
                size: PartSize::Bit,
                index: u64::from(*bit),
                span: e.span,
            },
        )),
        ExprKind::Member(base, name) => {
            let (size, index) = partial_name(&name.name)?;
            Some((
                base,
                PartSel {
                    size,
                    index,
                    span: e.span,
                },
            ))
        }
        _ => None,
    }
}

/// The variable and bit of `v.C`, CODESYS's bit access with an integer
/// constant `C` (`VAR_GLOBAL CONSTANT enable : INT := 2; ... w.enable`),
/// when `v` is a bit string or an integer and `C` no member of it.
fn const_bit(b: &BodyBuilder<'_>, e: &Expr) -> Option<u64> {
    let ExprKind::Member(base, name) = &e.kind else {
        return None;
    };
    let var = b.lookup_var(&name.key())?;
    if !var.constant {
        return None;
    }
    let el = b.scalar(var.ty).filter(|e| e.is_int() || e.is_bit())?;
    let n = match var.value.as_ref()? {
        Const::Int(i) => *i,
        Const::Bits(bits) => slot_to_int(*bits, el),
        _ => return None,
    };
    let base_ty = static_type(b, base)?;
    match b.types.get(base_ty).kind {
        TypeKind::Elem(t) if t.is_int() || (t.is_bit() && t != ElemType::Bool) => {
            Some(u64::try_from(n).unwrap_or(u64::MAX))
        }
        _ => None,
    }
}

/// The type of a variable reference, found without emitting code: names,
/// members and array elements (`None` for anything else).
fn static_type(b: &BodyBuilder<'_>, e: &Expr) -> Option<TypeId> {
    match &e.kind {
        ExprKind::Name(id) => b.lookup_var(&id.key()).map(|v| v.ty),
        ExprKind::Paren(x) => static_type(b, x),
        ExprKind::Index(base, _) => match &b.types.get(static_type(b, base)?).kind {
            TypeKind::Array { elem, .. } => Some(*elem),
            _ => None,
        },
        ExprKind::Member(base, name) => match &b.types.get(static_type(b, base)?).kind {
            TypeKind::Struct { fields: ms } | TypeKind::Pou { members: ms, .. } => ms
                .iter()
                .find(|m| m.name.eq_ignore_ascii_case(&name.name))
                .map(|m| m.ty),
            _ => None,
        },
        _ => None,
    }
}

/// All ones in the low `bits` bits.
fn low_mask(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

impl BodyBuilder<'_> {
    /// The variable and part of a partial access: `w.3`, `w.%B1`, or
    /// `w.C` with an integer constant `C` (CODESYS, W323).
    pub(super) fn part_of<'e>(&mut self, e: &'e Expr) -> Option<(&'e Expr, PartSel)> {
        if let Some(found) = part_target(e) {
            return Some(found);
        }
        let index = const_bit(self, e)?;
        let ExprKind::Member(base, name) = &e.kind else {
            return None;
        };
        self.diags.warning(
            "W323",
            name.span,
            format!(
                "bit access with the constant `{}` is a CODESYS extension (IEC 61131-3 \
                 writes the bit number: `.%X{index}`)",
                name.name
            ),
        );
        Some((
            base,
            PartSel {
                size: PartSize::Bit,
                index,
                span: e.span,
            },
        ))
    }

    /// Reads part `sel` of the value of `base`.
    pub(super) fn read_part(&mut self, base: &Expr, sel: PartSel) -> Val {
        let v = self.expr(base, None);
        if v.is_error() {
            return Val::error();
        }
        let Some(t) = v.ty().id() else {
            self.diags.error(
                "E302",
                sel.span,
                "partial access needs a typed variable, not a literal",
            );
            return Val::error();
        };
        let Some(el) = self.part_base(t, sel) else {
            return Val::error();
        };
        let a = self.materialize(&v);
        let w = sel.size.width();
        let pos = (sel.index as u32) * w;
        let shifted = if pos == 0 {
            a
        } else {
            let n = self.block.const_slot(u64::from(pos));
            let d = self.block.temp();
            self.block.emit(Op::Shift {
                d,
                a,
                b: n,
                kind: ShiftKind::Shr,
                bits: el.bits() as u8,
            });
            d
        };
        if w == 64 {
            return Val::Slot(shifted, TypeTable::elem(sel.size.elem()));
        }
        let mask = self.block.const_slot(low_mask(w));
        let r = self.block.temp();
        self.block.emit(Op::And {
            d: r,
            a: shifted,
            b: mask,
        });
        Val::Slot(r, TypeTable::elem(sel.size.elem()))
    }

    /// Replaces part `sel` of the variable `base` by `v` (read the
    /// variable, clear the part, OR in the new one, write back).
    pub(super) fn store_part(&mut self, base: &Expr, sel: PartSel, v: Val, value_span: Span) {
        let Some(p) = self.place(base) else { return };
        let Some(el) = self.part_base(p.ty, sel) else {
            return;
        };
        if !self.check_writable(&p, sel.span) {
            return;
        }
        let part_ty = TypeTable::elem(sel.size.elem());
        let v = self.coerce(v, part_ty, value_span, "partial access");
        if v.is_error() {
            return;
        }
        let s = self.materialize(&v);
        let Val::Slot(cur, _) = self.read_place(&p) else {
            return;
        };
        let bits = el.bits();
        let w = sel.size.width();
        let pos = (sel.index as u32) * w;
        let field = low_mask(w) << pos;
        let keep = self.block.const_slot(!field & low_mask(bits));
        let cleared = self.block.temp();
        self.block.emit(Op::And {
            d: cleared,
            a: cur,
            b: keep,
        });
        let moved = if pos == 0 {
            s
        } else {
            let n = self.block.const_slot(u64::from(pos));
            let m = self.block.temp();
            self.block.emit(Op::Shift {
                d: m,
                a: s,
                b: n,
                kind: ShiftKind::Shl,
                bits: bits as u8,
            });
            m
        };
        let mut out = self.block.temp();
        self.block.emit(Op::Or {
            d: out,
            a: cleared,
            b: moved,
        });
        if el.is_signed_int() && bits < 64 {
            let ext = self.block.temp();
            self.block.emit(Op::AddSI {
                d: ext,
                a: out,
                imm: 0,
                shift: (64 - bits) as u8,
            });
            out = ext;
        }
        self.write_place(&p, out);
    }

    /// The elementary type of a variable of type `t` that part `sel` is
    /// taken from, checked: a bit string or an integer (E302), wide enough
    /// (E423); on an integer type the access warns (W322).
    fn part_base(&mut self, t: TypeId, sel: PartSel) -> Option<ElemType> {
        let el = match self.types.get(t).kind {
            TypeKind::Elem(e) => Some(e),
            // A bit of an enumeration's base integer, as TwinCAT reads
            // and writes it (`stStatus.eRemote.0 := bRemote;`), W485.
            TypeKind::Enum { base, .. } if self.model.codesys_files.contains(&sel.span.file) => {
                self.enum_to_int_warning(t, base, sel.span);
                Some(base)
            }
            _ => None,
        };
        let Some(el) = el.filter(|e| (e.is_bit() && *e != ElemType::Bool) || e.is_int()) else {
            if t != TypeTable::error() {
                self.diags.error(
                    "E302",
                    sel.span,
                    format!(
                        "partial access needs a bit string (BYTE..LWORD) or an integer, found {}",
                        self.types.name(t)
                    ),
                );
            }
            return None;
        };
        let count = u64::from(el.bits() / sel.size.width());
        if sel.index >= count {
            let noun = sel.size.noun();
            let msg = if count == 0 {
                format!(
                    "a {el} ({} bits) has no {noun}: partial access beyond the variable's width",
                    el.bits()
                )
            } else {
                format!(
                    "{noun} {} does not exist in a {el}: it has {noun}s 0..{} (partial access \
                     beyond the variable's width)",
                    sel.index,
                    count - 1
                )
            };
            self.diags.error("E423", sel.span, msg);
            return None;
        }
        if el.is_int() {
            self.diags.warning(
                "W322",
                sel.span,
                format!(
                    "partial access on the integer type {el} is a CODESYS extension \
                     (IEC 61131-3 defines it on the bit strings BYTE..LWORD)"
                ),
            );
        }
        Some(el)
    }
}

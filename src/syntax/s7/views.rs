//! Reading and writing S7-200 operands in generated code: each area is one
//! array of BYTE (`S7_V` …); a bit is a bit of a byte, a word or double word
//! is composed from (and split into) consecutive bytes, most significant
//! first, so that every view of the same bytes overlaps as on the CPU.
//! Timer and counter current values are INT arrays (`S7_T`, `S7_C`), their
//! bits BOOL arrays (`S7_TB`, `S7_CB`).

use super::build::At;
use super::operands::{Operand, Width};
use crate::syntax::ast::{BinaryOp, Expr, Stmt};

/// Scratch variables the generated code uses to split a value into bytes
/// (a value is computed once, before any of its bytes is written).
pub(super) const SCRATCH_WORD: &str = "S7_W";
/// See [`SCRATCH_WORD`].
pub(super) const SCRATCH_DWORD: &str = "S7_D";

/// Why an operand cannot be used where it is written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum ViewError {
    /// The operand is not of the kind the instruction needs (what it needs).
    Kind(&'static str),
    /// A constant does not fit the width.
    ConstRange(i64, Width),
}

/// The IEC type of a width's unsigned view.
pub(super) fn bits_type(w: Width) -> &'static str {
    match w {
        Width::B => "BYTE",
        Width::W => "WORD",
        Width::D => "DWORD",
    }
}

/// What a width's operand is called in messages.
fn kind_name(w: Width) -> &'static str {
    match w {
        Width::B => "a byte operand (VB, IB, QB, MB, SMB) or a constant",
        Width::W => "a word operand (VW, IW, QW, MW, SMW, T, C) or a constant",
        Width::D => "a double-word operand (VD, ID, QD, MD, SMD) or a constant",
    }
}

/// The constant `v` as the bit pattern of width `w` (signed and unsigned
/// writings both accepted: `-1` and `16#FFFF` are the same word).
pub(super) fn const_bits(v: i64, w: Width) -> Result<i64, ViewError> {
    let bits = 8 * w.bytes();
    let lo = -(1i64 << (bits - 1));
    let hi = (1i64 << bits) - 1;
    if v < lo || v > hi {
        return Err(ViewError::ConstRange(v, w));
    }
    Ok(v & hi)
}

/// The value of `op` read as width `w` (a BYTE, WORD or DWORD expression).
pub(super) fn read(at: At, op: Operand, w: Width) -> Result<Expr, ViewError> {
    match op {
        Operand::Const(v) => Ok(at.typed(bits_type(w), const_bits(v, w)?)),
        Operand::Mem { area, width, addr } if width == w => {
            let conv = match w {
                Width::B => return Ok(at.index(area.image(), addr)),
                Width::W => "BYTE_TO_WORD",
                Width::D => "BYTE_TO_DWORD",
            };
            let n = w.bytes();
            let mut acc: Option<Expr> = None;
            for i in 0..n {
                let byte = at.call(conv, vec![at.index(area.image(), addr + i)]);
                let shift = 8 * (n - 1 - i);
                let part = if shift == 0 {
                    byte
                } else {
                    at.call("SHL", vec![byte, at.int(i64::from(shift))])
                };
                acc = Some(match acc {
                    None => part,
                    Some(a) => at.bin(BinaryOp::Or, a, part),
                });
            }
            Ok(acc.unwrap_or_else(|| at.typed(bits_type(w), 0)))
        }
        Operand::Timer(n) if w == Width::W => Ok(at.call("INT_TO_WORD", vec![at.index("S7_T", n)])),
        Operand::Counter(n) if w == Width::W => {
            Ok(at.call("INT_TO_WORD", vec![at.index("S7_C", n)]))
        }
        _ => Err(ViewError::Kind(kind_name(w))),
    }
}

/// Statements storing `value` (of width `w`'s type) into `op`.
pub(super) fn write(at: At, op: Operand, w: Width, value: Expr) -> Result<Vec<Stmt>, ViewError> {
    match op {
        Operand::Mem { area, width, addr } if width == w => {
            let (scratch, conv) = match w {
                Width::B => return Ok(vec![at.assign(at.index(area.image(), addr), value)]),
                Width::W => (SCRATCH_WORD, "WORD_TO_BYTE"),
                Width::D => (SCRATCH_DWORD, "DWORD_TO_BYTE"),
            };
            let n = w.bytes();
            let mut out = vec![at.assign(at.name(scratch), value)];
            for i in 0..n {
                let shift = 8 * (n - 1 - i);
                let part = if shift == 0 {
                    at.name(scratch)
                } else {
                    at.call("SHR", vec![at.name(scratch), at.int(i64::from(shift))])
                };
                out.push(at.assign(at.index(area.image(), addr + i), at.call(conv, vec![part])));
            }
            Ok(out)
        }
        Operand::Timer(n) if w == Width::W => {
            Ok(vec![at.assign(
                at.index("S7_T", n),
                at.call("WORD_TO_INT", vec![value]),
            )])
        }
        Operand::Counter(n) if w == Width::W => {
            Ok(vec![at.assign(
                at.index("S7_C", n),
                at.call("WORD_TO_INT", vec![value]),
            )])
        }
        _ => Err(ViewError::Kind(match w {
            Width::B => "a byte operand (VB, IB, QB, MB, SMB)",
            Width::W => "a word operand (VW, IW, QW, MW, SMW, T, C)",
            Width::D => "a double-word operand (VD, ID, QD, MD, SMD)",
        })),
    }
}

/// The value of a bit operand (a bit of an area, a timer or counter bit).
pub(super) fn read_bit(at: At, op: Operand) -> Result<Expr, ViewError> {
    match op {
        Operand::Bit { area, byte, bit } => Ok(at.bit(at.index(area.image(), byte), bit)),
        Operand::Timer(n) => Ok(at.index("S7_TB", n)),
        Operand::Counter(n) => Ok(at.index("S7_CB", n)),
        _ => Err(ViewError::Kind(
            "a bit operand (I0.0, Q0.1, M3.7, V6.1, SM0.0, T37, C0)",
        )),
    }
}

/// `op := value` for a bit of an area.
pub(super) fn write_bit(at: At, op: Operand, value: Expr) -> Result<Stmt, ViewError> {
    match op {
        Operand::Bit { area, byte, bit } => {
            Ok(at.assign(at.bit(at.index(area.image(), byte), bit), value))
        }
        _ => Err(ViewError::Kind(
            "a bit of I, Q, M, V or SM (I0.0, Q0.1, M3.7, V6.1)",
        )),
    }
}

/// The signed reading of a width (`WORD_TO_INT` …) and back.
pub(super) fn signed(w: Width) -> (&'static str, &'static str, &'static str) {
    match w {
        Width::B => ("BYTE_TO_USINT", "USINT_TO_BYTE", "USINT"),
        Width::W => ("WORD_TO_INT", "INT_TO_WORD", "INT"),
        Width::D => ("DWORD_TO_DINT", "DINT_TO_DWORD", "DINT"),
    }
}

//! S7-200 operands as STEP 7-Micro/WIN and the older listings write them:
//! bits `I0.0` `Q0.1` `M3.7` `V6.1` `SM0.1`, bytes `VB6`, words `VW10`,
//! double words `VD20`, timers `T37`, counters `C0`, constants (`50`,
//! `+50`, `-5`, `16#0100`, `2#101`, listing form `K50`, `K-5`, `KHFFFF`),
//! and the German areas `E` (inputs) and `A` (outputs).

/// A memory area with a byte image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Area {
    /// Inputs (`I`, German `E`).
    I,
    /// Outputs (`Q`, German `A`).
    Q,
    /// Bit memory `M`.
    M,
    /// Variable memory `V`.
    V,
    /// Special memory `SM`.
    Sm,
}

impl Area {
    /// Every area with a byte image, in declaration order.
    pub(super) const ALL: [Area; 5] = [Area::I, Area::Q, Area::M, Area::V, Area::Sm];

    /// The name of the byte-array variable that holds the area (the runtime's
    /// `s7_names` relies on these names).
    pub(super) fn image(self) -> &'static str {
        match self {
            Area::I => "S7_I",
            Area::Q => "S7_Q",
            Area::M => "S7_M",
            Area::V => "S7_V",
            Area::Sm => "S7_SM",
        }
    }

    /// Number of bytes (the CPU 214's sizes; V as the CPU 214, SM enough
    /// for the system bytes of the CPU 22x).
    pub(super) fn size(self) -> u32 {
        match self {
            Area::I | Area::Q => 16,
            Area::M => 32,
            Area::V => 4096,
            Area::Sm => 200,
        }
    }

    /// The English letter (`I`, `Q`, `M`, `V`, `SM`).
    pub(super) fn letter(self) -> &'static str {
        match self {
            Area::I => "I",
            Area::Q => "Q",
            Area::M => "M",
            Area::V => "V",
            Area::Sm => "SM",
        }
    }
}

/// Access width of a byte-image operand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Width {
    /// One byte (`VB6`).
    B,
    /// One word, two bytes, most significant first (`VW6`).
    W,
    /// One double word, four bytes (`VD6`).
    D,
}

impl Width {
    /// Bytes covered.
    pub(super) fn bytes(self) -> u32 {
        match self {
            Width::B => 1,
            Width::W => 2,
            Width::D => 4,
        }
    }
}

/// Number of timers and of counters (T0..T255, C0..C255).
pub(super) const TIMERS: u32 = 256;

/// A decoded operand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Operand {
    /// A bit of a byte image.
    Bit {
        /// Area.
        area: Area,
        /// Byte address.
        byte: u32,
        /// Bit number, 0 the least significant.
        bit: u8,
    },
    /// A byte, word or double word of a byte image.
    Mem {
        /// Area.
        area: Area,
        /// Width.
        width: Width,
        /// Address of its first (most significant) byte.
        addr: u32,
    },
    /// Timer `Tn`: its bit or its current value, by context.
    Timer(u32),
    /// Counter `Cn`: its bit or its current value, by context.
    Counter(u32),
    /// A constant.
    Const(i64),
}

/// Why an operand text is refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum OperandError {
    /// Not written as any S7-200 operand.
    NotAnOperand,
    /// An S7-200 operand this front-end does not model.
    Unsupported(&'static str),
    /// An address outside its area.
    OutOfRange(String),
}

fn number(s: &str) -> Option<u32> {
    if s.is_empty() || s.len() > 9 || !s.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}

/// A constant: decimal with or without sign, `16#…`, `2#…`, `K…`, `KH…`.
pub(super) fn parse_const(text: &str) -> Option<i64> {
    let t = text.to_ascii_uppercase().replace('_', "");
    let (negative, body) = match t.as_bytes().first()? {
        b'-' => (true, &t[1..]),
        b'+' => (false, &t[1..]),
        _ => (false, t.as_str()),
    };
    let value = if let Some(hex) = body.strip_prefix("16#") {
        i64::from_str_radix(hex, 16).ok()?
    } else if let Some(bin) = body.strip_prefix("2#") {
        i64::from_str_radix(bin, 2).ok()?
    } else if let Some(hex) = body.strip_prefix("KH") {
        i64::from_str_radix(hex, 16).ok()?
    } else if let Some(dec) = body.strip_prefix('K') {
        if negative {
            return None;
        }
        return parse_const(dec);
    } else {
        if body.is_empty() || !body.bytes().all(|b| b.is_ascii_digit()) || body.len() > 12 {
            return None;
        }
        body.parse::<i64>().ok()?
    };
    Some(if negative { -value } else { value })
}

/// The area of an area-letter group, German letters included.
fn area_of(letters: &str) -> Option<Area> {
    Some(match letters {
        "I" | "E" => Area::I,
        "Q" | "A" => Area::Q,
        "M" => Area::M,
        "V" => Area::V,
        "SM" => Area::Sm,
        _ => return None,
    })
}

/// What an unsupported operand letter group is, for the message.
fn unsupported(letters: &str) -> Option<&'static str> {
    Some(match letters {
        "AC" => "accumulators (AC0..AC3)",
        "L" | "LB" | "LW" | "LD" => "local memory (L)",
        "S" | "SB" | "SW" | "SD" => "sequence control relays (S)",
        "AIW" | "AQW" => "analog inputs and outputs (AIW, AQW)",
        "HC" => "high-speed counters (HC)",
        _ => return None,
    })
}

/// Decodes one operand.
pub(super) fn parse_operand(text: &str) -> Result<Operand, OperandError> {
    let t = text.trim().to_ascii_uppercase();
    if t.starts_with('*') || t.starts_with('&') {
        return Err(OperandError::Unsupported("indirect addressing (*VD, &VB)"));
    }
    if let Some(v) = parse_const(&t) {
        return Ok(Operand::Const(v));
    }
    let split = t
        .find(|c: char| c.is_ascii_digit())
        .ok_or(OperandError::NotAnOperand)?;
    let (letters, digits) = t.split_at(split);
    if let Some(what) = unsupported(letters) {
        return Err(OperandError::Unsupported(what));
    }
    let out_of_range = || OperandError::OutOfRange(text.trim().to_string());
    if letters == "T" || letters == "C" {
        let n = number(digits).ok_or(OperandError::NotAnOperand)?;
        if n >= TIMERS {
            return Err(out_of_range());
        }
        return Ok(if letters == "T" {
            Operand::Timer(n)
        } else {
            Operand::Counter(n)
        });
    }
    if let Some((byte, bit)) = digits.split_once('.') {
        let area = area_of(letters).ok_or(OperandError::NotAnOperand)?;
        let byte = number(byte).ok_or(OperandError::NotAnOperand)?;
        let bit = number(bit).ok_or(OperandError::NotAnOperand)?;
        if bit > 7 || byte >= area.size() {
            return Err(out_of_range());
        }
        return Ok(Operand::Bit {
            area,
            byte,
            bit: bit as u8,
        });
    }
    let addr = number(digits).ok_or(OperandError::NotAnOperand)?;
    let (area_letters, width) = match letters.as_bytes().last() {
        Some(b'B') => (&letters[..letters.len() - 1], Width::B),
        Some(b'W') => (&letters[..letters.len() - 1], Width::W),
        Some(b'D') => (&letters[..letters.len() - 1], Width::D),
        _ => return Err(OperandError::NotAnOperand),
    };
    let area = area_of(area_letters).ok_or(OperandError::NotAnOperand)?;
    if addr + width.bytes() > area.size() {
        return Err(out_of_range());
    }
    Ok(Operand::Mem { area, width, addr })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operands_in_both_styles() {
        assert_eq!(parse_const("+50"), Some(50));
        assert_eq!(parse_const("K50"), Some(50));
        assert_eq!(parse_const("K-5"), Some(-5));
        assert_eq!(parse_const("KHFFFF"), Some(0xFFFF));
        assert_eq!(parse_const("16#0100"), Some(0x100));
        assert_eq!(parse_const("-16#10"), Some(-16));
        assert_eq!(parse_const("V6"), None);
        assert_eq!(
            parse_operand("E0.4"),
            Ok(Operand::Bit {
                area: Area::I,
                byte: 0,
                bit: 4
            })
        );
        assert_eq!(
            parse_operand("vw10"),
            Ok(Operand::Mem {
                area: Area::V,
                width: Width::W,
                addr: 10
            })
        );
        assert_eq!(
            parse_operand("AB0"),
            Ok(Operand::Mem {
                area: Area::Q,
                width: Width::B,
                addr: 0
            })
        );
        assert_eq!(parse_operand("T37"), Ok(Operand::Timer(37)));
        assert!(matches!(
            parse_operand("AC0"),
            Err(OperandError::Unsupported(_))
        ));
        assert!(matches!(
            parse_operand("V6.8"),
            Err(OperandError::OutOfRange(_))
        ));
        assert!(matches!(
            parse_operand("VD4094"),
            Err(OperandError::OutOfRange(_))
        ));
        assert_eq!(parse_operand("X1"), Err(OperandError::NotAnOperand));
    }
}

//! Elementary IEC 61131-3 data types and how their values are encoded in a
//! 64-bit memory slot.
//!
//! Encoding (one `u64` slot per elementary value):
//! - BOOL: 0 or 1;
//! - signed integers (SINT INT DINT LINT): two's complement, sign-extended to 64 bits;
//! - unsigned integers and bit strings (USINT.. ULINT, BYTE.. LWORD, CHAR, WCHAR): zero-extended;
//! - REAL: the `f32` bit pattern in the low 32 bits; LREAL: the `f64` bit pattern;
//! - TIME, LTIME: signed nanoseconds;
//! - DATE, DT, LDATE, LDT: nanoseconds since 1970-01-01T00:00:00;
//! - TOD, LTOD: nanoseconds since midnight;
//! - STRING/WSTRING are not slot values: a slot holds the index of the string
//!   in the string store.

use std::fmt;

/// An elementary data type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ElemType {
    /// `BOOL`
    Bool,
    /// `SINT` (i8)
    Sint,
    /// `INT` (i16)
    Int,
    /// `DINT` (i32)
    Dint,
    /// `LINT` (i64)
    Lint,
    /// `USINT` (u8)
    Usint,
    /// `UINT` (u16)
    Uint,
    /// `UDINT` (u32)
    Udint,
    /// `ULINT` (u64)
    Ulint,
    /// `BYTE` (8-bit string)
    Byte,
    /// `WORD` (16-bit string)
    Word,
    /// `DWORD` (32-bit string)
    Dword,
    /// `LWORD` (64-bit string)
    Lword,
    /// `REAL` (f32)
    Real,
    /// `LREAL` (f64)
    Lreal,
    /// `TIME`
    Time,
    /// `LTIME`
    Ltime,
    /// `DATE`
    Date,
    /// `LDATE`
    Ldate,
    /// `TIME_OF_DAY` / `TOD`
    Tod,
    /// `LTIME_OF_DAY` / `LTOD`
    Ltod,
    /// `DATE_AND_TIME` / `DT`
    Dt,
    /// `LDATE_AND_TIME` / `LDT`
    Ldt,
    /// `CHAR`
    Char,
    /// `WCHAR`
    Wchar,
    /// `STRING`
    String,
    /// `WSTRING`
    WString,
}

/// Broad families used by the type rules.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// BOOL
    Bool,
    /// Signed integers.
    Signed,
    /// Unsigned integers.
    Unsigned,
    /// BYTE, WORD, DWORD, LWORD.
    Bits,
    /// REAL, LREAL.
    Real,
    /// TIME, LTIME.
    Duration,
    /// DATE, TOD, DT and long forms.
    DateTime,
    /// CHAR, WCHAR.
    Char,
    /// STRING, WSTRING.
    String,
}

impl ElemType {
    /// Every elementary type, in a fixed order.
    pub const ALL: [ElemType; 27] = [
        ElemType::Bool,
        ElemType::Sint,
        ElemType::Int,
        ElemType::Dint,
        ElemType::Lint,
        ElemType::Usint,
        ElemType::Uint,
        ElemType::Udint,
        ElemType::Ulint,
        ElemType::Byte,
        ElemType::Word,
        ElemType::Dword,
        ElemType::Lword,
        ElemType::Real,
        ElemType::Lreal,
        ElemType::Time,
        ElemType::Ltime,
        ElemType::Date,
        ElemType::Ldate,
        ElemType::Tod,
        ElemType::Ltod,
        ElemType::Dt,
        ElemType::Ldt,
        ElemType::Char,
        ElemType::Wchar,
        ElemType::String,
        ElemType::WString,
    ];

    /// Looks a type up by its IEC keyword (case-insensitive), including the
    /// long spellings `TIME_OF_DAY`, `DATE_AND_TIME` and their `L` forms.
    pub fn from_name(name: &str) -> Option<ElemType> {
        let upper = name.to_ascii_uppercase();
        Some(match upper.as_str() {
            "BOOL" => ElemType::Bool,
            "SINT" => ElemType::Sint,
            "INT" => ElemType::Int,
            "DINT" => ElemType::Dint,
            "LINT" => ElemType::Lint,
            "USINT" => ElemType::Usint,
            "UINT" => ElemType::Uint,
            "UDINT" => ElemType::Udint,
            "ULINT" => ElemType::Ulint,
            "BYTE" => ElemType::Byte,
            "WORD" => ElemType::Word,
            "DWORD" => ElemType::Dword,
            "LWORD" => ElemType::Lword,
            "REAL" => ElemType::Real,
            "LREAL" => ElemType::Lreal,
            "TIME" => ElemType::Time,
            "LTIME" => ElemType::Ltime,
            "DATE" => ElemType::Date,
            "LDATE" => ElemType::Ldate,
            "TOD" | "TIME_OF_DAY" => ElemType::Tod,
            "LTOD" | "LTIME_OF_DAY" => ElemType::Ltod,
            "DT" | "DATE_AND_TIME" => ElemType::Dt,
            "LDT" | "LDATE_AND_TIME" => ElemType::Ldt,
            "CHAR" => ElemType::Char,
            "WCHAR" => ElemType::Wchar,
            "STRING" => ElemType::String,
            "WSTRING" => ElemType::WString,
            _ => return None,
        })
    }

    /// The canonical IEC keyword.
    pub fn name(self) -> &'static str {
        match self {
            ElemType::Bool => "BOOL",
            ElemType::Sint => "SINT",
            ElemType::Int => "INT",
            ElemType::Dint => "DINT",
            ElemType::Lint => "LINT",
            ElemType::Usint => "USINT",
            ElemType::Uint => "UINT",
            ElemType::Udint => "UDINT",
            ElemType::Ulint => "ULINT",
            ElemType::Byte => "BYTE",
            ElemType::Word => "WORD",
            ElemType::Dword => "DWORD",
            ElemType::Lword => "LWORD",
            ElemType::Real => "REAL",
            ElemType::Lreal => "LREAL",
            ElemType::Time => "TIME",
            ElemType::Ltime => "LTIME",
            ElemType::Date => "DATE",
            ElemType::Ldate => "LDATE",
            ElemType::Tod => "TOD",
            ElemType::Ltod => "LTOD",
            ElemType::Dt => "DT",
            ElemType::Ldt => "LDT",
            ElemType::Char => "CHAR",
            ElemType::Wchar => "WCHAR",
            ElemType::String => "STRING",
            ElemType::WString => "WSTRING",
        }
    }

    /// The family this type belongs to.
    pub fn family(self) -> Family {
        use ElemType::*;
        match self {
            Bool => Family::Bool,
            Sint | Int | Dint | Lint => Family::Signed,
            Usint | Uint | Udint | Ulint => Family::Unsigned,
            Byte | Word | Dword | Lword => Family::Bits,
            Real | Lreal => Family::Real,
            Time | Ltime => Family::Duration,
            Date | Ldate | Tod | Ltod | Dt | Ldt => Family::DateTime,
            Char | Wchar => Family::Char,
            String | WString => Family::String,
        }
    }

    /// Width in bits of integer, bit-string, char and real types; 64 for
    /// time and date types, 1 for BOOL, 0 for strings.
    pub fn bits(self) -> u32 {
        use ElemType::*;
        match self {
            Bool => 1,
            Sint | Usint | Byte | Char => 8,
            Int | Uint | Word | Wchar => 16,
            Dint | Udint | Dword | Real => 32,
            Lint | Ulint | Lword | Lreal => 64,
            Time | Ltime | Date | Ldate | Tod | Ltod | Dt | Ldt => 64,
            String | WString => 0,
        }
    }

    /// True for SINT..LINT.
    pub fn is_signed_int(self) -> bool {
        self.family() == Family::Signed
    }

    /// True for USINT..ULINT.
    pub fn is_unsigned_int(self) -> bool {
        self.family() == Family::Unsigned
    }

    /// True for any integer type (ANY_INT).
    pub fn is_int(self) -> bool {
        matches!(self.family(), Family::Signed | Family::Unsigned)
    }

    /// True for BOOL and BYTE..LWORD (ANY_BIT).
    pub fn is_bit(self) -> bool {
        matches!(self.family(), Family::Bool | Family::Bits)
    }

    /// True for integer and real types (ANY_NUM).
    pub fn is_num(self) -> bool {
        matches!(
            self.family(),
            Family::Signed | Family::Unsigned | Family::Real
        )
    }

    /// True for REAL and LREAL.
    pub fn is_real(self) -> bool {
        self.family() == Family::Real
    }

    /// True for STRING and WSTRING.
    pub fn is_string(self) -> bool {
        self.family() == Family::String
    }

    /// The smallest and largest value of an integer or bit-string type, as i128.
    pub fn int_range(self) -> Option<(i128, i128)> {
        use ElemType::*;
        Some(match self {
            Sint => (i8::MIN as i128, i8::MAX as i128),
            Int => (i16::MIN as i128, i16::MAX as i128),
            Dint => (i32::MIN as i128, i32::MAX as i128),
            Lint => (i64::MIN as i128, i64::MAX as i128),
            Usint | Byte | Char => (0, u8::MAX as i128),
            Uint | Word | Wchar => (0, u16::MAX as i128),
            Udint | Dword => (0, u32::MAX as i128),
            Ulint | Lword => (0, u64::MAX as i128),
            Bool => (0, 1),
            _ => return None,
        })
    }

    /// Can a value of `self` be used where `to` is expected without an
    /// explicit conversion (IEC implicit widening, semantics.md §3)?
    pub fn widens_to(self, to: ElemType) -> bool {
        use ElemType::*;
        if self == to {
            return true;
        }
        let rank_signed = |t: ElemType| match t {
            Sint => 1,
            Int => 2,
            Dint => 3,
            Lint => 4,
            _ => 0,
        };
        let rank_unsigned = |t: ElemType| match t {
            Usint => 1,
            Uint => 2,
            Udint => 3,
            Ulint => 4,
            _ => 0,
        };
        let rank_bits = |t: ElemType| match t {
            Bool => 0,
            Byte => 1,
            Word => 2,
            Dword => 3,
            Lword => 4,
            _ => -1,
        };
        match self.family() {
            Family::Signed => match to.family() {
                Family::Signed => rank_signed(self) < rank_signed(to),
                // Exact in the mantissa: up to INT into REAL, up to DINT into LREAL.
                Family::Real => match to {
                    Real => rank_signed(self) <= 2,
                    _ => rank_signed(self) <= 3,
                },
                _ => false,
            },
            Family::Unsigned => match to.family() {
                Family::Unsigned => rank_unsigned(self) < rank_unsigned(to),
                Family::Signed => rank_unsigned(self) < rank_signed(to),
                Family::Real => match to {
                    Real => rank_unsigned(self) <= 2,
                    _ => rank_unsigned(self) <= 3,
                },
                _ => false,
            },
            Family::Bool | Family::Bits => rank_bits(to) > 0 && rank_bits(self) < rank_bits(to),
            Family::Real => self == Real && to == Lreal,
            Family::Duration => self == Time && to == Ltime,
            Family::Char => self == Char && to == Wchar,
            _ => false,
        }
    }
}

impl fmt::Display for ElemType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

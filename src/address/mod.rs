//! Direct addresses (`%IX0.3`, `%QW4`, `%I0.0.0.0.1`) as written, and
//! (in [`convention`]) the byte of the process image each one names under
//! the chosen [`Addressing`].
//!
//! What the text says, whatever the convention (see `docs/runtime.md`,
//! "Addressing"):
//!
//! - the size prefix gives the width: `X` (or none) one bit, `B` one byte,
//!   `W` two, `D` four, `L` eight;
//! - a bit address's last field is the bit (0–7) and the field before it
//!   the byte: `%IX0.3` is byte 0, bit 3; a bit address with a single
//!   field counts bits from the start of its table: `%IX10` is byte 1,
//!   bit 2;
//! - a byte, word, double or long word address's last field is its
//!   number, the [`IoAddress::index`]; which bytes that is depends on the
//!   convention (`%QW1` is bytes 2–3 under `iec`, holding register 1
//!   under `openplc`, bytes 1–2 under `byte`);
//! - the fields before those (the line, station and module of Moeller's
//!   five-field form `%I0.0.0.0.1`) must be 0: plcrun has one local I/O
//!   rack, so `%I0.0.0.0.1` is `%IX0.1` and `%Q0.0.0.1.7` is `%QX1.7`.
//!   An address with a non-zero leading field has no place in the image.
//!
//! This is a bottom stage: the checker uses it to warn of overlapping
//! located variables ([`overlap`]), the runtime to lay out the image.

pub mod convention;
mod io_link;
mod nc_axis;
pub mod overlap;

pub use convention::{Addressing, ImageSpot, ImageTable, UnknownAddressing};
pub use io_link::IoLink;
pub use nc_axis::NcAxis;

use std::fmt;

/// One of the three areas of the process image.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Area {
    /// `%I`: inputs, written by the host, read by the program.
    Input,
    /// `%Q`: outputs, written by the program, read by the host.
    Output,
    /// `%M`: memory (flags), shared by both.
    Memory,
}

impl Area {
    /// Index into per-area tables (`I`, `Q`, `M`).
    pub fn index(self) -> usize {
        match self {
            Area::Input => 0,
            Area::Output => 1,
            Area::Memory => 2,
        }
    }

    /// The area's letter.
    pub fn letter(self) -> char {
        match self {
            Area::Input => 'I',
            Area::Output => 'Q',
            Area::Memory => 'M',
        }
    }
}

/// How many bits an address covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Width {
    /// `X`: one bit.
    Bit,
    /// `B`: 8 bits.
    Byte,
    /// `W`: 16 bits.
    Word,
    /// `D`: 32 bits.
    Dword,
    /// `L`: 64 bits.
    Lword,
}

impl Width {
    /// Bytes covered (1 for a bit).
    pub fn bytes(self) -> usize {
        match self {
            Width::Bit | Width::Byte => 1,
            Width::Word => 2,
            Width::Dword => 4,
            Width::Lword => 8,
        }
    }

    /// Index into per-size tables (`X`, `B`, `W`, `D`, `L`).
    pub fn index(self) -> usize {
        match self {
            Width::Bit => 0,
            Width::Byte => 1,
            Width::Word => 2,
            Width::Dword => 3,
            Width::Lword => 4,
        }
    }

    /// The size prefix letter.
    pub fn letter(self) -> char {
        match self {
            Width::Bit => 'X',
            Width::Byte => 'B',
            Width::Word => 'W',
            Width::Dword => 'D',
            Width::Lword => 'L',
        }
    }
}

/// A direct address as written: area, size, number and bit. Where it
/// lies in the process image is [`Addressing::spot`]'s answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct IoAddress {
    /// `%I`, `%Q` or `%M`.
    pub area: Area,
    /// How much it covers.
    pub width: Width,
    /// The address's number: the byte of a bit address (`%QX1.2`: 1), the
    /// number after the size letter otherwise (`%QW4`: 4, the fifth word
    /// under `iec` and `openplc`, byte 4 under `byte`).
    pub index: usize,
    /// Bit inside the byte (0 unless `width` is [`Width::Bit`]).
    pub bit: u8,
}

impl fmt::Display for IoAddress {
    /// The canonical form: `%IX0.3`, `%QW4`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (a, w) = (self.area.letter(), self.width.letter());
        match self.width {
            Width::Bit => write!(f, "%{a}{w}{}.{}", self.index, self.bit),
            _ => write!(f, "%{a}{w}{}", self.index),
        }
    }
}

/// Why an address text does not name a place in the process image.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum AddressError {
    /// Not of the form `%` area, optional size, fields (`%IX0.3`, `%QW4`).
    Syntax {
        /// The text as given.
        text: String,
    },
    /// A bit number of 8 or more after a byte field (`%IX0.8`).
    BitOutOfRange {
        /// The text as given.
        text: String,
        /// The bit given.
        bit: u64,
    },
    /// A leading field of a multi-field address that is not 0
    /// (`%I1.0.0.0.1`): plcrun maps one local rack only.
    LeadingField {
        /// The text as given.
        text: String,
        /// The field's value.
        value: u64,
    },
    /// The address lies past the end of its area, whose size follows the
    /// highest address the program uses.
    OutOfRange {
        /// The text as given.
        text: String,
        /// The area's size in bytes.
        area_size: usize,
    },
    /// An access of another width than the address says (`write_word`
    /// with `%IX0.1`).
    WrongWidth {
        /// The text as given.
        text: String,
        /// The width the accessor needs.
        expected: Width,
    },
    /// The host writes only `%I` and `%M`; `%Q` belongs to the program.
    NotWritable {
        /// The text as given.
        text: String,
    },
}

impl fmt::Display for AddressError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AddressError::Syntax { text } => write!(
                f,
                "`{text}` is not a direct address (expected e.g. %IX0.3, %QW4, %I0.0.0.0.1)"
            ),
            AddressError::BitOutOfRange { text, bit } => {
                write!(f, "`{text}`: bit {bit} is not in 0..7")
            }
            AddressError::LeadingField { text, value } => write!(
                f,
                "`{text}`: leading field {value} is not 0 (plcrun maps one local rack: \
                 only the last byte and bit fields may be non-zero)"
            ),
            AddressError::OutOfRange { text, area_size } => write!(
                f,
                "`{text}` is outside the process image area ({area_size} bytes, sized by the \
                 highest address the program uses)"
            ),
            AddressError::WrongWidth { text, expected } => write!(
                f,
                "`{text}` is not a {} address",
                match expected {
                    Width::Bit => "bit (X)",
                    Width::Byte => "byte (B)",
                    Width::Word => "word (W)",
                    Width::Dword => "double word (D)",
                    Width::Lword => "long word (L)",
                }
            ),
            AddressError::NotWritable { text } => write!(
                f,
                "`{text}`: the host may write %I and %M only; %Q is written by the program"
            ),
        }
    }
}

impl std::error::Error for AddressError {}

/// Parses a direct address (see the module documentation).
/// Case-insensitive; blanks around it are ignored.
pub fn parse(text: &str) -> Result<IoAddress, AddressError> {
    let t = text.trim();
    let syntax = || AddressError::Syntax {
        text: text.to_string(),
    };
    let rest = t.strip_prefix('%').ok_or_else(syntax)?;
    let mut chars = rest.chars();
    let area = match chars.next().map(|c| c.to_ascii_uppercase()) {
        Some('I') => Area::Input,
        Some('Q') => Area::Output,
        Some('M') => Area::Memory,
        _ => return Err(syntax()),
    };
    let rest = chars.as_str();
    let (width, fields) = match rest.chars().next().map(|c| c.to_ascii_uppercase()) {
        Some('X') => (Width::Bit, &rest[1..]),
        Some('B') => (Width::Byte, &rest[1..]),
        Some('W') => (Width::Word, &rest[1..]),
        Some('D') => (Width::Dword, &rest[1..]),
        Some('L') => (Width::Lword, &rest[1..]),
        _ => (Width::Bit, rest),
    };
    let fields: Vec<u64> = fields
        .split('.')
        .map(|f| {
            if f.is_empty() || !f.bytes().all(|b| b.is_ascii_digit()) {
                return Err(syntax());
            }
            f.parse::<u64>().map_err(|_| syntax())
        })
        .collect::<Result<_, _>>()?;
    map(text, area, width, &fields)
}

/// The number and bit of parsed fields.
fn map(text: &str, area: Area, width: Width, fields: &[u64]) -> Result<IoAddress, AddressError> {
    // Fields that name the byte and bit; the rest must be 0.
    let own = match (width, fields.len()) {
        (Width::Bit, 1) => 1,
        (Width::Bit, _) => 2,
        _ => 1,
    };
    let Some(lead) = fields.len().checked_sub(own) else {
        return Err(AddressError::Syntax {
            text: text.to_string(),
        });
    };
    if let Some(&value) = fields[..lead].iter().find(|&&v| v != 0) {
        return Err(AddressError::LeadingField {
            text: text.to_string(),
            value,
        });
    }
    let too_big = || AddressError::OutOfRange {
        text: text.to_string(),
        area_size: 0,
    };
    let (byte, bit) = match (width, &fields[lead..]) {
        (Width::Bit, [linear]) => (linear / 8, (linear % 8) as u8),
        (Width::Bit, [byte, bit]) => {
            if *bit > 7 {
                return Err(AddressError::BitOutOfRange {
                    text: text.to_string(),
                    bit: *bit,
                });
            }
            (*byte, *bit as u8)
        }
        (_, [byte]) => (*byte, 0),
        _ => return Err(too_big()),
    };
    // Tables are in-memory buffers: anything past 16 MiB is surely a typo
    // (`Addressing::spot` checks the byte it comes to).
    if byte >= MAX_AREA_BYTES as u64 {
        return Err(too_big());
    }
    Ok(IoAddress {
        area,
        width,
        index: byte as usize,
        bit,
    })
}

/// The largest table of the image plcrun builds, in bytes.
pub const MAX_AREA_BYTES: usize = 1 << 24;

#[cfg(test)]
mod tests {
    use super::*;
    use rstest::rstest;

    #[rstest]
    #[case("%IX0.3", Area::Input, Width::Bit, 0, 3)]
    #[case("%ix2.7", Area::Input, Width::Bit, 2, 7)]
    #[case("%I0.1", Area::Input, Width::Bit, 0, 1)]
    #[case("%IX10", Area::Input, Width::Bit, 1, 2)]
    #[case("%QW4", Area::Output, Width::Word, 4, 0)]
    #[case("%MB7", Area::Memory, Width::Byte, 7, 0)]
    #[case("%MD12", Area::Memory, Width::Dword, 12, 0)]
    #[case("%QL16", Area::Output, Width::Lword, 16, 0)]
    #[case("%I0.0.0.0.1", Area::Input, Width::Bit, 0, 1)]
    #[case("%Q0.0.0.1.7", Area::Output, Width::Bit, 1, 7)]
    #[case("%M0.0.0.2.2", Area::Memory, Width::Bit, 2, 2)]
    #[case("%QX0.0.0.0.1", Area::Output, Width::Bit, 0, 1)]
    #[case("%IW0.0.0.6", Area::Input, Width::Word, 6, 0)]
    fn addresses_parse_to_numbers_and_bits(
        #[case] text: &str,
        #[case] area: Area,
        #[case] width: Width,
        #[case] index: usize,
        #[case] bit: u8,
    ) {
        let a = parse(text).unwrap();
        assert_eq!((a.area, a.width, a.index, a.bit), (area, width, index, bit));
    }

    #[test]
    fn canonical_text() {
        assert_eq!(parse("%I0.0.0.0.1").unwrap().to_string(), "%IX0.1");
        assert_eq!(parse("%qw4").unwrap().to_string(), "%QW4");
    }

    #[rstest]
    #[case("IX0.1")]
    #[case("%")]
    #[case("%ZX0.1")]
    #[case("%IX")]
    #[case("%IX0..1")]
    #[case("%IXa.1")]
    #[case("%IX0.1.")]
    #[case("%IW-1")]
    fn bad_syntax(#[case] text: &str) {
        assert!(
            matches!(parse(text), Err(AddressError::Syntax { .. })),
            "{text}"
        );
    }

    #[test]
    fn bad_fields() {
        assert_eq!(
            parse("%IX0.8"),
            Err(AddressError::BitOutOfRange {
                text: "%IX0.8".into(),
                bit: 8
            })
        );
        assert_eq!(
            parse("%I0.0.1.0.1"),
            Err(AddressError::LeadingField {
                text: "%I0.0.1.0.1".into(),
                value: 1
            })
        );
        assert!(matches!(
            parse("%QW99999999999"),
            Err(AddressError::OutOfRange { .. })
        ));
        let msg = parse("%I0.0.1.0.1").unwrap_err().to_string();
        assert!(msg.contains("leading field 1"), "{msg}");
    }
}

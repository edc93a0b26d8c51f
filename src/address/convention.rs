//! The three addressing conventions: which bytes of the process image a
//! direct address names (`docs/runtime.md`, "Addressing").
//!
//! | convention | `%QX1.2` | `%QB3` | `%QW1` | `%QD1` | `%QL1` | tables |
//! |---|---|---|---|---|---|---|
//! | `iec` (CODESYS) | byte 1, bit 2 | byte 3 | bytes 2–3 | bytes 4–7 | bytes 8–15 | one per area |
//! | `openplc` (matiec) | bit 2 of byte 1 of `%QX` | byte 3 of `%QB` | word 1 of `%QW` | double word 1 of `%QD` | long word 1 of `%QL` | one per area and size |
//! | `byte` (S7) | byte 1, bit 2 | byte 3 | bytes 1–2 | bytes 1–4 | bytes 1–8 | one per area |
//!
//! The convention is applied once, when the image is laid out: each
//! located variable gets its [`ImageSpot`] (table, byte, bit), and the
//! cycle copies bytes from there without looking at the convention again.

use super::{AddressError, Area, IoAddress, MAX_AREA_BYTES, Width};
use std::fmt;
use std::str::FromStr;

/// How direct addresses are numbered (`--addressing`, `Options::addressing`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Addressing {
    /// IEC 61131-3 as CODESYS lays it out: one byte image per area, a word
    /// address numbered in words (`%QWn` is bytes `2n`, `2n+1`), a double
    /// word in double words (`%QDn`: bytes `4n..4n+3`), a long word in long
    /// words; bits and bytes by byte, so `%QX0.0` lies inside `%QB0` and
    /// `%QW0`. The default for IEC sources (ST, IL, SFC, PLCopen XML).
    #[default]
    Iec,
    /// matiec and OpenPLC: every area has one table per size (`%QX`, `%QB`,
    /// `%QW`, `%QD`, `%QL`), each numbered in its own size; the tables never
    /// overlap (`%QX0.0` and `%QW0` are unrelated, `%QW1` is holding
    /// register 1). The default for PLCopen XML written by the OpenPLC
    /// Editor or Beremiz.
    OpenPlc,
    /// Every address a byte offset, as Siemens numbers its operands
    /// (`%QW1` is bytes 1 and 2, overlapping `%QW0` and `%QW2`). The
    /// default for S7-200 STL.
    Byte,
}

impl Addressing {
    /// Every convention, in the order the documentation lists them.
    pub const ALL: [Addressing; 3] = [Addressing::Iec, Addressing::OpenPlc, Addressing::Byte];

    /// The name the command line and the C ABI use (`iec`, `openplc`,
    /// `byte`).
    pub fn name(self) -> &'static str {
        match self {
            Addressing::Iec => "iec",
            Addressing::OpenPlc => "openplc",
            Addressing::Byte => "byte",
        }
    }

    /// The table of the image that holds `width`-sized addresses of
    /// `area`: the area's one table under `iec` and `byte`, that size's own
    /// table under `openplc`.
    pub fn table(self, area: Area, width: Width) -> ImageTable {
        match self {
            Addressing::OpenPlc => ImageTable {
                area,
                size: Some(width),
            },
            Addressing::Iec | Addressing::Byte => ImageTable { area, size: None },
        }
    }

    /// Where `at` lies in the image under this convention. Errs with
    /// [`AddressError::OutOfRange`] when its last byte would lie past the
    /// largest table plcrun builds ([`MAX_AREA_BYTES`]).
    ///
    /// ```
    /// use plcrun::{Addressing, address};
    /// let w = address::parse("%QW1").unwrap();
    /// assert_eq!(Addressing::Iec.spot(&w).unwrap().byte, 2);
    /// assert_eq!(Addressing::OpenPlc.spot(&w).unwrap().byte, 2); // in the %QW table
    /// assert_eq!(Addressing::Byte.spot(&w).unwrap().byte, 1);
    /// ```
    pub fn spot(self, at: &IoAddress) -> Result<ImageSpot, AddressError> {
        let scale = match (self, at.width) {
            (_, Width::Bit) | (Addressing::Byte, _) => 1,
            (Addressing::Iec | Addressing::OpenPlc, w) => w.bytes(),
        };
        let byte = at
            .index
            .checked_mul(scale)
            .filter(|b| b + at.width.bytes() <= MAX_AREA_BYTES)
            .ok_or_else(|| AddressError::OutOfRange {
                text: at.to_string(),
                area_size: 0,
            })?;
        Ok(ImageSpot {
            table: self.table(at.area, at.width),
            width: at.width,
            byte,
            bit: at.bit,
        })
    }
}

impl fmt::Display for Addressing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not an addressing convention.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownAddressing(pub String);

impl fmt::Display for UnknownAddressing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown addressing `{}` (expected iec, openplc or byte)",
            self.0
        )
    }
}

impl std::error::Error for UnknownAddressing {}

impl FromStr for Addressing {
    type Err = UnknownAddressing;

    /// `iec`, `openplc` or `byte`, in any case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Addressing::ALL
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| UnknownAddressing(s.to_string()))
    }
}

/// One byte table of the process image: an area's only table (`size`
/// `None`, under `iec` and `byte`) or the table of one size of an area
/// (under `openplc`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ImageTable {
    /// `%I`, `%Q` or `%M`.
    pub area: Area,
    /// The size whose addresses it holds, or `None` for all of them.
    pub size: Option<Width>,
}

impl ImageTable {
    /// How many tables an image can have: three shared, fifteen sized.
    pub const COUNT: usize = 18;

    /// Every table, in [`index`](Self::index) order.
    pub fn all() -> [ImageTable; ImageTable::COUNT] {
        const AREAS: [Area; 3] = [Area::Input, Area::Output, Area::Memory];
        const SIZES: [Width; 5] = [
            Width::Bit,
            Width::Byte,
            Width::Word,
            Width::Dword,
            Width::Lword,
        ];
        std::array::from_fn(|i| {
            if i < 3 {
                ImageTable {
                    area: AREAS[i],
                    size: None,
                }
            } else {
                ImageTable {
                    area: AREAS[(i - 3) / 5],
                    size: Some(SIZES[(i - 3) % 5]),
                }
            }
        })
    }

    /// Its index among the [`Self::COUNT`] tables: the three shared
    /// tables first, then the sized ones by area and size.
    pub fn index(self) -> usize {
        match self.size {
            None => self.area.index(),
            Some(w) => 3 + 5 * self.area.index() + w.index(),
        }
    }
}

impl fmt::Display for ImageTable {
    /// `%Q` for a shared table, `%QW` for a sized one.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.size {
            None => write!(f, "%{}", self.area.letter()),
            Some(w) => write!(f, "%{}{}", self.area.letter(), w.letter()),
        }
    }
}

/// Where a direct address lies in the image under a convention.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ImageSpot {
    /// The table.
    pub table: ImageTable,
    /// How much it covers.
    pub width: Width,
    /// Its first byte in the table.
    pub byte: usize,
    /// Bit inside the byte (0 unless `width` is [`Width::Bit`]).
    pub bit: u8,
}

impl ImageSpot {
    /// One past the last byte it covers.
    pub fn end(&self) -> usize {
        self.byte + self.width.bytes()
    }

    /// True when the two share a bit of the image (two bits only when
    /// they are the same bit).
    pub fn overlaps(&self, other: &ImageSpot) -> bool {
        if self.table != other.table || self.byte >= other.end() || other.byte >= self.end() {
            return false;
        }
        match (self.width, other.width) {
            (Width::Bit, Width::Bit) => self.bit == other.bit,
            _ => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::parse;
    use super::*;
    use rstest::rstest;

    fn spot(addressing: Addressing, text: &str) -> (String, usize, u8) {
        let s = addressing.spot(&parse(text).unwrap()).unwrap();
        (s.table.to_string(), s.byte, s.bit)
    }

    #[rstest]
    // iec: CODESYS' layout (%MW47 is bytes 94-95, %MD48 bytes 192-195).
    #[case(Addressing::Iec, "%QX0.0", "%Q", 0, 0)]
    #[case(Addressing::Iec, "%QX1.2", "%Q", 1, 2)]
    #[case(Addressing::Iec, "%QB3", "%Q", 3, 0)]
    #[case(Addressing::Iec, "%QW1", "%Q", 2, 0)]
    #[case(Addressing::Iec, "%MW47", "%M", 94, 0)]
    #[case(Addressing::Iec, "%MD48", "%M", 192, 0)]
    #[case(Addressing::Iec, "%QL2", "%Q", 16, 0)]
    #[case(Addressing::Iec, "%IX10", "%I", 1, 2)]
    #[case(Addressing::Iec, "%I0.0.0.0.1", "%I", 0, 1)]
    #[case(Addressing::Iec, "%IW0.0.0.3", "%I", 6, 0)]
    // openplc: one table per size, each numbered in its size.
    #[case(Addressing::OpenPlc, "%QX0.0", "%QX", 0, 0)]
    #[case(Addressing::OpenPlc, "%QX1.0", "%QX", 1, 0)]
    #[case(Addressing::OpenPlc, "%QB3", "%QB", 3, 0)]
    #[case(Addressing::OpenPlc, "%QW0", "%QW", 0, 0)]
    #[case(Addressing::OpenPlc, "%QW1", "%QW", 2, 0)]
    #[case(Addressing::OpenPlc, "%MW1", "%MW", 2, 0)]
    #[case(Addressing::OpenPlc, "%MD1", "%MD", 4, 0)]
    #[case(Addressing::OpenPlc, "%ML1", "%ML", 8, 0)]
    #[case(Addressing::OpenPlc, "%I0.0.0.1.7", "%IX", 1, 7)]
    // byte: every number a byte offset.
    #[case(Addressing::Byte, "%QW1", "%Q", 1, 0)]
    #[case(Addressing::Byte, "%MD48", "%M", 48, 0)]
    #[case(Addressing::Byte, "%QL3", "%Q", 3, 0)]
    #[case(Addressing::Byte, "%QX1.2", "%Q", 1, 2)]
    fn each_convention_places_addresses(
        #[case] addressing: Addressing,
        #[case] text: &str,
        #[case] table: &str,
        #[case] byte: usize,
        #[case] bit: u8,
    ) {
        assert_eq!(spot(addressing, text), (table.to_string(), byte, bit));
    }

    #[rstest]
    #[case(Addressing::Iec, "%QX0.0", "%QW0", true)]
    #[case(Addressing::Iec, "%QX2.0", "%QW1", true)]
    #[case(Addressing::Iec, "%QW0", "%QW1", false)]
    #[case(Addressing::Iec, "%MW2", "%MD1", true)]
    #[case(Addressing::Iec, "%MW1", "%MD1", false)]
    #[case(Addressing::Iec, "%QX0.0", "%QX0.1", false)]
    #[case(Addressing::Iec, "%QX0.0", "%IX0.0", false)]
    #[case(Addressing::OpenPlc, "%QX0.0", "%QW0", false)]
    #[case(Addressing::OpenPlc, "%MW0", "%MD0", false)]
    #[case(Addressing::OpenPlc, "%QW0", "%QW1", false)]
    #[case(Addressing::Byte, "%QW0", "%QW1", true)]
    #[case(Addressing::Byte, "%QW0", "%QW2", false)]
    #[case(Addressing::Byte, "%QX1.7", "%QW0", true)]
    fn overlaps_follow_the_convention(
        #[case] addressing: Addressing,
        #[case] a: &str,
        #[case] b: &str,
        #[case] overlap: bool,
    ) {
        let a = addressing.spot(&parse(a).unwrap()).unwrap();
        let b = addressing.spot(&parse(b).unwrap()).unwrap();
        assert_eq!(a.overlaps(&b), overlap);
        assert_eq!(b.overlaps(&a), overlap);
    }

    #[test]
    fn names_round_trip_and_unknown_names_are_refused() {
        for a in Addressing::ALL {
            assert_eq!(a.name().parse::<Addressing>(), Ok(a));
            assert_eq!(a.to_string().to_uppercase().parse::<Addressing>(), Ok(a));
        }
        let err = "codesys".parse::<Addressing>().unwrap_err();
        assert_eq!(
            err.to_string(),
            "unknown addressing `codesys` (expected iec, openplc or byte)"
        );
        assert_eq!(Addressing::default(), Addressing::Iec);
    }

    #[test]
    fn all_lists_the_tables_in_index_order() {
        for (i, t) in ImageTable::all().into_iter().enumerate() {
            assert_eq!(t.index(), i, "{t}");
        }
    }

    #[test]
    fn table_indices_are_distinct_and_in_range() {
        let mut seen = [false; ImageTable::COUNT];
        for area in [Area::Input, Area::Output, Area::Memory] {
            let sizes = [
                None,
                Some(Width::Bit),
                Some(Width::Byte),
                Some(Width::Word),
                Some(Width::Dword),
                Some(Width::Lword),
            ];
            for size in sizes {
                let i = ImageTable { area, size }.index();
                assert!(!seen[i], "{i}");
                seen[i] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn a_word_whose_bytes_would_pass_the_limit_is_out_of_range() {
        let at = parse(&format!("%ML{}", MAX_AREA_BYTES / 8)).unwrap();
        assert!(matches!(
            Addressing::Iec.spot(&at),
            Err(AddressError::OutOfRange { .. })
        ));
        assert!(Addressing::Byte.spot(&at).is_ok()); // bytes 2^21.. only
        let last = parse(&format!("%ML{}", MAX_AREA_BYTES / 8 - 1)).unwrap();
        assert!(Addressing::Iec.spot(&last).is_ok());
    }
}

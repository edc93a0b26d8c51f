//! Where each Modbus coil, discrete input and register sits in the process
//! image (OpenPLC's table, on plcrun's byte-addressed image; see
//! `docs/modbus.md`).
//!
//! | Modbus table | addresses | image |
//! |---|---|---|
//! | coils (FC 1, 5, 15) | 0–8191 | `%QX0.0`–`%QX1023.7`: coil `n` is bit `n % 8` of `%Q` byte `n / 8` |
//! | discrete inputs (FC 2) | 0–8191 | `%IX0.0`–`%IX1023.7`, likewise |
//! | input registers (FC 4) | 0–1023 | register `n` is the word `%IW(2n)`: `%I` bytes `2n`, `2n+1` |
//! | holding registers (FC 3, 6, 16) | 0–1023 | the word `%QW(2n)` |
//! | | 1024–2047 | the word `%MW(2(n−1024))` |
//! | | 2048–4095 | `%MD(4k)`, `k = (n−2048) / 2`, two registers, most significant word first |
//! | | 4096–8191 | `%ML(8k)`, `k = (n−4096) / 4`, four registers, most significant word first |
//!
//! A register's value is the word's value (the image stores it
//! little-endian; the wire carries it big-endian, as Modbus does), so a
//! client reads the same number the program wrote to `%QW4`.

use crate::runtime::io_address::Area;

/// Coils and discrete inputs each table holds (OpenPLC's 8192).
pub const BIT_COUNT: u16 = 8192;
/// Input registers (OpenPLC's 1024).
pub const INPUT_REGISTER_COUNT: u16 = 1024;
/// Holding registers: `%QW`, `%MW`, `%MD`, `%ML` (OpenPLC's 8192).
pub const HOLDING_REGISTER_COUNT: u16 = 8192;

/// First holding register of the `%MW` block.
const MW_FIRST: u16 = 1024;
/// First holding register of the `%MD` block.
const MD_FIRST: u16 = 2048;
/// First holding register of the `%ML` block.
const ML_FIRST: u16 = 4096;

/// Bytes of each area the Modbus tables reach (`%I`, `%Q`, `%M`): the
/// server keeps this much of each, whatever the program uses.
pub(crate) const TABLE_BYTES: [usize; 3] = [
    2 * INPUT_REGISTER_COUNT as usize, // %I: input registers reach furthest
    2 * (MW_FIRST as usize),           // %Q: holding registers 0-1023
    8 * ((HOLDING_REGISTER_COUNT - ML_FIRST) as usize / 4), // %M: the %ML block
];

/// One of the four Modbus data tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModbusTable {
    /// Read/write bits: `%QX`.
    Coils,
    /// Read-only bits: `%IX`.
    DiscreteInputs,
    /// Read-only registers: `%IW`.
    InputRegisters,
    /// Read/write registers: `%QW`, `%MW`, `%MD`, `%ML`.
    HoldingRegisters,
}

impl ModbusTable {
    /// How many addresses the table has.
    pub fn len(self) -> u16 {
        match self {
            ModbusTable::Coils | ModbusTable::DiscreteInputs => BIT_COUNT,
            ModbusTable::InputRegisters => INPUT_REGISTER_COUNT,
            ModbusTable::HoldingRegisters => HOLDING_REGISTER_COUNT,
        }
    }

    /// Always false: every table has addresses (for clippy's `len`).
    pub fn is_empty(self) -> bool {
        false
    }

    /// True when `count` addresses from `start` all exist.
    pub fn contains(self, start: u16, count: u16) -> bool {
        u32::from(start) + u32::from(count) <= u32::from(self.len())
    }

    /// The image area of a bit table.
    fn bit_area(self) -> Area {
        match self {
            ModbusTable::DiscreteInputs => Area::Input,
            _ => Area::Output,
        }
    }
}

/// Where one Modbus address sits in the image, as the client sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImagePlace {
    /// A bit: area, byte, bit (0–7).
    Bit(Area, usize, u8),
    /// A register: area and the byte holding its least significant half
    /// (the most significant half is the next byte).
    Word(Area, usize),
}

/// The place of address `n` of `table`, or `None` past the table's end.
///
/// ```
/// use plcrun::{Area, ImagePlace, ModbusTable, modbus_place};
///
/// assert_eq!(modbus_place(ModbusTable::Coils, 10), Some(ImagePlace::Bit(Area::Output, 1, 2)));
/// assert_eq!(modbus_place(ModbusTable::HoldingRegisters, 2), Some(ImagePlace::Word(Area::Output, 4)));
/// assert_eq!(modbus_place(ModbusTable::HoldingRegisters, 1025), Some(ImagePlace::Word(Area::Memory, 2)));
/// // %MD4: register 2050 is its most significant word (bytes 6, 7), 2051 the other.
/// assert_eq!(modbus_place(ModbusTable::HoldingRegisters, 2050), Some(ImagePlace::Word(Area::Memory, 6)));
/// assert_eq!(modbus_place(ModbusTable::HoldingRegisters, 2051), Some(ImagePlace::Word(Area::Memory, 4)));
/// assert_eq!(modbus_place(ModbusTable::InputRegisters, 1024), None);
/// ```
pub fn modbus_place(table: ModbusTable, n: u16) -> Option<ImagePlace> {
    if n >= table.len() {
        return None;
    }
    let n = usize::from(n);
    Some(match table {
        ModbusTable::Coils | ModbusTable::DiscreteInputs => {
            ImagePlace::Bit(table.bit_area(), n / 8, (n % 8) as u8)
        }
        ModbusTable::InputRegisters => ImagePlace::Word(Area::Input, 2 * n),
        ModbusTable::HoldingRegisters => holding_place(n),
    })
}

/// A holding register's word (see the module table).
fn holding_place(n: usize) -> ImagePlace {
    let (mw, md, ml) = (
        usize::from(MW_FIRST),
        usize::from(MD_FIRST),
        usize::from(ML_FIRST),
    );
    if n < mw {
        ImagePlace::Word(Area::Output, 2 * n)
    } else if n < md {
        ImagePlace::Word(Area::Memory, 2 * (n - mw))
    } else if n < ml {
        // Two registers per %MD, the most significant word first.
        let r = n - md;
        ImagePlace::Word(Area::Memory, 4 * (r / 2) + 2 * (1 - r % 2))
    } else {
        // Four registers per %ML, the most significant word first.
        let r = n - ml;
        ImagePlace::Word(Area::Memory, 8 * (r / 4) + 2 * (3 - r % 4))
    }
}

/// The image bytes a Modbus server reads and writes: the first
/// [`TABLE_BYTES`] of `%I`, `%Q` and `%M`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Tables {
    areas: [Vec<u8>; 3],
}

impl Default for Tables {
    fn default() -> Self {
        Tables {
            areas: TABLE_BYTES.map(|n| vec![0; n]),
        }
    }
}

impl Tables {
    /// The bytes of `area`.
    pub(crate) fn area(&self, area: Area) -> &[u8] {
        &self.areas[area.index()]
    }

    /// The bytes of `area`, writable.
    pub(crate) fn area_mut(&mut self, area: Area) -> &mut [u8] {
        &mut self.areas[area.index()]
    }

    /// Copies `other` into `self` (same sizes: no allocation).
    pub(crate) fn copy_from(&mut self, other: &Tables) {
        for (to, from) in self.areas.iter_mut().zip(&other.areas) {
            to.copy_from_slice(from);
        }
    }

    /// Packs `count` bits of `table` from `start` into `out`, least
    /// significant bit first (the Modbus layout); `out` holds
    /// `ceil(count / 8)` bytes. The caller checked the range.
    pub(crate) fn read_bits(&self, table: ModbusTable, start: u16, count: u16, out: &mut [u8]) {
        out.fill(0);
        for i in 0..count {
            if let Some(ImagePlace::Bit(area, byte, bit)) = modbus_place(table, start + i)
                && self.area(area)[byte] >> bit & 1 != 0
            {
                out[usize::from(i / 8)] |= 1 << (i % 8);
            }
        }
    }

    /// Writes `count` registers of `table` from `start` into `out`, two
    /// bytes each, most significant first (the Modbus layout).
    pub(crate) fn read_words(&self, table: ModbusTable, start: u16, count: u16, out: &mut [u8]) {
        for i in 0..count {
            let at = 2 * usize::from(i);
            if let Some(ImagePlace::Word(area, byte)) = modbus_place(table, start + i) {
                let bytes = self.area(area);
                let value = u16::from_le_bytes([bytes[byte], bytes[byte + 1]]);
                out[at..at + 2].copy_from_slice(&value.to_be_bytes());
            }
        }
    }
}

/// Masked byte updates `(area, byte, mask, bits)` that write `count`
/// coils from `start`, packed as in a Modbus request (`data`), or `count`
/// registers, two big-endian bytes each; `apply` is called once per byte
/// touched (per bit for coils).
pub(crate) fn for_each_byte_write(
    table: ModbusTable,
    start: u16,
    count: u16,
    data: &[u8],
    mut apply: impl FnMut(Area, usize, u8, u8),
) {
    for i in 0..count {
        match modbus_place(table, start + i) {
            Some(ImagePlace::Bit(area, byte, bit)) => {
                let on = data[usize::from(i / 8)] >> (i % 8) & 1;
                apply(area, byte, 1 << bit, on << bit);
            }
            Some(ImagePlace::Word(area, byte)) => {
                let at = 2 * usize::from(i);
                let value = u16::from_be_bytes([data[at], data[at + 1]]);
                let [lo, hi] = value.to_le_bytes();
                apply(area, byte, 0xFF, lo);
                apply(area, byte + 1, 0xFF, hi);
            }
            None => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_place_lies_inside_the_tables() {
        let tables = Tables::default();
        for table in [
            ModbusTable::Coils,
            ModbusTable::DiscreteInputs,
            ModbusTable::InputRegisters,
            ModbusTable::HoldingRegisters,
        ] {
            for n in 0..table.len() {
                match modbus_place(table, n).unwrap() {
                    ImagePlace::Bit(area, byte, _) => assert!(byte < tables.area(area).len()),
                    ImagePlace::Word(area, byte) => assert!(byte + 1 < tables.area(area).len()),
                }
            }
            assert_eq!(modbus_place(table, table.len()), None);
        }
    }

    #[test]
    fn double_and_long_words_go_most_significant_word_first() {
        let mut t = Tables::default();
        t.area_mut(Area::Memory)[8..12].copy_from_slice(&0x1234_5678u32.to_le_bytes());
        let mut out = [0u8; 4];
        t.read_words(ModbusTable::HoldingRegisters, 2048 + 4, 2, &mut out);
        assert_eq!(out, [0x12, 0x34, 0x56, 0x78]);
        t.area_mut(Area::Memory)[16..24].copy_from_slice(&0x0102_0304_0506_0708u64.to_le_bytes());
        let mut out = [0u8; 8];
        t.read_words(ModbusTable::HoldingRegisters, 4096 + 8, 4, &mut out);
        assert_eq!(out, [1, 2, 3, 4, 5, 6, 7, 8]);
    }

    #[test]
    fn writes_round_trip_through_reads() {
        let mut t = Tables::default();
        let data = [0b1010_0101, 0b11];
        let mut put = |area: Area, byte: usize, mask: u8, bits: u8| {
            let b = &mut t.area_mut(area)[byte];
            *b = (*b & !mask) | (bits & mask);
        };
        for_each_byte_write(ModbusTable::Coils, 5, 10, &data, &mut put);
        for_each_byte_write(
            ModbusTable::HoldingRegisters,
            1030,
            2,
            &[0xAB, 0xCD, 0x00, 0x01],
            &mut put,
        );
        let mut bits = [0u8; 2];
        t.read_bits(ModbusTable::Coils, 5, 10, &mut bits);
        assert_eq!(bits, data);
        assert_eq!(&t.area(Area::Memory)[12..16], &[0xCD, 0xAB, 0x01, 0x00]);
        let mut words = [0u8; 4];
        t.read_words(ModbusTable::HoldingRegisters, 1030, 2, &mut words);
        assert_eq!(words, [0xAB, 0xCD, 0x00, 0x01]);
    }
}

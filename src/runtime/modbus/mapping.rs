//! Where each Modbus coil, discrete input and register sits in the process
//! image: OpenPLC's table, on the image's addressing convention (see
//! `docs/modbus.md`).
//!
//! | Modbus table | addresses | `openplc` | `iec` (shared image) | `byte` |
//! |---|---|---|---|---|
//! | coils (FC 1, 5, 15) | 0–8191 | coil `n` is `%QX(n/8).(n%8)` | the same bit of `%Q` | the same |
//! | discrete inputs (FC 2) | 0–8191 | `%IX(n/8).(n%8)` | the same bit of `%I` | the same |
//! | input registers (FC 4) | 0–1023 | `%IWn` | `%IWn`: `%I` bytes `2n`, `2n+1` | `%IW(2n)` |
//! | holding registers (FC 3, 6, 16) | 0–1023 | `%QWn` | `%QWn` (bytes `2n`, `2n+1`) | `%QW(2n)` |
//! | | 1024–2047 | `%MW(n−1024)` | `%MW(n−1024)` | `%MW(2(n−1024))` |
//! | | 2048–4095 | `%MDk`, `k = (n−2048) / 2`, two registers | `%MDk` (bytes `4k..4k+3` of `%M`) | `%MD(4k)` |
//! | | 4096–8191 | `%MLk`, `k = (n−4096) / 4`, four registers | `%MLk` (bytes `8k..8k+7` of `%M`) | `%ML(8k)` |
//!
//! Under `iec` and `byte` the same register numbers reach the same bytes
//! of one shared image per area (so holding register 1024, `%MW0`, is the
//! low half of registers 2048–2049, `%MD0`); under `openplc` they reach
//! separate tables, as in OpenPLC. Double and long words go most
//! significant word first. A register's value is the word's value (the
//! image stores it little-endian; the wire carries it big-endian, as
//! Modbus does), so a client reads the same number the program wrote.

use crate::address::{Addressing, Area, ImageTable, Width};

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

/// Bytes of each image table the Modbus tables reach under `addressing`:
/// the server keeps this much of each, whatever the program uses.
fn table_bytes(addressing: Addressing) -> [usize; ImageTable::COUNT] {
    let bits = usize::from(BIT_COUNT) / 8;
    let inputs = 2 * usize::from(INPUT_REGISTER_COUNT);
    let outputs = 2 * usize::from(MW_FIRST);
    let words = 2 * usize::from(MD_FIRST - MW_FIRST);
    let dwords = 2 * usize::from(ML_FIRST - MD_FIRST);
    let lwords = 2 * usize::from(HOLDING_REGISTER_COUNT - ML_FIRST);
    let mut sizes = [0; ImageTable::COUNT];
    let mut set = |area, width, n: usize| {
        let i = addressing.table(area, width).index();
        sizes[i] = sizes[i].max(n);
    };
    set(Area::Input, Width::Bit, bits);
    set(Area::Input, Width::Word, inputs);
    set(Area::Output, Width::Bit, bits);
    set(Area::Output, Width::Word, outputs);
    set(Area::Memory, Width::Word, words);
    set(Area::Memory, Width::Dword, dwords);
    set(Area::Memory, Width::Lword, lwords);
    sizes
}

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
    /// A bit: image table, byte, bit (0–7).
    Bit(ImageTable, usize, u8),
    /// A register: image table and the byte holding its least significant
    /// half (the most significant half is the next byte).
    Word(ImageTable, usize),
}

/// The place of address `n` of `table` in an image numbered by
/// `addressing`, or `None` past the table's end.
///
/// ```
/// use plcrun::{Addressing, Area, ImagePlace, ImageTable, ModbusTable, Width, modbus_place};
///
/// let q = ImageTable { area: Area::Output, size: None };
/// let m = ImageTable { area: Area::Memory, size: None };
/// let iec = Addressing::Iec;
/// assert_eq!(modbus_place(iec, ModbusTable::Coils, 10), Some(ImagePlace::Bit(q, 1, 2)));
/// // Holding register 2 is %QW2: bytes 4, 5.
/// assert_eq!(modbus_place(iec, ModbusTable::HoldingRegisters, 2), Some(ImagePlace::Word(q, 4)));
/// assert_eq!(modbus_place(iec, ModbusTable::HoldingRegisters, 1025), Some(ImagePlace::Word(m, 2)));
/// // %MD1: register 2050 is its most significant word (bytes 6, 7), 2051 the other.
/// assert_eq!(modbus_place(iec, ModbusTable::HoldingRegisters, 2050), Some(ImagePlace::Word(m, 6)));
/// assert_eq!(modbus_place(iec, ModbusTable::HoldingRegisters, 2051), Some(ImagePlace::Word(m, 4)));
/// assert_eq!(modbus_place(iec, ModbusTable::InputRegisters, 1024), None);
/// // Under openplc, coils and registers are separate tables.
/// let qx = ImageTable { area: Area::Output, size: Some(Width::Bit) };
/// let qw = ImageTable { area: Area::Output, size: Some(Width::Word) };
/// let open = Addressing::OpenPlc;
/// assert_eq!(modbus_place(open, ModbusTable::Coils, 0), Some(ImagePlace::Bit(qx, 0, 0)));
/// assert_eq!(modbus_place(open, ModbusTable::HoldingRegisters, 1), Some(ImagePlace::Word(qw, 2)));
/// ```
pub fn modbus_place(addressing: Addressing, table: ModbusTable, n: u16) -> Option<ImagePlace> {
    if n >= table.len() {
        return None;
    }
    let n = usize::from(n);
    Some(match table {
        ModbusTable::Coils | ModbusTable::DiscreteInputs => ImagePlace::Bit(
            addressing.table(table.bit_area(), Width::Bit),
            n / 8,
            (n % 8) as u8,
        ),
        ModbusTable::InputRegisters => {
            ImagePlace::Word(addressing.table(Area::Input, Width::Word), 2 * n)
        }
        ModbusTable::HoldingRegisters => holding_place(addressing, n),
    })
}

/// A holding register's word (see the module table). The byte offsets are
/// the same under every convention: `byte` numbers `%QW(2n)` what `iec`
/// and `openplc` number `%QWn`; only the tables differ.
fn holding_place(addressing: Addressing, n: usize) -> ImagePlace {
    let (mw, md, ml) = (
        usize::from(MW_FIRST),
        usize::from(MD_FIRST),
        usize::from(ML_FIRST),
    );
    let memory = |width| addressing.table(Area::Memory, width);
    if n < mw {
        ImagePlace::Word(addressing.table(Area::Output, Width::Word), 2 * n)
    } else if n < md {
        ImagePlace::Word(memory(Width::Word), 2 * (n - mw))
    } else if n < ml {
        // Two registers per %MD, the most significant word first.
        let r = n - md;
        ImagePlace::Word(memory(Width::Dword), 4 * (r / 2) + 2 * (1 - r % 2))
    } else {
        // Four registers per %ML, the most significant word first.
        let r = n - ml;
        ImagePlace::Word(memory(Width::Lword), 8 * (r / 4) + 2 * (3 - r % 4))
    }
}

/// The image bytes a Modbus server reads and writes under one addressing
/// convention: the first bytes of each table the Modbus tables reach.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Tables {
    addressing: Addressing,
    tables: [Vec<u8>; ImageTable::COUNT],
}

impl Default for Tables {
    fn default() -> Self {
        Tables::new(Addressing::default())
    }
}

impl Tables {
    /// Zeroed tables for an image numbered by `addressing`.
    pub(crate) fn new(addressing: Addressing) -> Tables {
        Tables {
            addressing,
            tables: table_bytes(addressing).map(|n| vec![0; n]),
        }
    }

    /// The convention the tables follow.
    pub(crate) fn addressing(&self) -> Addressing {
        self.addressing
    }

    /// The bytes of `table`.
    pub(crate) fn table(&self, table: ImageTable) -> &[u8] {
        &self.tables[table.index()]
    }

    /// The bytes of `table`, writable.
    pub(crate) fn table_mut(&mut self, table: ImageTable) -> &mut [u8] {
        &mut self.tables[table.index()]
    }

    /// Copies `other` into `self` (no allocation unless the convention
    /// changed).
    pub(crate) fn copy_from(&mut self, other: &Tables) {
        if self.addressing != other.addressing {
            self.clone_from(other);
            return;
        }
        for (to, from) in self.tables.iter_mut().zip(&other.tables) {
            to.copy_from_slice(from);
        }
    }

    /// Packs `count` bits of `table` from `start` into `out`, least
    /// significant bit first (the Modbus layout); `out` holds
    /// `ceil(count / 8)` bytes. The caller checked the range.
    pub(crate) fn read_bits(&self, table: ModbusTable, start: u16, count: u16, out: &mut [u8]) {
        out.fill(0);
        for i in 0..count {
            if let Some(ImagePlace::Bit(t, byte, bit)) =
                modbus_place(self.addressing, table, start + i)
                && self.table(t)[byte] >> bit & 1 != 0
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
            if let Some(ImagePlace::Word(t, byte)) = modbus_place(self.addressing, table, start + i)
            {
                let bytes = self.table(t);
                let value = u16::from_le_bytes([bytes[byte], bytes[byte + 1]]);
                out[at..at + 2].copy_from_slice(&value.to_be_bytes());
            }
        }
    }
}

/// Masked byte updates `(table, byte, mask, bits)` that write `count`
/// coils from `start`, packed as in a Modbus request (`data`), or `count`
/// registers, two big-endian bytes each, into an image numbered by
/// `addressing`; `apply` is called once per byte touched (per bit for
/// coils).
pub(crate) fn for_each_byte_write(
    addressing: Addressing,
    table: ModbusTable,
    start: u16,
    count: u16,
    data: &[u8],
    mut apply: impl FnMut(ImageTable, usize, u8, u8),
) {
    for i in 0..count {
        match modbus_place(addressing, table, start + i) {
            Some(ImagePlace::Bit(t, byte, bit)) => {
                let on = data[usize::from(i / 8)] >> (i % 8) & 1;
                apply(t, byte, 1 << bit, on << bit);
            }
            Some(ImagePlace::Word(t, byte)) => {
                let at = 2 * usize::from(i);
                let value = u16::from_be_bytes([data[at], data[at + 1]]);
                let [lo, hi] = value.to_le_bytes();
                apply(t, byte, 0xFF, lo);
                apply(t, byte + 1, 0xFF, hi);
            }
            None => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL_TABLES: [ModbusTable; 4] = [
        ModbusTable::Coils,
        ModbusTable::DiscreteInputs,
        ModbusTable::InputRegisters,
        ModbusTable::HoldingRegisters,
    ];

    fn memory(addressing: Addressing, width: Width) -> ImageTable {
        addressing.table(Area::Memory, width)
    }

    #[test]
    fn every_place_lies_inside_the_tables() {
        for addressing in Addressing::ALL {
            let tables = Tables::new(addressing);
            for table in ALL_TABLES {
                for n in 0..table.len() {
                    match modbus_place(addressing, table, n).unwrap() {
                        ImagePlace::Bit(t, byte, _) => assert!(byte < tables.table(t).len()),
                        ImagePlace::Word(t, byte) => assert!(byte + 1 < tables.table(t).len()),
                    }
                }
                assert_eq!(modbus_place(addressing, table, table.len()), None);
            }
        }
    }

    #[test]
    fn openplc_tables_are_separate_and_iec_shares_one_image_per_area() {
        let open = Addressing::OpenPlc;
        let qx = open.table(Area::Output, Width::Bit);
        let qw = open.table(Area::Output, Width::Word);
        assert_ne!(qx, qw);
        // Coil 8 is %QX1.0; holding register 1 is %QW1, word 1 of %QW.
        assert_eq!(
            modbus_place(open, ModbusTable::Coils, 8),
            Some(ImagePlace::Bit(qx, 1, 0))
        );
        assert_eq!(
            modbus_place(open, ModbusTable::HoldingRegisters, 1),
            Some(ImagePlace::Word(qw, 2))
        );
        // 1024 + n is %MWn, 2048 + 2k %MDk, 4096 + 4k %MLk, in their tables.
        assert_eq!(
            modbus_place(open, ModbusTable::HoldingRegisters, 1025),
            Some(ImagePlace::Word(memory(open, Width::Word), 2))
        );
        assert_eq!(
            modbus_place(open, ModbusTable::HoldingRegisters, 2049),
            Some(ImagePlace::Word(memory(open, Width::Dword), 0))
        );
        assert_eq!(
            modbus_place(open, ModbusTable::HoldingRegisters, 4096 + 4),
            Some(ImagePlace::Word(memory(open, Width::Lword), 14))
        );
        // Under iec the same numbers reach the one %M image: %MW0 is the
        // low half of %MD0.
        let iec = Addressing::Iec;
        let m = memory(iec, Width::Word);
        assert_eq!(m, memory(iec, Width::Dword));
        assert_eq!(
            modbus_place(iec, ModbusTable::HoldingRegisters, 1024),
            modbus_place(iec, ModbusTable::HoldingRegisters, 2049)
        );
    }

    #[test]
    fn double_and_long_words_go_most_significant_word_first() {
        for addressing in Addressing::ALL {
            let mut t = Tables::new(addressing);
            t.table_mut(memory(addressing, Width::Dword))[8..12]
                .copy_from_slice(&0x1234_5678u32.to_le_bytes());
            let mut out = [0u8; 4];
            t.read_words(ModbusTable::HoldingRegisters, 2048 + 4, 2, &mut out);
            assert_eq!(out, [0x12, 0x34, 0x56, 0x78]);
            t.table_mut(memory(addressing, Width::Lword))[16..24]
                .copy_from_slice(&0x0102_0304_0506_0708u64.to_le_bytes());
            let mut out = [0u8; 8];
            t.read_words(ModbusTable::HoldingRegisters, 4096 + 8, 4, &mut out);
            assert_eq!(out, [1, 2, 3, 4, 5, 6, 7, 8]);
        }
    }

    #[test]
    fn writes_round_trip_through_reads() {
        for addressing in Addressing::ALL {
            let mut t = Tables::new(addressing);
            let data = [0b1010_0101, 0b11];
            let mut put = |table: ImageTable, byte: usize, mask: u8, bits: u8| {
                let b = &mut t.table_mut(table)[byte];
                *b = (*b & !mask) | (bits & mask);
            };
            for_each_byte_write(addressing, ModbusTable::Coils, 5, 10, &data, &mut put);
            for_each_byte_write(
                addressing,
                ModbusTable::HoldingRegisters,
                1030,
                2,
                &[0xAB, 0xCD, 0x00, 0x01],
                &mut put,
            );
            let mut bits = [0u8; 2];
            t.read_bits(ModbusTable::Coils, 5, 10, &mut bits);
            assert_eq!(bits, data);
            assert_eq!(
                &t.table(memory(addressing, Width::Word))[12..16],
                &[0xCD, 0xAB, 0x01, 0x00]
            );
            let mut words = [0u8; 4];
            t.read_words(ModbusTable::HoldingRegisters, 1030, 2, &mut words);
            assert_eq!(words, [0xAB, 0xCD, 0x00, 0x01]);
        }
    }
}

//! The process image: the `%I`, `%Q` and `%M` byte tables that a host
//! exchanges with its I/O between cycles.
//!
//! Which bytes an address names follows the image's [`Addressing`]
//! (`docs/runtime.md`, "Addressing"): under `iec` and `byte` each area is
//! one table, under `openplc` each area has one table per size (`%QX`,
//! `%QB`, `%QW`, `%QD`, `%QL`). The convention is applied once, when the
//! image is built: each located variable keeps its table and byte, and the
//! cycle copies bytes from there.
//!
//! Every located variable of the program (`AT %IX0.1`, `%QW4`, a direct
//! address used in code) keeps its own slot, which the program reads and
//! writes as before; the image is a byte view of those slots, exchanged at
//! cycle boundaries:
//!
//! - at the start of a cycle, before any program runs, each located
//!   variable whose bits in the image changed since they were last
//!   exchanged takes the image's value (inputs latched; `%M` and `%Q` bits
//!   changed through an overlapping variable are picked up the same way);
//! - at the end of the cycle, each `%Q` and `%M` variable whose value the
//!   cycle changed is written into the image (outputs published). Where
//!   variables overlap (`%MW0` and `%MX0.1` under `iec`), those that
//!   changed are written widest first, so that a bit written by the
//!   program lands on top of the word around it; the other overlapping
//!   variables take the merged bytes at the next cycle start.
//!
//! Multi-byte values are little-endian (least significant byte first), as
//! CODESYS lays out its image on x86 and ARM: a host on those machines can
//! copy words straight out of the byte slices. `TIME` at a `%D` address
//! is its value in milliseconds as an unsigned 32-bit integer, as CODESYS
//! stores TIME (T#0ms to T#49d17h2m47s295ms); a negative TIME, or one
//! past that, is stored modulo 2^32 ms, as 32-bit unsigned arithmetic
//! wraps (T#-1ms becomes 4 294 967 295, read back as T#49d17h2m47s295ms).
//! At an `%L` address, TIME is nanoseconds as a signed 64-bit integer.
//!
//! A program without located variables has an empty image and pays one
//! test per cycle for it.

use crate::address::{self, AddressError, Addressing, Area, ImageSpot, ImageTable, Width};
use crate::elementary::{ElemType, Family};
use crate::ir::image::Image;

/// Nanoseconds per millisecond, for TIME at a 32-bit address.
const NS_PER_MS: i64 = 1_000_000;

/// One located variable's place in the image.
#[derive(Debug, Clone)]
struct Binding {
    /// Its slot in PLC memory.
    slot: u32,
    /// Where it sits in the image.
    at: ImageSpot,
    /// `at.table.index()`, computed once.
    table: usize,
    /// Its elementary type (for the encoding).
    ty: ElemType,
    /// Its bits as last exchanged with the image (image encoding).
    seen: u64,
}

/// The `%I`, `%Q` and `%M` byte tables of a PLC (see the module
/// documentation for their layout and for when they are exchanged with
/// the program).
#[derive(Debug, Clone, Default)]
pub struct ProcessImage {
    /// How addresses are numbered.
    addressing: Addressing,
    /// The tables by [`ImageTable::index`], each as long as the highest
    /// address used in it (those the convention does not use stay empty).
    tables: [Vec<u8>; ImageTable::COUNT],
    /// Located variables, widest first, then by area and address.
    bindings: Vec<Binding>,
    /// `(slot, binding index)` sorted by slot.
    by_slot: Vec<(u32, usize)>,
    /// Located variables whose address has no place in the image.
    unmapped: Vec<(String, AddressError)>,
}

impl ProcessImage {
    /// The image of `image`'s located variables under `addressing`,
    /// filled from `memory`.
    pub(crate) fn new(image: &Image, memory: &[u64], addressing: Addressing) -> ProcessImage {
        let mut io = ProcessImage {
            addressing,
            ..ProcessImage::default()
        };
        let mut slots: Vec<u32> = Vec::new();
        for r in &image.globals {
            let Some(text) = &r.location else { continue };
            if slots.contains(&r.addr) {
                continue;
            }
            slots.push(r.addr);
            let Some(ty) = image.types.scalar(r.ty) else {
                continue;
            };
            match address::parse(text).and_then(|a| addressing.spot(&a)) {
                Ok(at) => io.bindings.push(Binding {
                    slot: r.addr,
                    at,
                    table: at.table.index(),
                    ty,
                    seen: 0,
                }),
                Err(e) => io.unmapped.push((text.clone(), e)),
            }
        }
        io.bindings.sort_by_key(|b| {
            (
                std::cmp::Reverse(b.at.width.bytes()),
                b.table,
                b.at.byte,
                b.at.bit,
            )
        });
        for b in &io.bindings {
            let table = &mut io.tables[b.table];
            if table.len() < b.at.end() {
                table.resize(b.at.end(), 0);
            }
        }
        for i in 0..io.bindings.len() {
            let b = &io.bindings[i];
            let bits = encode(b, memory[b.slot as usize]);
            put(&mut io.tables[b.table], &b.at, bits);
            io.bindings[i].seen = bits;
        }
        io.by_slot = io
            .bindings
            .iter()
            .enumerate()
            .map(|(i, b)| (b.slot, i))
            .collect();
        io.by_slot.sort_unstable();
        io
    }

    /// True when the program has no located variable in the image (then
    /// nothing is exchanged).
    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        self.bindings.is_empty()
    }

    /// Start of a cycle: located variables whose image bits changed take
    /// them.
    pub(crate) fn latch(&mut self, memory: &mut [u64]) {
        for b in &mut self.bindings {
            let bits = get(&self.tables[b.table], &b.at);
            if bits != b.seen {
                b.seen = bits;
                memory[b.slot as usize] = decode(b, bits);
            }
        }
    }

    /// End of a cycle: `%Q` and `%M` variables the cycle changed are
    /// written into the image.
    pub(crate) fn publish(&mut self, memory: &[u64]) {
        for b in &mut self.bindings {
            if b.at.table.area == Area::Input {
                continue;
            }
            let bits = encode(b, memory[b.slot as usize]);
            if bits != b.seen {
                b.seen = bits;
                put(&mut self.tables[b.table], &b.at, bits);
            }
        }
    }

    /// A host write by name into slot `slot` (value `raw`): when the slot
    /// is a located variable, the image takes the value at once.
    #[inline]
    pub(crate) fn stored(&mut self, slot: u32, raw: u64) {
        if self.by_slot.is_empty() {
            return;
        }
        if let Ok(k) = self.by_slot.binary_search_by_key(&slot, |&(s, _)| s) {
            let b = &mut self.bindings[self.by_slot[k].1];
            let bits = encode(b, raw);
            b.seen = bits;
            put(&mut self.tables[b.table], &b.at, bits);
        }
    }

    /// How this image numbers addresses.
    pub fn addressing(&self) -> Addressing {
        self.addressing
    }

    /// The bytes holding `width`-sized addresses of `area`: the whole
    /// area under `iec` and `byte`, that size's own table under `openplc`
    /// (`table(Area::Output, Width::Word)` is the `%QW` table, word `n` at
    /// bytes `2n`, `2n+1`). As long as the highest address the program
    /// uses there; empty when it uses none.
    pub fn table(&self, area: Area, width: Width) -> &[u8] {
        &self.tables[self.addressing.table(area, width).index()]
    }

    /// The bytes of `width`-sized addresses of `%I` or `%M`, writable by
    /// the host (the program sees them at the start of the next cycle);
    /// `None` for `%Q`, which the program writes.
    pub fn table_mut(&mut self, area: Area, width: Width) -> Option<&mut [u8]> {
        if area == Area::Output {
            return None;
        }
        Some(&mut self.tables[self.addressing.table(area, width).index()])
    }

    /// The bytes of one area: under `iec` and `byte` the whole area, under
    /// `openplc` its table of byte addresses (`%QB`; the other sizes are
    /// in [`table`](Self::table)).
    pub fn area(&self, area: Area) -> &[u8] {
        self.table(area, Width::Byte)
    }

    /// The bytes of any table, `%Q` included, for the crate's own servers
    /// (a Modbus client writes coils and holding registers, which are
    /// `%Q`); like a host write, the program sees them at the next cycle.
    pub(crate) fn table_bytes_mut(&mut self, table: ImageTable) -> &mut [u8] {
        &mut self.tables[table.index()]
    }

    /// The bytes of any table, by its identity.
    pub(crate) fn table_bytes(&self, table: ImageTable) -> &[u8] {
        &self.tables[table.index()]
    }

    /// The `%I` bytes ([`area`](Self::area)), for a host that copies its
    /// inputs in bulk. The program sees them at the start of the next
    /// cycle.
    pub fn inputs_mut(&mut self) -> &mut [u8] {
        let t = self.addressing.table(Area::Input, Width::Byte);
        &mut self.tables[t.index()]
    }

    /// The `%M` bytes ([`area`](Self::area)), writable by the host like
    /// `%I`.
    pub fn memory_mut(&mut self) -> &mut [u8] {
        let t = self.addressing.table(Area::Memory, Width::Byte);
        &mut self.tables[t.index()]
    }

    /// Located variables whose address has no place in the image (a
    /// Moeller address with a non-zero leading field, a bit number over
    /// 7), with the reason. They still work by name.
    pub fn unmapped(&self) -> &[(String, AddressError)] {
        &self.unmapped
    }

    /// Maps `text` for an access of `width`, checking it lies inside its
    /// table.
    fn locate(&self, text: &str, width: Width) -> Result<ImageSpot, AddressError> {
        let at = address::parse(text)?;
        if at.width != width {
            return Err(AddressError::WrongWidth {
                text: text.to_string(),
                expected: width,
            });
        }
        let at = self
            .addressing
            .spot(&at)
            .map_err(|_| AddressError::OutOfRange {
                text: text.to_string(),
                area_size: 0,
            })?;
        let size = self.tables[at.table.index()].len();
        if at.end() > size {
            return Err(AddressError::OutOfRange {
                text: text.to_string(),
                area_size: size,
            });
        }
        Ok(at)
    }

    /// Maps `text` for a host write of `width` (`%I` and `%M` only).
    fn locate_writable(&self, text: &str, width: Width) -> Result<ImageSpot, AddressError> {
        let at = self.locate(text, width)?;
        if at.table.area == Area::Output {
            return Err(AddressError::NotWritable {
                text: text.to_string(),
            });
        }
        Ok(at)
    }

    fn read(&self, text: &str, width: Width) -> Result<u64, AddressError> {
        let at = self.locate(text, width)?;
        Ok(get(&self.tables[at.table.index()], &at))
    }

    fn write(&mut self, text: &str, width: Width, bits: u64) -> Result<(), AddressError> {
        let at = self.locate_writable(text, width)?;
        put(&mut self.tables[at.table.index()], &at, bits);
        Ok(())
    }

    /// Reads a bit (`%IX0.3`, `%Q0.0.0.1.7`).
    pub fn read_bit(&self, address: &str) -> Result<bool, AddressError> {
        self.read(address, Width::Bit).map(|b| b != 0)
    }

    /// Reads a byte (`%QB2`).
    pub fn read_byte(&self, address: &str) -> Result<u8, AddressError> {
        self.read(address, Width::Byte).map(|b| b as u8)
    }

    /// Reads a word (`%QW4`: bytes 8 and 9 under `iec`, little-endian).
    pub fn read_word(&self, address: &str) -> Result<u16, AddressError> {
        self.read(address, Width::Word).map(|b| b as u16)
    }

    /// Reads a double word (`%QD8`).
    pub fn read_dword(&self, address: &str) -> Result<u32, AddressError> {
        self.read(address, Width::Dword).map(|b| b as u32)
    }

    /// Reads a long word (`%QL8`).
    pub fn read_lword(&self, address: &str) -> Result<u64, AddressError> {
        self.read(address, Width::Lword)
    }

    /// Writes a bit of `%I` or `%M`; the program sees it from the next
    /// cycle on.
    pub fn write_bit(&mut self, address: &str, value: bool) -> Result<(), AddressError> {
        self.write(address, Width::Bit, u64::from(value))
    }

    /// Writes a byte of `%I` or `%M`.
    pub fn write_byte(&mut self, address: &str, value: u8) -> Result<(), AddressError> {
        self.write(address, Width::Byte, u64::from(value))
    }

    /// Writes a word of `%I` or `%M` (little-endian).
    pub fn write_word(&mut self, address: &str, value: u16) -> Result<(), AddressError> {
        self.write(address, Width::Word, u64::from(value))
    }

    /// Writes a double word of `%I` or `%M`.
    pub fn write_dword(&mut self, address: &str, value: u32) -> Result<(), AddressError> {
        self.write(address, Width::Dword, u64::from(value))
    }

    /// Writes a long word of `%I` or `%M`.
    pub fn write_lword(&mut self, address: &str, value: u64) -> Result<(), AddressError> {
        self.write(address, Width::Lword, value)
    }
}

impl super::engine::Plc {
    /// The process image: read `%Q` (and `%I`, `%M`) between cycles.
    pub fn process_image(&self) -> &ProcessImage {
        &self.io
    }

    /// The process image, to write `%I` and `%M` between cycles; the
    /// program sees the change at the start of the next cycle.
    pub fn process_image_mut(&mut self) -> &mut ProcessImage {
        &mut self.io
    }
}

/// The bits at `at` (little-endian for several bytes).
fn get(area: &[u8], at: &ImageSpot) -> u64 {
    match at.width {
        Width::Bit => u64::from(area[at.byte] >> at.bit & 1),
        w => {
            let mut bytes = [0u8; 8];
            bytes[..w.bytes()].copy_from_slice(&area[at.byte..at.end()]);
            u64::from_le_bytes(bytes)
        }
    }
}

/// Writes `bits` at `at`.
fn put(area: &mut [u8], at: &ImageSpot, bits: u64) {
    match at.width {
        Width::Bit => {
            let mask = 1u8 << at.bit;
            if bits & 1 != 0 {
                area[at.byte] |= mask;
            } else {
                area[at.byte] &= !mask;
            }
        }
        w => area[at.byte..at.end()].copy_from_slice(&bits.to_le_bytes()[..w.bytes()]),
    }
}

/// A slot value in the image encoding of `b`.
fn encode(b: &Binding, raw: u64) -> u64 {
    let bits = (b.at.width.bytes() * 8) as u32;
    match b.at.width {
        Width::Bit => raw & 1,
        // Milliseconds modulo 2^32 (see the module documentation).
        Width::Dword if b.ty.family() == Family::Duration => {
            u64::from(((raw as i64) / NS_PER_MS) as u32)
        }
        Width::Lword => raw,
        _ => raw & ((1u64 << bits) - 1),
    }
}

/// Image bits decoded into the slot encoding of `b`'s type.
fn decode(b: &Binding, bits: u64) -> u64 {
    let width = (b.at.width.bytes() * 8) as u32;
    match b.at.width {
        Width::Bit => bits & 1,
        Width::Lword => bits,
        // Unsigned milliseconds, as CODESYS' TIME.
        Width::Dword if b.ty.family() == Family::Duration => {
            (i64::from(bits as u32) * NS_PER_MS) as u64
        }
        _ if b.ty.is_signed_int() => {
            let shift = 64 - width;
            (((bits << shift) as i64) >> shift) as u64
        }
        _ => bits,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(text: &str) -> ImageSpot {
        Addressing::Iec
            .spot(&address::parse(text).unwrap())
            .unwrap()
    }

    fn binding(text: &str, ty: ElemType) -> Binding {
        let at = spot(text);
        Binding {
            slot: 0,
            at,
            table: at.table.index(),
            ty,
            seen: 0,
        }
    }

    #[test]
    fn values_round_trip_through_the_image_encoding() {
        let cases = [
            ("%IX0.1", ElemType::Bool, 1u64),
            ("%IB0", ElemType::Sint, (-5i64) as u64),
            ("%IW0", ElemType::Int, (-1200i64) as u64),
            ("%IW0", ElemType::Word, 0xBEEF),
            ("%ID0", ElemType::Real, u64::from(1.5f32.to_bits())),
            ("%ID0", ElemType::Time, (250 * NS_PER_MS) as u64),
            ("%ID0", ElemType::Time, (u32::MAX as i64 * NS_PER_MS) as u64),
            ("%IL0", ElemType::Lreal, 2.5f64.to_bits()),
            ("%IL0", ElemType::Lint, (-7i64) as u64),
        ];
        for (text, ty, raw) in cases {
            let b = binding(text, ty);
            assert_eq!(decode(&b, encode(&b, raw)), raw, "{text} {ty:?}");
        }
    }

    #[test]
    fn a_negative_time_at_a_double_word_wraps_to_unsigned_milliseconds() {
        let b = binding("%QD0", ElemType::Time);
        assert_eq!(encode(&b, (-NS_PER_MS) as u64), u64::from(u32::MAX));
        assert_eq!(
            encode(&b, (-250 * NS_PER_MS) as u64),
            u64::from(u32::MAX - 249)
        );
        assert_eq!(
            decode(&b, u64::from(u32::MAX)),
            (i64::from(u32::MAX) * NS_PER_MS) as u64
        );
    }

    #[test]
    fn words_are_little_endian_and_bits_count_from_the_least_significant() {
        let mut area = vec![0u8; 4];
        put(&mut area, &spot("%IB1"), 0x34);
        put(&mut area, &spot("%IW1"), 0x1234);
        assert_eq!(area, [0, 0x34, 0x34, 0x12]);
        put(&mut area, &spot("%IX3.7"), 1);
        assert_eq!(area[3], 0x92);
        assert_eq!(get(&area, &spot("%IX1.2")), 1);
        assert_eq!(get(&area, &spot("%ID0")), 0x9234_3400);
    }
}

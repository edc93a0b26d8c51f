//! A view of a byte-addressed memory image: a bit of a byte, or a word or
//! double word over consecutive bytes, most significant byte first. This is
//! how the S7-200 front-end's operands (`V6.1`, `VW10`, `VD20`) are read
//! and written from outside the program: each memory area is an array of
//! BYTE slots, and a view combines or splits those slots, so that every view
//! of the same bytes sees the same value, as on the CPU.

/// Which part of the bytes starting at a [`super::names::VarRef`]'s slot a
/// view covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ByteView {
    /// Bit `n` (0 = least significant) of one byte.
    Bit(u8),
    /// `n` consecutive bytes (2 or 4), the first the most significant.
    BigEndian(u8),
}

impl ByteView {
    /// The view's value (a BOOL, WORD or DWORD in slot encoding) over the
    /// byte slots starting at `addr`.
    pub(crate) fn read(self, mem: &[u64], addr: u32) -> u64 {
        let at = |i: u32| mem.get((addr + i) as usize).copied().unwrap_or(0) & 0xFF;
        match self {
            ByteView::Bit(n) => (at(0) >> n) & 1,
            ByteView::BigEndian(len) => (0..u32::from(len)).fold(0, |acc, i| (acc << 8) | at(i)),
        }
    }

    /// Stores `raw` (a value of the view's type) into the byte slots
    /// starting at `addr`, leaving the other bits of a bit's byte as they are.
    pub(crate) fn write(self, mem: &mut [u64], addr: u32, raw: u64) {
        match self {
            ByteView::Bit(n) => {
                if let Some(slot) = mem.get_mut(addr as usize) {
                    let mask = 1u64 << n;
                    *slot = (*slot & !mask) | ((raw & 1) << n);
                }
            }
            ByteView::BigEndian(len) => {
                for i in 0..u32::from(len) {
                    let shift = 8 * (u32::from(len) - 1 - i);
                    if let Some(slot) = mem.get_mut((addr + i) as usize) {
                        *slot = (raw >> shift) & 0xFF;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::ByteView;

    #[test]
    fn views_overlap_big_endian() {
        let mut mem = vec![0u64; 8];
        ByteView::BigEndian(4).write(&mut mem, 2, 0x1234_5678);
        assert_eq!(&mem[2..6], &[0x12, 0x34, 0x56, 0x78]);
        assert_eq!(ByteView::BigEndian(2).read(&mem, 3), 0x3456);
        assert_eq!(ByteView::Bit(3).read(&mem, 2), 0); // 0x12 = 0001_0010
        assert_eq!(ByteView::Bit(4).read(&mem, 2), 1);
        ByteView::Bit(0).write(&mut mem, 5, 1);
        assert_eq!(ByteView::BigEndian(4).read(&mem, 2), 0x1234_5679);
        ByteView::Bit(4).write(&mut mem, 2, 0);
        assert_eq!(mem[2], 0x02);
    }
}

//! Executable memory for the generated code: one anonymous mapping per
//! image, written while it is read-write, then made read-and-execute
//! (never both writable and executable).

use std::ptr::NonNull;

/// Machine code of a set of functions, mapped executable.
pub(crate) struct CodeMemory {
    start: NonNull<u8>,
    /// Bytes mapped (whole pages).
    mapped: usize,
    /// Bytes of code in it.
    used: usize,
}

// SAFETY: the mapping is immutable once made executable and is only read
// (executed) through shared references.
unsafe impl Send for CodeMemory {}
// SAFETY: as above.
unsafe impl Sync for CodeMemory {}

impl CodeMemory {
    /// Maps `pieces` one after another (each at a 16-byte boundary) and
    /// returns the memory and the offset of each piece.
    pub(crate) fn new(pieces: &[Vec<u8>]) -> Result<(CodeMemory, Vec<usize>), String> {
        let mut offsets = Vec::with_capacity(pieces.len());
        let mut used = 0usize;
        for p in pieces {
            used = used.next_multiple_of(16);
            offsets.push(used);
            used += p.len();
        }
        // SAFETY: sysconf has no preconditions.
        let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) }.max(4096) as usize;
        let mapped = used.max(1).next_multiple_of(page);
        // SAFETY: an anonymous private mapping of fresh pages; the result
        // is checked against MAP_FAILED.
        let at = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                mapped,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            )
        };
        if at == libc::MAP_FAILED {
            return Err(format!("mmap of {mapped} bytes failed"));
        }
        let start = NonNull::new(at.cast::<u8>()).ok_or("mmap returned null")?;
        let memory = CodeMemory {
            start,
            mapped,
            used,
        };
        for (p, &off) in pieces.iter().zip(&offsets) {
            // SAFETY: off + p.len() <= used <= mapped, and the mapping is
            // still writable and not shared with anything.
            unsafe { std::ptr::copy_nonoverlapping(p.as_ptr(), start.as_ptr().add(off), p.len()) };
        }
        // SAFETY: the whole mapping, made read-and-execute.
        if unsafe { libc::mprotect(at, mapped, libc::PROT_READ | libc::PROT_EXEC) } != 0 {
            return Err("mprotect to read-and-execute failed".into());
        }
        Ok((memory, offsets))
    }

    /// The address of the byte at `offset`.
    pub(crate) fn at(&self, offset: usize) -> *const u8 {
        debug_assert!(offset < self.used.max(1));
        // SAFETY: offset lies in the mapping.
        unsafe { self.start.as_ptr().add(offset) }
    }

    /// Bytes of code.
    pub(crate) fn used(&self) -> usize {
        self.used
    }
}

impl Drop for CodeMemory {
    fn drop(&mut self) {
        // SAFETY: the mapping this value made; no code in it runs any
        // more (its owner, the machine, is being dropped).
        unsafe { libc::munmap(self.start.as_ptr().cast(), self.mapped) };
    }
}

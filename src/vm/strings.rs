//! STRING/WSTRING storage and the standard string functions. Lengths and
//! positions count characters; positions are 1-based as in IEC.

use super::FaultKind;
use crate::ir::op::StrFn;

/// A string variable with its declared capacity.
#[derive(Debug, Clone, PartialEq)]
pub struct PlcString {
    /// Current value.
    pub text: String,
    /// Maximum length in characters.
    pub max: u32,
    /// WSTRING.
    pub wide: bool,
}

impl PlcString {
    /// A string holding `init` (truncated to `max`).
    pub fn new(init: &str, max: u32, wide: bool) -> PlcString {
        let mut s = PlcString {
            text: String::with_capacity(max as usize),
            max,
            wide,
        };
        s.set(init);
        s
    }

    /// Replaces the value, truncating to the capacity; reuses the buffer.
    pub fn set(&mut self, value: &str) {
        self.text.clear();
        match value.char_indices().nth(self.max as usize) {
            Some((cut, _)) => self.text.push_str(&value[..cut]),
            None => self.text.push_str(value),
        }
    }

    /// The value.
    pub fn as_str(&self) -> &str {
        &self.text
    }

    /// Bytes per character: 1 (STRING) or 2 (WSTRING).
    fn unit(&self) -> u32 {
        if self.wide { 2 } else { 1 }
    }

    /// The size of the CODESYS buffer in bytes: the capacity and the
    /// terminating NUL, `(max + 1)` characters.
    pub fn byte_len(&self) -> u32 {
        (self.max + 1) * self.unit()
    }

    /// Character `i` of the buffer as a code unit: the text, then its
    /// terminating 0, then `tail`, what a byte view wrote past it (else
    /// 0). A STRING character beyond one byte (only a UTF-8 source can
    /// give one) reads as `?`.
    fn unit_at(&self, i: usize, tail: &[u16]) -> u16 {
        let len = if self.text.is_ascii() {
            self.text.len()
        } else {
            self.text.chars().count()
        };
        match i.cmp(&len) {
            std::cmp::Ordering::Less => {
                let c = if self.text.is_ascii() {
                    self.text.as_bytes()[i] as u32
                } else {
                    self.text.chars().nth(i).map_or(0, |c| c as u32)
                };
                code_unit(c, self.wide)
            }
            std::cmp::Ordering::Equal => 0,
            std::cmp::Ordering::Greater => tail.get(i - len - 1).copied().unwrap_or(0),
        }
    }

    /// Byte `k` of the buffer (little-endian characters for WSTRING), with
    /// `tail` the characters kept past the NUL; `k` must be below
    /// [`PlcString::byte_len`].
    pub fn byte_at(&self, k: u32, tail: &[u16]) -> u8 {
        let u = self.unit_at((k / self.unit()) as usize, tail);
        (u >> (8 * (k % self.unit()))) as u8
    }

    /// Writes byte `k` of the buffer as CODESYS does: a character of the
    /// text changes, a 0 ends the text there (the characters after it are
    /// kept past the NUL), a byte past the NUL is kept and joins the text
    /// when the NUL before it is overwritten. The last character position
    /// (`max`) holds the terminator: what is written there reads back 0.
    /// `tail` holds the characters past the NUL, before and after.
    pub fn set_byte(&mut self, k: u32, b: u8, tail: &mut Vec<u16>) {
        let cap = self.max as usize + 1;
        let mut units: Vec<u16> = (0..cap).map(|i| self.unit_at(i, tail)).collect();
        let (i, shift) = ((k / self.unit()) as usize, 8 * (k % self.unit()));
        let Some(u) = units.get_mut(i) else {
            return;
        };
        *u = (*u & !(0xFF << shift)) | ((b as u16) << shift);
        units[cap - 1] = 0;
        let end = units.iter().position(|&u| u == 0).unwrap_or(cap - 1);
        self.text.clear();
        for &u in &units[..end] {
            self.text
                .push(char::from_u32(u as u32).unwrap_or(char::REPLACEMENT_CHARACTER));
        }
        *tail = units.split_off(end + 1);
        while tail.last() == Some(&0) {
            tail.pop();
        }
    }
}

/// A character as a code unit of a STRING (one byte) or WSTRING (16 bits).
fn code_unit(c: u32, wide: bool) -> u16 {
    match (wide, c) {
        (false, 0..=0xFF) | (true, 0..=0xFFFF) => c as u16,
        _ => b'?' as u16,
    }
}

fn char_len(s: &str) -> usize {
    s.chars().count()
}

/// Byte offset of character `n` (clamped to the end).
fn byte_at(s: &str, n: usize) -> usize {
    s.char_indices().nth(n).map(|(i, _)| i).unwrap_or(s.len())
}

fn count(v: u64) -> Result<usize, FaultKind> {
    let v = v as i64;
    if v < 0 {
        return Err(FaultKind::ConversionOverflow);
    }
    Ok(v as usize)
}

/// Runs string function `f`. `args` are the argument slots (string ids or
/// integers as the function defines); `dst` is the destination slot's value
/// (a string id for string results). Returns `Some(v)` for integer results.
pub fn call(
    strings: &mut [PlcString],
    f: StrFn,
    dst: u64,
    args: &[u64; 4],
) -> Result<Option<u64>, FaultKind> {
    let text = |i: usize| strings[args[i] as usize].text.clone();
    let result = match f {
        StrFn::Len => return Ok(Some(char_len(&strings[args[0] as usize].text) as u64)),
        // Needs the memory and the types: run by `string_ops`.
        StrFn::JsonOfSymbol | StrFn::SymbolFromJson => return Ok(None),
        StrFn::Find => {
            let hay = &strings[args[0] as usize].text;
            let needle = &strings[args[1] as usize].text;
            let pos = if needle.is_empty() {
                0
            } else {
                hay.find(needle.as_str())
                    .map(|b| char_len(&hay[..b]) + 1)
                    .unwrap_or(0)
            };
            return Ok(Some(pos as u64));
        }
        StrFn::Left => {
            let s = text(0);
            let n = count(args[1])?;
            s[..byte_at(&s, n)].to_string()
        }
        StrFn::Right => {
            let s = text(0);
            let n = count(args[1])?;
            let len = char_len(&s);
            s[byte_at(&s, len.saturating_sub(n))..].to_string()
        }
        StrFn::Mid => {
            let s = text(0);
            let n = count(args[1])?;
            let pos = count(args[2])?.max(1) - 1;
            let start = byte_at(&s, pos);
            let end = byte_at(&s, pos + n);
            s[start..end.max(start)].to_string()
        }
        StrFn::Concat => {
            let mut s = text(0);
            s.push_str(&strings[args[1] as usize].text);
            s
        }
        StrFn::Insert => {
            let s = text(0);
            let pos = byte_at(&s, count(args[2])?);
            format!(
                "{}{}{}",
                &s[..pos],
                strings[args[1] as usize].text,
                &s[pos..]
            )
        }
        StrFn::Delete => {
            let s = text(0);
            let n = count(args[1])?;
            let pos = count(args[2])?.max(1) - 1;
            let start = byte_at(&s, pos);
            let end = byte_at(&s, pos + n);
            format!("{}{}", &s[..start], &s[end.max(start)..])
        }
        StrFn::Replace => {
            let s = text(0);
            let n = count(args[2])?;
            let pos = count(args[3])?.max(1) - 1;
            let start = byte_at(&s, pos);
            let end = byte_at(&s, pos + n);
            format!(
                "{}{}{}",
                &s[..start],
                strings[args[1] as usize].text,
                &s[end.max(start)..]
            )
        }
    };
    strings[dst as usize].set(&result);
    Ok(None)
}

#[cfg(test)]
mod byte_tests {
    use super::PlcString;

    #[test]
    fn bytes_of_a_string_buffer() {
        // STRING(5) 'AB': bytes A B NUL then zeros, 6 bytes in all.
        let mut s = PlcString::new("AB", 5, false);
        let mut tail = Vec::new();
        assert_eq!(s.byte_len(), 6);
        let bytes: Vec<u8> = (0..6).map(|k| s.byte_at(k, &tail)).collect();
        assert_eq!(bytes, [b'A', b'B', 0, 0, 0, 0]);
        // a byte past the NUL is kept, and joins when the NUL goes
        s.set_byte(3, b'D', &mut tail);
        assert_eq!((s.as_str(), s.byte_at(3, &tail)), ("AB", b'D'));
        s.set_byte(2, b'C', &mut tail);
        assert_eq!(s.as_str(), "ABCD");
        // a 0 ends the text; what follows stays in the buffer
        s.set_byte(1, 0, &mut tail);
        assert_eq!((s.as_str(), s.byte_at(2, &tail)), ("A", b'C'));
        // the last position is the terminator
        s.set_byte(1, b'B', &mut tail);
        s.set_byte(4, b'E', &mut tail);
        s.set_byte(5, b'F', &mut tail);
        assert_eq!((s.as_str(), s.byte_at(5, &tail)), ("ABCDE", 0));
    }

    #[test]
    fn latin1_and_wide_characters() {
        let mut tail = Vec::new();
        let mut s = PlcString::new("\u{e4}x", 4, false);
        assert_eq!((s.byte_at(0, &tail), s.byte_at(1, &tail)), (0xE4, b'x'));
        s.set_byte(1, 0xF6, &mut tail);
        assert_eq!(s.as_str(), "\u{e4}\u{f6}");
        let mut w = PlcString::new("\u{20ac}", 2, true);
        assert_eq!(
            (w.byte_len(), w.byte_at(0, &tail), w.byte_at(1, &tail)),
            (6, 0xAC, 0x20)
        );
        w.set_byte(2, b'a', &mut tail);
        assert_eq!(w.as_str(), "\u{20ac}a");
    }
}

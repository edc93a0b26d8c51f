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

//! Reading source bytes into text: UTF-8 (with or without a byte-order
//! mark), Windows-1252 (CODESYS and Moeller exports) or Latin-1, given or
//! detected.
//!
//! Windows-1252 differs from Latin-1 only in the 32 bytes 0x80-0x9F; that
//! table is all this module needs. Its five undefined bytes (0x81, 0x8D,
//! 0x8F, 0x90, 0x9D) decode to the C1 control characters of the same
//! number, so that every byte survives: inside a STRING literal it stays
//! that byte, inside a comment it does no harm, in code it is an invalid
//! character (E001) like any other control character.

use std::fmt;
use std::str::FromStr;

/// How the bytes of a source file are to be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SourceEncoding {
    /// Valid UTF-8 is UTF-8; a file with no valid multi-byte UTF-8
    /// sequence but other bytes above 0x7F is Windows-1252 (with warning
    /// W020); a file mixing both is damaged UTF-8 (E011).
    #[default]
    Detect,
    /// UTF-8 only: any other byte is E011.
    Utf8,
    /// Windows-1252 (code page 1252), the Western code page of Windows.
    Windows1252,
    /// ISO 8859-1: each byte is the character of the same number.
    Latin1,
}

impl SourceEncoding {
    /// The name accepted by `--encoding` for this choice.
    pub fn name(self) -> &'static str {
        match self {
            SourceEncoding::Detect => "detect",
            SourceEncoding::Utf8 => "utf-8",
            SourceEncoding::Windows1252 => "windows-1252",
            SourceEncoding::Latin1 => "latin-1",
        }
    }
}

/// `--encoding` named no encoding plcrun reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownEncoding(pub String);

impl fmt::Display for UnknownEncoding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown encoding `{}` (use utf-8, windows-1252, latin-1 or detect)",
            self.0
        )
    }
}

impl std::error::Error for UnknownEncoding {}

impl FromStr for SourceEncoding {
    type Err = UnknownEncoding;

    /// Reads `utf-8`, `windows-1252`, `latin-1` or `detect`, ignoring case,
    /// `-`/`_` and the usual aliases (`utf8`, `cp1252`, `iso-8859-1`).
    ///
    /// ```
    /// use plcrun::SourceEncoding;
    /// assert_eq!("CP1252".parse(), Ok(SourceEncoding::Windows1252));
    /// assert_eq!("iso-8859-1".parse(), Ok(SourceEncoding::Latin1));
    /// assert!("ebcdic".parse::<SourceEncoding>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let key: String = s
            .chars()
            .filter(|c| !matches!(c, '-' | '_'))
            .collect::<String>()
            .to_ascii_lowercase();
        match key.as_str() {
            "detect" | "auto" => Ok(SourceEncoding::Detect),
            "utf8" => Ok(SourceEncoding::Utf8),
            "windows1252" | "cp1252" | "win1252" => Ok(SourceEncoding::Windows1252),
            "latin1" | "iso88591" => Ok(SourceEncoding::Latin1),
            _ => Err(UnknownEncoding(s.to_string())),
        }
    }
}

/// The encoding a file's text was actually read in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TextEncoding {
    /// UTF-8 (possibly damaged: see [`Decoded::invalid_utf8_at`]).
    #[default]
    Utf8,
    /// Windows-1252.
    Windows1252,
    /// Latin-1.
    Latin1,
}

impl TextEncoding {
    /// The byte a STRING literal keeps for character `c` of a source read
    /// in this encoding, when it differs from the character's number: the
    /// Windows-1252 characters of 0x80-0x9F (`€` is byte 0x80, not U+20AC).
    pub fn string_byte(self, c: char) -> Option<u8> {
        if self != TextEncoding::Windows1252 || (c as u32) < 0x100 {
            return None;
        }
        WINDOWS_1252_HIGH
            .iter()
            .position(|&m| m == c)
            .map(|i| 0x80 + i as u8)
    }
}

impl fmt::Display for TextEncoding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            TextEncoding::Utf8 => "UTF-8",
            TextEncoding::Windows1252 => "Windows-1252",
            TextEncoding::Latin1 => "Latin-1",
        })
    }
}

/// Bytes 0x80-0x9F of Windows-1252 (the undefined ones as the C1 control
/// of the same number).
const WINDOWS_1252_HIGH: [char; 32] = [
    '\u{20AC}', '\u{0081}', '\u{201A}', '\u{0192}', '\u{201E}', '\u{2026}', '\u{2020}', '\u{2021}',
    '\u{02C6}', '\u{2030}', '\u{0160}', '\u{2039}', '\u{0152}', '\u{008D}', '\u{017D}', '\u{008F}',
    '\u{0090}', '\u{2018}', '\u{2019}', '\u{201C}', '\u{201D}', '\u{2022}', '\u{2013}', '\u{2014}',
    '\u{02DC}', '\u{2122}', '\u{0161}', '\u{203A}', '\u{0153}', '\u{009D}', '\u{017E}', '\u{0178}',
];

/// A file's bytes read as text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decoded {
    /// The text (UTF-8 in memory, whatever the file's encoding).
    pub text: String,
    /// The encoding it was read in.
    pub encoding: TextEncoding,
    /// Set when the encoding was detected rather than given: the byte
    /// offset in `text` of the first character that was not UTF-8, and
    /// that byte's value.
    pub detected_at: Option<(usize, u8)>,
    /// Set when the text was to be UTF-8 but is not: the byte offset of the
    /// first invalid byte (invalid bytes are replaced by U+FFFD).
    pub invalid_utf8_at: Option<usize>,
}

/// Reads `bytes` as `encoding` says. Never fails: bytes that are not
/// UTF-8 where UTF-8 is required become U+FFFD and are reported through
/// [`Decoded::invalid_utf8_at`].
///
/// ```
/// use plcrun::{SourceEncoding, TextEncoding, decode_source};
/// let d = decode_source(b"(* Gr\xfc\xdfe *) x", SourceEncoding::Detect);
/// assert_eq!(d.text, "(* Grüße *) x");
/// assert_eq!(d.encoding, TextEncoding::Windows1252);
/// assert_eq!(d.detected_at, Some((5, 0xfc)));
/// ```
pub fn decode_source(bytes: &[u8], encoding: SourceEncoding) -> Decoded {
    let single = |encoding: TextEncoding, detected_at| Decoded {
        text: bytes.iter().map(|&b| byte_char(b, encoding)).collect(),
        encoding,
        detected_at,
        invalid_utf8_at: None,
    };
    match encoding {
        SourceEncoding::Windows1252 => single(TextEncoding::Windows1252, None),
        SourceEncoding::Latin1 => single(TextEncoding::Latin1, None),
        SourceEncoding::Utf8 => utf8(bytes),
        SourceEncoding::Detect => {
            let Err(e) = std::str::from_utf8(bytes) else {
                return utf8(bytes);
            };
            if has_utf8_sequence(bytes) {
                return utf8(bytes);
            }
            // Everything before the first bad byte is ASCII here, so its
            // offset is the same in the bytes and in the text.
            let at = e.valid_up_to();
            single(TextEncoding::Windows1252, Some((at, bytes[at])))
        }
    }
}

/// `bytes` as UTF-8, lossily when they are not.
fn utf8(bytes: &[u8]) -> Decoded {
    let invalid_utf8_at = std::str::from_utf8(bytes).err().map(|e| e.valid_up_to());
    Decoded {
        text: String::from_utf8_lossy(bytes).into_owned(),
        encoding: TextEncoding::Utf8,
        detected_at: None,
        invalid_utf8_at,
    }
}

/// True when `bytes` hold at least one valid multi-byte UTF-8 sequence: a
/// file that has one next to invalid bytes is damaged UTF-8, not a file in
/// a single-byte code page (where such pairs, like `Ã©`, hardly occur).
fn has_utf8_sequence(bytes: &[u8]) -> bool {
    bytes.utf8_chunks().any(|chunk| !chunk.valid().is_ascii())
}

/// The character of byte `b` in a single-byte `encoding`.
fn byte_char(b: u8, encoding: TextEncoding) -> char {
    match b {
        0x80..=0x9F if encoding == TextEncoding::Windows1252 => {
            WINDOWS_1252_HIGH[usize::from(b - 0x80)]
        }
        _ => char::from(b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_windows_1252_byte_maps_back_to_itself_in_a_string() {
        for b in 0x80..=0x9Fu8 {
            let c = byte_char(b, TextEncoding::Windows1252);
            let back = TextEncoding::Windows1252
                .string_byte(c)
                .unwrap_or(c as u32 as u8);
            assert_eq!(back, b, "{c:?}");
        }
        assert_eq!(TextEncoding::Windows1252.string_byte('ä'), None);
        assert_eq!(TextEncoding::Utf8.string_byte('€'), None);
    }

    #[test]
    fn detection_follows_the_bytes() {
        assert_eq!(
            decode_source(b"abc", SourceEncoding::Detect).detected_at,
            None
        );
        let bom = decode_source(b"\xef\xbb\xbfx \xc3\xa4", SourceEncoding::Detect);
        assert_eq!(bom.encoding, TextEncoding::Utf8);
        assert_eq!(bom.text, "\u{feff}x ä");
        let mixed = decode_source(b"\xc3\xa4 \xe4", SourceEncoding::Detect);
        assert_eq!(mixed.encoding, TextEncoding::Utf8);
        assert_eq!(mixed.invalid_utf8_at, Some(3));
        let cp = decode_source(b"a\x80\x81", SourceEncoding::Detect);
        assert_eq!(cp.text, "a\u{20ac}\u{81}");
        assert_eq!(cp.detected_at, Some((1, 0x80)));
        let latin = decode_source(b"\x80\xe4", SourceEncoding::Latin1);
        assert_eq!(latin.text, "\u{80}ä");
        assert_eq!(
            decode_source(b"\xe4", SourceEncoding::Utf8).invalid_utf8_at,
            Some(0)
        );
    }
}

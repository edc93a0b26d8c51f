//! Source files given as bytes: read in the encoding asked for (or
//! detected), with a diagnostic saying what was assumed or what is wrong.

use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::encoding::{SourceEncoding, decode_source};
use crate::source::{FileId, SourceMap, Span};

/// Diagnostic code of a file that is not valid UTF-8 (and not read as a
/// single-byte code page).
const INVALID_UTF8: &str = "E011";

/// Warning code of a file detected as Windows-1252.
const DETECTED_1252: &str = "W020";

/// Adds the file `name` with content `bytes` to `sources`, read as
/// `encoding` says: a file detected as Windows-1252 gets a `W020` warning
/// naming its first non-UTF-8 byte; a file that should be UTF-8 and is not
/// is kept (invalid bytes replaced by U+FFFD) with an `E011` error, so
/// that its other errors are still found.
pub fn add_source_bytes(
    sources: &mut SourceMap,
    name: impl Into<String>,
    bytes: &[u8],
    encoding: SourceEncoding,
    diags: &mut Diagnostics,
) -> FileId {
    let decoded = decode_source(bytes, encoding);
    let id = sources.add_encoded(name, decoded.text, decoded.encoding);
    if let Some((at, byte)) = decoded.detected_at {
        let shown = sources.file(id).text[at..].chars().next().unwrap_or('?');
        let end = at + shown.len_utf8();
        diags.push(
            Diagnostic::warning(
                DETECTED_1252,
                Span::new(id, at, end),
                format!(
                    "the file is not UTF-8: read as Windows-1252 (byte {byte:#04X} is `{}`)",
                    shown.escape_debug()
                ),
            )
            .with_note(
                "say so with `--encoding windows-1252` (or latin-1), or save the file as UTF-8",
            ),
        );
    }
    if let Some(at) = decoded.invalid_utf8_at {
        let mut d = Diagnostic::error(
            INVALID_UTF8,
            Span::new(id, at, at + 1),
            "the file is not valid UTF-8 (invalid bytes replaced by U+FFFD)",
        );
        d = d.with_note(if encoding == SourceEncoding::Detect {
            "it also holds valid UTF-8 sequences, so it was not taken for Windows-1252; \
             `--encoding windows-1252` or `latin-1` reads it in a single-byte code page"
        } else {
            "if it is in a single-byte code page, `--encoding windows-1252` or `latin-1` \
             (plcrun run and check) reads it"
        });
        diags.push(d);
    }
    id
}

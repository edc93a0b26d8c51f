//! LSP positions (line, and column in UTF-16 code units unless the client
//! agreed to UTF-8) to byte offsets of a file's text, and back.

use lsp_types::{Position, Range};
use plcrun::SourceFile;

/// How columns are counted, as negotiated at initialisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Columns {
    /// UTF-8 bytes.
    Utf8,
    /// UTF-16 code units (the protocol's default).
    Utf16,
}

impl Columns {
    /// The byte offset of `pos` in `file` (clamped to the text).
    pub fn offset(self, file: &SourceFile, pos: Position) -> u32 {
        let starts = file.line_starts();
        let text = &file.text;
        let Some(&line_start) = starts.get(pos.line as usize) else {
            return text.len() as u32;
        };
        let line_end = starts
            .get(pos.line as usize + 1)
            .copied()
            .unwrap_or(text.len());
        let line = &text[line_start..line_end];
        let mut units = 0u32;
        for (i, c) in line.char_indices() {
            if units >= pos.character || c == '\n' || c == '\r' {
                return (line_start + i) as u32;
            }
            units += self.width(c);
        }
        line_end as u32
    }

    /// The position of byte `offset` of `file`.
    pub fn position(self, file: &SourceFile, offset: u32) -> Position {
        let starts = file.line_starts();
        let offset = (offset as usize).min(file.text.len());
        let line = starts.partition_point(|&s| s <= offset).saturating_sub(1);
        let start = starts.get(line).copied().unwrap_or(0);
        let column = match file.text.get(start..offset) {
            Some(prefix) => prefix.chars().map(|c| self.width(c)).sum(),
            None => (offset - start) as u32,
        };
        Position::new(line as u32, column)
    }

    /// The range of bytes `start..end` of `file`.
    pub fn range(self, file: &SourceFile, start: u32, end: u32) -> Range {
        Range::new(self.position(file, start), self.position(file, end))
    }

    fn width(self, c: char) -> u32 {
        match self {
            Columns::Utf8 => c.len_utf8() as u32,
            Columns::Utf16 => c.len_utf16() as u32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_columns_count_surrogate_pairs_and_accents() {
        let file = SourceFile::new("a.st", "x := 1;\n(* é𝄞 *) y := 2;\n");
        let y = file.text.find('y').unwrap() as u32;
        let pos = Columns::Utf16.position(&file, y);
        assert_eq!(pos, Position::new(1, 10));
        assert_eq!(Columns::Utf16.offset(&file, pos), y);
        let pos8 = Columns::Utf8.position(&file, y);
        assert_eq!(pos8, Position::new(1, 13));
        assert_eq!(Columns::Utf8.offset(&file, pos8), y);
        // Past the end of a line: its end; past the last line: the text's end.
        assert_eq!(Columns::Utf16.offset(&file, Position::new(0, 99)), 7);
        assert_eq!(
            Columns::Utf16.offset(&file, Position::new(9, 0)),
            file.text.len() as u32
        );
    }
}

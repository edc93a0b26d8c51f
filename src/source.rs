//! Source files and byte spans into them.
//!
//! Every AST node, diagnostic and runtime fault points back into the text the
//! user wrote through a [`Span`]; [`SourceMap`] turns a span into
//! `file:line:column` and an excerpt. [`encoding`] reads a file's bytes
//! into that text.

pub mod encoding;

use encoding::TextEncoding;

/// Index of a file inside a [`SourceMap`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct FileId(pub u32);

/// A half-open byte range `start..end` in one source file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// The file the range belongs to.
    pub file: FileId,
    /// Byte offset of the first character.
    pub start: u32,
    /// Byte offset one past the last character.
    pub end: u32,
}

impl Span {
    /// A span covering `start..end` in `file`.
    pub fn new(file: FileId, start: usize, end: usize) -> Span {
        Span {
            file,
            start: start as u32,
            end: end as u32,
        }
    }

    /// The smallest span covering both `self` and `other` (same file assumed).
    pub fn to(self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }
}

/// One loaded source file.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// The name shown in messages (the path as the user gave it).
    pub name: String,
    /// The full text.
    pub text: String,
    line_starts: Vec<usize>,
    encoding: TextEncoding,
    library: bool,
}

impl SourceFile {
    /// Wraps `text` under the display name `name`.
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> SourceFile {
        let text = text.into();
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        SourceFile {
            name: name.into(),
            text,
            line_starts,
            encoding: TextEncoding::Utf8,
            library: false,
        }
    }

    /// The same file, marked as read from `encoding` (a STRING literal of
    /// a Windows-1252 file keeps the file's bytes, see
    /// [`TextEncoding::string_byte`]).
    pub fn with_encoding(mut self, encoding: TextEncoding) -> SourceFile {
        self.encoding = encoding;
        self
    }

    /// Whether the file belongs to a library project loaded with an
    /// application (TwinCAT runs no implicit check in a library's code).
    pub fn is_library(&self) -> bool {
        self.library
    }

    /// The encoding the file's bytes were read in (UTF-8 for text given
    /// as a `&str`).
    pub fn encoding(&self) -> TextEncoding {
        self.encoding
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: u32) -> (usize, usize) {
        let offset = (offset as usize).min(self.text.len());
        let line = match self.line_starts.binary_search(&offset) {
            Ok(l) => l,
            Err(l) => l - 1,
        };
        let start = self.line_starts[line];
        let col = self
            .text
            .get(start..offset)
            .map(|s| s.chars().count())
            .unwrap_or(offset - start);
        (line + 1, col + 1)
    }

    /// The text of 1-based line `line`, without its line terminator.
    pub fn line_text(&self, line: usize) -> &str {
        let Some(&start) = self.line_starts.get(line.wrapping_sub(1)) else {
            return "";
        };
        let end = self
            .line_starts
            .get(line)
            .copied()
            .unwrap_or(self.text.len());
        self.text[start..end].trim_end_matches(['\n', '\r'])
    }

    /// Byte ranges of all lines (used by renderers).
    pub fn line_starts(&self) -> &[usize] {
        &self.line_starts
    }
}

/// All files of one compilation.
#[derive(Debug, Clone, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

/// `text` with each of `ranges` (whole tokens, declarations or XML
/// elements) turned into spaces, its line breaks kept, so that the rest
/// keeps its offsets, lines and columns; `None` when a range is out of
/// the text or cuts a character in two.
pub(crate) fn blank_out(
    text: &str,
    ranges: impl IntoIterator<Item = std::ops::Range<usize>>,
) -> Option<String> {
    let mut bytes = text.as_bytes().to_vec();
    for range in ranges {
        for b in bytes.get_mut(range)? {
            if !matches!(*b, b'\n' | b'\r') {
                *b = b' ';
            }
        }
    }
    String::from_utf8(bytes).ok()
}

impl SourceMap {
    /// An empty map.
    pub fn new() -> SourceMap {
        SourceMap::default()
    }

    /// Adds a file and returns its id.
    pub fn add(&mut self, name: impl Into<String>, text: impl Into<String>) -> FileId {
        self.files.push(SourceFile::new(name, text));
        FileId((self.files.len() - 1) as u32)
    }

    /// Marks file `id` as one of a library project's (see
    /// [`SourceFile::is_library`]).
    pub fn mark_library(&mut self, id: FileId) {
        if let Some(file) = self.files.get_mut(id.0 as usize) {
            file.library = true;
        }
    }

    /// Adds a file whose text was read in `encoding`, and returns its id.
    pub fn add_encoded(
        &mut self,
        name: impl Into<String>,
        text: impl Into<String>,
        encoding: TextEncoding,
    ) -> FileId {
        self.files
            .push(SourceFile::new(name, text).with_encoding(encoding));
        FileId((self.files.len() - 1) as u32)
    }

    /// The file with id `id`.
    pub fn file(&self, id: FileId) -> &SourceFile {
        &self.files[id.0 as usize]
    }

    /// All files, in the order they were added.
    pub fn files(&self) -> &[SourceFile] {
        &self.files
    }

    /// The map without the files `drop` names, the others in their order
    /// (their ids renumbered).
    pub fn without(&self, drop: &std::collections::HashSet<FileId>) -> SourceMap {
        let files = self.files.iter().enumerate();
        SourceMap {
            files: files
                .filter(|(i, _)| !drop.contains(&FileId(*i as u32)))
                .map(|(_, f)| f.clone())
                .collect(),
        }
    }

    /// The map with file `id`'s text replaced by `text`, its name, place
    /// and encoding kept.
    pub fn with_text(&self, id: FileId, text: impl Into<String>) -> SourceMap {
        let mut files = self.files.clone();
        let old = &self.files[id.0 as usize];
        files[id.0 as usize] =
            SourceFile::new(old.name.clone(), text).with_encoding(old.encoding());
        SourceMap { files }
    }

    /// `name:line:column` of the start of `span`.
    pub fn location(&self, span: Span) -> String {
        let file = self.file(span.file);
        let (line, col) = file.line_col(span.start);
        format!("{}:{}:{}", file.name, line, col)
    }
}

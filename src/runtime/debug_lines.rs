//! Where statements start, for a debugger: the line of every instruction
//! (from the spans the faults use), and the instructions that start a
//! line's code, where the debugger stops, breakpoints are set and steps end.
//!
//! The IR has no statement markers: an instruction starts a statement when
//! it is the first of its block or the previous instruction is on another
//! line. One line of ST or IL is so one stopping place (an IL line is one
//! instruction; a multi-line ST expression gives one place per line).

use crate::ir::image::Image;
use crate::ir::op::{CodeIdx, Op};
use crate::source::SourceMap;
use std::path::Path;
use std::sync::Arc;

/// The lines of a compiled program's instructions and its statement starts.
#[derive(Debug, Clone)]
pub struct LineTable {
    /// Per code block, per instruction: `(file index, 1-based line)`, or
    /// `None` for an instruction without a source place.
    lines: Vec<Vec<Option<(u32, u32)>>>,
    /// Per code block, per instruction: a statement starts there.
    starts: Arc<Vec<Vec<bool>>>,
    /// The files' names, as loaded.
    files: Vec<String>,
}

impl LineTable {
    /// The table of `image`, whose spans point into `sources`.
    pub fn new(image: &Image, sources: &SourceMap) -> LineTable {
        let files: Vec<String> = sources.files().iter().map(|f| f.name.clone()).collect();
        let mut lines = Vec::with_capacity(image.codes.len());
        let mut starts = Vec::with_capacity(image.codes.len());
        for block in &image.codes {
            let mut bl = Vec::with_capacity(block.ops.len());
            let mut st = Vec::with_capacity(block.ops.len());
            let mut previous = None;
            for (pc, op) in block.ops.iter().enumerate() {
                let span = block.spans.get(pc).copied().unwrap_or_default();
                let place = (span.end > 0 && (span.file.0 as usize) < files.len()).then(|| {
                    let file = sources.file(span.file);
                    (span.file.0, file.line_col(span.start).0 as u32)
                });
                let operand = matches!(op, Op::Operand { .. });
                st.push(place.is_some() && !operand && place != previous);
                if place.is_some() {
                    previous = place;
                }
                bl.push(place);
            }
            lines.push(bl);
            starts.push(st);
        }
        LineTable {
            lines,
            starts: Arc::new(starts),
            files,
        }
    }

    /// Per code block, per instruction: whether a statement starts there.
    pub(crate) fn starts(&self) -> &Arc<Vec<Vec<bool>>> {
        &self.starts
    }

    /// The index of the loaded file that `name` designates: the same name,
    /// the same file on disk, or a path ending with the loaded name.
    pub fn file_index(&self, name: &str) -> Option<usize> {
        if let Some(k) = self.files.iter().position(|f| f == name) {
            return Some(k);
        }
        let wanted = Path::new(name).canonicalize().ok();
        if let Some(wanted) = &wanted
            && let Some(k) = self
                .files
                .iter()
                .position(|f| Path::new(f).canonicalize().ok().as_ref() == Some(wanted))
        {
            return Some(k);
        }
        self.files.iter().position(|f| {
            let f = f.trim_start_matches("./");
            name.ends_with(f) && name[..name.len() - f.len()].ends_with(['/', '\\'])
        })
    }

    /// The statement starts on `line` of file number `file`, or when the
    /// line has none, on the next line that has some: that line and the
    /// `(code, pc)` places. `None` past the file's last statement.
    pub fn statements_at(&self, file: usize, line: u32) -> Option<(u32, Vec<(CodeIdx, u32)>)> {
        let mut best: Option<u32> = None;
        for (c, block) in self.lines.iter().enumerate() {
            for (pc, place) in block.iter().enumerate() {
                if let Some((f, l)) = place
                    && *f as usize == file
                    && *l >= line
                    && self.starts[c][pc]
                    && best.is_none_or(|b| *l < b)
                {
                    best = Some(*l);
                }
            }
        }
        let at = best?;
        let mut places = Vec::new();
        for (c, block) in self.lines.iter().enumerate() {
            for (pc, place) in block.iter().enumerate() {
                if *place == Some((file as u32, at)) && self.starts[c][pc] {
                    places.push((CodeIdx::new(c as u32), pc as u32));
                }
            }
        }
        Some((at, places))
    }
}

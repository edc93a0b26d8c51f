//! Where statements start, for a debugger: the line of every instruction
//! (from the spans the faults use), and the instructions that start a
//! line's code, where the debugger stops, breakpoints are set and steps end.
//!
//! The IR has no statement markers: an instruction starts a statement when
//! it is the first of its block or the previous instruction is on another
//! line. One line of ST or IL is so one stopping place (an IL line is one
//! instruction; a multi-line ST expression gives one place per line).

use crate::ir::image::Image;
use crate::ir::op::{ChartIdx, CodeIdx, Op};
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
    /// The lines of the SFC charts' steps, action associations and
    /// transitions (textual SFC, or the elements of a chart drawn in
    /// PLCopen XML).
    sfc: Vec<SfcPlace>,
}

/// What of an SFC chart a breakpoint watches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum SfcElement {
    /// A step becoming active.
    Step(u32),
    /// An action running (an association of it in a step).
    Action(u32),
    /// A transition firing.
    Transition(u32),
}

/// An SFC element's line.
#[derive(Debug, Clone)]
pub(crate) struct SfcPlace {
    pub chart: ChartIdx,
    pub element: SfcElement,
    /// The file's index and the 1-based line.
    pub file: usize,
    pub line: u32,
    /// The step's or action's name; `FROM -> TO` for a transition.
    pub name: String,
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
        let sfc = sfc_places(image, sources);
        LineTable {
            lines,
            starts: Arc::new(starts),
            files,
            sfc,
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

    /// The SFC elements on `line` of file number `file`.
    pub(crate) fn sfc_at(&self, file: usize, line: u32) -> Vec<&SfcPlace> {
        self.sfc
            .iter()
            .filter(|p| p.file == file && p.line == line)
            .collect()
    }

    /// The place of an SFC element.
    pub(crate) fn sfc_place(&self, chart: ChartIdx, element: SfcElement) -> Option<&SfcPlace> {
        self.sfc
            .iter()
            .find(|p| p.chart == chart && p.element == element)
    }

    /// A loaded file's name.
    pub(crate) fn file_name(&self, file: usize) -> Option<&str> {
        self.files.get(file).map(String::as_str)
    }
}

/// The words (identifiers) of a line, in order.
fn words(line: &str) -> Vec<&str> {
    line.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .collect()
}

/// The lines of the steps, associations and transitions of every chart
/// written in textual SFC, read from the text of the POU that runs it
/// (from its `Sfc` instruction's place to its `END_` line).
fn sfc_places(image: &Image, sources: &SourceMap) -> Vec<SfcPlace> {
    let mut places = Vec::new();
    for block in &image.codes {
        for (pc, op) in block.ops.iter().enumerate() {
            let Op::Sfc { chart } = *op else {
                continue;
            };
            let Some(c) = image.charts.get(chart.index()) else {
                continue;
            };
            let span = block.spans.get(pc).copied().unwrap_or_default();
            if span.end == 0 || span.file.0 as usize >= sources.files().len() {
                continue;
            }
            let file = sources.file(span.file);
            if file.text.trim_start().starts_with('<') {
                // A chart drawn in PLCopen XML.
                let found = super::debug_sfc_xml::xml_places(c, &file.text, span.start as usize);
                places.extend(found.into_iter().map(|(element, line, name)| SfcPlace {
                    chart,
                    element,
                    file: span.file.0 as usize,
                    line,
                    name,
                }));
                continue;
            }
            let (first, _) = file.line_col(span.start);
            let step_of = |name: &str| {
                c.steps
                    .iter()
                    .position(|s| s.name.eq_ignore_ascii_case(name))
                    .map(|k| k as u32)
            };
            let mut in_step = false;
            for (k, text) in file.text.lines().enumerate().skip(first.saturating_sub(1)) {
                let line = k as u32 + 1;
                let w = words(text);
                let Some(head) = w.first().map(|h| h.to_ascii_uppercase()) else {
                    continue;
                };
                let mut add = |element, name: String| {
                    places.push(SfcPlace {
                        chart,
                        element,
                        file: span.file.0 as usize,
                        line,
                        name,
                    })
                };
                match head.as_str() {
                    "END_PROGRAM" | "END_FUNCTION_BLOCK" => break,
                    "STEP" | "INITIAL_STEP" => {
                        if let Some(s) = w.get(1).and_then(|n| step_of(n)) {
                            add(SfcElement::Step(s), c.steps[s as usize].name.clone());
                        }
                        in_step = !text.to_ascii_uppercase().contains("END_STEP");
                    }
                    "END_STEP" => in_step = false,
                    "ACTION" => in_step = false,
                    "TRANSITION" => {
                        let upper: Vec<String> = w.iter().map(|x| x.to_ascii_uppercase()).collect();
                        let from_at = upper.iter().position(|x| x == "FROM");
                        let to_at = upper.iter().position(|x| x == "TO");
                        let (Some(f), Some(t)) = (from_at, to_at) else {
                            continue;
                        };
                        let mut from: Vec<u32> =
                            w[f + 1..t].iter().filter_map(|n| step_of(n)).collect();
                        let mut to: Vec<u32> =
                            w[t + 1..].iter().map_while(|n| step_of(n)).collect();
                        from.sort_unstable();
                        to.sort_unstable();
                        let found = c.transitions.iter().position(|tr| {
                            let mut a = tr.from.clone();
                            let mut b = tr.to.clone();
                            a.sort_unstable();
                            b.sort_unstable();
                            a == from && b == to
                        });
                        if let Some(tr) = found {
                            let name = format!(
                                "{} -> {}",
                                w[f + 1..t].join(", "),
                                w[t + 1..t + 1 + to.len()].join(", ")
                            );
                            add(SfcElement::Transition(tr as u32), name);
                        }
                    }
                    _ if in_step => {
                        if let Some(a) = c
                            .actions
                            .iter()
                            .position(|a| a.name.eq_ignore_ascii_case(w[0]))
                        {
                            add(SfcElement::Action(a as u32), c.actions[a].name.clone());
                        }
                    }
                    _ => {}
                }
            }
        }
    }
    places
}

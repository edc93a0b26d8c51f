//! Stimulus files: CSV tables of input values applied while a program runs.
//!
//! ```text
//! # comment lines and blank lines are skipped
//! time,  start, speed, %IX0.1, msg
//! 0ms,   TRUE,  10,    FALSE,  'idle'
//! 150ms, ,      20,    ,       "'a,b'"
//! T#1.5s,FALSE, ,      TRUE,
//! ```
//!
//! The first header is the key: `cycle` (whole numbers ≥ 0) or `time`
//! (non-negative durations such as `150ms`, `1.5s`, `T#1.5s`, `TIME#2m`),
//! case-insensitive. The other headers name variables exactly as the user
//! wrote them (trimmed): program variables, dotted paths, array elements,
//! located addresses. Resolving them is the caller's job.
//!
//! Every following row holds a key and one cell per variable. Cells are kept
//! as trimmed text (the caller decodes the IEC literal against the variable's
//! type); an empty cell means "leave the variable unchanged". Rows must come
//! in non-decreasing key order. Standard CSV quoting works, so a STRING cell
//! containing a comma is written `"'a,b'"` (the quote must be the first
//! character of the field). A line whose first non-blank character is `#` is a
//! comment; a line holding only blanks and commas is skipped as well.

use crate::value::literal::{format_duration, parse_duration_body};
use std::collections::HashMap;
use std::fmt;

/// What the first column of a stimulus counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StimulusKey {
    /// Cycle numbers, counting from 0.
    Cycle,
    /// Times on the scheduler's clock, in nanoseconds.
    Time,
}

/// A parsed stimulus file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Stimulus {
    /// Whether rows are keyed by cycle number or by time.
    pub key: StimulusKey,
    /// The variable names from the header (without the key column), trimmed,
    /// as written.
    pub columns: Vec<String>,
    /// The rows, in non-decreasing key order.
    pub rows: Vec<StimulusRow>,
}

/// One row of a stimulus.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StimulusRow {
    /// The 1-based line of the file where the row starts.
    pub line: usize,
    /// The key: a cycle number, or a time in nanoseconds.
    pub at: i64,
    /// One cell per entry of [`Stimulus::columns`]: the trimmed text, or
    /// `None` when the cell is empty (leave the variable unchanged).
    pub cells: Vec<Option<String>>,
}

/// Why a stimulus file was rejected.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StimulusError {
    /// The 1-based line of the file.
    pub line: usize,
    /// The 1-based CSV field concerned, when there is one (1 is the key
    /// column).
    pub column: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl StimulusError {
    fn new(line: usize, column: Option<usize>, message: impl Into<String>) -> Self {
        StimulusError {
            line,
            column,
            message: message.into(),
        }
    }
}

impl fmt::Display for StimulusError {
    /// `line 3: ...`
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for StimulusError {}

/// Parses the text of a stimulus CSV file (see the module docs).
pub fn parse_stimulus(text: &str) -> Result<Stimulus, StimulusError> {
    let text = text.strip_prefix('\u{FEFF}').unwrap_or(text);
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        // Row lengths are checked here, to name the line and the counts.
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());

    let mut header: Option<(StimulusKey, Vec<String>)> = None;
    let mut rows: Vec<StimulusRow> = Vec::new();
    let mut record = csv::StringRecord::new();
    let mut lines = LineCounter {
        text: text.as_bytes(),
        byte: 0,
        line: 1,
    };
    loop {
        let more = reader.read_record(&mut record).map_err(|err| {
            let line = lines.line_at(err.position().map_or(0, |p| p.byte()));
            StimulusError::new(line, None, format!("malformed CSV: {err}"))
        })?;
        if !more {
            break;
        }
        let line = lines.line_at(record.position().map_or(0, |p| p.byte()));
        let first = record.get(0).unwrap_or("").trim();
        if first.starts_with('#') || record.iter().all(|f| f.trim().is_empty()) {
            continue;
        }
        match &header {
            None => header = Some(parse_header(&record, line)?),
            Some((key, columns)) => {
                let row = parse_row(&record, line, *key, columns.len())?;
                if let Some(prev) = rows.last().filter(|prev| row.at < prev.at) {
                    return Err(StimulusError::new(
                        line,
                        Some(1),
                        format!(
                            "rows must be in non-decreasing {} order: {} comes after {} (line {})",
                            key_name(*key),
                            show_key(*key, row.at),
                            show_key(*key, prev.at),
                            prev.line
                        ),
                    ));
                }
                rows.push(row);
            }
        }
    }
    let Some((key, columns)) = header else {
        return Err(StimulusError::new(
            1,
            None,
            "the stimulus is empty: expected a header such as `cycle,x,y` or `time,x,y`",
        ));
    };
    Ok(Stimulus { key, columns, rows })
}

/// Finds the line where a record starts. The csv reader reports a record
/// at the byte where it started scanning, which is before the blank lines,
/// line terminators and comment lines it skipped; this skips them the same
/// way and counts the line breaks, incrementally.
struct LineCounter<'a> {
    text: &'a [u8],
    /// A byte offset already counted, and the 1-based line it is on.
    byte: usize,
    line: usize,
}

impl LineCounter<'_> {
    fn line_at(&mut self, reported: u64) -> usize {
        let text = self.text;
        let mut at = usize::try_from(reported).map_or(text.len(), |b| b.min(text.len()));
        loop {
            match text.get(at) {
                Some(b'\r' | b'\n') => at += 1,
                Some(b'#') => {
                    at = text[at..]
                        .iter()
                        .position(|&b| b == b'\n')
                        .map_or(text.len(), |i| at + i + 1);
                }
                _ => break,
            }
        }
        if at < self.byte {
            self.byte = 0;
            self.line = 1;
        }
        self.line += text[self.byte..at].iter().filter(|&&b| b == b'\n').count();
        self.byte = at;
        self.line
    }
}

fn parse_header(
    record: &csv::StringRecord,
    line: usize,
) -> Result<(StimulusKey, Vec<String>), StimulusError> {
    let first = record.get(0).unwrap_or("").trim();
    let key = if first.eq_ignore_ascii_case("cycle") {
        StimulusKey::Cycle
    } else if first.eq_ignore_ascii_case("time") {
        StimulusKey::Time
    } else {
        return Err(StimulusError::new(
            line,
            Some(1),
            format!("the first column must be `cycle` or `time`, found `{first}`"),
        ));
    };
    let mut columns = Vec::with_capacity(record.len().saturating_sub(1));
    let mut seen: HashMap<String, usize> = HashMap::new();
    for (i, field) in record.iter().enumerate().skip(1) {
        let name = field.trim();
        if name.is_empty() {
            return Err(StimulusError::new(
                line,
                Some(i + 1),
                format!("column {} has no name", i + 1),
            ));
        }
        if let Some(first_at) = seen.insert(name.to_lowercase(), i + 1) {
            return Err(StimulusError::new(
                line,
                Some(i + 1),
                format!(
                    "duplicate column `{name}` (same as column {first_at}; names are case-insensitive)"
                ),
            ));
        }
        columns.push(name.to_string());
    }
    Ok((key, columns))
}

fn parse_row(
    record: &csv::StringRecord,
    line: usize,
    key: StimulusKey,
    columns: usize,
) -> Result<StimulusRow, StimulusError> {
    if record.len() != columns + 1 {
        return Err(StimulusError::new(
            line,
            None,
            format!(
                "expected {} cells (the {} and {} value{}), found {}{}",
                columns + 1,
                key_name(key),
                columns,
                if columns == 1 { "" } else { "s" },
                record.len(),
                if record.iter().any(|f| f.contains('"')) {
                    "; a quoted cell must start with `\"` right after the comma"
                } else {
                    ""
                }
            ),
        ));
    }
    let key_text = record.get(0).unwrap_or("").trim();
    let at = parse_key(key, key_text).map_err(|msg| StimulusError::new(line, Some(1), msg))?;
    let cells = record
        .iter()
        .skip(1)
        .map(|cell| {
            let cell = cell.trim();
            (!cell.is_empty()).then(|| cell.to_string())
        })
        .collect();
    Ok(StimulusRow { line, at, cells })
}

fn key_name(key: StimulusKey) -> &'static str {
    match key {
        StimulusKey::Cycle => "cycle",
        StimulusKey::Time => "time",
    }
}

fn show_key(key: StimulusKey, at: i64) -> String {
    match key {
        StimulusKey::Cycle => at.to_string(),
        StimulusKey::Time => format_duration(at, "T#"),
    }
}

fn parse_key(key: StimulusKey, text: &str) -> Result<i64, String> {
    if text.is_empty() {
        return Err(format!("missing {}", key_name(key)));
    }
    match key {
        StimulusKey::Cycle => {
            if !text.bytes().all(|b| b.is_ascii_digit()) {
                return Err(format!(
                    "invalid cycle `{text}`: expected a whole number ≥ 0"
                ));
            }
            text.parse::<i64>()
                .map_err(|_| format!("cycle `{text}` is out of range"))
        }
        StimulusKey::Time => {
            let body = strip_prefix_ignore_case(text, "TIME#")
                .or_else(|| strip_prefix_ignore_case(text, "T#"))
                .unwrap_or(text);
            let nanos =
                parse_duration_body(body).map_err(|err| format!("invalid time `{text}`: {err}"))?;
            if nanos < 0 {
                return Err(format!("time `{text}` is negative"));
            }
            Ok(nanos)
        }
    }
}

fn strip_prefix_ignore_case<'a>(text: &'a str, prefix: &str) -> Option<&'a str> {
    let head = text.get(..prefix.len())?;
    head.eq_ignore_ascii_case(prefix)
        .then(|| &text[prefix.len()..])
}

/// Walks the rows of a [`Stimulus`] in order. A row is due at the start of
/// the first cycle whose number (for a `cycle` key) or clock time (for a
/// `time` key) is ≥ the row's key; each row is handed out once.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct StimulusCursor {
    next: usize,
}

impl StimulusCursor {
    /// A cursor before the first row.
    pub fn new() -> Self {
        StimulusCursor { next: 0 }
    }

    /// The rows that became due at this cycle (number `cycle`, clock
    /// `time_ns`), in file order, to apply before the cycle executes. Rows
    /// whose key has been passed in between are included, so nothing is lost
    /// when cycles are skipped. Empty when nothing is due.
    pub fn due<'a>(&mut self, stim: &'a Stimulus, cycle: u64, time_ns: i64) -> &'a [StimulusRow] {
        let now = match stim.key {
            StimulusKey::Cycle => i64::try_from(cycle).unwrap_or(i64::MAX),
            StimulusKey::Time => time_ns,
        };
        let start = self.next.min(stim.rows.len());
        let rest = &stim.rows[start..];
        let count = rest.partition_point(|row| row.at <= now);
        self.next = start + count;
        &rest[..count]
    }

    /// True once every row has been handed out.
    pub fn is_done(&self, stim: &Stimulus) -> bool {
        self.next >= stim.rows.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rstest::rstest;

    const MS: i64 = 1_000_000;

    fn cells(row: &StimulusRow) -> Vec<Option<&str>> {
        row.cells.iter().map(|c| c.as_deref()).collect()
    }

    fn err(text: &str) -> StimulusError {
        parse_stimulus(text).expect_err("should be rejected")
    }

    #[test]
    fn cycle_keyed() {
        let stim = parse_stimulus("cycle,start,Speed\n0,TRUE,10\n5,,20\n").unwrap();
        assert_eq!(stim.key, StimulusKey::Cycle);
        assert_eq!(stim.columns, ["start", "Speed"]);
        assert_eq!(stim.rows.len(), 2);
        assert_eq!((stim.rows[0].line, stim.rows[0].at), (2, 0));
        assert_eq!(cells(&stim.rows[0]), [Some("TRUE"), Some("10")]);
        assert_eq!((stim.rows[1].line, stim.rows[1].at), (3, 5));
        assert_eq!(cells(&stim.rows[1]), [None, Some("20")]);
    }

    #[test]
    fn time_keyed_with_prefixes_and_spaces() {
        let text = " Time , a ,b\n0ms,1,2\n150ms, , 3 \nT#1.5s,4,\ntime#2m,5,6\nt#1h,7,8\n";
        let stim = parse_stimulus(text).unwrap();
        assert_eq!(stim.key, StimulusKey::Time);
        assert_eq!(stim.columns, ["a", "b"]);
        let at: Vec<i64> = stim.rows.iter().map(|r| r.at).collect();
        assert_eq!(at, [0, 150 * MS, 1_500 * MS, 120_000 * MS, 3_600_000 * MS]);
        assert_eq!(cells(&stim.rows[1]), [None, Some("3")]);
        assert_eq!(cells(&stim.rows[2]), [Some("4"), None]);
    }

    #[test]
    fn names_are_kept_as_written() {
        let text =
            "CYCLE,inst.x,arr[2],\"grid[1,2]\",%IX0.1,%I0.0.0.0.1,S1.X\n0,1,2,3,TRUE,FALSE,TRUE\n";
        let stim = parse_stimulus(text).unwrap();
        assert_eq!(
            stim.columns,
            [
                "inst.x",
                "arr[2]",
                "grid[1,2]",
                "%IX0.1",
                "%I0.0.0.0.1",
                "S1.X"
            ]
        );
        assert_eq!(stim.rows[0].cells.len(), 6);
    }

    #[test]
    fn quoted_fields() {
        let text =
            "cycle,msg,n\n0,\"'a,b'\",1\n1,\"say \"\"hi\"\"\",2\n2,\"'two\nlines'\",3\n3,'x',4\n";
        let stim = parse_stimulus(text).unwrap();
        assert_eq!(cells(&stim.rows[0]), [Some("'a,b'"), Some("1")]);
        assert_eq!(cells(&stim.rows[1]), [Some("say \"hi\""), Some("2")]);
        assert_eq!(cells(&stim.rows[2]), [Some("'two\nlines'"), Some("3")]);
        // A row after a quoted line break knows its own line.
        assert_eq!(stim.rows[3].line, 6);
    }

    #[test]
    fn comments_blank_lines_and_line_numbers() {
        let text = "# a stimulus\n\ncycle,x\n# first\n0,1\n\n   \n  # indented comment, with \"quote\n,\n3,2\r\n4,3";
        let stim = parse_stimulus(text).unwrap();
        let lines: Vec<(usize, i64)> = stim.rows.iter().map(|r| (r.line, r.at)).collect();
        assert_eq!(lines, [(5, 0), (10, 3), (11, 4)]);
    }

    #[test]
    fn header_only_and_key_only() {
        let stim = parse_stimulus("cycle,x\n").unwrap();
        assert!(stim.rows.is_empty());
        let stim = parse_stimulus("cycle\n0\n2\n").unwrap();
        assert!(stim.columns.is_empty());
        assert_eq!(stim.rows.len(), 2);
    }

    #[test]
    fn byte_order_mark_is_ignored() {
        let stim = parse_stimulus("\u{FEFF}cycle,x\n0,1\n").unwrap();
        assert_eq!(stim.key, StimulusKey::Cycle);
    }

    #[test]
    fn equal_keys_are_allowed() {
        let stim = parse_stimulus("cycle,x\n1,1\n1,2\n").unwrap();
        assert_eq!(stim.rows.len(), 2);
    }

    #[rstest]
    #[case("", 1, None, "empty")]
    #[case("# only a comment\n", 1, None, "empty")]
    #[case("step,x\n0,1\n", 1, Some(1), "must be `cycle` or `time`, found `step`")]
    #[case("cycle,x,X\n", 1, Some(3), "duplicate column `X`")]
    #[case("cycle,a.b, A.B \n", 1, Some(3), "duplicate column `A.B`")]
    #[case("cycle,x,,y\n", 1, Some(3), "column 3 has no name")]
    #[case(
        "cycle,x,y\n0,1,2\n1,2\n",
        3,
        None,
        "expected 3 cells (the cycle and 2 values), found 2"
    )]
    #[case(
        "cycle,x\n0,1,2\n",
        2,
        None,
        "expected 2 cells (the cycle and 1 value), found 3"
    )]
    #[case(
        "cycle,s,n\n0, \"'a,b'\",1\n",
        2,
        None,
        "found 4; a quoted cell must start with `\"` right after the comma"
    )]
    #[case(
        "cycle,x\n0,1\n\n5,1\n3,1\n",
        5,
        Some(1),
        "non-decreasing cycle order: 3 comes after 5 (line 4)"
    )]
    #[case(
        "time,x\n20ms,1\n10ms,1\n",
        3,
        Some(1),
        "non-decreasing time order: T#10ms comes after T#20ms (line 2)"
    )]
    #[case("cycle,x\n-1,1\n", 2, Some(1), "invalid cycle `-1`")]
    #[case("cycle,x\n1.5,1\n", 2, Some(1), "invalid cycle `1.5`")]
    #[case("cycle,x\n,1\n", 2, Some(1), "missing cycle")]
    #[case("cycle,x\n99999999999999999999,1\n", 2, Some(1), "out of range")]
    #[case("time,x\n10,1\n", 2, Some(1), "invalid time `10`: missing unit")]
    #[case("time,x\nT#5x,1\n", 2, Some(1), "invalid time `T#5x`: unknown unit")]
    #[case("time,x\n-5ms,1\n", 2, Some(1), "time `-5ms` is negative")]
    #[case("time,x\nT#,1\n", 2, Some(1), "invalid time `T#`")]
    fn errors(
        #[case] text: &str,
        #[case] line: usize,
        #[case] column: Option<usize>,
        #[case] message: &str,
    ) {
        let e = err(text);
        assert_eq!((e.line, e.column), (line, column), "{e}");
        assert!(e.message.contains(message), "{e}");
        assert!(e.to_string().starts_with(&format!("line {line}: ")));
    }

    #[test]
    fn odd_input_does_not_panic() {
        for text in [
            "\"",
            "cycle,\"x\n0,1",
            "cycle,x\n\"0\"\"\",1\n",
            "time,x\nTIME#,1",
            "time,x\nT#é,1",
            "time,x\né,1",
            "\u{FEFF}",
            ",,,\n",
            "cycle,x\n0,\u{0}\n",
        ] {
            let _ = parse_stimulus(text);
        }
    }

    #[test]
    fn cursor_by_cycle() {
        let stim = parse_stimulus("cycle,x\n0,a\n5,b\n5,c\n7,d\n").unwrap();
        let mut cursor = StimulusCursor::new();
        let mut seen = Vec::new();
        for cycle in 0..10u64 {
            let due = cursor.due(&stim, cycle, cycle as i64 * 10 * MS);
            seen.push((cycle, due.iter().map(|r| r.at).collect::<Vec<_>>()));
        }
        assert_eq!(seen[0], (0, vec![0]));
        assert_eq!(seen[4], (4, vec![]));
        assert_eq!(seen[5], (5, vec![5, 5]));
        assert_eq!(seen[6], (6, vec![]));
        assert_eq!(seen[7], (7, vec![7]));
        assert!(cursor.is_done(&stim));
        assert!(cursor.due(&stim, 100, 0).is_empty());
    }

    #[test]
    fn cursor_by_time_rounds_up_to_the_next_cycle() {
        let stim = parse_stimulus("time,x\n0ms,a\n15ms,b\n20ms,c\n45ms,d\n47ms,e\n").unwrap();
        let mut cursor = StimulusCursor::new();
        let due_at: Vec<Vec<&str>> = (0..6u64)
            .map(|cycle| {
                cursor
                    .due(&stim, cycle, cycle as i64 * 10 * MS)
                    .iter()
                    .map(|r| r.cells[0].as_deref().unwrap_or(""))
                    .collect()
            })
            .collect();
        assert_eq!(
            due_at,
            [
                vec!["a"],
                vec![],
                vec!["b", "c"],
                vec![],
                vec![],
                vec!["d", "e"]
            ]
        );
    }

    #[test]
    fn cursor_catches_up_after_skipped_cycles() {
        let stim = parse_stimulus("cycle,x\n1,a\n2,b\n3,c\n").unwrap();
        let mut cursor = StimulusCursor::new();
        assert!(cursor.due(&stim, 0, 0).is_empty());
        assert_eq!(cursor.due(&stim, 2, 0).len(), 2);
        assert_eq!(cursor.due(&stim, u64::MAX, 0).len(), 1);
    }

    #[test]
    fn cursor_survives_a_different_stimulus() {
        let long = parse_stimulus("cycle,x\n0,1\n1,1\n2,1\n").unwrap();
        let short = parse_stimulus("cycle,x\n0,1\n").unwrap();
        let mut cursor = StimulusCursor::new();
        assert_eq!(cursor.due(&long, 5, 0).len(), 3);
        assert!(cursor.due(&short, 5, 0).is_empty());
    }
}

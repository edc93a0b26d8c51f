//! The trace: one row per cycle with the cycle number, the clock and the
//! traced values, written as an aligned table, CSV or JSON lines.
//!
//! CSV (`cycle,time,` then the names exactly as given; standard quoting):
//! ```text
//! cycle,time,start,count
//! 0,T#0s,TRUE,42
//! ```
//! JSON lines (keys in this order; values from [`TraceCell::json`]):
//! ```text
//! {"cycle":0,"time":"T#0s","start":true,"count":42}
//! ```
//! Table (columns left-aligned, two spaces apart; written by
//! [`TraceWriter::finish`], since the widths depend on every row; the rows
//! wait in memory, and past 4 MiB in a temporary file):
//! ```text
//! cycle  time  start  count
//! -----  ----  -----  -----
//! 0      T#0s  TRUE   42
//! ```
//!
//! Forced values ([`TraceWriter::row_marked`]): in the table and CSV, the
//! cell's text is followed by `!` (`TRUE!`, `42!`; no literal ends with
//! `!`, a string's ends with its quote); a JSON line gets a last key
//! `"forced"` listing the forced names. Rows without forced values are
//! written exactly as without forcing:
//! ```text
//! {"cycle":0,"time":"T#0s","start":true,"count":42,"forced":["start"]}
//! ```
//!
//! A streaming writer ([`TraceWriter::set_streaming`], used in real time)
//! writes and flushes every row as it comes, and so holds no rows: its
//! table columns are as wide as the header or the first row's value,
//! whichever is wider; a later, wider value shifts the rest of its row
//! right rather than the whole column.
//!
//! VCD waveforms ([`TraceFormat::Vcd`], made with [`TraceWriter::vcd`],
//! which needs each column's type): see [`super::trace_vcd`].
//!
//! With `changes_only`, the first row is written, then only rows where at
//! least one traced cell's text differs from the previous cycle's row (the
//! previous row given to [`TraceWriter::row`], written or not).

use super::table_rows::TableRows;
use super::trace_vcd::{VcdSignal, VcdSink, VcdTimescale};
use crate::elementary::ElemType;
use crate::value::format::{format_string, json_value, write_value};
use crate::value::literal::write_duration;
use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};
use std::fmt::Write as _;
use std::io::{self, Write};
use std::str::FromStr;

/// One JSON-lines row: `cycle`, `time`, then each traced name in order.
#[derive(Serialize)]
struct JsonRow<'a> {
    cycle: u64,
    time: &'a str,
    #[serde(flatten)]
    values: NamedCells<'a>,
    /// The names whose values are forced (left out when none is).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    forced: Vec<&'a str>,
}

/// Appended to the text of a forced cell in the table and CSV.
pub const FORCED_MARK: char = '!';

/// The traced values as a JSON object, in trace order.
struct NamedCells<'a> {
    names: &'a [String],
    cells: &'a [TraceCell],
}

impl Serialize for NamedCells<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.names.len()))?;
        for (name, cell) in self.names.iter().zip(self.cells) {
            map.serialize_entry(name, &cell.json)?;
        }
        map.end()
    }
}

/// How a trace is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TraceFormat {
    /// Human-readable aligned columns.
    Table,
    /// Comma-separated values with a header line.
    Csv,
    /// One JSON object per line.
    Jsonl,
    /// A VCD waveform (see [`TraceWriter::vcd`]).
    Vcd,
}

/// A trace format name that is not `table`, `csv`, `jsonl` or `vcd`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownTraceFormat(pub String);

impl std::fmt::Display for UnknownTraceFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "unknown trace format `{}` (expected table, csv, jsonl or vcd)",
            self.0
        )
    }
}

impl std::error::Error for UnknownTraceFormat {}

impl FromStr for TraceFormat {
    type Err = UnknownTraceFormat;

    /// `table`, `csv`, `jsonl` or `vcd` (case-insensitive).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        if s.eq_ignore_ascii_case("table") {
            Ok(TraceFormat::Table)
        } else if s.eq_ignore_ascii_case("csv") {
            Ok(TraceFormat::Csv)
        } else if s.eq_ignore_ascii_case("jsonl") {
            Ok(TraceFormat::Jsonl)
        } else if s.eq_ignore_ascii_case("vcd") {
            Ok(TraceFormat::Vcd)
        } else {
            Err(UnknownTraceFormat(s.to_string()))
        }
    }
}

impl std::fmt::Display for TraceFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            TraceFormat::Table => "table",
            TraceFormat::Csv => "csv",
            TraceFormat::Jsonl => "jsonl",
            TraceFormat::Vcd => "vcd",
        })
    }
}

/// One traced value: its literal text (table, CSV, change detection) and
/// its JSON form (JSON lines).
#[derive(Debug, Clone, PartialEq)]
pub struct TraceCell {
    /// The IEC literal text, as [`crate::Value::to_literal`] prints it.
    pub text: String,
    /// The value as JSON: BOOL as `true`/`false`, integers as JSON
    /// integers, REAL/LREAL as numbers (`"NaN"`, `"INF"`, `"-INF"` as
    /// strings), every other elementary type (bit strings, times, dates,
    /// characters) as its literal text, a STRING as its plain text.
    pub json: serde_json::Value,
}

impl TraceCell {
    /// The cell for an elementary (non-string) value.
    pub fn from_value(ty: ElemType, raw: u64) -> Self {
        let mut cell = TraceCell {
            text: String::new(),
            json: serde_json::Value::Null,
        };
        cell.set_value(ty, raw);
        cell
    }

    /// Overwrites the cell with another elementary value, reusing the text
    /// buffer (for callers that keep one row of cells across cycles).
    pub fn set_value(&mut self, ty: ElemType, raw: u64) {
        self.text.clear();
        write_value(&mut self.text, ty, raw);
        self.json = json_value(ty, raw);
    }

    /// The cell for a STRING (`wide == false`) or WSTRING value: the quoted
    /// literal as text, the plain string as JSON.
    pub fn from_string(s: &str, wide: bool) -> Self {
        TraceCell {
            text: format_string(s, wide),
            json: serde_json::Value::String(s.to_string()),
        }
    }
}

/// Where the rows go.
enum Sink<W: Write> {
    Csv(Box<csv::Writer<W>>),
    Plain(W),
    Vcd(Box<VcdSink<W>>),
}

/// Rows kept for the table until [`TraceWriter::finish`], and the column
/// widths so far.
struct TableBuffer {
    rows: TableRows,
    /// Width in characters of each column so far (header included).
    widths: Vec<usize>,
}

/// Writes a trace, row by row (see the module docs for the formats).
pub struct TraceWriter<W: Write> {
    sink: Sink<W>,
    format: TraceFormat,
    names: Vec<String>,
    changes_only: bool,
    /// Whether the CSV header has been written.
    header_written: bool,
    /// The previous cycle's cell texts (with `changes_only`).
    prev: Vec<String>,
    has_prev: bool,
    /// Scratch for the cycle number.
    cycle_text: String,
    /// Scratch for the time column.
    time_text: String,
    /// Scratch for one JSON line.
    line: Vec<u8>,
    table: TableBuffer,
    /// Write and flush each row at once (see the module docs).
    streaming: bool,
}

impl<W: Write> TraceWriter<W> {
    /// A writer of `format` to `out`, with one traced column per name (printed
    /// exactly as given). `changes_only` drops rows where no traced value
    /// changed since the previous cycle (the first row is always written).
    ///
    /// A VCD trace needs the type of each column: make it with
    /// [`Self::vcd`] (one made here refuses rows with `InvalidInput`).
    pub fn new(out: W, format: TraceFormat, names: Vec<String>, changes_only: bool) -> Self {
        let sink = match format {
            TraceFormat::Csv => Sink::Csv(Box::new(csv::WriterBuilder::new().from_writer(out))),
            TraceFormat::Table | TraceFormat::Jsonl => Sink::Plain(out),
            TraceFormat::Vcd => Sink::Vcd(Box::new(VcdSink::new(
                out,
                names.clone(),
                Vec::new(),
                VcdTimescale::NANOSECOND,
                changes_only,
            ))),
        };
        let mut table = TableBuffer {
            rows: TableRows::new(names.len() + 2),
            widths: Vec::new(),
        };
        if format == TraceFormat::Table {
            table.widths = ["cycle", "time"]
                .into_iter()
                .chain(names.iter().map(String::as_str))
                .map(|h| h.chars().count())
                .collect();
        }
        TraceWriter {
            sink,
            format,
            names,
            changes_only,
            header_written: false,
            prev: Vec::new(),
            has_prev: false,
            cycle_text: String::new(),
            time_text: String::new(),
            line: Vec::new(),
            table,
            streaming: false,
        }
    }

    /// A VCD writer (see [`super::trace_vcd`]): one variable per name, of
    /// the type `signals` gives in the same order
    /// ([`crate::Session::vcd_signals`] gives them for the traced names),
    /// timestamps in units of `timescale`. A row whose clock is not a whole
    /// number of units, or does not advance, is refused (`InvalidInput`).
    ///
    /// ```
    /// use plcrun::{ElemType, TraceCell, TraceFormat, TraceWriter, VcdSignal, VcdTimescale};
    /// let names = vec!["main.run".to_string()];
    /// let signals = vec![VcdSignal::Elementary(ElemType::Bool)];
    /// let timescale = VcdTimescale::for_cycle(10_000_000, 0); // 10 ms
    /// let mut w = TraceWriter::vcd(Vec::new(), names, signals, timescale, false);
    /// w.row(0, 0, &[TraceCell::from_value(ElemType::Bool, 1)])?;
    /// w.row(1, 10_000_000, &[TraceCell::from_value(ElemType::Bool, 0)])?;
    /// let vcd = String::from_utf8(w.finish()?).unwrap();
    /// assert!(vcd.contains("$timescale 10 ms $end"));
    /// assert!(vcd.ends_with("#0\n$dumpvars\n1!\n$end\n#1\n0!\n"));
    /// # Ok::<(), std::io::Error>(())
    /// ```
    pub fn vcd(
        out: W,
        names: Vec<String>,
        signals: Vec<VcdSignal>,
        timescale: VcdTimescale,
        changes_only: bool,
    ) -> Self {
        let sink = VcdSink::new(out, names.clone(), signals, timescale, changes_only);
        TraceWriter {
            sink: Sink::Vcd(Box::new(sink)),
            format: TraceFormat::Vcd,
            names,
            changes_only,
            header_written: false,
            prev: Vec::new(),
            has_prev: false,
            cycle_text: String::new(),
            time_text: String::new(),
            line: Vec::new(),
            table: TableBuffer {
                rows: TableRows::new(0),
                widths: Vec::new(),
            },
            streaming: false,
        }
    }

    /// Writes and flushes every row as it comes (see the module docs).
    /// Turn it on before the first row.
    pub fn set_streaming(&mut self, on: bool) {
        self.streaming = on;
    }

    /// Flushes what has been written so far (a buffered table is written
    /// by [`Self::finish`] only).
    pub fn flush(&mut self) -> io::Result<()> {
        match &mut self.sink {
            Sink::Csv(csv) => csv.flush(),
            Sink::Plain(out) => out.flush(),
            Sink::Vcd(vcd) => vcd.flush(),
        }
    }

    /// Records the row of cycle `cycle` at clock `time_ns`; `cells` has one
    /// entry per name, in the same order (else an `InvalidInput` error).
    pub fn row(&mut self, cycle: u64, time_ns: i64, cells: &[TraceCell]) -> io::Result<()> {
        self.write_row(cycle, time_ns, cells, &[])
    }

    /// As [`Self::row`], marking the cells whose `forced` entry is true (see
    /// the module documentation); an empty `forced` marks nothing, and so
    /// does VCD, which has no mark.
    pub fn row_marked(
        &mut self,
        cycle: u64,
        time_ns: i64,
        cells: &[TraceCell],
        forced: &[bool],
    ) -> io::Result<()> {
        if self.format != TraceFormat::Vcd && forced.iter().any(|&f| f) {
            let marked: Vec<TraceCell> = cells
                .iter()
                .zip(forced.iter().chain(std::iter::repeat(&false)))
                .map(|(c, &f)| {
                    let mut c = c.clone();
                    if f {
                        c.text.push(FORCED_MARK);
                    }
                    c
                })
                .collect();
            let names: Vec<String> = self
                .names
                .iter()
                .zip(forced)
                .filter(|(_, f)| **f)
                .map(|(n, _)| n.clone())
                .collect();
            return self.write_row(cycle, time_ns, &marked, &names);
        }
        self.write_row(cycle, time_ns, cells, &[])
    }

    #[inline(always)]
    fn write_row(
        &mut self,
        cycle: u64,
        time_ns: i64,
        cells: &[TraceCell],
        forced: &[String],
    ) -> io::Result<()> {
        if self.streaming {
            return self.streamed_row(cycle, time_ns, cells, forced);
        }
        self.record_row(cycle, time_ns, cells, forced)
    }

    /// A row in streaming mode: written, then flushed (out of the virtual
    /// run's path).
    #[cold]
    #[inline(never)]
    fn streamed_row(
        &mut self,
        cycle: u64,
        time_ns: i64,
        cells: &[TraceCell],
        forced: &[String],
    ) -> io::Result<()> {
        self.record_row(cycle, time_ns, cells, forced)?;
        self.flush()
    }

    #[inline(always)]
    fn record_row(
        &mut self,
        cycle: u64,
        time_ns: i64,
        cells: &[TraceCell],
        forced: &[String],
    ) -> io::Result<()> {
        if cells.len() != self.names.len() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "trace row has {} cells for {} traced names",
                    cells.len(),
                    self.names.len()
                ),
            ));
        }
        if let Sink::Vcd(vcd) = &mut self.sink {
            // VCD keeps its own last values (changes_only included).
            return vcd.row(time_ns, cells);
        }
        if self.changes_only && !self.changed(cells) {
            return Ok(());
        }
        self.cycle_text.clear();
        let _ = write!(self.cycle_text, "{cycle}");
        // The scratch string is lent out so that the row can borrow self.
        let mut time = std::mem::take(&mut self.time_text);
        time.clear();
        write_duration(&mut time, time_ns, "T#");
        let written = self.formatted_row(cycle, &time, cells, forced);
        self.time_text = time;
        written
    }

    /// Writes one row whose cycle number is in `cycle_text`.
    #[inline(always)]
    fn formatted_row(
        &mut self,
        cycle: u64,
        time: &str,
        cells: &[TraceCell],
        forced: &[String],
    ) -> io::Result<()> {
        match self.format {
            TraceFormat::Table if self.streaming => self.stream_table_row(time, cells),
            TraceFormat::Table => {
                let table = &mut self.table;
                let texts = [self.cycle_text.as_str(), time]
                    .into_iter()
                    .chain(cells.iter().map(|c| c.text.as_str()));
                for (width, text) in table.widths.iter_mut().zip(texts) {
                    *width = (*width).max(text.chars().count());
                    table.rows.push(text);
                }
                table.rows.end_row()
            }
            TraceFormat::Csv => {
                self.write_csv_header()?;
                let Sink::Csv(csv) = &mut self.sink else {
                    return Ok(());
                };
                let fields = [self.cycle_text.as_bytes(), time.as_bytes()]
                    .into_iter()
                    .chain(cells.iter().map(|c| c.text.as_bytes()));
                csv.write_record(fields)?;
                Ok(())
            }
            TraceFormat::Vcd => Ok(()),
            TraceFormat::Jsonl => {
                let line = &mut self.line;
                line.clear();
                let row = JsonRow {
                    cycle,
                    time,
                    values: NamedCells {
                        names: &self.names,
                        cells,
                    },
                    forced: forced.iter().map(String::as_str).collect(),
                };
                serde_json::to_writer(&mut *line, &row)?;
                line.push(b'\n');
                match &mut self.sink {
                    Sink::Plain(out) => out.write_all(line),
                    Sink::Csv(_) | Sink::Vcd(_) => Ok(()),
                }
            }
        }
    }

    /// Writes one table row now (the header and rule first, with the
    /// widths the first row fixes). Out of line: real-time runs only, kept
    /// out of the virtual run's row path.
    #[cold]
    #[inline(never)]
    fn stream_table_row(&mut self, time: &str, cells: &[TraceCell]) -> io::Result<()> {
        let texts = || {
            [self.cycle_text.as_str(), time]
                .into_iter()
                .chain(cells.iter().map(|c| c.text.as_str()))
        };
        if !self.header_written {
            for (width, text) in self.table.widths.iter_mut().zip(texts()) {
                *width = (*width).max(text.chars().count());
            }
            let header: Vec<&str> = ["cycle", "time"]
                .into_iter()
                .chain(self.names.iter().map(String::as_str))
                .collect();
            let rules: Vec<String> = self.table.widths.iter().map(|w| "-".repeat(*w)).collect();
            let line = table_line(&self.table.widths, header.into_iter());
            let rule = table_line(&self.table.widths, rules.iter().map(String::as_str));
            if let Sink::Plain(out) = &mut self.sink {
                out.write_all(line.as_bytes())?;
                out.write_all(rule.as_bytes())?;
            }
            self.header_written = true;
        }
        let line = table_line(&self.table.widths, texts());
        match &mut self.sink {
            Sink::Plain(out) => out.write_all(line.as_bytes()),
            Sink::Csv(_) | Sink::Vcd(_) => Ok(()),
        }
    }

    /// Writes what is still pending (the CSV header of an empty trace, the
    /// whole table), flushes, and hands the output back.
    pub fn finish(mut self) -> io::Result<W> {
        match self.format {
            TraceFormat::Csv => self.write_csv_header()?,
            TraceFormat::Table if self.header_written => {}
            TraceFormat::Table => self.write_table()?,
            TraceFormat::Jsonl | TraceFormat::Vcd => {}
        }
        match self.sink {
            Sink::Csv(csv) => csv.into_inner().map_err(|err| err.into_error()),
            Sink::Vcd(vcd) => vcd.finish(),
            Sink::Plain(mut out) => {
                out.flush()?;
                Ok(out)
            }
        }
    }

    /// True when the row must be written under `changes_only`; remembers
    /// the row as the previous cycle's either way.
    fn changed(&mut self, cells: &[TraceCell]) -> bool {
        if !self.has_prev {
            self.has_prev = true;
            self.prev = cells.iter().map(|c| c.text.clone()).collect();
            return true;
        }
        let mut changed = false;
        for (prev, cell) in self.prev.iter_mut().zip(cells) {
            if *prev != cell.text {
                changed = true;
                prev.clear();
                prev.push_str(&cell.text);
            }
        }
        changed
    }

    fn write_csv_header(&mut self) -> io::Result<()> {
        if self.header_written {
            return Ok(());
        }
        self.header_written = true;
        if let Sink::Csv(csv) = &mut self.sink {
            let fields = ["cycle", "time"]
                .into_iter()
                .chain(self.names.iter().map(String::as_str));
            csv.write_record(fields)?;
        }
        Ok(())
    }

    fn write_table(&mut self) -> io::Result<()> {
        let Sink::Plain(out) = &mut self.sink else {
            return Ok(());
        };
        let TableBuffer { rows, widths } = &mut self.table;
        let widths = &*widths;
        let mut line = String::new();
        let mut emit = |line: &mut String, cells: &mut dyn Iterator<Item = &str>| {
            line.clear();
            for (i, (text, width)) in cells.zip(widths).enumerate() {
                if i > 0 {
                    line.push_str("  ");
                }
                line.push_str(text);
                if i + 1 < widths.len() {
                    let pad = width.saturating_sub(text.chars().count());
                    line.extend(std::iter::repeat_n(' ', pad));
                }
            }
            let kept = line.trim_end_matches(' ').len();
            line.truncate(kept);
            line.push('\n');
            out.write_all(line.as_bytes())
        };
        let header = ["cycle", "time"]
            .into_iter()
            .chain(self.names.iter().map(String::as_str));
        emit(&mut line, &mut header.into_iter())?;
        let rules: Vec<String> = widths.iter().map(|w| "-".repeat(*w)).collect();
        emit(&mut line, &mut rules.iter().map(String::as_str))?;
        rows.for_each_row(|cells| emit(&mut line, cells))
    }
}

/// One table line: `texts` left-aligned in columns of `widths`, two spaces
/// apart, without trailing blanks.
fn table_line<'a>(widths: &[usize], texts: impl Iterator<Item = &'a str>) -> String {
    let mut line = String::new();
    for (i, text) in texts.enumerate() {
        if i > 0 {
            line.push_str("  ");
        }
        line.push_str(text);
        let width = widths.get(i).copied().unwrap_or(0);
        line.extend(std::iter::repeat_n(
            ' ',
            width.saturating_sub(text.chars().count()),
        ));
    }
    let kept = line.trim_end_matches(' ').len();
    line.truncate(kept);
    line.push('\n');
    line
}

#[cfg(test)]
mod tests {
    use super::*;
    use ElemType::{Bool, Int, Lreal, Real};
    use rstest::rstest;

    const MS: i64 = 1_000_000;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    /// Writes `rows` of (start: BOOL, count: INT) and returns the output.
    fn run(format: TraceFormat, changes_only: bool, rows: &[(bool, i16)]) -> String {
        let mut w = TraceWriter::new(Vec::new(), format, names(&["start", "Count"]), changes_only);
        for (cycle, &(start, count)) in rows.iter().enumerate() {
            let cells = [
                TraceCell::from_value(Bool, start as u64),
                TraceCell::from_value(Int, count as u64),
            ];
            w.row(cycle as u64, cycle as i64 * 10 * MS, &cells).unwrap();
        }
        String::from_utf8(w.finish().unwrap()).unwrap()
    }

    const ROWS: [(bool, i16); 4] = [(false, 0), (true, 0), (true, 0), (true, -1200)];

    #[test]
    fn csv_output() {
        assert_eq!(
            run(TraceFormat::Csv, false, &ROWS),
            "cycle,time,start,Count\n\
             0,T#0s,FALSE,0\n\
             1,T#10ms,TRUE,0\n\
             2,T#20ms,TRUE,0\n\
             3,T#30ms,TRUE,-1200\n"
        );
    }

    #[test]
    fn jsonl_output() {
        assert_eq!(
            run(TraceFormat::Jsonl, false, &ROWS[..2]),
            "{\"cycle\":0,\"time\":\"T#0s\",\"start\":false,\"Count\":0}\n\
             {\"cycle\":1,\"time\":\"T#10ms\",\"start\":true,\"Count\":0}\n"
        );
    }

    #[test]
    fn table_output() {
        assert_eq!(
            run(TraceFormat::Table, false, &ROWS),
            "cycle  time    start  Count\n\
             -----  ------  -----  -----\n\
             0      T#0s    FALSE  0\n\
             1      T#10ms  TRUE   0\n\
             2      T#20ms  TRUE   0\n\
             3      T#30ms  TRUE   -1200\n"
        );
    }

    #[rstest]
    #[case(
        TraceFormat::Csv,
        "cycle,time,start,Count\n0,T#0s,FALSE,0\n1,T#10ms,TRUE,0\n3,T#30ms,TRUE,-1200\n"
    )]
    #[case(
        TraceFormat::Table,
        "cycle  time    start  Count\n-----  ------  -----  -----\n0      T#0s    FALSE  0\n1      T#10ms  TRUE   0\n3      T#30ms  TRUE   -1200\n"
    )]
    fn changes_only(#[case] format: TraceFormat, #[case] expected: &str) {
        assert_eq!(run(format, true, &ROWS), expected);
    }

    #[test]
    fn changes_only_compares_with_the_previous_cycle_not_the_last_written_row() {
        // Cycle 0 is written (first), 1 changed, 2 did not, 3 changed back
        // (against cycle 2), 4 did not.
        let rows = [(false, 0), (false, 1), (false, 1), (false, 0), (false, 0)];
        assert_eq!(
            run(TraceFormat::Csv, true, &rows),
            "cycle,time,start,Count\n0,T#0s,FALSE,0\n1,T#10ms,FALSE,1\n3,T#30ms,FALSE,0\n"
        );
    }

    #[test]
    fn a_streaming_table_writes_each_row_at_once() {
        let mut w = TraceWriter::new(
            Vec::new(),
            TraceFormat::Table,
            names(&["start", "Count"]),
            false,
        );
        w.set_streaming(true);
        for (cycle, &(start, count)) in ROWS.iter().enumerate() {
            let cells = [
                TraceCell::from_value(Bool, start as u64),
                TraceCell::from_value(Int, count as u64),
            ];
            w.row(cycle as u64, cycle as i64 * 10 * MS, &cells).unwrap();
        }
        // Widths from the header and the first row; the wider -1200 and
        // T#10ms push their rows right.
        assert_eq!(
            String::from_utf8(w.finish().unwrap()).unwrap(),
            "cycle  time  start  Count\n\
             -----  ----  -----  -----\n\
             0      T#0s  FALSE  0\n\
             1      T#10ms  TRUE   0\n\
             2      T#20ms  TRUE   0\n\
             3      T#30ms  TRUE   -1200\n"
        );
    }

    #[test]
    fn streaming_csv_is_the_same_csv() {
        let mut w = TraceWriter::new(Vec::new(), TraceFormat::Csv, names(&["Count"]), false);
        w.set_streaming(true);
        w.row(0, 0, &[TraceCell::from_value(Int, 3)]).unwrap();
        assert_eq!(
            String::from_utf8(w.finish().unwrap()).unwrap(),
            "cycle,time,Count\n0,T#0s,3\n"
        );
    }

    #[test]
    fn a_table_longer_than_memory_holds_is_the_same_table() {
        let rows: Vec<(bool, i16)> = (0..2000).map(|k| (k % 3 == 0, (k * 7) as i16)).collect();
        let in_memory = run(TraceFormat::Table, false, &rows);
        let mut w = TraceWriter::new(
            Vec::new(),
            TraceFormat::Table,
            names(&["start", "Count"]),
            false,
        );
        w.table.rows = TableRows::with_limit(4, 100);
        for (cycle, &(start, count)) in rows.iter().enumerate() {
            let cells = [
                TraceCell::from_value(Bool, start as u64),
                TraceCell::from_value(Int, count as u64),
            ];
            w.row(cycle as u64, cycle as i64 * 10 * MS, &cells).unwrap();
        }
        assert_eq!(String::from_utf8(w.finish().unwrap()).unwrap(), in_memory);
    }

    #[test]
    fn empty_traces() {
        assert_eq!(
            run(TraceFormat::Csv, false, &[]),
            "cycle,time,start,Count\n"
        );
        assert_eq!(run(TraceFormat::Jsonl, false, &[]), "");
        assert_eq!(
            run(TraceFormat::Table, false, &[]),
            "cycle  time  start  Count\n-----  ----  -----  -----\n"
        );
    }

    #[test]
    fn no_traced_names() {
        let mut w = TraceWriter::new(Vec::new(), TraceFormat::Csv, Vec::new(), true);
        w.row(0, 0, &[]).unwrap();
        w.row(1, 10 * MS, &[]).unwrap();
        assert_eq!(
            String::from_utf8(w.finish().unwrap()).unwrap(),
            "cycle,time\n0,T#0s\n"
        );
    }

    fn strings_trace(format: TraceFormat) -> String {
        let mut w = TraceWriter::new(
            Vec::new(),
            format,
            names(&["msg", "grid[1,2]", "say \"x\""]),
            false,
        );
        let cells = [
            TraceCell::from_string("a,b", false),
            TraceCell::from_value(Real, u64::from(0.1f32.to_bits())),
            TraceCell::from_string("hé \"ho\"", true),
        ];
        w.row(7, 1_500 * MS, &cells).unwrap();
        String::from_utf8(w.finish().unwrap()).unwrap()
    }

    #[test]
    fn csv_quotes_when_needed() {
        assert_eq!(
            strings_trace(TraceFormat::Csv),
            "cycle,time,msg,\"grid[1,2]\",\"say \"\"x\"\"\"\n\
             7,T#1s500ms,\"'a,b'\",0.1,\"\"\"hé $\"\"ho$\"\"\"\"\"\n"
        );
    }

    #[test]
    fn jsonl_escapes_keys_and_strings() {
        assert_eq!(
            strings_trace(TraceFormat::Jsonl),
            "{\"cycle\":7,\"time\":\"T#1s500ms\",\"msg\":\"a,b\",\"grid[1,2]\":0.1,\"say \\\"x\\\"\":\"hé \\\"ho\\\"\"}\n"
        );
    }

    #[test]
    fn table_counts_characters_not_bytes() {
        assert_eq!(
            strings_trace(TraceFormat::Table),
            "cycle  time       msg    grid[1,2]  say \"x\"\n\
             -----  ---------  -----  ---------  -----------\n\
             7      T#1s500ms  'a,b'  0.1        \"hé $\"ho$\"\"\n"
        );
    }

    #[test]
    fn wrong_cell_count_is_an_error_not_a_panic() {
        let mut w = TraceWriter::new(Vec::new(), TraceFormat::Table, names(&["a"]), false);
        let err = w.row(0, 0, &[]).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
    }

    #[test]
    fn forced_cells_are_marked_and_unforced_rows_are_unchanged() {
        let cells = [
            TraceCell::from_string("a!", false),
            TraceCell::from_value(Int, 7),
        ];
        let write = |format, forced: &[bool]| {
            let mut w = TraceWriter::new(Vec::new(), format, names(&["s", "n"]), false);
            w.row_marked(0, 0, &cells, forced).unwrap();
            String::from_utf8(w.finish().unwrap()).unwrap()
        };
        assert_eq!(
            write(TraceFormat::Csv, &[false, true]),
            "cycle,time,s,n\n0,T#0s,'a!',7!\n"
        );
        assert_eq!(
            write(TraceFormat::Csv, &[false, false]),
            write(TraceFormat::Csv, &[])
        );
        assert_eq!(
            write(TraceFormat::Jsonl, &[true, true]),
            "{\"cycle\":0,\"time\":\"T#0s\",\"s\":\"a!\",\"n\":7,\"forced\":[\"s\",\"n\"]}\n"
        );
        assert_eq!(
            write(TraceFormat::Jsonl, &[false, false]),
            "{\"cycle\":0,\"time\":\"T#0s\",\"s\":\"a!\",\"n\":7}\n"
        );
    }

    #[test]
    fn cells_can_be_reused() {
        let mut cell = TraceCell::from_value(Int, 5);
        cell.set_value(Lreal, 2.5f64.to_bits());
        assert_eq!(cell.text, "2.5");
        assert_eq!(cell.json, serde_json::json!(2.5));
    }

    #[rstest]
    #[case("table", TraceFormat::Table)]
    #[case("csv", TraceFormat::Csv)]
    #[case("JSONL", TraceFormat::Jsonl)]
    fn formats_by_name(#[case] name: &str, #[case] format: TraceFormat) {
        assert_eq!(name.parse::<TraceFormat>(), Ok(format));
        assert_eq!(format.to_string(), name.to_ascii_lowercase());
    }

    #[test]
    fn unknown_format() {
        let err = "xml".parse::<TraceFormat>().unwrap_err();
        assert_eq!(err, UnknownTraceFormat("xml".into()));
        assert!(err.to_string().contains("`xml`"), "{err}");
    }
}

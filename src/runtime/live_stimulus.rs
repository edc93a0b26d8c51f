//! A stimulus read while the program runs: rows in the stimulus CSV format
//! arriving on a stream (standard input for `--stimulus -`), one row per
//! line.
//!
//! The header is read before the first cycle (its columns are resolved
//! then, so an unknown name is reported before anything runs). A thread
//! then reads the following lines as they come; before each cycle the rows
//! that have arrived are decoded against their variables' types and
//! applied once due — at the first cycle whose number (`cycle` key) or
//! clock (`time` key) reaches the row's key, so a row keyed `0` applies as
//! soon as it arrives. A cell that does not fit its variable ends the run
//! with an error naming the line and the column. Unlike a stimulus file, a
//! quoted cell may not span lines.
//!
//! ```
//! use plcrun::{LiveStimulus, Options, Plc, Session};
//! use std::io::Cursor;
//!
//! let src = "PROGRAM P VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR
//!            y := 2 * x; END_PROGRAM";
//! let plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
//! let mut session = Session::new(plc);
//! let input = Cursor::new("cycle,x\n0,21\n");
//! let live = LiveStimulus::start(session.plc(), input)?;
//! session.set_live_stimulus(live);
//! // The reader thread delivers the row; wait for it as a host would.
//! while session.plc().read("y")?.to_literal() != "42" {
//!     session.apply_live_stimulus()?;
//!     session.step()?;
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::engine::Plc;
use super::names::VarRef;
use super::plc_value::Value;
use super::session::StimulusBindError;
use super::session::stimulus_columns;
use super::stimulus::{StimulusError, StimulusKey, parse_stimulus};
use std::collections::VecDeque;
use std::fmt;
use std::io::{self, BufRead};
use std::sync::mpsc::{self, Receiver, TryRecvError};

/// Why a live stimulus could not be started or a row of it applied.
#[derive(Debug)]
pub enum LiveStimulusError {
    /// The stream could not be read.
    Read(io::Error),
    /// A line is not a valid stimulus header or row (the line numbers
    /// count every line of the stream, from 1).
    Format(StimulusError),
    /// A column or cell does not fit the program.
    Bind(StimulusBindError),
}

impl fmt::Display for LiveStimulusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LiveStimulusError::Read(e) => write!(f, "cannot read the stimulus: {e}"),
            LiveStimulusError::Format(e) => write!(f, "stimulus {e}"),
            LiveStimulusError::Bind(e) => write!(f, "stimulus {e}"),
        }
    }
}

impl std::error::Error for LiveStimulusError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            LiveStimulusError::Read(e) => Some(e),
            LiveStimulusError::Format(e) => Some(e),
            LiveStimulusError::Bind(e) => Some(e),
        }
    }
}

/// A line from the reader thread: its 1-based number and text.
type Line = io::Result<(usize, String)>;

/// A decoded row waiting to be due.
struct PendingRow {
    at: i64,
    cells: Vec<(usize, Value)>,
}

/// A stimulus fed while the program runs (see the module docs).
pub struct LiveStimulus {
    header: String,
    key: StimulusKey,
    names: Vec<String>,
    columns: Vec<VarRef>,
    lines: Receiver<Line>,
    /// True once the stream has ended (or failed, reported once).
    ended: bool,
    pending: VecDeque<PendingRow>,
    /// The key of the last row received, with its line.
    last: Option<(i64, usize)>,
}

impl fmt::Debug for LiveStimulus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("LiveStimulus")
            .field("columns", &self.names)
            .field("pending", &self.pending.len())
            .finish()
    }
}

/// True for a line the stimulus format skips (blank, comment, only commas).
fn is_skipped(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with('#') || t.chars().all(|c| c == ',' || c.is_whitespace())
}

impl LiveStimulus {
    /// Reads the header from `input` now, resolves its columns in `plc`,
    /// and starts a thread that reads the rows as they arrive. The thread
    /// ends at the end of the stream, or after the next line once the
    /// live stimulus is dropped.
    pub fn start(
        plc: &Plc,
        mut input: impl BufRead + Send + 'static,
    ) -> Result<LiveStimulus, LiveStimulusError> {
        let mut number = 0;
        let mut header = String::new();
        loop {
            header.clear();
            number += 1;
            if input
                .read_line(&mut header)
                .map_err(LiveStimulusError::Read)?
                == 0
            {
                return Err(LiveStimulusError::Format(StimulusError {
                    line: number,
                    column: None,
                    message:
                        "the stimulus is empty: expected a header such as `cycle,x,y` or `time,x,y`"
                            .into(),
                }));
            }
            if !is_skipped(&header) {
                break;
            }
        }
        let header = header.trim_end_matches(['\r', '\n']).to_string();
        let parsed = parse_stimulus(&header).map_err(|mut e| {
            e.line = number;
            LiveStimulusError::Format(e)
        })?;
        let columns = stimulus_columns(plc, &parsed.columns).map_err(LiveStimulusError::Bind)?;
        let (send, lines) = mpsc::channel();
        std::thread::spawn(move || read_lines(input, number, send));
        Ok(LiveStimulus {
            header,
            key: parsed.key,
            names: parsed.columns,
            columns,
            lines,
            ended: false,
            pending: VecDeque::new(),
            last: None,
        })
    }

    /// Resolves the columns again in `plc` (a new version of the program,
    /// after an online change) and re-decodes the rows waiting to be due
    /// for the new types; nothing changes on error.
    pub(crate) fn rebind(&mut self, plc: &Plc) -> Result<(), StimulusBindError> {
        let columns = stimulus_columns(plc, &self.names)?;
        let mut pending = VecDeque::with_capacity(self.pending.len());
        for row in &self.pending {
            let mut cells = Vec::with_capacity(row.cells.len());
            for (col, value) in &row.cells {
                let value = plc
                    .parse_value(&columns[*col], &value.to_literal())
                    .map_err(|error| StimulusBindError {
                        column: self.names[*col].clone(),
                        line: None,
                        error,
                    })?;
                cells.push((*col, value));
            }
            pending.push_back(PendingRow { at: row.at, cells });
        }
        self.columns = columns;
        self.pending = pending;
        Ok(())
    }

    /// True when the columns were resolved by another PLC than `plc`.
    pub(crate) fn is_bound_to_another(&self, plc: &Plc) -> bool {
        self.columns.first().is_some_and(|c| c.owner != plc.id)
    }

    /// Decodes the rows that have arrived and applies those due at the
    /// next cycle of `plc`.
    pub(crate) fn apply_due(&mut self, plc: &mut Plc) -> Result<(), LiveStimulusError> {
        if self.is_bound_to_another(plc) {
            // A new program version (online change): same names, new places.
            self.rebind(plc).map_err(LiveStimulusError::Bind)?;
        }
        while !self.ended {
            match self.lines.try_recv() {
                Ok(Ok((number, text))) => self.receive(plc, number, &text)?,
                Ok(Err(e)) => {
                    self.ended = true;
                    return Err(LiveStimulusError::Read(e));
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => self.ended = true,
            }
        }
        let now = match self.key {
            StimulusKey::Cycle => i64::try_from(plc.cycle()).unwrap_or(i64::MAX),
            StimulusKey::Time => plc.time(),
        };
        while let Some(row) = self.pending.front() {
            if row.at > now {
                break;
            }
            for (col, value) in &row.cells {
                // Decoded for these handles by this PLC in `receive`.
                plc.store(&self.columns[*col], value);
            }
            self.pending.pop_front();
        }
        Ok(())
    }

    /// Parses and decodes line `number`, queueing the row.
    fn receive(&mut self, plc: &Plc, number: usize, text: &str) -> Result<(), LiveStimulusError> {
        if is_skipped(text) {
            return Ok(());
        }
        let parsed = parse_stimulus(&format!("{}\n{text}", self.header)).map_err(|mut e| {
            e.line = number;
            LiveStimulusError::Format(e)
        })?;
        for row in parsed.rows {
            if let Some((prev, prev_line)) = self.last.filter(|(prev, _)| row.at < *prev) {
                return Err(LiveStimulusError::Format(StimulusError {
                    line: number,
                    column: Some(1),
                    message: format!(
                        "rows must be in non-decreasing order: {} comes after {prev} (line {prev_line})",
                        row.at
                    ),
                }));
            }
            self.last = Some((row.at, number));
            let mut cells = Vec::new();
            for (i, cell) in row.cells.iter().enumerate() {
                let Some(text) = cell else { continue };
                let value = plc.parse_value(&self.columns[i], text).map_err(|error| {
                    LiveStimulusError::Bind(StimulusBindError {
                        column: self.names[i].clone(),
                        line: Some(number),
                        error,
                    })
                })?;
                cells.push((i, value));
            }
            self.pending.push_back(PendingRow { at: row.at, cells });
        }
        Ok(())
    }
}

/// The reader thread: sends each line after `header_line` until the end of
/// the stream, a read error, or the receiver is gone.
fn read_lines(mut input: impl BufRead, header_line: usize, send: mpsc::Sender<Line>) {
    let mut number = header_line;
    loop {
        let mut line = String::new();
        number += 1;
        match input.read_line(&mut line) {
            Ok(0) => return,
            Ok(_) => {
                let text = line.trim_end_matches(['\r', '\n']).to_string();
                if send.send(Ok((number, text))).is_err() {
                    return;
                }
            }
            Err(e) => {
                let _ = send.send(Err(e));
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runtime::engine::Options;
    use std::io::Cursor;

    fn plc() -> Plc {
        let src = "PROGRAM P VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR
                   y := 2 * x; END_PROGRAM";
        Plc::compile_files(&[("p.st", src)], &Options::default()).unwrap()
    }

    /// Applies rows until the reader thread has delivered everything.
    fn drain(live: &mut LiveStimulus, plc: &mut Plc) -> Result<(), LiveStimulusError> {
        for _ in 0..1000 {
            live.apply_due(plc)?;
            if live.ended {
                return Ok(());
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        panic!("the reader thread never ended");
    }

    #[test]
    fn rows_apply_when_due_in_order() {
        let mut plc = plc();
        let input = Cursor::new("# comment\ncycle,x\n0,1\n\n3,5\n");
        let mut live = LiveStimulus::start(&plc, input).unwrap();
        drain(&mut live, &mut plc).unwrap();
        assert_eq!(plc.read("x").unwrap().to_literal(), "1");
        for _ in 0..3 {
            plc.run_cycle().unwrap();
            live.apply_due(&mut plc).unwrap();
        }
        assert_eq!(plc.read("x").unwrap().to_literal(), "5");
    }

    #[test]
    fn bad_cells_name_their_line_and_column() {
        let mut plc = plc();
        let input = Cursor::new("cycle,x\n0,1\n1,TRUE\n");
        let mut live = LiveStimulus::start(&plc, input).unwrap();
        let err = drain(&mut live, &mut plc).unwrap_err();
        let text = err.to_string();
        assert!(text.contains("line 3") && text.contains("`x`"), "{text}");
    }

    #[test]
    fn headers_are_checked_before_the_run() {
        let plc = plc();
        let err = LiveStimulus::start(&plc, Cursor::new("cycle,nope\n")).unwrap_err();
        assert!(matches!(err, LiveStimulusError::Bind(_)), "{err}");
        let err = LiveStimulus::start(&plc, Cursor::new("\n# only a comment\n")).unwrap_err();
        assert!(err.to_string().contains("empty"), "{err}");
        let err = LiveStimulus::start(&plc, Cursor::new("when,x\n")).unwrap_err();
        assert!(matches!(err, LiveStimulusError::Format(_)), "{err}");
    }

    #[test]
    fn rows_out_of_order_are_refused() {
        let mut plc = plc();
        let input = Cursor::new("cycle,x\n5,1\n2,1\n");
        let mut live = LiveStimulus::start(&plc, input).unwrap();
        let err = drain(&mut live, &mut plc).unwrap_err();
        assert!(err.to_string().contains("line 3"), "{err}");
    }
}

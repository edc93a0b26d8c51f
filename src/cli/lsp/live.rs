//! Live values as inlay hints: the server asks a running plcrun's web
//! monitor (`plcrun lsp --live ADDR`, docs/editors.md) for its variables,
//! at most a few times a second, and shows each value after the names of
//! the open document that stand for it ([`plcrun::Analysis::live_names`]).
//! When the PLC moved on, the server asks the client to fetch the hints
//! again (`workspace/inlayHint/refresh`), so they follow the scan without
//! stopping it.

use super::position::Columns;
use crate::cli::monitor_client::{host_port, monitor_get};
use lsp_types as lsp;
use plcrun::{Analysis, FileId};
use std::collections::HashMap;
use std::time::{Duration, Instant};

/// How old the values may be before they are asked again.
const FRESH: Duration = Duration::from_millis(250);
/// How long one question to the monitor may take.
const TIMEOUT: Duration = Duration::from_millis(400);

/// The monitor asked, and what it said last.
pub struct Live {
    host_port: String,
    /// Lower-case variable path -> value as a literal.
    values: HashMap<String, String>,
    /// The monitor's snapshot number and when it was read.
    seq: Option<u64>,
    read_at: Option<Instant>,
    /// The snapshot the client's hints show (asked to refresh after it).
    shown: Option<u64>,
    /// Why the last question failed, said once in the client's log.
    failure: Option<String>,
}

impl Live {
    /// Values from the web monitor at `address` (`HOST:PORT`, a port, or
    /// an `http://` URL).
    pub fn new(address: &str) -> Live {
        Live {
            host_port: host_port(address),
            values: HashMap::new(),
            seq: None,
            read_at: None,
            shown: None,
            failure: None,
        }
    }

    /// Reads the values again when they are older than [`FRESH`]; true
    /// when the monitor's snapshot changed since the client's hints.
    pub fn poll(&mut self) -> bool {
        if self.read_at.is_some_and(|t| t.elapsed() < FRESH) {
            return self.changed();
        }
        self.read_at = Some(Instant::now());
        match monitor_get(&self.host_port, "/api/variables", TIMEOUT) {
            Ok(answer) => {
                self.failure = None;
                self.seq = answer["seq"].as_u64();
                self.values = answer["variables"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter_map(|v| {
                        let path = v["path"].as_str()?.to_lowercase();
                        Some((path, v["value"].as_str()?.to_string()))
                    })
                    .collect();
            }
            Err(why) => {
                if self.failure.as_deref() != Some(&why) {
                    sayln!("plcrun lsp: live values from {}: {why}", self.host_port);
                }
                self.failure = Some(why);
                self.values.clear();
                self.seq = None;
            }
        }
        self.changed()
    }

    fn changed(&self) -> bool {
        self.seq != self.shown
    }

    /// The hints for `file` between byte offsets `from` and `to`: ` = value`
    /// after every name the monitor has a value for.
    pub fn hints(
        &mut self,
        analysis: &Analysis,
        file: FileId,
        (from, to): (u32, u32),
        columns: Columns,
    ) -> Vec<lsp::InlayHint> {
        self.poll();
        self.shown = self.seq;
        let source = analysis.sources().file(file);
        analysis
            .live_names(file)
            .into_iter()
            .filter(|n| n.span.end >= from && n.span.start <= to)
            .filter_map(|n| {
                let value = n
                    .paths
                    .iter()
                    .find_map(|p| self.values.get(&p.to_lowercase()))?;
                let at = columns.range(source, n.span.end, n.span.end).start;
                Some(lsp::InlayHint {
                    position: at,
                    label: lsp::InlayHintLabel::String(format!("= {value}")),
                    kind: None,
                    text_edits: None,
                    tooltip: Some(lsp::InlayHintTooltip::String(format!(
                        "{} in the running PLC (cycle values from {})",
                        n.paths[0], self.host_port
                    ))),
                    padding_left: Some(true),
                    padding_right: Some(false),
                    data: None,
                })
            })
            .collect()
    }
}

//! Helpers of the SFC tests: run a source text through the library and get
//! its CSV trace or its diagnostics, and read the trace's columns.

#![allow(dead_code)]

pub use super::library;

use library::{TraceRequest, check_rendered, csv_trace};

/// Runs a source text (file name `prog.st`) for `cycles` cycles with an
/// optional stimulus text, tracing `trace`; returns the CSV trace, as
/// `plcrun prog.st --cycles N --trace T --format csv [--stimulus S]` prints
/// it (panics with the diagnostics if the run fails).
pub fn trace_src(src: &str, stimulus: Option<&str>, cycles: u64, trace: &str) -> String {
    let request = TraceRequest {
        cycles,
        stimulus,
        trace: Some(trace),
        changes_only: false,
    };
    csv_trace(&[("prog.st", src)], &request)
}

/// Checks a source text (file name `prog.st`) as `plcrun check` does;
/// returns whether it has no error and the diagnostics as printed.
pub fn diagnostics(src: &str) -> (bool, String) {
    check_rendered(&[("prog.st", src)])
}

/// The rows of a CSV trace without the header, each split into cells.
pub fn rows(csv: &str) -> Vec<Vec<String>> {
    csv.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// One column of a CSV trace (by header name), one entry per row.
pub fn column(csv: &str, name: &str) -> Vec<String> {
    let header: Vec<&str> = csv.lines().next().unwrap_or("").split(',').collect();
    let k = header
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows(csv).into_iter().map(|r| r[k].clone()).collect()
}

/// A BOOL column as a string of `1`/`0`, one character per cycle.
pub fn bits(csv: &str, name: &str) -> String {
    column(csv, name)
        .iter()
        .map(|v| match v.as_str() {
            "TRUE" => '1',
            "FALSE" => '0',
            other => panic!("{name}: not a BOOL: {other}"),
        })
        .collect()
}

/// A cycle-keyed stimulus CSV with one row per cycle, from per-input bit
/// strings (`"0011"`: FALSE in cycles 0-1, TRUE in 2-3; missing cycles FALSE).
pub fn stimulus(inputs: &[(&str, &str)]) -> String {
    let n = inputs.iter().map(|(_, b)| b.len()).max().unwrap_or(0);
    let mut s = String::from("cycle");
    for (name, _) in inputs {
        s.push(',');
        s.push_str(name);
    }
    s.push('\n');
    for k in 0..n {
        s.push_str(&k.to_string());
        for (_, b) in inputs {
            let v = b.as_bytes().get(k).copied().unwrap_or(b'0');
            s.push_str(if v == b'1' { ",TRUE" } else { ",FALSE" });
        }
        s.push('\n');
    }
    s
}

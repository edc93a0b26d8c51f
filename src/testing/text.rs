//! The human-readable test report.

use super::{AssertionFailure, TestCase, TestOutcome, TestReport};
use std::fmt::Write;

/// One failed assertion on one line:
/// `file:line:col: cycle N: [element [i]: ]expected E, actual A[: message]`.
pub(crate) fn failure_line(f: &AssertionFailure) -> String {
    let mut s = format!("{}: cycle {}: ", f.location, f.cycle);
    if let Some(i) = f.index {
        let _ = write!(s, "element [{i}]: ");
    }
    if let Some(path) = &f.element {
        let _ = write!(s, "element {path}: ");
    }
    let _ = write!(s, "expected {}, actual {}", f.expected, f.actual);
    if !f.message.is_empty() {
        let _ = write!(s, ": {}", f.message);
    }
    s
}

/// The detail lines of a test that did not pass (empty when it passed).
pub(crate) fn details(case: &TestCase) -> Vec<String> {
    let mut lines: Vec<String> = case.left_out.iter().cloned().collect();
    lines.extend(case.failures.iter().map(failure_line));
    if case.more_failures > 0 {
        lines.push(format!(
            "... and {} more failed assertions",
            case.more_failures
        ));
    }
    if case.unfinished {
        lines.push(unfinished_line(case));
    }
    lines.extend(case.output.iter().map(|l| format!("log: {l}")));
    if let Some(fault) = &case.fault {
        lines.extend(fault.to_string().lines().map(str::to_string));
    }
    lines
}

/// Why an unfinished test failed.
pub(crate) fn unfinished_line(case: &TestCase) -> String {
    match case.suite {
        Some(_) => format!(
            "TEST_FINISHED was not called within {} cycles (timed out)",
            case.cycles
        ),
        None => format!("TEST_DONE was not set within {} cycles", case.cycles),
    }
}

fn plural(n: u64, one: &str) -> String {
    format!("{n} {one}{}", if n == 1 { "" } else { "s" })
}

pub(super) fn render(report: &TestReport) -> String {
    let mut out = String::new();
    for case in &report.cases {
        let verdict = match case.outcome() {
            TestOutcome::Passed => "PASS ",
            TestOutcome::Failed => "FAIL ",
            TestOutcome::Errored => "ERROR",
            TestOutcome::Skipped => "SKIP ",
        };
        let assertions = match case.suite {
            Some(_) => format!(", {}", plural(case.assertions as u64, "assertion")),
            None => String::new(),
        };
        let _ = writeln!(
            out,
            "{verdict} {} ({}, {}{assertions})",
            case.full_name(),
            case.file,
            plural(case.cycles, "cycle")
        );
        for line in details(case) {
            let _ = writeln!(out, "      {line}");
        }
    }
    let skipped = match report.count(TestOutcome::Skipped) {
        0 => String::new(),
        n => format!(", {n} skipped"),
    };
    let _ = writeln!(
        out,
        "{}: {} passed, {} failed, {} errored{skipped} in {:.3} s",
        plural(report.cases.len() as u64, "test"),
        report.count(TestOutcome::Passed),
        report.count(TestOutcome::Failed),
        report.count(TestOutcome::Errored),
        report.elapsed.as_secs_f64()
    );
    out
}

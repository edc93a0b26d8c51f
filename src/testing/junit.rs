//! The JUnit XML report (the layout GitLab, Jenkins and most CI systems
//! read): `<testsuites>`, one `<testsuite>`, a `<testcase>` per test with a
//! `<failure>` for failed assertions or an `<error>` for a runtime fault.

use super::text::{details, failure_line, unfinished_line};
use super::{TestOutcome, TestReport};
use std::fmt::Write;

/// `s` escaped for an XML attribute value or text node.
pub(crate) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // Characters XML 1.0 cannot hold at all.
            c if (c as u32) < 0x20 && !matches!(c, '\t' | '\n' | '\r') => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

pub(super) fn render(report: &TestReport, suite: &str) -> String {
    let total = report.cases.len();
    let failures = report.count(TestOutcome::Failed);
    let errors = report.count(TestOutcome::Errored);
    let skipped = report.count(TestOutcome::Skipped);
    let time = report.elapsed.as_secs_f64();
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let counts =
        format!("tests=\"{total}\" failures=\"{failures}\" errors=\"{errors}\" time=\"{time:.3}\"");
    let suite = escape(suite);
    let _ = writeln!(out, "<testsuites name=\"{suite}\" {counts}>");
    let _ = writeln!(
        out,
        "  <testsuite name=\"{suite}\" {counts} skipped=\"{skipped}\">"
    );
    for case in &report.cases {
        let _ = write!(
            out,
            "    <testcase name=\"{}\" classname=\"{}\" time=\"{:.3}\"",
            escape(&case.name),
            escape(case.suite.as_ref().unwrap_or(&case.file)),
            case.elapsed.as_secs_f64()
        );
        let body = escape(&details(case).join("\n"));
        match case.outcome() {
            TestOutcome::Passed => out.push_str("/>\n"),
            TestOutcome::Skipped => out.push_str(">\n      <skipped/>\n    </testcase>\n"),
            TestOutcome::Failed => {
                let (message, kind) = match case.failures.first() {
                    Some(f) => (failure_line(f), "AssertionFailure"),
                    None => (unfinished_line(case), "Unfinished"),
                };
                let _ = writeln!(
                    out,
                    ">\n      <failure message=\"{}\" type=\"{kind}\">{body}</failure>\n    </testcase>",
                    escape(&message)
                );
            }
            TestOutcome::Errored => {
                let (message, kind) = match (&case.fault, &case.left_out) {
                    (Some(f), _) => (
                        format!("{} in cycle {} at {}", f.fault.kind, f.cycle, f.location),
                        f.code(),
                    ),
                    (None, Some(why)) => (why.clone(), "NotCompiled"),
                    (None, None) => (String::new(), "R000"),
                };
                let _ = writeln!(
                    out,
                    ">\n      <error message=\"{}\" type=\"{kind}\">{body}</error>\n    </testcase>",
                    escape(&message)
                );
            }
        }
    }
    out.push_str("  </testsuite>\n</testsuites>\n");
    out
}

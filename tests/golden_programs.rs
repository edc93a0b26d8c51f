//! The seed programs in `programs/` print exactly their committed expected
//! traces (which are derived without plcrun, see `docs/programs.md`). They
//! run through the library's `Session`, which gives the CSV text `plcrun`
//! prints; ALG01 s1 also runs through the real binary, to standard output
//! and to an `--output` file, so that the command line stays covered end to
//! end byte for byte. Each run is also repeated to check that the output is
//! deterministic.

use crate::support::cli;
use crate::support::library;

use cli::{plcrun_ok, temp_file};
use library::{TraceRequest, csv_trace, repo_files, repo_text};
use rstest::rstest;

const ALG_TRACE: &str = "M0,M1,M2,M3,M4,V1,V2,L1";

/// Compares `actual` with the expected file byte for byte; on a mismatch,
/// names the first differing line.
fn assert_trace(actual: &str, expected_file: &str) {
    let expected = repo_text(expected_file);
    if actual != expected {
        let first = actual
            .lines()
            .zip(expected.lines())
            .position(|(a, e)| a != e)
            .map(|i| {
                format!(
                    "line {}: got {:?}, expected {:?}",
                    i + 1,
                    actual.lines().nth(i).unwrap(),
                    expected.lines().nth(i).unwrap()
                )
            })
            .unwrap_or_else(|| {
                format!(
                    "{} lines vs {} expected",
                    actual.lines().count(),
                    expected.lines().count()
                )
            });
        panic!("trace differs from {expected_file}: {first}");
    }
}

/// Runs `source` twice through the library, checks both runs are identical
/// and equal to the expected file.
fn check(source: &str, request: &TraceRequest, expected_file: &str) {
    let files = repo_files(&[source]);
    let first = csv_trace(&files, request);
    assert_trace(&first, expected_file);
    let second = csv_trace(&files, request);
    assert_eq!(first, second, "two runs of {source} differ");
}

#[rstest]
fn alg_programs_match_their_expected_traces(
    #[values("alg01", "alg02")] program: &str,
    #[values("s1", "s2", "s1s2", "sw1_held")] scenario: &str,
) {
    let stimulus = repo_text(&format!("programs/alg01_{scenario}.csv"));
    let request = TraceRequest {
        cycles: 1200,
        stimulus: Some(&stimulus),
        trace: Some(ALG_TRACE),
        changes_only: false,
    };
    check(
        &format!("programs/{program}.il"),
        &request,
        &format!("programs/{program}_{scenario}.expected.csv"),
    );
}

#[test]
fn cmd_monitor_matches_its_expected_trace() {
    let stimulus = repo_text("programs/cmd_monitor.csv");
    let request = TraceRequest {
        cycles: 125,
        stimulus: Some(&stimulus),
        ..TraceRequest::default()
    };
    check(
        "programs/cmd_monitor.st",
        &request,
        "programs/cmd_monitor.expected.csv",
    );
}

#[test]
fn comparator_matches_its_expected_trace() {
    let request = TraceRequest {
        cycles: 256,
        ..TraceRequest::default()
    };
    check(
        "programs/comparator.st",
        &request,
        "programs/comparator.expected.csv",
    );
}

/// The command line's arguments for ALG01 scenario s1.
const ALG01_S1: [&str; 9] = [
    "programs/alg01.il",
    "--cycles",
    "1200",
    "--stimulus",
    "programs/alg01_s1.csv",
    "--trace",
    ALG_TRACE,
    "--format",
    "csv",
];

/// The binary prints the expected trace on standard output, twice the same.
#[test]
fn alg01_s1_through_the_binary_prints_the_expected_trace() {
    let first = plcrun_ok(&ALG01_S1);
    assert_trace(&first, "programs/alg01_s1.expected.csv");
    let second = plcrun_ok(&ALG01_S1);
    assert_eq!(first, second, "two runs of plcrun {ALG01_S1:?} differ");
}

/// The same scenario written to a file with `--output` gives the same bytes.
#[test]
fn output_file_holds_the_same_trace() {
    let out = temp_file("alg01_s1.csv", "");
    let mut args = ALG01_S1.to_vec();
    args.extend(["--output", &out]);
    let stdout = plcrun_ok(&args);
    assert_eq!(stdout, "", "--output must keep standard output empty");
    let written = std::fs::read_to_string(&out).unwrap();
    assert_trace(&written, "programs/alg01_s1.expected.csv");
}

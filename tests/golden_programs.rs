//! The seed programs in `programs/` run through the real `plcrun` binary and
//! print exactly their committed expected traces (which are derived without
//! plcrun, see `docs/programs.md`). Each run is also repeated to check that
//! the output is deterministic.

use rstest::rstest;
use std::path::Path;
use std::process::Command;

const ALG_TRACE: &str = "M0,M1,M2,M3,M4,V1,V2,L1";

fn repo(path: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(path)
        .to_string_lossy()
        .into_owned()
}

/// Runs plcrun with `args` (paths relative to the repository root) and
/// returns its standard output; fails on a non-zero exit status.
fn run(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_plcrun"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .expect("run plcrun");
    assert!(
        out.status.success(),
        "plcrun {args:?} exited with {:?}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 trace")
}

/// Compares `actual` with the expected file byte for byte; on a mismatch,
/// names the first differing line.
fn assert_trace(actual: &str, expected_file: &str) {
    let expected = std::fs::read_to_string(repo(expected_file)).expect("expected trace");
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

/// Runs twice, checks both runs are identical and equal to the expected file.
fn check(args: &[&str], expected_file: &str) {
    let first = run(args);
    assert_trace(&first, expected_file);
    let second = run(args);
    assert_eq!(first, second, "two runs of {args:?} differ");
}

#[rstest]
fn alg_programs_match_their_expected_traces(
    #[values("alg01", "alg02")] program: &str,
    #[values("s1", "s2", "s1s2", "sw1_held")] scenario: &str,
) {
    let source = format!("programs/{program}.il");
    let stimulus = format!("programs/alg01_{scenario}.csv");
    check(
        &[
            &source,
            "--cycles",
            "1200",
            "--stimulus",
            &stimulus,
            "--trace",
            ALG_TRACE,
            "--format",
            "csv",
        ],
        &format!("programs/{program}_{scenario}.expected.csv"),
    );
}

#[test]
fn cmd_monitor_matches_its_expected_trace() {
    check(
        &[
            "programs/cmd_monitor.st",
            "--cycles",
            "125",
            "--stimulus",
            "programs/cmd_monitor.csv",
            "--format",
            "csv",
        ],
        "programs/cmd_monitor.expected.csv",
    );
}

#[test]
fn comparator_matches_its_expected_trace() {
    check(
        &[
            "programs/comparator.st",
            "--cycles",
            "256",
            "--format",
            "csv",
        ],
        "programs/comparator.expected.csv",
    );
}

/// The same scenario written to a file with `--output` gives the same bytes.
#[test]
fn output_file_holds_the_same_trace() {
    let dir = std::env::temp_dir().join(format!("plcrun-golden-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("alg01_s1.csv");
    let out_s = out.to_string_lossy().into_owned();
    let stdout = run(&[
        "programs/alg01.il",
        "--cycles",
        "1200",
        "--stimulus",
        "programs/alg01_s1.csv",
        "--trace",
        ALG_TRACE,
        "--format",
        "csv",
        "--output",
        &out_s,
    ]);
    assert_eq!(stdout, "", "--output must keep standard output empty");
    let written = std::fs::read_to_string(&out).unwrap();
    assert_trace(&written, "programs/alg01_s1.expected.csv");
    std::fs::remove_dir_all(&dir).ok();
}

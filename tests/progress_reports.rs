//! The library's progress reports (`plcrun::Progress`), which the command
//! line's progress bar draws: what each long piece of work reports, in
//! which order, and that the work's result does not depend on it.

use plcrun::{
    CompareOptions, Options, Pair, Plc, Progress, RandomStimulus, Session, SourceMap, TestOptions,
    TraceFormat, TraceWriter, run_seeds, run_seeds_reporting, run_tests_reporting,
};
use std::sync::Mutex;

/// Every report, in arrival order.
#[derive(Default)]
struct Log(Mutex<Vec<(u64, u64, String)>>);

impl Progress for Log {
    fn report(&self, done: u64, total: u64, stage: &str) {
        self.0
            .lock()
            .expect("not poisoned")
            .push((done, total, stage.to_string()));
    }
}

impl Log {
    fn take(self) -> Vec<(u64, u64, String)> {
        self.0.into_inner().expect("not poisoned")
    }
}

const COUNTER: &str = "PROGRAM P
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR
IF go THEN n := n + 1; END_IF;
END_PROGRAM";

fn plc() -> Plc {
    Plc::compile_files(&[("p.st", COUNTER)], &Options::default()).expect("compiles")
}

#[test]
fn a_run_reports_every_4096_cycles_and_at_its_end() {
    let mut session = Session::new(plc());
    let names = session.trace_names().to_vec();
    let mut out = TraceWriter::new(Vec::new(), TraceFormat::Csv, names, false);
    let log = Log::default();
    session.run_reporting(10_000, &mut out, &log).expect("runs");
    let log = log.take();
    let done: Vec<u64> = log.iter().map(|r| r.0).collect();
    assert_eq!(done, [0, 4096, 8192, 10_000]);
    assert!(log.iter().all(|r| r.1 == 10_000 && r.2 == "cycles"));
    assert_eq!(session.plc().cycle(), 10_000);
}

#[test]
fn a_comparison_reports_each_seed_once_and_finds_the_same() {
    let make = || Pair::new(plc(), plc(), &CompareOptions::default());
    let settings = RandomStimulus::default();
    let log = Log::default();
    let reported = run_seeds_reporting(make, &settings, 10..60, 30, 2, &log).expect("runs");
    let plain = run_seeds(make, &settings, 10..60, 30, 2).expect("runs");
    assert_eq!(reported, plain);
    let log = log.take();
    assert_eq!(log[0], (0, 50, "seeds".to_string()));
    // Two threads report in any order, but each count comes once.
    let mut done: Vec<u64> = log[1..].iter().map(|r| r.0).collect();
    done.sort_unstable();
    assert_eq!(done, (1..=50).collect::<Vec<_>>());
}

#[test]
fn a_test_run_reports_the_check_then_each_test() {
    let mut sources = SourceMap::new();
    sources.add(
        "t.st",
        "PROGRAM TEST_A AssertTrue(TRUE, 'a'); END_PROGRAM
         PROGRAM TEST_B AssertTrue(TRUE, 'b'); END_PROGRAM",
    );
    let log = Log::default();
    let report = run_tests_reporting(&sources, &TestOptions::default(), &log).expect("runs");
    assert!(report.all_passed());
    let stages: Vec<(u64, u64, String)> = log.take();
    let expected = [
        (0, 3, "check"),
        (1, 3, "TEST_A"),
        (2, 3, "TEST_B"),
        (3, 3, "done"),
    ];
    let expected: Vec<(u64, u64, String)> = expected
        .iter()
        .map(|&(d, t, s)| (d, t, s.to_string()))
        .collect();
    assert_eq!(stages, expected);
}

//! Running one test: compile the sources with the assertions declared,
//! then run cycles on the virtual clock until the test's cycles run out,
//! it sets `TEST_DONE`, or it faults.

use super::assertions::{self, Log, Recorded};
use super::discover::Found;
use super::{AssertionFailure, TestCase, TestError, TestOptions};
use crate::runtime::engine::{Options, Plc};
use crate::runtime::host_blocks::HostBlocks;
use crate::source::{FileId, SourceMap, Span};
use std::time::Instant;

/// The PROGRAM generated to run a test FUNCTION_BLOCK.
const WRAPPER: &str = "PLCRUN_TEST_MAIN";
/// Its instance of the test block.
const INSTANCE: &str = "test";

/// `file:line:column` of an encoded call position.
pub(super) fn locate(sources: &SourceMap, loc: i64) -> String {
    let file = (loc >> 32) as usize;
    let offset = (loc & 0xFFFF_FFFF) as usize;
    if file >= sources.files().len() {
        return "?".to_string();
    }
    sources.location(Span::new(FileId(file as u32), offset, offset + 1))
}

fn failure(sources: &SourceMap, r: Recorded, cycle: u64) -> AssertionFailure {
    AssertionFailure {
        location: locate(sources, r.loc),
        expected: r.expected,
        actual: r.actual,
        index: r.index,
        element: r.element,
        message: r.message,
        cycle,
    }
}

/// Compiles the runtime of `test`: its own sources, a wrapper PROGRAM for
/// a FUNCTION_BLOCK, the assertions recording into `log`.
fn compile(
    sources: &SourceMap,
    test: &Found,
    options: &TestOptions,
    log: &Log,
) -> Result<Plc, TestError> {
    let mut hosts = HostBlocks::new();
    assertions::register(&mut hosts, log).map_err(TestError::Host)?;
    let mut sources = sources.clone();
    let program = if test.is_block {
        sources.add(
            format!("<test {}>", test.name),
            format!(
                "PROGRAM {WRAPPER}\nVAR {INSTANCE} : {}; END_VAR\n{INSTANCE}();\nEND_PROGRAM\n",
                test.name
            ),
        );
        WRAPPER.to_string()
    } else {
        test.name.clone()
    };
    let plc_options = Options {
        cycle_time: options.cycle_time,
        program: Some(program),
        watchdog: options.watchdog,
        strict: options.strict,
        addressing: options.addressing,
        hosts,
        ..Options::default()
    };
    Plc::compile(sources, &plc_options).map_err(TestError::Compile)
}

/// Runs `test` on a fresh runtime.
pub(super) fn run(
    sources: &SourceMap,
    test: &Found,
    options: &TestOptions,
) -> Result<TestCase, TestError> {
    let start = Instant::now();
    let log = Log::default();
    let mut plc = compile(sources, test, options, &log)?;
    let done_path = if test.is_block {
        format!("{INSTANCE}.TEST_DONE")
    } else {
        "TEST_DONE".to_string()
    };
    let mut case = TestCase {
        name: test.name.clone(),
        suite: None,
        file: test.file.clone(),
        cycles: 0,
        elapsed: Default::default(),
        failures: Vec::new(),
        more_failures: 0,
        fault: None,
        unfinished: test.has_done,
        assertions: 0,
        output: Vec::new(),
        left_out: None,
        skipped: false,
    };
    for cycle in 0..test.cycle_limit() {
        let result = plc.run_cycle();
        case.cycles = cycle + 1;
        let recorded = log.take();
        let sources = plc.sources();
        case.failures
            .extend(recorded.into_iter().map(|r| failure(sources, r, cycle)));
        if let Err(fault) = result {
            case.fault = Some(fault);
            break;
        }
        if test.has_done && plc.read(&done_path).ok().and_then(|v| v.as_bool()) == Some(true) {
            case.unfinished = false;
            break;
        }
    }
    if case.fault.is_some() {
        case.unfinished = false;
    }
    case.more_failures = log.dropped();
    case.elapsed = start.elapsed();
    Ok(case)
}

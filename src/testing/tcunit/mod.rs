//! TcUnit suites under `plcrun test`: a FUNCTION_BLOCK that extends
//! `FB_TestSuite` is a suite; its tests are what it declares with
//! `TEST('name')` / `TEST_ORDERED('name')` while it runs. The runner calls
//! every suite instance once per cycle (one after the other with
//! `RUN_IN_SEQUENCE`), as TcUnit's `RUN` does, until every test called
//! `TEST_FINISHED`; docs/testing.md, "TcUnit suites".

mod assert_counts;
mod hosts;
mod state;

pub(crate) use state::State;

mod io_links;
mod nc_axes;

use super::assertions::{self, Log, Recorded};
use super::{AssertionFailure, TestCase, TestError, TestOptions};
use crate::diagnostics::Diagnostics;
use crate::runtime::engine::{Options, Plc};
use crate::runtime::host_blocks::HostBlocks;
use crate::source::{FileId, SourceMap};
use crate::syntax::ast::{Item, PouKind, TypeSpec};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The base block of every suite.
const BASE: &str = "FB_TestSuite";
/// The PROGRAM generated to call the suites.
const DRIVER: &str = "PLCRUN_TCUNIT_MAIN";
/// Cycles run at most before the unfinished tests time out.
pub(crate) const CYCLE_LIMIT: u64 = super::discover::DEFAULT_DONE_LIMIT;

/// One suite instance to run.
#[derive(Debug, Clone)]
pub(crate) struct SuiteInstance {
    /// Its name in the report: the instance's path in the PROGRAM that
    /// declares it (`PRG_TEST.fbMotorTest`), as TcUnit names it, or the
    /// block's name when no PROGRAM declares one.
    pub(crate) path: String,
    /// The suite's FUNCTION_BLOCK.
    pub(crate) block: String,
    /// The file declaring the block.
    pub(crate) file: String,
}

/// The suites of the sources and how to run them.
#[derive(Debug, Clone, Default)]
pub(crate) struct Plan {
    /// The suite instances, in the order they are called.
    pub(crate) suites: Vec<SuiteInstance>,
    /// A program calls `RUN_IN_SEQUENCE`.
    pub(crate) in_sequence: bool,
    /// The sources declare no `FB_TestSuite`: plcrun's is added.
    pub(crate) add_base: bool,
}

/// plcrun's `FB_TestSuite`: what suites read of TcUnit's own, the counts
/// of their assertions (`AssertResults.TotalAsserts`,
/// `AssertArrayResults.TotalArrayAsserts`; tcunit::assert_counts).
fn base_block() -> String {
    let total = hosts::TOTAL_ASSERTS;
    format!(
        "FUNCTION_BLOCK {BASE}
VAR
  AssertResults : FB_AssertResultStatic;
  AssertArrayResults : FB_AssertArrayResultStatic;
END_VAR
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_AssertResultStatic
PROPERTY TotalAsserts : UINT
GET
TotalAsserts := {total}(FALSE);
END_GET
END_PROPERTY
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_AssertArrayResultStatic
PROPERTY TotalArrayAsserts : UINT
GET
TotalArrayAsserts := {total}(TRUE);
END_GET
END_PROPERTY
END_FUNCTION_BLOCK
"
    )
}

/// TcUnit's parameter list, `GVL_Param_TcUnit`, with TcUnit's defaults:
/// suites read its limits (`TcUnit.GVL_Param_TcUnit.
/// MaxNumberOfAssertsForEachTestSuite`). plcrun's runner has no such
/// limits; the values are there to be read. Plain ST (a TwinCAT file would
/// bring plcrun's TwinCAT library into every run): a global is named with
/// any list as its qualifier (`sema::place`, `is_list_qualifier`).
const PARAMETERS: &str = "VAR_GLOBAL CONSTANT
    MaxNumberOfTestSuites : UINT := 1000;
    MaxNumberOfTestsForEachTestSuite : UINT := 100;
    MaxNumberOfAssertsForEachTestSuite : UINT := 1000;
    LogExtendedResults : BOOL := TRUE;
    xUnitEnablePublish : BOOL := FALSE;
    xUnitBufferSize : UDINT := 65535;
    xUnitFilePath : STRING(255) := '%TC_BOOTPRJPATH%tcunit_xunit_testresults.xml';
    AdsLogMessageFifoRingBufferSize : UINT := 2000;
    TimeBetweenTestSuitesExecution : TIME := T#0MS;
END_VAR
";

/// True when `text` writes the name of TcUnit's base block (any case):
/// a source without it declares no suite.
pub(crate) fn names_the_base(text: &str) -> bool {
    let base = BASE.as_bytes();
    text.as_bytes()
        .windows(base.len())
        .any(|w| w.eq_ignore_ascii_case(base))
}

/// The last segment of a possibly qualified name (`TcUnit.FB_TestSuite`).
fn last_segment(name: &str) -> &str {
    name.rsplit('.').next().unwrap_or(name)
}

/// True when `text` calls `RUN_IN_SEQUENCE` (any case, `TcUnit.` or not).
fn calls_in_sequence(text: &str) -> bool {
    let upper = text.to_ascii_uppercase();
    upper.match_indices("RUN_IN_SEQUENCE").any(|(i, m)| {
        let before = upper[..i].chars().next_back();
        let after = upper[i + m.len()..].trim_start();
        !before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_') && after.starts_with('(')
    })
}

/// Finds the suites of `sources`; parse errors go into `diags`.
pub(crate) fn plan(sources: &SourceMap, diags: &mut Diagnostics) -> Plan {
    let mut parents: HashMap<String, String> = HashMap::new();
    let mut blocks: Vec<(String, String)> = Vec::new();
    let mut programs = Vec::new();
    let mut in_sequence = false;
    for (i, file) in sources.files().iter().enumerate() {
        let unit = crate::syntax::parse_file(FileId(i as u32), &file.name, &file.text, diags);
        for item in unit.items {
            let Item::Pou(pou) = item else { continue };
            match pou.kind {
                PouKind::FunctionBlock => {
                    if let Some(parent) = pou.oop.as_ref().and_then(|o| o.extends.as_ref()) {
                        parents.insert(
                            pou.name.key(),
                            last_segment(&parent.name).to_ascii_uppercase(),
                        );
                    }
                    blocks.push((pou.name.name.clone(), file.name.clone()));
                }
                PouKind::Program => programs.push(pou),
                _ => {}
            }
        }
        in_sequence |= calls_in_sequence(&file.text);
    }
    let base_key = BASE.to_ascii_uppercase();
    let is_suite = |name: &str| {
        let mut key = name.to_ascii_uppercase();
        for _ in 0..64 {
            match parents.get(&key) {
                Some(p) if *p == base_key => return true,
                Some(p) => key = p.clone(),
                None => return false,
            }
        }
        false
    };
    let suites: Vec<&(String, String)> = blocks.iter().filter(|(n, _)| is_suite(n)).collect();
    let file_of = |name: &str| {
        suites
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, f)| f.clone())
    };
    let mut instances = Vec::new();
    for program in &programs {
        for block in &program.var_blocks {
            for decl in &block.decls {
                let TypeSpec::Named(ty) = &decl.ty else {
                    continue;
                };
                let Some(file) = file_of(last_segment(&ty.name)) else {
                    continue;
                };
                for name in &decl.names {
                    instances.push(SuiteInstance {
                        path: format!("{}.{}", program.name.name, name.name),
                        block: last_segment(&ty.name).to_string(),
                        file: file.clone(),
                    });
                }
            }
        }
    }
    if instances.is_empty() {
        // No program declares a suite: run each one no other suite extends.
        for (name, file) in &suites {
            let key = name.to_ascii_uppercase();
            if !parents.values().any(|p| *p == key) {
                instances.push(SuiteInstance {
                    path: name.clone(),
                    block: name.clone(),
                    file: file.clone(),
                });
            }
        }
    }
    let add_base = !blocks.iter().any(|(n, _)| n.eq_ignore_ascii_case(BASE)) && !suites.is_empty();
    Plan {
        suites: instances,
        in_sequence,
        add_base,
    }
}

/// The sources with what the suites need that TcUnit would give:
/// `FB_TestSuite` (when not declared) and, with `driver`, the PROGRAM that
/// calls the suites.
pub(crate) fn sources_for(sources: &SourceMap, plan: &Plan, driver: bool) -> SourceMap {
    let mut sources = sources.clone();
    if plan.add_base {
        sources.add("<TcUnit>", base_block());
        sources.add("<TcUnit parameters>", PARAMETERS);
    }
    if driver {
        let mut text = format!("PROGRAM {DRIVER}\nVAR\n");
        for (k, s) in plan.suites.iter().enumerate() {
            text.push_str(&format!("  suite{k} : {};\n", s.block));
        }
        text.push_str("END_VAR\n");
        for k in 0..plan.suites.len() {
            text.push_str(&format!(
                "IF {}(DINT#{k}) THEN suite{k}(); END_IF\n",
                hosts::ENTER
            ));
        }
        text.push_str("END_PROGRAM\n");
        sources.add("<TcUnit suites>", text);
    }
    sources
}

/// Registers the TcUnit functions and the assertions, counting for `state`.
pub(crate) fn register(hosts: &mut HostBlocks, state: &Arc<Mutex<State>>) -> Result<(), TestError> {
    hosts::register(hosts, state).map_err(TestError::Host)?;
    assertions::register(hosts, &Log::for_suites(state.clone())).map_err(TestError::Host)
}

fn failure(sources: &SourceMap, (r, cycle): (Recorded, u64)) -> AssertionFailure {
    AssertionFailure {
        location: super::run_one::locate(sources, r.loc),
        expected: r.expected,
        actual: r.actual,
        index: r.index,
        element: r.element,
        message: r.message,
        cycle,
    }
}

/// Runs every suite of `plan` on one runtime until every test finished
/// (or [`CYCLE_LIMIT`] cycles); one [`TestCase`] per test.
pub(crate) fn run(
    sources: &SourceMap,
    plan: &Plan,
    options: &TestOptions,
) -> Result<Vec<TestCase>, TestError> {
    // Under --keep-going a suite whose initialisation faults (its FB_init,
    // before any suite runs) is reported with the fault and left out, and
    // the others run again without it: one suite's fault does not take
    // the others with it, as a file that does not compile does not.
    let mut plan = plan.clone();
    let mut faulted = Vec::new();
    loop {
        let mut cases = run_plan(sources, &plan, options)?;
        let Some((at, k)) = init_fault_suite(&cases, &plan) else {
            faulted.extend(cases);
            return Ok(faulted);
        };
        // The fault is the suite's, whose instance raised it.
        let mut case = cases.swap_remove(at);
        case.suite = Some(plan.suites[k].path.clone());
        case.file = plan.suites[k].file.clone();
        faulted.push(case);
        if !options.keep_going || plan.suites.len() < 2 {
            return Ok(faulted);
        }
        plan.suites.remove(k);
    }
}

/// The case reporting a fault outside every test of the first cycle and
/// the suite (index in `plan`) whose initialisation raised it, under its
/// instance (`PLCRUN_TCUNIT_MAIN.suite3...`): (case index, suite index).
fn init_fault_suite(cases: &[TestCase], plan: &Plan) -> Option<(usize, usize)> {
    let at = cases.iter().position(|c| c.fault.is_some())?;
    let case = &cases[at];
    let fault = case.fault.as_ref()?;
    if fault.cycle != 0 || case.assertions > 0 {
        return None;
    }
    let prefix = format!("{DRIVER}.SUITE").to_ascii_uppercase();
    let instances = std::iter::once(fault.instance())
        .chain(fault.callers().iter().map(|c| c.instance.as_str()));
    instances
        .into_iter()
        .find_map(|i| {
            let upper = i.to_ascii_uppercase();
            let rest = upper.strip_prefix(&prefix)?;
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            digits
                .parse::<usize>()
                .ok()
                .filter(|&k| k < plan.suites.len())
        })
        .map(|k| (at, k))
}

/// Runs the suites of `plan` together, as TcUnit does.
fn run_plan(
    sources: &SourceMap,
    plan: &Plan,
    options: &TestOptions,
) -> Result<Vec<TestCase>, TestError> {
    let start = Instant::now();
    let state = Arc::new(Mutex::new(State::new(plan.suites.len(), plan.in_sequence)));
    let mut hosts = HostBlocks::new();
    register(&mut hosts, &state)?;
    let plc_options = Options {
        cycle_time: options.cycle_time,
        program: Some(DRIVER.to_string()),
        watchdog: options.watchdog,
        strict: options.strict,
        addressing: options.addressing,
        hosts,
        ..Options::default()
    };
    let mut plc =
        Plc::compile(sources_for(sources, plan, true), &plc_options).map_err(TestError::Compile)?;
    let lock = || state.lock().unwrap_or_else(|p| p.into_inner());
    let links = io_links::resolve(&plc, plan, &options.io_links);
    nc_axes::configure(&mut plc, plan, &options.nc_axes);
    let mut fault = None;
    let mut cycles = 0;
    let mut finished_at: HashMap<(usize, usize), Duration> = HashMap::new();
    for cycle in 0..CYCLE_LIMIT {
        lock().cycle = cycle;
        io_links::copy(&mut plc, &links);
        let result = plc.run_cycle();
        cycles = cycle + 1;
        let s = lock();
        for (k, suite) in s.suites.iter().enumerate() {
            for (t, test) in suite.tests.iter().enumerate() {
                if test.finished == Some(cycle) {
                    finished_at.insert((k, t), start.elapsed());
                }
            }
        }
        if let Err(f) = result {
            fault = Some((f, s.current(), s.current_suite()));
            break;
        }
        if s.all_finished() {
            break;
        }
    }
    let mut state = lock();
    let mut cases = Vec::new();
    let sources = plc.sources().clone();
    for (k, (instance, suite)) in plan.suites.iter().zip(state.suites.iter_mut()).enumerate() {
        for (t, test) in suite.tests.iter_mut().enumerate() {
            let mut case = TestCase {
                name: test.name.clone(),
                suite: Some(instance.path.clone()),
                file: instance.file.clone(),
                cycles: test.finished.map_or(cycles, |c| c + 1),
                elapsed: finished_at.get(&(k, t)).copied().unwrap_or(start.elapsed()),
                failures: std::mem::take(&mut test.failures)
                    .into_iter()
                    .map(|f| failure(&sources, f))
                    .collect(),
                more_failures: 0,
                fault: None,
                unfinished: test.finished.is_none() && !test.skipped,
                assertions: test.assertions.len(),
                output: std::mem::take(&mut test.output),
                left_out: None,
                skipped: test.skipped,
            };
            if test.duplicate {
                case.failures.push(AssertionFailure {
                    location: instance.file.clone(),
                    expected: "one TEST of this name per cycle".into(),
                    actual: "two".into(),
                    index: None,
                    element: None,
                    message: format!(
                        "test `{}` is declared twice in suite {}",
                        test.name, instance.path
                    ),
                    cycle: 0,
                });
            }
            if let Some((f, Some(at), _)) = &fault
                && *at == (k, t)
            {
                case.fault = Some(f.clone());
                case.unfinished = false;
            }
            cases.push(case);
        }
    }
    if let Some((f, None, suite)) = fault {
        // A fault outside any test (in a suite's own body): the first
        // unfinished test carries it; before any test was declared, a case
        // of the suite's own (or of the run, outside every suite) does, so
        // that the fault is never lost.
        match cases.iter().position(|c| c.unfinished) {
            Some(at) => {
                cases[at].fault = Some(f);
                cases[at].unfinished = false;
            }
            None => cases.push(body_fault_case(plan, suite, f, cycles, start.elapsed())),
        }
    }
    Ok(cases)
}

/// The case that reports fault `f` of the run when no test of it was
/// declared yet: named after the suite that was running (`suite`), or
/// after the runner when none was.
fn body_fault_case(
    plan: &Plan,
    suite: Option<usize>,
    f: crate::runtime::engine::RuntimeFault,
    cycles: u64,
    elapsed: Duration,
) -> TestCase {
    let instance = suite.and_then(|k| plan.suites.get(k));
    TestCase {
        name: "(before its first TEST)".into(),
        suite: Some(instance.map_or_else(|| DRIVER.to_string(), |i| i.path.clone())),
        file: instance.map(|i| i.file.clone()).unwrap_or_default(),
        cycles,
        elapsed,
        failures: Vec::new(),
        more_failures: 0,
        fault: Some(f),
        unfinished: false,
        assertions: 0,
        output: Vec::new(),
        left_out: None,
        skipped: false,
    }
}

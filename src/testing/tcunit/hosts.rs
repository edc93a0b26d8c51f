//! TcUnit's functions as host functions recording into the run's
//! [`State`]: `TEST`, `TEST_ORDERED`, `TEST_FINISHED`,
//! `TEST_FINISHED_NAMED`, `IS_TEST_FINISHED`, `TCUNIT_ADSLOGSTR` (and Tc2_System's
//! `ADSLOGSTR`), and `RUN` /
//! `RUN_IN_SEQUENCE` (which do nothing here: the runner calls the suites
//! itself), plus the runner's own `PLCRUN_TCUNIT_ENTER`.

use super::state::State;
use crate::elementary::ElemType;
use crate::runtime::host_blocks::{HostBlocks, HostDeclError, HostSignature};
use std::sync::{Arc, Mutex, MutexGuard};

/// The host function the generated program calls before each suite.
pub(crate) const ENTER: &str = "PLCRUN_TCUNIT_ENTER";
/// The host function an array assertion calls first (see
/// `sema::assert_tcunit`), for TcUnit's count of array assertions.
pub(crate) const ARRAY_ASSERT: &str = crate::sema::assert_calls::TCUNIT_ARRAY_ASSERT;
/// The host function behind `AssertResults.TotalAsserts` and
/// `AssertArrayResults.TotalArrayAsserts` (plcrun's `FB_TestSuite`).
pub(crate) const TOTAL_ASSERTS: &str = "PLCRUN_TCUNIT_TOTAL_ASSERTS";

fn lock(state: &Arc<Mutex<State>>) -> MutexGuard<'_, State> {
    state.lock().unwrap_or_else(|p| p.into_inner())
}

/// `msgFmtStr` with its `%s` replaced by `strArg`, as ADSLOGSTR formats.
fn format_log(format: &str, arg: &str) -> String {
    format.replacen("%s", arg, 1)
}

/// Registers TcUnit's functions, recording into `state`.
pub(crate) fn register(
    hosts: &mut HostBlocks,
    state: &Arc<Mutex<State>>,
) -> Result<(), HostDeclError> {
    let s = state.clone();
    hosts.function(
        HostSignature::function(ENTER, ElemType::Bool).input("Suite", ElemType::Dint),
        move |io| {
            let k = usize::try_from(io.get_i64("Suite")?).unwrap_or(usize::MAX);
            let run = lock(&s).enter(k);
            io.set_bool(ENTER, run)?;
            Ok(())
        },
    )?;
    for (name, ordered) in [("TEST", false), ("TEST_ORDERED", true)] {
        let s = state.clone();
        hosts.function(
            HostSignature::function(name, ElemType::Bool).input("TestName", ElemType::String),
            move |io| {
                let test = io.get_str("TestName")?;
                let counts = lock(&s).declare(&test, ordered);
                io.set_bool(name, counts)?;
                Ok(())
            },
        )?;
    }
    let s = state.clone();
    hosts.function(
        HostSignature::function("TEST_FINISHED", ElemType::Bool),
        move |io| {
            let done = lock(&s).finish_current();
            io.set_bool("TEST_FINISHED", done)?;
            Ok(())
        },
    )?;
    let s = state.clone();
    hosts.function(
        HostSignature::function("TEST_FINISHED_NAMED", ElemType::Bool)
            .input("TestName", ElemType::String),
        move |io| {
            let test = io.get_str("TestName")?;
            let found = lock(&s).finish_named(&test);
            io.set_bool("TEST_FINISHED_NAMED", found)?;
            Ok(())
        },
    )?;
    let s = state.clone();
    hosts.function(
        HostSignature::function("IS_TEST_FINISHED", ElemType::Bool)
            .input("TestName", ElemType::String),
        move |io| {
            let test = io.get_str("TestName")?;
            let done = lock(&s).is_finished(&test);
            io.set_bool("IS_TEST_FINISHED", done)?;
            Ok(())
        },
    )?;
    // TcUnit's assertion counts: an array assertion announces itself
    // (before its element comparisons), and a suite reads its totals.
    let s = state.clone();
    hosts.function(
        HostSignature::function(ARRAY_ASSERT, ElemType::Bool)
            .input("Loc", ElemType::Lint)
            .input("Expecteds", ElemType::String)
            .input("Actuals", ElemType::String)
            .input("Message", ElemType::String),
        move |io| {
            let shape = (io.get_str("Expecteds")?, io.get_str("Actuals")?);
            let message = io.get_str("Message")?;
            lock(&s).count_array(io.get_i64("Loc")?, shape, &message);
            io.set_bool(ARRAY_ASSERT, true)?;
            Ok(())
        },
    )?;
    let s = state.clone();
    hosts.function(
        HostSignature::function(TOTAL_ASSERTS, ElemType::Uint).input("Arrays", ElemType::Bool),
        move |io| {
            let total = lock(&s).total_asserts(io.get_bool("Arrays")?);
            io.set_i64(TOTAL_ASSERTS, total as i64)?;
            Ok(())
        },
    )?;
    // TcUnit's logger, and Tc2_System's ADSLOGSTR (result 0: no ADS
    // error), both into the test's log.
    for (name, result) in [
        ("TCUNIT_ADSLOGSTR", ElemType::Bool),
        ("ADSLOGSTR", ElemType::Dint),
    ] {
        let s = state.clone();
        hosts.function(
            HostSignature::function(name, result)
                .input("msgCtrlMask", ElemType::Dword)
                .input("msgFmtStr", ElemType::String)
                .input("strArg", ElemType::String),
            move |io| {
                let line = format_log(&io.get_str("msgFmtStr")?, &io.get_str("strArg")?);
                lock(&s).log(line);
                match result {
                    ElemType::Bool => io.set_bool(name, true)?,
                    _ => io.set_i64(name, 0)?,
                }
                Ok(())
            },
        )?;
    }
    for name in ["RUN", "RUN_IN_SEQUENCE"] {
        hosts.function(HostSignature::function(name, ElemType::Bool), move |io| {
            io.set_bool(name, true)?;
            Ok(())
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_log_format_takes_its_argument_once() {
        assert_eq!(super::format_log("value %s, %s", "7"), "value 7, %s");
        assert_eq!(super::format_log("plain", "7"), "plain");
    }
}

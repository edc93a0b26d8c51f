//! TcUnit's functions as host functions recording into the run's
//! [`State`]: `TEST`, `TEST_ORDERED`, `TEST_FINISHED`,
//! `TEST_FINISHED_NAMED`, `TCUNIT_ADSLOGSTR` (and Tc2_System's
//! `ADSLOGSTR`), and `RUN` /
//! `RUN_IN_SEQUENCE` (which do nothing here: the runner calls the suites
//! itself), plus the runner's own `PLCRUN_TCUNIT_ENTER`.

use super::state::State;
use crate::elementary::ElemType;
use crate::runtime::host_blocks::{HostBlocks, HostDeclError, HostSignature};
use std::sync::{Arc, Mutex, MutexGuard};

/// The host function the generated program calls before each suite.
pub(crate) const ENTER: &str = "PLCRUN_TCUNIT_ENTER";

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

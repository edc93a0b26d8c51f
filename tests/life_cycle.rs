//! A PLC's life cycle (docs/runtime.md, "Life cycle, faults and the
//! watchdog"): after a fault the PLC is stopped and says why, runs nothing
//! until a reset, and a cold reset brings back every initial value; a
//! stop handle interrupts a runaway cycle from another thread; every fault
//! kind has a stable code, documented.

use crate::support::plc;

use plc::{compile, lit, program, run};
use plcrun::{FaultKind, Options, Plc, PlcState};
use std::time::{Duration, Instant};

/// Counts cycles in `n`; divides by zero when `boom` is set. Initial
/// values everywhere, of several kinds (a string, an array, a timer).
fn counter() -> Plc {
    compile(&program(
        "",
        "n : DINT := 100; boom : BOOL; z : INT; s : STRING := 'init'; \
         a : ARRAY[1..3] OF INT := [7, 8, 9]; t : TON; q : BOOL;",
        "n := n + 1; s := 'changed'; a[2] := 0; t(IN := TRUE, PT := T#20ms); q := t.Q; \
         IF boom THEN z := z / z; END_IF;",
    ))
}

#[test]
fn a_fault_stops_the_plc_until_a_reset() {
    let mut plc = counter();
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "n"), "103");
    plc.write("boom", "TRUE").unwrap();
    let fault = plc.run_cycle().unwrap_err();
    assert_eq!(fault.fault.kind, FaultKind::DivisionByZero);
    assert_eq!(fault.cycle, 3);
    assert_eq!(plc.state(), PlcState::Faulted(&fault));
    assert_eq!(plc.fault(), Some(&fault));
    // The faulting cycle ran up to the fault; nothing runs after it.
    assert_eq!(lit(&plc, "n"), "104");
    plc.write("boom", "FALSE").unwrap();
    for _ in 0..3 {
        assert_eq!(plc.run_cycle(), Err(fault.clone()));
    }
    assert_eq!(lit(&plc, "n"), "104", "the counter does not move");
    assert_eq!(plc.cycle(), 3, "no cycle counted");
}

#[test]
fn a_cold_reset_restores_every_initial_value_and_cycles_run_again() {
    let mut plc = counter();
    run(&mut plc, 3);
    assert_eq!(
        [lit(&plc, "s"), lit(&plc, "a[2]"), lit(&plc, "q")],
        ["'changed'", "0", "TRUE"]
    );
    plc.write("boom", "TRUE").unwrap();
    plc.run_cycle().unwrap_err();
    plc.reset_cold();
    assert_eq!(plc.state(), PlcState::Ready);
    assert_eq!(plc.fault(), None);
    assert_eq!((plc.cycle(), plc.time()), (0, 0));
    for (name, initial) in [
        ("n", "100"),
        ("boom", "FALSE"),
        ("s", "'init'"),
        ("a[1]", "7"),
        ("a[2]", "8"),
        ("t.ET", "T#0s"),
        ("t.Q", "FALSE"),
        ("q", "FALSE"),
    ] {
        assert_eq!(lit(&plc, name), initial, "{name}");
    }
    // It runs again, as freshly loaded: the timer times from 0 again.
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "n"), "102");
    assert_eq!(lit(&plc, "q"), "FALSE");
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "q"), "TRUE");
}

/// A reset with no fault is a cold restart too.
#[test]
fn a_cold_reset_of_a_running_plc_restarts_it() {
    let mut plc = counter();
    run(&mut plc, 5);
    plc.reset_cold();
    assert_eq!(lit(&plc, "n"), "100");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "101");
}

fn endless(watchdog: Option<Duration>) -> Plc {
    let src = program(
        "",
        "x : DINT;",
        "x := x + 1; WHILE TRUE DO x := x + 1; END_WHILE;",
    );
    let options = Options {
        watchdog,
        ..Options::default()
    };
    Plc::compile_files(&[("test.st", &src)], &options).unwrap()
}

#[test]
fn abort_from_another_thread_ends_an_endless_cycle() {
    let mut plc = endless(None);
    let handle = plc.stop_handle();
    // Timed from before the aborter starts its 50 ms: timed after, the
    // abort could land a little under 50 ms into the cycle.
    let start = Instant::now();
    let aborter = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(50));
        handle.abort();
    });
    let fault = plc.run_cycle().expect_err("aborted");
    let took = start.elapsed();
    aborter.join().unwrap();
    assert_eq!(fault.fault.kind, FaultKind::Aborted);
    assert!(took >= Duration::from_millis(50), "{took:?}");
    assert!(took < Duration::from_secs(5), "{took:?}");
    assert!(
        fault.location.starts_with("test.st:6:"),
        "{}",
        fault.location
    );
    let shown = fault.to_string();
    assert!(
        shown.starts_with("error[R009]: runtime fault in cycle 0") && shown.contains("aborted"),
        "{shown}"
    );
    // Stopped, and stays so until reset.
    assert_eq!(plc.state(), PlcState::Faulted(&fault));
    assert_eq!(plc.run_cycle(), Err(fault));
    assert!(plc.stop_handle().is_abort_requested());
    plc.reset_cold();
    assert!(!plc.stop_handle().is_stop_requested());
    assert!(!plc.stop_handle().is_abort_requested());
    assert_eq!(lit(&plc, "x"), "0");
}

/// An abort asked between cycles interrupts the next one as it starts.
#[test]
fn abort_between_cycles_stops_the_next_cycle_at_once() {
    let mut plc = counter();
    run(&mut plc, 1);
    plc.stop_handle().abort();
    let fault = plc.run_cycle().unwrap_err();
    assert_eq!(fault.fault.kind, FaultKind::Aborted);
    assert_eq!(lit(&plc, "n"), "101", "nothing of the cycle ran");
    // A stop alone (no abort) does not interrupt anything: the run loop
    // that drives the PLC decides at the cycle boundary.
    plc.reset_cold();
    plc.stop_handle().stop();
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "n"), "101");
}

#[test]
fn fault_codes_are_distinct_stable_and_documented() {
    let kinds = [
        (FaultKind::DivisionByZero, "R001"),
        (
            FaultKind::IndexOutOfRange {
                index: 0,
                lo: 1,
                hi: 2,
            },
            "R002",
        ),
        (
            FaultKind::SubrangeViolation {
                value: 0,
                lo: 1,
                hi: 2,
            },
            "R003",
        ),
        (FaultKind::ConversionOverflow, "R004"),
        (FaultKind::MuxOutOfRange { k: 3, n: 2 }, "R005"),
        (FaultKind::InvalidBcd, "R006"),
        (FaultKind::NegativeExponent, "R007"),
        (FaultKind::Watchdog, "R008"),
        (FaultKind::Aborted, "R009"),
        (FaultKind::BadAddress, "R999"),
    ];
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/diagnostics.md"))
        .expect("docs/diagnostics.md");
    for (kind, code) in &kinds {
        assert_eq!(kind.code(), *code, "{kind}");
        assert!(
            doc.contains(&format!("## {code}")),
            "{code} has no section in docs/diagnostics.md"
        );
    }
}

/// The code leads the message, as in a compile diagnostic.
#[test]
fn a_fault_message_shows_its_code() {
    let mut plc = counter();
    plc.write("boom", "TRUE").unwrap();
    let fault = plc.run_cycle().unwrap_err();
    assert_eq!(fault.code(), "R001");
    let shown = fault.to_string();
    assert!(
        shown.starts_with("error[R001]: runtime fault in cycle 0 at test.st:6:"),
        "{shown}"
    );
    assert!(shown.contains("division by zero"), "{shown}");
}

/// A PLC (with its watchdog thread) moves to another thread, and dropping
/// it ends that thread at once.
#[test]
fn a_plc_with_a_watchdog_is_send_and_drops_promptly() {
    fn send<T: Send>(_: &T) {}
    let start = Instant::now();
    for _ in 0..20 {
        let mut plc = counter(); // default watchdog: 1 s, thread polling every 125 ms
        run(&mut plc, 1);
        send(&plc);
        std::thread::spawn(move || drop(plc)).join().unwrap();
    }
    assert!(
        start.elapsed() < Duration::from_secs(2),
        "{:?}",
        start.elapsed()
    );
}

//! Expected traces of the ST seed programs, derived independently of plcrun:
//! `programs/comparator.expected.csv` from integer arithmetic and
//! `programs/cmd_monitor.expected.csv` from the block's equations, both
//! checked here against the committed files and against facts worked out by
//! hand.
//!
//! Regenerate the files (after checking a change by hand!) with
//! `PLCRUN_BLESS_MODELS=1 cargo test --test suite seed_programs::`.

use crate::support;

use support::seed_models::{cmd_monitor_expected_csv, cmd_monitor_run, comparator_expected_csv};
use support::trace_text::{bool_changes, check_or_bless, read_repo_file};

#[test]
fn comparator_expected_trace_matches_arithmetic() {
    check_or_bless(
        "programs/comparator.expected.csv",
        &comparator_expected_csv(),
    );
}

#[test]
fn comparator_spot_checks() {
    let text = comparator_expected_csv();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "cycle,time,A,B,Sup,Inf,Egal");
    assert_eq!(lines.len(), 257);
    // Cycle 1: A = 1, B = 0 -- the pair the seed's Vi[5] typo got wrong.
    assert_eq!(lines[2], "1,T#10ms,1,0,TRUE,FALSE,FALSE");
    // Cycle 16: A = 0, B = 1.
    assert_eq!(lines[17], "16,T#160ms,0,1,FALSE,TRUE,FALSE");
    // Cycle 255: A = B = 15.
    assert_eq!(lines[256], "255,T#2s550ms,15,15,FALSE,FALSE,TRUE");
    // 16 equal pairs, 120 with A > B, 120 with A < B.
    let count = |col: usize| {
        lines[1..]
            .iter()
            .filter(|l| l.split(',').nth(col) == Some("TRUE"))
            .count()
    };
    assert_eq!((count(4), count(5), count(6)), (120, 120, 16));
}

#[test]
fn cmd_monitor_expected_trace_matches_model() {
    let stimulus = read_repo_file("programs/cmd_monitor.csv");
    check_or_bless(
        "programs/cmd_monitor.expected.csv",
        &cmd_monitor_expected_csv(&stimulus),
    );
}

// Hand derivation (T_CMD_MAX = T#100ms = 10 cycles, set by the first row; the
// TON's Q is first TRUE in the call made 10 cycles after the call that saw IN
// rise; ALRM_FF is set-dominant: Q1 := S1 OR (NOT R AND Q1)).
// - 5: auto mode, AUTO_CMD -> CMD. 10: FDBK arrives in time; at 15 the timer's
//   Q rises but NOT FDBK is FALSE: no alarm. 20: AUTO_CMD falls -> CMD falls.
// - 30: AUTO_CMD again, no FDBK -> CMD; at 40 the timer's Q rises -> ALRM.
//   45..47: ACK while the fault is present does not clear it (set dominant).
//   50: AUTO_CMD falls -> CMD falls, the timer resets, ALRM stays latched.
//   55: ACK -> ALRM falls.
// - 60: manual mode (AUTO_MODE FALSE), MAN_CMD with MAN_CMD_CHK still TRUE:
//   no command. 65: MAN_CMD_CHK falls -> CMD. 70: FDBK in time (75: no alarm).
//   80: MAN_CMD falls, MAN_CMD_CHK back -> CMD falls.
// - 85..87: AUTO_CMD in manual mode is ignored.
// - 90: MAN_CMD without check -> CMD; no FDBK until 105, so at 100 -> ALRM.
//   105: late FDBK does not clear the alarm. 110: ACK (fault gone) -> ALRM
//   falls. 115: MAN_CMD falls -> CMD falls.
#[test]
fn cmd_monitor_hand_derived() {
    let stimulus = read_repo_file("programs/cmd_monitor.csv");
    let changes = bool_changes(&["CMD", "ALRM"], &cmd_monitor_run(&stimulus));
    let expected: Vec<(usize, String)> = [
        (5, "CMD+"),
        (20, "CMD-"),
        (30, "CMD+"),
        (40, "ALRM+"),
        (50, "CMD-"),
        (55, "ALRM-"),
        (65, "CMD+"),
        (80, "CMD-"),
        (90, "CMD+"),
        (100, "ALRM+"),
        (110, "ALRM-"),
        (115, "CMD-"),
    ]
    .iter()
    .map(|&(k, s)| (k, s.to_string()))
    .collect();
    assert_eq!(changes, expected);
}

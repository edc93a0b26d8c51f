//! CHARIOT (programs/chariot.sfc) against the hand-derived trace in
//! programs/chariot.expected.csv, through the real binary (end to end, byte
//! for byte); the step time through the library.
//!
//! Derivation (10 ms cycles, cycle k at k × 10 ms; semantics §5):
//! - cycle 0: first call, INIT active; `dcy & fcA` is FALSE; no action is
//!   live so KMAV/KMAR keep FALSE; the plain statement gives VOM := fcA = TRUE.
//! - cycle 5: Dcy TRUE with FcA TRUE: INIT → AV fires; AV's `KMAV(N)` gives
//!   KMAV TRUE in the same call.
//! - cycle 10: FcA FALSE (the trolley left A): VOM FALSE.
//! - cycle 20: a second Dcy pulse: INIT is inactive, nothing happens.
//! - cycle 100: FcB TRUE: AV → ATT; KMAV's only step is gone → KMAV FALSE.
//!   ATT is activated at 1 s, ATT.T = T#0s.
//! - cycle 30000: Dcy pulse at B: ignored.
//! - cycle 60100: ATT.T = (60100 − 100) × 10 ms = 600 s = T#10m ≥ tX3: ATT → AR,
//!   KMAR TRUE. ATT keeps ATT.T = T#10m after its deactivation.
//! - cycle 60150: FcB FALSE (left B). cycle 60300: FcA TRUE: AR → INIT, KMAR
//!   FALSE, VOM TRUE. cycle 60310: Dcy again: INIT → AV, KMAV TRUE.

use crate::support::cli;
use crate::support::sfc_run;

use cli::plcrun_ok;
use sfc_run::column;
use sfc_run::library::{TraceRequest, csv_trace, repo_files, repo_text};

const TRACE: &str = "Dcy,FcA,FcB,INIT.X,AV.X,ATT.X,AR.X,KMAV,KMAR,VOM";

#[test]
fn chariot_matches_hand_derived_trace() {
    let args = [
        "programs/chariot.sfc",
        "--cycles",
        "60320",
        "--stimulus",
        "programs/chariot.csv",
        "--trace",
        TRACE,
        "--format",
        "csv",
        "--changes-only",
    ];
    let printed = plcrun_ok(&args);
    let want = repo_text("programs/chariot.expected.csv");
    assert_eq!(printed, want);
}

#[test]
fn chariot_waiting_step_time() {
    let request = TraceRequest {
        cycles: 60210,
        stimulus: Some(&repo_text("programs/chariot.csv")),
        trace: Some("ATT.X,ATT.T"),
        changes_only: false,
    };
    let trace = csv_trace(&repo_files(&["programs/chariot.sfc"]), &request);
    let t = column(&trace, "ATT.T");
    let x = column(&trace, "ATT.X");
    // Never active before cycle 100: T stays at its initial T#0s.
    assert_eq!((x[99].as_str(), t[99].as_str()), ("FALSE", "T#0s"));
    // Activated in cycle 100: T#0s, then 10 ms more each cycle.
    assert_eq!((x[100].as_str(), t[100].as_str()), ("TRUE", "T#0s"));
    assert_eq!(t[101], "T#10ms");
    assert_eq!(t[60099], "T#9m59s990ms");
    // Deactivated in cycle 60100 with the value it had in that call.
    assert_eq!((x[60100].as_str(), t[60100].as_str()), ("FALSE", "T#10m"));
    assert_eq!(t[60209], "T#10m");
}

//! CHARIOT (programs/chariot.sfc) run through the real binary against the
//! hand-derived trace in programs/chariot.expected.csv.
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

#[path = "support/sfc_run.rs"]
mod sfc_run;

use sfc_run::{column, plcrun, repo};

const TRACE: &str = "Dcy,FcA,FcB,INIT.X,AV.X,ATT.X,AR.X,KMAV,KMAR,VOM";

#[test]
fn chariot_matches_hand_derived_trace() {
    let src = repo("programs/chariot.sfc");
    let stim = repo("programs/chariot.csv");
    let r = plcrun(&[
        src.to_str().unwrap(),
        "--cycles",
        "60320",
        "--stimulus",
        stim.to_str().unwrap(),
        "--trace",
        TRACE,
        "--format",
        "csv",
        "--changes-only",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let want = std::fs::read_to_string(repo("programs/chariot.expected.csv")).unwrap();
    assert_eq!(r.stdout, want);
}

#[test]
fn chariot_waiting_step_time() {
    let src = repo("programs/chariot.sfc");
    let stim = repo("programs/chariot.csv");
    let r = plcrun(&[
        src.to_str().unwrap(),
        "--cycles",
        "60210",
        "--stimulus",
        stim.to_str().unwrap(),
        "--trace",
        "ATT.X,ATT.T",
        "--format",
        "csv",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let t = column(&r.stdout, "ATT.T");
    let x = column(&r.stdout, "ATT.X");
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

//! The expected traces of ALG01 and ALG02 (`programs/alg0?_<scenario>.expected.csv`)
//! are produced by the independent models in `tests/support/grafcet_models.rs`,
//! not by plcrun. This test keeps the committed files equal to the models'
//! output and checks the models against step-change cycles derived by hand.
//!
//! Regenerate the files (after checking a change by hand!) with
//! `PLCRUN_BLESS_MODELS=1 cargo test --test suite grafcet_models::`.

use crate::support;

use support::grafcet_models::{Algorithm, CYCLES, TRACED, expected_csv, run};
use support::trace_text::{bool_changes, check_or_bless, read_repo_file};

const SCENARIOS: [&str; 4] = ["s1", "s2", "s1s2", "sw1_held"];

fn stimulus(scenario: &str) -> String {
    read_repo_file(&format!("programs/alg01_{scenario}.csv"))
}

#[test]
fn committed_expected_traces_match_the_models() {
    for alg in [Algorithm::Alg01, Algorithm::Alg02] {
        for scenario in SCENARIOS {
            let file = format!("programs/{}_{scenario}.expected.csv", alg.file_stem());
            check_or_bless(&file, &expected_csv(alg, &stimulus(scenario)));
        }
    }
}

/// The cycles where a traced variable changes, as `(cycle, "NAME+ NAME-")`.
fn changes(alg: Algorithm, scenario: &str) -> Vec<(usize, String)> {
    bool_changes(&TRACED, &run(alg, &stimulus(scenario), CYCLES))
}

fn owned(list: &[(usize, &str)]) -> Vec<(usize, String)> {
    list.iter().map(|&(k, s)| (k, s.to_string())).collect()
}

// Hand derivations. Cycle k runs at k × 10 ms; the stimulus row of cycle k is
// applied before the program runs in cycle k; DT1 = DT2 = T#5s = 500 cycles.
//
// ALG01, scenario s1 (SW1 TRUE in cycles 10..14, S1 TRUE in cycles 30..34):
// - cycle 0: no step bit is set, so rung "Etape 0" sets M0.
// - cycle 10: SW1 -> M1 := M0 AND SW1; L1 := M1 AND NOT M23. M0 is still TRUE
//   in this cycle (its rung ran before M1 was set).
// - cycle 11: rung "Etape 0" sees M1 -> M0 FALSE.
// - cycle 30: S1 AND NOT S2 with M1 -> M2; M23 := M2 and T1 sees IN rise
//   (start = 300 ms); V1 := M2; L1 := ... AND NOT M23 -> FALSE. M1 still TRUE.
// - cycle 31: rung "Etape 1" sees M2 -> M1 FALSE.
// - cycle 530 (= 30 + 500): T1.ET = 5 s -> QT1 TRUE; rung "Etape 4", after the
//   T1 call, sets M4; T2 sees IN rise (start = 5.3 s); V1 := ... AND NOT M4.
// - cycle 531: rung "Etape 2" sees M4 -> M2 FALSE (M23 FALSE, T1 reset).
// - cycle 1030 (= 530 + 500): T2.Q TRUE -> QT2 TRUE, but rung "Etape 0" ran
//   before the T2 call and saw QT2 FALSE.
// - cycle 1031 (= 30 + 1001): rung "Etape 0" sees M4 AND QT2 -> M0; rung
//   "Etape 4" sees M0 -> M4 FALSE.
// ALG02 differs in two places, each adding one cycle:
// - APM4 := M23 AND QT1 runs *before* the T1 call, so it sees the QT1 of the
//   previous cycle: T1.Q rises in cycle 530, M4 is set in cycle 531 (M2 and
//   V1 last one cycle longer: M2 falls in 532, V1 in 531).
// - T2 therefore starts in 531, QT2 rises in 1031, APM0 sees it in 1032:
//   M0 set and M4 reset (SR4's RESET is M0, set earlier in the same scan)
//   in cycle 1032.
// Step 1 -> 2 is identical: SR1's RESET is M23, which in cycle 31 still holds
// the value computed in cycle 30 (TRUE), just as ALG01's rung "Etape 1" sees
// the M2 of cycle 30.

#[test]
fn alg01_s1_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg01, "s1"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (30, "M2+ V1+ L1-"),
            (31, "M1-"),
            (530, "M4+ V1-"),
            (531, "M2-"),
            (1031, "M0+ M4-"),
        ])
    );
}

#[test]
fn alg02_s1_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg02, "s1"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (30, "M2+ V1+ L1-"),
            (31, "M1-"),
            (531, "M4+ V1-"),
            (532, "M2-"),
            (1032, "M0+ M4-"),
        ])
    );
}

// Scenario s2 (SW1 in 10..14, S2 in 50..54): the same sequence through step 3
// and V2, with the branch taken at cycle 50: M4 at 550 (ALG02: 551), step 0
// again at 50 + 1001 = 1051 (ALG02: 1052).

#[test]
fn alg01_s2_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg01, "s2"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (50, "M3+ V2+ L1-"),
            (51, "M1-"),
            (550, "M4+ V2-"),
            (551, "M3-"),
            (1051, "M0+ M4-"),
        ])
    );
}

#[test]
fn alg02_s2_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg02, "s2"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (50, "M3+ V2+ L1-"),
            (51, "M1-"),
            (551, "M4+ V2-"),
            (552, "M3-"),
            (1052, "M0+ M4-"),
        ])
    );
}

// Scenario s1s2 (SW1 in 10..14, S1 and S2 both TRUE in 30..59, then S2 alone
// in 100..104): while both are TRUE neither receptivity S1·/S2 nor S2·/S1
// holds, so step 1 stays active (nothing changes in 30..99, L1 stays on).
// S2 alone at cycle 100 takes the step-3 branch: M4 at 600 (ALG02: 601),
// step 0 at 1101 (ALG02: 1102).

#[test]
fn alg01_s1s2_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg01, "s1s2"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (100, "M3+ V2+ L1-"),
            (101, "M1-"),
            (600, "M4+ V2-"),
            (601, "M3-"),
            (1101, "M0+ M4-"),
        ])
    );
}

#[test]
fn alg02_s1s2_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg02, "s1s2"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (100, "M3+ V2+ L1-"),
            (101, "M1-"),
            (601, "M4+ V2-"),
            (602, "M3-"),
            (1102, "M0+ M4-"),
        ])
    );
}

// Scenario sw1_held (SW1 TRUE from cycle 10 to 1099, S1 in 30..34): as s1
// until step 0 is reached again; SW1 is still TRUE then, so the scan that sets
// M0 also sets M1 (ALG01: rung "Etape 1" follows rung "Etape 0"; ALG02: APM1
// := M0 AND SW1 follows SR0) and L1 comes back on; M0 falls in the next scan.
// Releasing SW1 at 1100 changes nothing: the chart waits in step 1.

#[test]
fn alg01_sw1_held_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg01, "sw1_held"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (30, "M2+ V1+ L1-"),
            (31, "M1-"),
            (530, "M4+ V1-"),
            (531, "M2-"),
            (1031, "M0+ M1+ M4- L1+"),
            (1032, "M0-"),
        ])
    );
}

#[test]
fn alg02_sw1_held_hand_derived() {
    assert_eq!(
        changes(Algorithm::Alg02, "sw1_held"),
        owned(&[
            (0, "M0+"),
            (10, "M1+ L1+"),
            (11, "M0-"),
            (30, "M2+ V1+ L1-"),
            (31, "M1-"),
            (531, "M4+ V1-"),
            (532, "M2-"),
            (1032, "M0+ M1+ M4- L1+"),
            (1033, "M0-"),
        ])
    );
}

/// The cycles at which ALG01 and ALG02 print different rows on the same
/// stimulus (documented in docs/programs.md).
#[test]
fn alg01_and_alg02_differ_only_around_the_timer_transitions() {
    let expected: [(&str, &[usize]); 4] = [
        ("s1", &[530, 531, 1031]),
        ("s2", &[550, 551, 1051]),
        ("s1s2", &[600, 601, 1101]),
        ("sw1_held", &[530, 531, 1031, 1032]),
    ];
    for (scenario, cycles) in expected {
        let a = run(Algorithm::Alg01, &stimulus(scenario), CYCLES);
        let b = run(Algorithm::Alg02, &stimulus(scenario), CYCLES);
        let differing: Vec<usize> = (0..a.len()).filter(|&k| a[k] != b[k]).collect();
        assert_eq!(differing, cycles, "scenario {scenario}");
    }
}

//! The same grafcet written as a chart and by hand (ST/IL), driven with the
//! same stimulus through the library's `Session`; the cycles where they
//! differ are reported (and checked against what the methods predict).

use crate::support::sfc_run;

use sfc_run::library::{TraceRequest, csv_trace, repo_files, repo_text};
use sfc_run::rows;

use crate::support::rng;
use rng::Rng;

/// A stimulus with one row per cycle: each input flips with probability
/// 1/`flip` at every cycle.
fn random_stimulus(names: &[&str], cycles: usize, flip: u64, seed: u64) -> String {
    let mut rng = Rng(seed);
    let mut values = vec![false; names.len()];
    let mut s = format!("cycle,{}\n", names.join(","));
    for k in 0..cycles {
        for v in values.iter_mut() {
            if rng.next().is_multiple_of(flip) {
                *v = !*v;
            }
        }
        s.push_str(&k.to_string());
        for v in &values {
            s.push_str(if *v { ",TRUE" } else { ",FALSE" });
        }
        s.push('\n');
    }
    s
}

/// Runs a repository program against a stimulus text and returns its
/// trace rows (cells after `cycle,time`).
fn run(program: &str, stimulus: &str, cycles: usize, trace: &str) -> Vec<Vec<String>> {
    let request = TraceRequest {
        cycles: cycles as u64,
        stimulus: Some(stimulus),
        trace: Some(trace),
        changes_only: false,
    };
    let csv = csv_trace(&repo_files(&[program]), &request);
    rows(&csv).into_iter().map(|r| r[2..].to_vec()).collect()
}

/// Cycles at which the two traces differ in the given columns.
fn differences(a: &[Vec<String>], b: &[Vec<String>], cols: std::ops::Range<usize>) -> Vec<usize> {
    a.iter()
        .zip(b)
        .enumerate()
        .filter(|(_, (x, y))| x[cols.clone()] != y[cols.clone()])
        .map(|(k, _)| k)
        .collect()
}

const GRAF1_CYCLES: usize = 20_000;

#[test]
fn graf1_chart_sync_and_async() {
    let stim = random_stimulus(
        &["m", "a", "b", "c", "d"],
        GRAF1_CYCLES,
        6,
        0x9E37_79B9_7F4A_7C15,
    );
    let chart = run(
        "programs/graf1_sfc.sfc",
        &stim,
        GRAF1_CYCLES,
        "S10,S20,S30,X0.X,X1.X,X2.X,X3.X,X4.X",
    );
    let sync = run(
        "programs/graf1_sync.st",
        &stim,
        GRAF1_CYCLES,
        "S10,S20,S30,X0,X1,X2,X3,X4",
    );
    let asyn = run(
        "programs/graf1_async.st",
        &stim,
        GRAF1_CYCLES,
        "S10,S20,S30,X0,X1,X2,X3,X4",
    );
    // The chart really cycles under this stimulus (each step many times).
    let activations = |col: usize| {
        chart
            .windows(2)
            .filter(|w| w[0][col] == "FALSE" && w[1][col] == "TRUE")
            .count()
    };
    for col in 3..8 {
        assert!(
            activations(col) > 50,
            "step column {col}: {}",
            activations(col)
        );
    }
    // Synchronous method: same outputs and same step bits at every cycle.
    let sync_out = differences(&chart, &sync, 0..3);
    let sync_steps = differences(&chart, &sync, 3..8);
    eprintln!(
        "GRAF_1, {GRAF1_CYCLES} cycles: chart vs synchronous: {} output / {} step differences",
        sync_out.len(),
        sync_steps.len()
    );
    assert!(
        sync_out.is_empty(),
        "first differing cycles: {:?}",
        &sync_out[..sync_out.len().min(10)]
    );
    assert!(
        sync_steps.is_empty(),
        "first differing cycles: {:?}",
        &sync_steps[..sync_steps.len().min(10)]
    );
    // Asynchronous method: it differs. Every divergence (a cycle where the
    // two agreed on the steps in the previous cycle and disagree now) has
    // one of the two causes the method predicts: the "answer" comes one
    // scan after the "call", so two step bits are set at once; or a line
    // sees a bit set by a line above it in the same scan, so the async
    // version goes through two transitions in one scan. After a divergence
    // the two can stay out of phase for a long time (they then wait for
    // different receptivities), which is why many cycles differ.
    let async_out = differences(&chart, &asyn, 0..3);
    let async_steps = differences(&chart, &asyn, 3..8);
    let active = |row: &Vec<String>| row[3..8].iter().filter(|v| *v == "TRUE").count();
    let step_of = |row: &Vec<String>| row[3..8].iter().position(|v| v == "TRUE");
    let (mut overlaps, mut cascades) = (0, 0);
    for &k in &async_steps {
        if k == 0 || chart[k - 1][3..8] != asyn[k - 1][3..8] {
            continue;
        }
        if active(&asyn[k]) >= 2 {
            overlaps += 1;
            continue;
        }
        let before = step_of(&chart[k - 1]).unwrap_or(0);
        let (c, a) = (
            step_of(&chart[k]).unwrap_or(0),
            step_of(&asyn[k]).unwrap_or(0),
        );
        let advance = |to: usize| (to + 5 - before) % 5;
        assert!(
            advance(a) >= 2 && advance(a) > advance(c),
            "cycle {k}: async {:?} chart {:?}",
            &asyn[k][3..8],
            &chart[k][3..8]
        );
        cascades += 1;
    }
    eprintln!(
        "GRAF_1: chart vs asynchronous: {} cycles with different outputs, {} with different steps; \
         {overlaps} divergences by overlapping steps, {cascades} by cascaded transitions; first output differences at {:?}",
        async_out.len(),
        async_steps.len(),
        &async_out[..async_out.len().min(8)]
    );
    assert!(!async_out.is_empty());
    assert!(overlaps + cascades > 0);
    // The chart always has exactly one active step (single sequence).
    assert!(chart.iter().all(|r| active(r) == 1));
}

#[test]
fn transfer_station_chart_and_b_ft_il() {
    let cycles = 20_000;
    let stim = random_stimulus(
        &["I0_0", "I0_1", "I0_2", "I0_3", "I0_4"],
        cycles,
        5,
        0x2545_F491_4F6C_DD1D,
    );
    let chart = run(
        "programs/transfer_station.sfc",
        &stim,
        cycles,
        "O0_0,O0_1,O0_2,O0_3,X1.X,X2.X,X3.X,X4.X",
    );
    let il = run(
        "programs/transfer_station.il",
        &stim,
        cycles,
        "O0_0,O0_1,O0_2,O0_3,B_X1,B_X2,B_X3,B_X4",
    );
    let steps = |t: &[Vec<String>], col: usize| t.iter().filter(|r| r[col] == "TRUE").count();
    for col in 4..8 {
        assert!(steps(&chart, col) > 100, "step column {col} rarely active");
    }
    let d = differences(&chart, &il, 0..8);
    eprintln!(
        "transfer station, {cycles} cycles: {} differing cycles",
        d.len()
    );
    assert!(
        d.is_empty(),
        "first differing cycles: {:?}",
        &d[..d.len().min(10)]
    );
}

/// ALG01: the chart against the IL on the four ALG01 scenarios. The
/// outputs V1, V2, L1 agree at every cycle; the step bits differ exactly
/// where the IL updates them one after the other (hand-derived):
/// - the IL's previous step bit is cleared one scan after the next one is
///   set (its rung comes first): cycle 10 (M0), X (M1), X + 500 (M2 or M3);
/// - the IL's T2 output is copied after the step 0 rung, so step 0 comes
///   back one scan later than the chart's (which reads `E4.T` directly):
///   chart E0 at X + 1000, IL M0 at X + 1001;
/// - with SW1 held, the IL activates steps 0 and 1 in the same scan
///   (X + 1001); the chart takes one call per evolution (E1 at X + 1001
///   too, but E0 was active alone at X + 1000).
#[test]
fn alg01_chart_against_il() {
    let cases: [(&str, &[usize]); 4] = [
        ("s1", &[10, 30, 530, 1030]),
        ("s2", &[10, 50, 550, 1050]),
        ("s1s2", &[10, 100, 600, 1100]),
        ("sw1_held", &[10, 30, 530, 1030, 1031]),
    ];
    for (scenario, want_steps) in cases {
        let stim = repo_text(&format!("programs/alg01_{scenario}.csv"));
        let stim = stim.as_str();
        let chart = run(
            "programs/alg01.sfc",
            stim,
            1200,
            "V1,V2,L1,E0.X,E1.X,E2.X,E3.X,E4.X",
        );
        let il = run("programs/alg01.il", stim, 1200, "V1,V2,L1,M0,M1,M2,M3,M4");
        let out = differences(&chart, &il, 0..3);
        let steps = differences(&chart, &il, 3..8);
        eprintln!("ALG01 {scenario}: output differences {out:?}, step differences {steps:?}");
        assert!(out.is_empty(), "{scenario}: outputs differ at {out:?}");
        assert_eq!(steps, want_steps, "{scenario}");
    }
}

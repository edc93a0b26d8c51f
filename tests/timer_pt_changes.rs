//! TON, TOF and TP when PT changes: before, during and after timing,
//! upwards and downwards, and PT = 0 (`docs/semantics.md` §4, "Changes of
//! PT"). The rule: PT is read while the timer times; once Q has switched at
//! the end of the delay or pulse, Q and ET stay until IN changes. The
//! native blocks are also compared with the ST reference definitions in
//! `stdlib/` over long pseudo-random runs of IN and PT.

use plcrun::{Options, Plc, parse_time_literal};

/// A program calling one `fb` instance with IN := x, PT := pt, every
/// 10 ms cycle.
fn timer_program(fb: &str) -> String {
    format!(
        "PROGRAM main
VAR_INPUT x : BOOL; pt : TIME; END_VAR
VAR_OUTPUT q : BOOL; et : TIME; END_VAR
VAR t : {fb}; END_VAR
t(IN := x, PT := pt);
q := t.Q;
et := t.ET;
END_PROGRAM
"
    )
}

/// What one cycle of a scenario sets before it runs: IN, and PT in ms.
#[derive(Clone, Copy)]
struct Inputs {
    x: bool,
    pt_ms: i64,
}

/// Runs `fb` over `inputs` (cycle k gets `inputs[k]`) and returns
/// `(Q, ET in ms)` after each cycle.
fn run(fb: &str, inputs: &[Inputs]) -> Vec<(bool, i64)> {
    let src = timer_program(fb);
    let mut plc = Plc::compile_files(&[("timer.st", src.as_str())], &Options::default()).unwrap();
    inputs
        .iter()
        .map(|i| {
            plc.write("x", if i.x { "TRUE" } else { "FALSE" }).unwrap();
            plc.write("pt", &format!("T#{}ms", i.pt_ms)).unwrap();
            plc.run_cycle().unwrap();
            let q = plc.read("q").unwrap().to_literal() == "TRUE";
            let et = parse_time_literal(&plc.read("et").unwrap().to_literal()).unwrap();
            (q, et / 1_000_000)
        })
        .collect()
}

/// A scenario of `cycles` cycles: IN is TRUE in the cycles of `on`
/// (`(from, to)`: from `from` up to, not including, `to`), PT is `pt` from cycle 0 and `later` from cycle `at`.
fn scenario(
    cycles: usize,
    on: &[(usize, usize)],
    pt: i64,
    (at, later): (usize, i64),
) -> Vec<Inputs> {
    (0..cycles)
        .map(|k| Inputs {
            x: on.iter().any(|&(from, to)| (from..to).contains(&k)),
            pt_ms: if k >= at { later } else { pt },
        })
        .collect()
}

/// The cycles where Q is TRUE.
fn q_cycles(trace: &[(bool, i64)]) -> Vec<usize> {
    trace
        .iter()
        .enumerate()
        .filter(|(_, (q, _))| *q)
        .map(|(k, _)| k)
        .collect()
}

fn ets(trace: &[(bool, i64)]) -> Vec<i64> {
    trace.iter().map(|(_, et)| *et).collect()
}

// ---- TON ------------------------------------------------------------------

#[test]
fn ton_pt_changed_before_timing_is_the_new_delay() {
    // IN from cycle 5; PT 50 ms, 100 ms from cycle 2.
    for (later, first_q) in [(100, 15), (20, 7)] {
        let t = run("TON", &scenario(25, &[(5, 25)], 50, (2, later)));
        assert_eq!(
            q_cycles(&t),
            (first_q..25).collect::<Vec<_>>(),
            "PT {later}"
        );
    }
}

#[test]
fn ton_pt_raised_while_timing_lengthens_the_delay() {
    let t = run("TON", &scenario(15, &[(0, 15)], 50, (3, 100)));
    assert_eq!(q_cycles(&t), (10..15).collect::<Vec<_>>());
    assert_eq!(ets(&t)[..11], [0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100]);
}

#[test]
fn ton_pt_lowered_while_timing_shortens_it_or_ends_it_at_once() {
    // Above the elapsed time: Q when ET reaches the new PT.
    let t = run("TON", &scenario(12, &[(0, 12)], 100, (3, 80)));
    assert_eq!(q_cycles(&t), (8..12).collect::<Vec<_>>());
    // Below it: Q in the cycle PT drops, ET is the new PT.
    let t = run("TON", &scenario(12, &[(0, 12)], 100, (6, 30)));
    assert_eq!(q_cycles(&t), (6..12).collect::<Vec<_>>());
    assert_eq!(ets(&t)[5..], [50, 30, 30, 30, 30, 30, 30]);
}

#[test]
fn ton_pt_changed_after_q_rose_changes_nothing_until_in_falls() {
    for later in [200, 20, 0] {
        // Q from cycle 5; PT changes at 7; IN falls at 12 and rises at 14.
        let t = run("TON", &scenario(30, &[(0, 12), (14, 30)], 50, (7, later)));
        let mut expected: Vec<usize> = (5..12).collect();
        // The next rise times with the new PT.
        expected.extend((14 + later as usize / 10).min(30)..30);
        assert_eq!(q_cycles(&t), expected, "PT {later}");
        assert_eq!(
            ets(&t)[5..12],
            [50; 7],
            "ET stays where Q rose (PT {later})"
        );
        assert_eq!(ets(&t)[12..14], [0, 0]);
    }
}

#[test]
fn ton_pt_changed_while_in_is_false_changes_nothing() {
    let t = run("TON", &scenario(12, &[(0, 6)], 30, (8, 500)));
    assert_eq!(q_cycles(&t), vec![3, 4, 5]);
    assert_eq!(ets(&t)[6..], [0; 6]);
}

#[test]
fn ton_with_pt_zero_is_on_with_in() {
    let t = run("TON", &scenario(10, &[(2, 6), (8, 10)], 0, (4, 100)));
    // On at once with IN; PT raised at 4 does not switch it off; the rise at
    // 8 times the new 100 ms.
    assert_eq!(q_cycles(&t), vec![2, 3, 4, 5]);
    assert_eq!(ets(&t), [0, 0, 0, 0, 0, 0, 0, 0, 0, 10]);
}

// ---- TOF ------------------------------------------------------------------

#[test]
fn tof_pt_changed_before_the_fall_is_the_new_delay() {
    // IN in 0..3; PT 50 ms, 100 ms from cycle 1: Q falls at 3 + 10.
    let t = run("TOF", &scenario(20, &[(0, 3)], 50, (1, 100)));
    assert_eq!(q_cycles(&t), (0..13).collect::<Vec<_>>());
}

#[test]
fn tof_pt_raised_while_timing_lengthens_the_delay() {
    let t = run("TOF", &scenario(20, &[(0, 3)], 50, (5, 100)));
    assert_eq!(q_cycles(&t), (0..13).collect::<Vec<_>>());
    assert_eq!(ets(&t)[12..], [90, 100, 100, 100, 100, 100, 100, 100]);
}

#[test]
fn tof_pt_lowered_while_timing_shortens_it_or_ends_it_at_once() {
    let t = run("TOF", &scenario(20, &[(0, 3)], 100, (5, 60)));
    assert_eq!(q_cycles(&t), (0..9).collect::<Vec<_>>());
    // Elapsed 40 ms at cycle 7 when PT drops to 20: Q falls there, ET 20.
    let t = run("TOF", &scenario(20, &[(0, 3)], 100, (7, 20)));
    assert_eq!(q_cycles(&t), (0..7).collect::<Vec<_>>());
    assert_eq!(ets(&t)[6..9], [30, 20, 20]);
}

#[test]
fn tof_pt_changed_after_q_fell_does_not_switch_it_on_again() {
    // The case of issue #13: Q fell at 8 (IN FALSE since 3); PT raised at 10.
    for later in [200, 20, 0] {
        let t = run("TOF", &scenario(30, &[(0, 3), (20, 22)], 50, (10, later)));
        let mut expected: Vec<usize> = (0..8).collect();
        // The next fall, at 22, times with the new PT.
        expected.extend(20..(22 + later as usize / 10).min(30));
        assert_eq!(q_cycles(&t), expected, "PT {later}");
        assert_eq!(
            ets(&t)[8..20],
            [50; 12],
            "ET stays at the delay that ran (PT {later})"
        );
    }
}

#[test]
fn tof_pt_changed_before_in_ever_was_true_changes_nothing() {
    let t = run("TOF", &scenario(10, &[], 0, (3, 100)));
    assert_eq!(q_cycles(&t), Vec::<usize>::new());
    assert_eq!(ets(&t), [0; 10]);
}

#[test]
fn tof_with_pt_zero_follows_in() {
    let t = run("TOF", &scenario(12, &[(2, 5), (8, 10)], 0, (6, 100)));
    // Off in the cycle IN falls; raising PT at 6 does not switch it on; the
    // fall at 10 times the new 100 ms.
    assert_eq!(q_cycles(&t), vec![2, 3, 4, 8, 9, 10, 11]);
    assert_eq!(ets(&t)[5..8], [0, 0, 0]);
}

// ---- TP -------------------------------------------------------------------

#[test]
fn tp_pt_changed_before_the_pulse_is_the_new_length() {
    let t = run("TP", &scenario(20, &[(4, 20)], 50, (2, 80)));
    assert_eq!(q_cycles(&t), (4..12).collect::<Vec<_>>());
}

#[test]
fn tp_pt_raised_during_the_pulse_lengthens_it() {
    let t = run("TP", &scenario(20, &[(0, 2)], 50, (3, 100)));
    assert_eq!(q_cycles(&t), (0..10).collect::<Vec<_>>());
    assert_eq!(ets(&t)[9..12], [90, 0, 0], "ET back to 0: IN is FALSE");
}

#[test]
fn tp_pt_lowered_during_the_pulse_shortens_it_or_ends_it_at_once() {
    let t = run("TP", &scenario(20, &[(0, 20)], 100, (3, 60)));
    assert_eq!(q_cycles(&t), (0..6).collect::<Vec<_>>());
    let t = run("TP", &scenario(20, &[(0, 20)], 100, (5, 20)));
    assert_eq!(q_cycles(&t), (0..5).collect::<Vec<_>>());
    assert_eq!(ets(&t)[4..8], [40, 20, 20, 20]);
}

#[test]
fn tp_pt_changed_after_the_pulse_starts_no_new_one() {
    for later in [300, 10, 0] {
        // Pulse 0..5 with IN held to 15; PT changes at 8; IN rises again at 18.
        let t = run("TP", &scenario(40, &[(0, 15), (18, 40)], 50, (8, later)));
        let mut expected: Vec<usize> = (0..5).collect();
        expected.extend(18..(18 + later as usize / 10).min(40));
        assert_eq!(q_cycles(&t), expected, "PT {later}");
        assert_eq!(
            ets(&t)[5..15],
            [50; 10],
            "ET stays while IN is TRUE (PT {later})"
        );
        assert_eq!(ets(&t)[15..18], [0; 3]);
    }
}

#[test]
fn tp_with_pt_zero_gives_no_pulse() {
    let t = run("TP", &scenario(12, &[(2, 8)], 0, (5, 100)));
    assert_eq!(q_cycles(&t), Vec::<usize>::new());
    assert_eq!(ets(&t), [0; 12]);
}

// ---- native blocks against the ST reference definitions -------------------

/// A small deterministic generator (no dependency, same runs everywhere).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self, below: u64) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) % below
    }
}

#[test]
fn native_timers_agree_with_the_reference_definitions_when_pt_changes() {
    let reference: String = ["stdlib/ton.st", "stdlib/tof.st", "stdlib/tp.st"]
        .iter()
        .map(|p| {
            std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(p))
                .unwrap()
        })
        .collect();
    let program = "PROGRAM main
VAR_INPUT x : BOOL; pt : TIME; END_VAR
VAR
  a : TON; b : TOF; c : TP; ra : REF_TON; rb : REF_TOF; rc : REF_TP;
END_VAR
VAR_OUTPUT same : BOOL; END_VAR
a(IN := x, PT := pt); b(IN := x, PT := pt); c(IN := x, PT := pt);
ra(IN := x, PT := pt); rb(IN := x, PT := pt); rc(IN := x, PT := pt);
same := a.Q = ra.Q AND a.ET = ra.ET AND b.Q = rb.Q AND b.ET = rb.ET
        AND c.Q = rc.Q AND c.ET = rc.ET;
END_PROGRAM
";
    let files = [("ref.st", reference.as_str()), ("main.st", program)];
    for seed in 1..=4u64 {
        let mut plc = Plc::compile_files(&files, &Options::default()).unwrap();
        let mut rng = Lcg(seed);
        let (mut x, mut pt) = (false, 50);
        for cycle in 0..3_000 {
            // IN toggles now and then; PT jumps among a few values, 0 included.
            if rng.next(6) == 0 {
                x = !x;
            }
            if rng.next(9) == 0 {
                pt = [0, 10, 30, 50, 80, 200][rng.next(6) as usize];
            }
            plc.write("x", if x { "TRUE" } else { "FALSE" }).unwrap();
            plc.write("pt", &format!("T#{pt}ms")).unwrap();
            plc.run_cycle().unwrap();
            assert_eq!(
                plc.read("same").unwrap().to_literal(),
                "TRUE",
                "seed {seed}, cycle {cycle}"
            );
        }
    }
}

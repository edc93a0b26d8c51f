//! The native benchmark references reproduce the checksums of the benchmark
//! programs (`benches/programs/*.st`), and the generated benchmarks (bench a,
//! bench c unrolled) have exactly the regular structure the references loop
//! over.
//!
//! Every README cycle count up to 100 000 runs by default (about 2 s in a
//! debug build); the three longest (2 000 000 for a, 100 000 for b, 150 000
//! for d) are ignored, run them with
//! `cargo test --release --test suite native_reference:: -- --include-ignored`.

#[path = "../benches/native/mod.rs"]
mod native;

#[path = "../benches/generate.rs"]
mod generate;
// benches/generate.rs takes its random numbers from here.
use crate::support::rng;

use native::{
    BenchA, BenchB, BenchC, BenchD, BenchEmpty, Ctu, RTrig, Reference, Ton, cycle_time_ns, run,
};

/// Asserts that reference `R` gives `expected` after `cycles` cycles.
fn check<R: Reference>(cycles: u64, expected: i32) {
    let got = run::<R>(cycles);
    assert_eq!(got, expected, "bench {} after {cycles} cycles", R::NAME);
}

/// Like [`check`] with a tolerance for REAL rounding.
fn check_near<R: Reference>(cycles: u64, expected: i32, tolerance: i32) {
    let got = run::<R>(cycles);
    assert!(
        (got - expected).abs() <= tolerance,
        "bench {} after {cycles} cycles: {got}, expected {expected} ± {tolerance}",
        R::NAME
    );
}

// Standard FBs (semantics.md §4).

#[test]
fn r_trig_pulses_on_true_first_call_and_on_rising_edges() {
    let mut t = RTrig::default();
    let seen: Vec<bool> = [true, true, false, true, false, false]
        .iter()
        .map(|&clk| {
            t.call(clk);
            t.q
        })
        .collect();
    assert_eq!(seen, [true, false, false, true, false, false]);
}

#[test]
fn ctu_counts_rising_edges_resets_and_saturates() {
    let mut c = Ctu::default();
    for cu in [true, true, false, true, false, true] {
        c.call(cu, false, 3);
    }
    assert_eq!(c.cv, 3);
    assert!(c.q);
    // R wins over a rising CU, and the edge memory still follows CU.
    c.call(false, false, 3);
    c.call(true, true, 3);
    assert_eq!(c.cv, 0);
    assert!(!c.q);
    c.call(true, false, 3);
    assert_eq!(c.cv, 0, "CU stayed TRUE: no new edge");
    c.cv = i16::MAX;
    c.call(false, false, 3);
    c.call(true, false, 3);
    assert_eq!(c.cv, i16::MAX);
}

#[test]
fn ton_q_is_first_true_500_cycles_after_the_rise_with_pt_5s() {
    let mut t = Ton::default();
    let pt = 5_000_000_000;
    t.call(false, pt, cycle_time_ns(0));
    for k in 1..=500u64 {
        t.call(true, pt, cycle_time_ns(k));
        assert_eq!(t.q, k == 501, "cycle {k}");
    }
    t.call(true, pt, cycle_time_ns(501));
    assert!(t.q);
    assert_eq!(t.et, pt);
    t.call(false, pt, cycle_time_ns(502));
    assert!(!t.q);
    assert_eq!(t.et, 0);
}

#[test]
fn ton_with_zero_pt_is_true_in_the_same_call() {
    let mut t = Ton::default();
    t.call(true, 0, cycle_time_ns(7));
    assert!(t.q);
}

#[test]
fn a_bool_logic_1000() {
    check::<BenchA>(1000, 310_000);
}

#[test]
fn a_bool_logic_100_000() {
    check::<BenchA>(100_000, 32_083_051);
}

#[test]
#[ignore = "long: run in release with --include-ignored"]
fn a_bool_logic_2_000_000() {
    check::<BenchA>(2_000_000, 642_283_000);
}

#[test]
fn b_int_sieve_1000() {
    check::<BenchB>(1000, 122_909_001);
}

#[test]
fn b_int_sieve_2000() {
    check::<BenchB>(2000, 122_935_960);
}

#[test]
#[ignore = "long: run in release with --include-ignored"]
fn b_int_sieve_100_000() {
    check::<BenchB>(100_000, 122_957_102);
}

#[test]
fn c_fb_1000() {
    check::<BenchC>(1000, 50_281_112);
}

#[test]
fn c_fb_10_000() {
    check::<BenchC>(10_000, 263_227);
}

#[test]
fn c_fb_100_000() {
    check::<BenchC>(100_000, 277_825);
}

#[test]
fn c_fb_timers_run() {
    // ton_q is excluded from the checksum; it must still be live: a counter
    // above 25 for two consecutive cycles has its T#10ms timer done.
    let mut c = BenchC::new();
    let mut seen = 0;
    for k in 0..200 {
        c.cycle(native::cycle_time_ns(k));
        assert!((0..=1000).contains(&c.ton_q()));
        seen += c.ton_q();
    }
    assert!(seen > 0);
}

#[test]
fn d_real_math_1000() {
    check_near::<BenchD>(1000, 466_426, 1);
}

#[test]
fn d_real_math_8000() {
    check_near::<BenchD>(8000, 486_464, 1);
}

#[test]
#[ignore = "long: run in release with --include-ignored"]
fn d_real_math_150_000() {
    check_near::<BenchD>(150_000, 486_813, 1);
}

#[test]
fn empty_counts_cycles() {
    check::<BenchEmpty>(1000, 1000);
}

/// Statement lines of a program body (after `END_VAR`), trimmed, without
/// blank lines and comment-only lines.
fn body_lines(src: &str) -> Vec<&str> {
    let start = src.find("END_VAR").expect("END_VAR") + "END_VAR".len();
    src[start..]
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && (!l.starts_with("(*") || !l.ends_with("*)")))
        .collect()
}

#[test]
fn a_bool_logic_source_has_the_structure_of_the_reference() {
    use native::a_bool_logic::*;
    let src = include_str!("../benches/programs/bench_a_bool_logic.st");

    // Declarations: the first step of each chain starts TRUE, 200 TONs.
    let initially_true: Vec<String> = (0..STEPS)
        .filter(|k| k % CHAIN_LEN == 0)
        .map(|k| format!("X{k:03} : BOOL := TRUE;"))
        .collect();
    let declared_true: Vec<&str> = src
        .lines()
        .map(str::trim)
        .filter(|l| l.ends_with(":= TRUE;"))
        .collect();
    assert_eq!(declared_true, initially_true);
    assert_eq!(src.matches(" : TON;").count(), STEPS);
    assert!(src.contains(&format!("lfsr : WORD := 16#{LFSR_SEED:04X};")));

    // Statements, rendered from the reference's tables.
    let mut want = vec![
        "cycles := cycles + 1;".to_string(),
        "IF (lfsr AND 16#0001) <> 0 THEN".into(),
        format!("lfsr := SHR(lfsr, 1) XOR 16#{LFSR_TAPS:04X};"),
        "ELSE".into(),
        "lfsr := SHR(lfsr, 1);".into(),
        "END_IF;".into(),
    ];
    for bit in 0..16 {
        want.push(format!(
            "in{bit:02} := (lfsr AND 16#{:04X}) <> 0;",
            1u32 << bit
        ));
    }
    for k in 0..STEPS {
        let [a, b, c, d] = TRANSITION_INPUTS[k % 16];
        want.push(format!(
            "C{k:03} := X{k:03} AND ((in{a:02} XOR in{b:02}) OR (in{c:02} AND NOT in{d:02}));"
        ));
    }
    for k in 0..STEPS {
        let p = predecessor(k);
        want.push(format!("X{k:03} := (X{k:03} AND NOT C{k:03}) OR C{p:03};"));
    }
    for k in 0..STEPS {
        want.push(format!(
            "T{k:03}(IN := X{k:03}, PT := T#{}ms);",
            TIMER_PT_NS / 1_000_000
        ));
        want.push(format!("Y{k:03} := X{k:03} AND NOT T{k:03}.Q;"));
    }
    for chain in 0..CHAINS {
        let last = chain * CHAIN_LEN + CHAIN_LEN - 1;
        want.push(format!("IF C{last:03} THEN"));
        want.push("wraps := wraps + 1;".into());
        want.push("END_IF;".into());
    }
    want.push("pattern := 0;".into());
    let mut weight = 1;
    for chain in 0..CHAINS {
        for offset in 0..PATTERN_STEPS_PER_CHAIN {
            let k = chain * CHAIN_LEN + offset;
            want.push(format!(
                "IF X{k:03} THEN pattern := pattern + {weight}; END_IF;"
            ));
            weight += 1;
        }
    }
    want.push("checksum := wraps * 1000 + pattern;".into());
    want.push("END_PROGRAM".into());

    let got = body_lines(src);
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        assert_eq!(g, w, "statement line {i}");
    }
    assert_eq!(got.len(), want.len());
}

#[test]
fn c_fb_unrolled_source_is_the_array_program_unrolled() {
    use native::c_fb::{INSTANCES, TIMER_PT_NS};
    let src = include_str!("../benches/programs/bench_c_fb_unrolled.st");
    let decls = (0..INSTANCES)
        .filter(|i| {
            src.contains(&format!(
                "rt{i:03} : R_TRIG; cu{i:03} : CTU; tm{i:03} : TON;"
            ))
        })
        .count();
    assert_eq!(decls, INSTANCES);

    let pt = format!("T#{}ms", TIMER_PT_NS / 1_000_000);
    let mut want = vec![
        "cycles := cycles + 1;".to_string(),
        "sum_cv := 0;".into(),
        "ton_q := 0;".into(),
    ];
    for i in 0..INSTANCES {
        want.push(format!("rt{i:03}(CLK := ((cycles + {i}) MOD 4) < 2);"));
        want.push(format!("IF rt{i:03}.Q THEN pulses := pulses + 1; END_IF;"));
        want.push(format!(
            "cu{i:03}(CU := rt{i:03}.Q, R := cu{i:03}.Q, PV := {});",
            50 + i % 7
        ));
        want.push(format!("tm{i:03}(IN := cu{i:03}.CV > 25, PT := {pt});"));
        want.push(format!("IF tm{i:03}.Q THEN ton_q := ton_q + 1; END_IF;"));
        want.push(format!("sum_cv := sum_cv + INT_TO_DINT(cu{i:03}.CV);"));
    }
    want.push("checksum := sum_cv + (pulses MOD 100000) * 1000;".into());
    want.push("END_PROGRAM".into());
    assert_eq!(body_lines(src), want);

    // The array variant states the same per-instance work in a FOR loop.
    let array = include_str!("../benches/programs/bench_c_fb_array.st");
    for needle in [
        "trig[i](CLK := phase < 2);",
        "cnt[i](CU := trig[i].Q, R := cnt[i].Q, PV := DINT_TO_INT(50 + (i MOD 7)));",
        &format!("tmr[i](IN := cnt[i].CV > 25, PT := {pt});"),
        "checksum := sum_cv + (pulses MOD 100000) * 1000;",
    ] {
        assert!(array.contains(needle), "{needle}");
    }
}

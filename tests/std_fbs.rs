//! The standard function blocks (docs/semantics.md §4).
//!
//! 1. Hand-derived tables: each block driven through a short scenario, the
//!    expected outputs worked out from the rules of §4 (comments give the
//!    derivation).
//! 2. Side by side: each native block and its ST reference definition
//!    (`stdlib/<fb>.st`, block `REF_<FB>`) run in one program, called with
//!    the same pseudo-random inputs (fixed-seed xorshift) for 2000 cycles;
//!    their outputs must be identical after every cycle.

use crate::support::plc;

use plc::{compile, compile_files, lit, program};
use plcrun::Plc;
use plcrun::VarRef;
use rstest::rstest;

/// Runs `cycles` cycles of `src`; before cycle `k`, writes `inputs(k)`;
/// after it, records `outputs` as literals. Returns one row per cycle.
fn simulate(
    src: &str,
    cycles: usize,
    inputs: impl Fn(usize) -> Vec<(&'static str, String)>,
    outputs: &[&str],
) -> Vec<Vec<String>> {
    let mut plc = compile(src);
    let mut rows = Vec::new();
    for k in 0..cycles {
        for (name, value) in inputs(k) {
            plc.write(name, &value)
                .unwrap_or_else(|e| panic!("write {name}: {e}"));
        }
        plc.run_cycle().expect("no fault");
        rows.push(outputs.iter().map(|o| lit(&plc, o)).collect());
    }
    rows
}

fn b(x: bool) -> String {
    if x { "TRUE" } else { "FALSE" }.to_string()
}

/// The cycles in which column `col` of `rows` equals `value`.
fn cycles_where(rows: &[Vec<String>], col: usize, value: &str) -> Vec<usize> {
    rows.iter()
        .enumerate()
        .filter(|(_, r)| r[col] == value)
        .map(|(k, _)| k)
        .collect()
}

// ---------------------------------------------------------------- edges

#[test]
fn r_trig_pulses_on_rising_edges_including_a_true_first_call() {
    let clk = [true, true, false, true, false, false, true];
    let src = program("", "t : R_TRIG; c : BOOL;", "t(CLK := c);");
    let rows = simulate(&src, clk.len(), |k| vec![("c", b(clk[k]))], &["t.Q"]);
    let q: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    // M starts FALSE, so the TRUE first call pulses.
    assert_eq!(
        q,
        ["TRUE", "FALSE", "FALSE", "TRUE", "FALSE", "FALSE", "TRUE"]
    );
}

#[test]
fn f_trig_pulses_on_falling_edges_but_not_at_the_first_call() {
    let clk = [false, false, true, false, false, true, true, false];
    let src = program("", "t : F_TRIG; c : BOOL;", "t(CLK := c);");
    let rows = simulate(&src, clk.len(), |k| vec![("c", b(clk[k]))], &["t.Q"]);
    let q: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    // Q := NOT CLK AND NOT M; M := NOT CLK; M starts TRUE.
    assert_eq!(
        q,
        [
            "FALSE", "FALSE", "FALSE", "TRUE", "FALSE", "FALSE", "FALSE", "TRUE"
        ]
    );
}

// ---------------------------------------------------------------- bistables

#[rstest]
#[case("sr(S1 := s, R := r);")]
#[case("sr(SET1 := s, RESET := r);")]
fn sr_is_set_dominant(#[case] call: &str) {
    // Q1 := S1 OR (NOT R AND Q1)
    let seq = [
        (false, false, "FALSE"),
        (true, false, "TRUE"),
        (false, false, "TRUE"),
        (false, true, "FALSE"),
        (true, true, "TRUE"),
        (false, false, "TRUE"),
        (false, true, "FALSE"),
    ];
    let src = program("", "sr : SR; s, r : BOOL;", call);
    let rows = simulate(
        &src,
        seq.len(),
        |k| vec![("s", b(seq[k].0)), ("r", b(seq[k].1))],
        &["sr.Q1"],
    );
    for (k, (row, exp)) in rows.iter().zip(seq).enumerate() {
        assert_eq!(row[0], exp.2, "cycle {k}");
    }
}

#[rstest]
#[case("rs(S := s, R1 := r);")]
#[case("rs(SET := s, RESET1 := r);")]
fn rs_is_reset_dominant(#[case] call: &str) {
    // Q1 := NOT R1 AND (S OR Q1)
    let seq = [
        (false, false, "FALSE"),
        (true, false, "TRUE"),
        (false, false, "TRUE"),
        (false, true, "FALSE"),
        (true, true, "FALSE"),
        (true, false, "TRUE"),
        (true, true, "FALSE"),
    ];
    let src = program("", "rs : RS; s, r : BOOL;", call);
    let rows = simulate(
        &src,
        seq.len(),
        |k| vec![("s", b(seq[k].0)), ("r", b(seq[k].1))],
        &["rs.Q1"],
    );
    for (k, (row, exp)) in rows.iter().zip(seq).enumerate() {
        assert_eq!(row[0], exp.2, "cycle {k}");
    }
}

// ---------------------------------------------------------------- counters

#[rstest]
#[case("c(CU := cu, R := r, PV := 3);")]
#[case("c(CU := cu, RESET := r, PV := 3);")]
fn ctu_counts_rising_edges_and_resets(#[case] call: &str) {
    // cu: rises at 0, 3, 5, 7, 10 (held TRUE at 1: no count)
    let cu = [
        true, true, false, true, false, true, false, true, false, false, true,
    ];
    let r = [
        false, false, false, false, false, false, false, false, true, false, false,
    ];
    let src = program("", "c : CTU; cu, r : BOOL;", call);
    let rows = simulate(
        &src,
        cu.len(),
        |k| vec![("cu", b(cu[k])), ("r", b(r[k]))],
        &["c.CV", "c.Q"],
    );
    let cv: Vec<&str> = rows.iter().map(|x| x[0].as_str()).collect();
    // 1 1 1 2 2 3 3 4 | reset 0 0 | 1
    assert_eq!(cv, ["1", "1", "1", "2", "2", "3", "3", "4", "0", "0", "1"]);
    assert_eq!(cycles_where(&rows, 1, "TRUE"), [5, 6, 7]); // CV >= 3
}

#[test]
fn ctu_reset_wins_over_a_rising_edge_and_the_edge_is_still_remembered() {
    let cu = [true, true, false, true];
    let r = [true, false, false, false];
    let src = program(
        "",
        "c : CTU; cu, r : BOOL;",
        "c(CU := cu, R := r, PV := 1);",
    );
    let rows = simulate(
        &src,
        cu.len(),
        |k| vec![("cu", b(cu[k])), ("r", b(r[k]))],
        &["c.CV"],
    );
    // cycle 0: R -> 0 (the rise of CU is consumed); 1: CU still TRUE, no
    // edge -> 0; 3: new rise -> 1
    let cv: Vec<&str> = rows.iter().map(|x| x[0].as_str()).collect();
    assert_eq!(cv, ["0", "0", "0", "1"]);
}

#[rstest]
#[case("CTU", "32766", "32767")]
#[case("CTU_DINT", "2147483646", "2147483647")]
#[case("CTU_LINT", "9223372036854775806", "9223372036854775807")]
#[case("CTU_UDINT", "4294967294", "4294967295")]
#[case("CTU_ULINT", "18446744073709551614", "18446744073709551615")]
fn ctu_stops_at_the_largest_value_of_its_type(
    #[case] fb: &str,
    #[case] start: &str,
    #[case] max: &str,
) {
    let src = program(
        "",
        &format!("c : {fb}; cu : BOOL;"),
        "c(CU := cu, PV := 5);",
    );
    let mut plc = compile(&src);
    plc.write("c.CV", start).unwrap();
    let mut seen = Vec::new();
    for k in 0..6 {
        plc.write("cu", if k % 2 == 0 { "TRUE" } else { "FALSE" })
            .unwrap();
        plc.run_cycle().unwrap();
        seen.push(lit(&plc, "c.CV"));
    }
    // rises at 0, 2, 4: start + 1 = max, then no further count
    assert_eq!(seen, [max, max, max, max, max, max]);
    assert_eq!(lit(&plc, "c.Q"), "TRUE");
}

#[rstest]
#[case("CTD", "-32767", "-32768")]
#[case("CTD_DINT", "-2147483647", "-2147483648")]
#[case("CTD_LINT", "-9223372036854775807", "-9223372036854775808")]
#[case("CTD_UDINT", "1", "0")]
#[case("CTD_ULINT", "1", "0")]
fn ctd_stops_at_the_smallest_value_of_its_type(
    #[case] fb: &str,
    #[case] start: &str,
    #[case] min: &str,
) {
    let src = program(
        "",
        &format!("c : {fb}; cd : BOOL;"),
        "c(CD := cd, PV := 5);",
    );
    let mut plc = compile(&src);
    plc.write("c.CV", start).unwrap();
    let mut seen = Vec::new();
    for k in 0..6 {
        plc.write("cd", if k % 2 == 0 { "TRUE" } else { "FALSE" })
            .unwrap();
        plc.run_cycle().unwrap();
        seen.push(lit(&plc, "c.CV"));
    }
    assert_eq!(seen, [min, min, min, min, min, min]);
    assert_eq!(lit(&plc, "c.Q"), "TRUE"); // CV <= 0
}

#[rstest]
#[case("c(CD := cd, LD := ld, PV := 2);")]
#[case("c(CD := cd, LOAD := ld, PV := 2);")]
fn ctd_loads_and_counts_down(#[case] call: &str) {
    // LD at 0 loads PV = 2; CD rises at 1, 3, 5
    let cd = [false, true, false, true, false, true, false];
    let ld = [true, false, false, false, false, false, true];
    let src = program("", "c : CTD; cd, ld : BOOL;", call);
    let rows = simulate(
        &src,
        cd.len(),
        |k| vec![("cd", b(cd[k])), ("ld", b(ld[k]))],
        &["c.CV", "c.Q"],
    );
    let cv: Vec<&str> = rows.iter().map(|x| x[0].as_str()).collect();
    assert_eq!(cv, ["2", "1", "1", "0", "0", "-1", "2"]);
    assert_eq!(cycles_where(&rows, 1, "TRUE"), [3, 4, 5]);
}

#[rstest]
#[case("c(CU := cu, CD := cd, R := r, LD := ld, PV := 2);")]
#[case("c(CU := cu, CD := cd, RESET := r, LOAD := ld, PV := 2);")]
fn ctud_counts_both_ways_and_ignores_simultaneous_edges(#[case] call: &str) {
    // (cu, cd, r, ld)
    let seq = [
        (true, false, false, false),  // 0: up -> 1
        (false, false, false, false), // 1
        (true, true, false, false),   // 2: both rise -> no change (1)
        (false, false, false, false), // 3
        (false, true, false, false),  // 4: down -> 0
        (false, false, false, false), // 5
        (false, true, false, false),  // 6: down -> -1
        (true, false, false, true),   // 7: LD -> PV = 2 (the CU rise is lost)
        (false, false, false, false), // 8
        (true, false, true, true),    // 9: R wins over LD -> 0
        (false, false, false, false), // 10
        (true, false, false, false),  // 11: up -> 1
    ];
    let cv = ["1", "1", "1", "1", "0", "0", "-1", "2", "2", "0", "0", "1"];
    let src = program("", "c : CTUD; cu, cd, r, ld : BOOL;", call);
    let rows = simulate(
        &src,
        seq.len(),
        |k| {
            let (cu, cd, r, ld) = seq[k];
            vec![("cu", b(cu)), ("cd", b(cd)), ("r", b(r)), ("ld", b(ld))]
        },
        &["c.CV", "c.QU", "c.QD"],
    );
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row[0], cv[k], "CV at cycle {k}");
        let v: i32 = cv[k].parse().unwrap();
        assert_eq!(row[1], b(v >= 2), "QU at cycle {k}");
        assert_eq!(row[2], b(v <= 0), "QD at cycle {k}");
    }
}

// ---------------------------------------------------------------- timers

fn timer_rows(
    fb: &str,
    pt: &str,
    input: impl Fn(usize) -> bool,
    cycles: usize,
) -> Vec<Vec<String>> {
    let src = program(
        "",
        &format!("t : {fb}; x : BOOL;"),
        &format!("t(IN := x, PT := {pt});"),
    );
    simulate(&src, cycles, |k| vec![("x", b(input(k)))], &["t.Q", "t.ET"])
}

#[test]
fn ton_delays_by_exactly_pt() {
    // IN TRUE from 30 to 699; again 710..719 (shorter than PT).
    let rows = timer_rows(
        "TON",
        "T#5s",
        |k| (30..700).contains(&k) || (710..720).contains(&k),
        760,
    );
    // The call in cycle 30 sees IN rise (start = 300 ms); Q is first TRUE
    // 500 cycles later, at cycle 530 (ET = 5 s), and falls with IN at 700.
    assert_eq!(
        cycles_where(&rows, 0, "TRUE"),
        (530..700).collect::<Vec<_>>()
    );
    assert_eq!(rows[29][1], "T#0s");
    assert_eq!(rows[30][1], "T#0s");
    assert_eq!(rows[31][1], "T#10ms");
    assert_eq!(rows[280][1], "T#2s500ms");
    assert_eq!(rows[529][1], "T#4s990ms");
    assert_eq!(rows[530][1], "T#5s");
    assert_eq!(rows[699][1], "T#5s"); // ET stays at PT
    assert_eq!(rows[700][1], "T#0s");
    assert_eq!(rows[719][1], "T#90ms");
    assert_eq!(rows[720][1], "T#0s");
}

#[test]
fn ton_with_zero_pt_and_true_first_call() {
    let rows = timer_rows("TON", "T#0s", |k| k >= 3, 6);
    // PT = 0: Q TRUE in the call that sees IN rise
    assert_eq!(cycles_where(&rows, 0, "TRUE"), [3, 4, 5]);
    let rows = timer_rows("TON", "T#50ms", |_| true, 8);
    // IN TRUE at the first call starts the timer at cycle 0: Q at cycle 5
    assert_eq!(cycles_where(&rows, 0, "TRUE"), [5, 6, 7]);
    assert_eq!(rows[2][1], "T#20ms");
}

#[test]
fn rtc_runs_from_its_preset_while_in_is_true() {
    // IN TRUE in cycles 2..=251 and from 300; the 10 ms clock.
    let src = program(
        "",
        "c : RTC; x : BOOL; p : DT := DT#2024-02-28-23:59:59;",
        "c(IN := x, PDT := p);",
    );
    let rows = simulate(
        &src,
        310,
        |k| vec![("x", b((2..252).contains(&k) || k >= 300))],
        &["c.Q", "c.CDT"],
    );
    assert_eq!(rows[1], ["FALSE", "DT#1970-01-01-00:00:00"]);
    // Preset in the call that sees IN rise; then the clock's time since.
    assert_eq!(rows[2], ["TRUE", "DT#2024-02-28-23:59:59"]);
    assert_eq!(rows[3][1], "DT#2024-02-28-23:59:59.01");
    // 100 cycles = 1 s later: past midnight of a leap year's February 28.
    assert_eq!(rows[102][1], "DT#2024-02-29-00:00:00");
    assert_eq!(rows[251][1], "DT#2024-02-29-00:00:01.49");
    assert_eq!(rows[252], ["FALSE", "DT#1970-01-01-00:00:00"]);
    // A new rising edge presets again: PDT, not where the clock stopped.
    assert_eq!(rows[300][1], "DT#2024-02-28-23:59:59");
}

#[test]
fn tof_holds_q_for_pt_after_in_falls() {
    // IN TRUE 0..9, FALSE 10..29, TRUE 30..39, FALSE 40..44, TRUE 45..49, FALSE 50..
    let input = |k: usize| k < 10 || (30..40).contains(&k) || (45..50).contains(&k);
    let rows = timer_rows("TOF", "T#100ms", input, 70);
    // Falling edge at 10: start = 100 ms; Q := ET < PT stays TRUE until the
    // call at 20 (ET = 100 ms). At 40 the delay restarts but IN rises again
    // at 45 (before 100 ms): Q stays TRUE; falls 10 cycles after 50.
    let mut expected: Vec<usize> = (0..20).collect();
    expected.extend(30..60);
    assert_eq!(cycles_where(&rows, 0, "TRUE"), expected);
    assert_eq!(rows[9][1], "T#0s");
    assert_eq!(rows[10][1], "T#0s");
    assert_eq!(rows[15][1], "T#50ms");
    assert_eq!(rows[25][1], "T#100ms"); // stays at PT
    assert_eq!(rows[30][1], "T#0s");
    assert_eq!(rows[44][1], "T#40ms");
    assert_eq!(rows[45][1], "T#0s");
}

#[test]
fn tof_that_never_ran_is_off() {
    let rows = timer_rows("TOF", "T#100ms", |_| false, 3);
    for row in rows {
        assert_eq!(row, ["FALSE", "T#0s"]);
    }
}

#[test]
fn tp_pulses_for_pt_and_ignores_in_during_the_pulse() {
    // IN rises at 5, falls at 7, rises again at 9 (during the pulse), falls
    // at 12. Then IN rises at 30 and is held until 49; rises again at 60.
    let input =
        |k: usize| (5..7).contains(&k) || (9..12).contains(&k) || (30..50).contains(&k) || k >= 60;
    let rows = timer_rows("TP", "T#100ms", input, 75);
    // Pulse 1: starts at 5 (start = 50 ms), ends in the call where ET >= PT:
    // cycle 15. Pulse 2: 30..39. Pulse 3: 60..69 (IN held TRUE after it).
    let mut expected: Vec<usize> = (5..15).collect();
    expected.extend(30..40);
    expected.extend(60..70);
    assert_eq!(cycles_where(&rows, 0, "TRUE"), expected);
    assert_eq!(rows[8][1], "T#30ms"); // IN FALSE during the pulse: ET runs on
    assert_eq!(rows[14][1], "T#90ms");
    assert_eq!(rows[15][1], "T#0s"); // pulse over and IN FALSE: ET := 0
    assert_eq!(rows[40][1], "T#100ms"); // pulse over, IN still TRUE: ET holds PT
    assert_eq!(rows[49][1], "T#100ms");
    assert_eq!(rows[50][1], "T#0s");
    assert_eq!(rows[74][1], "T#100ms");
}

#[test]
fn tp_with_zero_pt_gives_no_pulse() {
    let rows = timer_rows("TP", "T#0s", |k| k % 3 == 1, 9);
    assert!(cycles_where(&rows, 0, "TRUE").is_empty());
}

#[test]
fn a_timer_that_is_not_called_does_not_change() {
    // Called in cycles 0..4 only (IN TRUE), then not called.
    let src = program(
        "",
        "t : TON; k : INT;",
        "IF k < 5 THEN t(IN := TRUE, PT := T#1s); END_IF; k := k + 1;",
    );
    let rows = simulate(&src, 20, |_| vec![], &["t.ET", "t.Q"]);
    assert_eq!(rows[4][0], "T#40ms");
    assert_eq!(rows[19], ["T#40ms", "FALSE"]);
}

// ---------------------------------------------------------------- side by side

use crate::support::rng;
use rng::Rng;

/// How to drive one kind of block.
struct Kind {
    /// Boolean inputs, each with its toggle probability in percent.
    bools: &'static [(&'static str, u64)],
    /// Non-boolean input and its candidate values (changed with 2 % chance).
    value: Option<(&'static str, &'static [&'static str])>,
    outputs: &'static [&'static str],
}

const EDGE: Kind = Kind {
    bools: &[("CLK", 30)],
    value: None,
    outputs: &["Q"],
};
const SR: Kind = Kind {
    bools: &[("S1", 25), ("R", 25)],
    value: None,
    outputs: &["Q1"],
};
const RS: Kind = Kind {
    bools: &[("S", 25), ("R1", 25)],
    value: None,
    outputs: &["Q1"],
};
const SIGNED_PV: &[&str] = &["-2", "0", "1", "3", "5", "8"];
const UNSIGNED_PV: &[&str] = &["0", "1", "3", "5", "8"];
const CTU_S: Kind = Kind {
    bools: &[("CU", 40), ("R", 3)],
    value: Some(("PV", SIGNED_PV)),
    outputs: &["Q", "CV"],
};
const CTU_U: Kind = Kind {
    value: Some(("PV", UNSIGNED_PV)),
    ..CTU_S
};
const CTD_S: Kind = Kind {
    bools: &[("CD", 40), ("LD", 3)],
    value: Some(("PV", SIGNED_PV)),
    outputs: &["Q", "CV"],
};
const CTD_U: Kind = Kind {
    value: Some(("PV", UNSIGNED_PV)),
    ..CTD_S
};
const CTUD_S: Kind = Kind {
    bools: &[("CU", 35), ("CD", 35), ("R", 2), ("LD", 3)],
    value: Some(("PV", SIGNED_PV)),
    outputs: &["QU", "QD", "CV"],
};
const CTUD_U: Kind = Kind {
    value: Some(("PV", UNSIGNED_PV)),
    ..CTUD_S
};
const TIMER: Kind = Kind {
    bools: &[("IN", 8)],
    value: Some(("PT", &["T#0s", "T#30ms", "T#50ms", "T#70ms", "T#100ms"])),
    outputs: &["Q", "ET"],
};

const RTC: Kind = Kind {
    bools: &[("IN", 15)],
    value: Some((
        "PDT",
        &[
            "DT#2024-01-31-12:00:00",
            "DT#1999-12-31-23:59:59",
            "DT#1970-01-01-00:00:00",
        ],
    )),
    outputs: &["Q", "CDT"],
};

fn kind(fb: &str) -> &'static Kind {
    let base = fb.split('_').next().unwrap();
    let unsigned = fb.ends_with("_UDINT") || fb.ends_with("_ULINT");
    match (base, unsigned) {
        ("R" | "F", _) => &EDGE,
        ("SR", _) => &SR,
        ("RS", _) => &RS,
        ("CTU", false) => &CTU_S,
        ("CTU", true) => &CTU_U,
        ("CTD", false) => &CTD_S,
        ("CTD", true) => &CTD_U,
        ("CTUD", false) => &CTUD_S,
        ("CTUD", true) => &CTUD_U,
        ("TON" | "TOF" | "TP", _) => &TIMER,
        ("RTC", _) => &RTC,
        _ => panic!("no driver for {fb}"),
    }
}

fn stdlib_file(fb: &str) -> String {
    let path = format!(
        "{}/stdlib/{}.st",
        env!("CARGO_MANIFEST_DIR"),
        fb.to_ascii_lowercase()
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[rstest]
fn native_block_matches_its_st_reference(
    #[values(
        "R_TRIG",
        "F_TRIG",
        "SR",
        "RS",
        "CTU",
        "CTD",
        "CTUD",
        "CTU_DINT",
        "CTU_LINT",
        "CTU_UDINT",
        "CTU_ULINT",
        "CTD_DINT",
        "CTD_LINT",
        "CTD_UDINT",
        "CTD_ULINT",
        "CTUD_DINT",
        "CTUD_LINT",
        "CTUD_UDINT",
        "CTUD_ULINT",
        "TON",
        "TOF",
        "TP",
        "RTC"
    )]
    fb: &str,
) {
    let k = kind(fb);
    let mut names: Vec<&str> = k.bools.iter().map(|(n, _)| *n).collect();
    if let Some((n, _)) = k.value {
        names.push(n);
    }
    // The program: one input variable per block input (`in_<pin>`), a `call`
    // flag (a block that is not called must not change), both blocks called
    // with the same arguments.
    let mut decls = format!("nat : {fb}; ref : REF_{fb}; call : BOOL := TRUE;\n");
    for (n, _) in k.bools {
        decls.push_str(&format!("in_{n} : BOOL;\n"));
    }
    if let Some((n, _)) = k.value {
        let ty = match (fb, n) {
            (_, "PT") => "TIME".to_string(),
            (_, "PDT") => "DT".to_string(),
            (f, _) if f.contains('_') => f.rsplit('_').next().unwrap().to_string(),
            _ => "INT".to_string(),
        };
        decls.push_str(&format!("in_{n} : {ty};\n"));
    }
    let args: Vec<String> = names.iter().map(|n| format!("{n} := in_{n}")).collect();
    let args = args.join(", ");
    let body = format!("IF call THEN nat({args}); ref({args}); END_IF;");
    let src = program("", &decls, &body);
    let reference = stdlib_file(fb);
    let mut plc: Plc = compile_files(&[("reference.st", &reference), ("test.st", &src)]);

    let resolve = |plc: &Plc, n: &str| -> VarRef { plc.resolve(n).unwrap() };
    let bool_refs: Vec<(VarRef, u64)> = k
        .bools
        .iter()
        .map(|(n, p)| (resolve(&plc, &format!("in_{n}")), *p))
        .collect();
    let value_ref = k.value.map(|(n, vals)| (format!("in_{n}"), vals));
    let call = resolve(&plc, "call");
    let outs: Vec<(String, VarRef, VarRef)> = k
        .outputs
        .iter()
        .map(|o| {
            (
                o.to_string(),
                resolve(&plc, &format!("nat.{o}")),
                resolve(&plc, &format!("ref.{o}")),
            )
        })
        .collect();
    let tru = plc.parse_value(&call, "TRUE").unwrap();
    let fls = plc.parse_value(&call, "FALSE").unwrap();

    // Seed from the block name so that each block gets its own sequence.
    let seed = fb.bytes().fold(0x9E37_79B9_7F4A_7C15u64, |h, c| {
        (h ^ u64::from(c)).wrapping_mul(0x100_0000_01B3)
    });
    let mut rng = Rng(seed | 1);
    let mut state: Vec<bool> = vec![false; bool_refs.len()];
    let mut changes = vec![0usize; outs.len()];
    let mut last: Vec<String> = vec![String::new(); outs.len()];
    for cycle in 0..2000 {
        for (i, (r, p)) in bool_refs.iter().enumerate() {
            if rng.chance(*p) {
                state[i] = !state[i];
            }
            plc.set(r, if state[i] { &tru } else { &fls }).unwrap();
        }
        if let Some((name, vals)) = &value_ref
            && (cycle == 0 || rng.chance(2))
        {
            let v = rng.pick(vals);
            plc.write(name, v).unwrap();
        }
        // Skip the calls in about 5 % of the cycles.
        plc.set(&call, if rng.chance(95) { &tru } else { &fls })
            .unwrap();
        plc.run_cycle()
            .unwrap_or_else(|f| panic!("{fb}: fault in cycle {cycle}: {f}"));
        for (i, (o, n, r)) in outs.iter().enumerate() {
            let native = plc.get(n).unwrap().to_literal();
            let refv = plc.get(r).unwrap().to_literal();
            assert_eq!(
                native, refv,
                "{fb}.{o} differs from REF_{fb}.{o} in cycle {cycle}"
            );
            if native != last[i] {
                changes[i] += 1;
                last[i] = native;
            }
        }
    }
    // The random inputs must actually exercise the block.
    for (i, (o, _, _)) in outs.iter().enumerate() {
        assert!(
            changes[i] > 10,
            "{fb}.{o} changed only {} times",
            changes[i]
        );
    }
}

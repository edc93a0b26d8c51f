//! The loop superinstructions (`StoreStep`, `ForScan`; docs/performance.md)
//! run a whole loop in one dispatch. They must behave exactly as the loop
//! written: same final values, same fault at the same place and cycle.
//! Each case runs a loop the compiler fuses next to its twin, the same
//! loop with one extra statement that prevents the fusion (padded so that
//! every column matches), and compares everything observable.

use crate::support::plc;
use crate::support::rng;

use plc::{compile, lit, program};
use plcrun::{Options, Plc};
use rng::Rng;
use std::time::Duration;

/// The statement that keeps the twin's loop from being fused, and the
/// blanks that take its place in the fused version.
const BREAKER: &str = "x := 0; ";
const PAD: &str = "        ";

/// Whether any block of the compiled program holds an instruction named `is`.
fn holds(plc: &Plc, is: &str) -> bool {
    plc.image()
        .instruction_count(is)
        .expect("an instruction name")
        > 0
}

/// Runs `cycles` cycles; the fault (kind, location, cycle) if one stops it.
fn outcome(plc: &mut Plc, cycles: u64) -> Option<String> {
    for _ in 0..cycles {
        if let Err(f) = plc.run_cycle() {
            return Some(format!(
                "{} at {} in cycle {}",
                f.fault.kind, f.location, f.cycle
            ));
        }
    }
    None
}

/// Compiles `fused` and `twin`, checks that only the first holds the
/// superinstruction, runs both and compares the fault and every variable
/// in `names`; returns the fault, if any.
fn same_behaviour(fused: &str, twin: &str, is: &str, names: &[String]) -> Option<String> {
    let (mut a, mut b) = (compile(fused), compile(twin));
    assert!(holds(&a, is), "not fused:\n{fused}");
    assert!(!holds(&b, is), "twin fused:\n{twin}");
    let (fa, fb) = (outcome(&mut a, 2), outcome(&mut b, 2));
    assert_eq!(fa, fb, "fault differs for\n{fused}");
    for n in names {
        assert_eq!(lit(&a, n), lit(&b, n), "{n} differs for\n{fused}");
    }
    fa
}

/// Counts how the random cases ended, so that a generator drifting towards
/// only faults (or none) fails the test instead of testing less.
#[derive(Default)]
struct Endings {
    faults: usize,
    clean: usize,
}

impl Endings {
    fn add(&mut self, fault: Option<String>) {
        match fault {
            Some(f) => {
                assert!(f.contains("out of bounds"), "{f}");
                self.faults += 1;
            }
            None => self.clean += 1,
        }
    }

    fn check(&self) {
        assert!(
            self.faults >= 30 && self.clean >= 30,
            "{} faults, {} clean",
            self.faults,
            self.clean
        );
    }
}

/// The loop superinstructions, by name.
const STORE_STEP: &str = "StoreStep";
const FOR_SCAN: &str = "ForScan";

/// An integer type, its range, and the array element names `a[lo..=hi]`.
struct Shape {
    ty: &'static str,
    min: i64,
    max: i64,
}

const SHAPES: [Shape; 3] = [
    Shape {
        ty: "SINT",
        min: -128,
        max: 127,
    },
    Shape {
        ty: "INT",
        min: -32768,
        max: 32767,
    },
    Shape {
        ty: "DINT",
        min: -2147483648,
        max: 2147483647,
    },
];

fn elements(lo: i64, hi: i64) -> Vec<String> {
    (lo..=hi).map(|k| format!("a[{k}]")).collect()
}

/// A value in `lo..=hi`.
fn between(rng: &mut Rng, lo: i64, hi: i64) -> i64 {
    lo + rng.below((hi - lo + 1) as usize) as i64
}

/// `WHILE j <cmp> n DO a[j] := v; j := j + k; END_WHILE` with random start,
/// step, limit and array bounds: loops that stay inside the array, run off
/// either end (index fault) or wrap around the type's range.
#[test]
fn strided_store_loops_behave_as_written() {
    let mut rng = Rng(0x5eed_1234_abcd_0001);
    let mut endings = Endings::default();
    for case in 0..300 {
        let shape = &SHAPES[rng.below(SHAPES.len())];
        let top = shape.max.min(i16::MAX as i64);
        let bottom = shape.min.max(i16::MIN as i64);
        let lo = between(&mut rng, bottom.max(-60), 20);
        let hi = lo + between(&mut rng, 0, 40);
        let up = rng.chance(70);
        let k = between(&mut rng, 1, 9) * if up { 1 } else { -1 };
        let start = between(&mut rng, lo - 5, hi + 5);
        // Mostly limits near the array; sometimes the type's extreme, so
        // that `j` wraps around before it leaves the loop.
        let limit = match rng.below(5) {
            0 if up => top,
            0 => bottom,
            _ => between(&mut rng, lo - 8, hi + 8).clamp(bottom, top),
        };
        let cmp = match (up, rng.below(10)) {
            // Each comparison runs its own loop in the executor.
            (_, 0) => "<>",
            (_, 1) => "=",
            (true, 2..=5) => "<=",
            (true, _) => "<",
            (false, 2..=5) => ">=",
            (false, _) => ">",
        };
        let (lo, hi) = (lo.max(shape.min), hi.min(shape.max));
        let decls = format!(
            "a : ARRAY[{lo}..{hi}] OF {ty}; j : {ty} := {start}; k : {ty} := {k}; v : {ty} := {v}; x : INT;",
            ty = shape.ty,
            v = case % 100 + 1,
        );
        let body = |filler: &str| {
            format!("WHILE j {cmp} {limit} DO a[j] := v; {filler}j := j + k; END_WHILE;")
        };
        let mut names = elements(lo, hi);
        names.push("j".to_string());
        endings.add(same_behaviour(
            &program("", &decls, &body(PAD)),
            &program("", &decls, &body(BREAKER)),
            STORE_STEP,
            &names,
        ));
    }
    endings.check();
}

/// The element stored can be the loop variable itself (`a[0]` indexes the
/// array it belongs to): the step must see the value just stored.
#[test]
fn a_strided_store_into_its_own_loop_variable() {
    let decls = "a : ARRAY[0..12] OF INT; x : INT;";
    let body = |filler: &str| {
        format!("WHILE a[0] <= 10 DO a[a[0]] := 1; {filler}a[0] := a[0] + 2; END_WHILE;")
    };
    let fused = program("", decls, &body(PAD));
    same_behaviour(
        &fused,
        &program("", decls, &body(BREAKER)),
        STORE_STEP,
        &elements(0, 12),
    );
    // a[0] = 0 stores 1 into a[0] itself, so the steps go 3, 5, 7, 9 and
    // end at 11.
    let mut plc = compile(&fused);
    outcome(&mut plc, 1);
    let set: Vec<String> = (0..=12).map(|k| lit(&plc, &format!("a[{k}]"))).collect();
    assert_eq!(
        set,
        [
            "11", "0", "0", "1", "0", "1", "0", "1", "0", "1", "0", "0", "0"
        ]
    );
}

/// The step can be an element of the array the loop stores into: every
/// turn must read it again, as the loop written does.
#[test]
fn a_strided_store_whose_step_is_an_element_it_overwrites() {
    let decls = "a : ARRAY[0..20] OF INT := [2]; v : INT := 5; j : INT; x : INT;";
    let body =
        |filler: &str| format!("WHILE j <= 20 DO a[j] := v; {filler}j := j + a[0]; END_WHILE;");
    let fused = program("", decls, &body(PAD));
    let mut names = elements(0, 20);
    names.push("j".to_string());
    same_behaviour(
        &fused,
        &program("", decls, &body(BREAKER)),
        STORE_STEP,
        &names,
    );
    // j = 0 stores 5 into a[0], the step: the loop goes on 5 by 5.
    let mut plc = compile(&fused);
    outcome(&mut plc, 1);
    assert_eq!(
        [0, 1, 2, 4, 5, 10, 15, 20].map(|k| lit(&plc, &format!("a[{k}]"))),
        ["5", "0", "0", "0", "5", "5", "5", "5"]
    );
    assert_eq!(lit(&plc, "j"), "25");
}

/// A step of zero never ends: the watchdog stops both loops at the same
/// place (the step statement, where the loop jumps back).
#[test]
fn an_endless_strided_store_is_stopped_by_the_watchdog() {
    let decls = "a : ARRAY[0..9] OF INT; j : INT := 2; k : INT; x : INT;";
    let body = |filler: &str| format!("WHILE j <= 9 DO a[j] := 5; {filler}j := j + k; END_WHILE;");
    let options = Options {
        watchdog: Some(Duration::from_millis(50)),
        ..Options::default()
    };
    let mut faults = Vec::new();
    for filler in [PAD, BREAKER] {
        let src = program("", decls, &body(filler));
        let mut plc = Plc::compile_files(&[("test.st", &src)], &options).unwrap();
        faults.push(outcome(&mut plc, 1).expect("the loop never ends"));
    }
    assert!(faults[0].starts_with("watchdog"), "{}", faults[0]);
    assert_eq!(faults[0], faults[1]);
}

/// `FOR i := s TO e BY st DO IF [NOT] f[i] THEN ... END_IF; END_FOR` with
/// random flags, bounds and steps, including ranges that leave the array.
#[test]
fn element_guarded_for_loops_behave_as_written() {
    let mut rng = Rng(0x5eed_1234_abcd_0002);
    let mut endings = Endings::default();
    for _ in 0..300 {
        let shape = &SHAPES[rng.below(SHAPES.len())];
        let lo = between(&mut rng, -40, 20);
        let hi = lo + between(&mut rng, 0, 40);
        let flags: Vec<&str> = (lo..=hi)
            .map(|_| if rng.chance(20) { "TRUE" } else { "FALSE" })
            .collect();
        let st = between(&mut rng, 1, 4) * if rng.chance(70) { 1 } else { -1 };
        let (s, e) = (
            between(&mut rng, lo - 3, hi + 3),
            between(&mut rng, lo - 3, hi + 3),
        );
        let not = if rng.chance(30) { "NOT " } else { "" };
        let decls = format!(
            "f : ARRAY[{lo}..{hi}] OF BOOL := [{}]; i : {ty}; n : DINT; h : DINT; x : INT;",
            flags.join(", "),
            ty = shape.ty,
        );
        let body = |filler: &str| {
            format!(
                "FOR i := {s} TO {e} BY {st} DO {filler}IF {not}f[i] THEN n := n + 1; h := h * 7 + i; END_IF; END_FOR;"
            )
        };
        let names = ["i", "n", "h"].map(String::from);
        endings.add(same_behaviour(
            &program("", &decls, &body(PAD)),
            &program("", &decls, &body(BREAKER)),
            FOR_SCAN,
            &names,
        ));
    }
    endings.check();
}

/// A loop up to the type's largest value ends (the control variable wraps
/// past it), exactly as the plain FOR loop does.
#[test]
fn an_element_guarded_loop_up_to_the_type_maximum_ends() {
    let decls = "f : ARRAY[120..127] OF BOOL := [FALSE, TRUE, FALSE, FALSE, FALSE, FALSE, FALSE, TRUE]; i : SINT; n : INT; x : INT;";
    let body = |filler: &str| {
        format!(
            "FOR i := 120 TO 127 DO {filler}IF f[i] THEN n := n * 10 + i - 119; END_IF; END_FOR;"
        )
    };
    let fused = program("", decls, &body(PAD));
    same_behaviour(
        &fused,
        &program("", decls, &body(BREAKER)),
        FOR_SCAN,
        &["i", "n"].map(String::from),
    );
    let mut plc = compile(&fused);
    assert_eq!(outcome(&mut plc, 1), None);
    assert_eq!(lit(&plc, "n"), "28");
    assert_eq!(lit(&plc, "i"), "-128");
}

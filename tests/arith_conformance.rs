//! Arithmetic conformance (issue #13 point 6): every integer, real,
//! bit-string and time operation, the numeric standard functions and every
//! `*_TO_*` conversion plcrun accepts, checked by property tests against
//! the independent model in tests/support/arith_model.rs.
//!
//! Each operation/type pair is compiled once (ST generated here) and run
//! on many generated inputs: inputs set through `Plc::set`, one
//! `run_cycle`, the output read back. A fault is compared by its code and
//! the PLC is reset cold for the next case.

use crate::support::arith_model;

use arith_model::*;
use plcrun::{ElemType as E, Options, Plc, Value, VarRef};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// Cases per property (a few hundred; the suite stays well under 60 s).
const CASES: u32 = 200;

const SIGNED: [E; 4] = [E::Sint, E::Int, E::Dint, E::Lint];
const UNSIGNED: [E; 4] = [E::Usint, E::Uint, E::Udint, E::Ulint];
const BITS: [E; 4] = [E::Byte, E::Word, E::Dword, E::Lword];
const REALS: [E; 2] = [E::Real, E::Lreal];

/// A compiled program `y := <expr>` over inputs `a`, `b`, `c`...
struct Rig {
    plc: Plc,
    ins: Vec<(VarRef, E)>,
    out: VarRef,
}

impl Rig {
    fn new(ins: &[E], out: E, expr: &str) -> Rig {
        let names = ["a", "b", "c", "d"];
        let decls: String = ins
            .iter()
            .zip(names)
            .map(|(t, n)| format!("{n} : {};\n", t.name()))
            .collect();
        let src = format!(
            "PROGRAM P\nVAR_INPUT\n{decls}END_VAR\nVAR_OUTPUT\ny : {};\nEND_VAR\ny := {expr};\nEND_PROGRAM\n",
            out.name()
        );
        let plc = Plc::compile_files(&[("arith.st", &src)], &Options::default())
            .unwrap_or_else(|e| panic!("compile error for\n{src}\n{e}"));
        let ins = ins
            .iter()
            .zip(names)
            .map(|(t, n)| (plc.resolve(n).expect("input"), *t))
            .collect();
        let out = plc.resolve("y").expect("output");
        Rig { plc, ins, out }
    }

    fn eval(&mut self, args: &[u64]) -> Out {
        for ((r, t), a) in self.ins.iter().zip(args) {
            self.plc
                .set(r, &Value::Scalar(*t, *a))
                .unwrap_or_else(|e| panic!("set {t:?} {a:#x}: {e}"));
        }
        match self.plc.run_cycle() {
            Ok(()) => match self.plc.get(&self.out).expect("read y") {
                Value::Scalar(t, raw) => Out::V(t, raw),
                Value::String(s, _) => Out::S(s),
                Value::Enum(..) => unreachable!("no enums here"),
            },
            Err(f) => {
                self.plc.reset_cold();
                Out::Fault(f.code())
            }
        }
    }
}

fn runner(cases: u32) -> TestRunner {
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha))
}

/// Checks `expr` over inputs of types `ins` against `model`.
fn check(ins: &[E], out: E, expr: &str, model: impl Fn(&[u64]) -> Out) {
    let mut rig = Rig::new(ins, out, expr);
    let strat: Vec<BoxedStrategy<u64>> = ins.iter().map(|t| arb(*t)).collect();
    let rig = std::cell::RefCell::new(&mut rig);
    runner(CASES)
        .run(&strat, |args| {
            let got = rig.borrow_mut().eval(&args).normalized();
            let want = model(&args).normalized();
            prop_assert_eq!(got, want, "{} with {:?} {:x?}", expr, ins, args);
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
}

/// Integer operations.
fn int_binary(t: E, op: &str, a: i128, b: i128) -> Out {
    let v = match op {
        "+" => a + b,
        "-" => a - b,
        // Wrapping: only the low 64 bits matter.
        "*" => a.wrapping_mul(b),
        "/" | "MOD" if b == 0 => return Out::Fault("R001"),
        "/" => a / b,
        "MOD" => a % b,
        _ => unreachable!(),
    };
    Out::V(t, wrap(t, v))
}

fn compare(op: &str, o: std::cmp::Ordering) -> bool {
    use std::cmp::Ordering::*;
    match op {
        "=" => o == Equal,
        "<>" => o != Equal,
        "<" => o == Less,
        "<=" => o != Greater,
        ">" => o == Greater,
        ">=" => o != Less,
        _ => unreachable!(),
    }
}

fn bool_out(b: bool) -> Out {
    Out::V(E::Bool, u64::from(b))
}

const CMP: [&str; 6] = ["=", "<>", "<", "<=", ">", ">="];

#[test]
fn integer_arithmetic_wraps_and_divides_toward_zero() {
    for t in SIGNED.into_iter().chain(UNSIGNED) {
        for op in ["+", "-", "*", "/", "MOD"] {
            check(&[t, t], t, &format!("a {op} b"), |x| {
                int_binary(t, op, num(t, x[0]), num(t, x[1]))
            });
        }
        for op in CMP {
            check(&[t, t], E::Bool, &format!("a {op} b"), |x| {
                bool_out(compare(op, num(t, x[0]).cmp(&num(t, x[1]))))
            });
        }
    }
    for t in SIGNED {
        check(&[t], t, "-a", |x| Out::V(t, wrap(t, -num(t, x[0]))));
        check(&[t], t, "ABS(a)", |x| {
            Out::V(t, wrap(t, num(t, x[0]).abs()))
        });
    }
    for t in UNSIGNED {
        check(&[t], t, "ABS(a)", |x| Out::V(t, x[0]));
    }
}

/// As [`check`], with the input strategies given.
fn check_with(
    ins: &[E],
    strat: Vec<BoxedStrategy<u64>>,
    out: E,
    expr: &str,
    model: impl Fn(&[u64]) -> Out,
) {
    let mut rig = Rig::new(ins, out, expr);
    let rig = std::cell::RefCell::new(&mut rig);
    runner(CASES)
        .run(&strat, |args| {
            let got = rig.borrow_mut().eval(&args).normalized();
            let want = model(&args).normalized();
            prop_assert_eq!(got, want, "{} with {:?} {:x?}", expr, ins, args);
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
}

/// Shift counts: mostly within twice the width, some negative or huge.
fn counts() -> BoxedStrategy<u64> {
    prop_oneof![4 => 0i64..140, 1 => any::<i16>().prop_map(i64::from)]
        .prop_map(|n| wrap(E::Int, i128::from(n)))
        .boxed()
}

/// SHL/SHR/ROL/ROR on the low `w` bits; the count is taken as an unsigned
/// number (a negative count is huge: SHL/SHR give 0, ROL/ROR rotate by it
/// modulo the width, so -1 rotates one place the other way).
fn shift_model(op: &str, w: u32, x: u64, n: i64) -> u64 {
    let mask = if w == 64 { u64::MAX } else { (1u64 << w) - 1 };
    let (x, n) = (x & mask, n as u64);
    let r = u64::from(w);
    match op {
        "SHL" if n >= r => 0,
        "SHL" => (x << n) & mask,
        "SHR" if n >= r => 0,
        "SHR" => x >> n,
        "ROL" | "ROR" => {
            let k = (n % r) as u32;
            let k = if op == "ROL" { k } else { (w - k) % w };
            ((x << k) | (x >> ((w - k) % w))) & mask
        }
        _ => unreachable!(),
    }
}

#[test]
fn bit_strings_logic_and_shifts() {
    for t in BITS {
        let m = wrap(t, -1);
        check(&[t, t], t, "a AND b", |x| Out::V(t, x[0] & x[1]));
        check(&[t, t], t, "a OR b", |x| Out::V(t, x[0] | x[1]));
        check(&[t, t], t, "a XOR b", |x| Out::V(t, x[0] ^ x[1]));
        check(&[t], t, "NOT a", |x| Out::V(t, !x[0] & m));
        for op in ["=", "<>"] {
            check(&[t, t], E::Bool, &format!("a {op} b"), |x| {
                bool_out(compare(op, x[0].cmp(&x[1])))
            });
        }
    }
    for t in BITS.into_iter().chain(SIGNED).chain(UNSIGNED) {
        for op in ["SHL", "SHR", "ROL", "ROR"] {
            let strat = vec![arb(t), counts()];
            check_with(&[t, E::Int], strat, t, &format!("{op}(a, b)"), |x| {
                let r = shift_model(op, width(t), x[0], x[1] as i64);
                Out::V(
                    t,
                    wrap(
                        t,
                        if signed(t) {
                            num_signed(t, r)
                        } else {
                            r.into()
                        },
                    ),
                )
            });
        }
    }
}

/// The low `width(t)` bits of `r` read as a signed number.
fn num_signed(t: E, r: u64) -> i128 {
    num(t, wrap(t, i128::from(r)))
}

fn real_binary(t: E, op: &str, a: f64, b: f64) -> Out {
    if t == E::Real {
        let (a, b) = (a as f32, b as f32);
        let v = match op {
            "+" => a + b,
            "-" => a - b,
            "*" => a * b,
            "/" => a / b,
            "**" => a.powf(b),
            _ => unreachable!(),
        };
        Out::V(t, u64::from(v.to_bits()))
    } else {
        let v = match op {
            "+" => a + b,
            "-" => a - b,
            "*" => a * b,
            "/" => a / b,
            "**" => a.powf(b),
            _ => unreachable!(),
        };
        Out::V(t, v.to_bits())
    }
}

#[test]
fn reals_follow_ieee_754() {
    for t in REALS {
        for op in ["+", "-", "*", "/", "**"] {
            check(&[t, t], t, &format!("a {op} b"), |x| {
                real_binary(t, op, real(t, x[0]), real(t, x[1]))
            });
        }
        check(&[t, t], t, "EXPT(a, b)", |x| {
            real_binary(t, "**", real(t, x[0]), real(t, x[1]))
        });
        for op in CMP {
            check(&[t, t], E::Bool, &format!("a {op} b"), |x| {
                let (a, b) = (real(t, x[0]), real(t, x[1]));
                // Every comparison with a NaN is FALSE, except `<>`.
                bool_out(match a.partial_cmp(&b) {
                    Some(o) => compare(op, o),
                    None => op == "<>",
                })
            });
        }
        check(&[t], t, "-a", |x| Out::V(t, real_slot(t, -real(t, x[0]))));
        check(&[t], t, "ABS(a)", |x| {
            Out::V(t, real_slot(t, real(t, x[0]).abs()))
        });
    }
}

/// Inputs of `t` for the numeric standard functions.
const NUMERIC: [E; 10] = [
    E::Sint,
    E::Int,
    E::Dint,
    E::Lint,
    E::Usint,
    E::Uint,
    E::Udint,
    E::Ulint,
    E::Real,
    E::Lreal,
];

/// Values of `t`, with -0.0 made +0.0.
fn no_neg_zero(t: E) -> BoxedStrategy<u64> {
    arb(t)
        .prop_map(move |x| {
            if REALS.contains(&t) && real(t, x) == 0.0 {
                real_slot(t, 0.0)
            } else {
                x
            }
        })
        .boxed()
}

/// The order of two values of `t` (`None` when a NaN is involved).
fn order(t: E, a: u64, b: u64) -> Option<std::cmp::Ordering> {
    if REALS.contains(&t) {
        real(t, a).partial_cmp(&real(t, b))
    } else {
        Some(num(t, a).cmp(&num(t, b)))
    }
}

#[test]
fn min_max_limit_sel_mux() {
    use std::cmp::Ordering::*;
    for t in NUMERIC.into_iter().chain(BITS).chain([E::Time, E::Ltime]) {
        // MAX/MIN keep the first input unless the second is strictly
        // greater/smaller; a NaN input is ignored (IEEE 754 maxNum/minNum:
        // NaN only when both are). Zeros are all +0.0 here: the sign of a
        // zero that MIN/MAX choose between -0.0 and +0.0 is not specified.
        let pick = move |a: u64, b: u64, want: std::cmp::Ordering| {
            let nan = |v: u64| REALS.contains(&t) && real(t, v).is_nan();
            if nan(b) || (!nan(a) && order(t, b, a) != Some(want)) {
                a
            } else {
                b
            }
        };
        let s3 = || vec![no_neg_zero(t), no_neg_zero(t), no_neg_zero(t)];
        check_with(&[t, t], s3()[..2].to_vec(), t, "MAX(a, b)", |x| {
            Out::V(t, pick(x[0], x[1], Greater))
        });
        check_with(&[t, t], s3()[..2].to_vec(), t, "MIN(a, b)", |x| {
            Out::V(t, pick(x[0], x[1], Less))
        });
        // LIMIT(MN, IN, MX) = MIN(MAX(IN, MN), MX).
        check_with(&[t, t, t], s3(), t, "LIMIT(a, b, c)", |x| {
            Out::V(t, pick(pick(x[1], x[0], Greater), x[2], Less))
        });
        check(&[E::Bool, t, t], t, "SEL(a, b, c)", |x| {
            Out::V(t, if x[0] != 0 { x[2] } else { x[1] })
        });
        let k = (-3i64..6).prop_map(|k| wrap(E::Int, i128::from(k))).boxed();
        check_with(
            &[E::Int, t, t, t],
            vec![k, arb(t), arb(t), arb(t)],
            t,
            "MUX(a, b, c, d)",
            |x| match x[0] as i64 {
                k @ 0..=2 => Out::V(t, x[1 + k as usize]),
                _ => Out::Fault("R005"),
            },
        );
    }
}

/// The `FROM_TO_TO` pairs plcrun compiles, found by compiling them all
/// (one assignment per line; lines with an error are the refused pairs,
/// and the rest is compiled again until it compiles cleanly, so a cap on
/// repeated diagnostics cannot hide a refusal).
fn accepted_conversions() -> Vec<(E, E)> {
    let mut left: Vec<(E, E)> = E::ALL
        .into_iter()
        .flat_map(|f| E::ALL.into_iter().map(move |t| (f, t)))
        .collect();
    loop {
        let mut src = String::from("PROGRAM P\nVAR\n");
        for t in E::ALL {
            src += &format!("v_{0} : {0};\n", t.name());
        }
        for (i, (_, t)) in left.iter().enumerate() {
            src += &format!("o{i} : {};\n", t.name());
        }
        src += "END_VAR\n";
        let first_line = src.lines().count() + 1;
        for (i, (f, t)) in left.iter().enumerate() {
            src += &format!("o{i} := {}_TO_{}(v_{});\n", f.name(), t.name(), f.name());
        }
        src += "END_PROGRAM\n";
        let refused: Vec<usize> = match Plc::compile_files(&[("t.st", &src)], &Options::default()) {
            Ok(_) => return left,
            Err(e) => e
                .diagnostics
                .iter()
                .filter(|d| d.severity == plcrun::Severity::Error)
                .map(|d| {
                    let loc = e.sources.location(d.span);
                    let line: usize = loc.split(':').nth(1).and_then(|l| l.parse().ok()).unwrap();
                    line - first_line
                })
                .collect(),
        };
        assert!(!refused.is_empty(), "compile failed without an error line");
        left = left
            .into_iter()
            .enumerate()
            .filter(|(i, _)| !refused.contains(i))
            .map(|(_, p)| p)
            .collect();
    }
}

/// Whether the model (numbers here, strings in [`string_conversion`])
/// defines `FROM_TO_TO`.
fn modelled(f: E, t: E) -> bool {
    kind(f) == K::Str || kind(t) == K::Str || convert(f, t, 0).is_some()
}

#[test]
fn conversion_table_is_exactly_the_modelled_one() {
    let accepted = accepted_conversions();
    let all: Vec<(E, E)> = E::ALL
        .into_iter()
        .flat_map(|f| E::ALL.into_iter().map(move |t| (f, t)))
        .collect();
    let mismatch: Vec<String> = all
        .iter()
        .filter(|(f, t)| accepted.contains(&(*f, *t)) != modelled(*f, *t))
        .map(|(f, t)| {
            let side = if modelled(*f, *t) {
                "modelled, refused"
            } else {
                "accepted, no model"
            };
            format!("{}_TO_{} ({side})", f.name(), t.name())
        })
        .collect();
    assert!(
        mismatch.is_empty(),
        "conversion table and model differ: {mismatch:?}"
    );
    let mut checked = 0;
    for (f, t) in accepted {
        if kind(f) == K::Str || kind(t) == K::Str {
            string_conversion(f, t);
        } else {
            check(&[f], t, &format!("{}_TO_{}(a)", f.name(), t.name()), |x| {
                convert(f, t, x[0]).unwrap()
            });
        }
        checked += 1;
    }
    eprintln!("conversions checked: {checked}");
}

/// What `STRING_TO_T(T_TO_STRING(x))` gives: `x`, except for the texts
/// that do not read back (the conversion fault).
fn read_back(t: E, x: u64) -> Out {
    let fails = match t {
        // INF and NaN are printed (`INF`, `NaN`) but not read back.
        E::Real | E::Lreal => !real(t, x).is_finite(),
        // The first day of the DT range has no midnight in range.
        E::Dt | E::Ldt => (x as i64).div_euclid(DAY).checked_mul(DAY).is_none(),
        // A lone UTF-16 surrogate is no character of a string.
        E::Wchar => (0xD800..0xE000).contains(&x),
        _ => false,
    };
    if fails {
        Out::Fault("R004")
    } else {
        Out::V(t, x)
    }
}

/// Conversions to and from STRING/WSTRING: integers and BOOL print as
/// their IEC literal without type prefix (`-42`, `TRUE`); every other
/// scalar reads back to the same value (`STRING_TO_X(X_TO_STRING(a)) = a`).
fn string_conversion(f: E, t: E) {
    match (kind(f), kind(t)) {
        (K::Str, K::Str) => {
            let expr = format!(
                "{}_TO_{}({}_TO_{}(a))",
                f.name(),
                t.name(),
                E::Lint.name(),
                f.name()
            );
            check(&[E::Lint], t, &expr, |x| Out::S((x[0] as i64).to_string()));
        }
        (K::Signed | K::Unsigned | K::Bool, K::Str) => {
            check(&[f], t, &format!("{}_TO_{}(a)", f.name(), t.name()), |x| {
                Out::S(match kind(f) {
                    K::Bool => (if x[0] != 0 { "TRUE" } else { "FALSE" }).into(),
                    _ => num(f, x[0]).to_string(),
                })
            });
        }
        (_, K::Str) => {
            let back = format!(
                "{}_TO_{}({}_TO_{}(a))",
                t.name(),
                f.name(),
                f.name(),
                t.name()
            );
            check(&[f], f, &back, |x| read_back(f, x[0]));
        }
        _ => {
            // INF and NaN are printed (`INF`, `NaN`) but not read back.
            let back = format!(
                "{}_TO_{}({}_TO_{}(a))",
                f.name(),
                t.name(),
                t.name(),
                f.name()
            );
            check(&[t], t, &back, |x| read_back(t, x[0]));
        }
    }
}

/// Durations and dates: nanosecond counts in an i64.
fn ns(x: u64) -> i128 {
    i128::from(x as i64)
}

/// A duration or date result: wraps in the i64 like integer arithmetic.
fn time_out(t: E, v: i128) -> Out {
    Out::V(t, v as u64)
}

/// TOD results stay within the day (wrapped around midnight).
fn tod_out(t: E, v: i128) -> Out {
    Out::V(t, (v as i64).rem_euclid(DAY) as u64)
}

#[test]
fn time_and_date_arithmetic() {
    for t in [E::Time, E::Ltime] {
        let n = t.name();
        for (expr, sub) in [("a + b", false), ("a - b", true)] {
            let f = |x: &[u64]| {
                time_out(
                    t,
                    if sub {
                        ns(x[0]) - ns(x[1])
                    } else {
                        ns(x[0]) + ns(x[1])
                    },
                )
            };
            check(&[t, t], t, expr, f);
            let fname = format!("{}_{n}(a, b)", if sub { "SUB" } else { "ADD" });
            check(&[t, t], t, &fname, f);
        }
        for op in CMP {
            check(&[t, t], E::Bool, &format!("a {op} b"), |x| {
                bool_out(compare(op, ns(x[0]).cmp(&ns(x[1]))))
            });
        }
        for k in [E::Dint, E::Lint, E::Udint, E::Ulint] {
            check(&[t, k], t, "a * b", |x| {
                time_out(t, ns(x[0]).wrapping_mul(num(k, x[1])))
            });
            check(&[t, k], t, &format!("MUL_{n}(a, b)"), |x| {
                time_out(t, ns(x[0]).wrapping_mul(num(k, x[1])))
            });
            // A ULINT divisor of 2^63 or more is the conversion fault.
            let div = |x: &[u64]| match num(k, x[1]) {
                0 => Out::Fault("R001"),
                d if d > i128::from(i64::MAX) => Out::Fault("R004"),
                d => time_out(t, ns(x[0]) / d),
            };
            check(&[t, k], t, "a / b", div);
            check(&[t, k], t, &format!("DIV_{n}(a, b)"), div);
        }
        for k in REALS {
            // A real factor: the exact product rounded half away from zero;
            // out of range or NaN is the conversion fault.
            check(&[t, k], t, "a * b", |x| {
                real_ns(t, (x[0] as i64) as f64 * real(k, x[1]))
            });
            check(&[t, k], t, "a / b", |x| match real(k, x[1]) {
                0.0 => Out::Fault("R001"),
                d => real_ns(t, (x[0] as i64) as f64 / d),
            });
        }
    }
    date_arithmetic();
}

fn real_ns(t: E, v: f64) -> Out {
    match integral(round_half_away(v)).and_then(|i| i64::try_from(i).ok()) {
        Some(i) => Out::V(t, i as u64),
        None => Out::Fault("R004"),
    }
}

fn date_arithmetic() {
    let plain = [
        (E::Tod, E::Time, "ADD_TOD_TIME"),
        (E::Ltod, E::Ltime, "ADD_LTOD_LTIME"),
        (E::Dt, E::Time, "ADD_DT_TIME"),
        (E::Ldt, E::Ltime, "ADD_LDT_LTIME"),
    ];
    for (d, t, add) in plain {
        let sub = add.replace("ADD", "SUB");
        let out = |x: &[u64], v: i128| {
            let _ = x;
            if kind(d) == K::Date && matches!(d, E::Tod | E::Ltod) {
                tod_out(d, v)
            } else {
                time_out(d, v)
            }
        };
        for expr in ["a + b".to_string(), format!("{add}(a, b)")] {
            check(&[d, t], d, &expr, |x| out(x, ns(x[0]) + ns(x[1])));
        }
        for expr in ["a - b".to_string(), format!("{sub}(a, b)")] {
            check(&[d, t], d, &expr, |x| out(x, ns(x[0]) - ns(x[1])));
        }
    }
    let diffs = [
        (E::Date, E::Time, "SUB_DATE_DATE"),
        (E::Ldate, E::Ltime, "SUB_LDATE_LDATE"),
        (E::Tod, E::Time, "SUB_TOD_TOD"),
        (E::Ltod, E::Ltime, "SUB_LTOD_LTOD"),
        (E::Dt, E::Time, "SUB_DT_DT"),
        (E::Ldt, E::Ltime, "SUB_LDT_LDT"),
    ];
    for (d, t, f) in diffs {
        for expr in ["a - b".to_string(), format!("{f}(a, b)")] {
            check(&[d, d], t, &expr, |x| time_out(t, ns(x[0]) - ns(x[1])));
        }
        for op in CMP {
            check(&[d, d], E::Bool, &format!("a {op} b"), |x| {
                bool_out(compare(op, ns(x[0]).cmp(&ns(x[1]))))
            });
        }
    }
    check(&[E::Date, E::Tod], E::Dt, "CONCAT_DATE_TOD(a, b)", |x| {
        time_out(E::Dt, ns(x[0]) + ns(x[1]))
    });
    check(
        &[E::Ldate, E::Ltod],
        E::Ldt,
        "CONCAT_LDATE_LTOD(a, b)",
        |x| time_out(E::Ldt, ns(x[0]) + ns(x[1])),
    );
}

/// `a ** b` on integers: repeated multiplication, wrapping; a negative
/// exponent is the fault R007.
fn int_pow(t: E, a: u64, b: i128) -> Out {
    // A ULINT exponent of 2^63 or more counts as negative (the power is
    // computed in 64-bit signed arithmetic).
    if b < 0 || b > i128::from(i64::MAX) {
        return Out::Fault("R007");
    }
    let (mut acc, mut base, mut e) = (1u64, a, b as u128);
    while e > 0 {
        if e & 1 == 1 {
            acc = acc.wrapping_mul(base);
        }
        base = base.wrapping_mul(base);
        e >>= 1;
    }
    Out::V(t, wrap(t, i128::from(acc)))
}

#[test]
fn expt_trunc_and_bcd() {
    for t in SIGNED.into_iter().chain(UNSIGNED) {
        let e = (-3i64..70)
            .prop_map(move |k| wrap(t, i128::from(k)))
            .boxed();
        check_with(&[t, t], vec![arb(t), e], t, "a ** b", |x| {
            int_pow(t, x[0], num(t, x[1]))
        });
    }
    for f in REALS {
        for t in SIGNED.into_iter().chain(UNSIGNED) {
            check(&[f], t, &format!("TRUNC_{}(a)", t.name()), |x| {
                real_trunc(t, real(f, x[0]))
            });
            let name = format!("{}_TRUNC_{}(a)", f.name(), t.name());
            check(&[f], t, &name, |x| real_trunc(t, real(f, x[0])));
        }
    }
    for b in BITS {
        let digits = width(b) / 4;
        for t in SIGNED.into_iter().chain(UNSIGNED) {
            check(
                &[b],
                t,
                &format!("{}_BCD_TO_{}(a)", b.name(), t.name()),
                |x| match from_bcd(x[0], digits) {
                    Some(v) => checked(t, v),
                    None => Out::Fault("R006"),
                },
            );
            check(
                &[t],
                b,
                &format!("{}_TO_BCD_{}(a)", t.name(), b.name()),
                |x| to_bcd(num(t, x[0]), digits).map_or(Out::Fault("R004"), |v| Out::V(b, v)),
            );
        }
    }
}

/// The number written in `digits` BCD nibbles, if every nibble is 0..9.
fn from_bcd(x: u64, digits: u32) -> Option<i128> {
    let mut v = 0i128;
    for k in (0..digits).rev() {
        let d = (x >> (4 * k)) & 0xF;
        if d > 9 {
            return None;
        }
        v = v * 10 + i128::from(d);
    }
    Some(v)
}

/// `v` in BCD if it is not negative and has at most `digits` digits.
fn to_bcd(v: i128, digits: u32) -> Option<u64> {
    if v < 0 || v >= 10i128.pow(digits) {
        return None;
    }
    let text = v.to_string();
    Some(
        text.bytes()
            .fold(0u64, |acc, c| acc << 4 | u64::from(c - b'0')),
    )
}

/// `v` of `t` as an ST typed literal.
fn literal(t: E, v: u64) -> String {
    match kind(t) {
        K::Signed | K::Unsigned => format!("{}#{}", t.name(), num(t, v)),
        K::Bits => format!("{}#16#{v:X}", t.name()),
        K::Real => {
            let text = if t == E::Real {
                format!("{:e}", f32::from_bits(v as u32))
            } else {
                format!("{:e}", f64::from_bits(v))
            };
            let (m, e) = text.split_once('e').unwrap();
            let m = if m.contains('.') {
                m.to_string()
            } else {
                format!("{m}.0")
            };
            format!("{}#{m}E{e}", t.name())
        }
        K::Dur => format!(
            "{}#{}ns",
            if t == E::Time { "T" } else { "LTIME" },
            v as i64
        ),
        _ => unreachable!(),
    }
}

/// Whether the exact (unwrapped) result of a folded operation is a value
/// of `out`: a constant expression that overflows is a compile error.
fn exact_fits(t: E, out: E, op: &str, a: u64, b: u64) -> bool {
    match kind(t) {
        K::Signed | K::Unsigned | K::Dur => {
            let (a, b) = (num(t, a), num(t, b));
            let v = match op {
                "+" => a + b,
                "-" => a - b,
                "*" => match a.checked_mul(b) {
                    Some(v) => v,
                    None => return false,
                },
                "/" | "MOD" if b == 0 => return false,
                "/" => a / b,
                "MOD" => a % b,
                _ => return true,
            };
            let (lo, hi) = if kind(out) == K::Dur {
                (i64::MIN.into(), i64::MAX.into())
            } else {
                range(out)
            };
            (lo..=hi).contains(&v)
        }
        K::Real if !["+", "-", "*", "/"].contains(&op) => {
            real(t, a).is_finite() && real(t, b).is_finite()
        }
        K::Real => match real_binary(t, op, real(t, a), real(t, b)) {
            Out::V(_, r) => {
                real(t, r).is_finite() && real(t, a).is_finite() && real(t, b).is_finite()
            }
            _ => false,
        },
        _ => true,
    }
}

/// Folding: `y_i := <lit> op <lit>` compiled as constants gives what the
/// run-time path gives for the same operands; an overflowing constant
/// expression is refused at compile time.
fn fold_check(t: E, out: E, op: &str, runner: &mut TestRunner) {
    let expr = if op.chars().all(char::is_alphabetic)
        && op != "MOD"
        && op != "AND"
        && op != "OR"
        && op != "XOR"
    {
        format!("{op}(a, b)")
    } else {
        format!("a {op} b")
    };
    let mut rig = Rig::new(&[t, t], out, &expr);
    let strat = (arb(t), arb(t));
    let mut good = Vec::new();
    let mut bad = Vec::new();
    for _ in 0..CASES {
        let (a, b) = proptest::strategy::ValueTree::current(&strat.new_tree(runner).unwrap());
        let finite = |v: u64| kind(t) != K::Real || real(t, v).is_finite();
        if exact_fits(t, out, op, a, b) {
            good.push((a, b));
        } else if kind(t) != K::Real && bad.len() < 2 && finite(a) && finite(b) {
            // (A real constant expression that overflows to an infinity
            // or gives NaN is left to run time; only the integers refuse.)
            bad.push((a, b));
        }
    }
    let lit_expr = |a: u64, b: u64| {
        expr.replace('a', "\u{1}")
            .replace('b', &literal(t, b))
            .replace('\u{1}', &literal(t, a))
    };
    let mut src = String::from("PROGRAM P\nVAR\n");
    for i in 0..good.len() {
        src += &format!("y{i} : {};\n", out.name());
    }
    src += "END_VAR\n";
    for (i, (a, b)) in good.iter().enumerate() {
        src += &format!("y{i} := {};\n", lit_expr(*a, *b));
    }
    src += "END_PROGRAM\n";
    let mut folded = Plc::compile_files(&[("fold.st", &src)], &Options::default())
        .unwrap_or_else(|e| panic!("folding {expr} on {t:?}:\n{e}"));
    folded.run_cycle().expect("constants do not fault");
    for (i, (a, b)) in good.iter().enumerate() {
        let got = match folded.read(&format!("y{i}")).unwrap() {
            Value::Scalar(ty, raw) => Out::V(ty, raw),
            v => panic!("{v:?}"),
        };
        let want = rig.eval(&[*a, *b]);
        assert_eq!(
            got.normalized(),
            want.normalized(),
            "folded {} vs run time",
            lit_expr(*a, *b)
        );
    }
    for (a, b) in bad {
        let src = format!(
            "PROGRAM P\nVAR\ny : {};\nEND_VAR\ny := {};\nEND_PROGRAM\n",
            out.name(),
            lit_expr(a, b)
        );
        assert!(
            Plc::compile_files(&[("fold.st", &src)], &Options::default()).is_err(),
            "overflowing constant accepted: {}",
            lit_expr(a, b)
        );
    }
}

#[test]
fn constant_folding_matches_run_time() {
    let mut runner = runner(CASES);
    for t in SIGNED.into_iter().chain(UNSIGNED) {
        for op in ["+", "-", "*", "/", "MOD", "MIN", "MAX"] {
            fold_check(t, t, op, &mut runner);
        }
        for op in CMP {
            fold_check(t, E::Bool, op, &mut runner);
        }
    }
    for t in REALS {
        for op in ["+", "-", "*", "/", "MIN", "MAX"] {
            fold_check(t, t, op, &mut runner);
        }
        for op in CMP {
            fold_check(t, E::Bool, op, &mut runner);
        }
    }
    for t in BITS {
        for op in ["AND", "OR", "XOR"] {
            fold_check(t, t, op, &mut runner);
        }
    }
    for t in [E::Time, E::Ltime] {
        for op in ["+", "-"] {
            fold_check(t, t, op, &mut runner);
        }
    }
}

//! The differential check: a generated program compiled twice, with the
//! optimizations (fused superinstructions, bounds proofs) and without,
//! fed the same inputs; every cycle's variables and faults must agree.
//! [`check_engines`] does the same with the native tier against the
//! interpreter (both optimized).

use super::st_gen::GenProgram;
use plcrun::{Options, Plc, RuntimeFault, VarRef};
use std::time::Duration;

/// What running a generated program both ways gave.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Verdict {
    /// Both builds ran `cycles` cycles with equal variables after each,
    /// ending with the same fault code if any.
    Agree {
        /// Cycles run.
        cycles: usize,
        /// The code of the fault both stopped at.
        fault: Option<&'static str>,
        /// How many of each [`FUSED`] instruction the optimized build
        /// holds (the unoptimized one holds none).
        fused: Vec<usize>,
    },
    /// Both builds refused the program with the same diagnostic codes (a
    /// constant expression that overflows, for instance).
    Refused {
        /// The error codes.
        codes: Vec<String>,
    },
    /// The wall-clock watchdog tripped in one of them: the machine was too
    /// busy to compare (the programs' loops are bounded).
    Watchdog,
}

/// The instructions that exist only in an optimized build: the loop
/// superinstructions, the accesses whose bounds check a FOR loop's range
/// proves, the fill idiom, the fused compare-and-branch on an element,
/// `a AND NOT b` and the multiply-add. (`JnCmpSI`/`JnCmpS` are left out:
/// a FOR loop's own exit test uses them in both builds.)
pub const FUSED: [&str; 14] = [
    "StoreStep",
    "ForScan",
    "AddBr",
    "LoadElemU",
    "StoreElemU",
    "FillElems",
    "JzElem",
    "JnzElem",
    "JnCmpF32",
    "JnCmpF64",
    "AndN",
    "OrN",
    "MulAddF32",
    "MulAddF64",
];

/// The options of one build: a small data budget, a generous watchdog.
fn options(optimize: bool) -> Options {
    Options {
        watchdog: Some(Duration::from_secs(2)),
        max_data_bytes: 1 << 20,
        optimize,
        ..Options::default()
    }
}

/// The error codes of a failed compile.
fn codes(e: &plcrun::CompileError) -> Vec<String> {
    let mut v: Vec<String> = e
        .diagnostics
        .iter()
        .filter(|d| d.severity == plcrun::Severity::Error)
        .map(|d| d.code.to_string())
        .collect();
    v.sort();
    v
}

/// Every variable of `plc` with its handle (resolved once: a program may
/// have tens of thousands of elements).
fn handles(plc: &Plc) -> Vec<(String, Option<VarRef>)> {
    plc.variables()
        .into_iter()
        .map(|v| {
            let r = plc.resolve(&v.path).ok();
            (v.path, r)
        })
        .collect()
}

/// The value of every variable of `vars`, as `path=value`.
fn snapshot(plc: &Plc, vars: &[(String, Option<VarRef>)]) -> Vec<String> {
    vars.iter()
        .map(|(path, r)| match r.as_ref().map(|r| plc.get(r)) {
            Some(Ok(value)) => format!("{path}={}", value.to_literal()),
            Some(Err(e)) => format!("{path}: {e}"),
            None => format!("{path}: unresolved"),
        })
        .collect()
}

/// A fault as compared: code, cycle, place.
fn fault_key(f: &RuntimeFault) -> (&'static str, u64, String) {
    (f.code(), f.cycle, f.location.clone())
}

/// Runs `p` optimized and unoptimized and compares them.
///
/// # Panics
/// When the two builds disagree (the fuzzer's finding), with both sides
/// and the program in the message.
pub fn check(p: &GenProgram) -> Verdict {
    compare(p, &options(true), &options(false))
}

/// Runs `p` on the native tier and on the interpreter and compares them
/// (the fused counts are the native build's).
///
/// # Panics
/// As [`check`].
pub fn check_engines(p: &GenProgram) -> Verdict {
    let native = Options {
        engine: plcrun::Engine::Native,
        ..options(true)
    };
    compare(p, &native, &options(true))
}

/// Runs `p` built with `fast` and with `plain` and compares them ("optimized"
/// and "unoptimized" in the messages are `fast` and `plain`).
fn compare(p: &GenProgram, fast: &Options, plain: &Options) -> Verdict {
    let files = [("gen.st", p.source.as_str())];
    let fast = Plc::compile_files(&files, fast);
    let plain_unoptimized = !plain.optimize;
    let plain = Plc::compile_files(&files, plain);
    let (mut fast, mut plain) = match (fast, plain) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(a), Err(b)) => {
            let (ca, cb) = (codes(&a), codes(&b));
            assert_eq!(ca, cb, "the builds refuse differently:\n{}", p.source);
            return Verdict::Refused { codes: ca };
        }
        (a, b) => panic!(
            "one build compiles, the other not:\noptimized: {:?}\nunoptimized: {:?}\n{}",
            a.err().map(|e| e.to_string()),
            b.err().map(|e| e.to_string()),
            p.source
        ),
    };
    let mut fused = Vec::with_capacity(FUSED.len());
    for name in FUSED {
        let count = |plc: &Plc| plc.image().instruction_count(name);
        if plain_unoptimized {
            assert_eq!(count(&plain), Some(0), "{name} in the unoptimized build");
        }
        fused.push(count(&fast).unwrap_or(0));
    }
    let (fast_vars, plain_vars) = (handles(&fast), handles(&plain));
    for (n, writes) in p.cycles.iter().enumerate() {
        for (name, value) in writes {
            let a = fast.write(name, value).map_err(|e| e.to_string());
            let b = plain.write(name, value).map_err(|e| e.to_string());
            assert_eq!(a, b, "writing {name} := {value}:\n{}", p.source);
        }
        let a = fast.run_cycle();
        let b = plain.run_cycle();
        let watchdog = |r: &Result<(), RuntimeFault>| matches!(r, Err(f) if f.code() == "R008");
        if watchdog(&a) || watchdog(&b) {
            return Verdict::Watchdog;
        }
        assert_eq!(
            a.as_ref().err().map(fault_key),
            b.as_ref().err().map(fault_key),
            "cycle {n}: the faults differ (optimized vs unoptimized):\n{}",
            p.source
        );
        let (sa, sb) = (snapshot(&fast, &fast_vars), snapshot(&plain, &plain_vars));
        if sa != sb {
            let diff: Vec<String> = sa
                .iter()
                .zip(&sb)
                .filter(|(x, y)| x != y)
                .map(|(x, y)| format!("  optimized {x}, unoptimized {y}"))
                .collect();
            panic!(
                "cycle {n}: the variables differ:\n{}\n{}",
                diff.join("\n"),
                p.source
            );
        }
        if let Err(f) = a {
            return Verdict::Agree {
                cycles: n + 1,
                fault: Some(f.code()),
                fused,
            };
        }
    }
    Verdict::Agree {
        cycles: p.cycles.len(),
        fault: None,
        fused,
    }
}

//! The native tier (`Engine::Native`, docs/adr/0009-native-tier.md)
//! against the interpreter, its reference: the benchmarks compile wholly
//! and give the same checksums; every program of `programs/` gives the
//! same trace and the same ending on both engines, and the seed programs
//! their committed expected traces; generated ST and IL programs give the
//! same variables after every cycle (time-boxed); a fault inside machine
//! code is the interpreter's fault, at the same place and cycle, with the
//! same call path. Without the `native` feature the engine runs everything
//! in the interpreter and these tests check the same equalities.

use crate::fuzz::differential;
use crate::fuzz::il_gen;
use crate::fuzz::st_gen;
use crate::support::library::{TraceRequest, repo_files, repo_text, run_csv_with};
use plcrun::{Engine, Options, Plc, RuntimeFault};
use std::path::Path;
use std::time::{Duration, Instant};

fn with(engine: Engine) -> Options {
    Options {
        engine,
        ..Options::default()
    }
}

/// Whether this build compiles native code (the `native` feature on
/// x86-64); otherwise every block is reported as interpreted.
fn native_available() -> bool {
    cfg!(all(feature = "native", target_arch = "x86_64"))
}

/// The names of the blocks of `plc` that fell back, with the reasons.
fn fallbacks(plc: &Plc) -> Vec<String> {
    let report = plc.native_report().expect("a native build has a report");
    report
        .fell_back
        .iter()
        .map(|f| format!("{}: {}", f.block, f.reason))
        .collect()
}

/// The checksum trace of `file` over `cycles` on `engine`.
fn bench_trace(file: &str, cycles: u64, engine: Engine) -> String {
    let request = TraceRequest {
        cycles,
        trace: Some("checksum"),
        changes_only: true,
        ..TraceRequest::default()
    };
    let (csv, end) = run_csv_with(&repo_files(&[file]), &request, &with(engine));
    end.unwrap_or_else(|e| panic!("{file} on {engine}: {e}"));
    csv
}

#[test]
fn the_benchmarks_compile_wholly_and_give_the_same_checksums() {
    for (file, cycles) in [
        ("benches/programs/bench_a_bool_logic.st", 200),
        ("benches/programs/bench_b_int_sieve.st", 20),
        ("benches/programs/bench_c_fb_unrolled.st", 50),
        ("benches/programs/bench_c_fb_array.st", 50),
        ("benches/programs/bench_d_real_math.st", 100),
    ] {
        let plc = Plc::compile_files(&[(file, repo_text(file).as_str())], &with(Engine::Native))
            .expect("the benchmark compiles");
        if native_available() {
            assert_eq!(fallbacks(&plc), Vec::<String>::new(), "{file}");
            let report = plc.native_report().unwrap();
            assert!(report.code_bytes > 0, "{file}: no code");
        } else {
            assert!(plc.native_report().unwrap().compiled.is_empty());
        }
        let interp = bench_trace(file, cycles, Engine::Interp);
        let native = bench_trace(file, cycles, Engine::Native);
        assert_eq!(native, interp, "{file}");
        assert!(
            interp.lines().count() > 2,
            "{file}: the checksum never moved"
        );
    }
}

/// The interpreter's report is `None`; the native engine's names the
/// blocks it compiled, or says why none was.
#[test]
fn the_report_accounts_for_every_block() {
    let src = "FUNCTION_BLOCK Acc VAR_INPUT x : INT; END_VAR VAR_OUTPUT s : INT; END_VAR
        s := s + x; END_FUNCTION_BLOCK
        PROGRAM P VAR a : Acc; n : INT; t : STRING; END_VAR
        n := n + 1; a(x := n); t := CONCAT(t, 'x'); END_PROGRAM";
    let interp = Plc::compile_files(&[("p.st", src)], &with(Engine::Interp)).unwrap();
    assert!(interp.native_report().is_none());
    let native = Plc::compile_files(&[("p.st", src)], &with(Engine::Native)).unwrap();
    let report = native.native_report().unwrap();
    if native_available() {
        assert!(report.compiled.iter().any(|b| b == "Acc"), "{report}");
        assert!(report.compiled.iter().any(|b| b == "P"), "{report}");
    } else {
        assert!(
            report
                .fell_back
                .iter()
                .all(|f| f.reason.contains("feature"))
        );
    }
}

/// Every source of `programs/` with each stimulus named after it (and
/// with none), on both engines: the same trace, the same ending.
#[test]
fn every_program_runs_the_same_on_both_engines() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("programs");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("programs/")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let sources = names.iter().filter(|n| {
        [".st", ".il", ".sfc", ".awl"]
            .iter()
            .any(|e| n.ends_with(e))
    });
    let mut natively = 0;
    for source in sources {
        let stem = source.split('.').next().unwrap_or(source);
        // alg02 runs ALG01's scenarios (its expected traces say so).
        let prefix = if stem == "alg02" { "alg01" } else { stem };
        let stimuli: Vec<&String> = names
            .iter()
            .filter(|n| {
                n.starts_with(prefix) && n.ends_with(".csv") && !n.ends_with("expected.csv")
            })
            .collect();
        let path = format!("programs/{source}");
        let files = repo_files(&[&path]);
        let text = files[0].1.clone();
        let Ok(plc) = Plc::compile_files(&[(path.as_str(), text.as_str())], &with(Engine::Native))
        else {
            // Sources that need others beside them (a chart's IL) are run
            // by their own tests.
            continue;
        };
        natively += plc.native_report().map_or(0, |r| r.compiled.len());
        let mut runs: Vec<Option<String>> = stimuli
            .iter()
            .map(|s| Some(repo_text(&format!("programs/{s}"))))
            .collect();
        runs.push(None);
        for stimulus in &runs {
            let request = TraceRequest {
                cycles: 600,
                stimulus: stimulus.as_deref(),
                ..TraceRequest::default()
            };
            let (a, ea) = run_csv_with(&files, &request, &with(Engine::Interp));
            let (b, eb) = run_csv_with(&files, &request, &with(Engine::Native));
            assert_eq!(b, a, "{path}: the traces differ");
            assert_eq!(
                eb.map_err(|e| e.to_string()),
                ea.map_err(|e| e.to_string()),
                "{path}: the runs end differently"
            );
        }
    }
    if native_available() {
        assert!(
            natively >= 5,
            "only {natively} blocks of programs/ compiled natively"
        );
    }
}

/// The seed programs' committed expected traces, on the native engine.
#[test]
fn the_seed_programs_give_their_expected_traces_natively() {
    let alg = "M0,M1,M2,M3,M4,V1,V2,L1";
    for program in ["alg01", "alg02"] {
        for scenario in ["s1", "s2", "s1s2", "sw1_held"] {
            let stimulus = repo_text(&format!("programs/alg01_{scenario}.csv"));
            let request = TraceRequest {
                cycles: 1200,
                stimulus: Some(&stimulus),
                trace: Some(alg),
                changes_only: false,
            };
            let files = repo_files(&[&format!("programs/{program}.il")]);
            let (csv, end) = run_csv_with(&files, &request, &with(Engine::Native));
            end.expect("no fault");
            let expected = repo_text(&format!("programs/{program}_{scenario}.expected.csv"));
            assert!(csv == expected, "{program} {scenario}: the trace differs");
        }
    }
    for (program, cycles, stimulus) in [
        ("cmd_monitor", 125, Some("programs/cmd_monitor.csv")),
        ("comparator", 256, None),
    ] {
        let stimulus = stimulus.map(repo_text);
        let request = TraceRequest {
            cycles,
            stimulus: stimulus.as_deref(),
            ..TraceRequest::default()
        };
        let files = repo_files(&[&format!("programs/{program}.st")]);
        let (csv, end) = run_csv_with(&files, &request, &with(Engine::Native));
        end.expect("no fault");
        let expected = repo_text(&format!("programs/{program}.expected.csv"));
        assert!(csv == expected, "{program}: the trace differs");
    }
}

/// The time each generator may take (a quarter of the fuzz smoke's).
fn budget() -> Duration {
    let secs: u64 = std::env::var("PLCRUN_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(25);
    Duration::from_secs(secs.div_ceil(4))
}

type Generator = fn(&mut arbitrary::Unstructured<'_>) -> arbitrary::Result<st_gen::GenProgram>;

/// Generated programs through both engines for the budget (at least 40);
/// returns how many agreed, and how many of those ran wholly natively.
fn generated(seed: u64, generate: Generator) -> (usize, usize) {
    let mut state = seed;
    let start = Instant::now();
    let (mut agreed, mut tried, mut whole) = (0, 0, 0);
    while start.elapsed() < budget() || tried < 40 {
        let data: Vec<u8> = (0..64 + (state % 2048) as usize)
            .map(|_| {
                // xorshift64*: reproducible from the seed.
                state ^= state >> 12;
                state ^= state << 25;
                state ^= state >> 27;
                (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 56) as u8
            })
            .collect();
        let mut u = arbitrary::Unstructured::new(&data);
        let Ok(program) = generate(&mut u) else {
            continue;
        };
        tried += 1;
        if let differential::Verdict::Agree { .. } = differential::check_engines(&program) {
            agreed += 1;
            let files = [("gen.st", program.source.as_str())];
            if let Ok(plc) = Plc::compile_files(&files, &with(Engine::Native)) {
                whole += plc.native_report().is_some_and(|r| r.fell_back.is_empty()) as usize;
            }
        }
    }
    eprintln!("{agreed} generated programs agreed, {whole} of them wholly native");
    (agreed, whole)
}

#[test]
fn generated_st_programs_run_the_same_on_both_engines() {
    let (agreed, whole) = generated(0x5EED_0F0A_7A11_E5E5, st_gen::generate);
    assert!(agreed >= 30, "only {agreed} generated ST programs ran");
    if native_available() {
        assert!(whole * 2 >= agreed, "only {whole} of {agreed} ran natively");
    }
}

#[test]
fn generated_il_programs_run_the_same_on_both_engines() {
    let (agreed, whole) = generated(0x0DDB_A11D_EC0D_E5E5, il_gen::generate);
    assert!(agreed >= 30, "only {agreed} generated IL programs ran");
    if native_available() {
        assert!(whole * 2 >= agreed, "only {whole} of {agreed} ran natively");
    }
}

/// The first fault of `src` on `engine` (within 20 cycles), and whether
/// the faulting program's blocks all ran natively.
fn fault_on(src: &str, engine: Engine) -> (RuntimeFault, bool) {
    let mut plc = Plc::compile_files(&[("f.st", src)], &with(engine)).expect("compiles");
    let whole = plc
        .native_report()
        .is_some_and(|r| r.fell_back.is_empty() && !r.compiled.is_empty());
    for _ in 0..20 {
        if let Err(f) = plc.run_cycle() {
            return (f, whole);
        }
    }
    panic!("no fault in 20 cycles:\n{src}");
}

/// Everything a fault report shows, as text.
fn described(f: &RuntimeFault) -> String {
    format!(
        "{f}\ncode {} at {} cycle {} in {} ({})\ncallers {:?}",
        f.code(),
        f.location,
        f.cycle,
        f.pou,
        f.instance(),
        f.callers()
    )
}

#[test]
fn faults_in_machine_code_are_the_interpreters() {
    let cases = [
        // Division by zero at cycle 3, in the program itself.
        "PROGRAM P VAR n : DINT; d : DINT := 3; q : DINT; END_VAR
         n := n + 1; d := d - 1;
         q := 100 / d; END_PROGRAM",
        // MOD by zero.
        "PROGRAM P VAR n : INT := 2; q : INT; END_VAR
         n := n - 1; q := 7 MOD n; END_PROGRAM",
        // An index out of range, read and written.
        "PROGRAM P VAR a : ARRAY[1..5] OF INT; i : INT; x : INT; END_VAR
         i := i + 2; x := a[i]; END_PROGRAM",
        "PROGRAM P VAR a : ARRAY[0..3] OF LREAL; i : INT := 1; END_VAR
         i := i * 2; a[i] := 1.5; END_PROGRAM",
        // Inside an FB two calls deep: the call path unwinds through
        // machine code.
        "FUNCTION_BLOCK Inner VAR_INPUT k : INT; END_VAR VAR_OUTPUT q : INT; END_VAR
           q := 10 / k; END_FUNCTION_BLOCK
         FUNCTION_BLOCK Outer VAR_INPUT k : INT; END_VAR VAR i : Inner; END_VAR
           i(k := k); END_FUNCTION_BLOCK
         PROGRAM P VAR o : Outer; n : INT := 3; END_VAR
           n := n - 1; o(k := n); END_PROGRAM",
        // In a FUNCTION.
        "FUNCTION Pick : INT VAR_INPUT i : INT; END_VAR VAR t : ARRAY[0..2] OF INT; END_VAR
           Pick := t[i]; END_FUNCTION
         PROGRAM P VAR n : INT; x : INT; END_VAR
           n := n + 1; x := Pick(n); END_PROGRAM",
        // A conversion overflow (out of line).
        "PROGRAM P VAR n : DINT := 32765; s : SINT; END_VAR
         n := n * 2; s := DINT_TO_SINT(n); END_PROGRAM",
    ];
    for src in cases {
        let (interp, _) = fault_on(src, Engine::Interp);
        let (native, whole) = fault_on(src, Engine::Native);
        if native_available() {
            assert!(whole, "not compiled wholly:\n{src}");
        }
        assert_eq!(described(&native), described(&interp), "\n{src}");
    }
}

/// An endless loop in machine code is stopped by the watchdog, which
/// names the loop's back edge as the interpreter does.
#[test]
fn the_watchdog_stops_an_endless_loop_in_machine_code() {
    let src = "PROGRAM P VAR n : DINT; END_VAR
        n := n + 1;
        WHILE n > 0 DO n := n + 1; IF n > 1000 THEN n := 1; END_IF; END_WHILE;
        END_PROGRAM";
    let mut faults = Vec::new();
    for engine in [Engine::Interp, Engine::Native] {
        let options = Options {
            engine,
            watchdog: Some(Duration::from_millis(50)),
            ..Options::default()
        };
        let mut plc = Plc::compile_files(&[("w.st", src)], &options).expect("compiles");
        let fault = plc.run_cycle().expect_err("the watchdog trips");
        assert_eq!(fault.code(), "R008", "{engine}: {fault}");
        faults.push((fault.location.clone(), fault.cycle));
    }
    // The location is one of the loop's back edges on both engines.
    assert_eq!(faults[0].1, faults[1].1);
    let line = |loc: &str| loc.split(':').nth(1).map(str::to_string);
    assert_eq!(line(&faults[0].0), line(&faults[1].0), "{faults:?}");
}

/// Every pair of edge values through the integer, bit and REAL
/// instructions the tier compiles inline, compared after every cycle
/// (all 100 pairs): wrap-around at each width, `MIN / -1`, signed MOD,
/// shift counts at and past the width, NaN and infinities.
#[test]
fn edge_values_compute_the_same_on_both_engines() {
    let source = "PROGRAM P
VAR
  n : DINT;
  i : DINT; j : DINT;
  dv : ARRAY[0..9] OF DINT := [-2147483648, -2147483647, -2, -1, 0, 1, 2, 2147483646, 2147483647, 12345];
  iv : ARRAY[0..9] OF INT := [-32768, -32767, -2, -1, 0, 1, 2, 32766, 32767, 300];
  uv : ARRAY[0..9] OF UDINT := [0, 1, 2, 3, 7, 8, 31, 32, 33, 4294967295];
  rv : ARRAY[0..9] OF REAL := [0.0, -0.0, 1.0, -1.5, 3.4E38, -3.4E38, 1.0E-45, 2.5, 0.1, 100.0];
  lv : ARRAY[0..9] OF LREAL := [0.0, -0.0, 1.0, -1.5, 1.7E308, -1.7E308, 4.9E-324, 2.5, 0.1, 100.0];
  a : DINT; b : DINT; x : INT; y : INT; u : UDINT; w : UDINT;
  add, sub, mul, quo, rem, neg, ab : DINT;
  iadd, isub, imul, iquo, irem : INT;
  uadd, usub, umul, uquo, urem : UDINT;
  lt, le, eq, ne, gt, ge, ult, flt, fle, feq, fne, dlt, dne : BOOL;
  bw : DWORD; bt : BYTE; wd : WORD; lw : LWORD;
  shl1, shr1, rol1, ror1 : DWORD; shb, rob, rrb : BYTE; rlw : LWORD; nw : WORD;
  r, s, radd, rsub, rmul, rdiv, rnan, rneg, rma : REAL;
  l, m, ladd, lsub, lmul, ldiv, lneg : LREAL;
  mn, mx : DINT; sel : DINT;
END_VAR
  i := n MOD 10; j := (n / 10) MOD 10; n := n + 1;
  a := dv[i]; b := dv[j]; x := iv[i]; y := iv[j]; u := uv[i]; w := uv[j];
  add := a + b; sub := a - b; mul := a * b; neg := -a; ab := ABS(a);
  IF b <> 0 THEN quo := a / b; rem := a MOD b; END_IF;
  iadd := x + y; isub := x - y; imul := x * y;
  IF y <> 0 THEN iquo := x / y; irem := x MOD y; END_IF;
  uadd := u + w; usub := u - w; umul := u * w;
  IF w <> 0 THEN uquo := u / w; urem := u MOD w; END_IF;
  lt := a < b; le := a <= b; eq := a = b; ne := a <> b; gt := a > b; ge := a >= b; ult := u < w;
  bw := UDINT_TO_DWORD(u); bt := DWORD_TO_BYTE(bw); wd := DWORD_TO_WORD(bw); lw := DWORD_TO_LWORD(bw) * 16#10001;
  shl1 := SHL(bw, w MOD 40); shr1 := SHR(bw, w MOD 40); rol1 := ROL(bw, w); ror1 := ROR(bw, w MOD 70);
  shb := SHL(bt, w MOD 12); rob := ROL(bt, w); rrb := ROR(bt, w MOD 9); rlw := ROL(lw, w); nw := NOT wd;
  r := rv[i]; s := rv[j];
  radd := r + s; rsub := r - s; rmul := r * s; rdiv := r / s; rneg := -r; rma := r * s + r;
  rnan := (r - r) / (s - s);
  flt := r < s; fle := rnan <= s; feq := rnan = rnan; fne := rnan <> rnan;
  l := lv[i]; m := lv[j];
  ladd := l + m; lsub := l - m; lmul := l * m; ldiv := l / m; lneg := -l;
  dlt := l < m; dne := ladd <> lsub;
  mn := MIN(a, b); mx := MAX(a, b); sel := SEL(lt, a, b);
END_PROGRAM";
    let program = st_gen::GenProgram {
        source: source.to_string(),
        cycles: vec![Vec::new(); 100],
    };
    match differential::check_engines(&program) {
        differential::Verdict::Agree { cycles, fault, .. } => {
            assert_eq!((cycles, fault), (100, None));
        }
        other => panic!("{other:?}"),
    }
    if native_available() {
        let plc = Plc::compile_files(&[("p.st", source)], &with(Engine::Native)).unwrap();
        assert_eq!(fallbacks(&plc), Vec::<String>::new());
    }
}

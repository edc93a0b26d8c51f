//! The fuzz smoke on stable Rust: the bodies of the libFuzzer targets
//! (`fuzz/src/targets.rs`, included here as they are) run over the seed
//! corpus, over mutants of it and over programs from the structure-aware
//! ST and IL generators, each generated program run optimized and
//! unoptimized and compared. Time-boxed (`PLCRUN_FUZZ_SECONDS`, default
//! 25 s for the mutants and 25 s shared by the two generators) so that CI
//! stays short; scripts/fuzz.sh runs the real fuzzer
//! (docs/robustness.md, "Fuzzing").

use crate::fuzz::differential;
use crate::fuzz::il_gen;
use crate::fuzz::seeds;
use crate::fuzz::st_gen;
use crate::fuzz::targets;

use std::path::Path;
use std::time::{Duration, Instant};

/// The time each time-boxed test may take.
fn budget() -> Duration {
    let secs = std::env::var("PLCRUN_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(25);
    Duration::from_secs(secs)
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A small deterministic generator (xorshift64*), so that a failure
/// reproduces.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    fn bytes(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.next() as u8).collect()
    }
}

/// The target bodies by name.
fn target(name: &str) -> fn(&[u8]) {
    match name {
        "lex" => targets::lex,
        "parse" => targets::parse,
        "plcopen" => targets::plcopen,
        "s7" => targets::s7,
        "check" => targets::check,
        "run" => targets::run,
        "gen_il_diff" => targets::gen_il_diff,
        "engines_agree" => targets::engines_agree,
        "modbus" => targets::modbus,
        #[cfg(feature = "opcua")]
        "opcua_write" => targets::opcua_write,
        _ => targets::gen_diff,
    }
}

#[test]
fn every_target_takes_every_seed() {
    let seeds = seeds::collect(root());
    // Source files and the programs inside the Rust tests.
    assert!(seeds.len() > 200, "only {} seeds found", seeds.len());
    for kind in [
        seeds::Kind::Iec,
        seeds::Kind::Il,
        seeds::Kind::S7,
        seeds::Kind::PlcOpen,
    ] {
        assert!(seeds.iter().any(|s| s.kind == kind), "no {kind:?} seed");
    }
    let corpora = seeds::corpora(&seeds);
    // scripts/fuzz.sh writes the libFuzzer corpora through this test.
    if let Ok(dir) = std::env::var("PLCRUN_FUZZ_CORPUS") {
        for (t, name, bytes) in &corpora {
            let d = Path::new(&dir).join(t);
            std::fs::create_dir_all(&d).expect("corpus directory");
            std::fs::write(d.join(name), bytes).expect("corpus file");
        }
    }
    for (t, name, bytes) in &corpora {
        let run = target(t);
        let outcome = std::panic::catch_unwind(|| run(bytes));
        assert!(outcome.is_ok(), "target {t} panicked on seed {name}");
    }
}

/// Bytes that often matter to the front-ends, spliced into mutants.
const DICTIONARY: &[&str] = &[
    ";",
    ":=",
    "(",
    ")",
    "[",
    "]",
    "..",
    ",",
    ".",
    "^",
    "#",
    "'",
    "\"",
    "(*",
    "*)",
    "{",
    "}",
    "//",
    "\n",
    "END_IF",
    "END_FOR",
    "END_VAR",
    "VAR",
    "IF",
    "THEN",
    "FOR",
    "TO",
    "BY",
    "DO",
    "WHILE",
    "CASE",
    "OF",
    "ARRAY[1..3] OF ",
    "STRING[",
    "16#",
    "2#",
    "T#",
    "TIME#",
    "D#",
    "TOD#",
    "LD ",
    "ST ",
    "JMP ",
    "CAL ",
    "%IX0.0",
    "%QW",
    "STEP ",
    "TRANSITION",
    "<pou",
    "</",
    "/>",
    "<",
    ">",
    "NETWORK",
    "=",
    "-",
    "1",
    "0",
    "32767",
    "-2147483648",
    "1E308",
    "\u{FFFD}",
    "\u{0}",
];

/// One random change to `input` (byte flip, deletion, duplication, a
/// dictionary word, a splice of `other`).
fn mutate(rng: &mut Rng, input: &[u8], other: &[u8]) -> Vec<u8> {
    let mut v = input.to_vec();
    let at = rng.below(v.len() + 1);
    match rng.below(6) {
        0 if !v.is_empty() => {
            let i = rng.below(v.len());
            v[i] ^= 1 << rng.below(8);
        }
        1 if !v.is_empty() => {
            let end = (at + 1 + rng.below(16)).min(v.len());
            v.drain(at.min(end)..end);
        }
        2 => {
            let end = (at + 1 + rng.below(64)).min(v.len());
            let piece = v[at.min(end)..end].to_vec();
            v.splice(at..at, piece);
        }
        3 if !other.is_empty() => {
            let from = rng.below(other.len());
            let end = (from + 1 + rng.below(256)).min(other.len());
            v.splice(at..at, other[from..end].iter().copied());
        }
        _ => {
            let word = DICTIONARY[rng.below(DICTIONARY.len())];
            v.splice(at..at, word.bytes());
        }
    }
    v
}

#[test]
fn mutants_of_the_seeds_do_not_crash_any_target() {
    let seeds = seeds::collect(root());
    let corpora = seeds::corpora(&seeds);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let start = Instant::now();
    let mut runs = 0usize;
    while start.elapsed() < budget() || runs < 500 {
        let (t, name, bytes) = &corpora[rng.below(corpora.len())];
        let (_, _, other) = &corpora[rng.below(corpora.len())];
        let mut input = bytes.clone();
        for _ in 0..1 + rng.below(4) {
            input = mutate(&mut rng, &input, other);
        }
        let run = target(t);
        let outcome = std::panic::catch_unwind(|| run(&input));
        assert!(
            outcome.is_ok(),
            "target {t} panicked on a mutant of {name}:\n{}",
            String::from_utf8_lossy(&input)
        );
        runs += 1;
    }
    eprintln!("{runs} mutants in {:.1} s", start.elapsed().as_secs_f64());
}

/// What one generator's programs gave through the differential check.
#[derive(Default)]
struct GenStats {
    agreed: usize,
    refused: usize,
    faults: std::collections::BTreeMap<&'static str, usize>,
    fused: [usize; differential::FUSED.len()],
    refusals: std::collections::BTreeMap<String, usize>,
    example: std::collections::BTreeMap<String, String>,
}

type Generator = fn(&mut arbitrary::Unstructured<'_>) -> arbitrary::Result<st_gen::GenProgram>;

/// Programs of `generate` through the differential check for `budget`
/// (and at least 100 programs); fails on a disagreement (in the check)
/// or when more than one in ten is refused (a generator bug).
fn run_generator(name: &str, seed: u64, generate: Generator, budget: Duration) -> GenStats {
    let mut rng = Rng(seed);
    let start = Instant::now();
    let mut st = GenStats::default();
    while start.elapsed() < budget || st.agreed + st.refused < 100 {
        let len = 64 + rng.below(4096);
        let data = rng.bytes(len);
        let mut u = arbitrary::Unstructured::new(&data);
        let Ok(program) = generate(&mut u) else {
            continue;
        };
        match differential::check(&program) {
            differential::Verdict::Agree {
                fault, fused: f, ..
            } => {
                st.agreed += 1;
                if let Some(code) = fault {
                    *st.faults.entry(code).or_default() += 1;
                }
                for (total, n) in st.fused.iter_mut().zip(f) {
                    *total += n;
                }
            }
            differential::Verdict::Refused { codes } => {
                st.refused += 1;
                let key = codes.join(",");
                *st.refusals.entry(key.clone()).or_default() += 1;
                st.example.entry(key).or_insert(program.source);
            }
            differential::Verdict::Watchdog => {}
        }
    }
    eprintln!(
        "{name}: {} generated programs agreed ({} ended in a fault: {:?}), {} refused {:?}, in {:.1} s",
        st.agreed,
        st.faults.values().sum::<usize>(),
        st.faults,
        st.refused,
        st.refusals,
        start.elapsed().as_secs_f64()
    );
    for (fused, n) in differential::FUSED.iter().zip(st.fused) {
        eprintln!("  {fused}: {n}");
    }
    if std::env::var_os("PLCRUN_FUZZ_VERBOSE").is_some() {
        for (codes, source) in &st.example {
            eprintln!("--- refused with {codes}:\n{source}");
        }
    }
    // The generators write type-correct programs: a refusal can only be a
    // constant expression that overflows or divides by zero.
    assert!(
        st.refused * 10 <= st.agreed,
        "{name}: too many generated programs refused: {:?}\n{:#?}",
        st.refusals,
        st.example
    );
    st
}

#[test]
fn generated_programs_run_the_same_optimized_and_unoptimized() {
    let st = run_generator("ST", 0xD1B5_4A32_D192_ED03, st_gen::generate, budget() / 2);
    // The optimizations are reached (the fused forms that the generator's
    // shapes produce).
    for (name, n) in differential::FUSED.iter().zip(st.fused) {
        if !matches!(*name, "JnCmpF32" | "JnCmpF64" | "OrN") {
            assert!(n > 0, "no generated program used {name}");
        }
    }
}

#[test]
fn generated_il_programs_run_the_same_optimized_and_unoptimized() {
    let st = run_generator("IL", 0x8CB9_2BA7_2F3D_8DD7, il_gen::generate, budget() / 2);
    // The fused forms IL lowering reaches: `ANDN`/`ORN` (and `AND(` over
    // a negated operand) become AndN/OrN.
    for name in ["AndN", "OrN"] {
        let at = differential::FUSED.iter().position(|f| *f == name);
        let n = at.map_or(0, |i| st.fused[i]);
        assert!(n > 0, "no generated IL program used {name}");
    }
    // Most IL programs run to the end or to a fault both builds agree on.
    assert!(st.agreed >= 90, "only {} IL programs ran", st.agreed);
}

#[test]
fn the_programs_and_benches_run_the_same_unoptimized() {
    let mut files = Vec::new();
    for dir in ["benches/programs", "programs"] {
        for entry in std::fs::read_dir(root().join(dir)).expect("directory") {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "st") {
                files.push(path);
            }
        }
    }
    files.sort();
    let mut fused = 0;
    for path in &files {
        let program = st_gen::GenProgram {
            source: std::fs::read_to_string(path).expect("source"),
            cycles: vec![Vec::new(); 3],
        };
        match differential::check(&program) {
            differential::Verdict::Agree { fused: f, .. } => fused += f.iter().sum::<usize>(),
            other => panic!("{}: {other:?}", path.display()),
        }
    }
    // The benchmarks use the fused forms (a fill, a sieve, scans).
    assert!(fused > 0, "no fused instruction in {files:?}");
}

/// `count` mutants (up to `depth` changes each) of `seeds` through
/// `target`, which must not panic; counted rather than timed, for the
/// fast targets.
fn counted_mutants(
    what: &str,
    seeds: &[(String, Vec<u8>)],
    target: fn(&[u8]),
    count: usize,
    depth: usize,
    rng: &mut Rng,
) {
    for n in 0..count {
        let (name, bytes) = &seeds[rng.below(seeds.len())];
        let (_, other) = &seeds[rng.below(seeds.len())];
        let mut input = bytes.clone();
        for _ in 0..1 + rng.below(depth) {
            input = mutate(rng, &input, other);
        }
        let outcome = std::panic::catch_unwind(|| target(&input));
        assert!(
            outcome.is_ok(),
            "mutant {n} of {name} broke the {what}: {input:?}"
        );
    }
}

/// The Modbus request path is fast (microseconds an input): it gets its
/// own run of mutants, counted rather than timed, on top of its share of
/// the timed one.
#[test]
fn modbus_request_path_survives_mutated_streams() {
    let seeds = targets::modbus_seeds();
    let mut rng = Rng(0xD1B5_4A32_D192_ED03);
    counted_mutants(
        "Modbus request path",
        &seeds,
        targets::modbus,
        20_000,
        6,
        &mut rng,
    );
}

/// The OPC UA Write path: mutants of encoded WriteRequests, counted.
#[cfg(feature = "opcua")]
#[test]
fn opcua_write_path_survives_mutated_requests() {
    let seeds = targets::opcua_write_seeds();
    assert!(seeds.len() > 20, "only {} seeds", seeds.len());
    // The seeds reach the checks and the PLC: each writable variable's
    // own request is accepted, and so are all of them together.
    let mut plc = plcrun::fuzzing::OpcUaWriteFuzz::new();
    let (_, all) = seeds.iter().find(|(n, _)| n == "write_all").unwrap();
    let accepted = plc.feed(all);
    eprintln!(
        "write_all: {accepted} of {} writes accepted",
        seeds.len() - 1
    );
    assert!(accepted >= 30, "only {accepted} seed writes accepted");
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    counted_mutants(
        "OPC UA write path",
        &seeds,
        targets::opcua_write,
        3_000,
        4,
        &mut rng,
    );
}

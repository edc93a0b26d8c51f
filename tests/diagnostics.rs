//! Compile-time diagnostics: one small broken program per code, with the
//! code and the `line:col` it must be reported at (worked out by counting
//! characters in the source); several errors in one file all reported;
//! `plcrun check` exit status; and no panic on malformed input (random
//! bytes, truncations and mutations of the real programs).
//!
//! Every code here has a section in docs/diagnostics.md (checked below).

use plcrun::{Diagnostics, FileId, Severity};
use plcrun::{Options, Plc};
use rstest::rstest;

/// `PROGRAM P` with `decls` on line 3 and `body` on line 5.
fn prog(decls: &str, body: &str) -> String {
    format!("PROGRAM P\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n")
}

/// Same after a prelude, which must be a single line (so `decls` stays on
/// line 4 and `body` on line 6).
fn prog_after(prelude: &str, decls: &str, body: &str) -> String {
    assert!(!prelude.contains('\n'));
    format!("{prelude}\n{}", prog(decls, body))
}

/// Every diagnostic as (code, severity, `line:col`, message).
fn diagnostics(src: &str) -> Vec<(String, Severity, String, String)> {
    let collect = |diags: &Diagnostics, sources: &plcrun::SourceMap| {
        diags
            .iter()
            .map(|d| {
                let loc = sources.location(d.span);
                let lc = loc.split_once(':').map(|x| x.1).unwrap_or("").to_string();
                (d.code.to_string(), d.severity, lc, d.message.clone())
            })
            .collect::<Vec<_>>()
    };
    match Plc::compile_files(&[("t.st", src)], &Options::default()) {
        Ok(p) => collect(p.warnings(), p.sources()),
        Err(e) => collect(&e.diagnostics, &e.sources),
    }
}

fn check_error(code: &str, src: &str, at: &str) {
    let diags = diagnostics(src);
    let errors: Vec<_> = diags.iter().filter(|d| d.1 == Severity::Error).collect();
    let found = errors
        .iter()
        .any(|d| d.0 == code && (d.2 == at || (at.ends_with(':') && d.2.starts_with(at))));
    assert!(found, "expected {code} at {at} for\n{src}\ngot {errors:#?}");
    // The example is about this code: it comes first.
    assert_eq!(errors[0].0, code, "first error for\n{src}\ngot {errors:#?}");
}

const F1: &str = "FUNCTION F : INT VAR_INPUT a : INT; END_VAR F := a; END_FUNCTION";
const F2: &str = "FUNCTION F : INT VAR_INPUT a, b : INT; END_VAR F := a + b; END_FUNCTION";
const INC: &str =
    "FUNCTION Inc : BOOL VAR_IN_OUT v : INT; END_VAR v := v + 1; Inc := TRUE; END_FUNCTION";

#[rstest]
// ---- E0xx: lexical
#[case("E001", prog("x : INT;", "x := 1; ?"), "5:9")]
#[case("E002", prog("x : INT;", "x := 1; (* never closed"), "5:9")]
#[case("E002", prog("x : INT;", "x := 1; /* never closed"), "5:9")]
#[case("E003", prog("s : STRING;", "s := 'abc;"), "5:6")]
#[case("E004", prog("s : STRING;", "s := 'a$Zb';"), "5:8")]
#[case("E005", prog("x : INT;", "x := 16#_FF;"), "5:6")]
#[case(
    "E005",
    prog("x : LINT;", "x := 999999999999999999999999999999999999999999;"),
    "5:6"
)]
#[case("E006", prog("t : TIME;", "t := T#5x;"), "5:6")]
#[case("E007", prog("d : DATE;", "d := D#2024-13-01;"), "5:6")]
#[case("E007", prog("d : TOD;", "d := TOD#25:00:00;"), "5:6")]
#[case("E008", prog("b : BOOL;", "b := BOOL#2;"), "5:6")]
#[case("E009", prog("x AT %IY1 : BOOL;", ""), "3:6")]
#[case("E010", prog("x : INT;", "x := 1; { never closed"), "5:9")]
// ---- E1xx: syntax
#[case("E101", prog("x : INT;", "x := ;"), "5:6")]
// reported just after the last token
#[case("E102", "PROGRAM P\nVAR x : INT; END_VAR\nx := 1;\n".to_string(), "4:1")]
#[case("E103", prog("x : INT;", "x;"), "5:1")]
#[case(
    "E104",
    "PROGRAM P\nVAR x : BOOL; END_VAR\nINITIAL_STEP S0: A(N, 5); END_STEP\nEND_PROGRAM\n".to_string(),
    "3:23"
)]
#[case(
    "E105",
    "PROGRAM P\nINITIAL_STEP S0: END_STEP\nSTEP S1: END_STEP\nTRANSITION (PRIO := 1) FROM S0 TO S1 := TRUE; END_TRANSITION\nEND_PROGRAM\n".to_string(),
    "4:13"
)]
// 250 nested negations; the innermost node deeper than 200 levels is the
// 51st `-` (column 6 + 50): it has 200 `-` and the `x` below it
#[case("E106", prog("x : INT;", &format!("x := {}x;", "-".repeat(250))), "5:56")]
#[case(
    "E107",
    prog("x : INT;", "CASE x OF x := 1; 1: x := 2; END_CASE;"),
    "5:11"
)]
#[case("E108", prog("w : WORD; b : BOOL;", "b := w.64;"), "5:8")]
#[case("E426", prog("x : BOOL R_EDGE;", ""), "3:1")]
#[case("E110", "METHOD M\nEND_METHOD\n".to_string(), "1:1")]
#[case("E111", "VAR x : INT; END_VAR\nPROGRAM P\nEND_PROGRAM\n".to_string(), "1:1")]
// ---- E2xx: names and declarations
#[case("E201", prog("x : INT;", "y := 1;"), "5:1")]
#[case("E201", prog("t : TON;", "t(IN := TRUE); x := t.QQ;"), "5:")]
#[case("E202", prog("x : INT; x : BOOL;", ""), "3:10")]
#[case("E202", format!("FUNCTION_BLOCK TON\nEND_FUNCTION_BLOCK\n{}", prog("", "")), "1:16")]
#[case("E203", prog("x : FOO;", ""), "3:5")]
#[case(
    "E204",
    "FUNCTION_BLOCK B\nVAR inner : B; END_VAR\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR b : B; END_VAR\nEND_PROGRAM\n".to_string(),
    "1:16"
)]
#[case("E205", prog("x : INT; a : ARRAY[1..x] OF INT;", ""), "3:23")]
#[case("E205", "PROGRAM P\nVAR CONSTANT c : INT; END_VAR\nEND_PROGRAM\n".to_string(), "2:14")]
#[case("E206", prog("a : ARRAY[5..1] OF INT;", ""), "3:")]
#[case("E206", prog("s : STRING[0];", ""), "3:")]
#[case("E207", prog("x AT %IW0 : BOOL;", ""), "3:")]
#[case("E208", "FUNCTION F : INT\nF := 1;\nEND_FUNCTION\n".to_string(), "1:")]
#[case(
    "E209",
    "PROGRAM Q\nEND_PROGRAM\nPROGRAM P\nVAR q : Q; END_VAR\nEND_PROGRAM\n".to_string(),
    "4:9"
)]
#[case("E210", "FUNCTION_BLOCK F\nVAR_TEMP RETAIN t : INT; END_VAR\nEND_FUNCTION_BLOCK\nPROGRAM P\nEND_PROGRAM\n".to_string(), "2:1")]
#[case("E210", "VAR_GLOBAL CONSTANT RETAIN g : INT := 1; END_VAR\nPROGRAM P\nEND_PROGRAM\n".to_string(), "1:1")]
// ---- E3xx: types
#[case("E301", prog("i : INT;", "i := TRUE;"), "5:6")]
#[case("E301", prog("i : INT; d : DINT;", "i := d;"), "5:6")]
#[case("E302", prog("r : REAL; b : BOOL;", "b := NOT r;"), "5:")]
#[case("E303", prog("i : INT;", "IF i THEN i := 0; END_IF;"), "5:4")]
#[case("E304", prog("a : ARRAY[1..3] OF INT;", "a[5] := 1;"), "5:3")]
#[case("E304", prog("s : SINT := 300;", ""), "3:")]
#[case("E305", prog("i : INT;", "i := INT#32767 + 1;"), "5:6")]
#[case("E306", prog("t : TIME; i : INT;", "t := t + i;"), "5:6")]
// ---- E4xx: statements and calls
#[case("E401", "PROGRAM P\nVAR CONSTANT c : INT := 1; END_VAR\nc := 2;\nEND_PROGRAM\n".to_string(), "3:1")]
#[case("E401", "PROGRAM P\nVAR CONSTANT c : INT := 1; END_VAR\nFOR c := 1 TO 3 DO END_FOR;\nEND_PROGRAM\n".to_string(), "3:5")]
#[case("E402", prog("x : INT;", "LD 1\nST 5"), "6:4")]
#[case("E403", prog("t : TON;", "t(IN := TRUE, FOO := 1);"), "5:15")]
#[case("E404", prog_after(F1, "x : INT;", "x := F(1, 2);"), "6:6")]
#[case("E405", prog("x : INT;", "EXIT;"), "5:1")]
#[case("E405", prog("x : INT;", "CONTINUE;"), "5:1")]
#[case("E406", prog("b : BOOL;", "b := TON(IN := TRUE);"), "5:6")]
#[case("E406", prog("x : INT;", "x := x(1);"), "5:6")]
#[case("E407", prog("r : REAL;", "FOR r := 1.0 TO 2.0 DO END_FOR;"), "5:5")]
#[case("E407", prog("i : INT;", "FOR i := 1 TO 2 BY 0 DO END_FOR;"), "5:")]
#[case(
    "E408",
    prog("i : INT;", "CASE i OF 1: i := 0; 1: i := 2; END_CASE;"),
    "5:22"
)]
#[case("E408", prog("i : INT;", "CASE i OF 5..1: i := 0; END_CASE;"), "5:11")]
#[case(
    "E409",
    "FUNCTION F : INT\nVAR_INPUT n : INT; END_VAR\nF := G(n - 1);\nEND_FUNCTION\nFUNCTION G : INT\nVAR_INPUT n : INT; END_VAR\nG := F(n);\nEND_FUNCTION\nPROGRAM P\nVAR x : INT; END_VAR\nx := F(1);\nEND_PROGRAM\n".to_string(),
    "7:6"
)]
#[case("E411", prog_after(F2, "x : INT;", "x := F(a := 1, 2);"), "6:16")]
#[case("E435", prog("p : POINTER TO INT;", "p := __NEW(INT);"), "5:6")]
#[case("E436", prog("t : TON := (RUNNING := TRUE);", ""), "3:13")]
#[case("E212", prog("x : ANY;", ""), "3:5")]
#[case(
    "E439",
    prog_after(
        "FUNCTION F : INT VAR_INPUT v : ANY_NUM; END_VAR F := 1; END_FUNCTION",
        "s : STRING; i : INT;",
        "i := F(s);"
    ),
    "6:8"
)]
#[case(
    "E440",
    prog_after(
        "FUNCTION F : INT VAR_INPUT v : ANY; END_VAR F := 1; END_FUNCTION",
        "t : TON; i : INT;",
        "i := F(t);"
    ),
    "6:8"
)]
#[case("E402", prog_after(INC, "x : INT;", "Inc(v := 5);"), "6:10")]
#[case("E412", format!("{INC}\nPROGRAM P\nVAR CONSTANT c : INT := 1; END_VAR\nInc(v := c);\nEND_PROGRAM\n"), "4:10")]
// ---- E5xx: IL
#[case("E501", "PROGRAM P\nVAR x : INT; END_VAR\n    LD 1\n    )\n    ST x\nEND_PROGRAM\n".to_string(), "4:5")]
#[case("E502", "PROGRAM P\nVAR x : INT; END_VAR\n    JMP nowhere\n    LD INT#1\n    ST x\nEND_PROGRAM\n".to_string(), "3:9")]
#[case("E503", "PROGRAM P\nVAR x : INT; END_VAR\nL1: LD 1\nL1: ST x\nEND_PROGRAM\n".to_string(), "4:1")]
#[case("E504", "PROGRAM P\nVAR x : INT; END_VAR\n    LD 1\n    ST\nEND_PROGRAM\n".to_string(), "4:5")]
#[case("E505", "PROGRAM P\nVAR x : INT; END_VAR\n    ST x\nEND_PROGRAM\n".to_string(), "3:5")]
#[case("E506", "PROGRAM P\nVAR x : INT; END_VAR\n    LD 5\n    JMPC L1\nL1: ST x\nEND_PROGRAM\n".to_string(), "4:5")]
// ---- E6xx: SFC
#[case("E601", "FUNCTION F : INT\nINITIAL_STEP S0: END_STEP\nEND_FUNCTION\n".to_string(), "1:10")]
// ---- E7xx: configurations
#[case(
    "E701",
    "PROGRAM P\nEND_PROGRAM\nCONFIGURATION A\nRESOURCE R ON PLC\nTASK T (INTERVAL := T#10ms);\nPROGRAM i WITH T : P;\nEND_RESOURCE\nEND_CONFIGURATION\nCONFIGURATION B\nRESOURCE R ON PLC\nTASK T (INTERVAL := T#10ms);\nPROGRAM i WITH T : P;\nEND_RESOURCE\nEND_CONFIGURATION\n".to_string(),
    "9:15"
)]
#[case(
    "E702",
    "PROGRAM P\nEND_PROGRAM\nCONFIGURATION A\nRESOURCE R ON PLC\nTASK T (INTERVAL := 5);\nPROGRAM i WITH T : P;\nEND_RESOURCE\nEND_CONFIGURATION\n".to_string(),
    "5:21"
)]
#[case(
    "E703",
    "PROGRAM P\nVAR_INPUT x : INT; END_VAR\nEND_PROGRAM\nCONFIGURATION A\nRESOURCE R ON PLC\nTASK T (INTERVAL := T#10ms);\nPROGRAM i WITH T : P(z := 1);\nEND_RESOURCE\nEND_CONFIGURATION\n".to_string(),
    "7:22"
)]
#[case(
    "E703",
    "PROGRAM P\nVAR_OUTPUT y : BOOL; END_VAR\nEND_PROGRAM\nCONFIGURATION A\nRESOURCE R ON PLC\nTASK T (INTERVAL := T#10ms);\nPROGRAM i WITH T : P(y => %IX0.0);\nEND_RESOURCE\nEND_CONFIGURATION\n".to_string(),
    "7:27"
)]
#[case(
    "E207",
    "PROGRAM P\nVAR_INPUT x : BOOL; END_VAR\nEND_PROGRAM\nCONFIGURATION A\nRESOURCE R ON PLC\nTASK T (INTERVAL := T#10ms);\nPROGRAM i WITH T : P(x := %IW2);\nEND_RESOURCE\nEND_CONFIGURATION\n".to_string(),
    "7:27"
)]
#[case(
    "E433",
    prog_after(
        "{attribute 'qualified_only'} TYPE E_Mode : (Idle, Run); END_TYPE",
        "m : E_Mode;",
        "m := Run;"
    ),
    "6:6"
)]
#[case("E434", "FUNCTION_BLOCK F\nVAR_INST n : INT; END_VAR\nEND_FUNCTION_BLOCK\n".to_string(), "2:1")]
fn each_error_code_at_its_place(#[case] code: &str, #[case] src: String, #[case] at: &str) {
    check_error(code, &src, at);
}

#[rstest]
#[case("W001", prog("x : INT;", "{ a pragma } x := 1;"), "5:1")]
#[case(
    "W155",
    prog("x : INT;", "{attribute 'pytmc' := 'pv: X'} x := 1;"),
    "5:1"
)]
#[case("W202", prog("x AT %IX0.0 : BOOL;", "x := TRUE;"), "5:1")]
#[case("W204", prog("c AT %QX0.0 : BOOL; r AT %QW0 : INT;", ""), "3:26")]
#[case(
    "W485",
    prog_after("TYPE E : (A, B := 5); END_TYPE", "n : DINT;", "n := E.B + 1;"),
    "6:6"
)]
#[case(
    "W486",
    prog_after("TYPE E : (A, B := 5); END_TYPE", "e : E;", "e := 5;"),
    "6:6"
)]
#[case("W487", prog_after(F2, "x : INT;", "x := F(1, b := 2);"), "6:6")]
#[case("W488", prog("i, j : INT;", "j := i AND 3;"), "5:6")]
#[case("W489", prog("a, b : TON;", "b := a;"), "5:1")]
fn warnings_do_not_stop_the_program(#[case] code: &str, #[case] src: String, #[case] at: &str) {
    let mut plc = Plc::compile_files(&[("t.st", &src)], &Options::default())
        .unwrap_or_else(|e| panic!("a warning must not fail the compilation:\n{e}"));
    let w: Vec<_> = diagnostics(&src)
        .into_iter()
        .filter(|d| d.1 == Severity::Warning)
        .collect();
    assert!(
        w.iter().any(|d| d.0 == code && d.2 == at),
        "expected {code} at {at}, got {w:#?}"
    );
    plc.run_cycle().unwrap();
}

/// Every code in the table above has a section in docs/diagnostics.md, and
/// every section is for a code the table tests (or is a placeholder).
#[test]
fn every_code_is_documented() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/diagnostics.md"))
        .expect("docs/diagnostics.md");
    let this = std::fs::read_to_string(file!()).unwrap();
    let mut tested: Vec<String> = Vec::new();
    for line in this.lines() {
        let l = line.trim_start();
        for prefix in ["#[case(\"E", "#[case(\"W", "\"E", "\"W"] {
            if let Some(rest) = l.strip_prefix(prefix)
                && rest.len() >= 4
                && rest[..3].chars().all(|c| c.is_ascii_digit())
                && rest.as_bytes()[3] == b'"'
            {
                tested.push(format!("{}{}", &prefix[prefix.len() - 1..], &rest[..3]));
            }
        }
    }
    tested.sort();
    tested.dedup();
    assert!(tested.len() > 50, "{tested:?}");
    for code in &tested {
        assert!(
            doc.contains(&format!("## {code}")),
            "{code} has no section `## {code}` in docs/diagnostics.md"
        );
    }
}

/// IEC 61131-3 forbids changing the FOR control variable in the loop body.
#[test]
fn assigning_the_for_control_variable_in_the_loop_is_an_error() {
    check_error(
        "E401",
        &prog("i : INT;", "FOR i := 1 TO 3 DO i := 5; END_FOR;"),
        "5:20",
    );
}

// ---------------------------------------------------------------- several errors

#[test]
fn all_errors_of_a_file_are_reported() {
    let src = prog(
        "i : INT; b : BOOL;",
        "i := TRUE; IF i THEN b := 1.5; END_IF; y := 0; EXIT;",
    );
    let codes: Vec<String> = diagnostics(&src)
        .into_iter()
        .filter(|d| d.1 == Severity::Error)
        .map(|d| format!("{}@{}", d.0, d.2))
        .collect();
    // "i := TRUE; IF i THEN b := 1.5; END_IF; y := 0; EXIT;"
    //  1234567890123456789012345678901234567890123456789012
    for expected in [
        "E301@5:6",
        "E303@5:15",
        "E304@5:27",
        "E201@5:40",
        "E405@5:48",
    ] {
        assert!(
            codes.contains(&expected.to_string()),
            "{expected} missing from {codes:?}"
        );
    }
}

#[test]
fn syntax_errors_in_several_places_are_all_reported() {
    let src = "PROGRAM P\nVAR x : INT; END_VAR\nx := ;\nx := 1;\nx := * 2;\nEND_PROGRAM\n";
    let errs: Vec<String> = diagnostics(src)
        .into_iter()
        .filter(|d| d.0 == "E101")
        .map(|d| d.2)
        .collect();
    assert!(errs.contains(&"3:6".to_string()), "{errs:?}");
    assert!(errs.contains(&"5:6".to_string()), "{errs:?}");
}

#[test]
fn errors_in_several_files_name_their_file() {
    let a = prog("x : INT;", "x := y;");
    let b = "FUNCTION G : INT\nG := TRUE;\nEND_FUNCTION\n";
    let err = Plc::compile_files(&[("a.st", &a), ("b.st", b)], &Options::default())
        .err()
        .expect("errors");
    let locs: Vec<String> = err
        .diagnostics
        .iter()
        .map(|d| format!("{} {}", d.code, err.sources.location(d.span)))
        .collect();
    assert!(locs.contains(&"E201 a.st:5:6".to_string()), "{locs:?}");
    assert!(locs.contains(&"E301 b.st:2:6".to_string()), "{locs:?}");
}

// ---------------------------------------------------------------- plcrun check

use crate::support::cli;
use cli::{plcrun, temp_file};

#[test]
fn check_exits_0_on_good_sources_even_with_warnings() {
    let (code, _, err) = plcrun(&["check", "programs/comparator.st", "programs/cmd_monitor.st"]);
    assert_eq!(code, 0, "{err}");
    let warn = temp_file("warn.st", prog("x : INT;", "{ pragma } x := 1;"));
    let (code, _, err) = plcrun(&["check", &warn]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("W001"), "{err}");
}

#[test]
fn check_exits_1_and_prints_every_error_with_its_place() {
    let bad = temp_file("bad.st", prog("x : INT;", "y := 1; x := TRUE;"));
    let (code, _, err) = plcrun(&["check", &bad]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("error[E201]"), "{err}");
    assert!(err.contains("bad.st:5:1"), "{err}");
    assert!(err.contains("error[E301]"), "{err}");
    assert!(err.contains("bad.st:5:14"), "{err}");
}

/// Through the library calls `plcrun check` makes: read the files, check
/// them, render what was found.
#[test]
fn check_reports_invalid_utf8() {
    let mut bytes = prog("x : INT;", "x := 1;").into_bytes();
    bytes.extend_from_slice(b"(* \xff\xfe *)\n");
    let f = temp_file("latin.st", bytes);
    let mut diags = Diagnostics::new();
    let sources = plcrun::load_files(&[&f], &mut diags).expect("the file is readable");
    diags.extend(plcrun::check(&sources, &plcrun::CheckOptions::default()).diagnostics);
    let err = diags.render(&sources);
    assert!(diags.has_errors(), "{err}");
    assert!(err.contains("E011"), "{err}");
}

#[test]
fn check_of_a_missing_file_is_a_usage_error() {
    let (code, _, _) = plcrun(&["check", "no/such/file.st"]);
    assert_eq!(code, 2);
}

// ---------------------------------------------------------------- robustness

use crate::support::rng;
use rng::Rng;

/// Parses and compiles `text`; must not panic, whatever it is.
fn must_not_panic(text: &str) {
    let mut d = Diagnostics::new();
    let _ = plcrun::syntax::parse(FileId(0), text, &mut d);
    let _ = Plc::compile_files(&[("fuzz.st", text)], &Options::default());
}

fn seed_sources() -> Vec<String> {
    let root = env!("CARGO_MANIFEST_DIR");
    [
        "programs/alg01.il",
        "programs/alg02.il",
        "programs/cmd_monitor.st",
        "programs/comparator.st",
        "stdlib/ton.st",
        "stdlib/ctud.st",
    ]
    .iter()
    .map(|p| std::fs::read_to_string(format!("{root}/{p}")).unwrap())
    .collect()
}

/// Runs `make(rng, seeds)` `n` times, checking for panics and reporting the
/// input that made one.
fn fuzz(n: usize, seed: u64, make: impl Fn(&mut Rng, &[String]) -> String) {
    let seeds = seed_sources();
    let mut rng = Rng(seed);
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut failure = None;
    for i in 0..n {
        let text = make(&mut rng, &seeds);
        if std::panic::catch_unwind(|| must_not_panic(&text)).is_err() {
            failure = Some((i, text));
            break;
        }
    }
    std::panic::set_hook(hook);
    if let Some((i, text)) = failure {
        panic!("case {i} panicked on input:\n{text:?}");
    }
}

const PIECES: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    ":=",
    ";",
    ":",
    ",",
    ".",
    "..",
    "#",
    "%IX0.1",
    "'",
    "\"",
    "(*",
    "*)",
    "{",
    "}",
    "IF",
    "THEN",
    "END_IF",
    "FOR",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "CASE",
    "OF",
    "END_CASE",
    "VAR",
    "END_VAR",
    "PROGRAM",
    "END_PROGRAM",
    "FUNCTION_BLOCK",
    "T#",
    "16#",
    "2#1",
    "1.5E",
    "=>",
    "**",
    "-",
    "NOT",
    "LD",
    "ST",
    "JMPC",
    "CAL",
    "\n",
    " ",
    "x",
    "1",
    "ARRAY",
    "STRUCT",
    "STEP",
    "TRANSITION",
    "$",
    "\u{e9}",
    "\u{1F600}",
    "\0",
];

#[test]
fn random_bytes_do_not_panic() {
    fuzz(800, 0x1234_5678_9ABC_DEF1, |rng, _| {
        let len = rng.below(200);
        let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        String::from_utf8_lossy(&bytes).into_owned()
    });
}

#[test]
fn random_token_soup_does_not_panic() {
    fuzz(800, 0x0F0F_1234_5555_AAAB, |rng, _| {
        (0..rng.below(120))
            .map(|_| PIECES[rng.below(PIECES.len())])
            .collect::<Vec<_>>()
            .join(if rng.below(2) == 0 { " " } else { "" })
    });
}

#[test]
fn truncated_programs_do_not_panic() {
    let seeds = seed_sources();
    let mut n = 0;
    for s in &seeds {
        let chars: Vec<(usize, char)> = s.char_indices().collect();
        // 60 cuts per seed (each a whole compile in a debug build): the
        // fuzz smoke's mutants (tests/fuzz_smoke.rs) cut and splice these
        // seeds further, time-boxed, within CI's budget.
        let step = (chars.len() / 60).max(1);
        for (i, _) in chars.iter().step_by(step) {
            must_not_panic(&s[..*i]);
            n += 1;
        }
    }
    assert!(n > 300, "{n} truncations");
}

#[test]
fn mutated_programs_do_not_panic() {
    // 400 mutants here; the fuzz smoke runs more of the same kind on every
    // fuzz target for its time box.
    fuzz(400, 0xDEAD_BEEF_0BAD_F00D, |rng, seeds| {
        let mut s: Vec<char> = seeds[rng.below(seeds.len())].chars().collect();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(s.len());
            match rng.below(4) {
                0 => {
                    s.remove(at);
                }
                1 => {
                    let p = PIECES[rng.below(PIECES.len())];
                    for (k, c) in p.chars().enumerate() {
                        s.insert(at + k, c);
                    }
                }
                2 => {
                    let end = (at + rng.below(40)).min(s.len());
                    s.drain(at..end);
                }
                _ => {
                    // duplicate a slice somewhere else
                    let end = (at + rng.below(60)).min(s.len());
                    let piece: Vec<char> = s[at..end].to_vec();
                    let to = rng.below(s.len());
                    for (k, c) in piece.into_iter().enumerate() {
                        s.insert(to + k, c);
                    }
                }
            }
        }
        s.into_iter().collect()
    });
}

/// docs/diagnostics.md: unsupported words are reported as such (E110).
/// (`REF_TO`, the word this test used, is supported now: tests/references.rs.)
#[test]
fn an_unsupported_word_is_reported_as_such() {
    check_error("E110", &prog("p : NAMESPACE;", ""), "3:5");
}

/// Every code the sources can emit has its section in docs/diagnostics.md.
#[test]
fn every_emitted_code_is_documented() {
    fn scan(dir: &std::path::Path, codes: &mut std::collections::BTreeSet<String>) {
        for entry in std::fs::read_dir(dir).expect("read src") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                scan(&path, codes);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path).expect("read file");
                for (i, _) in text.match_indices('"') {
                    let code = text.get(i + 1..i + 5).unwrap_or("");
                    let quoted = text.get(i + 5..i + 6) == Some("\"");
                    let shaped = code.len() == 4
                        && matches!(code.as_bytes()[0], b'E' | b'W')
                        && code[1..].bytes().all(|b| b.is_ascii_digit());
                    if quoted && shaped {
                        codes.insert(code.to_string());
                    }
                }
            }
        }
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut codes = std::collections::BTreeSet::new();
    scan(&root.join("src"), &mut codes);
    let docs = std::fs::read_to_string(root.join("docs/diagnostics.md")).expect("docs");
    let missing: Vec<&String> = codes
        .iter()
        .filter(|c| !docs.contains(&format!("## {c}\n")))
        .collect();
    assert!(codes.len() > 50, "found only {} codes", codes.len());
    assert!(missing.is_empty(), "undocumented codes: {missing:?}");
}

/// Declarations too large for PLC memory are errors, not crashes.
#[test]
fn oversized_declarations_are_reported() {
    let src = prog(
        "x : ARRAY[-9223372036854775808..9223372036854775807] OF BOOL;\n\
         y : ARRAY[0..60000000, 0..60000000] OF BOOL;\n\
         a, b : ARRAY[0..60000000] OF LINT;",
        "",
    );
    let codes: Vec<String> = diagnostics(&src).into_iter().map(|d| d.0).collect();
    assert!(codes.len() >= 3, "{codes:?}");
    assert!(codes.iter().all(|c| c == "E206"), "{codes:?}");
}

/// Edition-3 partial access is supported (tests/partial_access.rs), not
/// reported as a malformed direct address; a malformed one is named as a
/// partial access.
#[test]
fn partial_access_is_named_in_its_message() {
    let mut sources = plcrun::SourceMap::new();
    sources.add(
        "p.st",
        "PROGRAM P VAR b : BYTE; x : BOOL; END_VAR x := b.%X0; END_PROGRAM",
    );
    let report = plcrun::check(&sources, &plcrun::CheckOptions::default());
    assert!(report.diagnostics.is_empty(), "{:?}", report.diagnostics);
    let mut sources = plcrun::SourceMap::new();
    sources.add(
        "p.st",
        "PROGRAM P VAR b : BYTE; x : BOOL; END_VAR x := b.%X; END_PROGRAM",
    );
    let report = plcrun::check(&sources, &plcrun::CheckOptions::default());
    let e009: Vec<&str> = report
        .diagnostics
        .iter()
        .filter(|d| d.code == "E009")
        .map(|d| d.message.as_str())
        .collect();
    assert_eq!(e009.len(), 1, "{e009:?}");
    assert!(e009[0].starts_with("partial access `.%X`"), "{}", e009[0]);
    // A direct address elsewhere keeps its own message.
    let mut sources = plcrun::SourceMap::new();
    sources.add("q.st", "PROGRAM Q VAR x AT %Z0 : BOOL; END_VAR END_PROGRAM");
    let report = plcrun::check(&sources, &plcrun::CheckOptions::default());
    assert!(
        report
            .diagnostics
            .iter()
            .any(|d| d.code == "E009" && d.message.contains("must start with %I, %Q or %M")),
        "{:?}",
        report
            .diagnostics
            .iter()
            .map(|d| &d.message)
            .collect::<Vec<_>>()
    );
}

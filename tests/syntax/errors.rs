//! Diagnostics (code, line, column) and robustness on arbitrary input.

use super::common::*;
use rstest::rstest;

fn codes(src: &str) -> Vec<String> {
    parse_all(src)
        .1
        .into_iter()
        .map(|(c, l, col)| format!("{c}@{l}:{col}"))
        .collect()
}

#[rstest]
#[case::bad_duration("PROGRAM p\nx := T#5;\nEND_PROGRAM", &["E006@2:6"])]
#[case::bad_duration_unit("PROGRAM p\nx := T#5q;\nEND_PROGRAM", &["E006@2:6"])]
#[case::bad_hex_digit("PROGRAM p\nx := 16#G1;\nEND_PROGRAM", &["E005@2:6"])]
#[case::bad_base("PROGRAM p\nx := 3#1;\nEND_PROGRAM", &["E005@2:6"])]
#[case::empty_typed("PROGRAM p\nx := INT#;\nEND_PROGRAM", &["E008@2:6"])]
#[case::bad_bool("PROGRAM p\nx := BOOL#7;\nEND_PROGRAM", &["E008@2:6"])]
#[case::bad_date("PROGRAM p\nx := D#2023-02-30;\nEND_PROGRAM", &["E007@2:6"])]
#[case::bad_tod("PROGRAM p\nx := TOD#25:00:00;\nEND_PROGRAM", &["E007@2:6"])]
#[case::unterminated_string("PROGRAM p\nx := 'abc;\nEND_PROGRAM", &["E003@2:6", "E101@3:1"])]
#[case::bad_escape("PROGRAM p\nx := 'a$Qb';\nEND_PROGRAM", &["E004@2:8"])]
#[case::unterminated_comment("PROGRAM p\n(* open\nEND_PROGRAM", &["E002@2:1", "E102@3:12"])]
#[case::invalid_char("PROGRAM p\nx := 1 ? 2;\nEND_PROGRAM", &["E001@2:8", "E101@2:10"])]
#[case::bad_direct("PROGRAM p\nx := %Z1;\nEND_PROGRAM", &["E009@2:6"])]
#[case::bad_direct_size("PROGRAM p\nx := %IK1;\nEND_PROGRAM", &["E009@2:6"])]
#[case::unterminated_pragma("PROGRAM p\n{ open\nEND_PROGRAM", &["E010@2:1", "E102@3:12"])]
#[case::pragma_warning("PROGRAM p\n{attribute 'x'}\nx := 1;\nEND_PROGRAM", &["W001@2:1"])]
#[case::missing_semicolon("PROGRAM p\nIF x THEN y := 1\nEND_IF;\nEND_PROGRAM", &["E101@3:1"])]
#[case::several_errors("PROGRAM p\nx := ;\ny := 2;\nz := * 3;\nEND_PROGRAM", &["E101@2:6", "E101@4:6"])]
#[case::bare_name("PROGRAM p\nx;\nEND_PROGRAM", &["E103@2:1"])]
#[case::expr_statement("PROGRAM p\nf(1).q;\nEND_PROGRAM", &["E103@2:1"])]
#[case::il_unknown("PROGRAM p\nLD x\nFOO a b\nST y\nEND_PROGRAM", &["E101@3:7"])]
#[case::il_jmp_without_label("PROGRAM p\nLD x\nJMP\nST y\nEND_PROGRAM", &["E101@3:4"])]
#[case::il_two_errors("PROGRAM p\nLD x\nST 5 6\nLD :=\nST y\nEND_PROGRAM", &["E101@3:6", "E101@4:4"])]
#[case::case_stmt_before_label("PROGRAM p\nCASE x OF y := 1; 1: ; END_CASE\nEND_PROGRAM", &["E107@2:11"])]
#[case::bad_priority("PROGRAM p\nTRANSITION (PRIO := 1) FROM a TO b := x; END_TRANSITION\nEND_PROGRAM", &["E105@2:13"])]
#[case::bad_association("PROGRAM p\nSTEP s : a(N, T#1s); END_STEP\nEND_PROGRAM", &["E104@2:15"])]
#[case::bad_bit("PROGRAM p\nx := w.99;\nEND_PROGRAM", &["E108@2:8"])]
#[case::top_level_var("VAR x : INT; END_VAR", &["E111@1:1"])]
#[case::edge_qualifier("FUNCTION_BLOCK f\nVAR_INPUT c : BOOL R_EDGE; END_VAR\nEND_FUNCTION_BLOCK", &[])]
#[case::bad_edge_qualifier("FUNCTION_BLOCK f\nVAR_INPUT c : BOOL EDGY; END_VAR\nEND_FUNCTION_BLOCK", &["E425@2:20"])]
#[case::missing_end("PROGRAM p\nx := 1;\n", &["E102@3:1"])]
#[case::bad_decl("PROGRAM p\nVAR\n a : ;\n b : INT;\n c INT;\nEND_VAR\nEND_PROGRAM", &["E101@3:6", "E101@5:4"])]
#[case::garbage_between_pous("PROGRAM a END_PROGRAM\n+ + +\nPROGRAM b END_PROGRAM", &["E101@2:1"])]
fn diagnostics(#[case] src: &str, #[case] expected: &[&str]) {
    assert_eq!(codes(src), expected, "{:#?}", messages(src));
}

#[test]
fn messages_name_what_was_expected() {
    let m = messages("PROGRAM p\nIF x THEN y := 1\nEND_IF;\nEND_PROGRAM");
    assert_eq!(m, ["E101: expected `;`, found `END_IF`"]);
    let m = messages("PROGRAM p\nx := T#5;\nEND_PROGRAM");
    assert!(m[0].contains("missing unit"), "{m:?}");
    let m = messages("PROGRAM p\nx := 1;\n");
    assert!(
        m[0].contains("end of file") && m[0].contains("END_PROGRAM"),
        "{m:?}"
    );
    let m = messages("PROGRAM p\n{ pragma }\nEND_PROGRAM");
    assert!(m[0].contains("{ pragma }"), "{m:?}");
}

#[test]
fn recovery_keeps_the_rest_of_the_file() {
    let (unit, errs) = parse_all(
        "PROGRAM a\nx := ;\ny := 1;\nEND_PROGRAM\nFUNCTION_BLOCK b\nVAR_INPUT i : ; END_VAR\nEND_FUNCTION_BLOCK\nPROGRAM c\nz := 2;\nEND_PROGRAM",
    );
    assert_eq!(errs.len(), 2, "{errs:?}");
    assert_eq!(unit.items.len(), 3);
}

fn nested(open: &str, mid: &str, close: &str, n: usize) -> String {
    format!("{}{}{}", open.repeat(n), mid, close.repeat(n))
}

#[rstest]
#[case::parens(format!("PROGRAM p x := {}; END_PROGRAM", nested("(", "1", ")", 10_000)))]
#[case::unclosed_parens(format!("PROGRAM p x := {}", "(".repeat(10_000)))]
#[case::brackets(format!("PROGRAM p x := {}; END_PROGRAM", nested("a[", "1", "]", 5_000)))]
#[case::nots(format!("PROGRAM p x := {}a; END_PROGRAM", "NOT ".repeat(20_000)))]
#[case::minus(format!("PROGRAM p x := {}a; END_PROGRAM", "- ".repeat(20_000)))]
#[case::long_sum(format!("PROGRAM p x := a{}; END_PROGRAM", " + a".repeat(50_000)))]
#[case::long_pow(format!("PROGRAM p x := a{}; END_PROGRAM", " ** a".repeat(20_000)))]
#[case::calls(format!("PROGRAM p x := {}; END_PROGRAM", nested("f(", "1", ")", 5_000)))]
#[case::members(format!("PROGRAM p x := a{}; END_PROGRAM", ".b".repeat(20_000)))]
#[case::ifs(format!("PROGRAM p {} END_PROGRAM", nested("IF a THEN ", "x := 1;", " END_IF;", 5_000)))]
#[case::whiles(format!("PROGRAM p {} END_PROGRAM", nested("WHILE a DO ", "", " END_WHILE;", 5_000)))]
#[case::arrays(format!("TYPE t : {}INT; END_TYPE", "ARRAY[0..1] OF ".repeat(5_000)))]
#[case::array_init(format!("PROGRAM p VAR a : t := {}; END_VAR END_PROGRAM", nested("[", "1", "]", 5_000)))]
#[case::struct_init(format!("PROGRAM p VAR a : t := {}; END_VAR END_PROGRAM", nested("(a := ", "1", ")", 5_000)))]
#[case::il_deferred(format!("PROGRAM p\nLD a\n{}END_PROGRAM", "AND(\n".repeat(10_000)))]
fn deep_nesting_is_an_error_not_a_crash(#[case] src: String) {
    let (_unit, errs) = parse_all(&src);
    // Valid but absurd nesting is reported as E106; unbalanced input gets E10x.
    assert!(
        errs.iter()
            .all(|(c, _, _)| c.starts_with("E10") || c.starts_with("E11")),
        "{errs:?}"
    );
}

#[test]
fn moderate_nesting_is_fine() {
    parse_ok(&format!(
        "PROGRAM p x := {}; END_PROGRAM",
        nested("(", "1", ")", 150)
    ));
    parse_ok(&format!(
        "PROGRAM p {} END_PROGRAM",
        nested("IF a THEN ", "x := 1;", " END_IF;", 90)
    ));
}

use crate::support::rng;
use rng::Rng;

const PIECES: [&str; 40] = [
    "(",
    ")",
    "[",
    "]",
    ";",
    ":",
    ":=",
    "=>",
    ",",
    ".",
    "..",
    "\n",
    "'",
    "\"",
    "(*",
    "*)",
    "{",
    "}",
    "%",
    "#",
    "T#",
    "16#",
    "INT#",
    "END_IF",
    "IF",
    "THEN",
    "END_VAR",
    "VAR",
    "PROGRAM",
    "END_PROGRAM",
    "CAL",
    "LD",
    "AND(",
    "STEP",
    "TRANSITION",
    "ACTION",
    "|",
    "é",
    "$",
    "\u{0}",
];

fn mutate(rng: &mut Rng, src: &str) -> String {
    let mut s: Vec<char> = src.chars().collect();
    for _ in 0..1 + rng.below(6) {
        let at = rng.below(s.len() + 1);
        match rng.below(4) {
            0 => {
                let end = (at + rng.below(20)).min(s.len());
                s.drain(at..end);
            }
            1 => {
                let piece = PIECES[rng.below(PIECES.len())];
                for (k, c) in piece.chars().enumerate() {
                    s.insert(at + k, c);
                }
            }
            2 => s.truncate(at),
            _ => {
                let c = char::from_u32(rng.below(0x3000) as u32).unwrap_or('?');
                s.insert(at, c);
            }
        }
    }
    s.into_iter().collect()
}

#[test]
fn fuzz_mutated_programs_never_panic() {
    let seeds = [
        include_str!("../../programs/alg01.il"),
        include_str!("../../programs/chariot.sfc"),
        include_str!("../../benches/programs/bench_b_int_sieve.st"),
        include_str!("../../benches/programs/bench_c_fb_array.st"),
        include_str!("../../benches/programs/bench_d_real_math.st"),
        "CONFIGURATION c RESOURCE r ON x TASK t (INTERVAL := T#1s); PROGRAM i WITH t : p (a := 1); END_RESOURCE END_CONFIGURATION",
        "TYPE c : (a, b := 2); s : STRUCT x : INT := 1; END_STRUCT; END_TYPE",
    ];
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    // More rounds locally: PLCRUN_FUZZ_ROUNDS=100000 cargo test fuzz
    let rounds = std::env::var("PLCRUN_FUZZ_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(600);
    for round in 0..rounds {
        let seed = seeds[round % seeds.len()];
        let src = mutate(&mut rng, seed);
        let _ = parse_all(&src);
    }
}

#[test]
fn fuzz_random_token_soup_never_panics() {
    let mut rng = Rng(12345);
    for _ in 0..300 {
        let n = rng.below(200);
        let src: String = (0..n)
            .map(|_| {
                PIECES[rng.below(PIECES.len())].to_string()
                    + if rng.below(2) == 0 { " " } else { "" }
            })
            .collect();
        let _ = parse_all(&src);
        let _ = plcrun::syntax::parse_literal(&src);
    }
}

//! One typo, one error (issue #13 point 3): a single deleted, duplicated or
//! replaced token gives exactly one error, on the line of the typo, for at
//! least 90 % of the mutants that do not compile. Positions are sampled
//! deterministically (every few tokens) so the test stays fast;
//! `cargo run --release --example one_typo` measures every position.

use crate::support::one_typo;

/// The threshold this test holds: issue #13 asks for 90 %. The sampled
/// figure is 93.8 % (81.0 % before single-token repair, see
/// `src/syntax/repair.rs` and docs/robustness.md).
const TARGET_PERCENT: f64 = 90.0;

/// Every `STRIDE`-th token is altered (the starting token differs per
/// program), which keeps the test to seconds.
const STRIDE: usize = 23;

#[test]
fn one_typo_gives_one_error_on_its_line() {
    let mut total = one_typo::Tally::default();
    let mut programs = one_typo::shipped_programs();
    programs.extend(one_typo::generated_programs(3));
    let only = std::env::var("ONE_TYPO_ONLY").unwrap_or_default();
    for (i, (name, text)) in programs.iter().enumerate() {
        if name.contains(only.as_str()) {
            let tally = one_typo::measure(name, text, STRIDE, i % STRIDE);
            eprintln!("{name}: {:.1} % of {}", tally.percent(), tally.detected());
            total.add(&tally);
        }
    }
    eprintln!(
        "{:.1} % of {} detected mutants ({} silent)",
        total.percent(),
        total.detected(),
        total.silent
    );
    assert!(total.detected() > 500, "too few mutants: {total:?}");
    assert!(
        total.percent() >= TARGET_PERCENT,
        "{:.1} % of {} detected mutants give one error on the altered line (target {TARGET_PERCENT} %); misses:\n{}",
        total.percent(),
        total.detected(),
        total.examples.join("\n")
    );
}

#[test]
fn the_measure_notices_a_cascade() {
    // A second error on another line is a miss, one error elsewhere too.
    let text = "PROGRAM P\nVAR\n  a : INT;\nEND_VAR\na := 1;\nEND_PROGRAM\n";
    assert_eq!(one_typo::judge("p.st", text, 0), one_typo::Outcome::Silent);
    let broken = "PROGRAM P\nVAR\n  a : INT;\nEND_VAR\nb := 1;\nc := 2;\nEND_PROGRAM\n";
    assert!(matches!(
        one_typo::judge("p.st", broken, broken.find("b :=").unwrap()),
        one_typo::Outcome::Miss { errors: 2, .. }
    ));
    let one = "PROGRAM P\nVAR\n  a : INT;\nEND_VAR\nb := 1;\nEND_PROGRAM\n";
    assert_eq!(
        one_typo::judge("p.st", one, one.find("b :=").unwrap()),
        one_typo::Outcome::One
    );
    assert!(matches!(
        one_typo::judge("p.st", one, 0),
        one_typo::Outcome::Miss { errors: 1, .. }
    ));
}

/// The errors of `text` as `[code] message`.
fn messages(text: &str) -> Vec<String> {
    one_typo::errors("p.st", text)
        .into_iter()
        .map(|(_, m)| m)
        .collect()
}

#[test]
fn a_misspelt_name_gets_one_message_with_a_suggestion() {
    let text = "PROGRAM P\nVAR\n  counter : INT;\nEND_VAR\ncountr := 1;\ncountr := countr + 1;\nEND_PROGRAM\n";
    assert_eq!(
        messages(text),
        ["[E201] undeclared variable `countr`; did you mean `counter`?"]
    );
    // Nothing close: no suggestion.
    let text = "PROGRAM P\nVAR\n  counter : INT;\nEND_VAR\nspeed := 1;\nEND_PROGRAM\n";
    assert_eq!(messages(text), ["[E201] undeclared variable `speed`"]);
}

#[test]
fn suggestions_for_types_functions_members_and_enum_values() {
    let text = "TYPE Mode : (Idle, Running); END_TYPE\n\
        FUNCTION_BLOCK Motor\nVAR_INPUT\n  speed : INT;\nEND_VAR\nEND_FUNCTION_BLOCK\n\
        FUNCTION Twice : INT\nVAR_INPUT\n  x : INT;\nEND_VAR\nTwice := 2 * x;\nEND_FUNCTION\n\
        PROGRAM P\nVAR\n  m : Motr;\n  t : TNO;\n  k : Motor;\n  a : INT;\n  md : Mode;\nEND_VAR\n\
        a := Twcie(3);\nk(sped := 1);\na := k.spede;\nmd := Runing;\na := ABSS(a);\nEND_PROGRAM\n";
    let got = messages(text);
    for want in [
        "unknown type `Motr`; did you mean `Motor`?",
        "unknown type `TNO`; did you mean `TON`?",
        "unknown function `Twcie`; did you mean `Twice`?",
        "has no member `spede`; did you mean `speed`?",
        "has no input `sped`; did you mean `speed`?",
        "undeclared variable `Runing`; did you mean `RUNNING`?",
        "unknown function `ABSS`; did you mean `ABS`?",
    ] {
        assert!(
            got.iter().any(|m| m.contains(want)),
            "no `{want}` in {got:#?}"
        );
    }
}

#[test]
fn a_type_mismatch_names_the_expected_type() {
    let text = "PROGRAM P\nVAR\n  i : INT;\n  r : REAL;\nEND_VAR\ni := r;\nEND_PROGRAM\n";
    let got = messages(text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert!(got[0].contains("expected INT, found REAL"), "{got:?}");
}

#[test]
fn a_broken_declaration_does_not_make_its_uses_undeclared() {
    // `:` deleted: the declaration is salvaged, its uses are not reported.
    let text = "FUNCTION_BLOCK F\nVAR_INPUT\n  limit INT;\nEND_VAR\nVAR\n  n : INT;\nEND_VAR\nn := limit + 1;\nEND_FUNCTION_BLOCK\n\
        PROGRAM P\nVAR\n  f : F;\nEND_VAR\nf(limit := 3);\nEND_PROGRAM\n";
    let got = one_typo::errors("p.st", text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].0, 3, "{got:?}");
}

#[test]
fn a_missing_semicolon_is_reported_on_its_own_line() {
    let text = "PROGRAM P\nVAR\n  a : INT;\n  b : INT;\nEND_VAR\na := 1\nb := 2;\nEND_PROGRAM\n";
    let got = one_typo::errors("p.st", text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].0, 6, "{got:?}");
}

#[test]
fn a_broken_if_header_gives_one_error() {
    let text = "PROGRAM P\nVAR\n  a : INT;\nEND_VAR\nIF a > ) THEN\n  a := 1;\nELSE\n  a := 2;\nEND_IF;\na := 3;\nEND_PROGRAM\n";
    let got = one_typo::errors("p.st", text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].0, 5, "{got:?}");
}

#[test]
fn an_il_line_in_error_does_not_cascade() {
    let text = "PROGRAM P\nVAR\n  a : INT;\n  b : BOOL;\nEND_VAR\n  LD\n  ADD 1\n  ST a\n  LD b\n  ST b\nEND_PROGRAM\n";
    let got = one_typo::errors("p.il", text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].0, 6, "{got:?}");
}

#[test]
fn a_missing_end_if_is_reported_where_the_indentation_ends_the_block() {
    // `END_IF` deleted from `END_IF;`: the parser only notices at
    // `END_PROGRAM`; the `;` left at the IF's indentation is where it was.
    let text =
        "PROGRAM P\nVAR\n  a : INT;\nEND_VAR\nIF a > 0 THEN\n  a := 1;\n;\na := 2;\nEND_PROGRAM\n";
    let got = one_typo::errors("p.st", text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].0, 7, "{got:?}");
}

#[test]
fn a_lost_keyword_is_one_error_and_the_rest_is_still_checked() {
    // `TRANSITION` deleted: one error on its line; the steps it connected
    // are not reported, and a real error later still is.
    let text = "PROGRAM P\nVAR\n  go : BOOL;\n  n : INT;\nEND_VAR\nINITIAL_STEP S0:\nEND_STEP\nSTEP S1:\nEND_STEP\nFROM S0 TO S1 := go;\nEND_TRANSITION\nTRANSITION FROM S1 TO S0 := NOT go;\nEND_TRANSITION\nEND_PROGRAM\n";
    let got = one_typo::errors("p.sfc", text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].0, 10, "{got:?}");
    let worse = text.replace("NOT go", "NOT n + 1");
    let got = one_typo::errors("p.sfc", &worse);
    assert_eq!(got.len(), 2, "{got:?}");
    assert_eq!(got[1].0, 12, "{got:?}");
}

#[test]
fn an_il_call_missing_its_closing_parenthesis_is_one_error() {
    let text = "PROGRAM P\nVAR\n  t1 : TON;\n  c : BOOL;\nEND_VAR\n  CAL t1(IN := c, PT := T#5ms\n  LD t1.Q\n  ST c\nEND_PROGRAM\n";
    let got = one_typo::errors("p.il", text);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0].0, 6, "{got:?}");
    assert!(got[0].1.contains("`)`"), "{got:?}");
}

#[test]
fn a_repaired_typo_is_still_an_error() {
    // The repair decides what else is reported; the program stays refused.
    for text in [
        "PROGRAM P\nVAR\n  a : INT;\n\na := 1;\nEND_PROGRAM\n",
        "PROGRAM P\nVAR\n  a : INT;\nEND_VAR\nIF a > 0 a := 1;\nEND_IF;\nEND_PROGRAM\n",
        "PROGRAM P\nVAR\n  a : INT;\nEND_VAR\na := a * / 1;\nEND_PROGRAM\n",
    ] {
        let got = one_typo::errors("p.st", text);
        assert_eq!(got.len(), 1, "{text}: {got:?}");
        assert!(got[0].1.starts_with("[E10"), "{text}: {got:?}");
    }
}

//! CODESYS's POUs for implicit checks beyond `CheckBounds` (issue #25):
//! the division checks (`CheckDivDInt`, `CheckDivLInt`, `CheckDivReal`,
//! `CheckDivLReal`) and the subrange checks (`CheckRangeSigned`,
//! `CheckRangeUnsigned`, `CheckLRangeSigned`, `CheckLRangeUnsigned`),
//! declared in TwinCAT files as TwinCAT generates them.

use crate::support::plc::{lit, run};
use crate::support::twincat::{compile, compile_ok, declaration, pou};

/// TwinCAT's suggested division check for divisors of `ty`: 1 for 0.
fn div_check(name: &str, ty: &str) -> (String, String) {
    let file = format!("{name}.TcPOU");
    let text = pou(
        name,
        &format!("FUNCTION {name} : {ty}\nVAR_INPUT\n  divisor : {ty};\nEND_VAR"),
        &format!("IF divisor = 0 THEN\n  {name} := 1;\nELSE\n  {name} := divisor;\nEND_IF"),
        "",
    );
    (file, text)
}

/// A range check of `ty` that clamps to the bounds and counts its calls
/// in the global `GVL_Calls.n`.
fn range_check(name: &str, ty: &str) -> (String, String) {
    let file = format!("{name}.TcPOU");
    let text = pou(
        name,
        &format!("FUNCTION {name} : {ty}\nVAR_INPUT\n  value, lower, upper : {ty};\nEND_VAR"),
        &format!(
            "GVL_Calls.n := GVL_Calls.n + 1;\nIF value < lower THEN\n  {name} := lower;\n\
             ELSIF value > upper THEN\n  {name} := upper;\nELSE\n  {name} := value;\nEND_IF"
        ),
        "",
    );
    (file, text)
}

/// The project: `checks`, the global list of the call counter, `main`
/// as `P` and the `extra` files.
fn project(
    checks: &[(String, String)],
    main: &str,
    extra: &[(&str, &str)],
) -> Vec<(String, String)> {
    let calls = declaration("GVL", "GVL_Calls", "VAR_GLOBAL\n  n : DINT;\nEND_VAR");
    let mut all = checks.to_vec();
    all.push(("GVL_Calls.TcGVL".into(), calls));
    all.push(("P.TcPOU".into(), main.into()));
    all.extend(extra.iter().map(|(f, t)| (f.to_string(), t.to_string())));
    all
}

/// `files` as the compiler takes them.
fn refs(files: &[(String, String)]) -> Vec<(&str, &str)> {
    files
        .iter()
        .map(|(f, t)| (f.as_str(), t.as_str()))
        .collect()
}

#[test]
fn a_project_s_division_checks_replace_a_zero_divisor() {
    let checks = [
        div_check("CheckDivDInt", "DINT"),
        div_check("CheckDivLInt", "LINT"),
        div_check("CheckDivReal", "REAL"),
        div_check("CheckDivLReal", "LREAL"),
    ];
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  zero : INT;\n  uzero : UDINT;\n  lzero : LINT;\n  rzero : REAL;\n  \
         lrzero : LREAL;\n  i : INT := 7;\n  u : UDINT := 4000000000;\n  l : LINT := -9;\n  \
         r : REAL := 2.5;\n  lr : LREAL := 0.25;\n  two : SINT := 2;\n  qi : INT;\n  qu : UDINT;\n  \
         ql : LINT;\n  qr : REAL;\n  qlr : LREAL;\n  half : SINT;\n  m : INT;\nEND_VAR",
        "qi := i / zero;\nqu := u / uzero;\nql := l / lzero;\nqr := r / rzero;\n\
         qlr := lr / lrzero;\nhalf := two / two;\nm := i MOD 2;",
        "",
    );
    let mut plc = compile_ok(&refs(&project(&checks, &main, &[])));
    run(&mut plc, 1);
    // Each divides by the 1 its check returns for 0.
    assert_eq!(lit(&plc, "P.qi"), "7");
    assert_eq!(lit(&plc, "P.qu"), "4000000000");
    assert_eq!(lit(&plc, "P.ql"), "-9");
    assert_eq!(lit(&plc, "P.qr"), "2.5");
    assert_eq!(lit(&plc, "P.qlr"), "0.25");
    // A divisor that is not 0 comes back as it went (a SINT through DINT).
    assert_eq!(lit(&plc, "P.half"), "1");
    assert_eq!(lit(&plc, "P.m"), "1");
}

#[test]
fn without_a_division_check_a_zero_divisor_still_faults() {
    // Only the checks the project declares apply: here the integer one.
    let checks = [div_check("CheckDivDInt", "DINT")];
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  i : DINT := 7;\n  zero : DINT;\n  l : LINT := 7;\n  lzero : LINT;\n  \
         q : DINT;\n  ql : LINT;\nEND_VAR",
        "q := i / zero;\nql := l / lzero;",
        "",
    );
    let mut plc = compile_ok(&refs(&project(&checks, &main, &[])));
    let fault = plc.run_cycle().expect_err("LINT division by zero");
    assert!(fault.to_string().contains("division by zero"), "{fault}");
    assert_eq!(lit(&plc, "P.q"), "7");
}

#[test]
fn the_division_check_s_result_is_the_divisor() {
    // A check that turns every divisor into 2, as a test double would:
    // what it returns is what the division uses, cut back to the
    // divisor's width.
    let check = pou(
        "CheckDivDInt",
        "FUNCTION CheckDivDInt : DINT\nVAR_INPUT\n  divisor : DINT;\nEND_VAR",
        "GVL_Calls.n := GVL_Calls.n + 1;\nCheckDivDInt := 2;",
        "",
    );
    let checks = [("CheckDivDInt.TcPOU".to_string(), check)];
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  a : INT := 9;\n  b : INT := 3;\n  q : INT;\n  k : INT;\nEND_VAR",
        "q := a / b;\nk := a / 3;\nq := q + DIV(a, b);",
        "",
    );
    let mut plc = compile_ok(&refs(&project(&checks, &main, &[])));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.q"), "8");
    // A constant divisor goes through no check.
    assert_eq!(lit(&plc, "P.k"), "3");
    assert_eq!(lit(&plc, "GVL_Calls.n"), "2");
}

#[test]
fn a_project_s_range_checks_clamp_values_stored_in_subranges() {
    let checks = [
        range_check("CheckRangeSigned", "DINT"),
        range_check("CheckRangeUnsigned", "UDINT"),
        range_check("CheckLRangeSigned", "LINT"),
        range_check("CheckLRangeUnsigned", "ULINT"),
    ];
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  s : INT(-5..5);\n  u : UINT(10..20);\n  l : LINT(-100..100);\n  \
         w : ULINT(1..3);\n  x : INT := 40;\n  y : LINT := -1000;\n  inside : INT(0..9);\nEND_VAR",
        "s := x;\nu := INT_TO_UINT(x);\nl := y;\nw := LINT_TO_ULINT(y * y);\ninside := 4 + 1;",
        "",
    );
    let mut plc = compile_ok(&refs(&project(&checks, &main, &[])));
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.s"), "5");
    assert_eq!(lit(&plc, "P.u"), "20");
    assert_eq!(lit(&plc, "P.l"), "-100");
    assert_eq!(lit(&plc, "P.w"), "3");
    assert_eq!(lit(&plc, "P.inside"), "5");
    // s, u, l and w: a constant (in range, or E304) calls none.
    assert_eq!(lit(&plc, "GVL_Calls.n"), "4");
}

#[test]
fn without_a_range_check_a_value_outside_a_subrange_still_faults() {
    let checks = [range_check("CheckRangeUnsigned", "UDINT")];
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  s : INT(-5..5);\n  x : INT := 40;\nEND_VAR",
        "s := x;",
        "",
    );
    let mut plc = compile_ok(&refs(&project(&checks, &main, &[])));
    let fault = plc.run_cycle().expect_err("out of the subrange");
    assert!(fault.to_string().contains("R003"), "{fault}");
}

#[test]
fn a_no_check_pou_calls_no_division_or_range_check() {
    let checks = [
        div_check("CheckDivDInt", "DINT"),
        range_check("CheckRangeSigned", "DINT"),
    ];
    let raw = pou(
        "Raw",
        "{attribute 'no_check'}\nFUNCTION Raw : DINT\nVAR_INPUT\n  a, b : DINT;\nEND_VAR\nVAR\n  \
         s : DINT(0..3);\nEND_VAR",
        "s := a;\nRaw := a / b;",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  zero : DINT;\n  q : DINT;\nEND_VAR",
        "q := Raw(2, zero);",
        "",
    );
    let mut plc = compile_ok(&refs(&project(&checks, &main, &[("Raw.TcPOU", &raw)])));
    let fault = plc.run_cycle().expect_err("division by zero in Raw");
    assert!(fault.to_string().contains("division by zero"), "{fault}");
}

#[test]
fn a_check_declared_otherwise_than_codesys_is_not_called_and_said_so() {
    // CheckDivDInt on INT: not TwinCAT's declaration, so not a check.
    let odd = pou(
        "CheckDivDInt",
        "FUNCTION CheckDivDInt : INT\nVAR_INPUT\n  divisor : INT;\nEND_VAR",
        "CheckDivDInt := 1;",
        "",
    );
    let checks = [("CheckDivDInt.TcPOU".to_string(), odd)];
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  a : DINT := 6;\n  b : DINT := 3;\n  q : DINT;\nEND_VAR",
        "q := a / b;",
        "",
    );
    let mut plc = compile(&refs(&project(&checks, &main, &[]))).expect("compiles");
    let warned: Vec<String> = plc
        .warnings()
        .iter()
        .filter(|d| d.code == "W494")
        .map(|d| d.message.clone())
        .collect();
    assert_eq!(warned.len(), 1, "{warned:?}");
    assert!(warned[0].contains("CheckDivDInt"), "{warned:?}");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "P.q"), "2");
}

#[test]
fn a_method_declared_no_check_calls_no_check_and_its_block_s_others_do() {
    use crate::support::twincat::method;
    let checks = [div_check("CheckDivDInt", "DINT")];
    let raw = method(
        "{attribute 'no_check'}\nMETHOD M : DINT\nVAR_INPUT\n  a, b : DINT;\nEND_VAR",
        "M := a / b;",
    );
    let fb = pou(
        "Fb",
        "FUNCTION_BLOCK Fb\nVAR_INPUT\n  a, b : DINT;\nEND_VAR\nVAR_OUTPUT\n  q : DINT;\nEND_VAR",
        "q := a / b;",
        &raw,
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  f : Fb;\n  zero : DINT;\n  q : DINT;\n  r : DINT;\nEND_VAR",
        "f(a := 5, b := zero, q => q);\nr := f.M(6, zero);",
        "",
    );
    let mut plc = compile_ok(&refs(&project(&checks, &main, &[("Fb.TcPOU", &fb)])));
    // The pragma is honoured, not reported as ignored.
    assert!(plc.warnings().iter().all(|d| d.code != "W001"));
    let fault = plc.run_cycle().expect_err("division by zero in M");
    assert!(fault.to_string().contains("division by zero"), "{fault}");
    assert_eq!(lit(&plc, "P.q"), "5");
}

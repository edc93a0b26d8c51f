//! CODESYS's implicit conversions between integer types and bit strings
//! that may change the value (W490), in the files written in the CODESYS
//! V3 / TwinCAT dialect: the low bits of the two's complement are kept, as
//! TwinCAT does; `--strict` refuses them; in a plain IEC file they stay
//! E301.

use crate::support::plc::{lit, run};

/// A TwinCAT `.TcPOU` file holding PROGRAM `P` with `decls` and `body`.
fn tcpou(decls: &str, body: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <POU Name=\"P\" Id=\"{{00000000-0000-0000-0000-000000000001}}\" SpecialFunc=\"None\">\n    <Declaration><![CDATA[PROGRAM P\nVAR\n{decls}\nEND_VAR]]></Declaration>\n    <Implementation>\n      <ST><![CDATA[{body}]]></ST>\n    </Implementation>\n  </POU>\n</TcPlcObject>\n"
    )
}

fn compile(
    name: &str,
    text: &str,
    options: &plcrun::Options,
) -> Result<plcrun::Plc, plcrun::CompileError> {
    let options = plcrun::Options {
        program: Some("P".into()),
        ..options.clone()
    };
    plcrun::Plc::compile_files(&[(name, text)], &options)
}

fn error_codes(err: &plcrun::CompileError) -> Vec<&'static str> {
    err.diagnostics
        .iter()
        .filter(|d| d.severity == plcrun::Severity::Error)
        .map(|d| d.code)
        .collect()
}

fn w490s(plc: &plcrun::Plc) -> usize {
    plc.warnings().iter().filter(|d| d.code == "W490").count()
}

const DECLS: &str = "i : INT := -3; u, v : UDINT; l : ULINT := 16#1_0000_0005;
    big : UDINT := 3000000000; d : DINT; w : WORD := 16#1234; b : BYTE; s : SINT;";
const BODY: &str = "u := i; v := l; d := big; b := w; s := w;";

#[test]
fn narrowing_and_sign_changes_keep_the_low_bits() {
    let mut plc = compile("P.TcPOU", &tcpou(DECLS, BODY), &Default::default())
        .expect("TwinCAT compiles these");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "u"), "4294967293");
    assert_eq!(lit(&plc, "v"), "5");
    assert_eq!(lit(&plc, "d"), "-1294967296");
    assert_eq!(lit(&plc, "b"), "16#34");
    assert_eq!(lit(&plc, "s"), "52");
    assert_eq!(w490s(&plc), 5);
}

#[test]
fn conversions_that_keep_every_value_give_no_w490() {
    let text = tcpou(
        "i : INT := -3; d : DINT; b : BYTE := 7; j : INT; u : UINT := 9; w : WORD;",
        "d := i; j := b; w := u;",
    );
    let plc = compile("P.TcPOU", &text, &Default::default()).unwrap();
    assert_eq!(w490s(&plc), 0);
}

#[test]
fn strict_mode_plain_iec_files_and_other_types_refuse_them() {
    let strict = plcrun::Options {
        strict: true,
        ..Default::default()
    };
    let err = compile("P.TcPOU", &tcpou("i : INT; u : UDINT;", "u := i;"), &strict)
        .err()
        .expect("strict refuses");
    assert!(err.to_string().contains("error[W490]"), "{err}");
    // The same assignments in a plain ST file: E301 each, as IEC says.
    let st = format!("PROGRAM P\nVAR\n{DECLS}\nEND_VAR\n{BODY}\nEND_PROGRAM\n");
    let err = compile("p.st", &st, &Default::default())
        .err()
        .expect("IEC refuses");
    assert_eq!(error_codes(&err), ["E301"; 5]);
    // TIME and REAL are not integers: E301 in TwinCAT files too.
    let other = tcpou("t : TIME; d : DINT; r : REAL; i : INT;", "d := t; i := r;");
    let err = compile("P.TcPOU", &other, &Default::default())
        .err()
        .expect("no conversion");
    assert_eq!(error_codes(&err), ["E301", "E301"]);
}

/// Explicit conversions in a TwinCAT file keep the low bits too, as there
/// (`TIME_TO_INT(T#60S)` is -5536: SLAC's vacuum gauges store their
/// recovery time so); in a plain IEC file a value that does not fit stops
/// the PLC (R004).
#[test]
fn explicit_conversions_keep_the_low_bits_in_twincat_files() {
    let decls = "t : INT; b : BYTE; s : SINT; big : LINT := 16#1_2345_6789; d : TIME := T#60S;";
    let body = "t := TIME_TO_INT(d);\nb := INT_TO_BYTE(-1);\ns := LINT_TO_SINT(big);\n";
    let mut plc = compile("P.TcPOU", &tcpou(decls, body), &Default::default()).unwrap();
    run(&mut plc, 1);
    let got: Vec<String> = ["t", "b", "s"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    assert_eq!(got, ["-5536", "16#FF", "-119"]);
    let iec = format!("PROGRAM P\nVAR\n{decls}\nEND_VAR\nt := TIME_TO_INT(d);\nEND_PROGRAM\n");
    let mut plc = compile("p.st", &iec, &Default::default()).unwrap();
    let fault = plc.run_cycle().expect_err("R004 in an IEC file");
    assert_eq!(fault.code(), "R004", "{fault}");
}

/// A REAL converted to an integer in a TwinCAT file is rounded, then cut
/// to the target's width as TwinCAT's x64 targets do
/// (`LREAL_TO_UDINT(-1.0)` is 4294967295: lcls-twincat-motion's raw count
/// converter takes a position below the encoder's offset so); in a plain
/// IEC file it stops the PLC (R004).
#[test]
fn real_to_integer_conversions_keep_the_low_bits_in_twincat_files() {
    let decls = "u : UDINT; i : INT; w : USINT; x : LREAL := -1.0; y : LREAL := 40000.4; z : REAL := 300.0;";
    let body = "u := LREAL_TO_UDINT(x);\ni := LREAL_TO_INT(y);\nw := REAL_TO_USINT(z);\n";
    let mut plc = compile("P.TcPOU", &tcpou(decls, body), &Default::default()).unwrap();
    run(&mut plc, 1);
    let got: Vec<String> = ["u", "i", "w"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    assert_eq!(got, ["4294967295", "-25536", "44"]);
    let iec = format!("PROGRAM P\nVAR\n{decls}\nEND_VAR\nu := LREAL_TO_UDINT(x);\nEND_PROGRAM\n");
    let mut plc = compile("p.st", &iec, &Default::default()).unwrap();
    let fault = plc.run_cycle().expect_err("R004 in an IEC file");
    assert_eq!(fault.code(), "R004", "{fault}");
}

/// A signed and an unsigned integer combined in a TwinCAT file compute in
/// the smallest signed type holding both (INT and UINT in DINT); two
/// enumerations that are not strict meet through their integers (W485,
/// W486). In a plain IEC file both are E306.
#[test]
fn mixed_signs_and_two_enumerations_combine_in_twincat_files() {
    let types = "TYPE E_A : (A0, A1, A2); END_TYPE\nTYPE E_B : (B0, B1, B2); END_TYPE\n";
    let decls = "i : INT := -1; u : UINT := 40000; lt : BOOL; sum : DINT; ea : E_A := A2; eb : E_B := B2; eq : BOOL;";
    let body = "lt := i < u;\nsum := i + u;\neq := ea = eb;\nea := eb;\n";
    let dut = format!(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <DUT Name=\"E_A\" Id=\"{{00000000-0000-0000-0000-000000000002}}\">\n    <Declaration><![CDATA[{types}]]></Declaration>\n  </DUT>\n</TcPlcObject>\n"
    );
    let options = plcrun::Options {
        program: Some("P".into()),
        ..Default::default()
    };
    let pou = tcpou(decls, body);
    let mut plc =
        plcrun::Plc::compile_files(&[("E.TcDUT", dut.as_str()), ("P.TcPOU", &pou)], &options)
            .unwrap();
    run(&mut plc, 1);
    let got: Vec<String> = ["lt", "sum", "eq", "ea"]
        .iter()
        .map(|v| lit(&plc, &format!("P.{v}")))
        .collect();
    assert_eq!(got, ["TRUE", "39999", "TRUE", "A2"]);
    let iec = format!("{types}PROGRAM P\nVAR\n{decls}\nEND_VAR\n{body}END_PROGRAM\n");
    let Err(err) = compile("p.st", &iec, &Default::default()) else {
        panic!("mixed operands accepted in an IEC file");
    };
    assert!(
        error_codes(&err).contains(&"E306"),
        "{:?}",
        error_codes(&err)
    );
}

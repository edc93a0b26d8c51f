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

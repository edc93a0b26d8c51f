//! Instruction List: operators, modifiers, deferred operations, labels,
//! calls, and the line-orientation pass.

use super::common::*;
use plcrun::syntax::ast::*;
use rstest::rstest;

/// One IL instruction in a compact form.
fn show(i: &IlInstr) -> String {
    match &i.kind {
        IlInstrKind::Simple {
            op,
            negate,
            operand,
        } => format!(
            "{op:?}{}{}",
            if *negate { "N" } else { "" },
            operand
                .as_ref()
                .map(|o| format!(" {}", sx(o)))
                .unwrap_or_default()
        ),
        IlInstrKind::Deferred {
            op,
            negate,
            operand,
        } => format!(
            "{op:?}{}({}",
            if *negate { "N" } else { "" },
            operand.as_ref().map(sx).unwrap_or_default()
        ),
        IlInstrKind::Close => ")".into(),
        IlInstrKind::Jump { cond, label } => format!("JMP{:?} {}", cond, label.name),
        IlInstrKind::Call {
            cond,
            instance,
            args: a,
            outputs,
        } => format!(
            "CAL{:?} {}({}{})",
            cond,
            sx(instance),
            args(a),
            if outputs.is_empty() {
                String::new()
            } else {
                format!(
                    " | {}",
                    outputs
                        .iter()
                        .map(|o| format!(
                            "{} := {}",
                            o.dest.as_ref().map(sx).unwrap_or_default(),
                            o.output.name
                        ))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            }
        ),
        IlInstrKind::Return { cond } => format!("RET{cond:?}"),
        IlInstrKind::FunctionCall { name, args: a } => format!("FUN {} {}", name.name, args(a)),
        IlInstrKind::FbInput { pin, instance } => format!("PIN {} {}", pin.name, sx(instance)),
    }
}

fn one(line: &str) -> String {
    // A first `LD` line makes the body recognisably IL whatever the line under test.
    let lines = il(&format!("LD x\n{line}"));
    assert_eq!(lines.len(), 2, "{lines:?}");
    show(lines[1].instr.as_ref().unwrap())
}

#[rstest]
#[case("LD x", "Ld x")]
#[case("ld x", "Ld x")]
#[case("LDN x", "LdN x")]
#[case("ST y", "St y")]
#[case("STN y", "StN y")]
#[case("S y", "S y")]
#[case("R y", "R y")]
#[case("AND x", "And x")]
#[case("& x", "And x")]
#[case("ANDN x", "AndN x")]
#[case("&N x", "AndN x")]
#[case("OR x", "Or x")]
#[case("ORN x", "OrN x")]
#[case("XOR x", "Xor x")]
#[case("XORN x", "XorN x")]
#[case("NOT", "Not")]
#[case("ADD 5", "Add 5")]
#[case("SUB -5", "Sub -5")]
#[case("MUL 2.5", "Mul 2.5")]
#[case("DIV n", "Div n")]
#[case("MOD 7", "Mod 7")]
#[case("GT 1", "Gt 1")]
#[case("GE 1", "Ge 1")]
#[case("EQ 1", "Eq 1")]
#[case("NE 1", "Ne 1")]
#[case("LE 1", "Le 1")]
#[case("LT 1", "Lt 1")]
#[case("LD T#5s", "Ld T#5s")]
#[case("LD %IX0.1", "Ld %IX0.1")]
#[case("LD T1.Q", "Ld T1.Q")]
#[case("LD arr[2]", "Ld arr[2]")]
#[case("LD w.3", "Ld w.%X3")]
#[case("AND( x", "And(x")]
#[case("AND(x", "And(x")]
#[case("OR ( M4", "Or(M4")]
#[case("ANDN(", "AndN(")]
#[case(")", ")")]
#[case("JMP next", "JMPNone next")]
#[case("JMPC next", "JMPSome(true) next")]
#[case("JMPCN next", "JMPSome(false) next")]
#[case("RET", "RETNone")]
#[case("RETC", "RETSome(true)")]
#[case("RETCN", "RETSome(false)")]
#[case("CAL t1", "CALNone t1()")]
#[case("CALC t1", "CALSome(true) t1()")]
#[case("CALCN fbs[2]", "CALSome(false) fbs[2]()")]
#[case("CAL t1(IN := x, PT := T#1s)", "CALNone t1(IN := x, PT := T#1s)")]
#[case("CAL t1(x, T#1s)", "CALNone t1(x, T#1s)")]
#[case(
    "CAL t1(IN := x, Q => q, NOT ET => e)",
    "CALNone t1(IN := x, Q => q, NOT ET => e)"
)]
#[case("MAX b, c", "FUN MAX b, c")]
#[case("LIMIT 0, 100", "FUN LIMIT 0, 100")]
#[case("SEL a, b", "FUN SEL a, b")]
#[case("TRUNC", "FUN TRUNC ")]
#[case("MUX k := 1, a", "FUN MUX k := 1, a")]
#[case("S1 ff", "PIN S1 ff")]
#[case("R1 ff", "PIN R1 ff")]
#[case("CLK trig", "PIN CLK trig")]
#[case("CU ctr", "PIN CU ctr")]
#[case("CD ctr", "PIN CD ctr")]
#[case("PV ctr", "PIN PV ctr")]
#[case("IN tmr", "PIN IN tmr")]
#[case("PT tmr", "PIN PT tmr")]
fn il_instructions(#[case] src: &str, #[case] expected: &str) {
    assert_eq!(one(src), expected);
}

#[test]
fn labels_alone_and_before_instructions() {
    let lines = il("start: LD x\n\nloop:\n  ST y (* comment *)\n  JMPC loop\nend: RET");
    assert_eq!(lines.len(), 5);
    assert_eq!(lines[0].label.as_ref().unwrap().name, "start");
    assert_eq!(show(lines[0].instr.as_ref().unwrap()), "Ld x");
    assert_eq!(lines[1].label.as_ref().unwrap().name, "loop");
    assert!(lines[1].instr.is_none());
    assert!(lines[2].label.is_none());
    assert_eq!(lines[4].label.as_ref().unwrap().name, "end");
}

#[test]
fn deferred_over_several_lines() {
    let lines = il("LD a\nAND(\nLD b\nOR c\n)\nST q");
    let shown: Vec<String> = lines
        .iter()
        .map(|l| show(l.instr.as_ref().unwrap()))
        .collect();
    assert_eq!(shown, ["Ld a", "And(", "Ld b", "Or c", ")", "St q"]);
}

#[test]
fn moeller_call_with_output_list() {
    let lines = il("CAL T1(\n  IN := M23,\n  PT := DT1\n  |\n  QT1 := Q,\n  := ET\n)\nLD QT1");
    assert_eq!(lines.len(), 2);
    assert_eq!(
        show(lines[0].instr.as_ref().unwrap()),
        "CALNone T1(IN := M23, PT := DT1 | QT1 := Q,  := ET)"
    );
    let IlInstrKind::Call { outputs, .. } = &lines[0].instr.as_ref().unwrap().kind else {
        panic!()
    };
    assert!(outputs[1].dest.is_none());
}

#[test]
fn moeller_sr_call() {
    let lines = il("CAL SR0(\nSET1 := APM0,\nRESET:= M1\n|\nM0 := Q1\n)");
    assert_eq!(
        show(lines[0].instr.as_ref().unwrap()),
        "CALNone SR0(SET1 := APM0, RESET := M1 | M0 := Q1)"
    );
}

#[test]
fn line_spans_are_exact() {
    let src = "PROGRAM p\nVAR x : BOOL; END_VAR\n  LD x\n  ST x\nEND_PROGRAM";
    let unit = parse_ok(src);
    let Body::Il(lines) = &pou(&unit).body else {
        panic!()
    };
    let texts: Vec<&str> = lines
        .iter()
        .map(|l| &src[l.span.start as usize..l.span.end as usize])
        .collect();
    assert_eq!(texts, ["LD x", "ST x"]);
}

#[test]
fn function_body_in_il_and_st_pous_in_the_same_file() {
    let unit = parse_ok(
        "FUNCTION f : INT\nVAR_INPUT a : INT; END_VAR\nLD a\nADD 1\nST f\nEND_FUNCTION\n\
         PROGRAM p\nVAR r : INT; END_VAR\nr := f(2);\nEND_PROGRAM\n\
         FUNCTION_BLOCK fb\nVAR_INPUT i : BOOL; END_VAR VAR_OUTPUT o : BOOL; END_VAR\nLD i\nST o\nEND_FUNCTION_BLOCK",
    );
    let bodies: Vec<&'static str> = unit
        .items
        .iter()
        .map(|i| match i {
            Item::Pou(Pou {
                body: Body::Il(_), ..
            }) => "il",
            Item::Pou(Pou {
                body: Body::St(_), ..
            }) => "st",
            _ => "?",
        })
        .collect();
    assert_eq!(bodies, ["il", "st", "il"]);
}

#[test]
fn st_body_using_il_operator_names_as_variables_stays_st() {
    let s = stmts("ST := 1; LD := ST + 1; S := TRUE; R := FALSE;");
    assert_eq!(s.len(), 4);
}

#[test]
fn il_function_without_var_blocks() {
    let unit = parse_ok("FUNCTION f : BOOL\nLD TRUE\nST f\nEND_FUNCTION");
    assert!(matches!(&pou(&unit).body, Body::Il(l) if l.len() == 2));
}

#[test]
fn il_action_in_sfc() {
    let unit = parse_ok(
        "PROGRAM p VAR a : BOOL; END_VAR\nINITIAL_STEP s0 : act(N); END_STEP\n\
         ACTION act :\n  LD a\n  ST b\nEND_ACTION\nEND_PROGRAM",
    );
    let Body::Sfc(e) = &pou(&unit).body else {
        panic!()
    };
    let SfcElement::Action(a) = &e[1] else {
        panic!()
    };
    assert!(matches!(&a.body, Body::Il(l) if l.len() == 2));
}

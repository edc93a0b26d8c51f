//! Forcing and soft writes (docs/runtime.md, "Forcing") in IL, ST and SFC
//! programs, forced values in the trace and the process image, and the
//! writes refused from outside (CONSTANTs, SFC step flags).

use plcrun::{
    Force, Options, Plc, ReadOnlyReason, Session, TraceFormat, TraceWriter, VarError,
    parse_stimulus,
};

fn compile(name: &str, src: &str) -> Plc {
    Plc::compile_files(&[(name, src)], &Options::default()).expect("compiles")
}

fn lit(plc: &Plc, name: &str) -> String {
    plc.read(name).unwrap().to_literal()
}

const ST: &str = "
TYPE Pair : STRUCT a : INT; b : INT; END_STRUCT; END_TYPE
FUNCTION_BLOCK Counter
VAR_INPUT inc : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
total := total + inc;
END_FUNCTION_BLOCK
PROGRAM P
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; seen : BOOL; out AT %QX0.0 : BOOL; END_VAR
VAR arr : ARRAY[1..3] OF INT; pair : Pair; c : Counter; END_VAR
VAR CONSTANT limit : INT := 5; END_VAR
n := n + 1;
seen := go;
out := go;
arr[2] := n;
pair.b := n * 2;
c(inc := 1);
END_PROGRAM
";

#[test]
fn a_forced_output_keeps_its_value_whatever_the_program_writes() {
    let mut plc = compile("p.st", ST);
    plc.force("n", "100").unwrap();
    assert_eq!(lit(&plc, "n"), "100"); // at once
    for _ in 0..3 {
        plc.run_cycle().unwrap();
        assert_eq!(lit(&plc, "n"), "100");
    }
    // The program read the forced value before it ran: arr[2] = 101.
    assert_eq!(lit(&plc, "arr[2]"), "101");
    assert!(plc.unforce("n").unwrap());
    assert!(!plc.unforce("n").unwrap());
    assert_eq!(lit(&plc, "n"), "100"); // kept until written
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "n"), "101");
}

#[test]
fn a_forced_input_keeps_its_value_whatever_the_host_writes() {
    let mut plc = compile("p.st", ST);
    plc.force("go", "TRUE").unwrap();
    plc.write("go", "FALSE").unwrap(); // a soft write: accepted, overridden
    assert_eq!(lit(&plc, "go"), "TRUE");
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "seen"), "TRUE");
    // Unforcing applies the last soft write.
    plc.unforce("go").unwrap();
    assert_eq!(lit(&plc, "go"), "FALSE");
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "seen"), "FALSE");
}

#[test]
fn elements_fields_and_fb_variables_can_be_forced() {
    let mut plc = compile("p.st", ST);
    plc.force("arr[2]", "-7").unwrap();
    plc.force("pair.b", "3").unwrap();
    plc.force("c.total", "40").unwrap();
    for _ in 0..2 {
        plc.run_cycle().unwrap();
    }
    assert_eq!(lit(&plc, "arr[2]"), "-7");
    assert_eq!(lit(&plc, "pair.b"), "3");
    // The FB adds 1 to the forced 40 inside the cycle; the force wins after.
    assert_eq!(lit(&plc, "c.total"), "40");
    assert_eq!(
        plc.forces(),
        vec![
            Force {
                path: "arr[2]".into(),
                value: plc.read("arr[2]").unwrap()
            },
            Force {
                path: "pair.b".into(),
                value: plc.read("pair.b").unwrap()
            },
            Force {
                path: "c.total".into(),
                value: plc.read("c.total").unwrap()
            },
        ]
    );
    plc.unforce_all();
    assert!(plc.forces().is_empty());
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "c.total"), "41");
}

#[test]
fn a_forced_located_output_shows_in_the_process_image() {
    let mut plc = compile("p.st", ST);
    plc.write("go", "TRUE").unwrap();
    plc.force("%QX0.0", "FALSE").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "out"), "FALSE");
    assert!(!plc.process_image().read_bit("%QX0.0").unwrap());
    let r = plc.resolve("out").unwrap();
    assert!(
        plc.is_forced(&r),
        "the address and the name are one variable"
    );
    plc.unforce("out").unwrap();
    plc.run_cycle().unwrap();
    assert!(plc.process_image().read_bit("%QX0.0").unwrap());
}

#[test]
fn a_forced_input_ignores_the_process_image_and_the_stimulus() {
    let src = "PROGRAM P VAR_INPUT x AT %IX0.0 : BOOL; END_VAR VAR_OUTPUT y : BOOL; END_VAR
        y := x; END_PROGRAM";
    let mut plc = compile("p.st", src);
    plc.force("x", "TRUE").unwrap();
    plc.process_image_mut().write_bit("%IX0.0", false).unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "y"), "TRUE");
    assert!(plc.process_image().read_bit("%IX0.0").unwrap());
    let mut session = Session::new(plc);
    session.set_trace(&["x", "y"]).unwrap();
    session
        .bind_stimulus(parse_stimulus("cycle,x\n0,FALSE\n1,FALSE\n").unwrap())
        .unwrap();
    let mut out = TraceWriter::new(
        Vec::new(),
        TraceFormat::Csv,
        vec!["x".into(), "y".into()],
        false,
    );
    session.run(2, &mut out).unwrap();
    let csv = String::from_utf8(out.finish().unwrap()).unwrap();
    assert_eq!(
        csv,
        "cycle,time,x,y\n1,T#10ms,TRUE!,TRUE\n2,T#20ms,TRUE!,TRUE\n"
    );
}

#[test]
fn forced_values_are_marked_in_json_lines_only_when_forced() {
    let mut plc = compile("p.st", ST);
    plc.force("n", "9").unwrap();
    let mut session = Session::new(plc);
    session.set_trace(&["n", "seen"]).unwrap();
    let names = session.trace_names().to_vec();
    let mut out = TraceWriter::new(Vec::new(), TraceFormat::Jsonl, names.clone(), false);
    session.run(1, &mut out).unwrap();
    session.plc_mut().unforce_all();
    session.run(1, &mut out).unwrap();
    let text = String::from_utf8(out.finish().unwrap()).unwrap();
    assert_eq!(
        text,
        "{\"cycle\":0,\"time\":\"T#0s\",\"n\":9,\"seen\":false,\"forced\":[\"n\"]}\n\
         {\"cycle\":1,\"time\":\"T#10ms\",\"n\":10,\"seen\":false}\n"
    );
    let mut table = TraceWriter::new(Vec::new(), TraceFormat::Table, names, false);
    session.plc_mut().force("seen", "TRUE").unwrap();
    session.run(1, &mut table).unwrap();
    let text = String::from_utf8(table.finish().unwrap()).unwrap();
    assert_eq!(
        text,
        "cycle  time    n   seen\n-----  ------  --  -----\n2      T#20ms  11  TRUE!\n"
    );
}

const IL: &str = "PROGRAM Q
VAR_INPUT a : BOOL; END_VAR
VAR_OUTPUT y : BOOL; k : INT; END_VAR
LD a
ST y
LD k
ADD 1
ST k
END_PROGRAM
";

#[test]
fn forcing_works_in_il() {
    let mut plc = compile("q.il", IL);
    plc.force("y", "TRUE").unwrap();
    plc.force("k", "5").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "y"), "TRUE"); // the program stored a = FALSE
    assert_eq!(lit(&plc, "k"), "5");
    plc.unforce("k").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "k"), "6");
}

const SFC: &str = "PROGRAM Seq
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT running : BOOL; END_VAR
INITIAL_STEP Idle : END_STEP
TRANSITION FROM Idle TO Run := go; END_TRANSITION
STEP Run : running(N); END_STEP
TRANSITION FROM Run TO Idle := NOT go; END_TRANSITION
END_PROGRAM
";

#[test]
fn forcing_works_in_sfc() {
    let mut plc = compile("seq.sfc", SFC);
    plc.force("go", "TRUE").unwrap();
    plc.write("go", "FALSE").unwrap();
    plc.run_cycle().unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "Run.X"), "TRUE");
    assert_eq!(plc.active_steps("Seq"), Some(vec!["Run".to_string()]));
    // A forced output the action control writes.
    plc.force("running", "FALSE").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "running"), "FALSE");
    plc.unforce_all();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "go"), "FALSE"); // the soft write, applied on unforce
    plc.run_cycle().unwrap();
    assert_eq!(plc.active_steps("Seq"), Some(vec!["Idle".to_string()]));
}

#[test]
fn forcing_an_unknown_name_or_a_wrong_value_names_both() {
    let mut plc = compile("p.st", ST);
    let err = plc.force("nope", "1").unwrap_err();
    assert_eq!(
        err,
        VarError::Unknown {
            name: "nope".into()
        }
    );
    let err = plc.force("n", "TRUE").unwrap_err();
    assert!(matches!(err, VarError::ValueDoesNotFit { .. }), "{err:?}");
    let msg = err.to_string();
    assert!(
        msg.contains("`n`") && msg.contains("`TRUE`") && msg.contains("INT"),
        "{msg}"
    );
    assert!(plc.forces().is_empty());
}

#[test]
fn constants_and_step_flags_are_refused_from_outside_and_still_readable() {
    let mut plc = compile("p.st", ST);
    assert_eq!(lit(&plc, "limit"), "5");
    let err = plc.write("limit", "6").unwrap_err();
    assert_eq!(
        err,
        VarError::ReadOnly {
            path: "limit".into(),
            why: ReadOnlyReason::Constant
        }
    );
    assert!(err.to_string().contains("CONSTANT"), "{err}");
    assert!(plc.force("limit", "6").is_err());
    assert_eq!(lit(&plc, "limit"), "5");

    let mut seq = compile("seq.sfc", SFC);
    for flag in ["Idle.X", "Run.X", "Run.T"] {
        let value = if flag.ends_with('T') { "T#1s" } else { "TRUE" };
        for err in [seq.write(flag, value), seq.force(flag, value)] {
            assert!(
                matches!(
                    err,
                    Err(VarError::ReadOnly {
                        why: ReadOnlyReason::StepFlag,
                        ..
                    })
                ),
                "{flag}: {err:?}"
            );
        }
    }
    assert_eq!(
        seq.resolve("Run.X").unwrap().read_only(),
        Some(ReadOnlyReason::StepFlag)
    );
    // The chart is intact: Idle is still the only active step.
    seq.run_cycle().unwrap();
    assert_eq!(lit(&seq, "Idle.X"), "TRUE");
    assert_eq!(lit(&seq, "Run.X"), "FALSE");
    // And a stimulus column naming a step flag is refused when bound.
    let mut session = Session::new(seq);
    let err = session
        .bind_stimulus(parse_stimulus("cycle,Run.X\n0,TRUE\n").unwrap())
        .unwrap_err();
    assert!(matches!(err.error, VarError::ReadOnly { .. }), "{err}");
}

#[test]
fn global_constants_are_refused_too() {
    let src = "VAR_GLOBAL CONSTANT MAXV : INT := 3; END_VAR
        PROGRAM P VAR_EXTERNAL CONSTANT MAXV : INT; END_VAR VAR_OUTPUT y : INT; END_VAR
        y := MAXV; END_PROGRAM";
    let mut plc = compile("g.st", src);
    assert!(matches!(
        plc.write("MAXV", "4"),
        Err(VarError::ReadOnly {
            why: ReadOnlyReason::Constant,
            ..
        })
    ));
}

#[test]
fn a_force_applies_between_the_programs_of_a_tick() {
    let src = "VAR_GLOBAL g : INT; END_VAR
PROGRAM Writer VAR_EXTERNAL g : INT; END_VAR g := g + 1; END_PROGRAM
PROGRAM Reader VAR_EXTERNAL g : INT; END_VAR VAR_OUTPUT copy : INT; END_VAR copy := g; END_PROGRAM
CONFIGURATION C
RESOURCE R ON PLC
TASK T (INTERVAL := T#10ms, PRIORITY := 1);
PROGRAM w WITH T : Writer;
PROGRAM r WITH T : Reader;
END_RESOURCE
END_CONFIGURATION
";
    let mut plc = compile("c.st", src);
    plc.force("g", "50").unwrap();
    plc.run_cycle().unwrap();
    // The writer made 51; the force was applied again before the reader ran.
    assert_eq!(lit(&plc, "r.copy"), "50");
    assert_eq!(lit(&plc, "g"), "50");
    plc.unforce("g").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(lit(&plc, "r.copy"), "51");
    let vars = plc.variables();
    assert!(vars.iter().any(|v| v.path == "r.copy"), "{vars:#?}");
    assert!(vars.iter().any(|v| v.path == "g"), "{vars:#?}");
}

/// A live stimulus (`--stimulus -`) refuses the columns a stimulus file
/// refuses: a CONSTANT or an SFC step flag cannot be written from outside.
#[test]
fn a_live_stimulus_refuses_read_only_columns() {
    use plcrun::{LiveStimulus, LiveStimulusError, Options, Plc, VarError};
    let src = "PROGRAM P VAR CONSTANT k : INT := 3; END_VAR VAR n : INT; END_VAR
               n := n + k; END_PROGRAM";
    let plc = Plc::compile_files(&[("p.st", src)], &Options::default()).unwrap();
    let err = LiveStimulus::start(&plc, std::io::Cursor::new("cycle,k\n0,5\n")).unwrap_err();
    assert!(
        matches!(&err, LiveStimulusError::Bind(b) if matches!(b.error, VarError::ReadOnly { .. })),
        "{err}"
    );
    assert!(LiveStimulus::start(&plc, std::io::Cursor::new("cycle,n\n0,5\n")).is_ok());
}

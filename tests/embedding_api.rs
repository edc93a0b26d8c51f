//! The library API as an embedder uses it (docs/embedding.md): typed
//! errors for every way a variable access can go wrong, handles that only
//! their own PLC accepts, values checked against the variable's type, and
//! `Session` runs with their binding errors.

use plcrun::{
    CheckOptions, ElemType, Options, PathProblem, Plc, RunError, Session, SourceMap, TraceFormat,
    TraceWriter, Value, ValueProblem, VarError, check, parse_stimulus,
};

const PROGRAM: &str = "
TYPE Color : (Red, Green, Blue); END_TYPE
TYPE Percent : INT (0..100); END_TYPE
PROGRAM P
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR
VAR
    s : STRING[8];
    c : Color;
    pct : Percent;
    r : REAL;
    arr : ARRAY[1..3] OF INT;
    t : TON;
END_VAR
IF go THEN n := n + 1; END_IF
t(IN := go, PT := T#20ms);
END_PROGRAM
";

fn plc() -> Plc {
    Plc::compile_files(&[("p.st", PROGRAM)], &Options::default()).expect("compiles")
}

#[test]
fn every_path_problem_has_its_own_error() {
    let plc = plc();
    let err = |path: &str| plc.resolve(path).unwrap_err();
    assert!(matches!(
        err(""),
        VarError::BadPath {
            problem: PathProblem::Empty,
            ..
        }
    ));
    assert!(matches!(
        err("arr[1"),
        VarError::BadPath {
            problem: PathProblem::MissingBracket,
            ..
        }
    ));
    assert!(matches!(
        err("arr[x]"),
        VarError::BadPath {
            problem: PathProblem::IndexNotAnInteger(_),
            ..
        }
    ));
    assert!(matches!(
        err("n!"),
        VarError::BadPath {
            problem: PathProblem::Unexpected('!'),
            ..
        }
    ));
    assert_eq!(
        err("nope"),
        VarError::Unknown {
            name: "nope".into()
        }
    );
    assert!(matches!(err("%QX9.9"), VarError::NotLocated { .. }));
    assert!(matches!(err("t.Nope"), VarError::NoMember { member, .. } if member == "Nope"));
    assert!(matches!(err("n[1]"), VarError::NotAnArray { .. }));
    assert!(matches!(
        err("arr[1,2]"),
        VarError::IndexCount {
            dimensions: 1,
            given: 2,
            ..
        }
    ));
    assert!(matches!(
        err("arr[0]"),
        VarError::IndexOutOfBounds {
            index: 0,
            lo: 1,
            hi: 3,
            ..
        }
    ));
    assert!(matches!(err("arr"), VarError::NotAValue { .. }));
    assert!(matches!(err("t"), VarError::NotAValue { .. }));
    // The messages are the command line's.
    assert_eq!(
        err("arr[0]").to_string(),
        "`arr[0]`: index 0 is outside [1..3]"
    );
    assert_eq!(err("t").to_string(), "`t` is a TON, not a single value");
}

#[test]
fn literals_that_do_not_fit_are_refused_with_the_reason() {
    let mut plc = plc();
    let problem = |plc: &mut Plc, name: &str, lit: &str| match plc.write(name, lit) {
        Err(VarError::BadValue { problem, .. }) => problem,
        other => panic!("{name} := {lit}: {other:?}"),
    };
    assert_eq!(problem(&mut plc, "s", "abc"), ValueProblem::NotAString);
    assert_eq!(
        problem(&mut plc, "c", "Purple"),
        ValueProblem::NotAnEnumValue
    );
    assert_eq!(problem(&mut plc, "n", "40000"), ValueProblem::Invalid);
    assert_eq!(
        problem(&mut plc, "pct", "101"),
        ValueProblem::OutsideSubrange(101)
    );
    plc.write("s", "'hello'").unwrap();
    plc.write("c", "Color#Blue").unwrap();
    plc.write("pct", "100").unwrap();
    assert_eq!(plc.read("s").unwrap().as_str(), Some("hello"));
    assert_eq!(plc.read("c").unwrap(), Value::Enum("Blue".into(), 2));
    assert!(matches!(
        plc.read_i64("s"),
        Err(VarError::NotAnInteger { .. })
    ));
}

#[test]
fn set_refuses_values_of_another_type_or_outside_the_encoding() {
    let mut plc = plc();
    let wrong = |plc: &mut Plc, name: &str, v: Value| {
        let r = plc.resolve(name).unwrap();
        match plc.set(&r, &v) {
            Err(VarError::WrongValue { .. }) => {}
            other => panic!("{name} := {v:?}: {other:?}"),
        }
    };
    // A number into a string variable would corrupt its string index.
    wrong(&mut plc, "s", Value::Scalar(ElemType::Int, 3));
    // Raw slots outside the type's encoding.
    wrong(&mut plc, "n", Value::Scalar(ElemType::Int, 70_000));
    wrong(&mut plc, "go", Value::Scalar(ElemType::Bool, 2));
    wrong(&mut plc, "r", Value::Scalar(ElemType::Real, u64::MAX));
    // Another type, an ordinal that is not a value, a subrange overflow.
    wrong(&mut plc, "n", Value::Scalar(ElemType::Dint, 1));
    wrong(&mut plc, "c", Value::Enum("Nine".into(), 9));
    wrong(&mut plc, "pct", Value::Scalar(ElemType::Int, 200));
    wrong(&mut plc, "go", Value::String("x".into(), false));
    // What `get` gives back can always be set again.
    let n = plc.resolve("n").unwrap();
    plc.set(&n, &Value::Scalar(ElemType::Int, (-5i64) as u64))
        .unwrap();
    let v = plc.get(&n).unwrap();
    plc.set(&n, &v).unwrap();
    assert_eq!(plc.read_i64("n").unwrap(), -5);
    let e = plc
        .set(&n, &Value::Scalar(ElemType::Bool, 1))
        .unwrap_err()
        .to_string();
    assert_eq!(e, "`n` is of type INT and cannot hold TRUE");
}

#[test]
fn a_handle_works_only_with_the_plc_that_resolved_it() {
    let mut a = plc();
    let mut b = plc();
    let n_of_a = a.resolve("n").unwrap();
    assert_eq!(n_of_a.name(), "n");
    assert!(a.get(&n_of_a).is_ok());
    assert_eq!(
        b.get(&n_of_a),
        Err(VarError::ForeignHandle { path: "n".into() })
    );
    let one = Value::Scalar(ElemType::Int, 1);
    assert!(matches!(
        b.set(&n_of_a, &one),
        Err(VarError::ForeignHandle { .. })
    ));
    assert!(matches!(
        b.parse_value(&n_of_a, "1"),
        Err(VarError::ForeignHandle { .. })
    ));
    a.set(&n_of_a, &one).unwrap();
    assert_eq!(b.read_i64("n").unwrap(), 0, "b is untouched");
}

#[test]
fn several_plcs_run_independently_in_one_process() {
    let mut a = plc();
    let mut b = plc();
    a.write("go", "TRUE").unwrap();
    for _ in 0..5 {
        a.run_cycle().unwrap();
        b.run_cycle().unwrap();
    }
    assert_eq!(a.read_i64("n").unwrap(), 5);
    assert_eq!(b.read_i64("n").unwrap(), 0);
    assert_eq!(a.read("t.Q").unwrap().as_bool(), Some(true));
    assert_eq!(b.read("t.Q").unwrap().as_bool(), Some(false));
}

#[test]
fn session_reports_which_stimulus_column_or_cell_does_not_fit() {
    let mut session = Session::new(plc());
    let e = session
        .bind_stimulus(parse_stimulus("cycle,nope\n0,1\n").unwrap())
        .unwrap_err();
    assert_eq!((e.column.as_str(), e.line), ("nope", None));
    assert_eq!(e.to_string(), "column `nope`: unknown variable `nope`");
    let e = session
        .bind_stimulus(parse_stimulus("cycle,n\n0,1\n3,x\n").unwrap())
        .unwrap_err();
    assert_eq!((e.column.as_str(), e.line), ("n", Some(3)));
    assert!(matches!(e.error, VarError::BadValue { .. }));
    // A failed set_trace keeps the previous list.
    session.set_trace(&["n"]).unwrap();
    assert!(session.set_trace(&["n", "arr"]).is_err());
    assert_eq!(session.trace_names(), ["n"]);
}

#[test]
fn session_steps_and_stops_at_a_fault_after_writing_the_rows_before_it() {
    let src = "PROGRAM F VAR_INPUT d : INT := 1; END_VAR VAR_OUTPUT q : INT; END_VAR
               q := 10 / d; END_PROGRAM";
    let plc = Plc::compile_files(&[("f.st", src)], &Options::default()).unwrap();
    let mut session = Session::new(plc);
    session.set_trace(&["q"]).unwrap();
    session
        .bind_stimulus(parse_stimulus("cycle,d\n2,0\n").unwrap())
        .unwrap();
    session.step().unwrap();
    assert_eq!(session.cells()[0].text, "10");
    let mut out = TraceWriter::new(Vec::new(), TraceFormat::Csv, vec!["q".into()], false);
    let end = session.run(5, &mut out);
    let Err(RunError::Fault(fault)) = end else {
        panic!("expected a fault, got {end:?}");
    };
    assert_eq!(fault.cycle, 2);
    assert_eq!(fault.fault.kind, plcrun::FaultKind::DivisionByZero);
    let csv = String::from_utf8(out.finish().unwrap()).unwrap();
    assert_eq!(csv, "cycle,time,q\n1,T#10ms,10\n");
    assert_eq!(
        session.plc().cycle(),
        2,
        "the faulting cycle did not complete"
    );
}

#[test]
fn check_reports_without_building_a_program() {
    let mut sources = SourceMap::new();
    sources.add("a.st", "PROGRAM A VAR x : INT; END_VAR x := y; END_PROGRAM");
    let report = check(&sources, &CheckOptions::default());
    assert!(!report.is_ok());
    let codes: Vec<&str> = report.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(codes, ["E201"]);
    assert!(report.ir_listing.is_none());

    let mut sources = SourceMap::new();
    sources.add(
        "b.st",
        "PROGRAM B VAR x : INT; END_VAR x := x + 1; END_PROGRAM",
    );
    let options = CheckOptions {
        ir_listing: true,
        ..CheckOptions::default()
    };
    let report = check(&sources, &options);
    assert!(report.is_ok());
    let listing = report.ir_listing.expect("a listing");
    assert!(listing.contains("code 0 `B`"), "{listing}");
}

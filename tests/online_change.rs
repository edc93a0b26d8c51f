//! Online change: a new program version takes over a running PLC between
//! two cycles and keeps the state of what did not change.

use plcrun::{OnlineChangeError, Options, Plc, Retyped};

fn plc(src: &str) -> Plc {
    Plc::compile_files(&[("v1.st", src)], &Options::default()).expect("v1 compiles")
}

fn change(plc: &mut Plc, src: &str) -> plcrun::ChangeReport {
    plc.online_change_files(&[("v2.st", src)], &Options::default())
        .expect("online change applies")
}

fn read(plc: &Plc, name: &str) -> String {
    plc.read(name).expect("readable").to_literal()
}

fn cycles(plc: &mut Plc, n: usize) {
    for _ in 0..n {
        plc.run_cycle().expect("cycle runs");
    }
}

const TIMER_V1: &str = "
PROGRAM P
VAR start : BOOL := TRUE; t : TON; et : TIME; q : BOOL; END_VAR
t(IN := start, PT := T#100ms);
et := t.ET;
q := t.Q;
END_PROGRAM";

const TIMER_V2: &str = "
PROGRAM P
VAR start : BOOL := TRUE; t : TON; et : TIME; q : BOOL; calls : INT; END_VAR
t(IN := start, PT := T#100ms);
et := t.ET;
q := t.Q;
calls := calls + 1;
END_PROGRAM";

#[test]
fn a_running_timer_keeps_timing_across_an_online_change() {
    let mut p = plc(TIMER_V1);
    // IN rose in cycle 0 (clock 0): ET is 40 ms in cycle 4.
    cycles(&mut p, 5);
    assert_eq!(read(&p, "P.et"), "T#40ms");
    let report = change(&mut p, TIMER_V2);
    assert_eq!(report.initialised, ["P.calls"]);
    assert!(report.kept.contains(&"P.t".to_string()), "{report}");
    assert_eq!(p.cycle(), 5, "the cycle counter continues");
    assert_eq!(p.time(), 50_000_000, "the clock continues");
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.et"), "T#50ms", "the timer did not restart");
    assert_eq!(read(&p, "P.calls"), "1", "the new code runs");
    // 100 ms after IN rose, Q: cycle 10.
    cycles(&mut p, 4);
    assert_eq!(read(&p, "P.q"), "FALSE");
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.q"), "TRUE");
}

#[test]
fn edge_detectors_and_counters_keep_their_memory() {
    let v1 = "
PROGRAM P
VAR x : BOOL; r : R_TRIG; c : CTU; edges : INT; END_VAR
r(CLK := x);
IF r.Q THEN edges := edges + 1; END_IF
c(CU := x, PV := 100);
END_PROGRAM";
    // Same blocks, the body now also counts falling edges.
    let v2 = "
PROGRAM P
VAR x : BOOL; r : R_TRIG; c : CTU; edges : INT; f : F_TRIG; falls : INT; END_VAR
r(CLK := x);
IF r.Q THEN edges := edges + 1; END_IF
f(CLK := x);
IF f.Q THEN falls := falls + 1; END_IF
c(CU := x, PV := 100);
END_PROGRAM";
    let mut p = plc(v1);
    for _ in 0..3 {
        p.write("P.x", "TRUE").unwrap();
        cycles(&mut p, 1);
        p.write("P.x", "FALSE").unwrap();
        cycles(&mut p, 1);
    }
    p.write("P.x", "TRUE").unwrap();
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.edges"), "4");
    assert_eq!(read(&p, "P.c.CV"), "4");
    let report = change(&mut p, v2);
    assert_eq!(report.initialised, ["P.f", "P.falls"], "{report}");
    // x stays TRUE: no new rising edge for the kept R_TRIG and CTU.
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.edges"), "4", "R_TRIG kept its memory");
    assert_eq!(
        read(&p, "P.c.CV"),
        "4",
        "CTU kept its count and edge memory"
    );
    p.write("P.x", "FALSE").unwrap();
    cycles(&mut p, 1);
    p.write("P.x", "TRUE").unwrap();
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.edges"), "5");
    assert_eq!(read(&p, "P.c.CV"), "5");
    assert_eq!(read(&p, "P.falls"), "1");
}

#[test]
fn arrays_strings_and_structures_are_carried_by_content() {
    let v1 = "
TYPE Pt : STRUCT x : INT; y : INT; END_STRUCT; END_TYPE
PROGRAM P
VAR a : ARRAY[1..3] OF INT; s : STRING[10]; pt : Pt; b : ARRAY[0..1] OF INT; n : INT; END_VAR
n := n + 1;
a[1] := n; a[2] := n * 2; a[3] := n * 3;
s := 'abc';
pt.x := 5; pt.y := 6;
b[0] := 9;
END_PROGRAM";
    // A string declared first moves every slot and string id; b's bounds change.
    let v2 = "
TYPE Pt : STRUCT x : INT; y : INT; END_STRUCT; END_TYPE
PROGRAM P
VAR first : STRING := 'new'; a : ARRAY[1..3] OF INT; s : STRING[10]; pt : Pt;
    b : ARRAY[0..2] OF INT; n : INT; END_VAR
END_PROGRAM";
    let mut p = plc(v1);
    cycles(&mut p, 2);
    let report = change(&mut p, v2);
    for kept in ["P.a", "P.s", "P.pt", "P.n"] {
        assert!(report.kept.contains(&kept.to_string()), "{kept}: {report}");
    }
    assert_eq!(report.initialised, ["P.first"]);
    assert_eq!(
        report.retyped,
        [Retyped {
            path: "P.b".into(),
            old_type: "ARRAY[0..1] OF INT".into(),
            new_type: "ARRAY[0..2] OF INT".into(),
        }],
        "{report}"
    );
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.a[3]"), "6");
    assert_eq!(read(&p, "P.s"), "'abc'");
    assert_eq!(read(&p, "P.first"), "'new'");
    assert_eq!(read(&p, "P.pt.y"), "6");
    assert_eq!(read(&p, "P.b[0]"), "0", "re-initialised");
}

#[test]
fn retyped_and_removed_variables_are_reported() {
    let v1 = "
VAR_GLOBAL g : INT := 1; gone : BOOL; END_VAR
PROGRAM P
VAR_EXTERNAL g : INT; END_VAR
VAR x : INT; old : INT; keep : DINT; END_VAR
x := 3; old := 4; keep := keep + 1; g := 42;
END_PROGRAM";
    let v2 = "
VAR_GLOBAL g : INT := 1; END_VAR
PROGRAM P
VAR_EXTERNAL g : INT; END_VAR
VAR x : REAL := 1.5; keep : DINT; END_VAR
keep := keep + 1;
END_PROGRAM";
    let mut p = plc(v1);
    cycles(&mut p, 3);
    let report = change(&mut p, v2);
    assert_eq!(report.kept, ["P.keep", "g"], "{report}");
    assert_eq!(report.dropped, ["P.old", "gone"]);
    assert_eq!(report.retyped.len(), 1);
    assert_eq!(report.retyped[0].path, "P.x");
    assert!(!report.is_seamless());
    let text = report.to_string();
    assert!(text.contains("retyped P.x (INT -> REAL)"), "{text}");
    assert!(text.contains("dropped P.old"), "{text}");
    assert!(text.contains("kept g"), "{text}");
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.x"), "1.5");
    assert_eq!(read(&p, "P.keep"), "4");
    assert_eq!(read(&p, "g"), "42");
}

#[test]
fn a_changed_function_block_keeps_its_unchanged_members() {
    let v1 = "
FUNCTION_BLOCK Acc
VAR_INPUT inc : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
VAR t : TON; END_VAR
total := total + inc;
t(IN := TRUE, PT := T#1s);
END_FUNCTION_BLOCK
PROGRAM P
VAR acc : Acc; END_VAR
acc(inc := 2);
END_PROGRAM";
    let v2 = "
FUNCTION_BLOCK Acc
VAR_INPUT inc : INT; END_VAR
VAR_OUTPUT total : INT; calls : INT; END_VAR
VAR t : TON; END_VAR
total := total + inc;
calls := calls + 1;
t(IN := TRUE, PT := T#1s);
END_FUNCTION_BLOCK
PROGRAM P
VAR acc : Acc; END_VAR
acc(inc := 2);
END_PROGRAM";
    let mut p = plc(v1);
    cycles(&mut p, 3);
    let report = change(&mut p, v2);
    assert_eq!(
        report.kept,
        ["P.acc.inc", "P.acc.total", "P.acc.t"],
        "{report}"
    );
    assert_eq!(report.initialised, ["P.acc.calls"]);
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.acc.total"), "8");
    assert_eq!(read(&p, "P.acc.calls"), "1");
    assert_eq!(read(&p, "P.acc.t.ET"), "T#30ms");
}

const CHART: &str = "
PROGRAM P
VAR go : BOOL; n : INT; END_VAR
INITIAL_STEP S0 : END_STEP
STEP S1 : END_STEP
STEP S2 : END_STEP
TRANSITION FROM S0 TO S1 := go; END_TRANSITION
TRANSITION FROM S1 TO S2 := go; END_TRANSITION
TRANSITION FROM S2 TO S0 := go; END_TRANSITION
END_PROGRAM";

#[test]
fn an_unchanged_chart_keeps_its_active_step() {
    let mut p = plc(CHART);
    p.write("P.go", "TRUE").unwrap();
    cycles(&mut p, 2);
    p.write("P.go", "FALSE").unwrap();
    cycles(&mut p, 3);
    assert_eq!(read(&p, "P.S2.X"), "TRUE");
    let s2_time = read(&p, "P.S2.T");
    // A different condition on one transition: the shape is the same.
    let v2 = CHART.replace("TO S0 := go;", "TO S0 := go AND n = 0;");
    let report = change(&mut p, &v2);
    assert!(report.charts_restarted.is_empty(), "{report}");
    assert_eq!(report.kept, ["P"], "{report}");
    assert_eq!(read(&p, "P.S2.X"), "TRUE");
    assert_eq!(read(&p, "P.S2.T"), s2_time);
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.S2.X"), "TRUE");
    assert_eq!(read(&p, "P.S0.X"), "FALSE");
}

#[test]
fn a_changed_chart_restarts_at_its_initial_step() {
    let mut p = plc(CHART);
    p.write("P.go", "TRUE").unwrap();
    cycles(&mut p, 2);
    p.write("P.go", "FALSE").unwrap();
    cycles(&mut p, 3);
    assert_eq!(read(&p, "P.S2.X"), "TRUE");
    let v2 = CHART.replace(
        "TRANSITION FROM S2 TO S0 := go; END_TRANSITION",
        "STEP S3 : END_STEP\nTRANSITION FROM S2 TO S3 := go; END_TRANSITION\n\
         TRANSITION FROM S3 TO S0 := go; END_TRANSITION",
    );
    let report = change(&mut p, &v2);
    assert_eq!(report.charts_restarted, ["P"], "{report}");
    assert!(report.to_string().contains("chart restarted P"));
    assert!(report.kept.contains(&"P.go".to_string()));
    cycles(&mut p, 1);
    assert_eq!(read(&p, "P.S0.X"), "TRUE");
    assert_eq!(read(&p, "P.S2.X"), "FALSE");
}

#[test]
fn sources_that_do_not_compile_are_refused_and_the_program_runs_on() {
    let mut p = plc(TIMER_V1);
    cycles(&mut p, 3);
    let broken = "PROGRAM P VAR x : INT; END_VAR x := TRUE + ; END_PROGRAM";
    let err = p
        .online_change_files(&[("v2.st", broken)], &Options::default())
        .expect_err("refused");
    match &err {
        OnlineChangeError::Compile(e) => assert!(e.diagnostics.has_errors()),
        other => panic!("unexpected error {other:?}"),
    }
    assert!(err.to_string().contains("does not compile"), "{err}");
    // Same program, same state, same handles.
    let et = p.resolve("P.et").unwrap();
    cycles(&mut p, 1);
    assert_eq!(p.get(&et).unwrap().to_literal(), "T#30ms");
    assert_eq!(p.cycle(), 4);
}

#[test]
fn changed_tasks_are_refused() {
    let config = |interval: &str| {
        format!(
            "PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM
CONFIGURATION C RESOURCE R ON PLC
TASK T (INTERVAL := {interval}, PRIORITY := 1);
PROGRAM Main WITH T : P;
END_RESOURCE END_CONFIGURATION"
        )
    };
    let mut p = plc(&config("T#10ms"));
    cycles(&mut p, 2);
    let err = p
        .online_change_files(&[("v2.st", &config("T#20ms"))], &Options::default())
        .expect_err("refused");
    assert!(
        matches!(err, OnlineChangeError::TasksChanged { .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("tasks changed"), "{err}");
    cycles(&mut p, 1);
    assert_eq!(read(&p, "Main.n"), "3");
    // The same tasks apply.
    let report = change(&mut p, &config("T#10ms"));
    assert_eq!(report.kept, ["Main"]);
    cycles(&mut p, 1);
    assert_eq!(read(&p, "Main.n"), "4");
}

#[test]
fn handles_resolved_before_the_change_are_refused_after_it() {
    let mut p = plc(TIMER_V1);
    let et = p.resolve("P.et").unwrap();
    change(&mut p, TIMER_V2);
    assert!(p.get(&et).is_err());
    assert!(p.get(&p.resolve("P.et").unwrap()).is_ok());
}

#[test]
fn a_session_rebinds_its_trace_and_stimulus_and_refuses_a_lost_name() {
    use plcrun::{Session, SessionChangeError, parse_stimulus};
    let v1 = "PROGRAM P VAR_INPUT go : BOOL; END_VAR VAR_OUTPUT n : INT; END_VAR
IF go THEN n := n + 1; END_IF END_PROGRAM";
    // A variable declared first: every address moves.
    let v2 = "PROGRAM P VAR pad : ARRAY[1..5] OF INT; END_VAR VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR IF go THEN n := n + 2; END_IF END_PROGRAM";
    let mut s = Session::new(plc(v1));
    s.set_trace(&["n", "go"]).unwrap();
    s.bind_stimulus(parse_stimulus("cycle,go\n1,TRUE\n4,FALSE\n").unwrap())
        .unwrap();
    for _ in 0..3 {
        s.step().unwrap();
    }
    let cells = |s: &Session| -> Vec<String> { s.cells().iter().map(|c| c.text.clone()).collect() };
    assert_eq!(cells(&s), ["2", "TRUE"]);
    // A version without `go` cannot take the stimulus: refused, unchanged.
    let no_go = plc("PROGRAM P VAR_OUTPUT n : INT; END_VAR END_PROGRAM");
    let err = s.online_change(no_go).expect_err("refused");
    assert!(matches!(err, SessionChangeError::Trace(_)), "{err:?}");
    let new = Plc::compile_files(&[("v2.st", v2)], &Options::default()).unwrap();
    let report = s.online_change(new).unwrap();
    assert_eq!(report.initialised, ["P.pad"]);
    s.step().unwrap(); // cycle 3: go still TRUE, +2
    assert_eq!(cells(&s), ["4", "TRUE"]);
    s.step().unwrap(); // cycle 4: the stimulus goes on: go FALSE
    assert_eq!(cells(&s), ["4", "FALSE"]);
}

/// A new version loaded behind the session's back (through `plc_mut`) is
/// followed at the next step: the handles re-bind by name, or the step says
/// which name no longer fits, instead of reading the old layout.
#[test]
fn a_session_follows_a_change_made_through_plc_mut() {
    use plcrun::{RunError, Session, SessionChangeError, parse_stimulus};
    let v1 = "PROGRAM P VAR_INPUT go : BOOL; END_VAR VAR_OUTPUT n : INT; END_VAR
IF go THEN n := n + 1; END_IF END_PROGRAM";
    let v2 = "PROGRAM P VAR pad : ARRAY[1..500] OF INT; END_VAR VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR IF go THEN n := n + 2; END_IF END_PROGRAM";
    let opts = Options::default();
    let mut s = Session::new(plc(v1));
    s.set_trace(&["n", "go"]).unwrap();
    s.bind_stimulus(parse_stimulus("cycle,go\n1,TRUE\n4,FALSE\n").unwrap())
        .unwrap();
    for _ in 0..3 {
        s.step().unwrap();
    }
    s.plc_mut()
        .online_change_files(&[("v2.st", v2)], &opts)
        .unwrap();
    s.step().unwrap();
    let cells = |s: &Session| -> Vec<String> { s.cells().iter().map(|c| c.text.clone()).collect() };
    assert_eq!(cells(&s), ["4", "TRUE"]);
    s.step().unwrap();
    assert_eq!(cells(&s), ["4", "FALSE"], "the stimulus goes on");
    // A version without `go`: the step refuses, naming the column.
    s.plc_mut()
        .online_change_files(
            &[("v3.st", "PROGRAM P VAR_OUTPUT n : INT; END_VAR END_PROGRAM")],
            &opts,
        )
        .unwrap();
    let err = s.step().unwrap_err();
    assert!(
        matches!(err, RunError::PlcChanged(SessionChangeError::Trace(_))),
        "{err:?}"
    );
    assert!(
        err.to_string().contains("changed outside the session"),
        "{err}"
    );
    assert!(err.to_string().contains("go"), "{err}");
}

/// Forces follow the new version (or refuse it), the clock goes on, and a
/// stop handle given out before the change still aborts the new version.
#[test]
fn forces_clock_and_stop_handles_survive_an_online_change() {
    use plcrun::FaultKind;
    let v1 = "PROGRAM P VAR_OUTPUT n : INT; lamp : BOOL; END_VAR n := n + 1; END_PROGRAM";
    let v2 = "PROGRAM P VAR_OUTPUT n : INT; lamp : BOOL; m : INT; END_VAR
              n := n + 2; m := m + 1; WHILE m > 2 DO END_WHILE; END_PROGRAM";
    let v3 = "PROGRAM P VAR_OUTPUT n : INT; END_VAR n := n + 2; END_PROGRAM";
    let opts = Options::default();
    let mut plc = Plc::compile_files(&[("p.st", v1)], &opts).unwrap();
    let handle = plc.stop_handle();
    plc.force("lamp", "TRUE").unwrap();
    for _ in 0..3 {
        plc.run_cycle().unwrap();
    }
    assert_eq!(plc.time(), 30_000_000);
    // The forced variable is gone from v3: refused, nothing changes.
    let err = plc.online_change_files(&[("p.st", v3)], &opts).unwrap_err();
    assert!(
        matches!(&err, OnlineChangeError::ForceDoesNotFit { path, .. } if path == "lamp"),
        "{err}"
    );
    assert!(err.to_string().contains("unforce it first"), "{err}");
    assert_eq!(plc.read("n").unwrap().to_literal(), "3");
    plc.online_change_files(&[("p.st", v2)], &opts).unwrap();
    assert_eq!(plc.time(), 30_000_000, "the clock goes on");
    plc.write("lamp", "FALSE").unwrap();
    plc.run_cycle().unwrap();
    assert_eq!(plc.read("n").unwrap().to_literal(), "5");
    assert_eq!(
        plc.read("lamp").unwrap().to_literal(),
        "TRUE",
        "still forced"
    );
    assert_eq!(plc.forces().len(), 1);
    plc.run_cycle().unwrap();
    // m reaches 3: an endless loop, ended by the handle taken before.
    let stopper = std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_millis(50));
        handle.abort();
    });
    let fault = plc.run_cycle().unwrap_err();
    stopper.join().unwrap();
    assert_eq!(fault.fault.kind, FaultKind::Aborted);
}

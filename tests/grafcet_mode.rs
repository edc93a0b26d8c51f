//! IEC 60848 GRAFCET evolution (`Options::grafcet`, `--grafcet`) against
//! IEC 61131-3 SFC evolution: the example programs `programs/grafcet_*.sfc`
//! run in both modes and are compared with traces derived by hand from the
//! rules of each standard (the derivation is written beside every row),
//! plus the unstable-cycle fault, rule 5 and the forcing diagnostics.

use plcrun::{
    FaultKind, Options, Plc, RunError, Session, TraceFormat, TraceWriter, parse_stimulus,
};

/// Compiles `files` in the given mode, runs `cycles` cycles with the
/// stimulus and trace, returns the CSV text and how the run ended.
fn run(
    files: &[&str],
    grafcet: bool,
    cycles: u64,
    stimulus: Option<&str>,
    trace: &str,
) -> (String, Result<(), RunError>) {
    let texts: Vec<(String, String)> = files
        .iter()
        .map(|f| (f.to_string(), repo_text(f)))
        .collect();
    let named: Vec<(&str, &str)> = texts
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    run_texts(&named, grafcet, cycles, stimulus, trace)
}

fn run_texts(
    named: &[(&str, &str)],
    grafcet: bool,
    cycles: u64,
    stimulus: Option<&str>,
    trace: &str,
) -> (String, Result<(), RunError>) {
    let options = Options {
        grafcet,
        ..Options::default()
    };
    let plc = Plc::compile_files(named, &options).unwrap_or_else(|e| panic!("compile:\n{e}"));
    let mut session = Session::new(plc);
    if let Some(text) = stimulus {
        session
            .bind_stimulus(parse_stimulus(text).expect("stimulus"))
            .expect("stimulus fits");
    }
    let names: Vec<String> = trace.split(',').map(str::to_string).collect();
    session.set_trace(&names).expect("trace names");
    let mut writer = TraceWriter::new(
        Vec::new(),
        TraceFormat::Csv,
        session.trace_names().to_vec(),
        false,
    );
    let outcome = session.run(cycles, &mut writer);
    let csv = String::from_utf8(writer.finish().expect("in memory")).expect("UTF-8");
    (csv, outcome)
}

fn repo_text(path: &str) -> String {
    let full = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("read {path}: {e}"))
}

/// The expected CSV: the header, then the rows with their `--` comments
/// removed.
fn expected(header: &str, rows: &str) -> String {
    let mut out = format!("{header}\n");
    for line in rows.lines() {
        let row = line.split("--").next().unwrap_or("").trim();
        if !row.is_empty() {
            out.push_str(row);
            out.push('\n');
        }
    }
    out
}

fn ok_trace(r: (String, Result<(), RunError>)) -> String {
    match r {
        (csv, Ok(())) => csv,
        (_, Err(e)) => panic!("the run stopped: {e}"),
    }
}

const TRANSIENT_TRACE: &str = "a,b,X0.X,X1.X,X2.X,pass,seen,count";
const TRANSIENT_HEADER: &str = "cycle,time,a,b,X0.X,X1.X,X2.X,pass,seen,count";

#[test]
fn transient_program_under_iec_evolution_takes_one_transition_per_cycle() {
    let stimulus = repo_text("programs/grafcet_transient.csv");
    let got = ok_trace(run(
        &["programs/grafcet_transient.sfc"],
        false,
        13,
        Some(&stimulus),
        TRANSIENT_TRACE,
    ));
    // IEC 61131-3: one evolution per cycle, on the inputs of the cycle; N
    // is Q while the step is active; S stores, R (level) resets while X0
    // is active; P1 gives Q for one call on the rising input.
    let want = expected(
        TRANSIENT_HEADER,
        "
        0,T#0s,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,0     -- initial X0
        1,T#10ms,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,0
        2,T#20ms,TRUE,TRUE,FALSE,TRUE,FALSE,TRUE,TRUE,1       -- X0->X1 only; pass, seen, pulse
        3,T#30ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,1      -- X1->X2 one cycle later
        4,T#40ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,1
        5,T#50ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,1    -- NOT a: X2->X0, R resets seen
        6,T#60ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,1
        7,T#70ms,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,TRUE,2      -- a: X0->X1
        8,T#80ms,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,TRUE,2      -- b FALSE: X1 stays
        9,T#90ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,2      -- b: X1->X2
        10,T#100ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,2
        11,T#110ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,2  -- X2->X0, seen reset
        12,T#120ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,2
        ",
    );
    assert_eq!(got, want);
}

#[test]
fn transient_program_under_grafcet_evolution_reaches_the_stable_situation() {
    let stimulus = repo_text("programs/grafcet_transient.csv");
    let got = ok_trace(run(
        &["programs/grafcet_transient.sfc"],
        true,
        13,
        Some(&stimulus),
        TRANSIENT_TRACE,
    ));
    // IEC 60848: evolution repeats on the same inputs until stable. A step
    // entered and left in one cycle (transient) assigns no continuous
    // action (pass), but its actions on activation act (seen := 1, one
    // pulse of Tally).
    let want = expected(
        TRANSIENT_HEADER,
        "
        0,T#0s,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,0     -- initial X0
        1,T#10ms,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,0
        2,T#20ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,1      -- X0->X1->X2 (X2->X0 needs NOT a): X1 transient
        3,T#30ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,1
        4,T#40ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,1
        5,T#50ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,1    -- X2->X0 (X0->X1 needs a); R on activation
        6,T#60ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,1
        7,T#70ms,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,TRUE,2      -- X0->X1, b FALSE: X1 stable, pass
        8,T#80ms,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,TRUE,2
        9,T#90ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,2      -- X1->X2
        10,T#100ms,TRUE,TRUE,FALSE,FALSE,TRUE,FALSE,TRUE,2
        11,T#110ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,2  -- X2->X0
        12,T#120ms,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,2
        ",
    );
    assert_eq!(got, want);
}

const FORCING_TRACE: &str =
    "go,done,pause,emergency,ack,S0.X,S1.X,S2.X,S3.X,G1.P0.X,G1.P1.X,G1.P2.X,motor,unload,alarm";

#[test]
fn forcing_orders_hold_the_partial_grafcet() {
    let stimulus = repo_text("programs/grafcet_forcing.csv");
    let got = ok_trace(run(
        &["programs/grafcet_forcing.sfc"],
        true,
        16,
        Some(&stimulus),
        FORCING_TRACE,
    ));
    // GS evolves first, its stable situation's order is applied, then G1
    // is called: held (no evolution) while an order is active.
    let want = expected(
        &format!("cycle,time,{FORCING_TRACE}"),
        "
        0,T#0s,FALSE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE     -- S0, P0
        1,T#10ms,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE     -- go: P0->P1, motor
        2,T#20ms,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE
        3,T#30ms,TRUE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE      -- pause: S1, F/G1:{*}
        4,T#40ms,TRUE,TRUE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE       -- done, but G1 frozen in P1
        5,T#50ms,TRUE,TRUE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE
        6,T#60ms,TRUE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE      -- S1->S0: G1 evolves P1->P2
        7,T#70ms,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE     -- P2->P0->P1 in one cycle (go held)
        8,T#80ms,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE
        9,T#90ms,TRUE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE,FALSE,TRUE     -- emergency: S2, F/G1:{} empty
        10,T#100ms,TRUE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE,FALSE,TRUE
        11,T#110ms,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE,FALSE,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE   -- S3, F/G1:{P0}; go held but G1 forced
        12,T#120ms,TRUE,FALSE,FALSE,FALSE,FALSE,FALSE,FALSE,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE
        13,T#130ms,TRUE,FALSE,FALSE,FALSE,TRUE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE    -- ack: S0, G1 free: P0->P1
        14,T#140ms,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE
        15,T#150ms,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,FALSE,FALSE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE
        ",
    );
    assert_eq!(got, want);
}

#[test]
fn forcing_orders_are_refused_under_iec_evolution() {
    let text = repo_text("programs/grafcet_forcing.sfc");
    let err = Plc::compile_files(&[("f.sfc", &text)], &Options::default())
        .err()
        .expect("E630 without --grafcet");
    let codes: Vec<&str> = err.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(codes, ["E630", "E630", "E630"]);
}

const UNSTABLE: &str = "PROGRAM U
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT out : BOOL; END_VAR
INITIAL_STEP A : END_STEP
STEP B : out(N); END_STEP
STEP C : END_STEP
TRANSITION FROM A TO B := go; END_TRANSITION
TRANSITION FROM B TO C := TRUE; END_TRANSITION
TRANSITION FROM C TO B := go; END_TRANSITION
END_PROGRAM";

#[test]
fn an_unstable_cycle_is_fault_r020_naming_its_transitions() {
    let stim = "cycle,go\n0,FALSE\n2,TRUE\n";
    // IEC: A->B at cycle 2, then B->C, C->B alternate one per cycle.
    let (csv, outcome) = run_texts(&[("u.sfc", UNSTABLE)], false, 5, Some(stim), "go,out");
    assert!(outcome.is_ok());
    assert_eq!(
        csv,
        "cycle,time,go,out\n0,T#0s,FALSE,FALSE\n1,T#10ms,FALSE,FALSE\n2,T#20ms,TRUE,TRUE\n\
         3,T#30ms,TRUE,FALSE\n4,T#40ms,TRUE,TRUE\n"
    );
    // GRAFCET: at cycle 2, A->B, B->C, C->B, ... never stable: 3 steps,
    // bound 4 firings, then the fault names the cycle B->C, C->B.
    let (csv, outcome) = run_texts(&[("u.sfc", UNSTABLE)], true, 5, Some(stim), "go,out");
    assert_eq!(
        csv,
        "cycle,time,go,out\n0,T#0s,FALSE,FALSE\n1,T#10ms,FALSE,FALSE\n"
    );
    let Err(RunError::Fault(f)) = outcome else {
        panic!("expected a fault, got {outcome:?}");
    };
    assert_eq!(f.code(), "R020");
    assert_eq!(f.cycle, 2);
    let FaultKind::UnstableChart(u) = &f.fault.kind else {
        panic!("{f}");
    };
    assert_eq!(u.chart, "U");
    assert_eq!(u.bound, 4);
    let mut names = u.transitions.clone();
    names.sort();
    assert_eq!(names, ["B -> C", "C -> B"]);
    assert!(
        f.to_string().contains("unstable cycle of transitions"),
        "{f}"
    );
}

#[test]
fn rule_5_keeps_the_step_time_running_under_grafcet_evolution() {
    // A -> (A, B) on go and NOT B.X: A is deactivated and activated at
    // once. IEC restarts A.T; under IEC 60848 A simply stays active (no
    // new activation), so A.T keeps counting.
    let src = "PROGRAM R5
VAR_INPUT go : BOOL; END_VAR
INITIAL_STEP A : END_STEP
STEP B : END_STEP
TRANSITION FROM A TO (A, B) := go AND NOT B.X; END_TRANSITION
END_PROGRAM";
    let stim = "cycle,go\n0,FALSE\n3,TRUE\n";
    let iec = ok_trace(run_texts(
        &[("r5.sfc", src)],
        false,
        5,
        Some(stim),
        "A.T,B.X",
    ));
    let grafcet = ok_trace(run_texts(
        &[("r5.sfc", src)],
        true,
        5,
        Some(stim),
        "A.T,B.X",
    ));
    assert_eq!(
        iec,
        "cycle,time,A.T,B.X\n0,T#0s,T#0s,FALSE\n1,T#10ms,T#10ms,FALSE\n2,T#20ms,T#20ms,FALSE\n\
         3,T#30ms,T#0s,TRUE\n4,T#40ms,T#10ms,TRUE\n"
    );
    assert_eq!(
        grafcet,
        "cycle,time,A.T,B.X\n0,T#0s,T#0s,FALSE\n1,T#10ms,T#10ms,FALSE\n2,T#20ms,T#20ms,FALSE\n\
         3,T#30ms,T#30ms,TRUE\n4,T#40ms,T#40ms,TRUE\n"
    );
}

#[test]
fn a_pulse_on_deactivation_of_a_transient_step_still_acts() {
    // A -> B on go, B -> C on go: B is transient under GRAFCET evolution;
    // P0 on B acts on its deactivation, N on B does not.
    let src = "PROGRAM P
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT left, held : BOOL; END_VAR
INITIAL_STEP A : END_STEP
STEP B : left(P0); held(N); END_STEP
STEP C : END_STEP
TRANSITION FROM A TO B := go; END_TRANSITION
TRANSITION FROM B TO C := go; END_TRANSITION
END_PROGRAM";
    let stim = "cycle,go\n0,FALSE\n1,TRUE\n";
    let grafcet = ok_trace(run_texts(
        &[("p.sfc", src)],
        true,
        4,
        Some(stim),
        "left,held,C.X",
    ));
    assert_eq!(
        grafcet,
        "cycle,time,left,held,C.X\n0,T#0s,FALSE,FALSE,FALSE\n1,T#10ms,TRUE,FALSE,TRUE\n\
         2,T#20ms,FALSE,FALSE,TRUE\n3,T#30ms,FALSE,FALSE,TRUE\n"
    );
    // IEC: B active in cycle 1 (held), left pulses when B falls (cycle 2).
    let iec = ok_trace(run_texts(
        &[("p.sfc", src)],
        false,
        4,
        Some(stim),
        "left,held,C.X",
    ));
    assert_eq!(
        iec,
        "cycle,time,left,held,C.X\n0,T#0s,FALSE,FALSE,FALSE\n1,T#10ms,FALSE,TRUE,FALSE\n\
         2,T#20ms,TRUE,FALSE,TRUE\n3,T#30ms,FALSE,FALSE,TRUE\n"
    );
}

#[test]
fn chariot_scenario_gives_the_same_trace_under_grafcet_evolution() {
    // No two successive CHARIOT receptivities are TRUE together in the
    // scenario (Dcy is pressed after the trolley is back at A), so no
    // step is transient: the hand-derived IEC trace holds unchanged.
    let stimulus = repo_text("programs/chariot.csv");
    let trace = "Dcy,FcA,FcB,INIT.X,AV.X,ATT.X,AR.X,KMAV,KMAR,VOM";
    let expected = repo_text("programs/chariot.expected.csv");
    let files = ["programs/chariot.sfc"];
    let (csv, outcome) = {
        let texts = repo_text(files[0]);
        let options = Options {
            grafcet: true,
            ..Options::default()
        };
        let plc = Plc::compile_files(&[(files[0], &texts)], &options).expect("compiles");
        let mut session = Session::new(plc);
        session
            .bind_stimulus(parse_stimulus(&stimulus).unwrap())
            .unwrap();
        let names: Vec<String> = trace.split(',').map(str::to_string).collect();
        session.set_trace(&names).unwrap();
        let mut w = TraceWriter::new(
            Vec::new(),
            TraceFormat::Csv,
            session.trace_names().to_vec(),
            true,
        );
        let outcome = session.run(60320, &mut w);
        (String::from_utf8(w.finish().unwrap()).unwrap(), outcome)
    };
    assert!(outcome.is_ok());
    assert_eq!(csv, expected);
}

#[test]
fn chariot_with_dcy_held_leaves_init_in_the_same_cycle_under_grafcet_evolution() {
    // Dcy held when the trolley reaches A (FcA at cycle 5): IEC goes
    // AR -> INIT at 5 and INIT -> AV at 6; GRAFCET goes AR -> INIT -> AV
    // at 5 (INIT transient: KMAR drops and KMAV rises in the same cycle).
    let stim = "cycle,Dcy,FcA,FcB\n0,TRUE,TRUE,FALSE\n1,,FALSE,\n2,,,TRUE\n3,,,FALSE\n5,,TRUE,\n";
    let trace = "INIT.X,AV.X,AR.X,KMAV,KMAR";
    let src = repo_text("programs/chariot.sfc");
    // tX3 := T#10ms: ATT lasts one cycle.
    let src = src.replace("T#10m ;", "T#10ms ;");
    let iec = ok_trace(run_texts(&[("c.sfc", &src)], false, 7, Some(stim), trace));
    let grafcet = ok_trace(run_texts(&[("c.sfc", &src)], true, 7, Some(stim), trace));
    let head = "cycle,time,INIT.X,AV.X,AR.X,KMAV,KMAR\n";
    assert_eq!(
        iec,
        format!(
            "{head}0,T#0s,FALSE,TRUE,FALSE,TRUE,FALSE\n\
             1,T#10ms,FALSE,TRUE,FALSE,TRUE,FALSE\n\
             2,T#20ms,FALSE,FALSE,FALSE,FALSE,FALSE\n\
             3,T#30ms,FALSE,FALSE,TRUE,FALSE,TRUE\n\
             4,T#40ms,FALSE,FALSE,TRUE,FALSE,TRUE\n\
             5,T#50ms,TRUE,FALSE,FALSE,FALSE,FALSE\n\
             6,T#60ms,FALSE,TRUE,FALSE,TRUE,FALSE\n"
        )
    );
    assert_eq!(
        grafcet,
        format!(
            "{head}0,T#0s,FALSE,TRUE,FALSE,TRUE,FALSE\n\
             1,T#10ms,FALSE,TRUE,FALSE,TRUE,FALSE\n\
             2,T#20ms,FALSE,FALSE,FALSE,FALSE,FALSE\n\
             3,T#30ms,FALSE,FALSE,TRUE,FALSE,TRUE\n\
             4,T#40ms,FALSE,FALSE,TRUE,FALSE,TRUE\n\
             5,T#50ms,FALSE,TRUE,FALSE,TRUE,FALSE\n\
             6,T#60ms,FALSE,TRUE,FALSE,TRUE,FALSE\n"
        )
    );
}

/// The codes of compiling `src` under GRAFCET evolution.
fn grafcet_codes(src: &str) -> Vec<&'static str> {
    let options = Options {
        grafcet: true,
        ..Options::default()
    };
    match Plc::compile_files(&[("d.sfc", src)], &options) {
        Ok(plc) => plc.warnings().iter().map(|d| d.code).collect(),
        Err(e) => e.diagnostics.iter().map(|d| d.code).collect(),
    }
}

const FB: &str = "FUNCTION_BLOCK G
INITIAL_STEP P0 : END_STEP
STEP P1 : END_STEP
TRANSITION FROM P0 TO P1 := TRUE; END_TRANSITION
END_FUNCTION_BLOCK
FUNCTION_BLOCK PLAIN VAR_INPUT i : INT; END_VAR END_FUNCTION_BLOCK
";

fn forcer(decls: &str, order: &str) -> String {
    format!("{FB}PROGRAM M\nVAR {decls} END_VAR\nINITIAL_STEP S0 : {order} END_STEP\nEND_PROGRAM\n")
}

#[test]
fn forcing_order_diagnostics() {
    assert_eq!(
        grafcet_codes(&forcer("g : G;", "g(F, P1);")),
        Vec::<&str>::new()
    );
    assert_eq!(
        grafcet_codes(&forcer("g : G;", "g(FREEZE);")),
        Vec::<&str>::new()
    );
    assert_eq!(grafcet_codes(&forcer("g : G;", "nothing(F);")), ["E631"]);
    assert_eq!(grafcet_codes(&forcer("x : BOOL;", "x(F);")), ["E631"]);
    assert_eq!(grafcet_codes(&forcer("p : PLAIN;", "p(F);")), ["E631"]);
    assert_eq!(grafcet_codes(&forcer("g : G;", "g(F, P9);")), ["E632"]);
    assert_eq!(grafcet_codes(&forcer("g : G;", "g(FREEZE, P1);")), ["E633"]);
    assert_eq!(grafcet_codes(&forcer("g : G;", "g(F, T#1s);")), ["E633"]);
    let inout = format!(
        "{FB}FUNCTION_BLOCK M\nVAR_IN_OUT g : G; END_VAR\nINITIAL_STEP S0 : g(F); END_STEP\nEND_FUNCTION_BLOCK\n\
         PROGRAM Q VAR m : M; inner : G; END_VAR m(g := inner); END_PROGRAM\n"
    );
    assert_eq!(grafcet_codes(&inout), ["E634"]);
}

#[test]
fn a_frozen_grafcet_that_never_ran_keeps_its_initial_situation() {
    // S0 freezes g from the first cycle: g starts in P0 and stays there
    // although P0 -> P1 is always fireable.
    let src = forcer("g : G;", "g(FREEZE);")
        .replace("END_STEP\nEND_PROGRAM", "END_STEP\ng();\nEND_PROGRAM");
    let csv = ok_trace(run_texts(
        &[("z.sfc", &src)],
        true,
        3,
        None,
        "g.P0.X,g.P1.X",
    ));
    assert_eq!(
        csv,
        "cycle,time,g.P0.X,g.P1.X\n0,T#0s,TRUE,FALSE\n1,T#10ms,TRUE,FALSE\n2,T#20ms,TRUE,FALSE\n"
    );
}

#[test]
fn orders_meeting_on_one_grafcet_add_up_and_forced_active_wins() {
    // S0 -> (S1, S2, S3) on go: the orders {P1}, {} and {P2} hold g at
    // once. The course: a step forced to 0 by one grafcet and to 1 by
    // another is forced to 1; so g = {P1, P2}. Without go, g keeps {P0}
    // (its transitions read t, FALSE: it never evolves by itself).
    let src = "FUNCTION_BLOCK G
VAR_INPUT t : BOOL; END_VAR
INITIAL_STEP P0 : END_STEP
STEP P1 : END_STEP
STEP P2 : END_STEP
TRANSITION FROM P0 TO P1 := t; END_TRANSITION
TRANSITION FROM P1 TO P2 := t; END_TRANSITION
TRANSITION FROM P2 TO P0 := t; END_TRANSITION
END_FUNCTION_BLOCK
PROGRAM M
VAR_INPUT go : BOOL; END_VAR
VAR g : G; END_VAR
INITIAL_STEP S0 : END_STEP
STEP S1 : g(F, P1); END_STEP
STEP S2 : g(F); END_STEP
STEP S3 : g(F, P2); END_STEP
TRANSITION FROM S0 TO (S1, S2, S3) := go; END_TRANSITION
g();
END_PROGRAM";
    let stim = "cycle,go\n0,FALSE\n1,TRUE\n";
    let csv = ok_trace(run_texts(
        &[("m.sfc", src)],
        true,
        3,
        Some(stim),
        "g.P0.X,g.P1.X,g.P2.X",
    ));
    assert_eq!(
        csv,
        "cycle,time,g.P0.X,g.P1.X,g.P2.X\n0,T#0s,TRUE,FALSE,FALSE\n\
         1,T#10ms,FALSE,TRUE,TRUE\n2,T#20ms,FALSE,TRUE,TRUE\n"
    );
}

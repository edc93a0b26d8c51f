//! Forms of the CODESYS V3 / TwinCAT dialect met in SLAC's public
//! `lcls-twincat-*` libraries (issue #25): nested comments, keywords used
//! as names, empty declarations, the system interface an interface
//! extends, an enumeration's default named by its own value, `SUPER^.x`,
//! `THIS^.fb(...)` in an action, actions and `SUPER^()` called with the
//! block's inputs and outputs, initial values from whole structures,
//! constants and the null pointer, and strict enumerations compared with
//! integers. Each program's results are worked out by hand beside it.

use crate::support::plc::{lit, run};
use crate::support::twincat::{HEAD, action, compile, compile_ok, declaration, pou, refused};

#[test]
fn comments_nest_in_twincat_code_but_not_in_iec_text() {
    // Code commented out with its own comment inside: one comment.
    let body = "(* x := 100; (* a note *) x := 200; *)\nx := x + 1;";
    let main = pou("P", "PROGRAM P\nVAR x : INT; END_VAR", body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "x"), "2");
    // In an IEC file the first `*)` ends the comment, so the rest is code
    // that does not parse.
    let st = format!("PROGRAM P\nVAR x : INT; END_VAR\n{body}\nEND_PROGRAM\n");
    assert!(compile(&[("p.st", &st)]).is_err());
}

#[test]
fn transition_is_a_name_where_no_transition_starts() {
    let states = declaration(
        "DUT",
        "E_State",
        "{attribute 'qualified_only'}\nTYPE E_State : (IDLE, TRANSITION, DONE); END_TYPE",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR st : E_State := E_State.TRANSITION; n : INT; END_VAR",
        "IF st = E_State.TRANSITION THEN n := n + 1; st := E_State.DONE; END_IF",
        "",
    );
    let mut plc = compile_ok(&[("E_State.TcDUT", &states), ("P.TcPOU", &main)]);
    run(&mut plc, 3);
    assert_eq!(lit(&plc, "n"), "1");
    assert_eq!(lit(&plc, "st"), "DONE");
}

#[test]
fn an_empty_declaration_is_skipped_with_a_warning() {
    let main = pou(
        "P",
        "PROGRAM P\nVAR ; x : INT := 2;; y : INT; END_VAR",
        "y := x * 3;",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "y"), "6");
    // W360 is a CODESYS-extension warning: not shown for TwinCAT code,
    // refused under --strict like the others.
    assert!(plc.warnings().iter().all(|d| d.code != "W360"));
    let st = "PROGRAM P\nVAR x : INT := 2;; END_VAR\nEND_PROGRAM\n";
    let plc = crate::support::plc::compile(st);
    assert_eq!(
        plc.warnings().iter().filter(|d| d.code == "W360").count(),
        1
    );
}

#[test]
fn an_interface_extends_the_system_query_interface_with_a_trailing_comma() {
    let itf = format!(
        "{HEAD}<Itf Name=\"I_Axis\" Id=\"{{00000000-0000-0000-0000-000000000003}}\">\n<Declaration><![CDATA[INTERFACE I_Axis EXTENDS __SYSTEM.IQueryInterface, \n]]></Declaration>\n<Method Name=\"Pos\" Id=\"{{00000000-0000-0000-0000-000000000004}}\"><Declaration><![CDATA[METHOD Pos : LREAL]]></Declaration></Method>\n</Itf>\n</TcPlcObject>\n"
    );
    let axis = pou(
        "FB_Axis",
        "FUNCTION_BLOCK FB_Axis IMPLEMENTS I_Axis\nVAR f : LREAL := 1.5; END_VAR",
        "",
        "<Method Name=\"Pos\" Id=\"{00000000-0000-0000-0000-000000000005}\"><Declaration><![CDATA[METHOD Pos : LREAL]]></Declaration><Implementation><ST><![CDATA[Pos := f * 2;]]></ST></Implementation></Method>\n",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR a : FB_Axis; i : I_Axis; x : LREAL; END_VAR",
        "i := a; x := i.Pos();",
        "",
    );
    let mut plc = compile_ok(&[
        ("I_Axis.TcIO", &itf),
        ("FB_Axis.TcPOU", &axis),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "x"), "3.0");
}

#[test]
fn an_enumeration_s_default_may_name_its_own_value_alone() {
    let mode = declaration(
        "DUT",
        "E_Access",
        "{attribute 'qualified_only'}\n{attribute 'strict'}\nTYPE E_Access :\n(\n    LOCAL := 0,\n    REMOTE := 1,\n    LOCKED := 2\n) USINT := REMOTE;\nEND_TYPE",
    );
    let main = pou("P", "PROGRAM P\nVAR e : E_Access; END_VAR", "", "");
    let mut plc = compile_ok(&[("E_Access.TcDUT", &mode), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "e"), "REMOTE");
    // A variable's initial value still names it with its type.
    let bare = pou(
        "P",
        "PROGRAM P\nVAR e : E_Access := LOCKED; END_VAR",
        "",
        "",
    );
    let err = refused(&[("E_Access.TcDUT", &mode), ("P.TcPOU", &bare)]);
    assert!(err.to_string().contains("error[E433]"), "{err}");
}

#[test]
fn super_names_the_parent_s_variables_and_calls_its_body_with_inputs() {
    let base = pou(
        "FB_Base",
        "FUNCTION_BLOCK FB_Base\nVAR_INPUT k : INT; END_VAR\nVAR_OUTPUT n : INT; END_VAR\nVAR bRestore : BOOL := TRUE; END_VAR",
        "n := n + k;",
        "",
    );
    // The first call restores once through `SUPER^.bRestore`; every call
    // runs the parent's body with k := 2 * z (3 each time: n = 6, 12).
    let derived = pou(
        "FB_Derived",
        "FUNCTION_BLOCK FB_Derived EXTENDS FB_Base\nVAR_INPUT z : INT; END_VAR\nVAR nRestored : INT; END_VAR",
        "ACT_Persistent();\nSUPER^(k := z * 2);",
        &action(
            "ACT_Persistent",
            "IF SUPER^.bRestore THEN SUPER^.bRestore := FALSE; nRestored := nRestored + 1; END_IF",
        ),
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR d : FB_Derived; n : INT; r : INT; k : INT; END_VAR",
        "d(z := 3); n := d.n; r := d.nRestored; k := d.k;",
        "",
    );
    let mut plc = compile_ok(&[
        ("FB_Base.TcPOU", &base),
        ("FB_Derived.TcPOU", &derived),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 2);
    assert_eq!(
        [lit(&plc, "n"), lit(&plc, "r"), lit(&plc, "k")],
        ["12", "1", "6"]
    );
    // SUPER^ in a block that extends nothing is E918.
    let alone = pou(
        "FB_Alone",
        "FUNCTION_BLOCK FB_Alone\nVAR b : BOOL; END_VAR",
        "SUPER^.b := TRUE;",
        "",
    );
    let main = pou("P", "PROGRAM P\nVAR a : FB_Alone; END_VAR", "a();", "");
    let err = refused(&[("FB_Alone.TcPOU", &alone), ("P.TcPOU", &main)]);
    assert!(err.to_string().contains("error[E918]"), "{err}");
}

#[test]
fn an_action_called_with_arguments_sets_the_block_s_inputs_and_reads_its_outputs() {
    let table = pou(
        "FB_Table",
        "FUNCTION_BLOCK FB_Table\nVAR_INPUT key : DINT; step : DINT := 1; END_VAR\nVAR_OUTPUT bOk : BOOL; sum : DINT; END_VAR",
        "sum := 0;",
        &action("A_Add", "sum := sum + key * step; bOk := sum < 12;"),
    );
    // Cycle 1: key 5 (step keeps 1): sum 5, ok. Cycle 2: 10, ok. Cycle 3:
    // 15, not ok. An input not given keeps its value, as in a call of the
    // instance.
    let main = pou(
        "P",
        "PROGRAM P\nVAR t : FB_Table; ok : BOOL; x : DINT; END_VAR",
        "t.A_Add(key := 5, bOk => ok); x := t.sum;",
        "",
    );
    let mut plc = compile_ok(&[("FB_Table.TcPOU", &table), ("P.TcPOU", &main)]);
    run(&mut plc, 2);
    assert_eq!([lit(&plc, "x"), lit(&plc, "ok")], ["10", "TRUE"]);
    run(&mut plc, 1);
    assert_eq!([lit(&plc, "x"), lit(&plc, "ok")], ["15", "FALSE"]);
    // A name that is neither the action's nor the block's is E403.
    let typo = main.replace("key := 5", "kee := 5");
    let err = refused(&[("FB_Table.TcPOU", &table), ("P.TcPOU", &typo)]);
    assert!(err.to_string().contains("error[E403]"), "{err}");
}

#[test]
fn this_calls_an_fb_instance_of_the_block_from_an_action() {
    let fb = pou(
        "FB_Pump",
        "FUNCTION_BLOCK FB_Pump\nVAR tILK : TON; bTripped : BOOL; END_VAR",
        "ACT_Interlock();",
        &action(
            "ACT_Interlock",
            "This^.tILK(IN := TRUE, PT := T#20MS, Q => bTripped);",
        ),
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR p : FB_Pump; q : BOOL; END_VAR",
        "p(); q := p.bTripped;",
        "",
    );
    let mut plc = compile_ok(&[("FB_Pump.TcPOU", &fb), ("P.TcPOU", &main)]);
    // 10 ms cycles: the timer started at 0 ms reaches 20 ms in cycle 3.
    run(&mut plc, 2);
    assert_eq!(lit(&plc, "q"), "FALSE");
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "q"), "TRUE");
}

#[test]
fn initial_values_from_whole_structures_constants_and_the_null_pointer() {
    let st = declaration(
        "DUT",
        "ST_Beam",
        "TYPE ST_Beam : STRUCT nRate : UDINT; fEnergy : REAL; END_STRUCT END_TYPE",
    );
    let gvl = declaration(
        "GVL",
        "PMPS_GVL",
        "{attribute 'qualified_only'}\nVAR_GLOBAL CONSTANT\n    cstFullBeam : ST_Beam := (nRate := 120, fEnergy := 2.5);\n    EXCLUDED_ID : UDINT := 16#FFFFFFFF;\nEND_VAR\nVAR_GLOBAL\n    g_Dummy : ST_Beam := (nRate := 7);\nEND_VAR",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n    a : ST_Beam := PMPS_GVL.cstFullBeam;\n    b : ST_Beam := g_Dummy;\n    nID : DWORD := PMPS_GVL.EXCLUDED_ID;\n    p : POINTER TO INT := 0;\n    bNull : BOOL;\nEND_VAR",
        "bNull := p = 0;",
        "",
    );
    let mut plc = compile_ok(&[
        ("ST_Beam.TcDUT", &st),
        ("PMPS_GVL.TcGVL", &gvl),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    assert_eq!(
        [
            lit(&plc, "a.nRate"),
            lit(&plc, "a.fEnergy"),
            lit(&plc, "b.nRate"),
            lit(&plc, "nID"),
            lit(&plc, "bNull"),
        ],
        ["120", "2.5", "7", "16#FFFFFFFF", "TRUE"]
    );
    // In a plain IEC file a UDINT constant does not initialise a DWORD.
    let iec = "VAR_GLOBAL CONSTANT ID : UDINT := 5; END_VAR\nPROGRAM P\nVAR n : DWORD := ID; END_VAR\nEND_PROGRAM\n";
    let err = refused(&[("p.st", iec)]);
    assert!(err.to_string().contains("error[E301]"), "{err}");
}

#[test]
fn a_strict_enumeration_compares_with_an_integer_but_takes_no_arithmetic() {
    let cmd = declaration(
        "DUT",
        "E_Cmd",
        "{attribute 'qualified_only'}\n{attribute 'strict'}\nTYPE E_Cmd : (JOG := 0, MOVE := 3, HOME := 10); END_TYPE",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR nCommand : INT := 10; bHome : BOOL; bMove : BOOL; END_VAR",
        "bHome := nCommand = E_Cmd.HOME; bMove := nCommand <> E_Cmd.HOME;",
        "",
    );
    let mut plc = compile_ok(&[("E_Cmd.TcDUT", &cmd), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!([lit(&plc, "bHome"), lit(&plc, "bMove")], ["TRUE", "FALSE"]);
    let sum = main.replace(
        "bMove := nCommand <> E_Cmd.HOME;",
        "nCommand := nCommand + E_Cmd.HOME;",
    );
    let err = refused(&[("E_Cmd.TcDUT", &cmd), ("P.TcPOU", &sum)]);
    assert!(err.to_string().contains("error[E306]"), "{err}");
}

/// A `.TcTTO` task file calling `programs` every `cycle_us` µs.
fn task(name: &str, cycle_us: u32, priority: u32, programs: &[&str]) -> String {
    let calls: String = programs
        .iter()
        .map(|p| format!("<PouCall><Name>{p}</Name></PouCall>\n"))
        .collect();
    format!(
        "{HEAD}<Task Name=\"{name}\" Id=\"{{00000000-0000-0000-0000-000000000007}}\">\n<CycleTime>{cycle_us}</CycleTime>\n<Priority>{priority}</Priority>\n{calls}</Task>\n</TcPlcObject>\n"
    )
}

#[test]
fn task_information_follows_each_task_s_activations() {
    // FAST runs every 10 ms (ticks 0, 1, 2, 3), SLOW every 20 ms (ticks
    // 0 and 2): after 4 ticks FAST counted 4 activations, SLOW 2. Each
    // program reads its own task's element through the index its task
    // has while it runs; FirstCycle was TRUE in each task's first run
    // only (counted by nFirst).
    let reader = |name: &str| {
        pou(
            name,
            &format!(
                "PROGRAM {name}\nVAR idx : GETCURTASKINDEX; nIndex : BYTE; nCount : UDINT; nFirst : INT; nCycle : UDINT; nPrio : UINT; sName : STRING; nEx : DINT; END_VAR"
            ),
            "idx();\nnIndex := idx.index;\nnEx := GETCURTASKINDEXEX();\nnCount := TwinCAT_SystemInfoVarList._TaskInfo[idx.index].CycleCount;\nIF _TaskInfo[nEx].FirstCycle THEN nFirst := nFirst + 1; END_IF\nnCycle := _TaskInfo[nIndex].CycleTime;\nnPrio := _TaskInfo[nIndex].Priority;\nsName := _TaskInfo[nIndex].TaskName;",
            "",
        )
    };
    let (fast, slow) = (reader("PFast"), reader("PSlow"));
    let files = [
        ("PFast.TcPOU", fast.as_str()),
        ("PSlow.TcPOU", slow.as_str()),
        ("FAST.TcTTO", &task("FAST", 10_000, 10, &["PFast"])),
        ("SLOW.TcTTO", &task("SLOW", 20_000, 20, &["PSlow"])),
    ];
    let files: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, *t)).collect();
    let mut plc =
        plcrun::Plc::compile_files(&files, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    run(&mut plc, 4);
    let row = |p: &str| {
        [
            "nIndex", "nEx", "nCount", "nFirst", "nCycle", "nPrio", "sName",
        ]
        .map(|v| lit(&plc, &format!("{p}.{v}")))
    };
    assert_eq!(
        row("PFast"),
        ["16#1", "1", "4", "1", "100000", "10", "'FAST'"]
    );
    assert_eq!(
        row("PSlow"),
        ["16#2", "2", "2", "1", "200000", "20", "'SLOW'"]
    );
    // A cold reset counts again from the first cycle.
    plc.reset_cold();
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "PFast.nCount"), "1");
    assert_eq!(lit(&plc, "PFast.nFirst"), "1");
}

#[test]
fn a_pointer_to_a_block_in_one_list_does_not_hide_another_list_s_globals() {
    // `POINTER TO FB_Suite` in the first list lays the block out (which
    // compiles its body) before the second list is read: the body's
    // global must be declared by then (TcUnit's `GVL_TcUnit` points to
    // its suites, whose body reads TwinCAT's `_TaskInfo`).
    let first = declaration(
        "GVL",
        "GVL_A",
        "VAR_GLOBAL\n    pCurrent : POINTER TO FB_Suite;\n    aSuites : ARRAY[1..2] OF POINTER TO FB_Suite;\nEND_VAR",
    );
    let suite = pou(
        "FB_Suite",
        "FUNCTION_BLOCK FB_Suite\nVAR n : INT; END_VAR",
        "n := nLimit;",
        "",
    );
    let second = declaration(
        "GVL",
        "GVL_B",
        "VAR_GLOBAL\n    nLimit : INT := 7;\nEND_VAR",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR s : FB_Suite; x : INT; END_VAR",
        "GVL_A.pCurrent := ADR(s); s(); x := GVL_A.pCurrent^.n;",
        "",
    );
    let mut plc = compile_ok(&[
        ("GVL_A.TcGVL", &first),
        ("FB_Suite.TcPOU", &suite),
        ("GVL_B.TcGVL", &second),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "x"), "7");
}

#[test]
fn extending_a_block_that_is_not_declared_says_so() {
    let derived = pou(
        "FB_Gauge",
        "FUNCTION_BLOCK FB_Gauge EXTENDS FB_GaugeBase\nVAR x : INT; END_VAR",
        "",
        "",
    );
    let main = pou("P", "PROGRAM P\nVAR g : FB_Gauge; END_VAR", "g();", "");
    let err = refused(&[("FB_Gauge.TcPOU", &derived), ("P.TcPOU", &main)]);
    assert!(
        err.contains("error[E902]: `FB_GaugeBase` is not declared"),
        "{err}"
    );
    // A declared name that is no block keeps the first message.
    let st = "TYPE ST_Base : STRUCT a : INT; END_STRUCT END_TYPE\nFUNCTION_BLOCK F EXTENDS ST_Base END_FUNCTION_BLOCK\nPROGRAM P VAR f : F; END_VAR END_PROGRAM\n";
    let err = refused(&[("p.st", st)]);
    assert!(err.contains("`ST_Base` is not a FUNCTION_BLOCK"), "{err}");
}

#[test]
fn an_enumeration_connects_to_an_in_out_of_its_base_type_and_isvalidref_takes_members() {
    let states = declaration(
        "DUT",
        "E_InOut",
        "{attribute 'qualified_only'}\nTYPE E_InOut : (UNKNOWN := 0, OUT := 1, IN := 2) INT; END_TYPE",
    );
    // The block writes 2 through its INT in-out into the enumeration.
    let mover = pou(
        "FB_Move",
        "FUNCTION_BLOCK FB_Move\nVAR_IN_OUT setState : INT; END_VAR\nVAR r : REFERENCE TO INT; bValid : BOOL; END_VAR",
        "bValid := __ISVALIDREF(THIS^.r);\nIF setState = 1 THEN setState := 2; END_IF",
        "",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR e : E_InOut := E_InOut.OUT; m : FB_Move; v : BOOL := TRUE; END_VAR",
        "m(setState := e); v := m.bValid;",
        "",
    );
    let mut plc = compile_ok(&[
        ("E_InOut.TcDUT", &states),
        ("FB_Move.TcPOU", &mover),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    assert_eq!([lit(&plc, "e"), lit(&plc, "v")], ["IN", "FALSE"]);
    // A strict enumeration is connected the same way, as TwinCAT does
    // (an integer into its in-out is not: tests/twincat_pmps_forms.rs).
    let strict = states.replace(
        "{attribute 'qualified_only'}",
        "{attribute 'qualified_only'}\n{attribute 'strict'}",
    );
    let mut plc = compile_ok(&[
        ("E_InOut.TcDUT", &strict),
        ("FB_Move.TcPOU", &mover),
        ("P.TcPOU", &main),
    ]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "e"), "IN");
}

#[test]
fn an_initial_duration_adds_and_subtracts_constant_durations() {
    // lcls-twincat-general's circuit-breaker suite:
    // `tTrickle : TON := (PT := GVL_Logger.nTrickleTripTime + T#1s);`.
    let list = declaration(
        "GVL",
        "GVL_Logger",
        "{attribute 'qualified_only'}\nVAR_GLOBAL CONSTANT\n  nTrip : TIME := T#10S;\n  nLong : LTIME := LTIME#1H;\nEND_VAR",
    );
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  t : TON := (PT := GVL_Logger.nTrip + T#1S);\n  u : TIME := GVL_Logger.nTrip - T#250MS + T#1M;\n  l : LTIME := GVL_Logger.nLong - LTIME#1M;\n  pt : TIME;\nEND_VAR",
        "pt := t.PT;",
        "",
    );
    let mut plc = compile_ok(&[("GVL_Logger.TcGVL", &list), ("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(
        [lit(&plc, "pt"), lit(&plc, "u"), lit(&plc, "l")],
        ["T#11s", "T#1m9s750ms", "LT#59m"]
    );
    // A duration from anything but durations is still refused.
    let bad = pou(
        "P",
        "PROGRAM P\nVAR u : TIME := GVL_Logger.nTrip * 2; END_VAR",
        "",
        "",
    );
    let err = refused(&[("GVL_Logger.TcGVL", &list), ("P.TcPOU", &bad)]);
    assert!(err.contains("E205"), "{err}");
}

#[test]
fn attributes_only_tools_read_are_not_shown_for_twincat_code() {
    // SLAC's EPICS generator reads `pytmc` on most declarations; CODESYS's
    // `instance-path` does change the variable, and stays named (W151).
    let main = pou(
        "P",
        "PROGRAM P\nVAR\n  {attribute 'pytmc' := 'pv: TST:X\n    io: i'}\n  x : INT := 2;\n  {attribute 'instance-path'}\n  sPath : STRING;\nEND_VAR",
        "{flow}\nx := x + 1;\n{noflow}",
        "",
    );
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "x"), "3");
    let codes: Vec<&str> = plc.warnings().iter().map(|d| d.code).collect();
    assert_eq!(codes, ["W151"]);
    // In an IEC file the same attribute is shown, as W155.
    let st =
        "PROGRAM P\nVAR {attribute 'pytmc' := 'pv: X'} x : INT; END_VAR\nx := 1;\nEND_PROGRAM\n";
    let plc = crate::support::plc::compile(st);
    let codes: Vec<&str> = plc.warnings().iter().map(|d| d.code).collect();
    assert_eq!(codes, ["W155"]);
}

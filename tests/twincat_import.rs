//! TwinCAT 3 projects given to the command line (issue #25, point 1): a
//! folder or a `.plcproj` loads its `.TcPOU`/`.TcDUT`/`.TcGVL`/`.TcIO`/
//! `.TcTTO` files, methods, properties and actions run, the task file
//! sets the cycle, and every diagnostic points into the XML file at the
//! line and column of the ST text.

use crate::support::cli;

use cli::{plcrun, plcrun_ok, temp_project};
use std::path::Path;

/// The trace of the example project `tests/twincat/conveyor`, derived by
/// hand: MAIN adds its cycle number to the counter, resets it (an action)
/// in cycle 3 and reads it back through a property and an interface;
/// the task file says 10 ms.
const CONVEYOR_TRACE: &str = "\
cycle,time,MAIN.nCycle,MAIN.nTotal,MAIN.nViaItf,MAIN.stStats.nMax,MAIN.stStats.nResets,MAIN.fbCounter.nCalls,bRunning
0,T#0s,1,1,1,1,0,1,FALSE
1,T#10ms,2,3,3,3,0,2,FALSE
2,T#20ms,3,0,0,3,1,3,FALSE
3,T#30ms,4,4,4,4,1,4,FALSE
4,T#40ms,5,9,9,9,1,5,TRUE
";

const CONVEYOR_VARS: &str = "MAIN.nCycle,MAIN.nTotal,MAIN.nViaItf,MAIN.stStats.nMax,MAIN.stStats.nResets,MAIN.fbCounter.nCalls,bRunning";

#[test]
fn a_project_folder_and_its_plcproj_run_the_same_program_on_the_task_cycle() {
    for target in [
        "tests/twincat/conveyor",
        "tests/twincat/conveyor/Conveyor.plcproj",
    ] {
        let out = plcrun_ok(&[target, "--cycles", "5", "--trace", CONVEYOR_VARS]);
        assert_eq!(out, CONVEYOR_TRACE, "{target}");
    }
    let (code, _, err) = plcrun(&["check", "tests/twincat/conveyor"]);
    assert_eq!((code, err.as_str()), (0, "ok: 6 files checked\n"));
}

/// A `.TcPOU` file with `declaration`, then `inner` (methods, actions...),
/// and an ST body.
fn pou(name: &str, declaration: &str, body: &str, inner: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <POU Name=\"{name}\" Id=\"{{00000000-0000-0000-0000-000000000001}}\" SpecialFunc=\"None\">\n    <Declaration><![CDATA[{declaration}]]></Declaration>\n    <Implementation>\n      <ST><![CDATA[{body}]]></ST>\n    </Implementation>\n{inner}  </POU>\n</TcPlcObject>\n"
    )
}

fn task(name: &str, cycle: &str, programs: &[&str]) -> String {
    let calls: String = programs
        .iter()
        .map(|p| format!("    <PouCall>\n      <Name>{p}</Name>\n    </PouCall>\n"))
        .collect();
    format!(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <Task Name=\"{name}\" Id=\"{{00000000-0000-0000-0000-000000000002}}\">\n    <CycleTime>{cycle}</CycleTime>\n    <Priority>20</Priority>\n{calls}  </Task>\n</TcPlcObject>\n"
    )
}

#[test]
fn errors_in_a_method_body_point_at_its_line_and_column_in_the_xml_file() {
    let method = "    <Method Name=\"Bump\" Id=\"{00000000-0000-0000-0000-000000000003}\">\n      <Declaration><![CDATA[METHOD Bump : BOOL\n]]></Declaration>\n      <Implementation>\n        <ST><![CDATA[n := n + 1;\nn := missing * 2;\n]]></ST>\n      </Implementation>\n    </Method>\n";
    let dir = temp_project(&[(
        "FB_Bump.TcPOU",
        &pou(
            "FB_Bump",
            "FUNCTION_BLOCK FB_Bump\nVAR\n    n : INT;\nEND_VAR\n",
            "Bump();\n",
            method,
        ),
    )]);
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 1, "{err}");
    // The unknown name is on line 18 of the file, after `n := `.
    assert!(err.contains("FB_Bump.TcPOU:18:6"), "{err}");
    assert!(err.contains("n := missing * 2;"), "{err}");
}

#[test]
fn graphical_bodies_transitions_and_other_objects_are_refused_by_name() {
    let sfc = "<?xml version=\"1.0\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <POU Name=\"P\" Id=\"{0}\">\n    <Declaration><![CDATA[PROGRAM P\n]]></Declaration>\n    <Implementation>\n      <SFC>\n      </SFC>\n    </Implementation>\n    <Transition Name=\"t\" Id=\"{1}\"/>\n  </POU>\n</TcPlcObject>\n";
    let visu = "<?xml version=\"1.0\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <Visu Name=\"V\" Id=\"{2}\"/>\n</TcPlcObject>\n";
    let dir = temp_project(&[("P.TcPOU", sfc), ("V.TcPOU", visu)]);
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("error[E871]: `<SFC>` body refused: it is a sequential function chart")
            && err.contains("P.TcPOU:7:7"),
        "{err}"
    );
    assert!(
        err.contains("`<Transition>` refused") && err.contains("P.TcPOU:10:5"),
        "{err}"
    );
    assert!(
        err.contains("`<Visu>` refused") && err.contains("V.TcPOU:3:3"),
        "{err}"
    );
}

#[test]
fn malformed_files_and_bad_task_settings_are_errors_at_their_place() {
    let dir = temp_project(&[
        (
            "Broken.TcPOU",
            "<?xml version=\"1.0\"?>\n<TcPlcObject>\n  <POU Name=\"x\">\n</TcPlcObject>\n",
        ),
        ("Fast.TcTTO", &task("Fast", "0", &["MAIN"])),
        ("Slow.TcTTO", &task("Slow", "ten", &["MAIN"])),
        (
            "NoCycle.TcTTO",
            "<?xml version=\"1.0\"?>\n<TcPlcObject>\n  <Task Name=\"T\"><Priority>1</Priority></Task>\n</TcPlcObject>\n",
        ),
    ]);
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("error[E870]: malformed XML") && err.contains("Broken.TcPOU:4:"),
        "{err}"
    );
    assert!(
        err.contains("error[E873]: the cycle time of task `Fast` is `0`")
            && err.contains("Fast.TcTTO:4:16"),
        "{err}"
    );
    assert!(
        err.contains("the cycle time of task `Slow` is `ten`"),
        "{err}"
    );
    assert!(
        err.contains("error[E872]: task `T` has no `<CycleTime>`")
            && err.contains("NoCycle.TcTTO:3:3"),
        "{err}"
    );
}

#[test]
fn the_tasks_of_several_task_files_form_one_configuration() {
    let counter = |name: &str| {
        pou(
            name,
            &format!("PROGRAM {name}\nVAR\n    n : INT;\nEND_VAR\n"),
            "n := n + 1;\n",
            "",
        )
    };
    let dir = temp_project(&[
        ("Fast.TcPOU", &counter("Fast")),
        ("Slow.TcPOU", &counter("Slow")),
        ("FastTask.TcTTO", &task("FastTask", "1000", &["Fast"])),
        ("SlowTask.TcTTO", &task("SlowTask", "3000", &["Slow"])),
    ]);
    let out = plcrun_ok(&[&dir, "--cycles", "6", "--trace", "Fast.n,Slow.n"]);
    assert_eq!(
        out,
        "cycle,time,Fast.n,Slow.n\n0,T#0s,1,1\n1,T#1ms,2,1\n2,T#2ms,3,1\n3,T#3ms,4,2\n4,T#4ms,5,2\n5,T#5ms,6,2\n"
    );
}

#[test]
fn a_folder_without_a_project_file_loads_its_objects_and_sources() {
    let dir = temp_project(&[
        (
            "POUs/MAIN.TcPOU",
            &pou(
                "MAIN",
                "PROGRAM MAIN\nVAR\n    x : INT;\nEND_VAR\n",
                "x := Twice(x + 1);\n",
                "",
            ),
        ),
        (
            "lib/twice.st",
            "FUNCTION Twice : INT\nVAR_INPUT a : INT; END_VAR\nTwice := 2 * a;\nEND_FUNCTION\n",
        ),
        ("notes.txt", "not a source"),
    ]);
    let out = plcrun_ok(&[&dir, "--cycles", "3", "--trace", "x"]);
    assert_eq!(out, "cycle,time,x\n0,T#0s,2\n1,T#10ms,6\n2,T#20ms,14\n");
}

#[test]
fn a_folder_with_two_projects_or_none_is_a_usage_error() {
    let proj = "<?xml version=\"1.0\"?>\n<Project xmlns=\"http://schemas.microsoft.com/developer/msbuild/2003\">\n  <ItemGroup>\n    <Compile Include=\"MAIN.TcPOU\"/>\n  </ItemGroup>\n</Project>\n";
    let dir = temp_project(&[("a/A.plcproj", proj), ("b/B.plcproj", proj)]);
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("holds 2 TwinCAT projects: name one of") && err.contains("A.plcproj"),
        "{err}"
    );
    // The project names a file that is not there.
    let (code, _, err) = plcrun(&["check", &format!("{dir}/a/A.plcproj")]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("MAIN.TcPOU"), "{err}");
    let empty = temp_project(&[("readme.md", "nothing here")]);
    let (code, _, err) = plcrun(&["check", &empty]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("holds no .plcproj"), "{err}");
    let not_msbuild = temp_project(&[("X.plcproj", "<?xml version=\"1.0\"?>\n<project/>\n")]);
    let (code, _, err) = plcrun(&["check", &format!("{not_msbuild}/X.plcproj")]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("not a TwinCAT project"), "{err}");
}

#[test]
fn the_tc2_library_items_run_and_a_project_s_own_declaration_wins() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    l : T_MaxString;\n    r : T_MaxString;\n    a : ARRAY[0..3] OF INT := [1, 2, 3, 4];\n    b : ARRAY[0..3] OF INT;\n    nCopied : UDINT;\n    nSame : DINT;\n    nAfterSet : DINT;\n    rand : DRAND;\n    x : LREAL;\n    p : PVOID;\nEND_VAR\n",
        "l := F_LTrim('  ab c ');\nr := F_RTrim('  ab c ');\nnCopied := MEMCPY(ADR(b), ADR(a), SIZEOF(a));\nnSame := MEMCMP(ADR(a), ADR(b), SIZEOF(a));\nMEMSET(ADR(b), 0, 2);\nnAfterSet := MEMCMP(ADR(a), ADR(b), SIZEOF(a));\nMEMMOVE(ADR(a), ADR(b), 4);\nrand(Seed := 3);\nx := rand.Num;\np := ADR(a);\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main)]);
    let vars = "l,r,nCopied,nSame,nAfterSet,b[0],a[0],a[1],a[3]";
    let out = plcrun_ok(&[&dir, "--cycles", "1", "--trace", vars]);
    assert_eq!(
        out,
        "cycle,time,l,r,nCopied,nSame,nAfterSet,b[0],a[0],a[1],a[3]\n0,T#0s,'ab c ','  ab c',8,0,1,0,0,2,4\n"
    );
    // DRAND: in [0, 1), the same sequence for the same seed.
    let draws = |seed: &str| {
        let src = main.replace("Seed := 3", &format!("Seed := {seed}"));
        let dir = temp_project(&[("MAIN.TcPOU", &src)]);
        plcrun_ok(&[&dir, "--cycles", "50", "--trace", "x"])
    };
    let first = draws("3");
    assert_eq!(first, draws("3"));
    assert_ne!(first, draws("4"));
    for line in first.lines().skip(1) {
        let x: f64 = line.rsplit(',').next().unwrap().parse().unwrap();
        assert!((0.0..1.0).contains(&x), "{x}");
    }
    // The CODESYS-extension warnings (ADR, SIZEOF, POINTER TO) are not
    // shown for TwinCAT code, nor any of the library's own; --strict still
    // refuses them.
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!((code, err.as_str()), (0, "ok: 1 file checked\n"));
    let (code, _, err) = plcrun(&["check", "--strict", &dir]);
    assert_eq!(code, 1);
    assert!(
        err.contains("error[W301]") && !err.contains("<TwinCAT libraries>"),
        "{err}"
    );
    // A project declaring its own F_LTrim uses it.
    let own = pou(
        "F_LTrim",
        "FUNCTION F_LTrim : STRING\nVAR_INPUT in : STRING; END_VAR\n",
        "F_LTrim := 'mine';\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main), ("F_LTrim.TcPOU", &own)]);
    assert!(plcrun_ok(&[&dir, "--cycles", "1", "--trace", "l"]).ends_with("0,T#0s,'mine'\n"));
}

/// Tc2_EtherCAT's distributed-clock time: plcrun's clock starts at the
/// DC epoch (2000-01-01), and DCTIME64_TO_STRING prints dates across leap
/// years and century rules. Each count of nanoseconds below is worked out
/// by hand from the days before the date (e.g. 2024-02-29: 24 years with 6
/// leap days, then 31 + 28 days: 8 825 days).
#[test]
fn distributed_clock_times_start_at_the_epoch_and_print_as_dates() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    t : Tc2_EtherCAT.T_DCTIME64;\n    now : STRING;\n    a : STRING; b : STRING; c : STRING; d : STRING; e : STRING; f : STRING;\nEND_VAR\n",
        "t := Tc2_EtherCAT.F_GetCurDcTaskTime64();\nnow := DCTIME64_TO_STRING(in := t);\n\
         a := DCTIME64_TO_STRING(in := 0);\n\
         b := DCTIME64_TO_STRING(in := 762525296123456789);\n\
         c := DCTIME64_TO_STRING(in := 3160857600000000000);\n\
         d := DCTIME64_TO_STRING(in := 3281817600000000000);\n\
         e := DCTIME64_TO_STRING(in := 3287001600000000000);\n\
         f := DCTIME64_TO_STRING(in := 6311433600000000000);\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main)]);
    let out = plcrun_ok(&[&dir, "--cycles", "3", "--trace", "t,now,a,b,c,d,e,f"]);
    let last = out.lines().last().unwrap();
    assert_eq!(
        last,
        "2,T#20ms,20000000,'2000-01-01-00:00:00.020000000','2000-01-01-00:00:00.000000000',\
         '2024-02-29-12:34:56.123456789','2100-03-01-00:00:00.000000000',\
         '2103-12-31-00:00:00.000000000','2104-02-29-00:00:00.000000000',\
         '2200-01-01-00:00:00.000000000'"
    );
}

#[test]
fn twincat_io_declared_at_i_star_gets_addresses_that_check_map_lists() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    bStart AT %IX0.0 : BOOL;\n    bSensor AT %I* : BOOL;\n    nLevel AT %I* : INT;\n    bPump AT %Q* : BOOL;\nEND_VAR\n",
        "bPump := bStart AND bSensor AND nLevel > 10;\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main)]);
    let (code, out, err) = plcrun(&["check", "--map", &dir]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "%IX0.0  bStart : BOOL\n%IX1.0  MAIN.bSensor : BOOL\n%IW1    MAIN.nLevel : INT\n%QX0.0  MAIN.bPump : BOOL\n"
    );
}

/// A STRING or WSTRING at `%I*` (TcUnit-Verifier's protected variables)
/// compiles in TwinCAT, linked to no I/O: plcrun warns (W710) and keeps
/// it an ordinary variable, written by the program alone; the warning
/// points at the address in the XML. In a plain ST file it stays E710.
#[test]
fn a_string_at_i_star_stays_an_ordinary_variable_with_a_warning() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    nLevel AT %I* : INT;\n    sName AT %I* : STRING;\n    sOut : STRING;\nEND_VAR\n",
        "WRITE_PROTECTED_STRING(ADR(sName), 'pump 1');\nsOut := sName;\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main)]);
    let (code, out, err) = plcrun(&[&dir, "--cycles", "1", "--trace", "MAIN.sOut"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, "cycle,time,MAIN.sOut\n0,T#0s,'pump 1'\n");
    assert!(err.contains("warning[W710]"), "{err}");
    // `sName AT %I*`: line 7 of the object file, the address.
    assert!(err.contains("MAIN.TcPOU:7:14"), "{err}");
    let (_, map, _) = plcrun(&["check", "--map", &dir]);
    assert_eq!(map, "%IW0  MAIN.nLevel : INT\n");
    let st = cli::temp_file(
        "p.st",
        "PROGRAM P\nVAR s AT %I* : STRING; END_VAR\nEND_PROGRAM\n",
    );
    let (code, _, err) = plcrun(&["check", &st]);
    assert_ne!(code, 0);
    assert!(err.contains("error[E710]"), "{err}");
}

/// A STRING declared without a length holds 80 characters in a TwinCAT
/// file, as TwinCAT allocates it (254 in an IEC file); the other dates
/// and strings have their WRITE_PROTECTED functions too.
#[test]
fn a_string_without_a_length_holds_80_characters_in_a_twincat_file() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    s : STRING;\n    n, size : INT;\n    d : DATE;\n    tod : TIME_OF_DAY;\n    w : WSTRING;\nEND_VAR\n",
        "s := CONCAT('0123456789012345678901234567890123456789', '01234567890123456789012345678901234567890123456789');\nn := LEN(s);\nsize := SIZEOF(s);\nWRITE_PROTECTED_DATE(ADR(d), D#2000-01-01);\nWRITE_PROTECTED_TIME_OF_DAY(ADR(tod), TOD#06:21:11.492);\nWRITE_PROTECTED_WSTRING(ADR(w), \"wide\");\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main)]);
    let out = plcrun_ok(&[
        &dir,
        "--cycles",
        "1",
        "--trace",
        "MAIN.n,MAIN.size,MAIN.d,MAIN.tod,MAIN.w",
    ]);
    assert_eq!(
        out,
        "cycle,time,MAIN.n,MAIN.size,MAIN.d,MAIN.tod,MAIN.w\n0,T#0s,80,81,D#2000-01-01,TOD#06:21:11.492,\"\"\"wide\"\"\"\n"
    );
}

#[test]
fn a_global_named_with_its_list_reads_and_sizes_like_the_global() {
    let gvl = "<?xml version=\"1.0\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <GVL Name=\"GVL_Constants\" Id=\"{0}\">\n    <Declaration><![CDATA[{attribute 'qualified_only'}\nVAR_GLOBAL CONSTANT\n    MAX_N : INT := 3;\n    PI : LREAL := 3.5;\nEND_VAR\n]]></Declaration>\n  </GVL>\n</TcPlcObject>\n";
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    a : ARRAY[1..GVL_Constants.MAX_N] OF INT;\n    r : LREAL := GVL_Constants.PI * 2.0;\n    n : INT;\nEND_VAR\n",
        "a[GVL_Constants.MAX_N] := 5;\nn := a[3] + GVL_Constants.MAX_N;\n",
        "",
    );
    let dir = temp_project(&[("GVL_Constants.TcGVL", gvl), ("MAIN.TcPOU", &main)]);
    let out = plcrun_ok(&[&dir, "--cycles", "1", "--trace", "n,r"]);
    assert_eq!(out, "cycle,time,n,r\n0,T#0s,8,7.0\n");
    // A qualifier that is a variable keeps its meaning: `a.x` is no global.
    let bad = pou(
        "P",
        "PROGRAM P\nVAR\n    a : INT;\nEND_VAR\n",
        "a := a.MAX_N;\n",
        "",
    );
    let dir = temp_project(&[("GVL_Constants.TcGVL", gvl), ("P.TcPOU", &bad)]);
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 1);
    assert!(
        err.contains("error[E301]") && err.contains("P.TcPOU:10:"),
        "{err}"
    );
    // A name the list does not declare: the message says both halves.
    let missing = pou(
        "Q",
        "PROGRAM Q\nVAR\n    n : INT;\nEND_VAR\n",
        "n := GVL_Constants.MAX_M;\n",
        "",
    );
    let dir = temp_project(&[("GVL_Constants.TcGVL", gvl), ("Q.TcPOU", &missing)]);
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 1);
    assert!(
        err.contains("error[E201]: undeclared variable `GVL_Constants`; nor is `MAX_M` a global variable (if `GVL_Constants` is a global variable list, it does not declare `MAX_M`)"),
        "{err}"
    );
}

#[test]
fn a_structure_is_sized_by_a_parameter_list_constant_declared_after_it() {
    // TcUnit's ST_TestSuiteResults: `ARRAY[1..GVL_Param.Max] OF ...` in a
    // DUT, the parameter list being a `.TcGVL` of the same project. Types
    // are resolved before globals, so plain constants come first.
    let dut = "<?xml version=\"1.0\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <DUT Name=\"ST_Results\" Id=\"{0}\">\n    <Declaration><![CDATA[TYPE ST_Results :\nSTRUCT\n    Count : UINT(0..GVL_Param.MaxN);\n    Items : ARRAY[1..GVL_Param.MaxN] OF UINT;\nEND_STRUCT\nEND_TYPE\n]]></Declaration>\n  </DUT>\n</TcPlcObject>\n";
    let gvl = "<?xml version=\"1.0\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <GVL Name=\"GVL_Param\" Id=\"{1}\" ParameterList=\"True\">\n    <Declaration><![CDATA[{attribute 'qualified_only'}\nVAR_GLOBAL CONSTANT\n    MaxN : UINT := 4;\n    Path : T_MaxString := 'x';\nEND_VAR\n]]></Declaration>\n  </GVL>\n</TcPlcObject>\n";
    // An interface method prototype ends with `;` (TwinCAT writes it so).
    let itf = "<?xml version=\"1.0\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <Itf Name=\"I_Count\" Id=\"{2}\">\n    <Declaration><![CDATA[INTERFACE I_Count\n]]></Declaration>\n    <Method Name=\"Total\" Id=\"{3}\">\n      <Declaration><![CDATA[METHOD Total : DINT;\n]]></Declaration>\n    </Method>\n  </Itf>\n</TcPlcObject>\n";
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    r : ST_Results;\n    n : DINT;\n    h : SysFile.SysTypes.RTS_IEC_HANDLE;\nEND_VAR\n",
        "r.Items[GVL_Param.MaxN] := 7;\nr.Count := GVL_Param.MaxN;\nn := r.Items[4] + r.Count;\n",
        "",
    );
    let dir = temp_project(&[
        ("DUTs/ST_Results.TcDUT", dut),
        ("GVLs/GVL_Param.TcGVL", gvl),
        ("ITFs/I_Count.TcIO", itf),
        ("POUs/MAIN.TcPOU", &main),
    ]);
    // The type of a nested library namespace is named by its last part:
    // an unknown type, not a syntax error.
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("error[E203]: unknown type `RTS_IEC_HANDLE`"),
        "{err}"
    );
    assert_eq!(err.matches("error[").count(), 1, "{err}");
    let fixed = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    r : ST_Results;\n    n : DINT;\nEND_VAR\n",
        "r.Items[GVL_Param.MaxN] := 7;\nr.Count := GVL_Param.MaxN;\nn := r.Items[4] + r.Count;\n",
        "",
    );
    std::fs::write(Path::new(&dir).join("POUs/MAIN.TcPOU"), fixed).unwrap();
    let out = plcrun_ok(&[&dir, "--cycles", "1", "--trace", "MAIN.n"]);
    assert_eq!(out, "cycle,time,MAIN.n\n0,T#0s,11\n");
}

#[test]
fn a_call_into_a_library_that_is_not_there_is_one_named_error() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    r : UDINT;\nEND_VAR\n",
        "r := SysFile.SysFileClose(hFile := 0);\n",
        "",
    );
    let dir = temp_project(&[("POUs/MAIN.TcPOU", &main)]);
    let (code, _, err) = plcrun(&["check", &dir]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains(
            "error[E201]: unknown function `SysFile.SysFileClose`: nothing here is named `SysFile`"
        ),
        "{err}"
    );
    assert_eq!(err.matches("error[").count(), 1, "{err}");
}

#[test]
fn the_hex_string_case_and_wstring_length_functions_of_the_tc2_libraries() {
    // The examples of Beckhoff's DWORD_TO_HEXSTR page: 43981 gives 'ABCD' or
    // 'abcd', 15 with 4 digits '000F', 0 with 0 digits ''; a longer number
    // is never cut.
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    s1, s2, s3, s4, s5, s6, lc, uc : T_MaxString;\n    n : INT;\n    cpu : GETCPUCOUNTER;\n    lo : UDINT;\nEND_VAR\n",
        "s1 := DWORD_TO_HEXSTR(43981, 1, FALSE);\ns2 := WORD_TO_HEXSTR(43981, 1, TRUE);\ns3 := BYTE_TO_HEXSTR(15, 4, FALSE);\ns4 := DWORD_TO_HEXSTR(0, 0, FALSE);\ns5 := LWORD_TO_HEXSTR(16#1234567890ABCDEF, 2, FALSE);\ns6 := BYTE_TO_HEXSTR(0, 1, FALSE);\nlc := F_ToLCase('TcUnit 1.3-XYZ');\nuc := F_ToUCase('TcUnit 1.3-xyz');\nn := WLEN(\"Grüße\");\ncpu();\nlo := cpu.cpuCntLoDW;\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main)]);
    let out = plcrun_ok(&[
        &dir,
        "--cycles",
        "1",
        "--trace",
        "s1,s2,s3,s4,s5,s6,lc,uc,n",
    ]);
    assert_eq!(
        out,
        "cycle,time,s1,s2,s3,s4,s5,s6,lc,uc,n\n0,T#0s,'ABCD','abcd','000F','','1234567890ABCDEF','0','tcunit 1.3-xyz','TCUNIT 1.3-XYZ',5\n"
    );
}

/// Tc2_System's `WRITE_PROTECTED_<type>(ADDR, VAL)`: writes where the
/// address points, here a block's internal variable as lcls-twincat-
/// general's tests set them; a null address writes nothing and gives
/// FALSE.
#[test]
fn write_protected_functions_write_through_the_address() {
    let block = pou(
        "FB_Mon",
        "FUNCTION_BLOCK FB_Mon\nVAR\n    iSeverity : INT;\n    fValue : LREAL;\n    tDelay : TIME;\nEND_VAR\n",
        "",
        "",
    );
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    fb : FB_Mon;\n    s : INT;\n    v : LREAL;\n    t : TIME;\n    ok, none : BOOL;\nEND_VAR\n",
        "ok := WRITE_PROTECTED_INT(ADR(fb.iSeverity), 3);\nWRITE_PROTECTED_LREAL(ADR(fb.fValue), 2.5);\nWRITE_PROTECTED_TIME(ADR(fb.tDelay), T#1s);\nnone := WRITE_PROTECTED_INT(0, 7);\ns := fb.iSeverity;\nv := fb.fValue;\nt := fb.tDelay;\n",
        "",
    );
    let dir = temp_project(&[("FB_Mon.TcPOU", &block), ("MAIN.TcPOU", &main)]);
    let out = plcrun_ok(&[&dir, "--cycles", "1", "--trace", "ok,none,s,v,t"]);
    assert_eq!(
        out,
        "cycle,time,ok,none,s,v,t\n0,T#0s,TRUE,FALSE,3,2.5,T#1s\n"
    );
}

/// A write wider than its variable, as PMPS's arbiter test sets a UDINT
/// with `WRITE_PROTECTED_ULINT`: the bytes past the variable are zeros
/// (TwinCAT writes them over what follows) and are left out; a byte there
/// that is not zero would land in another variable: R031.
#[test]
fn a_write_protected_write_wider_than_its_variable() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    n : UDINT := 16#FFFFFFFF;\n    w : LINT := -1;\n    big : BOOL;\nEND_VAR\n",
        "WRITE_PROTECTED_ULINT(ADR(n), 7);\nWRITE_PROTECTED_INT(ADR(w), 5);\nIF big THEN\n    WRITE_PROTECTED_ULINT(ADR(n), 16#1_0000_0000);\nEND_IF\n",
        "",
    );
    let dir = temp_project(&[("MAIN.TcPOU", &main)]);
    // A narrower write leaves the variable's other bytes (TwinCAT's too).
    let out = plcrun_ok(&[&dir, "--cycles", "1", "--trace", "n,w"]);
    assert_eq!(out, "cycle,time,n,w\n0,T#0s,7,-65531\n");
    let (code, _, err) = plcrun(&[&dir, "--cycles", "1", "--set", "MAIN.big=TRUE"]);
    assert_ne!(code, 0);
    assert!(err.contains("error[R031]"), "{err}");
}

/// TcUnit's own forms: a suite registers itself with `THIS` (a pointer to
/// its instance) in a global array and is called through it
/// (`addresses[i]^.Method()` in an expression); a global instance named
/// like its type (`GetCpuCounter : GETCPUCOUNTER`, which keeps the library
/// block); a library version constant of type `ST_LibVersion`; `FIND`
/// with a formal then a positional argument (TwinCAT places it at its
/// position: STR2); `--trace GVL.count` names a global with its list.
#[test]
fn a_block_registers_itself_with_this_and_tcunit_s_other_forms_load() {
    let suite = pou(
        "FB_Suite",
        "FUNCTION_BLOCK FB_Suite\nVAR n : INT; registered : BOOL; END_VAR\n",
        "IF NOT registered THEN\n    GVL.count := GVL.count + 1;\n    GVL.suites[GVL.count] := THIS;\n    registered := TRUE;\nEND_IF\nn := n + 1;\n",
        "    <Method Name=\"Done\" Id=\"{00000000-0000-0000-0000-000000000003}\">\n      <Declaration><![CDATA[METHOD Done : BOOL\n]]></Declaration>\n      <Implementation>\n        <ST><![CDATA[Done := n >= 2;]]></ST>\n      </Implementation>\n    </Method>\n",
    );
    let gvl = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <GVL Name=\"GVL\" Id=\"{00000000-0000-0000-0000-000000000004}\">\n    <Declaration><![CDATA[{attribute 'qualified_only'}\nVAR_GLOBAL\n    suites : ARRAY[1..4] OF POINTER TO FB_Suite;\n    count : INT;\n    GetCpuCounter : GETCPUCOUNTER;\nEND_VAR\nVAR_GLOBAL CONSTANT\n    stLibVersion_Mine : ST_LibVersion := (iMajor := 1, iMinor := 3, iBuild := 2, sVersion := '1.3.2');\nEND_VAR\n]]></Declaration>\n  </GVL>\n</TcPlcObject>\n";
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    a, b : FB_Suite;\n    nDone : INT;\n    i : INT;\n    nMinor : UINT;\n    nDot : INT;\n    nLo : UDINT;\nEND_VAR\n",
        "a();\nb();\nnDone := 0;\nFOR i := 1 TO GVL.count DO\n    IF GVL.suites[i]^.Done() THEN nDone := nDone + 1; END_IF\nEND_FOR\nnMinor := GVL.stLibVersion_Mine.iMinor;\nnDot := FIND(STR1 := GVL.stLibVersion_Mine.sVersion, '.');\nGVL.GetCpuCounter();\nnLo := GVL.GetCpuCounter.cpuCntLoDW;\n",
        "",
    );
    let dir = temp_project(&[
        ("FB_Suite.TcPOU", &suite),
        ("GVL.TcGVL", gvl),
        ("MAIN.TcPOU", &main),
    ]);
    let out = plcrun_ok(&[
        &dir,
        "--cycles",
        "3",
        "--trace",
        "GVL.count,nDone,nMinor,nDot,nLo",
    ]);
    // Both suites registered in the first cycle; Done from the second
    // call on. The counter is the clock in 100 ns units: 10 ms = 100 000.
    assert_eq!(
        out,
        "cycle,time,GVL.count,nDone,nMinor,nDot,nLo\n0,T#0s,2,0,3,2,0\n1,T#10ms,2,2,3,2,100000\n2,T#20ms,2,2,3,2,200000\n"
    );
}

/// A `.plcproj` compiling MAIN and pinning `ST_Io` from the type system.
const PINNING_PROJECT: &str = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Project xmlns=\"http://schemas.microsoft.com/developer/msbuild/2003\">\n  <ItemGroup>\n    <Compile Include=\"MAIN.TcPOU\" />\n    <PinnedGlobalDataType Include=\"ST_Io\" />\n  </ItemGroup>\n</Project>\n";

/// The type system's `ST_Io` (an old version it hides, then the current
/// one), an enumeration, and a type the project does not pin.
const TYPE_SYSTEM: &str = "<?xml version=\"1.0\"?>\n<TcSmProject>\n\t<DataTypes>\n\t\t<DataType>\n\t\t\t<Name GUID=\"{B}\">ST_Io</Name>\n\t\t\t<SubItem><Name>fWidth</Name><Type>REAL</Type><Default><Value>2.5</Value></Default></SubItem>\n\t\t\t<SubItem><Name>aRaw</Name><Type>BYTE</Type><ArrayInfo><LBound>1</LBound><Elements>2</Elements></ArrayInfo></SubItem>\n\t\t\t<Hides><Hide GUID=\"{A}\"/></Hides>\n\t\t</DataType>\n\t\t<DataType>\n\t\t\t<Name GUID=\"{A}\">ST_Io</Name>\n\t\t\t<SubItem><Name>nOld</Name><Type>INT</Type></SubItem>\n\t\t</DataType>\n\t\t<DataType><Name>ST_Other</Name><SubItem><Name>x</Name><Type>NOPE</Type></SubItem></DataType>\n\t</DataTypes>\n</TcSmProject>\n";

#[test]
fn types_pinned_from_the_type_system_are_read_from_the_tmc_or_the_tsproj() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    stIo : ST_Io;\n    i_stIo AT %I* : ST_Io;\n    f : REAL;\nEND_VAR\n",
        "stIo.aRaw[2] := 7;\nf := stIo.fWidth + BYTE_TO_REAL(stIo.aRaw[2]);\n",
        "",
    );
    // The solution's .tsproj, the folder above the PLC project: its
    // current version of ST_Io (the other is hidden), and only that type.
    let dir = temp_project(&[
        ("Plc/Plc.plcproj", PINNING_PROJECT),
        ("Plc/MAIN.TcPOU", &main),
        ("Solution.tsproj", TYPE_SYSTEM),
    ]);
    let plc = format!("{dir}/Plc/Plc.plcproj");
    let out = plcrun_ok(&[&plc, "--cycles", "1", "--trace", "MAIN.f"]);
    assert_eq!(out, "cycle,time,MAIN.f\n0,T#0s,9.5\n");
    // Its fields get I/O addresses like any structure at %I*.
    let (code, out, err) = plcrun(&["check", "--map", &plc]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "%ID0  MAIN.i_stIo.fWidth : REAL\n%IB4  MAIN.i_stIo.aRaw[1] : BYTE\n%IB5  MAIN.i_stIo.aRaw[2] : BYTE\n"
    );
    // The PLC project's own .tmc, beside it and named like it, comes first.
    let tmc = TYPE_SYSTEM
        .replace("TcSmProject", "TcModuleClass")
        .replace("2.5", "4.5");
    std::fs::write(format!("{dir}/Plc/Plc.tmc"), tmc).unwrap();
    let out = plcrun_ok(&[&plc, "--cycles", "1", "--trace", "MAIN.f"]);
    assert_eq!(out, "cycle,time,MAIN.f\n0,T#0s,11.5\n");
    // A pinned type that is no structure, enumeration or alias is E874,
    // pointing into the type description.
    let broken = TYPE_SYSTEM.replace(
        "<SubItem><Name>fWidth</Name>",
        "<Method/><SubItem><Name>fWidth</Name>",
    );
    std::fs::write(format!("{dir}/Plc/Plc.tmc"), broken).unwrap();
    let (code, _, err) = plcrun(&["check", &plc]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("error[E874]: `ST_Io` is not a structure"),
        "{err}"
    );
    assert!(err.contains("Plc.tmc:4:3"), "{err}");
}

/// A type system whose global data types (`PersistentType="true"`) a
/// project uses without pinning them: `ST_Log` names `E_Kind` in turn;
/// `ST_Mine` the project declares itself; `ST_Unused` nobody names; and
/// `ST_Plain`, used but not a global type. The last three could not be
/// read: taking any of them is an error.
const PERSISTENT_TYPES: &str = "<?xml version=\"1.0\"?>\n<TcSmProject>\n\t<DataTypes>\n\t\t<DataType>\n\t\t\t<Name GUID=\"{C}\" PersistentType=\"true\">E_Kind</Name>\n\t\t\t<BaseType>INT</BaseType>\n\t\t\t<EnumInfo><Text>Cleared</Text><Enum>0</Enum></EnumInfo>\n\t\t\t<EnumInfo><Text>Raised</Text><Enum>2</Enum></EnumInfo>\n\t\t</DataType>\n\t\t<DataType>\n\t\t\t<Name GUID=\"{D}\" PersistentType=\"true\">ST_Log</Name>\n\t\t\t<SubItem><Name>kind</Name><Type GUID=\"{C}\">E_Kind</Type></SubItem>\n\t\t\t<SubItem><Name>id</Name><Type>UDINT</Type><Default><Value>7</Value></Default></SubItem>\n\t\t</DataType>\n\t\t<DataType><Name PersistentType=\"true\">ST_Mine</Name><SubItem><Name>x</Name><Type>NOPE</Type></SubItem></DataType>\n\t\t<DataType><Name PersistentType=\"true\">ST_Unused</Name><SubItem><Name>x</Name><Type>NOPE</Type></SubItem></DataType>\n\t\t<DataType><Name>ST_Plain</Name><SubItem><Name>x</Name><Type>NOPE</Type></SubItem></DataType>\n\t</DataTypes>\n</TcSmProject>\n";

#[test]
fn global_types_of_the_type_system_a_project_uses_are_taken_unpinned() {
    let project = PINNING_PROJECT
        .replace("    <PinnedGlobalDataType Include=\"ST_Io\" />\n", "")
        .replace(
            "<Compile Include=\"MAIN.TcPOU\" />",
            "<Compile Include=\"MAIN.TcPOU\" />\n    <Compile Include=\"ST_Mine.TcDUT\" />",
        );
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    log : ST_Log;\n    mine : ST_Mine;\n    n : UDINT;\nEND_VAR\n",
        "log.kind := E_Kind.Raised;\nn := log.id + INT_TO_UDINT(log.kind) + mine.y;\n",
        "",
    );
    let mine = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<TcPlcObject Version=\"1.1.0.1\">\n  <DUT Name=\"ST_Mine\" Id=\"{00000000-0000-0000-0000-000000000009}\">\n    <Declaration><![CDATA[TYPE ST_Mine :\nSTRUCT\n    y : UDINT := 100;\nEND_STRUCT\nEND_TYPE\n]]></Declaration>\n  </DUT>\n</TcPlcObject>\n";
    let dir = temp_project(&[
        ("Plc/Plc.plcproj", &project),
        ("Plc/MAIN.TcPOU", &main),
        ("Plc/ST_Mine.TcDUT", mine),
        ("Solution.tsproj", PERSISTENT_TYPES),
    ]);
    let plc = format!("{dir}/Plc/Plc.plcproj");
    let out = plcrun_ok(&[&plc, "--cycles", "1", "--trace", "MAIN.n"]);
    assert_eq!(out, "cycle,time,MAIN.n\n0,T#0s,109\n");
    // A type that is only in the solution's type system, not a global one,
    // stays unknown.
    let plain = main.replace("mine : ST_Mine;", "mine : ST_Mine; p : ST_Plain;");
    std::fs::write(format!("{dir}/Plc/MAIN.TcPOU"), plain).unwrap();
    let (code, _, err) = plcrun(&["check", &plc]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("error[E203]: unknown type `ST_Plain`"),
        "{err}"
    );
}

#[test]
fn the_language_server_reads_the_pinned_types_too() {
    use crate::support::lsp_client::LspClient;
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    stIo : ST_Io;\n    f : REAL;\nEND_VAR\n",
        "f := stIo.fWidth;\n",
        "",
    );
    let dir = temp_project(&[
        ("Plc/Plc.plcproj", PINNING_PROJECT),
        ("Plc/MAIN.TcPOU", &main),
        ("Solution.tsproj", TYPE_SYSTEM),
    ]);
    let file = std::path::PathBuf::from(format!("{dir}/Plc/MAIN.TcPOU"));
    let (mut client, _) = LspClient::start(Path::new(&dir));
    client.open(&file, &main);
    assert_eq!(
        client.diagnostics(&file, 0),
        Vec::<serde_json::Value>::new()
    );
}

/// A `.plcproj` compiling MAIN and referencing the library `Motor Lib` by
/// placeholder, as PMPS references `LCLS General`.
const REFERENCING_PROJECT: &str = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Project xmlns=\"http://schemas.microsoft.com/developer/msbuild/2003\">\n  <ItemGroup>\n    <Compile Include=\"MAIN.TcPOU\" />\n  </ItemGroup>\n  <ItemGroup>\n    <PlaceholderReference Include=\"Motor Lib\">\n      <DefaultResolution>Motor Lib, * (ACME)</DefaultResolution>\n      <Namespace>Motor_Lib</Namespace>\n    </PlaceholderReference>\n    <PlaceholderReference Include=\"Tc2_Standard\">\n      <DefaultResolution>Tc2_Standard, * (Beckhoff Automation GmbH)</DefaultResolution>\n    </PlaceholderReference>\n  </ItemGroup>\n</Project>\n";

/// The library project `Motor Lib` (its title), which references
/// `Units Lib` in turn.
const LIBRARY_PROJECT: &str = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Project>\n  <PropertyGroup>\n    <Name>MotorLib</Name>\n    <Title>Motor Lib</Title>\n  </PropertyGroup>\n  <ItemGroup>\n    <Compile Include=\"FB_Motor.TcPOU\" />\n    <LibraryReference Include=\"Units Lib, 1.2.0 (ACME)\" />\n  </ItemGroup>\n</Project>\n";

const UNITS_PROJECT: &str = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Project>\n  <PropertyGroup>\n    <Name>Units Lib</Name>\n  </PropertyGroup>\n  <ItemGroup>\n    <Compile Include=\"F_Rpm.TcPOU\" />\n  </ItemGroup>\n</Project>\n";

#[test]
fn library_projects_referenced_by_a_project_are_found_on_the_library_path() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR m : FB_Motor; n : INT; END_VAR\n",
        "m(nSteps := 3);\nn := m.nRpm + UDINT_TO_INT(m.nSize) * 100;\n",
        "",
    );
    // A library's STRING is TwinCAT's too: 80 characters (81 bytes).
    let motor = pou(
        "FB_Motor",
        "FUNCTION_BLOCK FB_Motor\nVAR_INPUT nSteps : INT; END_VAR\nVAR_OUTPUT nRpm : INT; nSize : UDINT; END_VAR\nVAR s : STRING; END_VAR\n",
        "nRpm := F_Rpm(nSteps);\nnSize := SIZEOF(s);\n",
        "",
    );
    let rpm = pou(
        "F_Rpm",
        "FUNCTION F_Rpm : INT\nVAR_INPUT n : INT; END_VAR\n",
        "F_Rpm := n * 20;\n",
        "",
    );
    let dir = temp_project(&[
        ("App/App.plcproj", REFERENCING_PROJECT),
        ("App/MAIN.TcPOU", &main),
        ("libs/motor/Motor.plcproj", LIBRARY_PROJECT),
        ("libs/motor/FB_Motor.TcPOU", &motor),
        ("libs/units/Units.plcproj", UNITS_PROJECT),
        ("libs/units/F_Rpm.TcPOU", &rpm),
    ]);
    let app = format!("{dir}/App/App.plcproj");
    // Without the library path, the library's block is unknown.
    let (code, _, err) = plcrun(&["check", &app]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("unknown type `FB_Motor`"), "{err}");
    // With it, the library and the one it references are loaded: their
    // sources are checked with the project's.
    let libs = format!("{dir}/libs");
    let (code, _, err) = plcrun(&["check", "--library-path", &libs, &app]);
    assert_eq!((code, err.as_str()), (0, "ok: 3 files checked\n"));
    let out = plcrun_ok(&[
        &app,
        "--library-path",
        &libs,
        "--cycles",
        "1",
        "--trace",
        "MAIN.n",
    ]);
    assert_eq!(out, "cycle,time,MAIN.n\n0,T#0s,8160\n");
    // A library path that is no folder is a usage error naming it.
    let (code, _, err) = plcrun(&["check", "--library-path", &app, &app]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("not a folder"), "{err}");
}

#[test]
fn a_project_s_implicit_checks_do_not_reach_into_its_library_projects() {
    // TwinCAT runs no implicit check in a library's code: the project's
    // CheckDivDInt turns its own division by zero into one by 1, while
    // the same division in the library `Units Lib` still faults.
    let project = REFERENCING_PROJECT.replace(
        "<Compile Include=\"MAIN.TcPOU\" />",
        "<Compile Include=\"MAIN.TcPOU\" />\n    <Compile Include=\"CheckDivDInt.TcPOU\" />",
    );
    let check = pou(
        "CheckDivDInt",
        "FUNCTION CheckDivDInt : DINT\nVAR_INPUT divisor : DINT; END_VAR\n",
        "IF divisor = 0 THEN CheckDivDInt := 1; ELSE CheckDivDInt := divisor; END_IF\n",
        "",
    );
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR m : FB_Motor; zero : INT; own : INT; n : INT; END_VAR\n",
        "own := 7 / zero;\nm(nSteps := zero);\nn := m.nRpm;\n",
        "",
    );
    let motor = pou(
        "FB_Motor",
        "FUNCTION_BLOCK FB_Motor\nVAR_INPUT nSteps : INT; END_VAR\nVAR_OUTPUT nRpm : INT; END_VAR\n",
        "nRpm := F_Rpm(nSteps);\n",
        "",
    );
    let rpm = pou(
        "F_Rpm",
        "FUNCTION F_Rpm : INT\nVAR_INPUT n : INT; END_VAR\n",
        "F_Rpm := 600 / n;\n",
        "",
    );
    let dir = temp_project(&[
        ("App/App.plcproj", &project),
        ("App/MAIN.TcPOU", &main),
        ("App/CheckDivDInt.TcPOU", &check),
        ("libs/motor/Motor.plcproj", LIBRARY_PROJECT),
        ("libs/motor/FB_Motor.TcPOU", &motor),
        ("libs/units/Units.plcproj", UNITS_PROJECT),
        ("libs/units/F_Rpm.TcPOU", &rpm),
    ]);
    let app = format!("{dir}/App/App.plcproj");
    let libs = format!("{dir}/libs");
    let args = [
        "--library-path",
        &libs,
        "--cycles",
        "1",
        "--trace",
        "MAIN.own",
    ];
    let mut all = vec![app.as_str()];
    all.extend(args);
    let (code, out, err) = plcrun(&all);
    // A runtime fault: exit status 3.
    assert_eq!(code, 3, "{out}{err}");
    assert!(err.contains("division by zero"), "{err}");
    assert!(err.contains("F_Rpm.TcPOU"), "{err}");
}

/// A solution whose I/O configuration links a test suite's output to the
/// input of the block it tests, as SLAC's vacuum library feeds its gauges.
const LOOPBACK_SOLUTION: &str = "<?xml version=\"1.0\"?>\n<TcSmProject>\n  <Mappings>\n    <OwnerA Name=\"TIPC^Plc^Plc Instance\">\n      <OwnerB Name=\"TIPC^Plc^Plc Instance\">\n        <Link VarA=\"PlcTask Inputs^PRG_TEST.fbPumpTest.fbPump.i_iRaw\" VarB=\"PlcTask Outputs^PRG_TEST.fbPumpTest.q_iRaw\"/>\n        <Link VarA=\"PlcTask Outputs^PRG_TEST.fbPumpTest.q_iRaw\" VarB=\"PlcTask Inputs^PRG_TEST.fbPumpTest.i_diWide\"/>\n      </OwnerB>\n      <OwnerB Name=\"TIID^Device 1 (EtherCAT)^Term 2 (EL3064)\">\n        <Link VarA=\"PlcTask Inputs^PRG_TEST.fbPumpTest.i_iOther\" VarB=\"AI Standard Channel 1^Value\"/>\n      </OwnerB>\n    </OwnerA>\n  </Mappings>\n</TcSmProject>\n";

const LOOPBACK_PROJECT: &str = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Project>\n  <ItemGroup>\n    <Compile Include=\"FB_Pump.TcPOU\" />\n    <Compile Include=\"FB_PumpTest.TcPOU\" />\n    <Compile Include=\"PRG_TEST.TcPOU\" />\n  </ItemGroup>\n</Project>\n";

#[test]
fn the_io_configuration_feeds_a_suite_s_outputs_back_to_the_inputs_it_links() {
    let pump = pou(
        "FB_Pump",
        "FUNCTION_BLOCK FB_Pump\nVAR\n  i_iRaw AT %I* : INT;\nEND_VAR\nVAR_OUTPUT rVolts : REAL; END_VAR\n",
        "rVolts := INT_TO_REAL(i_iRaw) / 100.0;\n",
        "",
    );
    // The suite writes 250 in cycle 0; the pump reads it from cycle 1 (an
    // input takes its output's value between two cycles), as does the
    // suite's own wider input; the input linked to a terminal stays 0.
    let suite = pou(
        "FB_PumpTest",
        "FUNCTION_BLOCK FB_PumpTest EXTENDS TcUnit.FB_TestSuite\nVAR\n  fbPump : FB_Pump;\n  q_iRaw AT %Q* : INT;\n  i_diWide AT %I* : DINT;\n  i_iOther AT %I* : INT;\n  n : INT;\nEND_VAR\n",
        "TEST('Loopback');\nq_iRaw := 250;\nfbPump();\nIF n = 0 THEN\n  AssertEquals_REAL(Expected := 0.0, Actual := fbPump.rVolts, Delta := 0.001, Message := 'not yet');\nELSE\n  AssertEquals_REAL(Expected := 2.5, Actual := fbPump.rVolts, Delta := 0.001, Message := 'fed back');\n  AssertEquals_DINT(Expected := 250, Actual := i_diWide, Message := 'wider input');\n  AssertEquals_INT(Expected := 0, Actual := i_iOther, Message := 'terminal');\n  TEST_FINISHED();\nEND_IF\nn := n + 1;\n",
        "",
    );
    let prg = pou(
        "PRG_TEST",
        "PROGRAM PRG_TEST\nVAR fbPumpTest : FB_PumpTest; END_VAR\n",
        "TcUnit.RUN();\n",
        "",
    );
    let dir = temp_project(&[
        ("Solution.tsproj", LOOPBACK_SOLUTION),
        ("Plc/Plc.plcproj", LOOPBACK_PROJECT),
        ("Plc/FB_Pump.TcPOU", &pump),
        ("Plc/FB_PumpTest.TcPOU", &suite),
        ("Plc/PRG_TEST.TcPOU", &prg),
    ]);
    let (code, out, err) = plcrun(&["test", &format!("{dir}/Plc/Plc.plcproj")]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.starts_with("PASS  PRG_TEST.fbPumpTest.Loopback ("),
        "{out}"
    );
    assert!(out.contains("2 cycles, 4 assertions"), "{out}");
}

/// An NC configuration with one axis (`Axis_Slow`) that limits the
/// velocity to 5 and enables the positive soft limit at 8, linked to the
/// suite's AXIS_REF by the PLC's `.xti`.
const NC_LIST: &str = "<?xml version=\"1.0\"?>\n<TcSmItem>\n  <Nc>\n    <Axis File=\"Axis_Slow.xti\" Id=\"7\"/>\n    <Axis File=\"Axis_Missing.xti\" Id=\"8\"/>\n  </Nc>\n</TcSmItem>\n";
const NC_AXIS: &str = "<?xml version=\"1.0\"?>\n<TcSmItem ClassName=\"CNcAxisDef\">\n  <Axis Id=\"7\" AxisType=\"1\">\n    <Name>__FILENAME__</Name>\n    <AxisPara>\n      <Velo Maximum=\"5\"/>\n    </AxisPara>\n    <Encoder Name=\"Enc\">\n      <EncPara Offset=\"2\">\n        <SoftEndMaxControl Enable=\"true\" Range=\"8\"/>\n      </EncPara>\n    </Encoder>\n  </Axis>\n</TcSmItem>\n";
const NC_LINKS: &str = "<?xml version=\"1.0\"?>\n<TcSmItem>\n  <Mappings>\n    <OwnerA Name=\"Plc Instance\">\n      <OwnerB Name=\"TINC^NC-Task 1 SAF^Axes^Axis_Slow\">\n        <Link VarA=\"PlcTask Inputs^PRG_TEST.fbAxisTest.ax.NcToPlc\" VarB=\"Outputs^ToPlc\"/>\n        <Link VarA=\"PlcTask Outputs^PRG_TEST.fbAxisTest.ax.PlcToNc\" VarB=\"Inputs^FromPlc\"/>\n      </OwnerB>\n    </OwnerA>\n  </Mappings>\n</TcSmItem>\n";

#[test]
fn a_suite_s_axis_takes_the_id_and_parameters_of_the_nc_axis_it_is_linked_to() {
    // The linked axis starts at its encoder offset (2), is refused a
    // velocity above its maximum (16#4221 = 16929) and a target beyond
    // its soft limit (16#4358 = 17240); the unlinked one keeps the
    // defaults and the next free id.
    let suite = pou(
        "FB_AxisTest",
        "FUNCTION_BLOCK FB_AxisTest EXTENDS TcUnit.FB_TestSuite\nVAR\n  ax : AXIS_REF;\n  free : AXIS_REF;\n  power : MC_Power;\n  fast : MC_MoveAbsolute;\n  far : MC_MoveAbsolute;\n  n : INT;\nEND_VAR\n",
        "TEST('Configured');\npower(Axis := ax, Enable := TRUE, Enable_Positive := TRUE, Enable_Negative := TRUE);\nfree.ReadStatus();\nIF n = 0 THEN\n  AssertEquals_UDINT(Expected := 7, Actual := ax.NcToPlc.AxisId, Message := 'id');\n  AssertEquals_LREAL(Expected := 2.0, Actual := ax.NcToPlc.ActPos, Delta := 0.0, Message := 'offset');\n  AssertEquals_UDINT(Expected := 2, Actual := free.NcToPlc.AxisId, Message := 'free id');\nELSIF n = 2 THEN\n  fast(Axis := ax, Execute := TRUE, Position := 4.0, Velocity := 6.0);\n  AssertEquals_UDINT(Expected := 16929, Actual := fast.ErrorID, Message := 'too fast');\nELSIF n = 3 THEN\n  ax.PlcrunReset();\nELSIF n = 4 THEN\n  far(Axis := ax, Execute := TRUE, Position := 9.0, Velocity := 5.0);\n  AssertEquals_UDINT(Expected := 17240, Actual := far.ErrorID, Message := 'beyond the limit');\n  TEST_FINISHED();\nEND_IF\nn := n + 1;\n",
        "",
    );
    let prg = pou(
        "PRG_TEST",
        "PROGRAM PRG_TEST\nVAR fbAxisTest : FB_AxisTest; END_VAR\n",
        "TcUnit.RUN();\n",
        "",
    );
    let project = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Project>\n  <ItemGroup>\n    <Compile Include=\"FB_AxisTest.TcPOU\" />\n    <Compile Include=\"PRG_TEST.TcPOU\" />\n  </ItemGroup>\n</Project>\n";
    let dir = temp_project(&[
        (
            "Solution.tsproj",
            "<?xml version=\"1.0\"?>\n<TcSmProject/>\n",
        ),
        ("_Config/NC/NC.xti", NC_LIST),
        ("_Config/NC/Axes/Axis_Slow.xti", NC_AXIS),
        ("_Config/PLC/Plc.xti", NC_LINKS),
        ("Plc/Plc.plcproj", project),
        ("Plc/FB_AxisTest.TcPOU", &suite),
        ("Plc/PRG_TEST.TcPOU", &prg),
    ]);
    let (code, out, err) = plcrun(&["test", &format!("{dir}/Plc/Plc.plcproj")]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("5 cycles, 5 assertions"), "{out}");
}

/// TwinCAT's `_AppInfo`: the project's name from its `.plcproj`, the port
/// and name of TwinCAT's first PLC, and TcUnit's way of reading it
/// (qualified by `TwinCAT_SystemInfoVarList`); a folder without a
/// `.plcproj` gives the folder's name.
#[test]
fn the_application_information_names_the_project() {
    let main = pou(
        "MAIN",
        "PROGRAM MAIN\nVAR\n    sName : STRING;\n    nPort : UINT;\n    sApp : STRING;\nEND_VAR\n",
        "sName := TwinCAT_SystemInfoVarList._AppInfo.ProjectName;\nnPort := _AppInfo.AdsPort;\nsApp := _AppInfo.AppName;\n",
        "",
    );
    let project = PINNING_PROJECT
        .replace("    <PinnedGlobalDataType Include=\"ST_Io\" />\n", "")
        .replace(
            "  <ItemGroup>",
            "  <PropertyGroup>\n    <Name>Conveyor It's</Name>\n  </PropertyGroup>\n  <ItemGroup>",
        );
    let dir = temp_project(&[("Plc/Plc.plcproj", &project), ("Plc/MAIN.TcPOU", &main)]);
    let trace = [
        "--cycles",
        "1",
        "--trace",
        "MAIN.sName,MAIN.nPort,MAIN.sApp",
    ];
    let plc = format!("{dir}/Plc/Plc.plcproj");
    let out = plcrun_ok(&[&[plc.as_str()], &trace[..]].concat());
    assert_eq!(
        out,
        "cycle,time,MAIN.sName,MAIN.nPort,MAIN.sApp\n0,T#0s,'Conveyor It$'s',851,'Port_851'\n"
    );
    let folder = temp_project(&[("Line7/MAIN.TcPOU", &main)]);
    let line = format!("{folder}/Line7");
    let out = plcrun_ok(&[&[line.as_str()], &trace[..]].concat());
    assert!(out.ends_with("0,T#0s,'Line7',851,'Port_851'\n"), "{out}");
}

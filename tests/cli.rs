//! The `plcrun` command line (docs/cli.md): options, stimulus files, trace
//! formats, names, exit statuses.

use crate::support::cli;

use cli::{plcrun, plcrun_ok, temp_file};

/// n counts executions; b is TRUE every 5th; y := x * 2; t is the clock.
const COUNTER: &str = "PROGRAM Count
VAR_OUTPUT n : INT; b : BOOL; END_VAR
VAR x : INT; y : INT; t : TIME; arr : ARRAY[1..3] OF INT; s : STRING; END_VAR
n := n + 1; b := n MOD 5 = 0; y := x * 2; t := PLC_CLOCK(); arr[2] := n * 10;
END_PROGRAM
";

fn counter() -> String {
    temp_file("count.st", COUNTER)
}

#[test]
fn default_trace_is_the_outputs_and_csv_rows_end_with_newline() {
    let out = plcrun_ok(&[&counter(), "--cycles", "3", "--format", "csv"]);
    assert_eq!(
        out,
        "cycle,time,n,b\n0,T#0s,1,FALSE\n1,T#10ms,2,FALSE\n2,T#20ms,3,FALSE\n"
    );
}

#[test]
fn default_format_is_csv() {
    let p = counter();
    let default = plcrun_ok(&[&p, "--cycles", "2"]);
    let csv = plcrun_ok(&[&p, "--cycles", "2", "--format", "csv"]);
    assert_eq!(default, csv);
    assert!(default.starts_with("cycle,time,"), "{default}");
}

#[test]
fn set_gives_initial_values() {
    let out = plcrun_ok(&[
        &counter(),
        "--cycles",
        "2",
        "--format",
        "csv",
        "--set",
        "x=21",
        "--set",
        "n=100",
        "--set",
        "s='hi'",
        "--trace",
        "y,n,s",
    ]);
    assert_eq!(
        out,
        "cycle,time,y,n,s\n0,T#0s,42,101,'hi'\n1,T#10ms,42,102,'hi'\n"
    );
}

#[test]
fn set_with_unknown_name_or_bad_value_is_a_usage_error() {
    let p = counter();
    for (set, needle) in [
        ("nope=1", "nope"),
        ("x=abc", "abc"),
        ("x=40000", "40000"),
        ("x", "NAME=VALUE"),
    ] {
        let (code, out, err) = plcrun(&[&p, "--cycles", "1", "--set", set]);
        assert_eq!(code, 2, "--set {set}: {err}");
        assert!(err.contains(needle), "--set {set}: {err}");
        assert_eq!(out, "");
    }
}

#[test]
fn changes_only_keeps_the_first_row_and_the_changes() {
    // b is TRUE when n = 5, 10 (cycles 4, 9): rows 0, 4, 5, 9, 10
    let out = plcrun_ok(&[
        &counter(),
        "--cycles",
        "12",
        "--format",
        "csv",
        "--trace",
        "b",
        "--changes-only",
    ]);
    assert_eq!(
        out,
        "cycle,time,b\n0,T#0s,FALSE\n4,T#40ms,TRUE\n5,T#50ms,FALSE\n9,T#90ms,TRUE\n10,T#100ms,FALSE\n"
    );
}

#[test]
fn table_format_aligns_the_same_values() {
    let out = plcrun_ok(&[
        &counter(),
        "--cycles",
        "11",
        "--format",
        "table",
        "--trace",
        "n,b",
    ]);
    let lines: Vec<&str> = out.lines().collect();
    let header: Vec<&str> = lines[0].split_whitespace().collect();
    assert_eq!(header, ["cycle", "time", "n", "b"]);
    let data: Vec<Vec<&str>> = lines
        .iter()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|f| f.first().is_some_and(|c| c.parse::<u32>().is_ok()))
        .collect();
    assert_eq!(data.len(), 11);
    assert_eq!(data[10], ["10", "T#100ms", "11", "FALSE"]);
    // columns are aligned: every data row has "n" at the header's offset
    let n_at = lines[0].find(" n ").unwrap() + 1;
    for l in &lines[1..] {
        if l.starts_with(|c: char| c.is_ascii_digit()) {
            assert!(l[n_at..].starts_with(|c: char| c.is_ascii_digit()), "{l:?}");
        }
    }
}

#[test]
fn jsonl_has_one_object_per_cycle_in_trace_order() {
    let out = plcrun_ok(&[
        &counter(),
        "--cycles",
        "3",
        "--format",
        "jsonl",
        "--trace",
        "n,b,t",
    ]);
    let rows: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("each line is JSON"))
        .collect();
    assert_eq!(rows.len(), 3);
    let last = rows[2].as_object().unwrap();
    // keys in trace order (checked on the text: the JSON map sorts them)
    let line = out.lines().nth(2).unwrap();
    let at = |k: &str| line.find(&format!("\"{k}\":")).unwrap();
    assert!(
        at("cycle") < at("time") && at("time") < at("n") && at("n") < at("b") && at("b") < at("t")
    );
    assert_eq!(last.len(), 5);
    assert_eq!(last["cycle"], 2);
    assert_eq!(last["time"], "T#20ms");
    // n = 3, b = FALSE, t = T#20ms, as JSON number / boolean / literal
    // string (or all as the IEC literal strings: either is a faithful
    // rendering of the value)
    let same = |v: &serde_json::Value, native: serde_json::Value, text: &str| {
        *v == native || v.as_str() == Some(text)
    };
    assert!(same(&last["n"], 3.into(), "3"), "{}", last["n"]);
    assert!(same(&last["b"], false.into(), "FALSE"), "{}", last["b"]);
    assert_eq!(last["t"], "T#20ms");
}

#[test]
fn output_writes_the_trace_to_a_file() {
    let dest = temp_file("out.csv", "");
    let (code, out, err) = plcrun(&[
        &counter(),
        "--cycles",
        "2",
        "--format",
        "csv",
        "--output",
        &dest,
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, "");
    assert_eq!(
        std::fs::read_to_string(&dest).unwrap(),
        "cycle,time,n,b\n0,T#0s,1,FALSE\n1,T#10ms,2,FALSE\n"
    );
}

#[test]
fn cycle_time_sets_the_clock_step() {
    for (opt, t3) in [("5ms", "T#15ms"), ("T#100ms", "T#300ms"), ("1s", "T#3s")] {
        let out = plcrun_ok(&[
            &counter(),
            "--cycles",
            "4",
            "--format",
            "csv",
            "--trace",
            "t",
            "--cycle-time",
            opt,
        ]);
        let last = out.lines().last().unwrap();
        assert_eq!(last, format!("3,{t3},{t3}"), "--cycle-time {opt}");
    }
}

#[test]
fn bad_option_values_are_usage_errors() {
    let p = counter();
    for args in [
        vec![p.as_str(), "--cycles", "1", "--cycle-time", "0ms"],
        vec![p.as_str(), "--cycles", "1", "--cycle-time", "fast"],
        vec![p.as_str(), "--cycles", "1", "--format", "xml"],
        vec![p.as_str(), "--cycles", "many"],
        vec![p.as_str(), "--cycles", "1", "--watchdog", "soon"],
        vec![p.as_str(), "--cycles", "1", "--no-such-option"],
        vec!["no/such/file.st", "--cycles", "1"],
    ] {
        let (code, _, err) = plcrun(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(!err.is_empty());
    }
}

#[test]
fn compile_errors_exit_1() {
    let p = temp_file("broken.st", "PROGRAM P\nx := 1;\nEND_PROGRAM\n");
    let (code, out, err) = plcrun(&[&p, "--cycles", "1"]);
    assert_eq!(code, 1);
    assert_eq!(out, "");
    assert!(
        err.contains("E201") && err.contains("broken.st:2:1"),
        "{err}"
    );
}

const TWO: &str = "PROGRAM A
VAR_OUTPUT x : INT; END_VAR
x := x + 1;
END_PROGRAM
PROGRAM B
VAR_OUTPUT y : INT; END_VAR
y := y + 2;
END_PROGRAM
";

#[test]
fn program_chooses_among_several() {
    let p = temp_file("two.st", TWO);
    let out = plcrun_ok(&[&p, "--cycles", "2", "--format", "csv", "--program", "b"]);
    assert_eq!(out, "cycle,time,y\n0,T#0s,2\n1,T#10ms,4\n");
    let out = plcrun_ok(&[&p, "--cycles", "1", "--format", "csv", "--program", "A"]);
    assert_eq!(out, "cycle,time,x\n0,T#0s,1\n");
}

#[test]
fn ambiguous_or_unknown_program_is_a_usage_error() {
    let p = temp_file("two.st", TWO);
    let (code, _, err) = plcrun(&[&p, "--cycles", "1"]);
    assert_eq!(code, 2, "{err}");
    let (code, _, err) = plcrun(&[&p, "--cycles", "1", "--program", "zz"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("zz"));
}

#[test]
fn unknown_trace_name_is_a_usage_error_naming_it() {
    for name in ["nope", "arr[7]", "arr.x", "n.field", "%QX9.9"] {
        let (code, out, err) =
            plcrun(&[&counter(), "--cycles", "1", "--trace", &format!("n,{name}")]);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(err.contains(name), "{name}: {err}");
        assert_eq!(out, "");
    }
}

#[test]
fn trace_names_paths_elements_and_any_case() {
    let out = plcrun_ok(&[
        "programs/cmd_monitor.st",
        "--cycles",
        "50",
        "--cycle-time",
        "5ms",
        "--set",
        "T_CMD_MAX=T#50ms",
        "--set",
        "AUTO_MODE=TRUE",
        "--set",
        "AUTO_CMD=TRUE",
        "--format",
        "csv",
        "--trace",
        "CMD,mon.cmd_tmr.ET,MON.CMD_TMR.Q,ALRM",
    ]);
    let lines: Vec<&str> = out.lines().collect();
    // names are printed as written
    assert_eq!(lines[0], "cycle,time,CMD,mon.cmd_tmr.ET,MON.CMD_TMR.Q,ALRM");
    // CMD from cycle 0; the TON runs from cycle 0; 50 ms = 10 cycles of 5 ms:
    // Q and the alarm (no feedback) at cycle 10
    assert_eq!(lines[1 + 9], "9,T#45ms,TRUE,T#45ms,FALSE,FALSE");
    assert_eq!(lines[1 + 10], "10,T#50ms,TRUE,T#50ms,TRUE,TRUE");
    let out = plcrun_ok(&[
        "programs/comparator.st",
        "--cycles",
        "6",
        "--format",
        "csv",
        "--trace",
        "A,abits[0],ABITS[1],abits[2]",
    ]);
    // A = n MOD 16 = 5 at cycle 5: bits 1, 0, 1
    assert_eq!(out.lines().last().unwrap(), "5,T#50ms,5,TRUE,FALSE,TRUE");
}

// ---------------------------------------------------------------- stimulus

#[test]
fn stimulus_keyed_by_time() {
    let stim = temp_file("time.csv", "time,x\n0ms,1\n155ms,5\nT#0.3s,7\n");
    let out = plcrun_ok(&[
        &counter(),
        "--cycles",
        "32",
        "--format",
        "csv",
        "--trace",
        "y",
        "--changes-only",
        "--stimulus",
        &stim,
    ]);
    // 155 ms is due at the first cycle at or after it: cycle 16 (160 ms);
    // 300 ms at cycle 30
    assert_eq!(
        out,
        "cycle,time,y\n0,T#0s,2\n16,T#160ms,10\n30,T#300ms,14\n"
    );
}

#[test]
fn stimulus_keyed_by_cycle_with_empty_cells_and_same_cycle_rows() {
    let stim = temp_file(
        "cycle.csv",
        "cycle, x , s\n0, 1, 'a'\n2,,'b'\n2, 3,\n4, -4, 'c,d'\n",
    );
    // (the last cell is not CSV-quoted: 'c,d' splits into two cells)
    let (code, _, _) = plcrun(&[&counter(), "--cycles", "1", "--stimulus", &stim]);
    assert_eq!(code, 2, "a row with too many cells is rejected");
    let stim = temp_file(
        "cycle.csv",
        "cycle, x , s\n0, 1, 'a'\n2,,'b'\n2, 3,\n4, -4,\"'c,d'\"\n",
    );
    // the trace is CSV too: a value containing a comma is quoted
    let out = plcrun_ok(&[
        &counter(),
        "--cycles",
        "6",
        "--format",
        "csv",
        "--trace",
        "y,s",
        "--stimulus",
        &stim,
    ]);
    assert_eq!(
        out,
        "cycle,time,y,s\n0,T#0s,2,'a'\n1,T#10ms,2,'a'\n2,T#20ms,6,'b'\n3,T#30ms,6,'b'\n4,T#40ms,-8,\"'c,d'\"\n5,T#50ms,-8,\"'c,d'\"\n"
    );
}

#[test]
fn bad_stimulus_files_are_usage_errors() {
    let p = counter();
    for (name, text, needle) in [
        ("unknown.csv", "cycle,x,zz\n0,1,2\n", "zz"),
        ("literal.csv", "cycle,x\n0,1\n3,abc\n", "abc"),
        ("range.csv", "cycle,x\n0,40000\n", "x"),
        ("unsorted.csv", "cycle,x\n5,1\n3,2\n", "3"),
        ("key.csv", "step,x\n0,1\n", "step"),
        ("negative.csv", "cycle,x\n-1,1\n", "-1"),
        ("badtime.csv", "time,x\n10parsecs,1\n", "10parsecs"),
    ] {
        let stim = temp_file(name, text);
        let (code, out, err) = plcrun(&[&p, "--cycles", "5", "--stimulus", &stim]);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(err.contains(needle), "{name}: {err}");
        assert_eq!(out, "", "{name}");
    }
    let (code, _, _) = plcrun(&[&p, "--cycles", "5", "--stimulus", "no/such.csv"]);
    assert_eq!(code, 2);
}

#[test]
fn located_addresses_in_stimulus_and_trace() {
    // ALG01: SW1 is %I0.0.0.0.0, L1 is %Q0.0.0.1.7. Pressing SW1 at 100 ms
    // (cycle 10) activates step 1 and L1 in that cycle (docs/programs.md,
    // scenario s1); step 0 falls one cycle later.
    let stim = temp_file(
        "alg.csv",
        "time,%I0.0.0.0.0\n0ms,FALSE\n100ms,TRUE\n150ms,FALSE\n",
    );
    let out = plcrun_ok(&[
        "programs/alg01.il",
        "--cycles",
        "20",
        "--format",
        "csv",
        "--stimulus",
        &stim,
        "--trace",
        "%I0.0.0.0.0,M0,M1,%Q0.0.0.1.7,L1",
        "--changes-only",
    ]);
    assert_eq!(
        out,
        "cycle,time,%I0.0.0.0.0,M0,M1,%Q0.0.0.1.7,L1\n\
         0,T#0s,FALSE,TRUE,FALSE,FALSE,FALSE\n\
         10,T#100ms,TRUE,TRUE,TRUE,TRUE,TRUE\n\
         11,T#110ms,TRUE,FALSE,TRUE,TRUE,TRUE\n\
         15,T#150ms,FALSE,FALSE,TRUE,TRUE,TRUE\n"
    );
}

#[test]
fn help_and_version_exit_0() {
    let (code, out, _) = plcrun(&["--help"]);
    assert_eq!(code, 0);
    assert!(out.contains("--cycles"));
    let (code, out, _) = plcrun(&["--version"]);
    assert_eq!(code, 0);
    assert!(out.contains("plcrun"));
}

#[test]
fn watchdog_zero_disables_the_watchdog() {
    // About two million loop iterations: far more than 1 ms per cycle.
    let path = temp_file(
        "busy.st",
        "PROGRAM Busy VAR_OUTPUT x : DINT; END_VAR VAR i : DINT; END_VAR
         FOR i := 1 TO 2000000 DO x := x + 1; END_FOR; END_PROGRAM",
    );
    let (code, _, stderr) = plcrun(&[&path, "--cycles", "1", "--watchdog", "1ms"]);
    assert_eq!(code, 3, "a 1 ms watchdog stops the cycle: {stderr}");
    let out = plcrun_ok(&[&path, "--cycles", "1", "--watchdog", "0"]);
    assert_eq!(out, "cycle,time,x\n0,T#0s,2000000\n");
    let out = plcrun_ok(&[&path, "--cycles", "1", "--watchdog", "T#0s"]);
    assert_eq!(out, "cycle,time,x\n0,T#0s,2000000\n");
}

#[test]
fn default_trace_expands_aggregate_outputs_into_their_values() {
    let path = temp_file(
        "agg.st",
        "TYPE Pair : STRUCT a : BOOL; b : INT; END_STRUCT; END_TYPE
         FUNCTION_BLOCK Cnt VAR_INPUT go : BOOL; END_VAR VAR_OUTPUT n : INT; END_VAR
         IF go THEN n := n + 1; END_IF END_FUNCTION_BLOCK
         PROGRAM Agg
         VAR_OUTPUT
             v : ARRAY[1..2] OF INT;
             g : ARRAY[0..1, 1..2] OF BOOL;
             p : Pair;
             c : Cnt;
             t : TON;
             big : ARRAY[1..300] OF BYTE;
             last : DINT;
         END_VAR
         v[2] := 7; g[1, 2] := TRUE; p.b := 3; c(go := TRUE);
         t(IN := TRUE, PT := T#10ms); last := 1;
         END_PROGRAM",
    );
    let (code, out, err) = plcrun(&[&path, "--cycles", "2"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        // (CSV quotes the headers that hold a comma.)
        "cycle,time,v[1],v[2],\"g[0,1]\",\"g[0,2]\",\"g[1,1]\",\"g[1,2]\",p.a,p.b,c.n,t.Q,t.ET,last\n\
         0,T#0s,0,7,FALSE,FALSE,FALSE,TRUE,FALSE,3,1,FALSE,T#0s,1\n\
         1,T#10ms,0,7,FALSE,FALSE,FALSE,TRUE,FALSE,3,2,TRUE,T#10ms,1\n"
    );
    assert!(
        err.contains("note: `big` (300 values) is left out of the default trace"),
        "{err}"
    );
}

#[test]
fn variables_named_cycle_or_time_are_traced_by_their_path() {
    let path = temp_file(
        "clock.st",
        "PROGRAM Clk VAR_OUTPUT Time : INT; cycle : BOOL; END_VAR
         Time := Time + 1; cycle := TRUE; END_PROGRAM",
    );
    let out = plcrun_ok(&[&path, "--cycles", "1"]);
    assert_eq!(out, "cycle,time,Clk.Time,Clk.cycle\n0,T#0s,1,TRUE\n");
    let out = plcrun_ok(&[&path, "--cycles", "1", "--format", "jsonl"]);
    assert_eq!(
        out,
        "{\"cycle\":0,\"time\":\"T#0s\",\"Clk.Time\":1,\"Clk.cycle\":true}\n"
    );
    let (code, _, err) = plcrun(&[&path, "--cycles", "1", "--trace", "time"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("`time` is the trace's own column"), "{err}");
    let out = plcrun_ok(&[&path, "--cycles", "1", "--trace", "clk.time"]);
    assert_eq!(out, "cycle,time,clk.time\n0,T#0s,1\n");
}

//! `plcrun debug` (docs/editors.md, "Debugging"): a scripted client drives
//! the real binary over stdio with Content-Length framed Debug Adapter
//! Protocol messages — breakpoints in CHARIOT, steps by statement, cycle
//! steps, variable writes that change what the program does, conditions,
//! hit counts, forces, faults, and errors answered instead of panics.

use crate::support::cli::temp_file;
use crate::support::dap_client::DapClient;
use serde_json::{Value, json};

const CHARIOT: &str = "programs/chariot.sfc";

/// Line numbers below refer to this program.
const MAIN: &str = "FUNCTION_BLOCK Motor
VAR_INPUT run : BOOL; END_VAR
VAR_OUTPUT speed : INT; END_VAR
IF run THEN
    speed := speed + 1;
END_IF
END_FUNCTION_BLOCK
PROGRAM Main
VAR motor : Motor; n : INT; d : INT := 1; q : INT; clock : TON; END_VAR
n := n + 1;
motor(run := TRUE);
q := 100 / d;
clock(IN := TRUE, PT := T#1h);
END_PROGRAM
";

/// Starts the adapter, launches `program` with `args`, sets `breakpoints`
/// (lines of `file`), and lets it run.
fn launched(program: &[&str], args: &[&str], file: &str, breakpoints: Value) -> DapClient {
    launched_with(program, args, file, breakpoints, false)
}

fn launched_with(
    program: &[&str],
    args: &[&str],
    file: &str,
    breakpoints: Value,
    stop_on_entry: bool,
) -> DapClient {
    let mut c = DapClient::start();
    let caps = c.ok("initialize", json!({"adapterID": "plcrun"}));
    assert_eq!(caps["supportsConditionalBreakpoints"], true);
    c.ok(
        "launch",
        json!({"program": program, "args": args, "stopOnEntry": stop_on_entry}),
    );
    c.event("initialized");
    let set = c.ok(
        "setBreakpoints",
        json!({"source": {"path": file}, "breakpoints": breakpoints}),
    );
    for b in set["breakpoints"].as_array().unwrap() {
        assert_eq!(b["verified"], true, "{b:#}");
    }
    c.ok("configurationDone", json!({}));
    c
}

/// The top frame's `(name, line)`.
fn top(c: &mut DapClient) -> (String, u64) {
    let st = c.ok("stackTrace", json!({"threadId": 1}));
    let f = &st["stackFrames"][0];
    (
        f["name"].as_str().unwrap().to_string(),
        f["line"].as_u64().unwrap(),
    )
}

/// The variables of scope `scope` of frame 1, by name.
fn scope_vars(c: &mut DapClient, scope: &str) -> Vec<(String, String, u64)> {
    let scopes = c.ok("scopes", json!({"frameId": 1}));
    let reference = scopes["scopes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == scope)
        .unwrap_or_else(|| panic!("no scope {scope}: {scopes:#}"))["variablesReference"]
        .clone();
    let vars = c.ok("variables", json!({"variablesReference": reference}));
    vars["variables"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| {
            (
                v["name"].as_str().unwrap().to_string(),
                v["value"].as_str().unwrap().to_string(),
                v["variablesReference"].as_u64().unwrap(),
            )
        })
        .collect()
}

fn value_of(vars: &[(String, String, u64)], name: &str) -> String {
    vars.iter()
        .find(|v| v.0 == name)
        .unwrap_or_else(|| panic!("no {name} in {vars:?}"))
        .1
        .clone()
}

fn evaluate(c: &mut DapClient, expr: &str) -> String {
    let r = c.ok("evaluate", json!({"expression": expr, "frameId": 1}));
    r["result"].as_str().unwrap().to_string()
}

#[test]
fn a_breakpoint_in_chariot_stops_there_with_its_variables_and_stack() {
    // Line 39: `VOM := fcA;`, the body's statement after the chart.
    let mut c = launched(
        &[CHARIOT],
        &["--cycles", "100", "--stimulus", "programs/chariot.csv"],
        CHARIOT,
        json!([{"line": 39}]),
    );
    let stopped = c.event("stopped");
    assert_eq!(stopped["reason"], "breakpoint");
    assert_eq!(stopped["threadId"], 1);
    let st = c.ok("stackTrace", json!({"threadId": 1}));
    let f = &st["stackFrames"][0];
    assert_eq!(f["name"], "CHARIOT");
    assert_eq!(f["line"], 39);
    assert!(
        f["source"]["path"]
            .as_str()
            .unwrap()
            .ends_with("programs/chariot.sfc"),
        "{f:#}"
    );
    let io = scope_vars(&mut c, "Inputs/Outputs");
    // Cycle 0 of the stimulus: FcA TRUE, Dcy FALSE; the chart is in INIT.
    assert_eq!(value_of(&io, "FcA"), "TRUE");
    assert_eq!(value_of(&io, "Dcy"), "FALSE");
    assert_eq!(value_of(&io, "KMAV"), "FALSE");
    assert_eq!(value_of(&io, "tX3"), "T#10m");
    let locals = scope_vars(&mut c, "Locals");
    let (_, _, init) = locals.iter().find(|v| v.0 == "INIT").unwrap().clone();
    assert!(init > 0, "a step has members");
    let x = c.ok("variables", json!({"variablesReference": init}));
    assert_eq!(x["variables"][0]["name"], "X");
    assert_eq!(x["variables"][0]["value"], "TRUE");
    c.ok("disconnect", json!({}));
    assert_eq!(c.finish(), 0);
}

#[test]
fn a_breakpoint_in_chariots_action_stops_when_the_action_runs() {
    // Line 23: step AV's association `KMAV(N, fcB)`; the stimulus presses
    // Dcy at cycle 5, with the trolley at A: AV becomes active and its
    // action runs in that cycle.
    let mut c = launched(
        &[CHARIOT],
        &["--cycles", "200", "--stimulus", "programs/chariot.csv"],
        CHARIOT,
        json!([{"line": 23}]),
    );
    assert_eq!(c.event("stopped")["reason"], "breakpoint");
    let st = c.ok("stackTrace", json!({"threadId": 1}));
    let frames = st["stackFrames"].as_array().unwrap();
    assert_eq!(frames[0]["name"], "CHARIOT.KMAV");
    assert_eq!(frames[0]["line"], 23);
    assert_eq!(frames[1]["name"], "CHARIOT");
    assert_eq!(evaluate(&mut c, "AV.X"), "TRUE");
    assert_eq!(evaluate(&mut c, "INIT.X"), "FALSE");
    let io = scope_vars(&mut c, "Inputs/Outputs");
    assert_eq!(value_of(&io, "Dcy"), "TRUE");
    assert_eq!(value_of(&io, "FcA"), "TRUE");
    // The step line stops when the step becomes active; the transition
    // header when it fires (FcB at cycle 100).
    c.ok(
        "setBreakpoints",
        json!({"source": {"path": CHARIOT}, "breakpoints": [{"line": 25}, {"line": 28}]}),
    );
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("CHARIOT.AV -> ATT".into(), 25));
    assert_eq!(evaluate(&mut c, "FcB"), "TRUE");
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("CHARIOT.ATT".into(), 28));
    assert_eq!(evaluate(&mut c, "ATT.X"), "TRUE");
    c.ok("disconnect", json!({}));
}

#[test]
fn under_grafcet_evolution_chariots_action_stops_too() {
    let mut c = launched(
        &[CHARIOT],
        &[
            "--grafcet",
            "--cycles",
            "200",
            "--stimulus",
            "programs/chariot.csv",
        ],
        CHARIOT,
        json!([{"line": 23}]),
    );
    c.event("stopped");
    assert_eq!(top(&mut c), ("CHARIOT.KMAV".into(), 23));
    assert_eq!(evaluate(&mut c, "AV.X"), "TRUE");
    c.ok("disconnect", json!({}));
}

#[test]
fn a_breakpoint_in_a_chariot_transition_names_it_in_the_stack() {
    // Line 20: INIT -> AV's condition `dcy & fcA`.
    let mut c = launched(
        &[CHARIOT],
        &["--cycles", "10"],
        CHARIOT,
        json!([{"line": 20}]),
    );
    assert_eq!(c.event("stopped")["reason"], "breakpoint");
    let st = c.ok("stackTrace", json!({"threadId": 1}));
    let names: Vec<&str> = st["stackFrames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    assert_eq!(names.len(), 2, "{st:#}");
    assert!(names[0].starts_with("CHARIOT."), "{names:?}");
    assert_eq!(names[1], "CHARIOT");
    assert_eq!(st["stackFrames"][0]["line"], 20);
    // `terminate` ends the program; the `disconnect` after it, the adapter.
    c.ok("terminate", json!({}));
    c.event("terminated");
    c.ok("disconnect", json!({}));
    assert_eq!(c.finish(), 0);
}

#[test]
fn steps_go_by_statement_into_and_out_of_a_block() {
    let main = temp_file("main.st", MAIN);
    let mut c = launched(&[&main], &["--cycles", "5"], &main, json!([{"line": 10}]));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Main".into(), 10));
    assert_eq!(evaluate(&mut c, "n"), "0");
    c.ok("next", json!({"threadId": 1}));
    assert_eq!(c.event("stopped")["reason"], "step");
    assert_eq!(top(&mut c), ("Main".into(), 11));
    // The statement ran: n is 1.
    assert_eq!(evaluate(&mut c, "n"), "1");
    c.ok("stepIn", json!({"threadId": 1}));
    c.event("stopped");
    let st = c.ok("stackTrace", json!({"threadId": 1}));
    assert_eq!(st["stackFrames"][0]["name"], "Main.motor (Motor)");
    assert_eq!(st["stackFrames"][0]["line"], 4);
    assert_eq!(st["stackFrames"][1]["name"], "Main");
    assert_eq!(st["stackFrames"][1]["line"], 11);
    let io = scope_vars(&mut c, "Inputs/Outputs");
    assert_eq!(value_of(&io, "run"), "TRUE");
    c.ok("next", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Main.motor (Motor)".into(), 5));
    c.ok("stepOut", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Main".into(), 12));
    // Over a call: from 11 the next stop is 12, not inside Motor.
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Main".into(), 10));
    c.ok("next", json!({"threadId": 1}));
    c.event("stopped");
    c.ok("next", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Main".into(), 12));
    c.ok("disconnect", json!({}));
}

#[test]
fn il_steps_by_instruction() {
    let il = temp_file(
        "count.il",
        "PROGRAM Count\nVAR a : INT; b : INT; END_VAR\nLD a\nADD 1\nST a\nST b\nEND_PROGRAM\n",
    );
    let mut c = launched(&[&il], &["--cycles", "3"], &il, json!([{"line": 4}]));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Count".into(), 4));
    c.ok("next", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Count".into(), 5));
    assert_eq!(evaluate(&mut c, "a"), "0");
    c.ok("next", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Count".into(), 6));
    assert_eq!(evaluate(&mut c, "a"), "1");
    c.ok("disconnect", json!({}));
}

#[test]
fn a_cycle_step_advances_the_clock_by_one_cycle() {
    let main = temp_file("main.st", MAIN);
    let mut c = launched_with(&[&main], &["--cycles", "10"], &main, json!([]), true);
    assert_eq!(c.event("stopped")["reason"], "entry");
    c.ok("cycleStep", json!({"threadId": 1}));
    let s = c.event("stopped");
    assert_eq!(s["description"], "Cycle boundary: before cycle 1");
    let first = evaluate(&mut c, "clock.ET");
    c.ok("cycleStep", json!({"threadId": 1}));
    let s = c.event("stopped");
    assert_eq!(s["description"], "Cycle boundary: before cycle 2");
    // The default cycle time is 10 ms: the timer's ET grew by one cycle.
    assert_eq!(
        (first.as_str(), evaluate(&mut c, "clock.ET").as_str()),
        ("T#0s", "T#10ms")
    );
    assert_eq!(evaluate(&mut c, "n"), "2");
    // From a boundary, a step goes to the cycle's first statement.
    c.ok("next", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("Main".into(), 10));
    c.ok("disconnect", json!({}));
}

#[test]
fn setting_a_variable_changes_what_chariot_does() {
    // No stimulus: Dcy and FcA stay FALSE, the trolley never leaves INIT...
    let mut c = launched(
        &[CHARIOT],
        &["--cycles", "10"],
        CHARIOT,
        json!([{"line": 20}]),
    );
    c.event("stopped");
    // ...unless the debugger presses the button with the trolley at A.
    let scopes = c.ok("scopes", json!({"frameId": 2}));
    let io = scopes["scopes"][1]["variablesReference"].clone();
    for name in ["Dcy", "FcA"] {
        let set = c.ok(
            "setVariable",
            json!({"variablesReference": io, "name": name, "value": "TRUE"}),
        );
        assert_eq!(set["value"], "TRUE");
    }
    let bad = c.request(
        "setVariable",
        json!({"variablesReference": io, "name": "Dcy", "value": "42"}),
    );
    assert_eq!(bad["success"], false);
    c.ok(
        "setBreakpoints",
        json!({"source": {"path": CHARIOT}, "breakpoints": []}),
    );
    c.ok("cycleStep", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(evaluate(&mut c, "AV.X"), "TRUE");
    assert_eq!(evaluate(&mut c, "KMAV"), "TRUE");
    c.ok("disconnect", json!({}));
}

#[test]
fn conditions_and_hit_counts_choose_the_stops() {
    let main = temp_file("main.st", MAIN);
    let mut c = launched(
        &[&main],
        &["--cycles", "20"],
        &main,
        json!([{"line": 11, "condition": "n MOD 4 = 3"}]),
    );
    c.event("stopped");
    assert_eq!(evaluate(&mut c, "n"), "3");
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(evaluate(&mut c, "n"), "7");
    c.ok(
        "setBreakpoints",
        json!({"source": {"path": main}, "breakpoints": [{"line": 12, "hitCondition": "% 5"}]}),
    );
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(evaluate(&mut c, "n"), "11");
    assert_eq!(evaluate(&mut c, "n * 2 + 1 > 22 AND motor.run"), "TRUE");
    c.ok("disconnect", json!({}));
}

#[test]
fn a_force_from_evaluate_holds_over_the_program() {
    let main = temp_file("main.st", MAIN);
    // Line 10, `n := n + 1;`: stops before it runs.
    let mut c = launched(&[&main], &["--cycles", "20"], &main, json!([{"line": 10}]));
    c.event("stopped");
    assert_eq!(evaluate(&mut c, "n"), "0");
    let r = evaluate(&mut c, "force n := 100");
    assert!(r.contains("forced"), "{r}");
    // Written at once, held from the next cycle on: each cycle starts
    // with n = 100 whatever the program wrote in the last one.
    for _ in 0..2 {
        c.ok("continue", json!({"threadId": 1}));
        c.event("stopped");
        assert_eq!(evaluate(&mut c, "n"), "100");
    }
    c.ok("evaluate", json!({"expression": "unforce n", "frameId": 1}));
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(evaluate(&mut c, "n"), "100");
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(evaluate(&mut c, "n"), "101");
    // The custom request does the same.
    c.ok("force", json!({"name": "q", "value": "7"}));
    assert_eq!(evaluate(&mut c, "q"), "7");
    let bad = c.request("force", json!({"name": "q", "value": "TRUE"}));
    assert_eq!(bad["success"], false);
    c.ok("disconnect", json!({}));
}

#[test]
fn a_fault_stops_with_its_code_and_instance_path() {
    let main = temp_file("main.st", MAIN);
    let mut c = launched(
        &[&main],
        &["--cycles", "5", "--set", "d=0"],
        &main,
        json!([]),
    );
    let s = c.event("stopped");
    assert_eq!(s["reason"], "exception");
    let text = s["text"].as_str().unwrap();
    assert!(text.contains("division by zero"), "{text}");
    assert!(s["description"].as_str().unwrap().contains("Main"), "{s:#}");
    assert_eq!(top(&mut c), ("Main".into(), 12));
    c.ok("continue", json!({"threadId": 1}));
    assert_eq!(c.event("exited")["exitCode"], 3);
    c.event("terminated");
}

#[test]
fn bad_requests_get_error_responses() {
    let mut c = DapClient::start();
    c.ok("initialize", json!({"adapterID": "plcrun"}));
    let early = c.request("stackTrace", json!({"threadId": 1}));
    assert_eq!(early["success"], false);
    let missing = c.request("launch", json!({"program": "no/such/file.st"}));
    assert_eq!(missing["success"], false);
    let flags = c.request(
        "launch",
        json!({"program": CHARIOT, "args": ["--no-such-flag"]}),
    );
    assert_eq!(flags["success"], false);
    assert!(flags["message"].as_str().unwrap().contains("no-such-flag"));
    let shape = c.request("launch", json!({"program": 42}));
    assert_eq!(shape["success"], false);
    c.ok(
        "launch",
        json!({"program": CHARIOT, "args": ["--cycles", "1000000"]}),
    );
    c.event("initialized");
    let set = c.ok(
        "setBreakpoints",
        json!({"source": {"path": "elsewhere.st"}, "breakpoints": [{"line": 3}]}),
    );
    assert_eq!(set["breakpoints"][0]["verified"], false);
    let hits = c.ok(
        "setBreakpoints",
        json!({"source": {"path": CHARIOT}, "breakpoints": [{"line": 39, "hitCondition": "often"}]}),
    );
    assert_eq!(hits["breakpoints"][0]["verified"], false);
    c.ok("configurationDone", json!({}));
    let running = c.request("stackTrace", json!({"threadId": 1}));
    assert_eq!(running["success"], false);
    c.ok("pause", json!({"threadId": 1}));
    assert_eq!(c.event("stopped")["reason"], "pause");
    let bad_frame = c.request("scopes", json!({"frameId": 99}));
    assert_eq!(bad_frame["success"], false);
    let bad_ref = c.request("variables", json!({"variablesReference": 999}));
    assert_eq!(bad_ref["success"], false);
    let bad_expr = c.request("evaluate", json!({"expression": "(1 +", "frameId": 1}));
    assert_eq!(bad_expr["success"], false);
    let unknown = c.request(
        "evaluate",
        json!({"expression": "nothing_here", "frameId": 1}),
    );
    assert_eq!(unknown["success"], false);
    c.ok("disconnect", json!({}));
    assert_eq!(c.finish(), 0);
}

#[test]
fn breakpoints_on_a_chart_drawn_in_plcopen_xml_stop_at_its_elements() {
    // tests/plcopen/chariot.xml is CHARIOT drawn: line 55 is step AV's
    // `<step>`, 70 the `<action>` of its action block (KMAV), 75 the
    // `<transition>` AV -> ATT, 84 step ATT's `<step>`. The stimulus
    // presses Dcy at cycle 5 (AV), FcB comes at cycle 100 (ATT).
    const DRAWN: &str = "tests/plcopen/chariot.xml";
    let mut c = launched(
        &[DRAWN],
        &["--cycles", "200", "--stimulus", "programs/chariot.csv"],
        DRAWN,
        json!([{"line": 55}, {"line": 70}]),
    );
    assert_eq!(c.event("stopped")["reason"], "breakpoint");
    assert_eq!(top(&mut c), ("CHARIOT.AV".into(), 55));
    assert_eq!(evaluate(&mut c, "AV.X"), "TRUE");
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("CHARIOT.KMAV".into(), 70));
    c.ok(
        "setBreakpoints",
        json!({"source": {"path": DRAWN}, "breakpoints": [{"line": 75}, {"line": 84}]}),
    );
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("CHARIOT.AV -> ATT".into(), 75));
    assert_eq!(evaluate(&mut c, "FcB"), "TRUE");
    c.ok("continue", json!({"threadId": 1}));
    c.event("stopped");
    assert_eq!(top(&mut c), ("CHARIOT.ATT".into(), 84));
    c.ok("disconnect", json!({}));
}

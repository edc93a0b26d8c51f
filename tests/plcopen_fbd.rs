//! FBD bodies of PLCopen XML projects (issue #29, point 1): lowered to ST
//! by the importer, they run like their hand-written ST twins on random
//! stimulus; feedback paths, execution order, jumps and returns follow the
//! hand-derived traces below; malformed networks get coded diagnostics at
//! their place in the XML.

use crate::support::graphic;

use graphic::*;

const FBD_OUTPUTS: &str =
    "q_and,q_nor,q_cv,q_cq,q_t,q_mux,q_sum,q_acc,q_move,q_eno,q_link,q_rise,q_skip,q_after";

#[test]
fn every_fbd_element_runs_like_its_st_twin() {
    for seed in [7, 1234, 99_991] {
        let stimulus = random_stimulus(&["a", "b", "c"], &["n", "k"], 120, seed);
        let xml = trace_of(
            &["tests/plcopen/fbd_elements.xml"],
            FBD_OUTPUTS,
            &stimulus,
            120,
        );
        let st = trace_of(
            &["tests/plcopen/fbd_elements.st"],
            FBD_OUTPUTS,
            &stimulus,
            120,
        );
        assert_same(&xml, &st, &format!("seed {seed}"));
        // The stimulus does reach the interesting states.
        for (name, seen) in [
            ("q_cq", "TRUE"),
            ("q_t", "TRUE"),
            ("q_rise", "TRUE"),
            ("q_eno", "FALSE"),
        ] {
            assert!(
                column(&xml, name).iter().any(|c| c == seen),
                "{name} never {seen}"
            );
        }
    }
}

/// A program `P` with BOOL input `a`, `c`, INT outputs `q`, `i`, BOOL outputs `x`, `y`.
fn program(elements: &[String]) -> String {
    let iface = format!(
        "{}{}",
        vars("inputVars", &["a", "c"]),
        vars("outputVars", &["q:INT", "i:INT", "x", "y"])
    );
    project(&graphic_pou("P", "program", &iface, "FBD", elements))
}

#[test]
fn a_connection_back_to_an_earlier_block_reads_the_previous_cycle() {
    // q := ADD(1, <ADD's own output>): 1, 2, 3, ... (the hidden variable
    // starts at 0).
    let text = program(&[
        in_var(1, "1", 10),
        block(
            2,
            "ADD",
            10,
            &[("IN1", &["1"]), ("IN2", &["2:OUT"])],
            &["OUT"],
            "",
        ),
        out_var(3, "q", &["2:OUT"], 10, ""),
    ]);
    let trace = trace_text(&text, "q", "cycle,a\n0,FALSE\n", 5);
    assert_eq!(column(&trace, "q"), ["1", "2", "3", "4", "5"]);
}

#[test]
fn the_difference_of_two_moments_kept_for_eno_is_a_duration() {
    // SUB(t1, t2) on DTs, its ENO chained to LT's EN: the importer keeps
    // SUB's result in a hidden variable, which must be a TIME (DT - DT),
    // not a DT like its first input (Beremiz's iec61131_lang_test met E306
    // `<` of DT and TIME here).
    let iface = format!(
        "{}{}",
        vars("inputVars", &["a", "t1:DT", "t2:DT"]),
        vars("outputVars", &["x", "d:TIME"])
    );
    let text = project(&graphic_pou(
        "P",
        "program",
        &iface,
        "FBD",
        &[
            in_var(1, "a", 10),
            in_var(2, "t1", 20),
            in_var(3, "t2", 30),
            block(
                4,
                "SUB",
                20,
                &[("EN", &["1"]), ("IN1", &["2"]), ("IN2", &["3"])],
                &["ENO", "OUT"],
                "",
            ),
            in_var(5, "T#10s", 40),
            block(
                6,
                "LT",
                30,
                &[("EN", &["4:ENO"]), ("IN1", &["4:OUT"]), ("IN2", &["5"])],
                &["ENO", "OUT"],
                "",
            ),
            out_var(7, "x", &["6:OUT"], 30, ""),
            out_var(8, "d", &["4:OUT"], 50, ""),
        ],
    ));
    let stimulus = "cycle,a,t1,t2\n\
                    0,TRUE,DT#2024-01-01-00:00:05,DT#2024-01-01-00:00:00\n\
                    1,TRUE,DT#2024-01-01-00:01:00,DT#2024-01-01-00:00:00\n";
    let trace = trace_text(&text, "x,d", stimulus, 2);
    assert_eq!(column(&trace, "d"), ["T#5s", "T#1m"]);
    assert_eq!(column(&trace, "x"), ["TRUE", "FALSE"]);
}

#[test]
fn execution_order_ids_win_over_positions() {
    let a = "0110100";
    let stimulus = bit_stimulus(&[("a", a)]);
    // x := a at the top, y := x below it: y follows a in the same cycle.
    let by_place = |xo: &str, yo: &str, y_row: u32| {
        program(&[
            in_var(1, "a", 10),
            out_var(2, "x", &["1"], 10, xo),
            in_var(3, "x", 20),
            out_var(4, "y", &["3"], y_row, yo),
        ])
    };
    let trace = trace_text(&by_place("", "", 20), "x,y", &stimulus, 7);
    assert_eq!(bits(&trace, "y"), a);
    // Numbered y first: it reads the x of the previous cycle.
    let numbered = by_place(" executionOrderId=\"2\"", " executionOrderId=\"1\"", 20);
    let trace = trace_text(&numbered, "x,y", &stimulus, 7);
    assert_eq!(bits(&trace, "x"), a);
    assert_eq!(bits(&trace, "y"), "0011010");
    // Unnumbered with y drawn above x: top to bottom, the same delay.
    let trace = trace_text(&by_place("", "", 5), "x,y", &stimulus, 7);
    assert_eq!(bits(&trace, "y"), "0011010");
}

#[test]
fn a_backward_jump_loops_and_a_return_leaves_the_body() {
    // i := 0; L: i := i + 1; IF i < 5 THEN JMP L; q := i * 10 (unless c: RETURN first).
    let text = program(&[
        in_var(1, "0", 0),
        out_var(2, "i", &["1"], 0, ""),
        "<label localId=\"3\" label=\"L\"><position x=\"0\" y=\"10\"/></label>".to_string(),
        in_var(4, "i + 1", 20),
        out_var(5, "i", &["4"], 20, ""),
        in_var(6, "i &lt; 5", 30),
        format!(
            "<jump localId=\"7\" label=\"L\"><position x=\"300\" y=\"30\"/>{}</jump>",
            point(&["6"])
        ),
        in_var(8, "c", 40),
        format!(
            "<return localId=\"9\"><position x=\"300\" y=\"40\"/>{}</return>",
            point(&["8"])
        ),
        in_var(10, "i * 10", 50),
        out_var(11, "q", &["10"], 50, ""),
    ]);
    let stimulus = bit_stimulus(&[("c", "00110")]);
    let trace = trace_text(&text, "i,q", &stimulus, 5);
    assert_eq!(column(&trace, "i"), ["5", "5", "5", "5", "5"]);
    // q keeps its value while c returns before it.
    assert_eq!(column(&trace, "q"), ["50", "50", "50", "50", "50"]);
    let first_returns = text.replace("i * 10", "i * 10 + 1");
    let stimulus = bit_stimulus(&[("c", "11001")]);
    let trace = trace_text(&first_returns, "q", &stimulus, 5);
    assert_eq!(column(&trace, "q"), ["0", "0", "51", "51", "51"]);
}

#[test]
fn function_and_function_block_bodies_in_fbd() {
    // FUNCTION Twice : INT := x * 2; FUNCTION_BLOCK Acc: total := total + inc;
    // the program: acc1(inc := Twice(3)); q := acc1.total.
    let twice = graphic_pou(
        "Twice",
        "function",
        &format!(
            "<returnType><INT/></returnType>{}",
            vars("inputVars", &["x:INT"])
        ),
        "FBD",
        &[
            in_var(1, "x", 10),
            in_var(2, "2", 20),
            block(
                3,
                "MUL",
                10,
                &[("IN1", &["1"]), ("IN2", &["2"])],
                &["OUT"],
                "",
            ),
            out_var(4, "Twice", &["3:OUT"], 10, ""),
        ],
    );
    let acc = graphic_pou(
        "Acc",
        "functionBlock",
        &format!(
            "{}{}",
            vars("inputVars", &["inc:INT"]),
            vars("outputVars", &["total:INT"])
        ),
        "FBD",
        &[
            in_var(1, "total", 10),
            in_var(2, "inc", 20),
            block(
                3,
                "ADD",
                10,
                &[("IN1", &["1"]), ("IN2", &["2"])],
                &["OUT"],
                "",
            ),
            out_var(4, "total", &["3:OUT"], 10, ""),
        ],
    );
    let main = graphic_pou(
        "P",
        "program",
        &format!(
            "{}{}",
            vars("outputVars", &["q:INT"]),
            vars("localVars", &["acc1:Acc"])
        ),
        "FBD",
        &[
            in_var(1, "3", 10),
            block(2, "Twice", 10, &[("x", &["1"])], &["OUT"], ""),
            block(
                3,
                "Acc",
                10,
                &[("inc", &["2:OUT"])],
                &["total"],
                " instanceName=\"acc1\"",
            ),
            out_var(4, "q", &["3:total"], 10, ""),
        ],
    );
    let text = project(&format!("{twice}\n{acc}\n{main}"));
    let trace = trace_text(&text, "q", "", 3);
    assert_eq!(column(&trace, "q"), ["6", "12", "18"]);
}

/// The only error of `text`: `(code, location, message)`.
fn only_error(text: &str) -> (String, String, String) {
    let found = errors(text);
    assert_eq!(found.len(), 1, "{found:#?}");
    found[0].clone()
}

#[test]
fn malformed_networks_get_coded_errors_at_their_element() {
    let dangling = program(&[out_var(1, "x", &["42"], 10, "")]);
    let (code, at, _) = only_error(&dangling);
    assert_eq!(
        (code.as_str(), at),
        ("E808", location_of(&dangling, "42\""))
    );

    let lost = program(&[
        "<continuation localId=\"1\" name=\"NOWHERE\"><position x=\"0\" y=\"0\"/><connectionPointOut/></continuation>".to_string(),
        out_var(2, "x", &["1"], 10, ""),
    ]);
    let (code, at, message) = only_error(&lost);
    assert_eq!(
        (code.as_str(), at),
        ("E816", location_of(&lost, "<continuation"))
    );
    assert!(message.contains("NOWHERE"), "{message}");

    let no_pin = program(&[
        in_var(1, "a", 10),
        block(2, "NOT", 10, &[("IN", &["1"])], &["OUT"], ""),
        out_var(3, "x", &["2:Q"], 10, ""),
    ]);
    let (code, at, message) = only_error(&no_pin);
    assert_eq!(code, "E817");
    assert_eq!(at, location_of(&no_pin, "<connection refLocalId=\"2\""));
    assert!(message.contains("`Q`"), "{message}");

    // Drawn but not wired: an outVariable writes nothing, with a warning.
    let unconnected = program(&[
        "<outVariable localId=\"1\"><position x=\"0\" y=\"0\"/><connectionPointIn/><expression>x</expression></outVariable>".to_string(),
    ]);
    let found = diagnostics(&unconnected);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(
        (found[0].0.as_str(), found[0].1.clone()),
        ("W802", location_of(&unconnected, "<outVariable"))
    );
    let trace = trace_text(&unconnected, "x", &bit_stimulus(&[("a", "1")]), 1);
    assert_eq!(bits(&trace, "x"), "0");

    let no_label = program(&[
        in_var(1, "a", 10),
        format!(
            "<jump localId=\"2\" label=\"Far\"><position x=\"0\" y=\"0\"/>{}</jump>",
            point(&["1"])
        ),
    ]);
    let (code, at, _) = only_error(&no_label);
    assert_eq!(
        (code.as_str(), at),
        ("E819", location_of(&no_label, "Far\""))
    );

    // A function output read twice whose type nothing tells: refused, not guessed.
    let untyped = program(&[
        in_var(1, "1", 10),
        in_var(2, "2", 20),
        block(
            3,
            "ADD",
            10,
            &[("IN1", &["1"]), ("IN2", &["2"])],
            &["OUT"],
            "",
        ),
        block(
            4,
            "MUL",
            30,
            &[("IN1", &["3:OUT"]), ("IN2", &["3:OUT"])],
            &["OUT"],
            "",
        ),
        block(
            5,
            "GT",
            40,
            &[("IN1", &["4:OUT"]), ("IN2", &["2"])],
            &["OUT"],
            "",
        ),
        out_var(6, "x", &["5:OUT"], 40, ""),
    ]);
    let (code, at, message) = only_error(&untyped);
    assert_eq!(code, "E820");
    assert_eq!(at, location_of(&untyped, "<block localId=\"3\""));
    assert!(message.contains("ADD"), "{message}");
}

#[test]
fn errors_in_expressions_point_at_their_characters() {
    let text = program(&[in_var(1, "a AND zz", 10), out_var(2, "x", &["1"], 10, "")]);
    let (code, at, _) = only_error(&text);
    assert_eq!((code.as_str(), at), ("E201", location_of(&text, "zz<")));
    // A type error in a block's input is reported, at the input.
    let text = program(&[
        in_var(1, "T#1s", 10),
        block(2, "NOT", 10, &[("IN", &["1"])], &["OUT"], ""),
        out_var(3, "x", &["2:OUT"], 10, ""),
    ]);
    assert!(!errors(&text).is_empty());
}

#[test]
fn truncated_and_flipped_fixtures_never_panic() {
    for fixture in [
        "tests/plcopen/fbd_elements.xml",
        "tests/plcopen/ld_elements.xml",
    ] {
        let bytes = repo_text(fixture).into_bytes();
        let (unit, diags) = plcrun::syntax::plcopen::parse_bytes(&bytes);
        assert!(!diags.has_errors() && !unit.items.is_empty(), "{fixture}");
        for cut in (0..bytes.len()).step_by(211) {
            let (_, diags) = plcrun::syntax::plcopen::parse_bytes(&bytes[..cut]);
            assert!(diags.has_errors(), "{fixture} cut at {cut}");
        }
        let mut flipped = bytes.clone();
        for i in (0..flipped.len()).step_by(97) {
            flipped[i] ^= 0x04;
            let _ = plcrun::syntax::plcopen::parse_bytes(&flipped);
        }
    }
}

#[test]
fn a_long_chain_of_blocks_ends_quickly() {
    // 3000 NOT functions in series: each kept inline up to a depth, then
    // stored; no deep recursion, no quadratic blow-up.
    let mut els = vec![in_var(1, "a", 0)];
    for k in 0..3000u32 {
        let from = if k == 0 {
            "1".to_string()
        } else {
            format!("{}:OUT", 9 + k)
        };
        els.push(block(
            10 + k,
            "NOT",
            k + 1,
            &[("IN", &[from.as_str()])],
            &["OUT"],
            "",
        ));
    }
    els.push(out_var(5, "x", &["3009:OUT"], 5000, ""));
    let text = program(&els);
    let started = std::time::Instant::now();
    let trace = trace_text(&text, "x", &bit_stimulus(&[("a", "01")]), 2);
    assert!(started.elapsed().as_secs() < 20, "{:?}", started.elapsed());
    // An even number of NOTs: x is a.
    assert_eq!(bits(&trace, "x"), "01");
}

#[test]
fn a_function_block_with_en_runs_only_when_enabled_and_its_eno_says_so() {
    // Inc counts its calls; EN := a, ENO -> x, n -> q.
    let inc = "<pou name=\"Inc\" pouType=\"functionBlock\"><interface><outputVars><variable name=\"n\"><type><INT/></type></variable></outputVars></interface><body><ST><xhtml:p>n := n + 1;</xhtml:p></ST></body></pou>";
    let main = graphic_pou(
        "P",
        "program",
        &format!(
            "{}{}{}",
            vars("inputVars", &["a"]),
            vars("outputVars", &["q:INT", "x"]),
            vars("localVars", &["i1:Inc"])
        ),
        "FBD",
        &[
            in_var(1, "a", 10),
            block(
                2,
                "Inc",
                10,
                &[("EN", &["1"])],
                &["ENO", "n"],
                " instanceName=\"i1\"",
            ),
            out_var(3, "x", &["2:ENO"], 10, ""),
            out_var(4, "q", &["2:n"], 20, ""),
        ],
    );
    let text = project(&format!("{inc}\n{main}"));
    let trace = trace_text(&text, "q,x", &bit_stimulus(&[("a", "0110101")]), 7);
    assert_eq!(column(&trace, "q"), ["0", "1", "2", "2", "3", "3", "4"]);
    assert_eq!(bits(&trace, "x"), "0110101");
}

#[test]
fn a_chart_with_a_wired_condition_an_fbd_action_and_an_fbd_transition_runs_like_its_twin() {
    // S0 --[go, a contact wired to the condition]--> S1 (action Count in
    // FBD: n := n + 1) --[transition Back in FBD: n >= 3]--> S0.
    let conn = |id: &str| point(&[id]);
    let chart = format!(
        "<step localId=\"1\" name=\"S0\" initialStep=\"true\"/>\
         <leftPowerRail localId=\"20\"><position x=\"0\" y=\"0\"/><connectionPointOut formalParameter=\"\"/></leftPowerRail>\
         <contact localId=\"21\"><position x=\"10\" y=\"0\"/>{}<connectionPointOut/><variable>go</variable></contact>\
         <transition localId=\"2\">{}<condition>{}</condition></transition>\
         <step localId=\"3\" name=\"S1\">{}</step>\
         <actionBlock localId=\"4\">{}<action><reference name=\"Count\"/></action></actionBlock>\
         <transition localId=\"5\">{}<condition><reference name=\"Back\"/></condition></transition>\
         <jumpStep localId=\"6\" targetName=\"S0\">{}</jumpStep>",
        conn("20"),
        conn("1"),
        conn("21"),
        conn("2"),
        conn("3"),
        conn("3"),
        conn("5"),
    );
    let count = graphic_pou(
        "unused",
        "program",
        "",
        "FBD",
        &[
            in_var(1, "n", 10),
            in_var(2, "1", 20),
            block(
                3,
                "ADD",
                10,
                &[("IN1", &["1"]), ("IN2", &["2"])],
                &["OUT"],
                "",
            ),
            out_var(4, "n", &["3:OUT"], 10, ""),
        ],
    );
    let back = graphic_pou(
        "unused",
        "program",
        "",
        "FBD",
        &[
            in_var(1, "n", 10),
            in_var(2, "3", 20),
            block(
                3,
                "GE",
                10,
                &[("IN1", &["1"]), ("IN2", &["2"])],
                &["OUT"],
                "",
            ),
            out_var(4, "Back", &["3:OUT"], 10, ""),
        ],
    );
    // The <body> of each helper POU, reused as an action's and a transition's body.
    let body_of = |pou: &str| {
        let s = pou.find("<body>").unwrap();
        let e = pou.rfind("</body>").unwrap() + "</body>".len();
        pou[s..e].to_string()
    };
    let pou = format!(
        "<pou name=\"P\" pouType=\"program\"><interface>{}{}</interface>\
         <actions><action name=\"Count\">{}</action></actions>\
         <transitions><transition name=\"Back\">{}</transition></transitions>\
         <body><SFC>{chart}</SFC></body></pou>",
        vars("inputVars", &["go"]),
        vars("outputVars", &["n:INT"]),
        body_of(&count),
        body_of(&back),
    );
    let xml = project(&pou);
    let twin = "PROGRAM P\nVAR_INPUT go : BOOL; END_VAR\nVAR_OUTPUT n : INT; END_VAR\n\
        INITIAL_STEP S0 : END_STEP\nSTEP S1 : Count(N); END_STEP\n\
        TRANSITION FROM S0 TO S1 := go; END_TRANSITION\n\
        TRANSITION FROM S1 TO S0 := n >= 3; END_TRANSITION\n\
        ACTION Count : n := n + 1; END_ACTION\nEND_PROGRAM\n";
    for seed in [5, 6] {
        let stimulus = random_stimulus(&["go"], &[], 60, seed);
        let names = "n,S0.X,S1.X";
        let a = trace_text(&xml, names, &stimulus, 60);
        let request = TraceRequest {
            cycles: 60,
            stimulus: Some(&stimulus),
            trace: Some(names),
            changes_only: false,
        };
        let b = csv_trace(&[("twin.sfc", twin)], &request);
        assert_same(&a, &b, &format!("seed {seed}"));
        assert!(column(&a, "S1.X").iter().any(|c| c == "TRUE"));
    }
    // A transition network that would need a statement is refused by name.
    let stateful = xml.replace("typeName=\"GE\"", "typeName=\"GE\" instanceName=\"g\"");
    let found = errors(&stateful);
    assert!(
        found
            .iter()
            .any(|d| d.0 == "E807" && d.2.contains("transition")),
        "{found:#?}"
    );
}

#[test]
fn a_body_starting_with_an_unread_function_is_st_not_il() {
    // ADD's result is read by nobody: the call is a statement, `ADD(...);`,
    // which must not be read as the IL operator `ADD(`.
    let text = program(&[
        in_var(1, "i", 10),
        in_var(2, "1", 20),
        block(
            3,
            "ADD",
            10,
            &[("IN1", &["1"]), ("IN2", &["2"])],
            &["OUT"],
            "",
        ),
        in_var(4, "a", 30),
        out_var(5, "x", &["4"], 30, ""),
    ]);
    assert!(errors(&text).is_empty(), "{:#?}", errors(&text));
    let trace = trace_text(&text, "x", &bit_stimulus(&[("a", "01")]), 2);
    assert_eq!(bits(&trace, "x"), "01");
}

#[test]
fn a_long_chain_of_in_out_pins_is_refused_not_a_stack_overflow() {
    // 5000 instances, each passing the variable of its in-out on to the
    // next one's: the value is written inline through every pin, so the
    // chain is refused past a depth instead of exhausting the stack.
    let mut els = vec![in_var(1, "i", 0)];
    for k in 0..5000u32 {
        let from = if k == 0 {
            "1".to_string()
        } else {
            format!("{}:v", 9 + k)
        };
        els.push(format!(
            "<block localId=\"{}\" typeName=\"Pass\" instanceName=\"p\"><position x=\"0\" y=\"{k}\"/><inputVariables/><inOutVariables><variable formalParameter=\"v\">{}<connectionPointOut/></variable></inOutVariables><outputVariables/></block>",
            10 + k,
            point(&[from.as_str()])
        ));
    }
    els.push(out_var(5, "q", &["5009:v"], 6000, ""));
    let text = program(&els);
    let found = errors(&text);
    assert!(
        found
            .iter()
            .any(|d| d.0 == "E807" && d.2.contains("deeply")),
        "{:?}",
        &found[..found.len().min(3)]
    );
}

#[test]
fn a_runtime_fault_in_a_block_names_the_pou_and_the_block_in_the_xml() {
    let text = project(&graphic_pou(
        "P",
        "program",
        &format!(
            "{}{}",
            vars("inputVars", &["d:INT"]),
            vars("outputVars", &["q:INT"])
        ),
        "FBD",
        &[
            in_var(1, "10", 10),
            in_var(2, "d", 20),
            block(
                3,
                "DIV",
                10,
                &[("IN1", &["1"]), ("IN2", &["2"])],
                &["OUT"],
                "",
            ),
            out_var(4, "q", &["3:OUT"], 10, ""),
        ],
    ));
    let request = TraceRequest {
        cycles: 3,
        stimulus: Some("cycle,d\n0,2\n1,0\n"),
        trace: Some("q"),
        changes_only: false,
    };
    let (csv, outcome) = run_csv(&[("t.xml", text.as_str())], &request);
    assert_eq!(column(&csv, "q"), ["5"]);
    let fault = outcome
        .expect_err("division by zero in cycle 1")
        .to_string();
    // The fault is at the block's typeName, in P.
    let at = location_of(&text, "DIV\"");
    assert!(
        fault.contains(&at) && fault.contains('P'),
        "{fault} (expected {at})"
    );
}

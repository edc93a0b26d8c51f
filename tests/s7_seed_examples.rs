//! The three worked examples of the S7-200 "table method" seed
//! (`programs/s7_table_example{1,2,3}.awl`, see docs/programs.md).
//!
//! - The committed `programs/s7_table_example*.expected.csv` are the output of
//!   the independent GRAFCET models in `support/s7_table_models.rs` (no
//!   plcrun inside) on the committed stimuli; the models are also checked
//!   against changes worked out by hand (steps, outputs, the forcing tables
//!   `Tf1`/`Tf0` and the freezing byte `VB0`), and the stimuli against the
//!   GRAFCETs (every transition fires).
//! - plcrun runs each `.awl` listing with its stimulus; its values must equal
//!   the model's, cycle by cycle, and its CSV text the committed file.
//!
//! Regenerate the expected files (after checking a change by hand!) with
//! `PLCRUN_BLESS_MODELS=1 cargo test --test suite s7_seed_examples::`.

use crate::support;

use std::collections::BTreeSet;
use support::library::{TraceRequest, check_rendered, repo_files, run_csv};
use support::s7_table_models::{Run, example1, example2, example3};
use support::trace_text::{check_or_bless, read_repo_file};

/// One worked example: its files, its number of cycles and its model.
struct Example {
    name: &'static str,
    cycles: u64,
    model: fn(&str, u64) -> Run,
}

const EXAMPLES: [Example; 3] = [
    Example {
        name: "s7_table_example1",
        cycles: 40,
        model: example1::run,
    },
    Example {
        name: "s7_table_example2",
        cycles: 560,
        model: example2::run,
    },
    Example {
        name: "s7_table_example3",
        cycles: 140,
        model: example3::run,
    },
];

fn model_run(example: &Example) -> Run {
    let stimulus = read_repo_file(&format!("programs/{}.csv", example.name));
    (example.model)(&stimulus, example.cycles)
}

#[test]
fn committed_expected_traces_match_the_models() {
    for example in &EXAMPLES {
        let run = model_run(example);
        check_or_bless(
            &format!("programs/{}.expected.csv", example.name),
            &run.csv(),
        );
    }
}

/// The changes of the named columns only, as `(cycle, "NAME=value ...")`.
fn changes_of(run: &Run, columns: &[&str]) -> Vec<(usize, String)> {
    run.changes()
        .into_iter()
        .filter_map(|(cycle, text)| {
            let kept: Vec<&str> = text
                .split(' ')
                .filter(|part| columns.iter().any(|c| part.split('=').next() == Some(*c)))
                .collect();
            (!kept.is_empty()).then(|| (cycle, kept.join(" ")))
        })
        .collect()
}

fn assert_changes(run: &Run, columns: &[&str], by_hand: &[(usize, &str)]) {
    let model = changes_of(run, columns);
    let by_hand: Vec<(usize, String)> = by_hand.iter().map(|(c, t)| (*c, t.to_string())).collect();
    for (k, (m, h)) in model.iter().zip(&by_hand).enumerate() {
        assert_eq!(m, h, "change #{k}: model vs by hand");
    }
    assert_eq!(model.len(), by_hand.len(), "number of changes: {model:?}");
}

/// Example 1, worked out by hand from the GRAFCET of the listing's SBR 4 and
/// the receptivities of SBR 3 (t0 = t2 = t3 = a demand, t1 = a sensor and no
/// demand, t4 = t7 = no demand, t5 = a demand, t6 = 1).
#[test]
fn example1_model_agrees_with_the_hand_derivation() {
    let run = model_run(&EXAMPLES[0]);
    let steps = ["V20.0", "V20.1", "V20.2", "V20.3", "V20.4", "V20.5"];
    assert_changes(
        &run,
        &steps,
        &[
            (0, "V20.0=TRUE"),
            // p1 pressed: t0 and t2 fire together (rule 4)
            (5, "V20.0=FALSE V20.1=TRUE V20.3=TRUE"),
            // held: t3 brings X0 back, t0/t2 take it again next scan
            (6, "V20.0=TRUE V20.3=FALSE"),
            (7, "V20.0=FALSE V20.3=TRUE"),
            (8, "V20.0=TRUE V20.3=FALSE"),
            (9, "V20.0=FALSE V20.3=TRUE"),
            // released on sensor b2: t1; then t4 (no demand)
            (10, "V20.1=FALSE V20.2=TRUE"),
            (11, "V20.0=TRUE V20.2=FALSE"),
            // p0 in {X0, X3}: X0 and X3 deactivated and activated -> stay (rule 5)
            (15, "V20.1=TRUE"),
            (20, "V20.1=FALSE V20.2=TRUE"),
            // p3: t5 from X2 with t0, t2, t3
            (21, "V20.1=TRUE V20.2=FALSE V20.4=TRUE"),
            (22, "V20.4=FALSE V20.5=TRUE"),
            (23, "V20.5=FALSE"),
            (25, "V20.1=FALSE V20.2=TRUE"),
            (26, "V20.2=FALSE"),
            (30, "V20.1=TRUE"),
            (34, "V20.1=FALSE V20.2=TRUE"),
            (35, "V20.2=FALSE"),
        ],
    );
    assert_changes(
        &run,
        &["VB100", "VB102", "VB104"],
        &[
            (5, "VB100=16#2"),
            (10, "VB100=16#0 VB102=16#4 VB104=16#4"),
            (11, "VB104=16#0"),
            (15, "VB100=16#1 VB102=16#0"),
            (20, "VB100=16#0 VB102=16#4 VB104=16#4"),
            (21, "VB100=16#8 VB102=16#0 VB104=16#0"),
            (23, "VB100=16#0"),
            (25, "VB102=16#2 VB104=16#2"),
            (26, "VB104=16#0"),
            // p1 and p2 together: p1 wins; then p2 alone
            (30, "VB100=16#2 VB102=16#0"),
            (32, "VB100=16#4"),
            (34, "VB100=16#0 VB102=16#2 VB104=16#2"),
            (35, "VB104=16#0"),
        ],
    );
}

/// Example 2 by hand: dcy held at power-on is no edge; X1 forces G1 to
/// {X10}; the G1 cycle h1, v1, h0, 5 s; au freezes G1 (h1 is then ignored);
/// leaving X3 forces G1 to 0; dcy again, and h1 (still held) acts at once.
#[test]
fn example2_model_agrees_with_the_hand_derivation() {
    let run = model_run(&EXAMPLES[1]);
    let steps = [
        "V20.0", "V20.1", "V20.2", "V20.3", "V21.0", "V21.1", "V21.2", "V21.3", "VB0",
    ];
    assert_changes(
        &run,
        &steps,
        &[
            (0, "V20.0=TRUE VB0=16#FF"),
            (5, "V20.0=FALSE V20.1=TRUE V21.0=TRUE"),
            (6, "V20.1=FALSE V20.2=TRUE"),
            (10, "V21.0=FALSE V21.1=TRUE"),
            (15, "V21.1=FALSE V21.2=TRUE"),
            (20, "V21.2=FALSE V21.3=TRUE"),
            // T37 started in scan 20 (200 ms), done in scan 520 (5200 ms)
            (521, "V21.0=TRUE V21.3=FALSE"),
            (530, "V20.2=FALSE V20.3=TRUE VB0=16#FD"),
            (540, "V20.0=TRUE V20.3=FALSE V21.0=FALSE VB0=16#FF"),
            (550, "V20.0=FALSE V20.1=TRUE V21.0=TRUE"),
            (551, "V20.1=FALSE V20.2=TRUE V21.0=FALSE V21.1=TRUE"),
        ],
    );
    assert_changes(
        &run,
        &["VB61", "VB71"],
        &[
            (0, "VB71=16#F"),
            (5, "VB61=16#1"),
            (6, "VB61=16#0 VB71=16#0"),
            (540, "VB71=16#F"),
            (550, "VB61=16#1"),
            (551, "VB61=16#0 VB71=16#0"),
        ],
    );
}

/// Example 3 by hand: see the scenario in docs/programs.md.
#[test]
fn example3_model_agrees_with_the_hand_derivation() {
    let run = model_run(&EXAMPLES[2]);
    assert_changes(
        &run,
        &["VB20", "VB21", "VB22", "VB23", "VB0"],
        &[
            (0, "VB20=16#1 VB0=16#FF"),
            (5, "VB20=16#2 VB21=16#1"),
            (6, "VB20=16#4"),
            (10, "VB21=16#2 VB22=16#1"),
            (11, "VB21=16#4"),
            (15, "VB22=16#2"),
            (20, "VB22=16#4"),
            (25, "VB22=16#8"),
            // T33 (10 ms, K30) started in scan 25, done in scan 55
            (56, "VB22=16#1"),
            (60, "VB21=16#1 VB22=16#0"),
            (65, "VB21=16#2 VB22=16#1"),
            (66, "VB21=16#4"),
            (70, "VB20=16#8 VB0=16#F1"),
            (78, "VB20=16#1 VB21=16#0 VB22=16#0 VB0=16#FF"),
            (85, "VB20=16#2 VB21=16#1"),
            (86, "VB20=16#4"),
            (90, "VB21=16#8 VB23=16#1"),
            (91, "VB21=16#10"),
            (95, "VB23=16#2"),
            (102, "VB23=16#1"),
            (105, "VB23=16#4"),
            (115, "VB23=16#1"),
            (120, "VB21=16#1 VB23=16#0"),
            // T10 and T13 together (rule 4), each forcing its graph
            (125, "VB21=16#A VB22=16#1 VB23=16#1"),
            (126, "VB21=16#14"),
            (127, "VB21=16#11 VB22=16#0 VB23=16#0"),
            (128, "VB21=16#18 VB23=16#1"),
            (129, "VB21=16#10"),
            (130, "VB20=16#8 VB0=16#F1"),
            (135, "VB20=16#1 VB21=16#0 VB23=16#0 VB0=16#FF"),
        ],
    );
    assert_changes(
        &run,
        &["Q0.0", "Q0.1", "Q0.2", "Q0.3"],
        &[
            (10, "Q0.2=TRUE"),
            (15, "Q0.2=FALSE"),
            (20, "Q0.0=TRUE Q0.1=TRUE"),
            (25, "Q0.0=FALSE Q0.1=FALSE Q0.3=TRUE"),
            (27, "Q0.3=FALSE"),
            (56, "Q0.2=TRUE"),
            (60, "Q0.2=FALSE"),
            (65, "Q0.2=TRUE"),
            (78, "Q0.2=FALSE"),
            (97, "Q0.2=TRUE"),
            (98, "Q0.2=FALSE"),
            (99, "Q0.1=TRUE"),
            (100, "Q0.1=FALSE"),
            // step 32: V+ set by a, kept, reset by b
            (107, "Q0.0=TRUE"),
            (112, "Q0.0=FALSE"),
            (125, "Q0.2=TRUE"),
            (127, "Q0.2=FALSE"),
        ],
    );
}

/// The stimuli exercise the GRAFCETs fully: every transition fires at
/// least once.
#[test]
fn stimuli_fire_every_transition() {
    let all: [&[&str]; 3] = [
        &["t0", "t1", "t2", "t3", "t4", "t5", "t6", "t7"],
        &["T0", "T1", "T2", "T3", "T10", "T11", "T12", "T13"],
        &[
            "T0", "T1", "T2", "T3", "T10", "T11", "T12", "T13", "T14", "T15", "T20", "T21", "T22",
            "T23", "T30", "T31", "T32", "T33",
        ],
    ];
    for (example, names) in EXAMPLES.iter().zip(all) {
        let run = model_run(example);
        let fired: BTreeSet<&str> = run.fired.iter().map(|(_, n)| *n).collect();
        for name in names {
            assert!(fired.contains(name), "{}: {name} never fires", example.name);
        }
    }
}

/// A traced value as a number: BOOL literals as 0/1, `16#..` and decimal
/// integers as themselves (so that BOOL/BYTE display choices of the
/// front-end do not matter, only the values).
fn numeric(text: &str) -> Option<u64> {
    match text {
        "TRUE" => Some(1),
        "FALSE" => Some(0),
        _ => match text.strip_prefix("16#") {
            Some(hex) => u64::from_str_radix(&hex.replace('_', ""), 16).ok(),
            None => text.parse().ok(),
        },
    }
}

/// The model's last five changes up to `cycle`, for a failure message.
fn last_changes(model: &Run, cycle: usize) -> Vec<(usize, String)> {
    let mut changes: Vec<_> = model
        .changes()
        .into_iter()
        .filter(|(c, _)| *c <= cycle)
        .collect();
    let keep = changes.len().saturating_sub(5);
    changes.drain(..keep);
    changes
}

/// Runs the `.awl` listing in plcrun and compares its trace with the
/// model's, value by value, naming the first difference.
fn plcrun_matches_model(example: &Example) {
    let source = format!("programs/{}.awl", example.name);
    let stimulus = read_repo_file(&format!("programs/{}.csv", example.name));
    let model = model_run(example);
    let names = model.names.join(",");
    let request = TraceRequest {
        cycles: example.cycles,
        stimulus: Some(&stimulus),
        trace: Some(&names),
        changes_only: false,
    };
    let (csv, outcome) = run_csv(&repo_files(&[&source]), &request);
    if let Err(e) = outcome {
        panic!("{source}: the run stopped: {e}");
    }
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    for name in &model.names {
        assert!(
            header.contains(name),
            "{source}: no column {name} in {header:?}"
        );
    }
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), model.rows.len(), "{source}: number of cycles");
    for (cycle, (got, want)) in rows.iter().zip(&model.rows).enumerate() {
        for (name, expected) in model.names.iter().zip(want) {
            let column = header
                .iter()
                .position(|h| h == name)
                .expect("checked above");
            let actual = got.get(column).copied().unwrap_or("");
            assert_eq!(
                numeric(actual),
                numeric(expected),
                "{source}: first difference at cycle {cycle}, {name}: plcrun {actual}, model \
                 {expected}\n(the model's last changes up to there: {:?})",
                last_changes(&model, cycle)
            );
        }
    }
}

#[test]
fn plcrun_runs_example1_as_its_model() {
    plcrun_matches_model(&EXAMPLES[0]);
}

#[test]
fn plcrun_runs_example2_as_its_model() {
    plcrun_matches_model(&EXAMPLES[1]);
}

#[test]
fn plcrun_runs_example3_as_its_model() {
    plcrun_matches_model(&EXAMPLES[2]);
}

/// plcrun's CSV trace of each example is the committed expected file byte
/// for byte (the command of docs/programs.md, through the library), and
/// `plcrun check` has nothing to say about the three listings.
#[test]
fn plcrun_prints_the_committed_expected_traces() {
    for example in &EXAMPLES {
        let source = format!("programs/{}.awl", example.name);
        let files = repo_files(&[&source]);
        let named: Vec<(&str, &str)> = files
            .iter()
            .map(|(n, t)| (n.as_str(), t.as_str()))
            .collect();
        let (clean, rendered) = check_rendered(&named);
        assert!(clean && rendered.is_empty(), "{source}: {rendered}");
        let expected_file = format!("programs/{}.expected.csv", example.name);
        let expected = read_repo_file(&expected_file);
        let names = expected
            .lines()
            .next()
            .and_then(|h| h.strip_prefix("cycle,time,"))
            .expect("an expected trace has a header");
        let stimulus = read_repo_file(&format!("programs/{}.csv", example.name));
        let request = TraceRequest {
            cycles: example.cycles,
            stimulus: Some(&stimulus),
            trace: Some(names),
            changes_only: false,
        };
        let (csv, outcome) = run_csv(&files, &request);
        assert!(outcome.is_ok(), "{source}: {outcome:?}");
        let first = csv.lines().zip(expected.lines()).position(|(a, e)| a != e);
        if let Some(i) = first {
            panic!(
                "{source}: line {} differs from {expected_file}:\n  plcrun:   {}\n  expected: {}",
                i + 1,
                csv.lines().nth(i).unwrap_or(""),
                expected.lines().nth(i).unwrap_or("")
            );
        }
        assert_eq!(
            csv.lines().count(),
            expected.lines().count(),
            "{source}: line count"
        );
    }
}

//! `plcrun compare` on the command line: argument order, exit statuses,
//! the counterexample file replayed by a plain run, identical output on
//! any number of jobs, usage errors.

use crate::support::cli;

use cli::{plcrun, temp_file};

const ALG: [&str; 3] = ["programs/alg01.il", "--", "programs/alg02.il"];

fn compare(args: &[&str]) -> (i32, String, String) {
    let mut all = vec!["compare"];
    all.extend_from_slice(args);
    plcrun(&all)
}

#[test]
fn equivalent_exits_0_and_different_exits_1() {
    let (code, out, err) = compare(&[
        "programs/transfer_station.sfc",
        "--",
        "programs/transfer_station.il",
        "--cycles",
        "1000",
        "--random",
        "1",
        "--seeds",
        "4",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("verdict: EQUIVALENT on all 4 seeds"), "{out}");
    let (code, out, err) = compare(&[ALG[0], ALG[1], ALG[2], "--cycles", "2000", "--random", "1"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        out.contains("verdict: DIFFERENT (1 of 1 seeds differ; first: seed 1)"),
        "{out}"
    );
    assert!(out.contains("shrunk counterexample:"), "{out}");
}

#[test]
fn options_may_come_before_a_or_after_b() {
    let before = compare(&["--cycles", "800", "--random", "3", ALG[0], ALG[1], ALG[2]]);
    let after = compare(&[ALG[0], ALG[1], ALG[2], "--cycles", "800", "--random", "3"]);
    assert_eq!(before, after);
    assert_eq!(before.0, 1, "{}", before.2);
}

/// The value of column `name` at trace row `cycle` of a CSV trace.
fn trace_value(csv: &str, name: &str, cycle: u64) -> String {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == name).unwrap();
    let row = lines.nth(cycle as usize).unwrap();
    row.split(',').nth(col).unwrap().to_string()
}

#[test]
fn the_counterexample_replays_in_a_plain_run_of_each_program() {
    let file = temp_file("cx.csv", "");
    let (code, out, err) = compare(&[
        ALG[0],
        ALG[1],
        ALG[2],
        "--cycles",
        "3000",
        "--random",
        "1",
        "--seeds",
        "8",
        "--lag",
        "1",
        "--counterexample",
        &file,
    ]);
    assert_eq!(code, 1, "{err}");
    // "  difference at cycle N:" then "    NAME: A = X, B = Y  (...)".
    let tail = out.split("  difference at cycle ").nth(1).expect(&out);
    let cycle: u64 = tail.split(':').next().unwrap().parse().unwrap();
    let line = tail.lines().nth(1).unwrap().trim();
    let (name, rest) = line.split_once(": A = ").unwrap();
    let (a_value, rest) = rest.split_once(", B = ").unwrap();
    let b_value = rest.split_whitespace().next().unwrap();
    let csv = std::fs::read_to_string(&file).unwrap();
    assert!(csv.contains("# plcrun compare counterexample"), "{csv}");
    let cycles = (cycle + 1).to_string();
    for (program, want) in [
        ("programs/alg01.il", a_value),
        ("programs/alg02.il", b_value),
    ] {
        let (code, trace, err) = plcrun(&[program, "--stimulus", &file, "--cycles", &cycles]);
        assert_eq!(code, 0, "{err}");
        assert_eq!(trace_value(&trace, name, cycle), want, "{program}");
    }
    // The replayed A and B traces really differ where compare says.
    let replay = |p: &str| plcrun(&[p, "--stimulus", &file, "--cycles", &cycles]).1;
    assert_ne!(replay("programs/alg01.il"), replay("programs/alg02.il"));
    // compare reads its own counterexample back.
    let (code, again, _) = compare(&[
        ALG[0],
        ALG[1],
        ALG[2],
        "--cycles",
        &cycles,
        "--stimulus",
        &file,
        "--lag",
        "1",
    ]);
    assert_eq!(code, 1);
    assert!(
        again.contains(&format!("first difference: cycle {cycle}\n")),
        "{again}"
    );
}

#[test]
fn the_report_is_the_same_on_one_or_two_jobs() {
    let run = |jobs: &str| {
        compare(&[
            "programs/graf1_sfc.sfc",
            "--",
            "programs/graf1_async.st",
            "--cycles",
            "1000",
            "--random",
            "10",
            "--seeds",
            "6",
            "--jobs",
            jobs,
        ])
    };
    let one = run("1");
    assert_eq!(one.0, 1, "{}", one.2);
    assert_eq!(one, run("2"));
}

#[test]
fn a_stimulus_file_drives_both_programs() {
    // The seed's own scenario: ALG02 is one cycle behind ALG01 there.
    let stim = ["--cycles", "700", "--stimulus", "programs/alg01_s1.csv"];
    let mut args = ALG.to_vec();
    args.extend_from_slice(&stim);
    let (code, out, err) = compare(&args);
    assert_eq!(code, 1, "{err}");
    assert!(
        out.contains("stimulus: programs/alg01_s1.csv, 700 cycles"),
        "{out}"
    );
    assert!(out.contains("first difference: cycle 530\n"), "{out}");
    args.extend_from_slice(&["--lag", "1"]);
    let (code, out, err) = compare(&args);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("verdict: EQUIVALENT on this stimulus"),
        "{out}"
    );
}

#[test]
fn usage_errors_exit_2_with_a_clear_message() {
    let cases: [(&[&str], &str); 6] = [
        (
            &["--cycles", "10", "--random", "1", "--map", "A.nope=B.V1"],
            "error: `nope` is not a variable of program A",
        ),
        (
            &["--cycles", "10"],
            "error: give the stimulus: --stimulus FILE, or --random SEED",
        ),
        (
            &["--cycles", "10", "--random", "1", "--ignore", "Q9"],
            "error: --ignore Q9: not an input or compared output of either program",
        ),
        (
            &["--cycles", "10", "--random", "1", "--max-hold", "0"],
            "error: --max-hold (0) must not be below --min-hold (1)",
        ),
        (
            &["--cycles", "10", "--random", "1", "--map", "V1"],
            "error: --map `V1`: expected A_NAME=B_NAME",
        ),
        (
            &["--cycles", "10", "--stimulus", "programs/chariot.csv"],
            "is not an input both programs read",
        ),
    ];
    for (extra, message) in cases {
        let mut args = ALG.to_vec();
        args.extend_from_slice(extra);
        let (code, _, err) = compare(&args);
        assert_eq!(code, 2, "{extra:?}: {err}");
        assert!(err.contains(message), "{extra:?}: {err}");
    }
    let other = temp_file(
        "o.st",
        "PROGRAM O VAR_INPUT go : BOOL; END_VAR VAR_OUTPUT V1 : BOOL; END_VAR V1 := go; END_PROGRAM",
    );
    let (code, _, err) = compare(&[
        "programs/alg01.il",
        "--",
        &other,
        "--cycles",
        "5",
        "--random",
        "1",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("error: the programs have no common input (A reads SW1, S1, S2; B reads go)"),
        "{err}"
    );
    let broken = temp_file(
        "b.st",
        "PROGRAM B VAR_OUTPUT V1 : BOOL; END_VAR V1 := nope; END_PROGRAM",
    );
    let (code, _, err) = compare(&[
        "programs/alg01.il",
        "--",
        &broken,
        "--cycles",
        "5",
        "--random",
        "1",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("program B") && err.contains("does not compile"),
        "{err}"
    );
    // B's files are required.
    let (code, _, _) = compare(&["programs/alg01.il", "--cycles", "5", "--random", "1"]);
    assert_eq!(code, 2);
}

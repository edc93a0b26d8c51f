//! The repairs of docs/programs.md ("S7-200 table method") that change what
//! a listing does, undone one at a time: each listing as printed shows the
//! failure the documentation gives as the reason for the repair. (The
//! repaired listings are checked against their models in
//! `s7_seed_examples.rs`.)

use crate::support;

use support::library::{TraceRequest, csv_trace, repo_text};

/// `text` with `from` replaced by `to`, which must occur exactly once.
fn undo(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "`{from}` must occur once");
    text.replacen(from, to, 1)
}

/// Runs `source` (as the file `name`) with example `n`'s stimulus for
/// `cycles` cycles and returns, per cycle, the values of `trace`.
fn run(n: u32, source: &str, cycles: u64, trace: &str) -> Vec<Vec<String>> {
    let stimulus = repo_text(&format!("programs/s7_table_example{n}.csv"));
    let name = format!("programs/s7_table_example{n}_as_printed.awl");
    let request = TraceRequest {
        cycles,
        stimulus: Some(&stimulus),
        trace: Some(trace),
        changes_only: false,
    };
    csv_trace(&[(name, source.to_string())], &request)
        .lines()
        .skip(1)
        .map(|l| l.split(',').skip(2).map(str::to_string).collect())
        .collect()
}

fn example(n: u32) -> String {
    repo_text(&format!("programs/s7_table_example{n}.awl"))
}

#[test]
fn example1_without_unfreezing_never_leaves_step_0() {
    let printed = undo(
        &example(1),
        "NETWORK // Defigeage des graphes (mise a 1 de tous les bits\nLD SM0.0\nFILL KHFFFF VW0 K1\n",
        "",
    );
    for (cycle, row) in run(1, &printed, 40, "VB20,VB0").iter().enumerate() {
        assert_eq!(row, &["16#1", "16#0"], "cycle {cycle}");
    }
}

#[test]
fn example2_forcing_its_own_graph_kills_it_in_the_first_scan() {
    let printed = undo(
        &undo(
            &undo(
                &example(2),
                "S V71.0 K4 // repair: printed \"V70.0\" (G0 would force itself to 0)",
                "S V70.0 K4",
            ),
            "S V71.0 K4 // repair: printed \"V70.0\"\n",
            "S V70.0 K4\n",
        ),
        "S V61.0 K1 // repair: printed \"V60.0\"",
        "S V60.0 K1",
    );
    for (cycle, row) in run(2, &printed, 560, "VB20,VB21").iter().enumerate() {
        assert_eq!(row, &["16#0", "16#0"], "cycle {cycle}");
    }
}

#[test]
fn example3_without_ld_before_the_ts_update_does_not_evolve() {
    let text = example(3);
    let network64 = text.find("NETWORK64").expect("NETWORK64");
    let ld = network64 + text[network64..].find("LD SM0.0\n").expect("its LD");
    let printed = format!("{}{}", &text[..ld], &text[ld + "LD SM0.0\n".len()..]);
    for (cycle, row) in run(3, &printed, 140, "VB20,VB21").iter().enumerate() {
        assert_eq!(row, &["16#1", "16#0"], "cycle {cycle}");
    }
}

#[test]
fn example3_with_a_conditional_jump_cannot_latch_v_plus_in_step_32() {
    let printed = undo(&example(3), "LD SM0.0\nJMP K11", "JMP K11");
    let rows = run(3, &printed, 140, "VB23,Q0.0");
    // Step 32 is active from 105 to 114 and a is pressed at 107.
    for (cycle, row) in rows.iter().enumerate().take(115).skip(105) {
        assert_eq!(row, &["16#4", "FALSE"], "cycle {cycle}");
    }
}

#[test]
fn example3_timing_step_22_locks_gauto_in_step_23() {
    let printed = undo(
        &example(3),
        "LD V22.3 // repair: printed \"V22.2\"; T23 (X23 -> X20) waits for T33",
        "LD V22.2",
    );
    let rows = run(3, &printed, 140, "VB22");
    // Step 23 from scan 25 until X10 forces Gauto to 0 in scan 60 (the
    // repaired listing is back in step 20 at 56).
    for (cycle, row) in rows.iter().enumerate().take(60).skip(25) {
        assert_eq!(row, &["16#8"], "cycle {cycle}");
    }
}

#[test]
fn example3_t13_setting_ts_leaves_step_10_active() {
    let printed = undo(
        &example(3),
        "S V51.0 K1 // repair: printed \"S V21.0 K1\" (Td of X10 is V51.0)",
        "S V21.0 K1",
    );
    let rows = run(3, &printed, 140, "VB21");
    // manu at 90: T13 fires; X10 and X13 are both active (16#9), where the
    // repaired listing has X13 alone (16#8).
    assert_eq!(rows[90], ["16#9"]);
}

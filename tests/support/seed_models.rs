//! Independent models of the ST seed programs `programs/comparator.st` and
//! `programs/cmd_monitor.st`. Nothing here uses the plcrun engine.
#![allow(dead_code)]

use super::grafcet_models::{Sr, Ton};
use super::trace_text::{CYCLE_MS, Stimulus, bool_lit, parse_bool, parse_time_ms, trace_csv};

/// Cycles of the comparator trace: one per (A, B) pair.
pub const COMPARATOR_CYCLES: u64 = 256;

/// The comparator's expected trace from plain integer arithmetic: cycle k
/// tests A = k MOD 16, B = k / 16; Sup = A > B, Inf = A < B, Egal = A = B.
/// The program's outputs, in declaration order, are A, B, Sup, Inf, Egal.
pub fn comparator_expected_csv() -> String {
    let rows: Vec<Vec<String>> = (0..COMPARATOR_CYCLES)
        .map(|k| {
            let (a, b) = (k % 16, k / 16);
            vec![
                a.to_string(),
                b.to_string(),
                bool_lit(a > b).to_string(),
                bool_lit(a < b).to_string(),
                bool_lit(a == b).to_string(),
            ]
        })
        .collect();
    trace_csv(&["A", "B", "Sup", "Inf", "Egal"], &rows)
}

/// Cycles of the CMD_MONITOR scenario.
pub const CMD_MONITOR_CYCLES: u64 = 125;

/// The CMD_MONITOR test program: the FB's four statements on plain variables.
#[derive(Debug, Default)]
pub struct CmdMonitor {
    pub auto_cmd: bool,
    pub auto_mode: bool,
    pub man_cmd: bool,
    pub man_cmd_chk: bool,
    pub t_cmd_max_ms: u64,
    pub fdbk: bool,
    pub ack: bool,
    pub cmd: bool,
    pub alrm: bool,
    tmr: Ton,
    ff: Sr,
}

impl CmdMonitor {
    pub fn new() -> Self {
        // T_CMD_MAX : TIME := T#500ms in the test program.
        CmdMonitor {
            t_cmd_max_ms: 500,
            ..Default::default()
        }
    }

    fn set(&mut self, name: &str, value: &str) {
        match name.to_ascii_uppercase().as_str() {
            "AUTO_CMD" => self.auto_cmd = parse_bool(value),
            "AUTO_MODE" => self.auto_mode = parse_bool(value),
            "MAN_CMD" => self.man_cmd = parse_bool(value),
            "MAN_CMD_CHK" => self.man_cmd_chk = parse_bool(value),
            "FDBK" => self.fdbk = parse_bool(value),
            "ACK" => self.ack = parse_bool(value),
            "T_CMD_MAX" => self.t_cmd_max_ms = parse_time_ms(value),
            other => panic!("CMD_MONITOR_TEST has no variable {other}"),
        }
    }

    pub fn scan(&mut self, now_ms: u64) {
        self.cmd = (self.auto_cmd && self.auto_mode)
            || (self.man_cmd && !self.man_cmd_chk && !self.auto_mode);
        self.tmr.call(now_ms, self.cmd, self.t_cmd_max_ms);
        self.ff.call(self.tmr.q && !self.fdbk, self.ack);
        self.alrm = self.ff.q1;
    }
}

/// Runs the CMD_MONITOR test program on the stimulus; rows are (CMD, ALRM).
pub fn cmd_monitor_run(stimulus_text: &str) -> Vec<Vec<bool>> {
    let stimulus = Stimulus::parse(stimulus_text);
    let mut next = 0;
    let mut m = CmdMonitor::new();
    (0..CMD_MONITOR_CYCLES)
        .map(|k| {
            for (name, value) in stimulus.due(k, &mut next) {
                m.set(&name, &value);
            }
            m.scan(k * CYCLE_MS);
            vec![m.cmd, m.alrm]
        })
        .collect()
}

/// The expected default trace (the program's outputs CMD, ALRM).
pub fn cmd_monitor_expected_csv(stimulus_text: &str) -> String {
    let rows: Vec<Vec<String>> = cmd_monitor_run(stimulus_text)
        .into_iter()
        .map(|r| r.into_iter().map(|b| bool_lit(b).to_string()).collect())
        .collect();
    trace_csv(&["CMD", "ALRM"], &rows)
}

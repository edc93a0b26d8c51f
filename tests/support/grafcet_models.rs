//! Independent models of the seed programs ALG01 and ALG02
//! (`programs/alg01.il`, `programs/alg02.il`).
//!
//! Each model is the IL listing transcribed rung by rung, in program order,
//! as plain boolean equations on plain Rust variables:
//! - `LD a / AND b / ANDN c / OR d / ST x` is `x := ((a && b) && !c) || d`,
//!   evaluated left to right exactly as the accumulator would;
//! - `OR ( a AND b )` ORs the parenthesised sub-expression into the CR;
//! - `CAL T1( IN := M23, PT := DT1 | QT1 := Q, := ET )` calls the TON and
//!   then copies its Q into QT1 (the empty destination for ET is ignored);
//! - `CAL SR0( SET1 := APM0, RESET := M1 | M0 := Q1 )` computes the
//!   set-dominant flip-flop `Q1 := SET1 OR (NOT RESET AND Q1)` and copies Q1
//!   into M0.
//!
//! The TON is the rule of the execution semantics (docs/semantics.md §4): on
//! a call with IN TRUE after a call with IN FALSE (or the first call) it
//! records start := now; while IN is TRUE, ET := min(now - start, PT) and
//! Q := ET >= PT; when IN is FALSE, Q := FALSE and ET := 0. "now" is the
//! cycle's virtual clock value, `cycle × 10 ms`.
//!
//! Nothing here uses the plcrun engine.
#![allow(dead_code)]

use super::trace_text::{CYCLE_MS, Stimulus, bool_lit, parse_bool, trace_csv};

/// The variables traced by the committed ALG01/ALG02 expected files, in the
/// order of `--trace M0,M1,M2,M3,M4,V1,V2,L1`.
pub const TRACED: [&str; 8] = ["M0", "M1", "M2", "M3", "M4", "V1", "V2", "L1"];

/// Number of cycles of every committed ALG01/ALG02 scenario (`--cycles 1200`).
pub const CYCLES: u64 = 1200;

/// The on-delay timer of the standard library, on a millisecond clock.
#[derive(Debug, Default, Clone)]
pub struct Ton {
    prev_in: bool,
    start_ms: u64,
    pub q: bool,
    pub et_ms: u64,
}

impl Ton {
    pub fn call(&mut self, now_ms: u64, input: bool, pt_ms: u64) {
        if input {
            if !self.prev_in {
                self.start_ms = now_ms;
            }
            self.et_ms = (now_ms - self.start_ms).min(pt_ms);
            self.q = self.et_ms >= pt_ms;
        } else {
            self.q = false;
            self.et_ms = 0;
        }
        self.prev_in = input;
    }
}

/// The set-dominant flip-flop: `Q1 := S1 OR (NOT R AND Q1)`.
#[derive(Debug, Default, Clone)]
pub struct Sr {
    pub q1: bool,
}

impl Sr {
    pub fn call(&mut self, set1: bool, reset: bool) {
        self.q1 = set1 || (!reset && self.q1);
    }
}

/// The inputs of both programs.
#[derive(Debug, Default, Clone, Copy)]
pub struct Inputs {
    pub sw1: bool,
    pub s1: bool,
    pub s2: bool,
}

impl Inputs {
    fn set(&mut self, name: &str, value: &str) {
        let v = parse_bool(value);
        match name.to_ascii_uppercase().as_str() {
            "SW1" => self.sw1 = v,
            "S1" => self.s1 = v,
            "S2" => self.s2 = v,
            other => panic!("ALG01/ALG02 have no input {other}"),
        }
    }
}

/// DT1 and DT2 of both listings: `T#5S`.
const DT_MS: u64 = 5_000;

/// The variables of ALG01 (all BOOLs start FALSE).
#[derive(Debug, Default, Clone)]
pub struct Alg01 {
    pub m: [bool; 5],
    pub m23: bool,
    pub qt1: bool,
    pub qt2: bool,
    pub v1: bool,
    pub v2: bool,
    pub l1: bool,
    pub t1: Ton,
    pub t2: Ton,
}

impl Alg01 {
    /// One execution of the program body, rung by rung.
    pub fn scan(&mut self, i: Inputs, now_ms: u64) {
        let [m0, m1, m2, m3, m4] = &mut self.m;
        // Etape 0: LDN M1 ANDN M2 ANDN M3 ANDN M4 OR ( M4 AND QT2 ) ST M0
        *m0 = (!*m1 && !*m2 && !*m3 && !*m4) || (*m4 && self.qt2);
        // Etape 1: LD M0 AND SW1 OR M1 ANDN M2 ANDN M3 ST M1
        *m1 = ((*m0 && i.sw1) || *m1) && !*m2 && !*m3;
        // Etape 2: LD M1 AND S1 ANDN S2 OR M2 ANDN M4 ST M2
        *m2 = ((*m1 && i.s1 && !i.s2) || *m2) && !*m4;
        // Etape 3: LD M1 AND S2 ANDN S1 OR (M3 ) ANDN M4 ST M3
        *m3 = ((*m1 && i.s2 && !i.s1) || *m3) && !*m4;
        // LD M2 OR M3 ST M23
        self.m23 = *m2 || *m3;
        // CAL T1( IN := M23, PT := DT1 | QT1 := Q, := ET )
        self.t1.call(now_ms, self.m23, DT_MS);
        self.qt1 = self.t1.q;
        // Etape 4: LD M23 AND QT1 OR M4 ANDN M0 ST M4
        *m4 = ((self.m23 && self.qt1) || *m4) && !*m0;
        // CAL T2( IN := M4, PT := DT2 | QT2 := Q, := ET )
        self.t2.call(now_ms, *m4, DT_MS);
        self.qt2 = self.t2.q;
        // Actions: V1, V2, L1
        self.v1 = (*m2 || self.v1) && !*m4;
        self.v2 = (*m3 || self.v2) && !*m4;
        self.l1 = (*m1 || self.l1) && !self.m23;
    }
}

/// The variables of ALG02 (all BOOLs start FALSE, SR outputs too).
#[derive(Debug, Default, Clone)]
pub struct Alg02 {
    pub m: [bool; 5],
    pub apm: [bool; 5],
    pub sr: [Sr; 5],
    pub m23: bool,
    pub qt1: bool,
    pub qt2: bool,
    pub v1: bool,
    pub v2: bool,
    pub l1: bool,
    pub t1: Ton,
    pub t2: Ton,
}

impl Alg02 {
    /// One execution of the program body, rung by rung.
    pub fn scan(&mut self, i: Inputs, now_ms: u64) {
        // Initialisation étape M0:
        // LDN M1 ANDN M2 ANDN M3 ANDN M4 OR ( M4 AND QT2 ) ST APM0
        let m = &mut self.m;
        self.apm[0] = (!m[1] && !m[2] && !m[3] && !m[4]) || (m[4] && self.qt2);
        // CAL SR0( SET1 := APM0, RESET := M1 | M0 := Q1 )
        self.sr[0].call(self.apm[0], m[1]);
        m[0] = self.sr[0].q1;
        // LD M0 AND SW1 ST APM1
        self.apm[1] = m[0] && i.sw1;
        // CAL SR1( SET1 := APM1, RESET := M23 | M1 := Q1 )
        self.sr[1].call(self.apm[1], self.m23);
        m[1] = self.sr[1].q1;
        // LD M1 AND S1 ANDN S2 ST APM2
        self.apm[2] = m[1] && i.s1 && !i.s2;
        // CAL SR2( SET1 := APM2, RESET := M4 | M2 := Q1 )
        self.sr[2].call(self.apm[2], m[4]);
        m[2] = self.sr[2].q1;
        // LD M1 ANDN S1 AND S2 ST APM3
        self.apm[3] = m[1] && !i.s1 && i.s2;
        // CAL SR3( SET1 := APM3, RESET := M4 | M3 := Q1 )
        self.sr[3].call(self.apm[3], m[4]);
        m[3] = self.sr[3].q1;
        // LD M2 OR M3 ST M23
        self.m23 = m[2] || m[3];
        // LD M23 AND QT1 ST APM4   (QT1 as left by the previous cycle's T1 call)
        self.apm[4] = self.m23 && self.qt1;
        // CAL SR4( SET1 := APM4, RESET := M0 | M4 := Q1 )
        self.sr[4].call(self.apm[4], m[0]);
        m[4] = self.sr[4].q1;
        // CAL T1( IN := M23, PT := DT1 | QT1 := Q, := ET )
        self.t1.call(now_ms, self.m23, DT_MS);
        self.qt1 = self.t1.q;
        // CAL T2( IN := M4, PT := DT2 | QT2 := Q, := ET )
        self.t2.call(now_ms, m[4], DT_MS);
        self.qt2 = self.t2.q;
        // Actions, copied from ALG01: V1, V2, L1
        self.v1 = (m[2] || self.v1) && !m[4];
        self.v2 = (m[3] || self.v2) && !m[4];
        self.l1 = (m[1] || self.l1) && !self.m23;
    }
}

/// Which of the two listings to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    Alg01,
    Alg02,
}

impl Algorithm {
    pub fn file_stem(self) -> &'static str {
        match self {
            Algorithm::Alg01 => "alg01",
            Algorithm::Alg02 => "alg02",
        }
    }
}

/// Runs `alg` for `cycles` cycles on the stimulus text and returns the traced
/// values (`TRACED` order) of every cycle, recorded after the program ran.
pub fn run(alg: Algorithm, stimulus_text: &str, cycles: u64) -> Vec<Vec<bool>> {
    let stimulus = Stimulus::parse(stimulus_text);
    let mut next_row = 0;
    let mut inputs = Inputs::default();
    let mut a1 = Alg01::default();
    let mut a2 = Alg02::default();
    let mut rows = Vec::new();
    for k in 0..cycles {
        // (1) stimulus rows due, (2) the program, (3) the trace row.
        for (name, value) in stimulus.due(k, &mut next_row) {
            inputs.set(&name, &value);
        }
        let now_ms = k * CYCLE_MS;
        let row = match alg {
            Algorithm::Alg01 => {
                a1.scan(inputs, now_ms);
                [
                    a1.m[0], a1.m[1], a1.m[2], a1.m[3], a1.m[4], a1.v1, a1.v2, a1.l1,
                ]
            }
            Algorithm::Alg02 => {
                a2.scan(inputs, now_ms);
                [
                    a2.m[0], a2.m[1], a2.m[2], a2.m[3], a2.m[4], a2.v1, a2.v2, a2.l1,
                ]
            }
        };
        rows.push(row.to_vec());
    }
    rows
}

/// The expected trace CSV of `alg` on the stimulus, as
/// `plcrun programs/<alg>.il --cycles 1200 --stimulus <file>
/// --trace M0,M1,M2,M3,M4,V1,V2,L1 --format csv` must print it.
pub fn expected_csv(alg: Algorithm, stimulus_text: &str) -> String {
    let rows: Vec<Vec<String>> = run(alg, stimulus_text, CYCLES)
        .into_iter()
        .map(|r| r.into_iter().map(|b| bool_lit(b).to_string()).collect())
        .collect();
    trace_csv(&TRACED, &rows)
}

//! Independent models of the three worked examples of the Siemens S7-200
//! "table method" seed (`programs/s7_table_example{1,2,3}.awl`).
//!
//! The models do not interpret STL. Each is the example's GRAFCET written as
//! data (steps, transitions with one upstream and one downstream step,
//! receptivities as plain boolean expressions) and run with the seed's
//! rules and cycle order (seed chapters 2.3-2.6, 4.2):
//! 1. first scan: the initial steps are active and "active forever" (their
//!    rising edge is false), all graphs are free, edges of inputs are false;
//! 2. preliminary computations (edge of `dcy`, the input words of example 1);
//! 3. receptivities, each ANDed with its graph's "free" bit (the freezing
//!    order of the previous scan, chapter 5.4: `Ti = receptivity . Figeage`);
//! 4. evolution (rules 2-5): every transition whose upstream step is active
//!    and whose receptivity is true is fired; `Ts = Tp./Td + Ta`, so an
//!    activated step stays active even if also deactivated (rule 5);
//! 5. forcing: the forcing orders of the steps active after the evolution
//!    give "forced to 0" and "forced to 1" sets; `Ts = Ts./Tf0 + Tf1`
//!    (forced to 1 wins);
//! 6. timers (IEC on-delay on the virtual clock, docs/semantics.md §4, with
//!    the S7-200 preset K times the timer's resolution);
//! 7. outputs and the freezing orders for the next scan.
//!
//! Step numbers are the seed's (X0..X7, X10..X17, ...): step `n` is bit
//! `n % 10` of table byte `n / 10`, so its activity is `V(20 + n/10).(n%10)`
//! in `Ts`, its rising edge `V(30 + n/10).(n%10)` in `Tpulse`, its forcing
//! orders `V(60 + ...)` (to 1) and `V(70 + ...)` (to 0).
//!
//! The few places where the listing's own data flow (not the GRAFCET)
//! decides a value are modelled explicitly and say so: example 1's
//! `VB100`/`VB102`/`VB104` (the listing's SBR 11 and its `FILL K0 VW40 K40`,
//! which also clears `VB104` at the start of every scan) and example 3's
//! latched `A0.0` in step 32.
//!
//! Nothing here uses the plcrun engine.
#![allow(dead_code)]

use super::trace_text::{CYCLE_MS, Stimulus, bool_lit, parse_bool, trace_csv};
use std::collections::BTreeMap;

/// Activity of the steps, indexed by the seed's step number.
pub type Steps = [bool; 80];

/// A transition of a GRAFCET: one upstream and one downstream step (all the
/// seed's transitions have one of each).
#[derive(Debug, Clone, Copy)]
pub struct Transition {
    /// The seed's name (`T0`, `T13`, `t5`).
    pub name: &'static str,
    /// The upstream step.
    pub from: usize,
    /// The downstream step.
    pub to: usize,
}

const fn tr(name: &'static str, from: usize, to: usize) -> Transition {
    Transition { name, from, to }
}

/// Rules 2 to 5: fires every enabled transition whose receptivity is true,
/// all at once (rule 4); activation wins over deactivation (rule 5).
pub fn evolve(active: &Steps, transitions: &[Transition], receptive: &[bool]) -> Steps {
    assert_eq!(transitions.len(), receptive.len());
    let mut activate = [false; 80];
    let mut deactivate = [false; 80];
    for (t, &r) in transitions.iter().zip(receptive) {
        if active[t.from] && r {
            activate[t.to] = true;
            deactivate[t.from] = true;
        }
    }
    std::array::from_fn(|s| (active[s] && !deactivate[s]) || activate[s])
}

/// The names of the transitions `evolve` fires on the same arguments.
pub fn fired(active: &Steps, transitions: &[Transition], receptive: &[bool]) -> Vec<&'static str> {
    transitions
        .iter()
        .zip(receptive)
        .filter(|(t, r)| active[t.from] && **r)
        .map(|(t, _)| t.name)
        .collect()
}

/// The forcing orders of one scan: steps forced to 0 and to 1.
#[derive(Debug, Clone)]
pub struct Forcing {
    /// Forced to 0 (`Tf0`).
    pub to_zero: Steps,
    /// Forced to 1 (`Tf1`).
    pub to_one: Steps,
}

impl Forcing {
    /// No order.
    pub fn none() -> Forcing {
        Forcing {
            to_zero: [false; 80],
            to_one: [false; 80],
        }
    }

    /// Forces the steps of `graph` to 0.
    pub fn zero(&mut self, graph: &[usize]) {
        for &s in graph {
            self.to_zero[s] = true;
        }
    }

    /// Forces `step` to 1.
    pub fn one(&mut self, step: usize) {
        self.to_one[step] = true;
    }

    /// `Ts = Ts./Tf0 + Tf1`: a step forced to 0 by one order and to 1 by
    /// another is forced to 1 (seed chapter 2.3, comments).
    pub fn apply(&self, active: &Steps) -> Steps {
        std::array::from_fn(|s| (active[s] && !self.to_zero[s]) || self.to_one[s])
    }
}

/// The table byte of steps `10k .. 10k+7` (`byte` = k) as the S7 byte holds it.
pub fn table_byte(steps: &Steps, byte: usize) -> u8 {
    (0..8).fold(0u8, |acc, bit| {
        acc | (u8::from(steps[byte * 10 + bit]) << bit)
    })
}

/// Rising edges of step activity (`Tpulse = Ts./Tp`).
pub fn rising(now: &Steps, before: &Steps) -> Steps {
    std::array::from_fn(|s| now[s] && !before[s])
}

/// The S7-200 on-delay timer as the IEC TON on the virtual clock: it starts
/// in the scan its enable rises and is done when `now - start >= preset`.
#[derive(Debug, Clone, Default)]
pub struct Ton {
    start_ms: Option<u64>,
    /// The timer bit.
    pub done: bool,
}

impl Ton {
    /// One execution of `TON` with enable `en` at clock `now_ms`.
    pub fn call(&mut self, en: bool, now_ms: u64, preset_ms: u64) {
        if en {
            let start = *self.start_ms.get_or_insert(now_ms);
            self.done = now_ms - start >= preset_ms;
        } else {
            self.start_ms = None;
            self.done = false;
        }
    }
}

/// Formats a byte as plcrun prints a BYTE (`16#1F`).
pub fn byte_lit(b: u8) -> String {
    format!("16#{b:X}")
}

/// The current value of every input named by the stimulus (all FALSE at
/// first), updated cycle by cycle.
pub struct Inputs {
    stimulus: Stimulus,
    next: usize,
    values: BTreeMap<String, bool>,
}

impl Inputs {
    /// Starts with every input of the stimulus FALSE.
    pub fn new(stimulus_text: &str) -> Inputs {
        let stimulus = Stimulus::parse(stimulus_text);
        let values = stimulus.names.iter().map(|n| (n.clone(), false)).collect();
        Inputs {
            stimulus,
            next: 0,
            values,
        }
    }

    /// Applies the rows due at the start of `cycle`.
    pub fn advance(&mut self, cycle: u64) {
        for (name, value) in self.stimulus.due(cycle, &mut self.next) {
            self.values.insert(name, parse_bool(&value));
        }
    }

    /// The value of input `name` (`I0.4`); inputs the stimulus does not
    /// name are FALSE.
    pub fn get(&self, name: &str) -> bool {
        self.values.get(name).copied().unwrap_or(false)
    }

    /// The input byte `IB0` / `IB1`.
    pub fn byte(&self, byte: u8) -> u8 {
        (0..8).fold(0u8, |acc, bit| {
            acc | (u8::from(self.get(&format!("I{byte}.{bit}"))) << bit)
        })
    }
}

/// A model's run: traced names and one row of literals per cycle.
pub struct Run {
    /// Traced names, S7 operand names.
    pub names: Vec<&'static str>,
    /// One row per cycle.
    pub rows: Vec<Vec<String>>,
    /// The transitions fired, by cycle.
    pub fired: Vec<(u64, &'static str)>,
}

impl Run {
    /// The CSV text as plcrun prints it (`cycle,time,NAME...`).
    pub fn csv(&self) -> String {
        trace_csv(&self.names, &self.rows)
    }

    /// For every cycle where some traced value changed (the first row is
    /// compared with all FALSE / 16#0), the changes as `NAME=value`.
    pub fn changes(&self) -> Vec<(usize, String)> {
        let mut prev: Vec<String> = self
            .names
            .iter()
            .map(|n| if n.contains('.') { "FALSE" } else { "16#0" }.to_string())
            .collect();
        let mut out = Vec::new();
        for (k, row) in self.rows.iter().enumerate() {
            let parts: Vec<String> = row
                .iter()
                .zip(&prev)
                .zip(&self.names)
                .filter(|((now, before), _)| now != before)
                .map(|((now, _), name)| format!("{name}={now}"))
                .collect();
            if !parts.is_empty() {
                out.push((k, parts.join(" ")));
            }
            prev.clone_from(row);
        }
        out
    }
}

fn bits(steps: &Steps, list: &[usize]) -> Vec<String> {
    list.iter()
        .map(|&s| bool_lit(steps[s]).to_string())
        .collect()
}

// ------------------------------------------------------------ example 1

/// Example 1: positioning axis, one graph G0 (steps 0-5, transitions t0-t7).
pub mod example1 {
    use super::*;

    /// Traced operands of example 1.
    pub const TRACED: [&str; 14] = [
        "Q0.0", "Q0.1", "Q0.2", "Q0.3", "V20.0", "V20.1", "V20.2", "V20.3", "V20.4", "V20.5",
        "VB30", "VB100", "VB102", "VB104",
    ];

    /// The graph as the listing's SBR 4 draws it (figures are missing).
    pub const TRANSITIONS: [Transition; 8] = [
        tr("t0", 0, 1),
        tr("t1", 1, 2),
        tr("t2", 0, 3),
        tr("t3", 3, 0),
        tr("t4", 2, 0),
        tr("t5", 2, 4),
        tr("t6", 4, 5),
        tr("t7", 5, 0),
    ];

    /// Runs `cycles` scans on the stimulus text.
    pub fn run(stimulus: &str, cycles: u64) -> Run {
        let mut inputs = Inputs::new(stimulus);
        let mut active: Steps = [false; 80];
        active[0] = true; // rule 1
        let mut before = active; // "active forever": no rising edge at start
        let mut rows = Vec::new();
        let mut fired_log = Vec::new();
        for cycle in 0..cycles {
            inputs.advance(cycle);
            // Preliminary (SBR 11): the first pressed demand button wins;
            // while one is pressed the position byte is not read (CRET).
            let demand_button = (4..8).find(|&b| inputs.get(&format!("I0.{b}")));
            let (vb100, vb102) = match demand_button {
                Some(b) => (1u8 << (b - 4), 0u8),
                None => (0, inputs.byte(0) & 0x0F),
            };
            // The saved position VB104 is cleared every scan before the
            // receptivities (SBR 1's FILL K0 VW40 K40 reaches VB119).
            let vb104_seen = 0u8;
            let t4 = vb104_seen == vb100;
            let receptive = [
                vb100 >= 1, // t0: a demand
                vb102 >= 1, // t1: a position sensor
                vb100 >= 1, // t2 (listing: V80.0)
                vb100 >= 1, // t3 (listing: V80.0)
                t4,
                !t4,
                true, // t6
                t4,   // t7
            ];
            let evolved = evolve(&active, &TRANSITIONS, &receptive);
            for name in fired(&active, &TRANSITIONS, &receptive) {
                fired_log.push((cycle, name));
            }
            // No forcing in example 1 (SBR 5: NOP).
            let x = |s: usize| evolved[s];
            let moving = x(3) || x(5);
            let direction = x(4) && vb102 >= vb100; // V6.0
            let vb104 = if x(2) { vb102 } else { 0 };
            let mut row = vec![
                bool_lit(moving).to_string(),
                bool_lit(direction).to_string(),
                bool_lit(moving && direction).to_string(),
                bool_lit(moving && !direction).to_string(),
            ];
            row.extend(bits(&evolved, &[0, 1, 2, 3, 4, 5]));
            row.push(byte_lit(table_byte(&rising(&evolved, &before), 0)));
            row.push(byte_lit(vb100));
            row.push(byte_lit(vb102));
            row.push(byte_lit(vb104));
            rows.push(row);
            before = evolved;
            active = evolved;
        }
        Run {
            names: TRACED.to_vec(),
            rows,
            fired: fired_log,
        }
    }
}

// ------------------------------------------------------------ example 2

/// Example 2: safety graph G0 (steps 0-3) and production graph G1 (steps
/// 10-13), with forcing (X0, X1) and freezing (X3) of G1.
pub mod example2 {
    use super::*;

    /// Traced operands of example 2.
    pub const TRACED: [&str; 15] = [
        "Q0.0", "Q0.1", "Q0.2", "V20.0", "V20.1", "V20.2", "V20.3", "V21.0", "V21.1", "V21.2",
        "V21.3", "VB0", "VB31", "VB61", "VB71",
    ];

    /// G0 then G1, as drawn by SBR 4.
    pub const TRANSITIONS: [Transition; 8] = [
        tr("T0", 0, 1),
        tr("T1", 1, 2),
        tr("T2", 2, 3),
        tr("T3", 3, 0),
        tr("T10", 10, 11),
        tr("T11", 11, 12),
        tr("T12", 12, 13),
        tr("T13", 13, 10),
    ];

    const G1: [usize; 4] = [10, 11, 12, 13];

    /// Runs `cycles` scans on the stimulus text.
    pub fn run(stimulus: &str, cycles: u64) -> Run {
        let mut inputs = Inputs::new(stimulus);
        let mut active: Steps = [false; 80];
        active[0] = true;
        let mut before = active;
        let mut free1 = true;
        let mut dcy_before = false;
        let mut t37 = Ton::default();
        let mut rows = Vec::new();
        let mut fired_log = Vec::new();
        for cycle in 0..cycles {
            inputs.advance(cycle);
            let io = |n: &str| inputs.get(n);
            let (v0, v1, h0, h1, dcy, au) = (
                io("I0.0"),
                io("I0.1"),
                io("I0.2"),
                io("I0.3"),
                io("I0.4"),
                io("I0.5"),
            );
            if cycle == 0 {
                dcy_before = dcy; // a dcy held at power-on is no edge
            }
            let dcy_up = dcy && !dcy_before;
            dcy_before = dcy;
            let receptive = [
                !au && dcy_up,
                true,
                au,
                !au,
                h1 && free1,
                v1 && free1,
                h0 && free1,
                t37.done && free1,
            ];
            let evolved = evolve(&active, &TRANSITIONS, &receptive);
            for name in fired(&active, &TRANSITIONS, &receptive) {
                fired_log.push((cycle, name));
            }
            let mut orders = Forcing::none();
            if evolved[0] {
                orders.zero(&G1);
            }
            if evolved[1] {
                orders.zero(&G1);
                orders.one(10);
            }
            let now = orders.apply(&evolved);
            t37.call(now[13], cycle * CYCLE_MS, 50 * 100);
            free1 = !now[3];
            let mut row = vec![
                bool_lit(now[11]).to_string(),
                bool_lit(now[12] && v0).to_string(),
                bool_lit(now[10]).to_string(),
            ];
            row.extend(bits(&now, &[0, 1, 2, 3, 10, 11, 12, 13]));
            row.push(byte_lit(if free1 { 0xFF } else { 0xFD }));
            row.push(byte_lit(table_byte(&rising(&now, &before), 1)));
            row.push(byte_lit(table_byte(&orders.to_one, 1)));
            row.push(byte_lit(table_byte(&orders.to_zero, 1)));
            rows.push(row);
            before = now;
            active = now;
        }
        Run {
            names: TRACED.to_vec(),
            rows,
            fired: fired_log,
        }
    }
}

// ------------------------------------------------------------ example 3

/// Example 3: G0 (GS, 0-3) forces G1 (GC, 10-14) and freezes G1-G3 in X3;
/// G1 forces G2 (Gauto, 20-23) and G3 (Gmanu, 30-32).
pub mod example3 {
    use super::*;

    /// Traced operands of example 3.
    pub const TRACED: [&str; 17] = [
        "Q0.0", "Q0.1", "Q0.2", "Q0.3", "Q0.4", "Q0.5", "VB20", "VB21", "VB22", "VB23", "VB0",
        "VB61", "VB62", "VB63", "VB71", "VB72", "VB73",
    ];

    /// The four graphs, as drawn by SBR 4.
    pub const TRANSITIONS: [Transition; 18] = [
        tr("T0", 0, 1),
        tr("T1", 1, 2),
        tr("T2", 2, 3),
        tr("T3", 3, 0),
        tr("T10", 10, 11),
        tr("T11", 11, 12),
        tr("T12", 12, 10),
        tr("T13", 10, 13),
        tr("T14", 13, 14),
        tr("T15", 14, 10),
        tr("T20", 20, 21),
        tr("T21", 21, 22),
        tr("T22", 22, 23),
        tr("T23", 23, 20),
        tr("T30", 30, 31),
        tr("T31", 31, 30),
        tr("T32", 30, 32),
        tr("T33", 32, 30),
    ];

    const G1: [usize; 5] = [10, 11, 12, 13, 14];
    const G2: [usize; 4] = [20, 21, 22, 23];
    const G3: [usize; 3] = [30, 31, 32];

    /// Runs `cycles` scans on the stimulus text.
    pub fn run(stimulus: &str, cycles: u64) -> Run {
        let mut inputs = Inputs::new(stimulus);
        let mut active: Steps = [false; 80];
        active[0] = true;
        let mut free = true; // G1, G2, G3 share one freezing order (not X3)
        let mut dcy_before = false;
        let mut t33 = Ton::default();
        let mut v_plus = false; // A0.0 is latched in step 32
        let mut rows = Vec::new();
        let mut fired_log = Vec::new();
        for cycle in 0..cycles {
            inputs.advance(cycle);
            let io = |n: &str| inputs.get(n);
            let (v0, v1, h0, h1) = (io("I0.0"), io("I0.1"), io("I0.2"), io("I0.3"));
            let (dcy, manu, auto, au) = (io("I1.0"), io("I1.1"), io("I1.2"), io("I1.3"));
            let (vh, vv, a, b) = (io("I1.4"), io("I1.5"), io("I1.6"), io("I1.7"));
            if cycle == 0 {
                dcy_before = dcy;
            }
            let dcy_up = dcy && !dcy_before;
            dcy_before = dcy;
            let receptive = [
                !au && dcy_up,
                true,
                au,
                !au,
                v0 && free && dcy_up,
                free,
                !auto && free,
                manu && free && !auto,
                free,
                !manu && free,
                h1 && free,
                v1 && free,
                h0 && free,
                t33.done && free,
                vh && free,
                !vh && free,
                vv && free && !vh,
                !vv && free,
            ];
            let evolved = evolve(&active, &TRANSITIONS, &receptive);
            for name in fired(&active, &TRANSITIONS, &receptive) {
                fired_log.push((cycle, name));
            }
            let mut orders = Forcing::none();
            if evolved[0] {
                orders.zero(&G1);
                orders.zero(&G2);
                orders.zero(&G3);
            }
            if evolved[1] {
                orders.zero(&G1);
                orders.one(10);
            }
            if evolved[10] {
                orders.zero(&G2);
                orders.zero(&G3);
            }
            if evolved[11] {
                orders.zero(&G2);
                orders.one(20);
            }
            if evolved[13] {
                orders.zero(&G3);
                orders.one(30);
            }
            let x = orders.apply(&evolved);
            t33.call(x[23], cycle * CYCLE_MS, 30 * 10);
            free = !x[3];
            if x[32] {
                if a {
                    v_plus = true;
                }
                if b {
                    v_plus = false;
                }
            } else {
                v_plus = x[22] && v0;
            }
            let mut row: Vec<String> = [
                v_plus,
                (x[22] && v0) || (x[31] && b),
                x[20] || (x[31] && a),
                v0 && h0,
                x[12],
                x[14],
            ]
            .iter()
            .map(|&v| bool_lit(v).to_string())
            .collect();
            for byte in 0..4 {
                row.push(byte_lit(table_byte(&x, byte)));
            }
            row.push(byte_lit(if free { 0xFF } else { 0xF1 }));
            for byte in 1..4 {
                row.push(byte_lit(table_byte(&orders.to_one, byte)));
            }
            for byte in 1..4 {
                row.push(byte_lit(table_byte(&orders.to_zero, byte)));
            }
            rows.push(row);
            active = x;
        }
        Run {
            names: TRACED.to_vec(),
            rows,
            fired: fired_log,
        }
    }
}

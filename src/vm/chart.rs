//! Execution of `Op::Sfc`: one call of a chart (evolution, then action
//! control), driven by the chart's step table and the state kept in the
//! instance memory.
//!
//! Work per call is proportional to the active steps, their outgoing
//! transitions and the live actions: nothing iterates over the whole chart.
//!
//! Its functions are all inlined into the executor (`#[inline(always)]`):
//! `vm::grafcet` shares some of them, which would otherwise leave them out
//! of line and cost the IEC path calls (callgrind: +15 % on CHARIOT).

use super::debug::ChartEvent;
use super::{Fault, Machine, exec};
use crate::ir::chart::{
    ActionKind, Chart, Condition, Duration, Evolution, Qualifier, action_layout as al, header as hd,
};
use crate::ir::image::Image;
use crate::ir::type_table::step_layout as sl;

/// Runs one call of chart `chart` for the instance at `base`.
#[inline(always)]
pub(super) fn run<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    chart: crate::ir::op::ChartIdx,
    base: usize,
) -> Result<(), Fault> {
    let Some(c) = img.charts.get(chart.index()) else {
        return Ok(());
    };
    // The evolution rules are chosen once, at compile time, per chart.
    if c.evolution == Evolution::Grafcet {
        return super::grafcet::run::<DEBUG>(m, img, c, chart, base);
    }
    let now = m.now;
    let h = base + c.header as usize;
    if m.mem[h + hd::STARTED as usize] == 0 {
        m.mem[h + hd::STARTED as usize] = 1;
        for &s in &c.initial {
            activate(m, c, base, s, now);
            if DEBUG {
                m.debug_chart(img, chart, ChartEvent::Step(s));
            }
        }
    }
    let epoch = m.mem[h + hd::EPOCH as usize].wrapping_add(1);
    m.mem[h + hd::EPOCH as usize] = epoch;
    evolve::<DEBUG>(m, img, c, chart, base, epoch, now)?;
    actions::<DEBUG>(m, img, c, chart, base, epoch, now)
}

/// Marks step `s` active from `now` and inserts it into the active list.
#[inline(always)]
pub(super) fn activate(m: &mut Machine, c: &Chart, base: usize, s: u32, now: i64) {
    let rec = base + c.steps[s as usize].rec as usize;
    m.mem[rec + sl::X as usize] = 1;
    m.mem[rec + sl::START as usize] = now as u64;
    m.mem[rec + sl::T as usize] = 0;
    let n_at = base + (c.header + hd::N_ACTIVE) as usize;
    insert_sorted(m, base + c.active as usize, n_at, s as u64);
}

/// Inserts `v` into the sorted list at `at` whose length is at `n_at`
/// (no duplicates; the list has room for every possible element).
#[inline(always)]
pub(super) fn insert_sorted(m: &mut Machine, at: usize, n_at: usize, v: u64) {
    let n = m.mem[n_at] as usize;
    let list = &mut m.mem[at..at + n + 1];
    match list[..n].binary_search(&v) {
        Ok(_) => {}
        Err(pos) => {
            list.copy_within(pos..n, pos + 1);
            list[pos] = v;
            m.mem[n_at] = (n + 1) as u64;
        }
    }
}

/// Is step `s` active?
#[inline]
pub(super) fn active(m: &Machine, c: &Chart, base: usize, s: u32) -> bool {
    m.mem[base + (c.steps[s as usize].rec + sl::X) as usize] != 0
}

/// Evaluates transition `t`'s condition (at most once per call).
#[inline(always)]
pub(super) fn condition<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    base: usize,
    t: u32,
    epoch: u64,
) -> Result<bool, Fault> {
    match c.transitions[t as usize].cond {
        Condition::Const(b) => Ok(b),
        Condition::Frame(o) => Ok(m.mem[base + o as usize] != 0),
        Condition::Code(code) => {
            let slot = base + (c.cache + t) as usize;
            let cached = m.mem[slot];
            if cached >> 1 == epoch {
                return Ok(cached & 1 != 0);
            }
            exec::call::<DEBUG, false>(m, img, code, base)?;
            let v = m.mem[base + (c.header + hd::COND) as usize] != 0;
            m.mem[slot] = (epoch << 1) | v as u64;
            Ok(v)
        }
    }
}

/// Evolution: `.T` update, choice of the transitions that fire on the
/// current situation, then deactivation and activation of their steps.
#[inline(always)]
fn evolve<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    chart: crate::ir::op::ChartIdx,
    base: usize,
    epoch: u64,
    now: i64,
) -> Result<(), Fault> {
    let act = base + c.active as usize;
    let n_at = base + (c.header + hd::N_ACTIVE) as usize;
    let n = m.mem[n_at] as usize;
    for i in 0..n {
        let s = m.mem[act + i] as usize;
        let rec = base + c.steps[s].rec as usize;
        let start = m.mem[rec + sl::START as usize] as i64;
        m.mem[rec + sl::T as usize] = now.wrapping_sub(start) as u64;
    }
    // Pass 1: for every active step, the first clearable outgoing
    // transition in priority order (0 = none), on the unchanged situation.
    let mut any = false;
    for i in 0..n {
        let s = m.mem[act + i] as usize;
        let step = &c.steps[s];
        let mut winner = 0u64;
        for &t in &step.out {
            let tr = &c.transitions[t as usize];
            if !tr.from.iter().all(|&p| active(m, c, base, p)) {
                continue;
            }
            if condition::<DEBUG>(m, img, c, base, t, epoch)? {
                winner = t as u64 + 1;
                break;
            }
        }
        m.mem[base + step.scratch as usize] = winner;
        any |= winner != 0;
    }
    if !any {
        return Ok(());
    }
    // Pass 2: a transition fires when it wins every one of its preceding
    // steps; its preceding steps are deactivated at once (firing decisions
    // only read the winners, never `.X`).
    let fired_at = base + c.cache as usize + c.transitions.len();
    let mut fired = 0usize;
    for i in 0..n {
        let s = m.mem[act + i] as usize;
        let w = m.mem[base + c.steps[s].scratch as usize];
        if w == 0 {
            continue;
        }
        let tr = &c.transitions[(w - 1) as usize];
        // Fire once, from the first preceding step in the active list.
        if tr.from.iter().any(|&p| (p as usize) < s) && tr.from.len() > 1 {
            // Another preceding step comes earlier in the sorted list and
            // handled (or rejected) this transition already.
            continue;
        }
        if !tr
            .from
            .iter()
            .all(|&p| m.mem[base + c.steps[p as usize].scratch as usize] == w)
        {
            continue;
        }
        m.mem[fired_at + fired] = w - 1;
        fired += 1;
        for &p in &tr.from {
            m.mem[base + (c.steps[p as usize].rec + sl::X) as usize] = 0;
        }
    }
    if fired == 0 {
        return Ok(());
    }
    // Drop the deactivated steps from the active list.
    let mut kept = 0usize;
    for i in 0..n {
        let s = m.mem[act + i];
        if active(m, c, base, s as u32) {
            m.mem[act + kept] = s;
            kept += 1;
        }
    }
    m.mem[n_at] = kept as u64;
    // Pass 3: activation. A step deactivated above and activated here
    // stays active with `.T` restarted (rule 5); a step that was active and
    // not deactivated is left as it is.
    for k in 0..fired {
        let t = m.mem[fired_at + k] as usize;
        for &q in &c.transitions[t].to {
            if !active(m, c, base, q) {
                activate(m, c, base, q, now);
            }
        }
    }
    if DEBUG {
        for k in 0..fired {
            let t = m.mem[fired_at + k] as u32;
            m.debug_chart(img, chart, ChartEvent::Fired(t));
            for &q in &c.transitions[t as usize].to {
                m.debug_chart(img, chart, ChartEvent::Step(q));
            }
        }
    }
    Ok(())
}

/// Reads a duration.
#[inline]
pub(super) fn duration(m: &Machine, base: usize, d: Duration) -> u64 {
    match d {
        Duration::None => 0,
        Duration::Const(v) => v as u64,
        Duration::Frame(o) => m.mem[base + o as usize],
        Duration::Abs(a) => m.mem[a as usize],
    }
}

/// Action control for every live action, in execution order.
#[inline(always)]
fn actions<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    chart: crate::ir::op::ChartIdx,
    base: usize,
    epoch: u64,
    now: i64,
) -> Result<(), Fault> {
    let act = base + c.active as usize;
    let n_active = m.mem[base + (c.header + hd::N_ACTIVE) as usize] as usize;
    let live = base + c.live as usize;
    let live_n = base + (c.header + hd::N_LIVE) as usize;
    // Inputs: OR over the active steps of each association's qualifier;
    // for a timed qualifier the duration of the first active step (in
    // declaration order) that gives it.
    for i in 0..n_active {
        let s = m.mem[act + i] as usize;
        for a in &c.steps[s].assocs {
            let rec = base + c.actions[a.action as usize].rec as usize;
            if m.mem[rec + al::IN_EPOCH as usize] != epoch {
                m.mem[rec + al::IN_EPOCH as usize] = epoch;
                m.mem[rec + al::INPUTS as usize] = 0;
                insert_sorted(m, live, live_n, a.action as u64);
            }
            let bit = a.qualifier.bit();
            let inputs = m.mem[rec + al::INPUTS as usize];
            if inputs & bit == 0 {
                let slot = match a.qualifier {
                    Qualifier::L => Some(al::DUR_L),
                    Qualifier::D => Some(al::DUR_D),
                    Qualifier::DS => Some(al::DUR_DS),
                    Qualifier::SD => Some(al::DUR_SD),
                    Qualifier::SL => Some(al::DUR_SL),
                    _ => None,
                };
                if let Some(slot) = slot {
                    m.mem[rec + slot as usize] = duration(m, base, a.duration);
                }
                m.mem[rec + al::INPUTS as usize] = inputs | bit;
            }
        }
    }
    let n_live = m.mem[live_n] as usize;
    let mut kept = 0usize;
    for i in 0..n_live {
        let a = m.mem[live + i] as usize;
        let action = &c.actions[a];
        let rec = base + action.rec as usize;
        let inputs = if m.mem[rec + al::IN_EPOCH as usize] == epoch {
            m.mem[rec + al::INPUTS as usize]
        } else {
            0
        };
        let q = control(m, rec, inputs, now);
        let old_q = m.mem[rec + al::Q as usize] != 0;
        if DEBUG && q {
            m.debug_chart(img, chart, ChartEvent::Action(a as u32));
        }
        match action.kind {
            ActionKind::Body(code) => {
                m.mem[rec + al::Q as usize] = q as u64;
                if q || old_q {
                    m.mem[rec + al::A as usize] = 1;
                    exec::call::<DEBUG, false>(m, img, code, base)?;
                }
                m.mem[rec + al::A as usize] = q as u64;
            }
            ActionKind::Frame(o) => {
                m.mem[rec + al::Q as usize] = q as u64;
                m.mem[base + o as usize] = q as u64;
            }
            ActionKind::Abs(at) => {
                m.mem[rec + al::Q as usize] = q as u64;
                m.mem[at as usize] = q as u64;
            }
        }
        let stored = m.mem[rec + al::S_SET as usize]
            | m.mem[rec + al::SD_SET as usize]
            | m.mem[rec + al::DS_SET as usize]
            | m.mem[rec + al::SL_SET as usize];
        if inputs != 0 || q || stored != 0 {
            m.mem[live + kept] = a as u64;
            kept += 1;
        }
    }
    m.mem[live_n] = kept as u64;
    Ok(())
}

/// ACTION_CONTROL for one action: updates its stored state and returns Q.
#[inline(always)]
fn control(m: &mut Machine, rec: usize, inputs: u64, now: i64) -> bool {
    let r = |k: u32| rec + k as usize;
    let prev = m.mem[r(al::PREV)];
    m.mem[r(al::PREV)] = inputs;
    let has = |q: Qualifier| inputs & q.bit() != 0;
    let rose = |q: Qualifier| inputs & q.bit() != 0 && prev & q.bit() == 0;
    let fell = |q: Qualifier| inputs & q.bit() == 0 && prev & q.bit() != 0;
    let since = |at: u64| now.wrapping_sub(at as i64);
    let reset = has(Qualifier::R);
    // Timers of L, D and DS follow their inputs whatever R does.
    if rose(Qualifier::L) {
        m.mem[r(al::L_AT)] = now as u64;
    }
    if rose(Qualifier::D) {
        m.mem[r(al::D_AT)] = now as u64;
    }
    if rose(Qualifier::DS) {
        m.mem[r(al::DS_AT)] = now as u64;
    }
    if reset {
        for k in [al::S_SET, al::SD_SET, al::DS_SET, al::SL_SET] {
            m.mem[r(k)] = 0;
        }
        return false;
    }
    if has(Qualifier::S) {
        m.mem[r(al::S_SET)] = 1;
    }
    if rose(Qualifier::SD) && m.mem[r(al::SD_SET)] == 0 {
        m.mem[r(al::SD_SET)] = 1;
        m.mem[r(al::SD_AT)] = now as u64;
        m.mem[r(al::SD_T)] = m.mem[r(al::DUR_SD)];
    }
    if rose(Qualifier::SL) && m.mem[r(al::SL_SET)] == 0 {
        m.mem[r(al::SL_SET)] = 1;
        m.mem[r(al::SL_AT)] = now as u64;
        m.mem[r(al::SL_T)] = m.mem[r(al::DUR_SL)];
    }
    if has(Qualifier::DS) && since(m.mem[r(al::DS_AT)]) >= m.mem[r(al::DUR_DS)] as i64 {
        m.mem[r(al::DS_SET)] = 1;
    }
    let l_part = has(Qualifier::L) && since(m.mem[r(al::L_AT)]) < m.mem[r(al::DUR_L)] as i64;
    let d_part = has(Qualifier::D) && since(m.mem[r(al::D_AT)]) >= m.mem[r(al::DUR_D)] as i64;
    let pulse = rose(Qualifier::P) || rose(Qualifier::P1) || fell(Qualifier::P0);
    let sd_part =
        m.mem[r(al::SD_SET)] != 0 && since(m.mem[r(al::SD_AT)]) >= m.mem[r(al::SD_T)] as i64;
    let sl_part =
        m.mem[r(al::SL_SET)] != 0 && since(m.mem[r(al::SL_AT)]) < m.mem[r(al::SL_T)] as i64;
    has(Qualifier::N)
        || m.mem[r(al::S_SET)] != 0
        || l_part
        || d_part
        || pulse
        || sd_part
        || m.mem[r(al::DS_SET)] != 0
        || sl_part
}

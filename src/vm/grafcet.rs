//! IEC 60848 GRAFCET evolution of a chart (`--grafcet`), the alternative
//! to `vm::chart`'s IEC 61131-3 evolution, chosen per chart at compile
//! time (`Chart::evolution`), never tested inside the IEC path's loops.
//!
//! One call: evolution is iterated on the same inputs until no transition
//! can fire (a stable situation), firing all fireable transitions at once
//! in every round (rule 4), a step both deactivated and activated staying
//! active without a new activation (rule 5). Steps entered and left in the
//! same call (transient) emit their activation and deactivation events
//! (S, R, P, P1, SD, SL on activation; P0 on deactivation) but assign no
//! continuous action (N, L, D, DS): those follow the stable situation only.
//! Then the forcing orders of the stable situation's steps are applied,
//! then action control. A chart held by a forcing order does not evolve
//! in its next call. See docs/grafcet.md.

use super::chart::{activate, active, condition, duration, insert_sorted};
use super::debug::ChartEvent;
use super::fault::UnstableCycle;
use super::{Fault, FaultKind, Machine, exec};
use crate::ir::chart::{
    ActionKind, Chart, ForcingOrder, InstanceAt, Qualifier, action_layout as al, header as hd,
    started,
};
use crate::ir::image::Image;
use crate::ir::op::{ChartIdx, CodeIdx, Op};
use crate::ir::type_table::step_layout as sl;

/// Qualifiers whose input is a level of the stable situation.
const LEVELS: u64 = bit(Qualifier::N) | bit(Qualifier::L) | bit(Qualifier::D) | bit(Qualifier::DS);
/// Qualifiers that act on the step's activation, transient or not.
const ON_ACTIVATION: u64 = bit(Qualifier::S)
    | bit(Qualifier::R)
    | bit(Qualifier::P)
    | bit(Qualifier::P1)
    | bit(Qualifier::SD)
    | bit(Qualifier::SL);
/// Qualifiers that act on the step's deactivation.
const ON_DEACTIVATION: u64 = bit(Qualifier::P0);
/// Scratch mark of a step deactivated in the current round.
const LEFT: u64 = u64::MAX;

const fn bit(q: Qualifier) -> u64 {
    1 << (q as u32)
}

/// Runs one call of chart `c` (number `index`) for the instance at `base`.
/// Kept out of line: the IEC path that calls it must not change shape.
#[inline(never)]
pub(super) fn run<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    index: ChartIdx,
    base: usize,
) -> Result<(), Fault> {
    let now = m.now;
    let h = base + c.header as usize;
    let state = m.mem[h + hd::STARTED as usize];
    if state & started::RUNNING == 0 {
        // The initial situation is "active since ever": no activation
        // events (S, P1... of an initial step do not act at start).
        for &s in &c.initial {
            activate(m, c, base, s, now);
        }
    }
    m.mem[h + hd::STARTED as usize] = started::RUNNING;
    let epoch = m.mem[h + hd::EPOCH as usize].wrapping_add(1);
    let last = if state & started::FORCED != 0 {
        // Held by a forcing order: forcing has priority over evolution.
        step_times(m, c, base, now);
        epoch
    } else {
        stabilize::<DEBUG>(m, img, c, index, base, epoch, now).map_err(|f| locate(img, index, f))?
    };
    m.mem[h + hd::EPOCH as usize] = last;
    apply_forcings(m, c, base, now);
    actions::<DEBUG>(m, img, c, index, base, epoch, now)
}

/// `.T := now - activation` for every active step.
fn step_times(m: &mut Machine, c: &Chart, base: usize, now: i64) {
    let act = base + c.active as usize;
    let n = m.mem[base + (c.header + hd::N_ACTIVE) as usize] as usize;
    for i in 0..n {
        let s = m.mem[act + i] as usize;
        let rec = base + c.steps[s].rec as usize;
        let start = m.mem[rec + sl::START as usize] as i64;
        m.mem[rec + sl::T as usize] = now.wrapping_sub(start) as u64;
    }
}

/// The most firing rounds one call may take before its evolution is
/// declared unstable.
fn bound(c: &Chart) -> usize {
    c.steps.len() + 1
}

/// Fires rounds until none fires; returns the last condition stamp used.
/// Each round evaluates conditions afresh (stamp `epoch + round`).
fn stabilize<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    index: ChartIdx,
    base: usize,
    epoch: u64,
    now: i64,
) -> Result<u64, Fault> {
    let mut stamp = epoch;
    let mut rounds = 0usize;
    loop {
        if round::<DEBUG>(m, img, c, index, base, stamp, epoch, now)? == 0 {
            return Ok(stamp);
        }
        rounds += 1;
        stamp = stamp.wrapping_add(1);
        if rounds > bound(c) {
            return Err(unstable(m, img, c, index, base, stamp, epoch, now));
        }
    }
}

/// One evolution round on the current situation: the transitions that
/// fire (same choice as IEC: priorities per step, a transition fires when
/// it wins all its preceding steps), deactivation, then activation with
/// the events. Returns how many fired; their indexes are at the fired list.
#[allow(clippy::too_many_arguments)]
fn round<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    index: ChartIdx,
    base: usize,
    stamp: u64,
    epoch: u64,
    now: i64,
) -> Result<usize, Fault> {
    step_times(m, c, base, now);
    let act = base + c.active as usize;
    let n_at = base + (c.header + hd::N_ACTIVE) as usize;
    let n = m.mem[n_at] as usize;
    // The same choice of winners as vm/chart.rs's pass 1, written out
    // again on purpose: one shared inline function measured +0.6 % on
    // CHARIOT's IEC evolution (callgrind, `vm::exec::run`, 2 000 cycles).
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
            if condition::<DEBUG>(m, img, c, base, t, stamp)? {
                winner = t as u64 + 1;
                break;
            }
        }
        m.mem[base + step.scratch as usize] = winner;
        any |= winner != 0;
    }
    if !any {
        return Ok(0);
    }
    let fired_at = base + c.cache as usize + c.transitions.len();
    let mut fired = 0usize;
    for i in 0..n {
        let s = m.mem[act + i] as usize;
        let w = m.mem[base + c.steps[s].scratch as usize];
        if w == 0 {
            continue;
        }
        let tr = &c.transitions[(w - 1) as usize];
        if tr.from.len() > 1 && tr.from.iter().any(|&p| (p as usize) < s) {
            continue;
        }
        if tr
            .from
            .iter()
            .all(|&p| m.mem[base + c.steps[p as usize].scratch as usize] == w)
        {
            m.mem[fired_at + fired] = w - 1;
            fired += 1;
        }
    }
    if fired == 0 {
        return Ok(0);
    }
    for k in 0..fired {
        let t = m.mem[fired_at + k] as usize;
        for &p in &c.transitions[t].from {
            let step = &c.steps[p as usize];
            m.mem[base + (step.rec + sl::X) as usize] = 0;
            m.mem[base + step.scratch as usize] = LEFT;
        }
    }
    let mut kept = 0usize;
    for i in 0..n {
        let s = m.mem[act + i];
        if active(m, c, base, s as u32) {
            m.mem[act + kept] = s;
            kept += 1;
        }
    }
    m.mem[n_at] = kept as u64;
    for k in 0..fired {
        let t = m.mem[fired_at + k] as usize;
        for &q in &c.transitions[t].to {
            if active(m, c, base, q) {
                continue;
            }
            let step = &c.steps[q as usize];
            if m.mem[base + step.scratch as usize] == LEFT {
                // Rule 5: it stays active, with no new activation (its
                // time runs on).
                m.mem[base + (step.rec + sl::X) as usize] = 1;
                let act_n = base + (c.header + hd::N_ACTIVE) as usize;
                insert_sorted(m, act, act_n, q as u64);
            } else {
                activate(m, c, base, q, now);
                events(m, c, base, q, epoch, ON_ACTIVATION);
            }
        }
    }
    if DEBUG {
        for k in 0..fired {
            let t = m.mem[fired_at + k] as u32;
            m.debug_chart(img, index, ChartEvent::Fired(t));
            for &q in &c.transitions[t as usize].to {
                m.debug_chart(img, index, ChartEvent::Step(q));
            }
        }
    }
    for k in 0..fired {
        let t = m.mem[fired_at + k] as usize;
        for &p in &c.transitions[t].from {
            m.mem[base + c.steps[p as usize].scratch as usize] = 0;
            if !active(m, c, base, p) {
                events(m, c, base, p, epoch, ON_DEACTIVATION);
            }
        }
    }
    Ok(fired)
}

/// Adds the inputs of step `s`'s associations whose qualifier is in `mask`
/// to their actions for this call (stamped `epoch`).
fn events(m: &mut Machine, c: &Chart, base: usize, s: u32, epoch: u64, mask: u64) {
    for a in &c.steps[s as usize].assocs {
        if a.qualifier.bit() & mask != 0 {
            input(m, c, base, a, epoch);
        }
    }
}

/// Adds one association's qualifier to its action's inputs of this call,
/// with its duration for a timed qualifier (the first one given wins).
fn input(m: &mut Machine, c: &Chart, base: usize, a: &crate::ir::chart::Association, epoch: u64) {
    let rec = base + c.actions[a.action as usize].rec as usize;
    if m.mem[rec + al::IN_EPOCH as usize] != epoch {
        m.mem[rec + al::IN_EPOCH as usize] = epoch;
        m.mem[rec + al::INPUTS as usize] = 0;
        let live = base + c.live as usize;
        let live_n = base + (c.header + hd::N_LIVE) as usize;
        insert_sorted(m, live, live_n, a.action as u64);
    }
    let bit = a.qualifier.bit();
    let inputs = m.mem[rec + al::INPUTS as usize];
    if inputs & bit != 0 {
        return;
    }
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

/// The fault of an evolution that reached the bound: evolution goes on
/// (the PLC stops anyway) until a situation repeats, and the transitions
/// fired over one period of that repetition are named.
#[allow(clippy::too_many_arguments)]
fn unstable(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    index: ChartIdx,
    base: usize,
    mut stamp: u64,
    epoch: u64,
    now: i64,
) -> Fault {
    let situation = |m: &Machine| -> Vec<u64> {
        let act = base + c.active as usize;
        let n = m.mem[base + (c.header + hd::N_ACTIVE) as usize] as usize;
        m.mem[act..act + n].to_vec()
    };
    // Brent's cycle search over the situations.
    let mut mark = situation(m);
    let (mut power, mut lambda) = (1usize, 0usize);
    let mut period = None;
    for _ in 0..64 * bound(c).max(16) {
        match round::<false>(m, img, c, index, base, stamp, epoch, now) {
            Ok(0) => break,
            Ok(_) => {}
            Err(f) => return f,
        }
        stamp = stamp.wrapping_add(1);
        lambda += 1;
        let now_at = situation(m);
        if now_at == mark {
            period = Some(lambda);
            break;
        }
        if lambda == power {
            mark = now_at;
            power *= 2;
            lambda = 0;
        }
    }
    let mut names: Vec<String> = Vec::new();
    let fired_at = base + c.cache as usize + c.transitions.len();
    for _ in 0..period.unwrap_or(bound(c)) {
        let fired = match round::<false>(m, img, c, index, base, stamp, epoch, now) {
            Ok(0) => break,
            Ok(k) => k,
            Err(f) => return f,
        };
        stamp = stamp.wrapping_add(1);
        for k in 0..fired {
            let name = transition_name(c, m.mem[fired_at + k] as usize);
            if !names.contains(&name) {
                names.push(name);
            }
        }
    }
    Fault {
        kind: FaultKind::UnstableChart(Box::new(UnstableCycle {
            chart: c.name.clone(),
            bound: bound(c),
            transitions: names,
        })),
        code: CodeIdx::new(0),
        pc: UNLOCATED,
    }
}

/// `Fault::pc` of the unstable-chart fault until [`locate`] places it.
const UNLOCATED: u32 = u32::MAX;

/// Places the chart's own fault at its `Op::Sfc` (faults of condition
/// blocks already carry their place). Only on the fault path: `exec`'s
/// dispatch of `Op::Sfc` stays as it is.
fn locate(img: &Image, index: ChartIdx, mut f: Fault) -> Fault {
    if f.pc != UNLOCATED {
        return f;
    }
    for (k, block) in img.codes.iter().enumerate() {
        let at = block
            .ops
            .iter()
            .position(|op| matches!(op, Op::Sfc { chart } if *chart == index));
        if let Some(pc) = at {
            f.code = CodeIdx::new(k as u32);
            f.pc = pc as u32;
            break;
        }
    }
    f
}

/// `A -> B`, or `(A, B) -> C` for a convergence or divergence.
fn transition_name(c: &Chart, t: usize) -> String {
    let side = |steps: &[u32]| {
        let names: Vec<&str> = steps
            .iter()
            .map(|&s| c.steps[s as usize].name.as_str())
            .collect();
        if names.len() == 1 {
            names[0].to_string()
        } else {
            format!("({})", names.join(", "))
        }
    };
    let tr = &c.transitions[t];
    format!("{} -> {}", side(&tr.from), side(&tr.to))
}

/// Applies the forcing orders held by the active steps: the forced chart
/// gets the order's situation (a step entering it starts its time, one
/// staying active keeps it) and is marked held for its next call. Orders
/// meeting on one chart before it runs add up: the first imposes its
/// situation, the next ones add their steps (forced active wins over
/// forced inactive), and a freeze keeps what they imposed.
fn apply_forcings(m: &mut Machine, c: &Chart, base: usize, now: i64) {
    for f in &c.forcings {
        if !active(m, c, base, f.step) {
            continue;
        }
        let inst = match f.instance {
            InstanceAt::Frame(o) => base + o as usize,
            InstanceAt::Abs(a) => a as usize,
        };
        let h = inst + f.header as usize;
        let situation = match &f.order {
            ForcingOrder::Freeze => {
                m.mem[h + hd::STARTED as usize] |= started::FORCED;
                continue;
            }
            ForcingOrder::Situation(s) => s,
        };
        let imposed = m.mem[h + hd::STARTED as usize] & started::IMPOSED != 0;
        let list = h + hd::SIZE as usize;
        let mut n = 0usize;
        for (i, &rec) in f.steps.iter().enumerate() {
            let r = inst + rec as usize;
            let wanted = situation.binary_search(&(i as u32)).is_ok();
            let was = m.mem[r + sl::X as usize] != 0;
            if wanted && !was {
                m.mem[r + sl::X as usize] = 1;
                m.mem[r + sl::START as usize] = now as u64;
                m.mem[r + sl::T as usize] = 0;
            } else if !wanted && was && !imposed {
                m.mem[r + sl::X as usize] = 0;
            }
            // The active list, rebuilt in step order (it stays sorted).
            if m.mem[r + sl::X as usize] != 0 {
                m.mem[list + n] = i as u64;
                n += 1;
            }
        }
        m.mem[h + hd::N_ACTIVE as usize] = n as u64;
        m.mem[h + hd::STARTED as usize] = started::RUNNING | started::FORCED | started::IMPOSED;
    }
}

/// Action control: the continuous inputs of the stable situation's steps
/// join the events recorded during evolution; every live action is then
/// controlled and drives its output as under IEC evolution.
fn actions<const DEBUG: bool>(
    m: &mut Machine,
    img: &Image,
    c: &Chart,
    index: ChartIdx,
    base: usize,
    epoch: u64,
    now: i64,
) -> Result<(), Fault> {
    let act = base + c.active as usize;
    let n_active = m.mem[base + (c.header + hd::N_ACTIVE) as usize] as usize;
    for i in 0..n_active {
        let s = m.mem[act + i] as usize;
        for a in &c.steps[s].assocs {
            if a.qualifier.bit() & LEVELS != 0 {
                input(m, c, base, a, epoch);
            }
        }
    }
    let live = base + c.live as usize;
    let live_n = base + (c.header + hd::N_LIVE) as usize;
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
            m.debug_chart(img, index, ChartEvent::Action(a as u32));
        }
        m.mem[rec + al::Q as usize] = q as u64;
        match action.kind {
            ActionKind::Body(code) => {
                if q || old_q {
                    m.mem[rec + al::A as usize] = 1;
                    exec::call::<DEBUG, false>(m, img, code, base)?;
                }
                m.mem[rec + al::A as usize] = q as u64;
            }
            ActionKind::Frame(o) => m.mem[base + o as usize] = q as u64,
            ActionKind::Abs(at) => m.mem[at as usize] = q as u64,
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

/// Action control under IEC 60848: N, L, D, DS are levels of the stable
/// situation (L and D timed from their level's rise); S, R, SD, SL are
/// events of the activation (R applied after S, so a reset in the same
/// call wins); P, P1 and P0 give Q for the call of their event.
fn control(m: &mut Machine, rec: usize, inputs: u64, now: i64) -> bool {
    let r = |k: u32| rec + k as usize;
    let prev = m.mem[r(al::PREV)];
    m.mem[r(al::PREV)] = inputs & LEVELS;
    let has = |q: Qualifier| inputs & q.bit() != 0;
    let rose = |q: Qualifier| inputs & q.bit() != 0 && prev & q.bit() == 0;
    let since = |at: u64| now.wrapping_sub(at as i64);
    if rose(Qualifier::L) {
        m.mem[r(al::L_AT)] = now as u64;
    }
    if rose(Qualifier::D) {
        m.mem[r(al::D_AT)] = now as u64;
    }
    if rose(Qualifier::DS) {
        m.mem[r(al::DS_AT)] = now as u64;
    }
    if has(Qualifier::S) {
        m.mem[r(al::S_SET)] = 1;
    }
    if has(Qualifier::SD) && m.mem[r(al::SD_SET)] == 0 {
        m.mem[r(al::SD_SET)] = 1;
        m.mem[r(al::SD_AT)] = now as u64;
        m.mem[r(al::SD_T)] = m.mem[r(al::DUR_SD)];
    }
    if has(Qualifier::SL) && m.mem[r(al::SL_SET)] == 0 {
        m.mem[r(al::SL_SET)] = 1;
        m.mem[r(al::SL_AT)] = now as u64;
        m.mem[r(al::SL_T)] = m.mem[r(al::DUR_SL)];
    }
    if has(Qualifier::R) {
        for k in [al::S_SET, al::SD_SET, al::DS_SET, al::SL_SET] {
            m.mem[r(k)] = 0;
        }
    }
    if has(Qualifier::DS) && since(m.mem[r(al::DS_AT)]) >= m.mem[r(al::DUR_DS)] as i64 {
        m.mem[r(al::DS_SET)] = 1;
    }
    let l_part = has(Qualifier::L) && since(m.mem[r(al::L_AT)]) < m.mem[r(al::DUR_L)] as i64;
    let d_part = has(Qualifier::D) && since(m.mem[r(al::D_AT)]) >= m.mem[r(al::DUR_D)] as i64;
    let pulse = has(Qualifier::P) || has(Qualifier::P1) || has(Qualifier::P0);
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

//! The CHARIOT closed loop of `examples/chariot_loop` (issue #9, point 11,
//! virtual time), run in-process through the example's own modules: the
//! timeline of the first round trip against a derivation by hand, the
//! number of round trips, and the plant's refusal of impossible commands;
//! and the same loop on the wall clock (a quicker plant, 2.5 s), checked
//! for round trips and sane task statistics.
//!
//! Derivation (10 ms cycles; cart at 1 m/s = 10 mm per cycle on a 1.5 m
//! track; the operator presses Dcy after the VOM lamp has been lit for 50
//! cycles, i.e. from the 50th cycle after the one that lit it):
//! - cycle 0: INIT; FcA closed, so VOM := fcA is TRUE.
//! - cycle 50: Dcy & FcA: INIT → AV, KMAV in the same call.
//! - cycle 51: the cart is at 10 mm: FcA open, VOM off (Dcy still held: the
//!   operator saw the lamp lit in cycle 50). Cycle 52: Dcy released.
//! - cycles 50..199 move the cart 150 × 10 mm: FcB in cycle 200: AV → ATT,
//!   KMAV off.
//! - ATT.T reaches tX3 = T#1s in cycle 300 (active from 200): ATT → AR,
//!   KMAR on; FcB opens in cycle 301.
//! - cycles 300..449 bring the cart back: FcA in cycle 450: AR → INIT, VOM.
//!
//! So one round trip takes 450 cycles: back at A in cycles 450, 900, 1350,
//! 1800 of a 2000-cycle run.

#[path = "../examples/chariot_loop/closed_loop.rs"]
mod closed_loop;
#[path = "../examples/chariot_loop/plant.rs"]
mod plant;
#[path = "../examples/chariot_loop/realtime.rs"]
mod realtime;

use plant::{Cart, Operator, PlantError};

#[test]
fn the_first_round_trip_follows_the_hand_derivation() {
    let run = closed_loop::run(460).expect("the loop runs");
    let timeline: Vec<String> = run.events.iter().map(|e| e.to_string()).collect();
    let want = [
        "   0.00 s      0 mm  INIT  in: FcA          out: VOM",
        "   0.50 s      0 mm  AV    in: Dcy FcA      out: KMAV VOM",
        "   0.51 s     10 mm  AV    in: Dcy          out: KMAV",
        "   0.52 s     20 mm  AV    in: -            out: KMAV",
        "   2.00 s   1500 mm  ATT   in: FcB          out: -",
        "   3.00 s   1500 mm  AR    in: FcB          out: KMAR",
        "   3.01 s   1490 mm  AR    in: -            out: KMAR",
        "   4.50 s      0 mm  INIT  in: FcA          out: VOM",
    ];
    assert_eq!(timeline, want);
    let cycles: Vec<u64> = run.events.iter().map(|e| e.cycle).collect();
    assert_eq!(cycles, [0, 50, 51, 52, 200, 300, 301, 450]);
    assert_eq!(run.round_trips, [450]);
}

#[test]
fn the_cart_keeps_making_round_trips() {
    let run = closed_loop::run(2000).expect("the loop runs");
    assert_eq!(run.round_trips, [450, 900, 1350, 1800]);
    // Never both contactors, never past a station by more than one step.
    assert!(
        run.events
            .iter()
            .all(|e| !(e.signals.kmav && e.signals.kmar))
    );
    assert!(
        run.events
            .iter()
            .all(|e| (0..=1500).contains(&e.position_mm))
    );
}

#[test]
fn the_plant_refuses_what_would_break_a_real_one() {
    let mut cart = Cart::new();
    assert_eq!(
        cart.advance(7, true, true),
        Err(PlantError::BothContactors { cycle: 7 })
    );
    for cycle in 0..5 {
        cart.advance(cycle, false, true).unwrap();
    }
    assert_eq!(cart.position_mm, -50);
    assert_eq!(
        cart.advance(5, false, true),
        Err(PlantError::EndStop {
            cycle: 5,
            position_mm: -60
        })
    );
    let mut operator = Operator::new();
    let presses: Vec<bool> = (0..70).map(|_| operator.button(true)).collect();
    assert_eq!(presses.iter().filter(|p| **p).count(), 10);
    assert!(presses[49] && !presses[48] && !presses[59]);
    assert!(!operator.button(false));
}

/// Real time on a shared 2-core machine: the bounds are loose on purpose
/// (no timeline to the cycle), but the loop must go round and the
/// statistics must be there and consistent.
#[test]
fn the_loop_goes_round_in_real_time_with_sane_statistics() {
    let setup = realtime::Setup::quick();
    let mut live = 0;
    let run = realtime::run(setup, std::time::Duration::from_millis(2500), |_| live += 1)
        .expect("the loop runs");
    assert_eq!(live, run.events.len(), "every change is handed over live");
    assert!(!run.round_trips.is_empty(), "no round trip: {run:#?}");
    // The chart's steps in their order, starting in INIT.
    let steps: Vec<&str> = run.events.iter().map(|e| e.signals.step).collect();
    let mut order = steps.clone();
    order.dedup();
    let cycle = ["INIT", "AV", "ATT", "AR"];
    assert!(order.len() >= 5, "{order:?}");
    for (i, step) in order.iter().enumerate() {
        assert_eq!(*step, cycle[i % 4], "{order:?}");
    }
    assert!(
        run.events
            .iter()
            .all(|e| !(e.signals.kmav && e.signals.kmar) && (0..=300).contains(&e.position_mm))
    );
    // Time goes forward with the cycles.
    assert!(
        run.events
            .windows(2)
            .all(|w| w[0].cycle < w[1].cycle && w[0].time_ns < w[1].time_ns)
    );
    let [stats] = run.stats.as_slice() else {
        panic!("one task expected: {:?}", run.stats)
    };
    assert_eq!(stats.interval_ns, 10_000_000);
    // 250 deadlines in 2.5 s; a loaded machine may miss some.
    assert!(stats.cycles >= 100 && stats.cycles <= 251, "{stats:?}");
    assert!(stats.overruns < stats.cycles, "{stats:?}");
    for t in [stats.execution.unwrap(), stats.start_jitter.unwrap()] {
        assert!(
            0 <= t.min_ns && t.min_ns <= t.mean_ns && t.mean_ns <= t.max_ns,
            "{t:?}"
        );
    }
    let exec = stats.execution.unwrap();
    assert!(exec.max_ns < 1_000_000_000, "{exec:?}");
    let last = *run.round_trips.last().unwrap();
    assert!(last <= stats.cycles + stats.overruns, "{run:#?}");
}

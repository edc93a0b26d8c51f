//! programs/chariot.sfc in a closed loop with the simulated plant on the
//! wall clock: a [`TaskRunner`] runs the chart on its own thread at its
//! cycle time, and the plant lives in the session's per-cycle hook, which
//! runs between two cycles: it reads what the cycle did, moves the cart
//! and writes the inputs of the next cycle through resolved handles. The
//! hook sends each change of the signals to the caller's thread, which
//! prints them as they happen; at the end the runner's statistics say how
//! the task kept its deadlines.

use super::closed_loop::{CHART, Event, Io, LoopError, Signals};
use super::plant::{Cart, Operator};
use plcrun::{Options, Plc, RunError, Session, TaskRunner, TaskStats, TraceFormat, TraceWriter};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::time::{Duration, Instant};

/// The plant and the PLC's timing for a run.
#[derive(Debug, Clone)]
pub struct Setup {
    /// The cart at the start.
    pub cart: Cart,
    /// The operator.
    pub operator: Operator,
    /// The waiting time at B (the chart's input `tX3`), an IEC literal.
    pub wait_at_b: &'static str,
    /// The PLC's cycle time, in nanoseconds.
    pub cycle_time_ns: i64,
}

impl Setup {
    /// The plant of the virtual-time loop: 1.5 m at 1 m/s, 1 s at B, 10 ms
    /// cycles (a round trip takes 4.5 s).
    pub fn standard() -> Setup {
        Setup {
            cart: Cart::new(),
            operator: Operator::new(),
            wait_at_b: super::closed_loop::WAIT_AT_B,
            cycle_time_ns: 10_000_000,
        }
    }

    /// A quicker plant for tests: a 0.3 m track, 0.2 s at B, the button
    /// pressed after 0.1 s (a round trip takes about 0.9 s).
    pub fn quick() -> Setup {
        let mut setup = Setup::standard();
        setup.cart.track_mm = 300;
        setup.operator.wait_cycles = 10;
        setup.operator.press_cycles = 5;
        setup.wait_at_b = "T#200ms";
        setup
    }
}

/// A finished real-time run.
#[derive(Debug, Clone)]
pub struct RealTimeRun {
    /// The changes of the signals, in order.
    pub events: Vec<Event>,
    /// The cycles in which the cart came back to A from B.
    pub round_trips: Vec<u64>,
    /// The task's statistics at the end.
    pub stats: Vec<TaskStats>,
}

/// What the hook reports to the caller's thread.
enum Message {
    Event(Event),
    RoundTrip(u64),
    /// The plant crashed or a variable could not be accessed; the run is
    /// being stopped.
    Failed(LoopError),
}

/// The plant's side of the loop, owned by the per-cycle hook.
struct PlantHook {
    io: Io,
    cart: Cart,
    operator: Operator,
    /// The button as written for the cycle under way.
    dcy: bool,
    been_at_b: bool,
    last: Option<Signals>,
    tx: Sender<Message>,
}

impl PlantHook {
    /// After the cycle `plc.cycle() - 1`: record it, move the cart, write
    /// the next cycle's inputs.
    fn between_cycles(&mut self, plc: &mut Plc) -> Result<(), LoopError> {
        let cycle = plc.cycle().saturating_sub(1);
        let signals = self.io.signals(plc, self.dcy, &self.cart)?;
        if self.last.as_ref() != Some(&signals) {
            let event = Event {
                cycle,
                time_ns: plc.last_cycle_time(),
                position_mm: self.cart.position_mm,
                signals: signals.clone(),
            };
            let _ = self.tx.send(Message::Event(event));
        }
        self.cart
            .advance(cycle, signals.kmav, signals.kmar)
            .map_err(LoopError::Plant)?;
        self.last = Some(signals);
        self.prepare(plc, cycle + 1)
    }

    /// Writes the inputs of `cycle` (and notes a round trip ending in it).
    fn prepare(&mut self, plc: &mut Plc, cycle: u64) -> Result<(), LoopError> {
        if self.cart.at_a() && self.been_at_b {
            let _ = self.tx.send(Message::RoundTrip(cycle));
        }
        self.been_at_b = (self.been_at_b || self.cart.at_b()) && !self.cart.at_a();
        self.dcy = self.operator.button(self.io.lamp(plc)?);
        self.io.write_inputs(plc, self.dcy, &self.cart)?;
        Ok(())
    }
}

/// Runs the loop on the wall clock for `wall` of real time, handing each
/// change of the signals to `on_event` as it happens.
pub fn run(
    setup: Setup,
    wall: Duration,
    mut on_event: impl FnMut(&Event),
) -> Result<RealTimeRun, LoopError> {
    let options = Options {
        cycle_time: setup.cycle_time_ns,
        ..Options::default()
    };
    let mut plc = Plc::compile_files(&[("chariot.sfc", CHART)], &options)
        .map_err(|e| LoopError::Compile(Box::new(e)))?;
    plc.write("tX3", setup.wait_at_b)?;
    let (tx, rx) = mpsc::channel();
    let mut hook = PlantHook {
        io: Io::resolve(&plc)?,
        cart: setup.cart,
        operator: setup.operator,
        dcy: false,
        been_at_b: false,
        last: None,
        tx,
    };
    hook.prepare(&mut plc, 0)?;
    let stop = plc.stop_handle();
    let mut session = Session::new(plc);
    let hook_stop = stop.clone();
    let failed = hook.tx.clone();
    session.set_cycle_hook(move |plc| {
        if let Err(e) = hook.between_cycles(plc) {
            let _ = failed.send(Message::Failed(e));
            hook_stop.stop();
        }
    });
    let runner = TaskRunner::real_time(session.plc());
    let stats = runner.stats();
    let trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
    let thread = runner.spawn(session, None, trace);
    let mut run = RealTimeRun {
        events: Vec::new(),
        round_trips: Vec::new(),
        stats: Vec::new(),
    };
    let end = Instant::now() + wall;
    let mut failure = None;
    while failure.is_none() && !thread.is_finished() {
        let left = end.saturating_duration_since(Instant::now());
        if left.is_zero() {
            break;
        }
        match receive(
            &rx,
            left.min(Duration::from_millis(50)),
            &mut run,
            &mut on_event,
        ) {
            Ok(()) => {}
            Err(e) => failure = Some(e),
        }
    }
    stop.stop();
    let outcome = thread.join();
    // What the last cycles sent before the stop.
    while let Ok(message) = rx.try_recv() {
        if let Err(e) = record(message, &mut run, &mut on_event) {
            failure.get_or_insert(e);
        }
    }
    if let Some(e) = failure {
        return Err(e);
    }
    match outcome.result {
        Ok(()) => {}
        Err(RunError::Fault(f)) => return Err(LoopError::Fault(Box::new(f))),
        Err(e) => return Err(LoopError::Run(Box::new(e))),
    }
    run.stats = stats.snapshot();
    Ok(run)
}

/// Waits up to `timeout` for a message from the hook and records it.
fn receive(
    rx: &Receiver<Message>,
    timeout: Duration,
    run: &mut RealTimeRun,
    on_event: &mut impl FnMut(&Event),
) -> Result<(), LoopError> {
    match rx.recv_timeout(timeout) {
        Ok(message) => record(message, run, on_event),
        Err(RecvTimeoutError::Timeout | RecvTimeoutError::Disconnected) => Ok(()),
    }
}

fn record(
    message: Message,
    run: &mut RealTimeRun,
    on_event: &mut impl FnMut(&Event),
) -> Result<(), LoopError> {
    match message {
        Message::Event(event) => {
            on_event(&event);
            run.events.push(event);
            Ok(())
        }
        Message::RoundTrip(cycle) => {
            run.round_trips.push(cycle);
            Ok(())
        }
        Message::Failed(e) => Err(e),
    }
}

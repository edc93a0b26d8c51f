//! Tasks through the library: virtual-time scheduling one base tick or
//! one task at a time, the clock, the cycle and stop hooks, and real-time
//! runs with their statistics (loose bounds: the machine is shared).

use plcrun::{
    Clock, Options, Plc, RunError, Session, TaskRunner, TaskStats, TraceFormat, TraceWriter,
};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

const TWO_TASKS: &str = "
PROGRAM Count VAR_OUTPUT n : DINT; END_VAR n := n + 1; END_PROGRAM
PROGRAM Clock VAR_OUTPUT t : TIME; END_VAR VAR tm : TON; END_VAR
  tm(IN := TRUE, PT := T#1h); t := tm.ET;
END_PROGRAM
CONFIGURATION C RESOURCE R ON PLC
  TASK fast(INTERVAL := T#2ms, PRIORITY := 1);
  TASK slow(INTERVAL := T#5ms, PRIORITY := 0);
  PROGRAM a WITH fast : Count;
  PROGRAM b WITH slow : Count;
  PROGRAM c WITH slow : Clock;
END_RESOURCE END_CONFIGURATION";

fn plc() -> Plc {
    Plc::compile_files(&[("two.st", TWO_TASKS)], &Options::default()).expect("compiles")
}

fn read(plc: &Plc, name: &str) -> String {
    plc.read(name).expect("readable").to_literal()
}

fn csv_trace(names: &[&str]) -> TraceWriter<Vec<u8>> {
    let names = names.iter().map(|s| s.to_string()).collect();
    TraceWriter::new(Vec::new(), TraceFormat::Csv, names, false)
}

#[test]
fn plc_and_session_can_move_to_another_thread() {
    fn assert_send<T: Send>() {}
    assert_send::<Plc>();
    assert_send::<Session>();
    assert_send::<TaskRunner>();
}

#[test]
fn base_ticks_run_each_task_at_its_interval_on_the_virtual_clock() {
    let mut plc = plc();
    assert_eq!(plc.cycle_time(), 1_000_000);
    let mut runs = Vec::new();
    for _ in 0..20 {
        plc.run_cycle().unwrap();
        runs.push((read(&plc, "a.n"), read(&plc, "b.n")));
    }
    // 20 ticks of 1 ms: fast at 0, 2, ... 18 ms; slow at 0, 5, 10, 15 ms.
    assert_eq!(runs[19], ("10".to_string(), "4".to_string()));
    assert_eq!(runs[4], ("3".to_string(), "1".to_string()));
    assert_eq!(runs[5], ("3".to_string(), "2".to_string()));
    // The slow task's timer saw the virtual time of its last run: 15 ms.
    assert_eq!(read(&plc, "c.t"), "T#15ms");
    assert_eq!((plc.cycle(), plc.time()), (20, 20_000_000));
}

#[test]
fn one_task_steps_alone_at_the_callers_clock() {
    let mut plc = plc();
    let now = Arc::new(AtomicU64::new(0));
    let reading = Arc::clone(&now);
    plc.set_clock(Clock::from_fn(move || {
        reading.load(Ordering::Relaxed) as i64
    }));
    assert!(!plc.clock().is_virtual());
    plc.run_task("slow").unwrap();
    now.store(7_000_000, Ordering::Relaxed);
    plc.run_task("slow").unwrap();
    assert_eq!(read(&plc, "b.n"), "2");
    assert_eq!(read(&plc, "a.n"), "0");
    assert_eq!(read(&plc, "c.t"), "T#7ms");
    assert_eq!(plc.last_cycle_time(), 7_000_000);
    let names: Vec<String> = plc.tasks().into_iter().map(|t| t.name).collect();
    assert_eq!(names, ["fast", "slow"]);
}

#[test]
fn the_measured_virtual_run_gives_the_plain_runs_trace() {
    let names = ["a.n", "b.n", "c.t"];
    let mut plain = Session::new(plc());
    plain.set_trace(&names).unwrap();
    let mut out = csv_trace(&names);
    plain.run(30, &mut out).unwrap();
    let expected = String::from_utf8(out.finish().unwrap()).unwrap();

    let mut measured = Session::new(plc());
    measured.set_trace(&names).unwrap();
    let mut runner = TaskRunner::virtual_time(measured.plc());
    let mut out = csv_trace(&names);
    runner.run(&mut measured, Some(30), &mut out).unwrap();
    assert_eq!(String::from_utf8(out.finish().unwrap()).unwrap(), expected);
    let stats = runner.stats().snapshot();
    assert_eq!((stats[0].cycles, stats[1].cycles), (15, 6));
    assert!(stats[0].start_jitter.is_none());
    assert!(stats[0].execution.is_some());
}

#[test]
fn the_cycle_hook_runs_between_cycles_and_the_stop_hook_at_a_clean_end() {
    let src = "PROGRAM P VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR
               y := x + 1; END_PROGRAM";
    let mut session =
        Session::new(Plc::compile_files(&[("p.st", src)], &Options::default()).unwrap());
    // A plant that feeds the output back as the next input.
    session.set_cycle_hook(|plc| {
        let y = plc.read("y").unwrap().to_literal();
        plc.write("x", &y).unwrap();
    });
    let saved = Arc::new(Mutex::new(Vec::new()));
    let into = Arc::clone(&saved);
    session.set_on_stop(move |plc| {
        into.lock().unwrap().push(plc.read("y")?.to_literal());
        Ok(())
    });
    session.set_trace(&["y"]).unwrap();
    let mut out = csv_trace(&["y"]);
    session.run(5, &mut out).unwrap();
    assert_eq!(*saved.lock().unwrap(), ["5"]);
    // A stop asked before the run: no cycle, still a clean stop.
    session.plc().stop_handle().stop();
    session.run(5, &mut out).unwrap();
    assert_eq!(session.plc().cycle(), 5);
    assert_eq!(*saved.lock().unwrap(), ["5", "5"]);
}

#[test]
fn a_failing_stop_hook_is_reported() {
    let src = "PROGRAM P END_PROGRAM";
    let mut session =
        Session::new(Plc::compile_files(&[("p.st", src)], &Options::default()).unwrap());
    session.set_on_stop(|_| Err("disk full".into()));
    let err = session.run(1, &mut csv_trace(&[])).unwrap_err();
    assert!(matches!(err, RunError::OnStop(_)), "{err}");
    assert_eq!(err.to_string(), "at the stop: disk full");
}

/// The activations a cyclic task of `interval_ms` had in `elapsed`.
fn expected_activations(elapsed: Duration, interval_ms: u64) -> f64 {
    elapsed.as_secs_f64() * 1000.0 / interval_ms as f64
}

fn check_sane(s: &TaskStats, elapsed: Duration, interval_ms: u64) {
    let expected = expected_activations(elapsed, interval_ms);
    let activations = (s.cycles + s.overruns) as f64;
    assert!(
        (activations - expected).abs() <= 0.3 * expected + 1.0,
        "{} activations, expected about {expected}: {s:?}",
        activations
    );
    assert!(s.cycles as f64 >= 0.5 * expected, "{s:?}");
    for t in [s.execution.unwrap(), s.start_jitter.unwrap()] {
        assert!(t.min_ns <= t.mean_ns && t.mean_ns <= t.max_ns, "{s:?}");
        assert!(t.min_ns <= t.p99_ns && t.p99_ns <= t.max_ns, "{s:?}");
    }
    // The jitter is a delay (a run never starts before its deadline) and
    // on any machine far below a second.
    let jitter = s.start_jitter.unwrap();
    assert!(jitter.min_ns >= 0 && jitter.max_ns < 1_000_000_000, "{s:?}");
}

#[test]
fn two_tasks_in_real_time_have_sane_statistics() {
    let mut session = Session::new(plc());
    session.set_trace(&["a.n", "c.t"]).unwrap();
    let mut runner = TaskRunner::real_time(session.plc());
    assert!(runner.is_real_time());
    let mut out = csv_trace(&["a.n", "c.t"]);
    let started = Instant::now();
    runner.run(&mut session, Some(300), &mut out).unwrap();
    let elapsed = started.elapsed();
    let stats = runner.stats().snapshot();
    check_sane(&stats[0], elapsed, 2);
    check_sane(&stats[1], elapsed, 5);
    // The program saw the real clock: the slow task's TON ran about as
    // long as the run (its last run at most one interval before the end).
    let timer_ms = session.plc().read("c.t").unwrap();
    let plcrun::Value::Scalar(_, raw) = timer_ms else {
        panic!("TIME is a scalar")
    };
    let timer = Duration::from_nanos(raw);
    assert!(timer <= elapsed, "{timer:?} > {elapsed:?}");
    assert!(
        timer + Duration::from_millis(100) >= elapsed,
        "{timer:?} vs {elapsed:?}"
    );
    // The trace's time column is the real clock of each cycle.
    let trace = String::from_utf8(out.finish().unwrap()).unwrap();
    assert_eq!(trace.lines().count(), 301);
    // After the run the PLC is back on the virtual clock.
    assert!(session.plc().clock().is_virtual());
}

#[test]
fn a_task_too_slow_for_its_interval_counts_overruns_and_skips() {
    let src = "PROGRAM Count VAR_OUTPUT n : DINT; END_VAR n := n + 1; END_PROGRAM";
    let options = Options {
        cycle_time: 1_000_000,
        ..Options::default()
    };
    let mut session = Session::new(Plc::compile_files(&[("p.st", src)], &options).unwrap());
    // Every cycle takes 5 ms more than its 1 ms interval.
    session.set_cycle_hook(|_| std::thread::sleep(Duration::from_millis(5)));
    let mut runner = TaskRunner::real_time(session.plc());
    let started = Instant::now();
    runner
        .run(&mut session, Some(20), &mut csv_trace(&[]))
        .unwrap();
    let elapsed = started.elapsed();
    let s = &runner.stats().snapshot()[0];
    assert_eq!(s.cycles, 20);
    // About 5 missed activations per cycle, skipped: 20 cycles take about
    // 20 × 5 ms, not the 20 × 6 ms that queueing the misses would.
    assert!(s.overruns >= 4 * 19, "{s:?}");
    // Every activation counted is a millisecond that passed: no more than
    // the run lasted, and at least the 20 × 5 ms the hook slept. (The run
    // also prepares the real-time thread before its first cycle, which
    // can take tens of milliseconds on a loaded machine: no lower bound
    // from the elapsed time.)
    let activations = (s.cycles + s.overruns) as f64;
    assert!(
        activations <= expected_activations(elapsed, 1) + 1.0,
        "{s:?} in {elapsed:?}"
    );
    assert!(activations >= 5.0 * 19.0, "{s:?} in {elapsed:?}");
    assert_eq!(session.plc().read("n").unwrap().to_literal(), "20");
}

#[test]
fn the_stop_handle_ends_a_real_time_run_on_another_thread() {
    let plc = plc();
    let stop = plc.stop_handle();
    let runner = TaskRunner::real_time(&plc);
    let stats = runner.stats();
    let mut session = Session::new(plc);
    session.set_trace(&["a.n"]).unwrap();
    let thread = runner.spawn(session, None, csv_trace(&["a.n"]));
    std::thread::sleep(Duration::from_millis(60));
    // Readable while it runs.
    assert!(stats.snapshot()[0].cycles > 0, "{:?}", stats.snapshot());
    assert!(!thread.is_finished());
    let asked = Instant::now();
    stop.stop();
    let outcome = thread.join();
    let took = asked.elapsed();
    assert!(took < Duration::from_millis(500), "stopped after {took:?}");
    outcome.result.unwrap();
    // Every cycle that ran has its row.
    let cycles = outcome.session.plc().cycle();
    let trace = String::from_utf8(outcome.trace.finish().unwrap()).unwrap();
    assert_eq!(trace.lines().count() as u64, cycles + 1);
    let last = trace.lines().last().unwrap();
    assert!(last.starts_with(&format!("{},", cycles - 1)), "{last}");
}

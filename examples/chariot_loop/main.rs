//! CHARIOT in a closed loop you can watch: `cargo run --example chariot_loop`.
//!
//! programs/chariot.sfc runs on the virtual clock (10 ms cycles) against a
//! simulated cart (plant.rs): the operator presses the start button at
//! station A, the cart runs to B, waits (1 s here instead of the
//! program's 10 minutes), comes back. The example prints every change of
//! the signals and fails (exit status 1) unless the cart makes at least
//! four round trips in 20 s without crashing.
//!
//! `-- --realtime [--seconds S] [--quick]` runs the same loop on the wall
//! clock for S seconds (default 10; realtime.rs), printing the changes as
//! they happen and, at the end, the task's statistics and the number of
//! round trips; `--quick` uses a shorter track and wait (a round trip in
//! about 0.9 s instead of 4.5 s).

mod closed_loop;
mod plant;
mod realtime;

use std::process::ExitCode;
use std::time::Duration;

/// 20 s of virtual time.
const CYCLES: u64 = 2000;
/// One round trip takes 4.5 s (0.5 s loading, 1.5 s each way, 1 s at B).
const MIN_ROUND_TRIPS: usize = 4;
/// The real-time run's default length, in seconds.
const DEFAULT_SECONDS: f64 = 10.0;

/// The command line: `[--realtime [--seconds S] [--quick]]`.
struct Args {
    realtime: bool,
    seconds: f64,
    quick: bool,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        realtime: false,
        seconds: DEFAULT_SECONDS,
        quick: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--realtime" => args.realtime = true,
            "--quick" => args.quick = true,
            "--seconds" => {
                let text = it.next().ok_or("--seconds needs a value")?;
                args.seconds = text
                    .parse()
                    .ok()
                    .filter(|s: &f64| s.is_finite() && *s > 0.0)
                    .ok_or(format!("--seconds `{text}`: expected a positive number"))?;
            }
            other => {
                return Err(format!(
                    "unknown argument `{other}` (expected --realtime, --seconds S, --quick)"
                ));
            }
        }
    }
    if !args.realtime && (args.quick || args.seconds != DEFAULT_SECONDS) {
        return Err("--seconds and --quick go with --realtime".into());
    }
    Ok(args)
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(args) => args,
        Err(e) => {
            eprintln!("chariot_loop: {e}");
            return ExitCode::FAILURE;
        }
    };
    if args.realtime {
        return real_time(&args);
    }
    let run = match closed_loop::run(CYCLES) {
        Ok(run) => run,
        Err(e) => {
            eprintln!("chariot_loop: {e}");
            return ExitCode::FAILURE;
        }
    };
    println!("CHARIOT closed loop, {CYCLES} cycles of 10 ms (virtual time)");
    for event in &run.events {
        println!("{event}");
    }
    let trips = run.round_trips.len();
    println!(
        "{trips} round trips, back at A in cycles {:?}",
        run.round_trips
    );
    if trips < MIN_ROUND_TRIPS {
        eprintln!("chariot_loop: expected at least {MIN_ROUND_TRIPS} round trips");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}

/// The loop on the wall clock: fails on a crash or a fault, or when a run
/// long enough for two round trips made none.
fn real_time(args: &Args) -> ExitCode {
    let setup = if args.quick {
        realtime::Setup::quick()
    } else {
        realtime::Setup::standard()
    };
    let round_trip_s = if args.quick { 0.9 } else { 4.5 };
    println!(
        "CHARIOT closed loop, {} s on the wall clock, cycles of {} ms",
        args.seconds,
        setup.cycle_time_ns / 1_000_000
    );
    let wall = Duration::from_secs_f64(args.seconds);
    let run = match realtime::run(setup, wall, |event| println!("{event}")) {
        Ok(run) => run,
        Err(e) => {
            eprintln!("chariot_loop: {e}");
            return ExitCode::FAILURE;
        }
    };
    print!("{}", plcrun::format_stats_table(&run.stats));
    let trips = run.round_trips.len();
    println!(
        "{trips} round trips, back at A in cycles {:?}",
        run.round_trips
    );
    if trips == 0 && args.seconds >= 2.0 * round_trip_s {
        eprintln!("chariot_loop: no round trip in {} s", args.seconds);
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}

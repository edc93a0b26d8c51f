//! CHARIOT in a closed loop you can watch: `cargo run --example chariot_loop`.
//!
//! programs/chariot.sfc runs on the virtual clock (10 ms cycles) against a
//! simulated cart (plant.rs): the operator presses the start button at
//! station A, the cart runs to B, waits (1 s here instead of the
//! program's 10 minutes), comes back. The example prints every change of
//! the signals and fails (exit status 1) unless the cart makes at least
//! four round trips in 20 s without crashing.

mod closed_loop;
mod plant;

use std::process::ExitCode;

/// 20 s of virtual time.
const CYCLES: u64 = 2000;
/// One round trip takes 4.5 s (0.5 s loading, 1.5 s each way, 1 s at B).
const MIN_ROUND_TRIPS: usize = 4;

fn main() -> ExitCode {
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

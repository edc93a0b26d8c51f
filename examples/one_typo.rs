//! Prints the "one typo, one error" figure (docs/robustness.md): every
//! token of every program in `programs/` and of the generated programs is
//! deleted, duplicated and replaced in turn, and the proportion of
//! mutants with exactly one error on the altered line is printed.
//!
//! `cargo run --release --example one_typo [--stride K] [--misses N]`
//! (`--stride K`: every K-th token only).

#[path = "../tests/support/one_typo.rs"]
mod one_typo;

fn main() {
    let option = |name: &str, default: usize| -> usize {
        std::env::args()
            .skip_while(|a| a != name)
            .nth(1)
            .and_then(|n| n.parse().ok())
            .unwrap_or(default)
    };
    let show = option("--misses", 0);
    let stride = option("--stride", 1).max(1);
    let mut total = one_typo::Tally::default();
    let mut programs = one_typo::shipped_programs();
    programs.extend(one_typo::generated_programs(6));
    for (name, text) in &programs {
        let tally = one_typo::measure(name, text, stride, 0);
        println!(
            "{name:32} {:6} mutants  {:5} silent  {:5} one error on the line  {:6.1} %",
            tally.one + tally.silent + tally.miss,
            tally.silent,
            tally.one,
            tally.percent()
        );
        total.add(&tally);
    }
    println!(
        "total: {} mutants, {} silent, {} of {} detected with exactly one error on the altered line: {:.1} %",
        total.one + total.silent + total.miss,
        total.silent,
        total.one,
        total.detected(),
        total.percent()
    );
    for example in total.examples.iter().take(show) {
        println!("  miss: {example}");
    }
}

//! What retained data costs: a program with 1 000 retained values (800
//! DINT, 150 REAL, 50 STRING[16]) run cycle by cycle
//!
//! - without saving (the baseline),
//! - handing a snapshot to a `RetainSaver` after every cycle (the cost on
//!   the cycle's path, with the writer thread writing meanwhile),
//! - `RetainSaver::offer` alone (the snapshot copy),
//! - the writer thread's time per file (JSON text, write, fsync, rename,
//!   fsync of the directory), to a file in `target/` and, if present, on
//!   `/dev/shm` (no disk: text and write only),
//! - `Plc::save_retain`, the synchronous save.
//!
//! Usage: `cargo bench --bench retain` (prints medians over batches).

use plcrun::{Options, Plc, RetainSaver};
use std::path::Path;
use std::time::Instant;

const SOURCE: &str = "
PROGRAM P
VAR RETAIN
  counts : ARRAY[1..800] OF DINT;
  levels : ARRAY[1..150] OF REAL;
  labels : ARRAY[1..50] OF STRING[16];
END_VAR
VAR i : INT; k : DINT; END_VAR
k := k + 1;
FOR i := 1 TO 800 DO counts[i] := counts[i] + i; END_FOR;
FOR i := 1 TO 150 DO levels[i] := levels[i] + 0.25; END_FOR;
labels[(k MOD 50) + 1] := DINT_TO_STRING(k);
END_PROGRAM
";

fn compile() -> Plc {
    Plc::compile_files(&[("retain_bench.st", SOURCE)], &Options::default()).expect("compiles")
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// Median over `batches` of the time per iteration of `f` run `n` times, in ns.
fn per_iteration(batches: usize, n: u32, mut f: impl FnMut()) -> f64 {
    let times = (0..batches)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..n {
                f();
            }
            t.elapsed().as_nanos() as f64 / n as f64
        })
        .collect();
    median(times)
}

/// Cycles with a snapshot offered after every `every`-th, to a saver
/// writing `path`: (ns per cycle, ns per offer alone, files written,
/// writer ns per file).
fn with_saver(plc: &mut Plc, path: &Path, every: u64) -> (f64, f64, u64, f64) {
    let saver = RetainSaver::new(plc, path).expect("saver");
    let with_offer = per_iteration(15, 2000, || {
        plc.run_cycle().expect("runs");
        if plc.cycle().is_multiple_of(every) {
            saver.offer(plc).expect("own plc");
        }
    });
    let offer = per_iteration(15, 2000, || saver.offer(plc).expect("own plc"));
    saver.flush();
    let saves = saver.saves();
    let per_save = saver.writer_time().as_nanos() as f64 / saves.max(1) as f64;
    saver.finish().expect("saved");
    (with_offer, offer, saves, per_save)
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/retain-bench");
    std::fs::create_dir_all(&dir).expect("target/retain-bench");
    let mut plc = compile();
    assert_eq!(plc.retained().len(), 1000);

    let cycle = per_iteration(15, 2000, || plc.run_cycle().expect("runs"));
    let disk = dir.join("every_cycle.json");
    let (with_offer, offer, saves, per_save) = with_saver(&mut plc, &disk, 1);
    let size = std::fs::metadata(&disk).map(|m| m.len()).unwrap_or(0);
    println!("retained values: 1000 (800 DINT, 150 REAL, 50 STRING[16]); file {size} bytes");
    println!("run_cycle alone:                       {cycle:>10.0} ns/cycle");
    println!("run_cycle + offer (file in target/):   {with_offer:>10.0} ns/cycle");
    println!(
        "  difference:                          {:>10.0} ns/cycle",
        with_offer - cycle
    );
    println!("RetainSaver::offer alone (snapshot):   {offer:>10.0} ns");
    println!("writer per save, target/ (fsync):      {per_save:>10.0} ns ({saves} files)");
    let shm = Path::new("/dev/shm");
    if shm.is_dir() {
        let mem = shm.join(format!("plcrun-retain-bench-{}.json", std::process::id()));
        let (with_offer, offer, saves, per_save) = with_saver(&mut plc, &mem, 1);
        let _ = std::fs::remove_file(&mem);
        println!("run_cycle + offer (file on /dev/shm):  {with_offer:>10.0} ns/cycle");
        println!("RetainSaver::offer alone (snapshot):   {offer:>10.0} ns");
        println!("writer per save, /dev/shm (no disk):   {per_save:>10.0} ns ({saves} files)");
    }
    let (every10, _, saves, _) = with_saver(&mut plc, &disk, 10);
    println!("run_cycle + offer every 10th cycle:    {every10:>10.0} ns/cycle ({saves} files)");
    let file = dir.join("direct.json");
    let sync = per_iteration(9, 20, || plc.save_retain(&file).expect("saves"));
    println!("Plc::save_retain (synchronous, fsync): {sync:>10.0} ns/save");
}

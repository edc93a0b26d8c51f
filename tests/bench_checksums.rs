//! The benchmark programs give the checksums the benchmark suite publishes
//! (benches/README.md): an end-to-end check of the executor's fused
//! instructions on real work.

use rstest::rstest;

#[rstest]
#[case("bench_a_bool_logic.st", include_str!("../benches/programs/bench_a_bool_logic.st"), 1000, 310000)]
#[case("bench_b_int_sieve.st", include_str!("../benches/programs/bench_b_int_sieve.st"), 1000, 122909001)]
#[case("bench_c_fb_unrolled.st", include_str!("../benches/programs/bench_c_fb_unrolled.st"), 1000, 50281112)]
#[case("bench_c_fb_array.st", include_str!("../benches/programs/bench_c_fb_array.st"), 1000, 50281112)]
#[case("bench_d_real_math.st", include_str!("../benches/programs/bench_d_real_math.st"), 1000, 466426)]
fn benchmark_programs_reach_the_published_checksums(
    #[case] name: &str,
    #[case] text: &str,
    #[case] cycles: u64,
    #[case] checksum: i64,
) {
    let mut plc = plcrun::Plc::compile_files(&[(name, text)], &plcrun::Options::default())
        .unwrap_or_else(|e| panic!("{name}:\n{e}"));
    for _ in 0..cycles {
        plc.run_cycle().unwrap_or_else(|f| panic!("{name}: {f}"));
    }
    let got = plc.read_i64("checksum").expect("checksum");
    // REAL rounding may move bench d by one (suite's README).
    let tolerance = if name.contains("real") { 1 } else { 0 };
    assert!(
        (got - checksum).abs() <= tolerance,
        "{name}: {got}, expected {checksum}"
    );
}

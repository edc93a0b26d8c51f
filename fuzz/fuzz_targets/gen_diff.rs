#![no_main]
//! Fuzz target `gen_diff`: see `plcrun_fuzz::targets::gen_diff`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::gen_diff(data));

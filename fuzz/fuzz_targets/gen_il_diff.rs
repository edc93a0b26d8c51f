#![no_main]
//! Fuzz target `gen_il_diff`: see `plcrun_fuzz::targets::gen_il_diff`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::gen_il_diff(data));

#![no_main]
//! Fuzz target `run`: see `plcrun_fuzz::targets::run`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::run(data));

#![no_main]
//! Fuzz target `check`: see `plcrun_fuzz::targets::check`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::check(data));

#![no_main]
//! Fuzz target `plcopen`: see `plcrun_fuzz::targets::plcopen`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::plcopen(data));

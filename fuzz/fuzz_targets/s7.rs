#![no_main]
//! Fuzz target `s7`: see `plcrun_fuzz::targets::s7`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::s7(data));

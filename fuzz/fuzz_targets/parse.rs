#![no_main]
//! Fuzz target `parse`: see `plcrun_fuzz::targets::parse`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::parse(data));

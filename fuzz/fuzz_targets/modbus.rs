#![no_main]
//! Fuzz target `modbus`: see `plcrun_fuzz::targets::modbus`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::modbus(data));

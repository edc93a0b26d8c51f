#![no_main]
//! Fuzz target `opcua_write`: see `plcrun_fuzz::targets::opcua_write`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::opcua_write(data));

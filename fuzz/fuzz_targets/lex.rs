#![no_main]
//! Fuzz target `lex`: see `plcrun_fuzz::targets::lex`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::lex(data));

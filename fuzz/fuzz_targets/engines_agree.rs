#![no_main]
//! Fuzz target `engines_agree`: see `plcrun_fuzz::targets::engines_agree`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| plcrun_fuzz::targets::engines_agree(data));

//! The bodies of plcrun's fuzz targets, the structure-aware ST and IL
//! generators and the optimized-vs-unoptimized differential check. The
//! libFuzzer targets (`fuzz_targets/`) are one line each;
//! `tests/fuzz_smoke.rs` in the main crate includes these same files to
//! run them on stable Rust.

pub mod differential;
pub mod il_gen;
pub mod seeds;
pub mod st_gen;
pub mod targets;

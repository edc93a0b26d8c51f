//! Every integration test of the package but four, in one test binary.
//!
//! One binary instead of a hundred: each test binary links the whole
//! library and its dependencies (the OPC UA stack among them), so a hundred
//! of them took most of CI's link time and tens of gigabytes of disk.
//! Each file stays a module of its own (`cargo test --test suite opcua_cli::`
//! runs one). The four that stay apart are listed in Cargo.toml with why;
//! tests/suite_membership.rs checks that no file under tests/ is left out.

/// The helpers the test files share, each compiled once.
mod support {
    pub mod access_diags;
    pub mod arith_model;
    pub mod cli;
    #[cfg(feature = "cli")]
    pub mod dap_client;
    #[cfg(feature = "cli")]
    pub mod framed;
    pub mod grafcet_models;
    pub mod graphic;
    #[cfg(feature = "cli")]
    pub mod http;
    pub mod library;
    #[cfg(feature = "cli")]
    pub mod lsp_client;
    pub mod one_typo;
    #[cfg(feature = "opcua")]
    pub mod opcua_client;
    pub mod plc;
    pub mod rng;
    pub mod s7_table_models;
    pub mod seed_models;
    pub mod sfc_run;
    pub mod trace_text;
    pub mod twincat;
}

/// The fuzz targets' bodies and generators (fuzz/src), which the fuzz
/// smoke and the fuzz regressions run on stable Rust.
#[path = "../fuzz/src"]
#[allow(dead_code)]
mod fuzz {
    pub mod differential;
    pub mod il_gen;
    pub mod seeds;
    pub mod st_gen;
    pub mod targets;
}

#[path = "addressing.rs"]
mod addressing;
#[path = "any_params.rs"]
mod any_params;
#[path = "architecture.rs"]
mod architecture;
#[path = "arith_conformance.rs"]
mod arith_conformance;
#[path = "assert_nested.rs"]
mod assert_nested;
#[path = "assertion_shadowing.rs"]
mod assertion_shadowing;
#[path = "assignment_expressions.rs"]
mod assignment_expressions;
#[path = "bench_checksums.rs"]
mod bench_checksums;
#[path = "bounds_proofs.rs"]
mod bounds_proofs;
#[path = "chariot_closed_loop.rs"]
mod chariot_closed_loop;
#[cfg(feature = "cli")]
#[path = "cli.rs"]
mod cli;
#[cfg(feature = "cli")]
#[path = "cli_force.rs"]
mod cli_force;
#[cfg(feature = "cli")]
#[path = "cli_output.rs"]
mod cli_output;
#[cfg(feature = "cli")]
#[path = "cli_reading.rs"]
mod cli_reading;
#[path = "codesys_compat.rs"]
mod codesys_compat;
#[path = "codesys_dialect.rs"]
mod codesys_dialect;
#[path = "codesys_export.rs"]
mod codesys_export;
#[path = "codesys_v3_forms.rs"]
mod codesys_v3_forms;
#[path = "compare.rs"]
mod compare;
#[cfg(feature = "cli")]
#[path = "compare_cli.rs"]
mod compare_cli;
#[path = "compat_left.rs"]
mod compat_left;
#[path = "constructs_enumerated.rs"]
mod constructs_enumerated;
#[cfg(feature = "cli")]
#[path = "debug_adapter.rs"]
mod debug_adapter;
#[path = "declaration_order.rs"]
mod declaration_order;
#[cfg(feature = "cli")]
#[path = "diagnostics.rs"]
mod diagnostics;
#[path = "draw.rs"]
mod draw;
#[cfg(feature = "cli")]
#[path = "draw_cli.rs"]
mod draw_cli;
#[path = "element_addresses.rs"]
mod element_addresses;
#[path = "embedding_api.rs"]
mod embedding_api;
#[path = "en_parameters.rs"]
mod en_parameters;
#[path = "encoding.rs"]
mod encoding;
#[path = "eno_bodies.rs"]
mod eno_bodies;
#[path = "fault_path.rs"]
mod fault_path;
#[cfg(feature = "cli")]
#[path = "fault_path_cli.rs"]
mod fault_path_cli;
#[path = "fb_init.rs"]
mod fb_init;
#[path = "fb_internals.rs"]
mod fb_internals;
#[path = "fb_self_reference.rs"]
mod fb_self_reference;
#[path = "fb_values.rs"]
mod fb_values;
#[path = "forcing.rs"]
mod forcing;
#[path = "fuzz_regressions.rs"]
mod fuzz_regressions;
#[path = "fuzz_smoke.rs"]
mod fuzz_smoke;
#[cfg(feature = "cli")]
#[path = "golden_programs.rs"]
mod golden_programs;
#[cfg(feature = "cli")]
#[path = "grafcet_cli.rs"]
mod grafcet_cli;
#[path = "grafcet_mode.rs"]
mod grafcet_mode;
#[path = "grafcet_models.rs"]
mod grafcet_models;
#[path = "host_blocks.rs"]
mod host_blocks;
#[path = "il_literal_join.rs"]
mod il_literal_join;
#[path = "il_operators.rs"]
mod il_operators;
#[path = "implicit_checks.rs"]
mod implicit_checks;
#[path = "implicit_int_conversions.rs"]
mod implicit_int_conversions;
#[path = "input_qualifiers.rs"]
mod input_qualifiers;
#[path = "input_writes.rs"]
mod input_writes;
#[path = "life_cycle.rs"]
mod life_cycle;
#[cfg(feature = "cli")]
#[path = "limits.rs"]
mod limits;
#[path = "loop_superinstructions.rs"]
mod loop_superinstructions;
#[cfg(feature = "cli")]
#[path = "lsp.rs"]
mod lsp;
#[path = "method_local_constants.rs"]
mod method_local_constants;
#[path = "modbus.rs"]
mod modbus;
#[cfg(feature = "cli")]
#[path = "modbus_cli.rs"]
mod modbus_cli;
#[path = "modbus_openplc.rs"]
mod modbus_openplc;
#[path = "native_engine.rs"]
mod native_engine;
#[path = "native_reference.rs"]
mod native_reference;
#[path = "native_registers.rs"]
mod native_registers;
#[path = "one_typo.rs"]
mod one_typo;
#[path = "online_change.rs"]
mod online_change;
#[cfg(feature = "cli")]
#[path = "online_change_cli.rs"]
mod online_change_cli;
#[path = "oop.rs"]
mod oop;
#[path = "oop_properties.rs"]
mod oop_properties;
#[path = "oop_reentry.rs"]
mod oop_reentry;
#[path = "oop_values.rs"]
mod oop_values;
#[cfg(all(feature = "cli", feature = "opcua"))]
#[path = "opcua_cli.rs"]
mod opcua_cli;
#[cfg(all(feature = "cli", feature = "opcua"))]
#[path = "opcua_python.rs"]
mod opcua_python;
#[cfg(feature = "opcua")]
#[path = "opcua_server.rs"]
mod opcua_server;
#[path = "open_arrays.rs"]
mod open_arrays;
#[cfg(feature = "cli")]
#[path = "packaging.rs"]
mod packaging;
#[path = "partial_access.rs"]
mod partial_access;
#[path = "plcopen.rs"]
mod plcopen;
#[cfg(feature = "cli")]
#[path = "plcopen_cli.rs"]
mod plcopen_cli;
#[path = "plcopen_codesys_members.rs"]
mod plcopen_codesys_members;
#[path = "plcopen_config_vars.rs"]
mod plcopen_config_vars;
#[path = "plcopen_export_graphic.rs"]
mod plcopen_export_graphic;
#[path = "plcopen_fbd.rs"]
mod plcopen_fbd;
#[path = "plcopen_ld.rs"]
mod plcopen_ld;
#[path = "pointer_byte_views.rs"]
mod pointer_byte_views;
#[path = "pointers.rs"]
mod pointers;
#[path = "process_image.rs"]
mod process_image;
#[path = "progress_reports.rs"]
mod progress_reports;
#[cfg(feature = "cli")]
#[path = "project_commands.rs"]
mod project_commands;
#[cfg(feature = "cli")]
#[path = "project_file.rs"]
mod project_file;
#[path = "reference_calls.rs"]
mod reference_calls;
#[path = "references.rs"]
mod references;
#[path = "refused_declarations.rs"]
mod refused_declarations;
#[cfg(feature = "cli")]
#[path = "reload_cli.rs"]
mod reload_cli;
#[path = "retain.rs"]
mod retain;
#[cfg(feature = "cli")]
#[path = "retain_cli.rs"]
mod retain_cli;
#[cfg(feature = "cli")]
#[path = "runtime_faults.rs"]
mod runtime_faults;
#[path = "s7_200.rs"]
mod s7_200;
#[path = "s7_seed_as_printed.rs"]
mod s7_seed_as_printed;
#[path = "s7_seed_examples.rs"]
mod s7_seed_examples;
#[path = "seed_programs.rs"]
mod seed_programs;
#[cfg(feature = "cli")]
#[path = "serve_cli.rs"]
mod serve_cli;
#[cfg(feature = "cli")]
#[path = "sfc_chariot.rs"]
mod sfc_chariot;
#[path = "sfc_equivalence.rs"]
mod sfc_equivalence;
#[path = "sfc_qualifiers.rs"]
mod sfc_qualifiers;
#[path = "sfc_semantics.rs"]
mod sfc_semantics;
#[cfg(feature = "cli")]
#[path = "source_cli.rs"]
mod source_cli;
#[path = "source_files.rs"]
mod source_files;
#[path = "st_language.rs"]
mod st_language;
#[path = "std_fbs.rs"]
mod std_fbs;
#[path = "std_functions.rs"]
mod std_functions;
#[path = "std_names.rs"]
mod std_names;
#[path = "strict.rs"]
mod strict;
#[path = "suite_membership.rs"]
mod suite_membership;
#[path = "syntax/main.rs"]
mod syntax;
#[path = "tcunit_any_types.rs"]
mod tcunit_any_types;
#[path = "tcunit_counts.rs"]
mod tcunit_counts;
#[path = "tcunit_disabled.rs"]
mod tcunit_disabled;
#[cfg(feature = "cli")]
#[path = "tcunit_runner.rs"]
mod tcunit_runner;
#[path = "test_runner.rs"]
mod test_runner;
#[path = "test_runner_all_errors.rs"]
mod test_runner_all_errors;
#[cfg(feature = "cli")]
#[path = "test_runner_cli.rs"]
mod test_runner_cli;
#[path = "test_runner_enums.rs"]
mod test_runner_enums;
#[path = "timer_pt_changes.rs"]
mod timer_pt_changes;
#[path = "try_catch.rs"]
mod try_catch;
#[path = "twincat_ads_log.rs"]
mod twincat_ads_log;
#[cfg(feature = "cli")]
#[path = "twincat_event_logger.rs"]
mod twincat_event_logger;
#[path = "twincat_import.rs"]
mod twincat_import;
#[path = "twincat_json_dom.rs"]
mod twincat_json_dom;
#[path = "twincat_library_forms.rs"]
mod twincat_library_forms;
#[path = "twincat_memory.rs"]
mod twincat_memory;
#[path = "twincat_motion.rs"]
mod twincat_motion;
#[path = "twincat_pmps_forms.rs"]
mod twincat_pmps_forms;
#[path = "twincat_utilities.rs"]
mod twincat_utilities;
#[path = "typing_compat.rs"]
mod typing_compat;
#[path = "unions.rs"]
mod unions;
#[path = "var_config.rs"]
mod var_config;
#[path = "var_config_elements.rs"]
mod var_config_elements;
#[path = "variables.rs"]
mod variables;
#[cfg(feature = "cli")]
#[path = "vcd.rs"]
mod vcd;
#[cfg(feature = "cli")]
#[path = "web_browser.rs"]
mod web_browser;
#[cfg(feature = "cli")]
#[path = "web_cli.rs"]
mod web_cli;

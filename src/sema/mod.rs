//! Semantic analysis and lowering: resolves every name, types every
//! expression (IEC implicit widening only), folds constants, and emits the
//! typed IR. All diagnostics are collected; nothing stops at the first error.
//!
//! Three phases, each the only owner of what it builds:
//! 1. declarations (`declare`, `type_decl`, `layout`, `decl_consts`)
//!    build the `Model`: types, POU interfaces and layouts, globals,
//!    constants, enumeration values;
//! 2. bodies (`body` and the expression, statement, call, IL and SFC
//!    files) — one `BodyBuilder` per POU reads the model without
//!    changing it and appends code to the shared output tables
//!    (`Program`);
//! 3. linking (`link`) places memory, relocates and builds the image.
//!
//! A function block's instance size includes its temporaries, so the
//! declaration phase has an FB's body emitted as soon as an instance of it
//! is laid out, and then records the frame size in the model.

// Shared by the phases.
pub mod consts;
pub mod model;
mod program;

// Phase 1: declarations.
mod any_params;
mod const_order;
mod const_sizeof;
mod decl_consts;
mod declare;
mod global_instances;
mod implicit_int;
mod implicit_real;
mod incomplete_address;
mod inheritance_depth;
mod layout;
mod nesting;
mod self_ref_types;
mod sfc;
mod type_decl;

// Phase 2: one body builder per POU.
mod aggregate_copy;
mod aggregate_zero;
mod any_args;
pub(crate) mod assert_calls;
mod assert_enums;
mod assert_nested;
mod assert_shadow;
mod assert_tcunit;
mod assign_expr;
mod bcd_width;
mod binary;
mod bits_arith;
mod bits_neg;
mod body;
mod body_names;
mod bounds;
mod calls;
mod compat_typing;
mod computed_inits;
mod edge_inputs;
mod emit;
mod en_params;
mod eno_body;
mod eno_uses;
mod enum_int;
mod enum_qualified;
mod exception_code;
mod expr;
mod fb_copy;
mod fb_init_values;
mod fb_member_read;
mod fn_call;
mod for_loop;
mod grafcet_forcing;
mod il;
mod il_aggregate_results;
mod il_recovery;
mod implicit_bounds;
mod implicit_checks;
mod implicit_div;
mod implicit_range;
mod in_out_constant;
mod in_out_read;
mod input_write;
pub(crate) mod instance_calls;
mod int_bit_ops;
mod literal_widening;
mod memory_idioms;
mod mixed_args;
mod namespace_calls;
mod open_arrays;
mod partial_access;
mod place;
mod pointer_index;
mod pou_name;
mod raise_exception;
mod ref_inits;
mod refs;
mod sfc_emit;
mod short_circuit;
mod std_convert;
mod std_convert_dates;
mod std_numeric;
mod std_shadow;
mod std_strings;
mod std_typed_names;
mod stdfuncs;
mod stmt;
mod struct_returns;
mod suggest;
mod try_catch;
mod typeck;
mod undeclared;
mod unions;

// Phase 3: linking.
mod link;
mod oop;

use crate::diagnostics::Diagnostics;
use crate::ir::verify::VerifiedImage;
use crate::syntax::ast::CompilationUnit;

/// What to build.
#[derive(Debug, Clone, Default)]
pub struct CompileOptions {
    /// The PROGRAM to run when there is no CONFIGURATION (or to pick one).
    pub program: Option<String>,
    /// Cycle time in nanoseconds for the implicit task.
    pub cycle_time: i64,
    /// Only check; do not require a runnable program.
    pub check_only: bool,
    /// FUNCTIONs and FUNCTION_BLOCKs whose bodies the host provides (their
    /// declarations are among the sources, with empty bodies): each body
    /// becomes `Op::CallHost` with its index in this list.
    pub host_pous: Vec<String>,
    /// Charts follow IEC 60848 GRAFCET evolution (search for stability,
    /// forcing orders) instead of IEC 61131-3 SFC evolution.
    pub grafcet: bool,
    /// Most bytes of program data (variables, instances, constants) the
    /// image may hold; 0 means [`DEFAULT_MAX_DATA_BYTES`]. Beyond it: E120.
    pub max_data_bytes: usize,
    /// Compatibility-extension warnings (`W300`-`W399`) are errors
    /// (`--strict`).
    pub strict: bool,
    /// Emit only the plain instruction forms: no fused superinstructions
    /// and no bounds proofs (`Options::optimize` off), so that a program
    /// can be run both ways and the traces compared.
    pub unoptimized: bool,
    /// How direct addresses are numbered: decides which located
    /// variables overlap (W204).
    pub addressing: crate::address::Addressing,
    /// The files written in the CODESYS V3 / TwinCAT 3 dialect (TwinCAT
    /// project files, CODESYS PLCopen XML exports): the implicit integer
    /// conversions CODESYS makes (W490) are accepted in them only.
    pub codesys_files: Vec<crate::source::FileId>,
    /// Those of `codesys_files` but plcrun's own TwinCAT library: the
    /// user's TwinCAT code (STRING of 80 characters by default, W710, the
    /// project's implicit checks: implicit_checks.rs).
    pub checked_files: Vec<crate::source::FileId>,
    /// The files of library projects loaded with the application: no
    /// implicit check is called in them, as in TwinCAT.
    pub library_files: Vec<crate::source::FileId>,
}

/// Default limit of a program's data: 512 MiB (one instance or structure
/// may hold up to [`MAX_FRAME_SLOTS`], which is as much).
pub const DEFAULT_MAX_DATA_BYTES: usize = 512 << 20;

impl CompileOptions {
    /// The data limit in 8-byte slots (never above [`MAX_MEMORY_SLOTS`]).
    pub(crate) fn max_data_slots(&self) -> usize {
        let bytes = if self.max_data_bytes == 0 {
            DEFAULT_MAX_DATA_BYTES
        } else {
            self.max_data_bytes
        };
        (bytes / 8).clamp(1, MAX_MEMORY_SLOTS)
    }
}

/// Checks and lowers parsed files into a verified image. Returns `None` when
/// there were errors (all of them are in `diags`).
pub fn compile(
    units: &[CompilationUnit],
    options: &CompileOptions,
    diags: &mut Diagnostics,
) -> Option<VerifiedImage> {
    // The passes see what came before (parse errors stop the linking).
    let before = diags.len();
    let none = std::collections::HashSet::new();
    let (image, guards) = compile_pass(units, options, &none, diags);
    if guards.is_empty() {
        return image;
    }
    // Methods in a cycle of calls through interfaces: compiled again with
    // their re-entry guards (oop::reentry), in place of the first pass.
    diags.truncate(before);
    compile_pass(units, options, &guards, diags).0
}

/// One compilation, with re-entry guards in the `guarded` methods; also
/// returns the methods a cycle reaches that have none.
fn compile_pass(
    units: &[CompilationUnit],
    options: &CompileOptions,
    guarded: &std::collections::HashSet<String>,
    diags: &mut Diagnostics,
) -> (Option<VerifiedImage>, std::collections::HashSet<String>) {
    let none = std::collections::HashSet::new();
    if let Some(too_deep) = inheritance_depth::check(units) {
        // Lowering would copy the inherited members n² times: refuse first.
        diags.push(too_deep);
        return (None, none);
    }
    en_params::check(units, diags);
    // Instances whose blocks declare FB_init or FB_exit: hidden methods
    // call them.
    let with_init = instance_calls::with_instance_calls(units, diags);
    let units = with_init.as_deref().unwrap_or(units);
    let lowered = oop::lower::lower(units, guarded, diags);
    let units = lowered.as_ref().map_or(units, |(u, _)| u.as_slice());
    if let Some(too_deep) = nesting::check(units) {
        // The declaration phase would recurse that deep: refuse first.
        diags.push(too_deep);
        return (None, none);
    }
    // POUs whose body uses ENO declare it (a copy only when one does).
    let with_eno = eno_body::with_implicit_eno(units, diags);
    let units = with_eno.as_deref().unwrap_or(units);
    let mut declarer = declare::Declarer::new(units, diags);
    declarer.set_host_pous(&options.host_pous);
    declarer.set_grafcet(options.grafcet);
    declarer.set_codesys_files(&options.codesys_files);
    declarer.set_checked_files(&options.checked_files);
    declarer.set_library_files(&options.library_files);
    declarer.set_data_limit(options.max_data_slots());
    if let Some((_, info)) = lowered.as_ref() {
        oop::methods::allocate(&mut declarer, info.clone());
    }
    declarer.set_unoptimized(options.unoptimized);
    declarer.declare_all();
    let declared = declarer.finish();
    let (image, request) = link::link(units, declared, options, guarded, diags);
    let image = if diags.has_errors() { None } else { image };
    (image, request)
}

/// Upper bound of the whole PLC memory, in 8-byte slots (2 GiB).
pub const MAX_MEMORY_SLOTS: usize = 256 << 20;

/// Upper bound of one POU instance or structure, in slots.
pub const MAX_FRAME_SLOTS: u32 = 64 << 20;

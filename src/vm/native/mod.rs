//! The native tier (`--engine native`): verified code blocks compiled to
//! machine code with Cranelift, the interpreter kept as the reference and
//! as the fallback for every block the tier cannot compile
//! (docs/adr/0009-native-tier.md).
//!
//! A block is compiled only when every one of its instructions is
//! supported ([`support`]); otherwise the whole block runs in the
//! interpreter, and the [`NativeReport`] names the first instruction that
//! kept it there. Compiled code keeps the interpreter's memory: frame
//! slots in the machine's one `Vec<u64>`, read and written at the offsets
//! the verifier proved inside the frame. Faults leave the machine code
//! through helpers that build the same [`crate::vm::Fault`] the
//! interpreter would (same kind, block, instruction), so the runtime's
//! location, cycle and call-stack reporting is shared.

#[cfg(feature = "native")]
mod code_memory;
#[cfg(feature = "native")]
mod compile;
#[cfg(feature = "native")]
mod ctx;
mod engine;
#[cfg(feature = "native")]
mod helpers;
#[cfg(feature = "native")]
mod lower;
mod report;
#[cfg(feature = "native")]
mod support;

#[cfg(feature = "native")]
pub(crate) use compile::{Compiled, compile};
#[cfg(feature = "native")]
pub(crate) use ctx::enter;
pub use engine::{Engine, UnknownEngine};
pub use report::{NativeFallback, NativeReport};

/// What `--engine native` does with `image` in a build without the
/// `native` feature: every block stays in the interpreter, and the report
/// says why.
#[cfg(not(feature = "native"))]
pub(crate) fn unavailable(image: &crate::ir::image::Image) -> NativeReport {
    NativeReport {
        fell_back: image
            .codes
            .iter()
            .map(|b| NativeFallback {
                block: b.name.clone(),
                reason: "this build has no native tier (cargo feature `native`)".into(),
            })
            .collect(),
        ..NativeReport::default()
    }
}

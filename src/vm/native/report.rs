//! What the native tier made of an image: which blocks run as machine
//! code, which stayed in the interpreter and why, and what it cost.

use std::fmt;
use std::time::Duration;

/// The outcome of compiling a program's code blocks for
/// [`crate::Engine::Native`] ([`crate::Plc::native_report`]).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct NativeReport {
    /// Names of the blocks that run as machine code.
    pub compiled: Vec<String>,
    /// The blocks that run in the interpreter, each with the reason.
    pub fell_back: Vec<NativeFallback>,
    /// Bytes of machine code generated (the executable memory mapped for
    /// it is this rounded up to whole pages).
    pub code_bytes: usize,
    /// Wall time spent translating and compiling.
    pub compile_time: Duration,
}

/// One code block the native tier left to the interpreter.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NativeFallback {
    /// The block (POU, or `POU.action`).
    pub block: String,
    /// Why: the first instruction the tier does not compile, or what else
    /// kept the block out (e.g. a build without the `native` feature).
    pub reason: String,
}

impl fmt::Display for NativeReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "native: {} block(s) compiled, {} in the interpreter; {} bytes of code in {:.1} ms",
            self.compiled.len(),
            self.fell_back.len(),
            self.code_bytes,
            self.compile_time.as_secs_f64() * 1e3
        )?;
        for fb in &self.fell_back {
            writeln!(f, "  interpreted: {}: {}", fb.block, fb.reason)?;
        }
        Ok(())
    }
}

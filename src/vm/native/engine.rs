//! The choice of executor (`--engine`, [`crate::Options::engine`]).

use std::fmt;
use std::str::FromStr;

/// Which executor runs a program's code blocks.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum Engine {
    /// The interpreter (the reference, and the default).
    #[default]
    Interp,
    /// Machine code compiled with Cranelift when the program is loaded
    /// (docs/adr/0009-native-tier.md): every code block whose
    /// instructions the tier supports runs natively, every other block in
    /// the interpreter, with the same results and faults.
    /// [`crate::Plc::native_report`] says which blocks compiled. A build
    /// without the `native` feature runs everything in the interpreter
    /// and says so there.
    Native,
}

/// `--engine` named no engine.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownEngine(pub String);

impl fmt::Display for UnknownEngine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown engine `{}` (use interp or native)", self.0)
    }
}

impl std::error::Error for UnknownEngine {}

impl FromStr for Engine {
    type Err = UnknownEngine;

    /// Reads `interp` (or `interpreter`) or `native`, ignoring case.
    ///
    /// ```
    /// use plcrun::Engine;
    /// assert_eq!("native".parse(), Ok(Engine::Native));
    /// assert_eq!("Interp".parse(), Ok(Engine::Interp));
    /// assert!("jit".parse::<Engine>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "interp" | "interpreter" => Ok(Engine::Interp),
            "native" => Ok(Engine::Native),
            _ => Err(UnknownEngine(s.to_string())),
        }
    }
}

impl fmt::Display for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Engine::Interp => "interp",
            Engine::Native => "native",
        })
    }
}

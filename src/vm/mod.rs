//! The interpreter: executes IR code blocks over one flat slot memory.
//!
//! The executor resolves nothing at run time: every operand is a slot index
//! relative to the frame base, every operation carries its type. Faults
//! (division by zero, index out of range, conversion overflow, watchdog)
//! stop execution and report the code block and instruction, which the
//! runtime maps back to a source location.
//!
//! Only a [`VerifiedImage`] can be run: the executor's unchecked frame
//! accesses are sound because `ir::verify` accepted every instruction
//! (docs/adr/0004-verified-then-unchecked-execution.md).

mod chart;
mod exec;
mod fault;
mod host;
mod string_ops;
mod strings;

pub use fault::{Fault, FaultKind, HostFailure};
pub(crate) use host::{HostDispatch, HostFrame, HostLink};
pub use strings::PlcString;

use crate::ir::op::CodeIdx;
use crate::ir::verify::VerifiedImage;
use std::time::{Duration, Instant};

/// How many backward jumps run between two looks at the wall clock.
pub(crate) const WATCHDOG_STRIDE: u32 = 4096;

/// The mutable state of a running PLC: memory, strings, clock, watchdog.
#[derive(Debug, Clone)]
pub struct Machine {
    /// All slots (globals, program instances, FB instances, function frames).
    pub(crate) mem: Vec<u64>,
    /// String variables, indexed by the string id a slot holds.
    pub(crate) strings: Vec<PlcString>,
    /// The current cycle's clock value in nanoseconds.
    pub(crate) now: i64,
    watchdog: Option<Duration>,
    deadline: Option<Instant>,
    /// Runs the bodies of host-registered POUs (`Op::CallHost`).
    pub(crate) host: HostLink,
}

impl Machine {
    /// A machine holding the image's initial memory.
    pub fn new(image: &VerifiedImage) -> Machine {
        Machine {
            mem: image.memory.clone(),
            strings: image
                .strings
                .iter()
                .map(|s| PlcString::new(&s.init, s.max, s.wide))
                .collect(),
            now: 0,
            watchdog: None,
            deadline: None,
            host: HostLink::default(),
        }
    }

    /// Sets the wall-clock limit for one cycle (`None` disables it).
    pub fn set_watchdog(&mut self, limit: Option<Duration>) {
        self.watchdog = limit;
    }

    /// Starts the watchdog for a new cycle. The wall clock is first read
    /// when the cycle has taken `WATCHDOG_STRIDE` backward jumps (a few
    /// microseconds of looping), so cycles without long loops never pay for
    /// reading it; straight-line code always terminates.
    pub fn start_cycle(&mut self) {
        self.deadline = None;
    }

    /// Runs code block `code` with frame base `base` (a frame outside
    /// memory faults with `BadAddress`).
    pub fn run(&mut self, image: &VerifiedImage, code: CodeIdx, base: u32) -> Result<(), Fault> {
        exec::run(self, image.image(), code, base as usize)
    }

    /// Called every `WATCHDOG_STRIDE` backward jumps of one block: true
    /// when the cycle has run out of time.
    #[cold]
    fn watchdog_expired(&mut self) -> bool {
        let Some(limit) = self.watchdog else {
            return false;
        };
        let now = Instant::now();
        match self.deadline {
            None => {
                self.deadline = Some(now + limit);
                false
            }
            Some(d) => now >= d,
        }
    }
}

#[cfg(test)]
mod tests;

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

mod byte_view;
mod chart;
mod debug;
mod exception;
mod exec;
mod fault;
mod grafcet;
mod host;
mod interrupt;
mod json_of_symbol;
mod loop_kernels;
pub(crate) mod native;
mod refs;
mod string_ops;
mod strings;
mod symbol_from_json;
mod type_at;

pub(crate) use debug::{ChartEvent, DebugFrame, DebugHook};
#[cfg(feature = "native")]
pub(crate) use exec::{index_fault, int_pow};
pub(crate) use fault::CallSite;
pub use fault::{Fault, FaultKind, HostFailure, UnstableCycle};
pub(crate) use host::{HostDispatch, HostFrame, HostLink};
pub(crate) use interrupt::Interrupt;
pub use strings::PlcString;

use crate::ir::op::CodeIdx;
use crate::ir::verify::VerifiedImage;
use std::sync::Arc;

/// The mutable state of a running PLC: memory, strings, clock, and the
/// interrupt word other threads use to stop it.
#[derive(Debug)]
pub struct Machine {
    /// All slots (globals, program instances, FB instances, function frames).
    pub(crate) mem: Vec<u64>,
    /// String variables, indexed by the string id a slot holds.
    pub(crate) strings: Vec<PlcString>,
    /// The current cycle's clock value in nanoseconds.
    pub(crate) now: i64,
    /// Polled at every backward jump and call (see [`Interrupt`]).
    interrupt: Arc<Interrupt>,
    /// Runs the bodies of host-registered POUs (`Op::CallHost`).
    pub(crate) host: HostLink,
    /// The objects references were taken from (`REF`, `ADR`).
    pub(crate) refs: refs::RefTable,
    /// The calls a fault unwound through, innermost first (filled on the
    /// error path only; see [`Self::take_callers`]).
    unwind: Vec<CallSite>,
    /// The attached debugger, if any (see [`debug`]): while there is
    /// none, [`Self::run`] runs the plain executor.
    debug: Option<Box<debug::Debugging>>,
    /// Machine code of the image's blocks (`--engine native`); `None`
    /// runs everything in the interpreter.
    #[cfg(feature = "native")]
    native: Option<Box<native::Compiled>>,
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
            interrupt: Arc::default(),
            host: HostLink::default(),
            refs: refs::RefTable::default(),
            unwind: Vec::new(),
            debug: None,
            #[cfg(feature = "native")]
            native: None,
        }
    }

    /// Puts every variable back to its initial value (the memory and the
    /// strings the machine had when it was built from `image`).
    pub(crate) fn reinitialise(&mut self, image: &VerifiedImage) {
        // Same image, same sizes: the buffers are reused.
        self.unwind.clear();
        self.mem.clear();
        self.mem.extend_from_slice(&image.memory);
        // Bytes byte views kept past a string's NUL go with the strings.
        self.refs.tails.clear();
        self.strings.truncate(image.strings.len());
        for (k, init) in image.strings.iter().enumerate() {
            match self.strings.get_mut(k) {
                Some(s) => *s = PlcString::new(&init.init, init.max, init.wide),
                None => self
                    .strings
                    .push(PlcString::new(&init.init, init.max, init.wide)),
            }
        }
    }

    /// The interrupt word this machine polls, to share with the threads
    /// that may stop it.
    pub(crate) fn interrupt(&self) -> &Arc<Interrupt> {
        &self.interrupt
    }

    /// Runs code block `code` with frame base `base` (a frame outside
    /// memory faults with `BadAddress`). After a fault, the calls it
    /// unwound through wait in [`Self::take_callers`].
    pub fn run(&mut self, image: &VerifiedImage, code: CodeIdx, base: u32) -> Result<(), Fault> {
        if self.debug.is_some() {
            return exec::call::<true, false>(self, image.image(), code, base as usize);
        }
        #[cfg(feature = "native")]
        if let Some(native) = &self.native
            && native.fits(image.image())
        {
            return exec::call::<false, true>(self, image.image(), code, base as usize);
        }
        exec::call::<false, false>(self, image.image(), code, base as usize)
    }

    /// Gives this machine the native code of its image (`None`: run
    /// everything in the interpreter). Native code is used only while the
    /// image the machine runs is the one it was compiled from.
    #[cfg(feature = "native")]
    pub(crate) fn set_native(&mut self, native: Option<Box<native::Compiled>>) {
        self.native = native;
    }

    /// The native code this machine holds.
    #[cfg(feature = "native")]
    pub(crate) fn native(&self) -> Option<&native::Compiled> {
        self.native.as_deref()
    }

    /// Swaps the native code of two machines (online change: the new
    /// version's code goes with its image).
    #[cfg(feature = "native")]
    pub(crate) fn swap_native(&mut self, other: &mut Machine) {
        std::mem::swap(&mut self.native, &mut other.native);
    }

    /// Runs a block for native code that calls one it could not compile
    /// (the interpreter, which runs compiled callees natively again).
    #[cfg(feature = "native")]
    pub(crate) fn call_mixed(
        &mut self,
        img: &crate::ir::image::Image,
        code: CodeIdx,
        base: usize,
    ) -> Result<(), Fault> {
        exec::call::<false, true>(self, img, code, base)
    }

    /// Runs one string or reference instruction for native code, exactly
    /// as the interpreter does.
    ///
    /// # Safety
    /// `fp` is the frame of a verified block that holds `op`, inside this
    /// machine's memory.
    #[cfg(feature = "native")]
    pub(crate) unsafe fn out_of_line(
        &mut self,
        img: &crate::ir::image::Image,
        fp: *mut u64,
        op: &crate::ir::op::Op,
    ) -> Result<(), FaultKind> {
        use crate::ir::op::Op;
        match op {
            Op::CmpStr { .. }
            | Op::StrMov { .. }
            | Op::StrConst { .. }
            | Op::StrCall { .. }
            | Op::ToStr { .. }
            | Op::FromStr { .. } => {
                // SAFETY: the caller's contract.
                unsafe { string_ops::run(self, img, fp, op) }
            }
            // SAFETY: the caller's contract (refs::run answers any other
            // instruction with a fault).
            _ => unsafe { refs::run(self, img, fp, op) },
        }
    }

    /// Sets string `id` to `text` (a block's entry strings, for native
    /// code).
    #[cfg(feature = "native")]
    pub(crate) fn set_string(&mut self, id: u64, text: &str) {
        self.strings[id as usize].set(text);
    }

    /// The calls the last fault unwound through, innermost first (the
    /// caller of the faulting block first, the block `run` was given
    /// last); empties the list for the next fault.
    pub(crate) fn take_callers(&mut self) -> Vec<CallSite> {
        std::mem::take(&mut self.unwind)
    }

    /// The calls the last fault unwound through (as [`Self::take_callers`]
    /// gives them, without taking them).
    pub(crate) fn callers(&self) -> &[CallSite] {
        &self.unwind
    }

    /// Forgets the calls noted after the first `keep` (a fault caught by
    /// a `__TRY`: they belong to no fault any more).
    pub(crate) fn forget_callers(&mut self, keep: usize) {
        self.unwind.truncate(keep);
    }

    /// Notes, while a fault unwinds, the call at `pc` of `code` running at
    /// `base`. Out of line and cold: the dispatch loop pays for it on the
    /// error path only, with values it keeps anyway.
    #[cold]
    #[inline(never)]
    pub(crate) fn unwound(&mut self, code: CodeIdx, pc: usize, base: usize) {
        self.unwind.push(CallSite {
            code,
            pc: pc as u32,
            base,
        });
    }
}

#[cfg(test)]
mod tests;

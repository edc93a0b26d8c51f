//! What the executor does for a debugger: keep a call stack and hand it
//! every statement start.
//!
//! Nothing here runs on a machine without a debugger: [`Machine::run`]
//! then runs the plain variant of the executor (`exec::call::<false>`),
//! whose code has no check, no call and no stack for debugging, and the
//! program's instructions are the ones the compiler emitted. With a
//! debugger attached it runs the debugging variant (`exec::call::<true>`),
//! which pushes a frame at every block entry and, before every
//! instruction, records the instruction in the top frame and, at a
//! statement start, calls the [`DebugHook`]. The hook may stop the PLC
//! there (block its thread until the user resumes), read and write the
//! memory, or end the cycle with a fault kind (`Aborted`).

use super::{FaultKind, Machine};
use crate::ir::image::Image;
use crate::ir::op::{ChartIdx, CodeIdx};
use std::sync::Arc;

/// One block running under the debugger: its code, the instruction it is
/// at, and its frame base.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct DebugFrame {
    /// The code block.
    pub code: CodeIdx,
    /// The instruction it runs (for a caller: its call instruction).
    pub pc: u32,
    /// The frame base it runs at.
    pub base: usize,
}

/// What a debugger does at a statement start.
pub(crate) trait DebugHook: Send {
    /// The statement starting at the top frame's instruction is about to
    /// run. `stack` is outermost first. An `Err` ends the cycle with that
    /// fault kind.
    fn statement(
        &mut self,
        img: &Image,
        m: &mut Machine,
        stack: &[DebugFrame],
    ) -> Result<(), FaultKind>;

    /// Chart `chart`, run by the top frame's block, did `event`.
    fn chart(
        &mut self,
        img: &Image,
        m: &mut Machine,
        stack: &[DebugFrame],
        chart: ChartIdx,
        event: ChartEvent,
    );
}

/// What an SFC chart did, for chart breakpoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ChartEvent {
    /// Step `n` became active.
    Step(u32),
    /// Transition `n` fired.
    Fired(u32),
    /// Action `n` is about to run (its Q is TRUE).
    Action(u32),
}

/// A machine's debugging state (see the module's documentation).
pub(crate) struct Debugging {
    /// Per code block, per instruction: whether a statement starts there.
    pub starts: Arc<Vec<Vec<bool>>>,
    /// The blocks running, outermost first.
    pub stack: Vec<DebugFrame>,
    /// The debugger.
    pub hook: Box<dyn DebugHook>,
}

impl std::fmt::Debug for Debugging {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Debugging")
            .field("stack", &self.stack)
            .finish_non_exhaustive()
    }
}

impl Machine {
    /// Attaches a debugger: from the next run on, the machine runs the
    /// debugging variant of the executor.
    pub(crate) fn attach_debugger(
        &mut self,
        starts: Arc<Vec<Vec<bool>>>,
        hook: Box<dyn DebugHook>,
    ) {
        self.debug = Some(Box::new(Debugging {
            starts,
            stack: Vec::new(),
            hook,
        }));
    }

    /// Detaches the debugger: the next run is the plain executor again.
    pub(crate) fn detach_debugger(&mut self) {
        self.debug = None;
    }

    /// A block is entered (debugging variant only).
    #[inline(never)]
    pub(super) fn debug_enter(&mut self, code: CodeIdx, base: usize) {
        if let Some(d) = &mut self.debug {
            d.stack.push(DebugFrame { code, pc: 0, base });
        }
    }

    /// A block returns or unwinds (debugging variant only).
    #[inline(never)]
    pub(super) fn debug_leave(&mut self) {
        if let Some(d) = &mut self.debug {
            d.stack.pop();
        }
    }

    /// Instruction `pc` of `code` is about to run (debugging variant
    /// only): noted in the top frame, and given to the hook when a
    /// statement starts there.
    #[inline(never)]
    pub(super) fn debug_at(
        &mut self,
        img: &Image,
        code: CodeIdx,
        pc: usize,
    ) -> Result<(), FaultKind> {
        let Some(d) = &mut self.debug else {
            return Ok(());
        };
        if let Some(top) = d.stack.last_mut() {
            top.pc = pc as u32;
        }
        let start = d
            .starts
            .get(code.index())
            .and_then(|b| b.get(pc))
            .copied()
            .unwrap_or(false);
        if !start {
            return Ok(());
        }
        // The hook gets the machine: the state is taken out meanwhile.
        let Some(mut d) = self.debug.take() else {
            return Ok(());
        };
        let done = d.hook.statement(img, self, &d.stack);
        if self.debug.is_none() {
            self.debug = Some(d);
        }
        done
    }

    /// An SFC chart event (debugging variant only).
    #[inline(never)]
    pub(super) fn debug_chart(&mut self, img: &Image, chart: ChartIdx, event: ChartEvent) {
        let Some(mut d) = self.debug.take() else {
            return;
        };
        d.hook.chart(img, self, &d.stack, chart, event);
        if self.debug.is_none() {
            self.debug = Some(d);
        }
    }
}

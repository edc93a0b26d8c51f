//! The executor's side of host-registered FUNCTIONs and FUNCTION_BLOCKs:
//! `Op::CallHost` hands the current frame to whatever the runtime linked
//! in ([`HostDispatch`]); the pins, the closures and their per-instance
//! state live in the runtime (`runtime::host_blocks`).

use super::{FaultKind, PlcString};
use crate::ir::op::HostIdx;
use std::fmt;
use std::sync::{Arc, Mutex};

/// What a host body sees of the machine during one call.
pub(crate) struct HostFrame<'a> {
    /// The frame of the call: the FB instance or the function's frame.
    pub(crate) frame: &'a mut [u64],
    /// String variables (a STRING pin's slot holds an index here).
    pub(crate) strings: &'a mut [PlcString],
    /// Absolute address of the frame's first slot (tells instances apart).
    pub(crate) base: usize,
    /// The current cycle's clock, in nanoseconds.
    pub(crate) now: i64,
}

/// Runs host bodies by their `Image::hosts` index.
pub(crate) trait HostDispatch: Send {
    /// Runs body `id` on `frame`; an error is the fault to report
    /// (a host failure, a panic turned into one).
    fn call(&mut self, id: HostIdx, frame: HostFrame<'_>) -> Result<(), FaultKind>;
}

/// The dispatcher linked into a machine, if any (shared by clones).
#[derive(Clone, Default)]
pub(crate) struct HostLink(pub(crate) Option<Arc<Mutex<dyn HostDispatch>>>);

impl fmt::Debug for HostLink {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.0.is_some() {
            "HostLink(linked)"
        } else {
            "HostLink(none)"
        })
    }
}

/// Runs host body `id` on `frame` (at absolute address `base`) through
/// `link`. Out of line: programs that call no host body never come here.
/// `frame` is the executor's view of the current frame and the machine's
/// memory is not touched otherwise, so the executor's pointers stay valid.
#[cold]
#[inline(never)]
pub(super) fn call(
    link: &HostLink,
    strings: &mut [PlcString],
    now: i64,
    id: HostIdx,
    frame: &mut [u64],
    base: usize,
) -> Result<(), FaultKind> {
    let unlinked = || FaultKind::host(format!("#{}", id.get()), "no host code is linked");
    let link = link.0.as_ref().ok_or_else(unlinked)?;
    let frame = HostFrame {
        frame,
        strings,
        base,
        now,
    };
    // A host body that panicked left the dispatcher's own state
    // consistent (it catches panics itself), so a poisoned lock is
    // still usable.
    let mut dispatch = link.lock().unwrap_or_else(|p| p.into_inner());
    dispatch.call(id, frame)
}

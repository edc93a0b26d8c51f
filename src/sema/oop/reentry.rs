//! Re-entry guards of methods that a cycle of calls may reach again.
//!
//! IEC 61131-3 forbids recursion (E409), but a call through an interface
//! reaches whichever block the interface holds at run time, so code such
//! as PMPS's veto arbiter (`CheckRequest` asks its higher authority's
//! `CheckRequest`, through an interface its own block implements too)
//! forms a cycle in the call graph that, at run time, goes to another
//! instance. plcrun keeps a method's variables in its instance, so
//! another instance is safe and the same one is not: such a method
//! (found by a first pass, `sema::link::recursion`) gets a hidden BOOL
//! that is TRUE while it runs on the instance, and entering it again on
//! the same instance stops the PLC (R081) instead of overwriting the
//! running call's variables. Each method can then be active once per
//! instance, which bounds how deep the cycle can nest
//! (`sema::link::call_depth`).

use crate::ir::op::{Op, Slot, Target};
use crate::sema::body::BodyBuilder;
use crate::sema::model::Storage;

impl BodyBuilder<'_> {
    /// At a guarded method's entry: faults if its flag (hidden variable
    /// `key`) is set, else sets it. The flag's slot.
    pub(super) fn enter_guard(&mut self, key: &str) -> Option<Slot> {
        let Storage::Frame(o) = self.lookup_var(key)?.storage else {
            return None;
        };
        let flag = Slot::new(o);
        let free = self.block.emit(Op::Jz {
            c: flag,
            t: Target::UNPATCHED,
        });
        self.block.emit(Op::FaultReentry);
        let set = self.block.here();
        self.block.patch(free, set);
        let one = self.block.const_slot(1);
        self.block.mov(flag, one);
        self.block.last_def = None;
        Some(flag)
    }

    /// At a guarded method's exit (every RETURN jumps there): clears its
    /// flag.
    pub(super) fn leave_guard(&mut self, flag: Slot) {
        let zero = self.block.const_slot(0);
        self.block.mov(flag, zero);
        self.block.last_def = None;
    }
}

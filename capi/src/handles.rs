//! Handles as C sees them: small integers checked against a table, not
//! pointers. A handle of a freed PLC, a handle freed twice, a zeroed or
//! made-up value, or a variable handle of another PLC is detected and
//! refused with `PLC_E_INVALID_HANDLE`, never dereferenced.
//!
//! A PLC handle is `generation << 32 | (slot + 1)`: freeing a PLC bumps its
//! slot's generation, so the old value no longer matches when the slot is
//! reused. A variable handle is `owner tag << 32 | (index + 1)` into its
//! PLC's list of resolved variables; the tag is unique per created PLC
//! (a 32-bit counter).

use crate::failure::Failure;
use crate::slot_table::SlotTable;
use crate::status::{PLC_E_INVALID_HANDLE, PLC_E_PANIC};
use plcrun::{Plc, VarRef};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};

/// A compiled PLC, as C holds it (`plc_handle`). Zero is never valid.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlcHandle {
    /// Generation and slot (see the module's documentation).
    pub id: u64,
}

/// A variable resolved by one PLC (`plc_var`). Zero is never valid.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlcVar {
    /// Owner tag and index (see the module's documentation).
    pub id: u64,
}

/// One PLC with what the C side keeps beside it.
pub(crate) struct Entry {
    pub plc: Plc,
    /// Variables resolved through `plc_resolve`, in order of resolution.
    pub vars: Vec<VarRef>,
    /// Tells this PLC's variable handles from another's.
    pub tag: u32,
    /// The OPC UA server `plc_opcua_start` started, with its scan side.
    pub opcua: Option<(plcrun::opcua::OpcUaServer, plcrun::opcua::OpcUaExchange)>,
}

impl Entry {
    pub fn new(plc: Plc) -> Entry {
        static NEXT_TAG: AtomicU32 = AtomicU32::new(1);
        Entry {
            plc,
            vars: Vec::new(),
            tag: NEXT_TAG.fetch_add(1, Ordering::Relaxed),
            opcua: None,
        }
    }

    /// The handle of a variable, resolving `path` once: the same path
    /// gives the same handle, so resolving in a loop does not grow the list.
    pub fn resolve(&mut self, path: &str) -> Result<PlcVar, Failure> {
        let trimmed = path.trim();
        let index = match self.vars.iter().position(|v| v.name() == trimmed) {
            Some(i) => i,
            None => {
                self.vars.push(self.plc.resolve(path)?);
                self.vars.len() - 1
            }
        };
        Ok(PlcVar {
            id: u64::from(self.tag) << 32 | (index as u64 + 1),
        })
    }
}

/// The variable behind `var` among the variables `vars` of the PLC tagged
/// `tag`, if that PLC resolved it.
pub(crate) fn var_ref(vars: &[VarRef], tag: u32, var: PlcVar) -> Result<&VarRef, Failure> {
    let (owner, index) = ((var.id >> 32) as u32, var.id as u32 as usize);
    if owner != tag || index == 0 {
        return Err(invalid_var(var));
    }
    vars.get(index - 1).ok_or_else(|| invalid_var(var))
}

fn invalid_var(var: PlcVar) -> Failure {
    Failure::new(
        PLC_E_INVALID_HANDLE,
        format!("variable handle {:#x} was not resolved by this PLC", var.id),
    )
}

/// Every PLC created through the C ABI and not yet freed.
static TABLE: SlotTable<Arc<Mutex<Entry>>> = SlotTable::new();

/// Registers a PLC and gives its handle.
pub(crate) fn insert(entry: Entry) -> PlcHandle {
    PlcHandle {
        id: TABLE.insert(Arc::new(Mutex::new(entry))),
    }
}

fn invalid(plc: PlcHandle) -> Failure {
    Failure::new(
        PLC_E_INVALID_HANDLE,
        format!(
            "PLC handle {:#x} is not valid (never created, or freed)",
            plc.id
        ),
    )
}

/// Removes a PLC; it is dropped when the last call still using it ends.
pub(crate) fn remove(plc: PlcHandle) -> Result<(), Failure> {
    if TABLE.remove(plc.id) {
        Ok(())
    } else {
        Err(invalid(plc))
    }
}

/// Runs `f` on the PLC behind `plc`. Calls on one PLC from several
/// threads are serialised by its lock; different PLCs run in parallel.
pub(crate) fn with_entry<T>(
    plc: PlcHandle,
    f: impl FnOnce(&mut Entry) -> Result<T, Failure>,
) -> Result<T, Failure> {
    let shared = TABLE.get(plc.id).ok_or_else(|| invalid(plc))?;
    let mut entry = shared.lock().map_err(|_| {
        Failure::new(
            PLC_E_PANIC,
            "an earlier call on this PLC failed inside plcrun (PLC_E_PANIC); \
             its state is unknown: free it",
        )
    })?;
    f(&mut entry)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::guard::guard;
    use crate::status::{PLC_E_INVALID_HANDLE, PLC_OK};
    use plcrun::Options;

    #[test]
    fn a_plc_a_panic_went_through_refuses_later_calls_but_can_be_freed() {
        let source = "PROGRAM P VAR x : INT; END_VAR x := x + 1; END_PROGRAM";
        let plc = Plc::compile_files(&[("p.st", source)], &Options::default()).unwrap();
        let h = insert(Entry::new(plc));
        assert_eq!(
            guard(|| with_entry(h, |e| e.plc.run_cycle().map_err(|f| Failure::from(&f)))),
            PLC_OK
        );
        // A bug inside a call, while the PLC is locked.
        let status = guard(|| with_entry(h, |_| -> Result<(), Failure> { panic!("bug") }));
        assert_eq!(status, PLC_E_PANIC);
        let status = guard(|| with_entry(h, |e| e.plc.run_cycle().map_err(|f| Failure::from(&f))));
        assert_eq!(status, PLC_E_PANIC);
        assert_eq!(guard(|| remove(h)), PLC_OK);
        assert_eq!(guard(|| remove(h)), PLC_E_INVALID_HANDLE);
    }

    #[test]
    fn handles_of_a_reused_slot_differ() {
        let source = "PROGRAM P VAR x : INT; END_VAR x := 1; END_PROGRAM";
        let make = || Plc::compile_files(&[("p.st", source)], &Options::default()).unwrap();
        let first = insert(Entry::new(make()));
        remove(first).unwrap();
        let second = insert(Entry::new(make()));
        assert_ne!(first, second);
        assert!(with_entry(first, |_| Ok(())).is_err());
        assert!(with_entry(second, |_| Ok(())).is_ok());
        remove(second).unwrap();
    }
}

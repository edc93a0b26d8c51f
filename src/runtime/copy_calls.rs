//! The calls an online change makes on the instances it copies: an
//! instance of a function block whose declaration changed is copied into
//! the new layout (CODESYS and TwinCAT do the same), with the old
//! instance's `FB_exit(bInCopyCode := TRUE)` before the copy and the new
//! instance's `FB_reinit()` after it, where the block has them
//! (docs/semantics.md §24). Instances of unchanged blocks stay as they
//! are and get neither.

use super::engine::{Plc, RuntimeFault};
use super::online_change::Copied;
use crate::ir::image::{CopyCalls, Image};
use crate::ir::type_table::TypeId;

/// The copy calls of type `ty` in `image`, if it has any.
fn calls_of(image: &Image, ty: TypeId) -> Option<&CopyCalls> {
    image.copy_calls.iter().find(|c| c.ty == ty)
}

impl Plc {
    /// Runs `FB_exit(bInCopyCode := TRUE)` on the copied instances of the
    /// running version that declare it; true when one ran (the copy
    /// must then be made again, to carry what it wrote). A fault stops
    /// the PLC, which keeps running this version.
    pub(super) fn exit_copied(&mut self, copied: &[Copied]) -> Result<bool, RuntimeFault> {
        let mut ran = false;
        for c in copied {
            let Some((code, flag)) = calls_of(&self.image, c.old.0).and_then(|k| k.exit) else {
                continue;
            };
            let base = c.old.1;
            if let Some(slot) = self.machine.mem.get_mut((base + flag) as usize) {
                *slot = 1;
            }
            if let Err(fault) = self.machine.run(&self.image, code, base) {
                return Err(self.fail(fault, base as usize));
            }
            ran = true;
        }
        Ok(ran)
    }

    /// Runs `FB_reinit()` on the copied instances of the new version (now
    /// running) that declare it. A fault stops the PLC.
    pub(super) fn reinit_copied(&mut self, copied: &[Copied]) -> Result<(), RuntimeFault> {
        for c in copied {
            let Some(code) = calls_of(&self.image, c.new.0).and_then(|k| k.reinit) else {
                continue;
            };
            let base = c.new.1;
            if let Err(fault) = self.machine.run(&self.image, code, base) {
                return Err(self.fail(fault, base as usize));
            }
        }
        Ok(())
    }
}

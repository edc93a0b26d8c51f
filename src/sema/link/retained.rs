//! The table of retained values: every single value that a RETAIN or
//! PERSISTENT declaration keeps, found by walking the globals and the
//! program instances down to elementary values.
//!
//! Rules: a variable in a RETAIN (PERSISTENT) block is retained whole —
//! array elements, structure fields, and every variable of an FB instance
//! including a native block's hidden state, except those its type declares
//! NON_RETAIN. A VAR RETAIN inside an FB type is retained in every
//! instance, wherever the instance is declared. SFC step and action
//! records, VAR_TEMP, VAR_IN_OUT and VAR_EXTERNAL are never retained (a
//! chart restarts at its initial step).

use super::super::model::Storage;
use super::Linker;
use crate::ir::image::ProgramInstance;
use crate::ir::op::NativeFb;
use crate::ir::retained::{RetainedStorage, RetainedVar};
use crate::ir::type_table::{MemberKind, Retention, TypeId, TypeKind};

/// Whether values found under a place are retained, and how.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Keep {
    /// Not retained (but an FB type inside may retain its own variables).
    No,
    /// RETAIN.
    Retain,
    /// PERSISTENT.
    Persistent,
}

impl Keep {
    /// What a member declared with `r` keeps, inside a place keeping `self`.
    fn under(self, r: Retention) -> Keep {
        match r {
            Retention::Inherit => self,
            Retention::NonRetain => Keep::No,
            Retention::Retain => Keep::Retain,
            Retention::Persistent => Keep::Persistent,
        }
    }
}

impl Linker<'_> {
    /// The retained values of the globals, then of each program instance,
    /// in declaration order.
    pub(super) fn retained_vars(&self, instances: &[ProgramInstance]) -> Vec<RetainedVar> {
        let mut out = Vec::new();
        for (key, g) in &self.model.globals {
            let keep = match self.model.global_retention.get(key) {
                Some(r) => Keep::No.under(*r),
                None => Keep::No,
            };
            if let Storage::Abs(a) = g.storage {
                self.walk(&mut out, g.name.clone(), g.ty, a, keep);
            }
        }
        for (name, addr, ty, persistent) in &self.model.retained_located {
            let keep = if *persistent {
                Keep::Persistent
            } else {
                Keep::Retain
            };
            self.walk(&mut out, name.clone(), *ty, *addr, keep);
        }
        for inst in instances {
            self.walk(&mut out, inst.name.clone(), inst.ty, inst.base, Keep::No);
        }
        out
    }

    /// Pushes the retained single values inside `path` (of type `ty` at
    /// absolute address `addr`).
    fn walk(&self, out: &mut Vec<RetainedVar>, path: String, ty: TypeId, addr: u32, keep: Keep) {
        if keep == Keep::No && !self.may_retain(ty) {
            return;
        }
        match &self.types.get(ty).kind {
            TypeKind::Elem(_) | TypeKind::Enum { .. } | TypeKind::Subrange { .. } => {
                out.push(leaf(path, ty, RetainedStorage::Slot(addr), keep, false));
            }
            TypeKind::Str { .. } => {
                let string = self.out.memory.get(addr as usize).copied().unwrap_or(0) as u32;
                let storage = RetainedStorage::Text { slot: addr, string };
                out.push(leaf(path, ty, storage, keep, false));
            }
            TypeKind::Array { dims, elem } => {
                let size = self.types.size(*elem);
                let count: u64 = dims.iter().map(|d| d.len()).product();
                let mut index: Vec<i64> = dims.iter().map(|d| d.lo).collect();
                for k in 0..count {
                    let text: Vec<String> = index.iter().map(i64::to_string).collect();
                    let at = addr + (k as u32) * size;
                    self.walk(out, format!("{path}[{}]", text.join(",")), *elem, at, keep);
                    // The last index runs fastest, as in memory.
                    for d in (0..dims.len()).rev() {
                        if index[d] < dims[d].hi {
                            index[d] += 1;
                            break;
                        }
                        index[d] = dims[d].lo;
                    }
                }
            }
            TypeKind::Struct { fields } => {
                for f in fields {
                    let p = format!("{path}.{}", f.name);
                    self.walk(out, p, f.ty, addr + f.offset, keep.under(f.retain));
                }
            }
            TypeKind::Pou { members, .. } => {
                for m in members.iter().filter(|m| retainable(m.kind)) {
                    let p = format!("{path}.{}", m.name);
                    self.walk(out, p, m.ty, addr + m.offset, keep.under(m.retain));
                }
            }
            TypeKind::NativeFb(fb) => {
                let timer = matches!(fb, NativeFb::Ton | NativeFb::Tof | NativeFb::Tp);
                for (i, pin) in crate::stdlib::interface(*fb).iter().enumerate() {
                    let ty = crate::ir::type_table::TypeTable::elem(pin.ty);
                    let storage = RetainedStorage::Slot(addr + i as u32);
                    let clock = timer && pin.name == "START";
                    out.push(leaf(
                        format!("{path}.{}", pin.name),
                        ty,
                        storage,
                        keep,
                        clock,
                    ));
                }
            }
            // References are not retained: they start NULL after a restart.
            TypeKind::Step
            | TypeKind::Void
            | TypeKind::Error
            | TypeKind::Ref { .. }
            | TypeKind::OpenArray { .. } => {}
        }
    }

    /// Whether a value of `ty` holds a variable its type declares RETAIN
    /// or PERSISTENT (so that walking an unretained place can find it).
    fn may_retain(&self, ty: TypeId) -> bool {
        match &self.types.get(ty).kind {
            TypeKind::Array { elem, .. } => self.may_retain(*elem),
            TypeKind::Pou { members, .. } => members.iter().any(|m| {
                retainable(m.kind)
                    && (matches!(m.retain, Retention::Retain | Retention::Persistent)
                        || self.may_retain(m.ty))
            }),
            _ => false,
        }
    }
}

/// Members whose values outlive a call and belong to the instance.
fn retainable(kind: MemberKind) -> bool {
    matches!(
        kind,
        MemberKind::Input
            | MemberKind::Output
            | MemberKind::Local
            | MemberKind::Field
            | MemberKind::Hidden
    )
}

fn leaf(
    path: String,
    ty: TypeId,
    storage: RetainedStorage,
    keep: Keep,
    clock: bool,
) -> RetainedVar {
    RetainedVar {
        path,
        ty,
        storage,
        persistent: keep == Keep::Persistent,
        clock_instant: clock,
    }
}

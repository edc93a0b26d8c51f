//! Initial values: instances and static frames written into memory (with
//! their string variables), and what a code block resets on entry.

use super::{EntryResets, Linker};
use crate::ir::image::StringInit;
use crate::ir::op::Slot;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind};
use crate::sema::model::{ConstInit, Storage};
use crate::syntax::ast::PouKind;

impl Linker<'_> {
    /// Writes the initial value of a `ty` at `at` in `buf`, collecting string slots.
    fn write_init(
        &self,
        buf: &mut [u64],
        at: usize,
        ty: TypeId,
        init: Option<&ConstInit>,
        strs: &mut Vec<(usize, StringInit)>,
    ) {
        let default;
        let init = match init {
            Some(i) => Some(i),
            None => {
                default = self.model.type_inits.get(&ty).cloned();
                default.as_ref()
            }
        };
        match &self.types.get(ty).kind {
            TypeKind::Elem(_) | TypeKind::Enum { .. } | TypeKind::Subrange { .. } => {
                let Some(slot) = buf.get_mut(at) else { return };
                *slot = match init {
                    Some(ConstInit::Scalar(b)) => *b,
                    _ => match self.model.default_init(self.types, ty) {
                        ConstInit::Scalar(b) => b,
                        _ => 0,
                    },
                };
            }
            TypeKind::Str { max, wide } => {
                let text = match init {
                    Some(ConstInit::Str(s)) => s.clone(),
                    _ => String::new(),
                };
                strs.push((
                    at,
                    StringInit {
                        max: *max,
                        wide: *wide,
                        init: text,
                    },
                ));
            }
            TypeKind::Array { dims, elem } => {
                let n: u64 = dims.iter().map(|d| d.len()).product();
                let stride = self.types.size(*elem) as usize;
                let items = match init {
                    Some(ConstInit::Array(v)) => v.as_slice(),
                    _ => &[],
                };
                for k in 0..n as usize {
                    self.write_init(buf, at + k * stride, *elem, items.get(k), strs);
                }
            }
            TypeKind::Struct { fields } => {
                let overrides = match init {
                    Some(ConstInit::Struct(v)) => v.as_slice(),
                    _ => &[],
                };
                let type_defaults = match self.model.type_inits.get(&ty) {
                    Some(ConstInit::Struct(v)) => v.clone(),
                    _ => Vec::new(),
                };
                for (k, m) in fields.iter().enumerate() {
                    let fi = overrides
                        .iter()
                        .find(|(i, _)| *i == k)
                        .or_else(|| type_defaults.iter().find(|(i, _)| *i == k))
                        .map(|(_, c)| c);
                    self.write_init(buf, at + m.offset as usize, m.ty, fi, strs);
                }
            }
            TypeKind::NativeFb(fb) => {
                for (k, p) in crate::stdlib::interface(*fb).iter().enumerate() {
                    if let Some(slot) = buf.get_mut(at + k) {
                        *slot = p.init;
                    }
                }
                // `ton : TON := (PT := T#5S)` (fb_init_values.rs): one slot a pin.
                if let Some(ConstInit::Struct(given)) = init {
                    for (k, ci) in given {
                        if let (Some(slot), ConstInit::Scalar(b)) = (buf.get_mut(at + k), ci) {
                            *slot = *b;
                        }
                    }
                }
            }
            TypeKind::Pou { code, .. } => {
                let Some(p) = self.model.pous.iter().position(|p| p.code == *code) else {
                    return;
                };
                for var in self.model.pous[p].vars.values() {
                    match var.storage {
                        Storage::Frame(o) => {
                            self.write_init(buf, at + o as usize, var.ty, var.init.as_ref(), strs)
                        }
                        // A VAR_IN_OUT no call has connected yet.
                        Storage::Ref(o) => {
                            if let Some(slot) = buf.get_mut(at + o as usize) {
                                *slot = crate::ir::image::NOT_CONNECTED;
                            }
                        }
                        _ => {}
                    }
                }
                for &(slot, value) in &self.model.pous[p].consts {
                    if let Some(s) = buf.get_mut(at + slot.index()) {
                        *s = value;
                    }
                }
                // `fb : FB_X := (limit := 10)` (fb_init_values.rs), by member.
                if let (Some(ConstInit::Struct(given)), TypeKind::Pou { members, .. }) =
                    (init, &self.types.get(ty).kind)
                {
                    for (k, ci) in given {
                        if let Some(m) = members.get(*k) {
                            self.write_init(buf, at + m.offset as usize, m.ty, Some(ci), strs);
                        }
                    }
                }
            }
            TypeKind::Ref { .. } => {
                if let Some(slot) = buf.get_mut(at) {
                    *slot = crate::ir::refs::NULL;
                }
            }
            // An `ARRAY[*]` is only ever a VAR_IN_OUT: the caller binds it.
            TypeKind::Step | TypeKind::Void | TypeKind::Error | TypeKind::OpenArray { .. } => {}
        }
    }

    /// Writes initial values into absolute memory and allocates string ids.
    pub(super) fn instantiate(&mut self, addr: u32, ty: TypeId, init: Option<&ConstInit>) {
        let mut strs = Vec::new();
        let mut buf = std::mem::take(&mut self.out.memory);
        self.write_init(&mut buf, addr as usize, ty, init, &mut strs);
        for (slot, s) in strs {
            if let Some(s) = buf.get_mut(slot) {
                *s = self.out.strings.len() as u64;
            }
            self.out.strings.push(s);
        }
        self.out.memory = buf;
    }

    /// Entry resets of a POU's VAR_TEMP (FBs, programs) or of all its
    /// non-input variables (functions).
    pub(super) fn entry_resets(&mut self, p: usize) -> EntryResets {
        self.entry_resets_of(p, None)
    }

    /// Entry resets of the variables of POU `p` whose keys are in `only`
    /// (a method's temporaries), or as [`Self::entry_resets`] says.
    pub(super) fn entry_resets_of(&mut self, p: usize, only: Option<&[String]>) -> EntryResets {
        let kind = self.model.pous[p].kind;
        let size = self.model.pous[p].vars_size as usize;
        let mut buf = vec![0u64; size];
        let mut strs = Vec::new();
        let mut slots = Vec::new();
        let vars: Vec<_> = self.model.pous[p]
            .vars
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        for (key, var) in vars {
            let reset = match (only, kind) {
                (Some(keys), _) => keys.contains(&key),
                (None, PouKind::Function) => {
                    !matches!(var.kind, MemberKind::Input | MemberKind::InOut)
                }
                (None, _) => var.kind == MemberKind::Temp,
            };
            let Storage::Frame(o) = var.storage else {
                continue;
            };
            if !reset {
                continue;
            }
            let before = strs.len();
            self.write_init(&mut buf, o as usize, var.ty, var.init.as_ref(), &mut strs);
            let n = self.types.size(var.ty) as usize;
            let string_slots: Vec<usize> = strs[before..].iter().map(|(s, _)| *s).collect();
            for (k, value) in buf.iter().enumerate().skip(o as usize).take(n) {
                if !string_slots.contains(&k) {
                    slots.push((Slot::new(k as u32), *value));
                }
            }
        }
        let strings = strs
            .into_iter()
            .map(|(slot, s)| (Slot::new(slot as u32), self.out.str_const(&s.init)))
            .collect();
        (slots, strings)
    }
}

//! The frame cache: frame slots held in Cranelift variables across
//! instructions, so that a value computed by one instruction reaches the
//! next in a register instead of through memory.
//!
//! A held slot is *clean* (memory has its value too) or *dirty* (only the
//! variable has it). A slot that is not held has its value in memory.
//! Everything that reads the frame behind the translation's back (a
//! helper, a call, a fault report, a load through an address) is preceded
//! by a write-back of what it may read; everything that may write the
//! frame drops what it may write, so the next use loads it again. A
//! variable is not tied to one slot: at most [`MAX_HELD`] are live, and a
//! freed one serves the next slot (this bounds register pressure and the
//! SSA builder's tables, whose size grows with variables times blocks).

use super::{I32, I64, Lower};
use crate::ir::op::{Op, Slot};
use crate::ir::operands::{Access, Operand, operands};
use cranelift_codegen::ir::{InstBuilder, MemFlagsData, Value, types};
use cranelift_frontend::Variable;

/// The most slots held at once; one more writes back and drops the least
/// recently used. About the general registers left beside the frame
/// pointer and the context: holding more only moves the values to spill
/// slots on the stack instead of the frame.
pub(super) const MAX_HELD: usize = 8;

/// One held slot.
#[derive(Clone, Copy)]
pub(super) struct Held {
    pub(super) slot: u32,
    pub(super) var: Variable,
    /// Memory does not have the value yet.
    pub(super) dirty: bool,
    /// When it was last used (for eviction).
    used: u32,
    /// The value as a float of each width, once computed in this region
    /// (a value that dominates the rest of the region; cleared where
    /// paths merge).
    f32: Option<Value>,
    f64: Option<Value>,
    /// For an address made by `ElemRef` in this region: the frame slots
    /// (relative, `lo..hi`) it points at one of.
    into: Option<(u64, u64)>,
}

/// The held slots at one point of the translation.
#[derive(Default)]
pub(super) struct Cache {
    pub(super) held: Vec<Held>,
    /// Every variable declared so far, and those no slot uses now.
    all: Vec<Variable>,
    free: Vec<Variable>,
    clock: u32,
}

impl Cache {
    pub(super) fn find(&self, slot: u32) -> Option<usize> {
        self.held.iter().position(|h| h.slot == slot)
    }
}

impl Lower<'_, '_> {
    // --- memory ---

    /// Loads frame slot `s` from memory.
    pub(super) fn load_slot(&mut self, s: u32) -> Value {
        let (at, off) = self.slot_at(Slot::new(s));
        self.b.ins().load(I64, MemFlagsData::trusted(), at, off)
    }

    /// Stores `v` into frame slot `s` in memory.
    pub(super) fn store_slot(&mut self, s: u32, v: Value) {
        let (at, off) = self.slot_at(Slot::new(s));
        self.b.ins().store(MemFlagsData::trusted(), v, at, off);
    }

    // --- reading and writing slots ---

    /// The value of frame slot `s`.
    pub(super) fn get(&mut self, s: Slot) -> Value {
        self.cache.clock += 1;
        let clock = self.cache.clock;
        if let Some(i) = self.cache.find(s.get()) {
            self.cache.held[i].used = clock;
            return self.b.use_var(self.cache.held[i].var);
        }
        let v = self.load_slot(s.get());
        self.hold(s.get(), v, false);
        v
    }

    /// Frame slot `s` becomes `v` (written back later).
    pub(super) fn set(&mut self, s: Slot, v: Value) {
        self.cache.clock += 1;
        let clock = self.cache.clock;
        match self.cache.find(s.get()) {
            Some(i) => {
                let h = &mut self.cache.held[i];
                h.dirty = true;
                h.used = clock;
                h.f32 = None;
                h.f64 = None;
                h.into = None;
                let var = h.var;
                self.b.def_var(var, v);
            }
            None => self.hold(s.get(), v, true),
        }
    }

    fn hold(&mut self, slot: u32, v: Value, dirty: bool) {
        if self.cache.held.len() >= MAX_HELD {
            self.evict();
        }
        let var = self.take_var();
        self.b.def_var(var, v);
        self.cache.held.push(Held {
            slot,
            var,
            dirty,
            used: self.cache.clock,
            f32: None,
            f64: None,
            into: None,
        });
    }

    /// Slot `s` becomes `v`, an address of one of the frame slots
    /// `range` (relative to the frame).
    pub(super) fn set_pointer(&mut self, s: Slot, v: Value, range: (u64, u64)) {
        self.set(s, v);
        let i = self.cache.find(s.get()).expect("held after set");
        self.cache.held[i].into = Some(range);
    }

    /// The frame slots (relative) the address held in `s` points at one
    /// of, when known (`set_pointer`).
    pub(super) fn points_into(&self, s: Slot) -> Option<(u64, u64)> {
        self.cache
            .find(s.get())
            .and_then(|i| self.cache.held[i].into)
    }

    /// A variable that neither the current state nor `taken` uses.
    pub(super) fn spare_var(&mut self, taken: &[(u32, Variable)]) -> Variable {
        let busy = |v: Variable, c: &Cache| {
            c.held.iter().any(|h| h.var == v) || taken.iter().any(|&(_, w)| w == v)
        };
        if let Some(&v) = self.cache.all.iter().find(|&&v| !busy(v, &self.cache)) {
            return v;
        }
        let v = self.b.declare_var(I64);
        self.cache.all.push(v);
        v
    }

    fn take_var(&mut self) -> Variable {
        if let Some(v) = self.cache.free.pop() {
            return v;
        }
        let v = self.b.declare_var(I64);
        self.cache.all.push(v);
        v
    }

    /// Writes back and drops the least recently used slot.
    fn evict(&mut self) {
        let Some(i) = (0..self.cache.held.len()).min_by_key(|&i| self.cache.held[i].used) else {
            return;
        };
        self.drop_held(i);
    }

    /// Writes back (if dirty) and drops held entry `i`.
    pub(super) fn drop_held(&mut self, i: usize) {
        let h = self.cache.held.swap_remove(i);
        if h.dirty {
            let v = self.b.use_var(h.var);
            self.store_slot(h.slot, v);
        }
        self.cache.free.push(h.var);
    }

    /// Slot `s` as an `f64` (`wide`) or as the `f32` in its low 32 bits.
    pub(super) fn get_float(&mut self, s: Slot, wide: bool) -> Value {
        let bits = self.get(s);
        let i = self.cache.find(s.get()).expect("held after get");
        let known = if wide {
            self.cache.held[i].f64
        } else {
            self.cache.held[i].f32
        };
        if let Some(v) = known {
            return v;
        }
        let v = if wide {
            self.b.ins().bitcast(types::F64, MemFlagsData::new(), bits)
        } else {
            // Little-endian: the REAL is the slot's low 32 bits.
            let low = self.b.ins().ireduce(I32, bits);
            self.b.ins().bitcast(types::F32, MemFlagsData::new(), low)
        };
        let h = &mut self.cache.held[i];
        if wide {
            h.f64 = Some(v);
        } else {
            h.f32 = Some(v);
        }
        v
    }

    /// Slot `s` becomes `v`: an `f64`, or an `f32` zero-extended to 64
    /// bits (the interpreter's `of_f32`).
    pub(super) fn set_float(&mut self, s: Slot, v: Value, wide: bool) {
        let bits = if wide {
            self.b.ins().bitcast(I64, MemFlagsData::new(), v)
        } else {
            let b = self.b.ins().bitcast(I32, MemFlagsData::new(), v);
            self.b.ins().uextend(I64, b)
        };
        self.set(s, bits);
        let i = self.cache.find(s.get()).expect("held after set");
        let h = &mut self.cache.held[i];
        if wide {
            h.f64 = Some(v);
        } else {
            h.f32 = Some(v);
        }
    }

    // --- keeping memory current ---

    /// Writes back every dirty slot in `lo..hi`; they stay held, clean.
    pub(super) fn write_back_range(&mut self, lo: u64, hi: u64) {
        for i in 0..self.cache.held.len() {
            let h = self.cache.held[i];
            if h.dirty && (lo..hi).contains(&u64::from(h.slot)) {
                let v = self.b.use_var(h.var);
                self.store_slot(h.slot, v);
                self.cache.held[i].dirty = false;
            }
        }
    }

    /// Writes back every dirty slot; they stay held, clean.
    pub(super) fn write_back_all(&mut self) {
        self.write_back_range(0, u64::MAX);
    }

    /// Writes back every dirty slot on a path that leaves the main one (a
    /// fault, a poll): the main path's state does not change.
    pub(super) fn write_back_copy(&mut self) {
        for h in self.cache.held.clone() {
            if h.dirty {
                let v = self.b.use_var(h.var);
                self.store_slot(h.slot, v);
            }
        }
    }

    /// Writes back and drops every held slot in `lo..hi` (something is
    /// about to write memory there).
    pub(super) fn drop_range(&mut self, lo: u64, hi: u64) {
        let mut i = 0;
        while i < self.cache.held.len() {
            if (lo..hi).contains(&u64::from(self.cache.held[i].slot)) {
                self.drop_held(i);
            } else {
                i += 1;
            }
        }
    }

    /// Before pure instruction `op` runs in Rust: its inputs written
    /// back, its results dropped (the helper reads and writes memory).
    pub(super) fn around_pure(&mut self, op: &Op) {
        let mut o = *op;
        let mut slots = Vec::new();
        operands(&mut o, &mut |x| {
            if let Operand::Slot(s, access) = x {
                slots.push((u64::from(s.get()), access == Access::In));
            }
        });
        for &(s, read) in &slots {
            if read {
                self.write_back_range(s, s + 1);
            }
        }
        for &(s, read) in &slots {
            if !read {
                self.drop_range(s, s + 1);
            }
        }
    }

    /// Writes back and drops every held slot.
    pub(super) fn drop_all(&mut self) {
        self.drop_range(0, u64::MAX);
    }

    /// Loads every held slot again (memory may have changed under it; no
    /// slot is dirty here), on the current path only.
    pub(super) fn reload_copy(&mut self) {
        for h in self.cache.held.clone() {
            let v = self.load_slot(h.slot);
            self.b.def_var(h.var, v);
        }
    }

    /// Forgets the float values known for held slots (paths merge here,
    /// and some defined their variables again).
    pub(super) fn forget_floats(&mut self) {
        for h in &mut self.cache.held {
            h.f32 = None;
            h.f64 = None;
        }
    }

    /// The cache on entry to a region whose predecessors agreed to hold
    /// `entry`, of which `dirty` may be dirty (`None`: all may be).
    pub(super) fn enter(&mut self, entry: &[(u32, Variable)], dirty: Option<&[u32]>) {
        self.cache.clock += 1;
        let clock = self.cache.clock;
        self.cache.held = entry
            .iter()
            .map(|&(slot, var)| Held {
                slot,
                var,
                dirty: dirty.is_none_or(|d| d.contains(&slot)),
                used: clock,
                f32: None,
                f64: None,
                into: None,
            })
            .collect();
        self.cache.free = self
            .cache
            .all
            .iter()
            .copied()
            .filter(|v| !entry.iter().any(|&(_, w)| w == *v))
            .collect();
    }
}

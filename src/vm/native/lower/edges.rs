//! Where regions meet: the slots held on entry to each region (a run of
//! instructions starting at a jump target or after a branch), and the
//! code on each edge that brings the predecessor's cache to it.
//!
//! The first edge translated into a region fixes what the region holds:
//! the slots that edge holds and that are used again at or after the
//! region (or inside a loop around it). Every other edge then writes back
//! what it holds dirty that the region does not hold, and loads what the
//! region holds that it does not (memory has the value of a slot that is
//! not held), so on every path into the region each of its variables has
//! its slot's current value. Memory is therefore always right, whatever
//! the choice; the choice only decides how many loads and stores remain.

use super::Lower;
use crate::ir::op::Op;
use crate::ir::operands::{Callee, Operand, operands};
use cranelift_codegen::ir::{Block, InstBuilder, Value};
use cranelift_frontend::Variable;
use std::collections::HashMap;

/// What the translation knows about the block's regions.
pub(super) struct Regions {
    /// The slots (and their variables) held on entry to the region that
    /// starts at each instruction, once an edge has fixed them.
    pub(super) entry: Vec<Option<Vec<(u32, Variable)>>>,
    /// The slots of each region's entry that some edge translated so far
    /// brings dirty (the others arrive clean on every edge; a loop head's
    /// back edges come later, so all of its slots count dirty).
    dirty_in: Vec<Vec<u32>>,
    /// Whether a later instruction jumps back to the region (its block is
    /// sealed only at the end).
    pub(super) loop_head: Vec<bool>,
    /// Whether each instruction lies inside a loop.
    in_loop: Vec<bool>,
    /// The farthest back edge to each loop head.
    loop_end: Vec<usize>,
    /// The last instruction at which each slot may be used again,
    /// counting a use inside a loop as a use at the loop's back edge.
    live_until: HashMap<u32, usize>,
}

impl Regions {
    /// Analyses the instructions `ops` of one block.
    pub(super) fn new(ops: &[Op]) -> Self {
        let n = ops.len();
        let mut loop_head = vec![false; n + 1];
        let mut loop_end = vec![0; n + 1];
        // The farthest back edge of a loop around each instruction.
        let mut reach: Vec<usize> = (0..n).collect();
        for (pc, op) in ops.iter().enumerate() {
            if let ([Some(t)], _) = super::flow::successors(op)
                && t <= pc
            {
                loop_head[t] = true;
                loop_end[t] = loop_end[t].max(pc);
                for r in &mut reach[t..=pc] {
                    *r = (*r).max(pc);
                }
            }
        }
        let mut live_until = HashMap::new();
        for (pc, op) in ops.iter().enumerate() {
            let mut o = *op;
            for (lo, len) in slots_of(&mut o) {
                for s in lo..lo + len {
                    let e = live_until.entry(s).or_insert(0);
                    *e = (*e).max(reach[pc]);
                }
            }
        }
        let in_loop = (0..=n)
            .map(|pc| pc < n && (reach[pc] > pc || loop_head[pc]))
            .collect();
        Regions {
            entry: vec![None; n + 1],
            dirty_in: vec![Vec::new(); n + 1],
            loop_head,
            in_loop,
            loop_end,
            live_until,
        }
    }

    fn live_at(&self, slot: u32, pc: usize) -> bool {
        self.live_until.get(&slot).is_some_and(|&u| u >= pc)
    }

    /// Whether straight-line code (outside loops) lets every held slot go
    /// at instruction `pc`, the start of a window of [`WINDOW`]
    /// instructions: values held across a whole long block would make the
    /// register allocator's work grow with the square of its length.
    pub(super) fn window_ends(&self, pc: usize) -> bool {
        pc.is_multiple_of(WINDOW) && !self.in_loop[pc]
    }

    /// Whether an edge from `from` to `t` crosses a window boundary
    /// outside loops (the region then holds nothing on entry).
    fn crosses_window(&self, from: usize, t: usize) -> bool {
        from / WINDOW != t / WINDOW && !self.in_loop[t] && !self.in_loop[from.min(t)]
    }
}

/// Instructions per window of straight-line code (see
/// [`Regions::window_ends`]).
const WINDOW: usize = 128;

/// The frame slots `op` names, as runs `(first, length)`: its slot
/// operands, the runs it reads and a standard FB's whole instance.
fn slots_of(op: &mut Op) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    operands(op, &mut |o| match o {
        Operand::Slot(s, _) => out.push((s.get(), 1)),
        Operand::Run(s, n) => out.push((s.get(), n)),
        Operand::Instance(s, Callee::Native(fb)) => out.push((s.get(), fb.instance_slots())),
        Operand::Instance(s, Callee::Fb(_)) => out.push((s.get(), 1)),
        _ => {}
    });
    out
}

impl Lower<'_, '_> {
    /// Fixes what the region at `t` holds, if no edge has yet.
    fn fix_entry(&mut self, t: usize) {
        if self.regions.entry[t].is_some() {
            return;
        }
        let crosses = self.regions.crosses_window(self.pc, t);
        let mut entry: Vec<(u32, Variable)> = self
            .cache
            .held
            .iter()
            .filter(|h| !crosses && self.regions.live_at(h.slot, t))
            .map(|h| (h.slot, h.var))
            .collect();
        if self.regions.loop_head[t] {
            self.hold_loop_slots(t, &mut entry);
        }
        self.regions.entry[t] = Some(entry);
    }

    /// Adds to the entry of loop head `t` the slots its loop names, in
    /// the order they first appear, up to the cache's size: each edge in
    /// loads them once and the loop keeps them in registers.
    fn hold_loop_slots(&mut self, t: usize, entry: &mut Vec<(u32, Variable)>) {
        let end = self.regions.loop_end[t];
        for op in &self.ops[t..=end] {
            let mut o = *op;
            for (first, len) in slots_of(&mut o) {
                for slot in first..first + len {
                    if entry.len() >= super::cache::MAX_HELD {
                        return;
                    }
                    if !entry.iter().any(|&(s, _)| s == slot) {
                        let var = self.spare_var(entry);
                        entry.push((slot, var));
                    }
                }
            }
        }
    }

    /// Notes which of region `t`'s slots the edge from here brings dirty.
    fn note_dirty(&mut self, t: usize) {
        self.fix_entry(t);
        let entry = self.regions.entry[t].as_deref().unwrap_or(&[]);
        for &(slot, _) in entry {
            let dirty = self.cache.held.iter().any(|h| h.slot == slot && h.dirty);
            if dirty && !self.regions.dirty_in[t].contains(&slot) {
                self.regions.dirty_in[t].push(slot);
            }
        }
    }

    /// Whether the edge from here to `t` needs code of its own.
    fn edge_needs_code(&mut self, t: usize) -> bool {
        self.note_dirty(t);
        let entry = self.regions.entry[t].as_deref().unwrap_or(&[]);
        let held = &self.cache.held;
        held.iter()
            .any(|h| h.dirty && !entry.iter().any(|&(s, _)| s == h.slot))
            || entry.iter().any(|&(s, var)| {
                held.iter()
                    .find(|h| h.slot == s)
                    .is_none_or(|h| h.var != var)
            })
    }

    /// Brings the cache to what region `t` holds on entry (see the module
    /// comment), in the current block.
    fn reconcile(&mut self, t: usize) {
        self.note_dirty(t);
        let entry = self.regions.entry[t].clone().unwrap_or_default();
        for h in self.cache.held.clone() {
            if h.dirty && !entry.iter().any(|&(s, _)| s == h.slot) {
                let v = self.b.use_var(h.var);
                self.store_slot(h.slot, v);
            }
        }
        // All values first, then the definitions: a variable may move
        // from one slot to another on this edge.
        let mut defs: Vec<(Variable, Value)> = Vec::new();
        for &(slot, var) in &entry {
            match self.cache.find(slot) {
                Some(i) if self.cache.held[i].var == var => {}
                Some(i) => defs.push((var, self.b.use_var(self.cache.held[i].var))),
                None => defs.push((var, self.load_slot(slot))),
            }
        }
        for (var, v) in defs {
            self.b.def_var(var, v);
        }
    }

    /// Writes back and drops the held slots that no successor in
    /// `targets` uses again, once before the branch rather than on each
    /// edge.
    pub(super) fn retire(&mut self, targets: &[usize]) {
        let mut i = 0;
        while i < self.cache.held.len() {
            let slot = self.cache.held[i].slot;
            if targets.iter().any(|&t| self.regions.live_at(slot, t)) {
                i += 1;
            } else {
                self.drop_held(i);
            }
        }
    }

    /// Writes back and drops the held slots that no instruction after `pc`
    /// uses (they would only take registers).
    pub(super) fn retire_after(&mut self, pc: usize) {
        let mut i = 0;
        while i < self.cache.held.len() {
            if self.regions.live_at(self.cache.held[i].slot, pc + 1) {
                i += 1;
            } else {
                self.drop_held(i);
            }
        }
    }

    /// Jumps to instruction `t` from the current block. (It changes
    /// nothing in the cache: the other edge of a branch is translated
    /// from the same state after it.)
    pub(super) fn jump_to(&mut self, t: usize) {
        self.reconcile(t);
        let to = self.start(t);
        self.b.ins().jump(to, &[]);
    }

    /// The block an edge to instruction `t` branches to: the region's own
    /// block, or a new one for the edge's code (filled by `fill_edge`).
    pub(super) fn edge_block(&mut self, t: usize) -> (Block, bool) {
        if self.edge_needs_code(t) {
            (self.b.create_block(), true)
        } else {
            (self.start(t), false)
        }
    }

    /// Fills the block made by `edge_block` for an edge to `t`.
    pub(super) fn fill_edge(&mut self, block: Block, t: usize) {
        self.b.switch_to_block(block);
        self.b.seal_block(block);
        self.jump_to(t);
    }

    /// To instruction `yes` when `cond` is non-zero, else to `no`.
    pub(super) fn branch_two(&mut self, cond: Value, yes: usize, no: usize) {
        self.retire(&[yes, no]);
        let (a, fill_a) = self.edge_block(yes);
        let (b, fill_b) = self.edge_block(no);
        self.b.ins().brif(cond, a, &[], b, &[]);
        if fill_a {
            self.fill_edge(a, yes);
        }
        if fill_b {
            self.fill_edge(b, no);
        }
    }

    /// Starts translating the region at instruction `pc`.
    pub(super) fn enter_region(&mut self, pc: usize) {
        // A region no edge has reached yet holds nothing, unless it is a
        // loop head (the back edges bring the loop's slots).
        if self.regions.entry[pc].is_none() {
            let mut entry = Vec::new();
            if self.regions.loop_head[pc] {
                self.hold_loop_slots(pc, &mut entry);
            }
            self.regions.entry[pc] = Some(entry);
        }
        let entry = self.regions.entry[pc].clone().unwrap_or_default();
        let dirty = if self.regions.loop_head[pc] {
            None
        } else {
            Some(std::mem::take(&mut self.regions.dirty_in[pc]))
        };
        self.enter(&entry, dirty.as_deref());
    }
}

#[cfg(test)]
mod tests {
    use super::Regions;
    use crate::ir::op::{Op, Slot, Target};

    #[test]
    fn a_use_inside_a_loop_lives_until_its_back_edge() {
        let s = Slot::new;
        let ops = [
            Op::Mov { d: s(1), s: s(2) },
            Op::Mov { d: s(3), s: s(1) },
            Op::Jz {
                c: s(3),
                t: Target::new(1),
            },
            Op::Mov { d: s(4), s: s(4) },
            Op::Ret,
        ];
        let r = Regions::new(&ops);
        assert!(r.loop_head[1] && !r.loop_head[0]);
        // Slot 1 is read at 1, inside the loop 1..=2: live at the back edge.
        assert!(r.live_at(1, 2) && !r.live_at(1, 3));
        assert!(r.live_at(2, 0) && !r.live_at(2, 1));
        assert!(r.live_at(4, 3) && !r.live_at(4, 4));
    }
}

//! What is retained, in the order of the image's table, and how each value
//! is copied out of a running PLC and written as text: the part of the
//! retain machinery that runs on the cycle's path ([`RetainLayout::take`]).

use super::fingerprint::{fingerprint, type_text};
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::retained::RetainedStorage;
use crate::ir::type_table::{TypeId, TypeKind};
use crate::vm::Machine;

/// How a retained value is stored and printed.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Shape {
    /// An elementary value (a subrange as its base type); the index into
    /// [`Snapshot::slots`].
    Scalar(ElemType, usize),
    /// An enumeration value; the index into [`Snapshot::slots`].
    Enum(Vec<(String, i64)>, usize),
    /// A STRING or WSTRING; the index into [`Snapshot::strings`].
    Text(bool, usize),
}

/// One retained value as the file names it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Entry {
    /// The outside path (`P.counter`).
    pub name: String,
    /// The type as the file spells it (`DINT`, `STRING[80]`).
    pub ty: String,
    /// How it is stored and printed.
    pub shape: Shape,
    /// Declared PERSISTENT.
    pub persistent: bool,
    /// A timer's start instant, saved relative to the snapshot's clock.
    pub clock_instant: bool,
    /// Absolute address of its slot (for a string, the slot holding its id).
    pub slot: u32,
    /// Its type in the image.
    pub type_id: TypeId,
}

/// The retained values of one compiled program.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RetainLayout {
    /// In the image's order.
    pub entries: Vec<Entry>,
    /// Addresses copied into [`Snapshot::slots`], in order.
    slot_addrs: Vec<u32>,
    /// The same as runs of consecutive addresses `(first address, length)`
    /// (an array is one run), copied slice by slice.
    slot_runs: Vec<(usize, usize)>,
    /// String ids copied into [`Snapshot::strings`], in order, with their
    /// capacity in characters.
    string_ids: Vec<(u32, u32)>,
    /// The fingerprint of the names and types.
    pub fingerprint: String,
}

/// The retained values at one moment, raw.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Snapshot {
    /// The number of the next cycle when it was taken.
    pub cycle: u64,
    /// The clock of the next cycle when it was taken (ns).
    pub now: i64,
    /// The slot values, as [`RetainLayout`] orders them.
    pub slots: Vec<u64>,
    /// The string values, as [`RetainLayout`] orders them.
    pub strings: Vec<String>,
}

impl RetainLayout {
    /// The layout of `image`'s retained table.
    pub(crate) fn new(image: &Image) -> RetainLayout {
        let mut layout = RetainLayout {
            entries: Vec::with_capacity(image.retained.len()),
            slot_addrs: Vec::new(),
            slot_runs: Vec::new(),
            string_ids: Vec::new(),
            fingerprint: String::new(),
        };
        for r in &image.retained {
            let (shape, slot) = match (r.storage, &image.types.get(r.ty).kind) {
                (RetainedStorage::Text { slot, string }, TypeKind::Str { wide, max }) => {
                    layout.string_ids.push((string, *max));
                    (Shape::Text(*wide, layout.string_ids.len() - 1), slot)
                }
                (RetainedStorage::Slot(a), TypeKind::Enum { values, .. }) => {
                    layout.slot_addrs.push(a);
                    (Shape::Enum(values.clone(), layout.slot_addrs.len() - 1), a)
                }
                (RetainedStorage::Slot(a), _) => {
                    let e = image.types.scalar(r.ty).unwrap_or(ElemType::Lint);
                    layout.slot_addrs.push(a);
                    (Shape::Scalar(e, layout.slot_addrs.len() - 1), a)
                }
                // The linker makes a text storage only for strings.
                (RetainedStorage::Text { .. }, _) => continue,
            };
            layout.entries.push(Entry {
                name: r.path.clone(),
                ty: type_text(&image.types, r.ty),
                shape,
                persistent: r.persistent,
                clock_instant: r.clock_instant,
                slot,
                type_id: r.ty,
            });
        }
        for &a in &layout.slot_addrs {
            match layout.slot_runs.last_mut() {
                Some((first, len)) if *first + *len == a as usize => *len += 1,
                _ => layout.slot_runs.push((a as usize, 1)),
            }
        }
        let pairs = layout
            .entries
            .iter()
            .map(|e| (e.name.as_str(), e.ty.as_str()));
        layout.fingerprint = fingerprint(pairs);
        layout
    }

    /// An empty snapshot with room for every value (strings at their
    /// capacity), so that [`Self::take`] does not allocate.
    pub(crate) fn buffer(&self) -> Snapshot {
        Snapshot {
            cycle: 0,
            now: 0,
            slots: vec![0; self.slot_addrs.len()],
            // A character takes at most 4 bytes in UTF-8.
            strings: (self.string_ids.iter())
                .map(|&(_, max)| String::with_capacity((max as usize).saturating_mul(4)))
                .collect(),
        }
    }

    /// Copies the retained values of `machine` into `snap` (on the cycle's
    /// path: plain copies into reserved room). Values that the machine does
    /// not hold (it runs another image) are left as they are.
    pub(crate) fn take(&self, machine: &Machine, cycle: u64, now: i64, snap: &mut Snapshot) {
        snap.cycle = cycle;
        snap.now = now;
        snap.slots.resize(self.slot_addrs.len(), 0);
        let mut at = 0;
        for &(first, len) in &self.slot_runs {
            if let (Some(src), Some(dst)) = (
                machine.mem.get(first..first + len),
                snap.slots.get_mut(at..at + len),
            ) {
                dst.copy_from_slice(src);
            }
            at += len;
        }
        snap.strings.resize_with(self.string_ids.len(), String::new);
        for (dst, &(id, _)) in snap.strings.iter_mut().zip(&self.string_ids) {
            if let Some(s) = machine.strings.get(id as usize) {
                dst.clone_from(&s.text);
            }
        }
    }

    /// Puts the values of `snap` (taken with this layout) back into
    /// `machine` — only the entries `only` marks, when given; a timer's
    /// start instant is moved to the clock `now`.
    pub(crate) fn put(
        &self,
        snap: &Snapshot,
        machine: &mut Machine,
        now: i64,
        only: Option<&[bool]>,
    ) {
        for (k, e) in self.entries.iter().enumerate() {
            if only.is_some_and(|m| !m.get(k).copied().unwrap_or(false)) {
                continue;
            }
            match e.shape {
                Shape::Scalar(_, i) | Shape::Enum(_, i) => {
                    let mut v = snap.slots.get(i).copied().unwrap_or(0);
                    if e.clock_instant {
                        v = shift_instant(v, snap.now, now);
                    }
                    if let Some(slot) = machine.mem.get_mut(e.slot as usize) {
                        *slot = v;
                    }
                }
                Shape::Text(_, i) => {
                    let id = self.string_ids.get(i).map_or(u32::MAX, |s| s.0);
                    if let (Some(s), Some(text)) =
                        (machine.strings.get_mut(id as usize), snap.strings.get(i))
                    {
                        s.set(text);
                    }
                }
            }
        }
    }
}

/// An instant taken on clock `from`, moved to clock `to` (the same time
/// before `to` as it was before `from`).
pub(crate) fn shift_instant(instant: u64, from: i64, to: i64) -> u64 {
    (instant as i64).wrapping_sub(from).wrapping_add(to) as u64
}

//! A table of live objects addressed by generation-checked 64-bit ids:
//! the slot index (from 1) in the low half, the slot's generation in the
//! high half. Freeing a slot advances its generation, so a freed, foreign
//! or made-up id is refused every time (only a slot reused 2^32 times could
//! bring an old id back). PLC handles and stop tokens both live in one.

use std::sync::{Mutex, MutexGuard, PoisonError};

struct Slot<T> {
    generation: u32,
    value: Option<T>,
}

/// Live objects of type `T` by id.
pub(crate) struct SlotTable<T> {
    slots: Mutex<Vec<Slot<T>>>,
}

impl<T: Clone> SlotTable<T> {
    /// An empty table (usable in a `static`).
    pub(crate) const fn new() -> Self {
        SlotTable {
            slots: Mutex::new(Vec::new()),
        }
    }

    /// The slots; only ever locked around a few vector operations that
    /// cannot panic, so a poisoned lock still holds consistent data.
    fn slots(&self) -> MutexGuard<'_, Vec<Slot<T>>> {
        self.slots.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Stores `value` in a free slot and gives its id (never 0).
    pub(crate) fn insert(&self, value: T) -> u64 {
        let mut slots = self.slots();
        let index = match slots.iter().position(|s| s.value.is_none()) {
            Some(i) => {
                slots[i].value = Some(value);
                i
            }
            None => {
                slots.push(Slot {
                    generation: 1,
                    value: Some(value),
                });
                slots.len() - 1
            }
        };
        u64::from(slots[index].generation) << 32 | (index as u64 + 1)
    }

    /// The slot index of a live id.
    fn live_index(slots: &[Slot<T>], id: u64) -> Option<usize> {
        let (generation, index) = ((id >> 32) as u32, id as u32 as usize);
        let i = index.checked_sub(1)?;
        let slot = slots.get(i)?;
        (slot.generation == generation && slot.value.is_some()).then_some(i)
    }

    /// A clone of the value behind a live id (the table is not locked
    /// while the caller uses it).
    pub(crate) fn get(&self, id: u64) -> Option<T> {
        let slots = self.slots();
        let i = Self::live_index(&slots, id)?;
        slots[i].value.clone()
    }

    /// Frees a live id's slot; false when the id is not live.
    pub(crate) fn remove(&self, id: u64) -> bool {
        let mut slots = self.slots();
        let Some(i) = Self::live_index(&slots, id) else {
            return false;
        };
        slots[i].value = None;
        slots[i].generation = slots[i].generation.wrapping_add(1).max(1);
        true
    }
}

//! The image of the last completed cycle as the clients read it: two
//! copies of the tables, one being read while the scan side fills the
//! other, so that the scan never waits for a client.

use super::mapping::Tables;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{PoisonError, RwLock};

/// Two buffers and which one is current.
#[derive(Debug, Default)]
pub(crate) struct Published {
    buffers: [RwLock<Tables>; 2],
    current: AtomicUsize,
}

impl Published {
    /// Runs `read` on the current tables. Blocks only while the scan side
    /// writes that buffer (a copy of a few kilobytes), never on the scan.
    pub(crate) fn read<R>(&self, read: impl FnOnce(&Tables) -> R) -> R {
        let i = self.current.load(Ordering::Acquire);
        let guard = self.buffers[i]
            .read()
            .unwrap_or_else(PoisonError::into_inner);
        read(&guard)
    }

    /// Publishes `tables` into the other buffer and makes it current,
    /// unless a client still reads that buffer (then nothing changes and
    /// false is returned: the next cycle publishes again). Never blocks.
    pub(crate) fn try_publish(&self, tables: &Tables) -> bool {
        let next = 1 - self.current.load(Ordering::Acquire);
        let Ok(mut buffer) = self.buffers[next].try_write() else {
            return false;
        };
        buffer.copy_from(tables);
        drop(buffer);
        self.current.store(next, Ordering::Release);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::address::{Addressing, Area, Width};

    #[test]
    fn a_reader_holding_the_back_buffer_makes_the_publish_wait_a_cycle() {
        let p = Published::default();
        let mut t = Tables::default();
        let q = Addressing::Iec.table(Area::Output, Width::Byte);
        t.table_mut(q)[0] = 1;
        assert!(p.try_publish(&t));
        assert_eq!(p.read(|t| t.table(q)[0]), 1);
        // A reader still on buffer 0 (the old one) blocks the next publish.
        let old = p.buffers[0].read().unwrap();
        t.table_mut(q)[0] = 2;
        assert!(!p.try_publish(&t));
        assert_eq!(p.read(|t| t.table(q)[0]), 1);
        drop(old);
        assert!(p.try_publish(&t));
        assert_eq!(p.read(|t| t.table(q)[0]), 2);
    }
}

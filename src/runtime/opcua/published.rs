//! The values of the last completed cycle as the server reads them: two
//! frames, one being read by the server while the scan side fills the
//! other, so that the scan never waits for the server.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::SystemTime;

/// The served values of one cycle.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    /// The cycle that produced them (the PLC's cycle counter).
    pub(crate) cycle: u64,
    /// When the scan side copied them.
    pub(crate) at: SystemTime,
    /// Each leaf's slot (a string's slot is its handle: see `text`).
    pub(crate) raw: Vec<u64>,
    /// Each STRING leaf's text (empty for the others).
    pub(crate) text: Vec<String>,
}

impl Frame {
    /// A frame for `leaves` values, all zero.
    pub(crate) fn new(leaves: usize) -> Frame {
        Frame {
            cycle: 0,
            at: SystemTime::UNIX_EPOCH,
            raw: vec![0; leaves],
            text: vec![String::new(); leaves],
        }
    }
}

/// Two frames and which one is current.
#[derive(Debug)]
pub(crate) struct Published {
    frames: [Mutex<Frame>; 2],
    current: AtomicUsize,
}

impl Published {
    /// Two empty frames for `leaves` values.
    pub(crate) fn new(leaves: usize) -> Published {
        Published {
            frames: [
                Mutex::new(Frame::new(leaves)),
                Mutex::new(Frame::new(leaves)),
            ],
            current: AtomicUsize::new(0),
        }
    }

    /// Fills the frame the server is not reading with `fill` and makes it
    /// current, unless the server still holds it (then nothing changes and
    /// false is returned: the next cycle publishes). Never blocks.
    pub(crate) fn try_publish(&self, fill: impl FnOnce(&mut Frame)) -> bool {
        let next = 1 - self.current.load(Ordering::Acquire);
        let Ok(mut frame) = self.frames[next].try_lock() else {
            return false;
        };
        fill(&mut frame);
        drop(frame);
        self.current.store(next, Ordering::Release);
        true
    }

    /// Runs `read` on the current frame. Blocks only while the scan side
    /// fills that frame, which it does only once it is no longer current.
    pub(crate) fn read<R>(&self, read: impl FnOnce(&Frame) -> R) -> R {
        let i = self.current.load(Ordering::Acquire);
        let frame = self.frames[i]
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        read(&frame)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_the_server_holds_is_not_overwritten() {
        let p = Published::new(1);
        assert!(p.try_publish(|f| f.raw[0] = 1));
        assert_eq!(p.read(|f| f.raw[0]), 1);
        // The server still holds frame 0 (the old one), which the next
        // publish would fill: it is put off.
        let held = p.frames[0].lock().unwrap();
        assert!(!p.try_publish(|f| f.raw[0] = 2));
        assert_eq!(p.read(|f| f.raw[0]), 1);
        drop(held);
        assert!(p.try_publish(|f| f.raw[0] = 3));
        assert_eq!(p.read(|f| f.raw[0]), 3);
    }
}

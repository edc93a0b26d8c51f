//! Exception handlers of a code block (`__TRY ... __CATCH`): a table kept
//! beside the instructions, read only when a fault happens, so that a
//! guarded statement costs nothing while nothing faults.

use super::op::Slot;

/// One `__TRY` region of a block: a fault at an instruction in
/// `start..end` (or in a call made there) writes its exception code into
/// `exception` and goes on at `catch`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Handler {
    /// First instruction of the guarded statements.
    pub start: u32,
    /// One past their last instruction.
    pub end: u32,
    /// First instruction of the `__CATCH` statements.
    pub catch: u32,
    /// The frame slot of the `__CATCH` variable.
    pub exception: Slot,
}

/// The innermost handler guarding instruction `pc`, if any: regions
/// nest, so of those holding `pc` it is the shortest (two may start at
/// the same instruction).
pub fn guarding(handlers: &[Handler], pc: u32) -> Option<&Handler> {
    handlers
        .iter()
        .filter(|h| h.start <= pc && pc < h.end)
        .min_by_key(|h| h.end - h.start)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn handler(start: u32, end: u32, catch: u32) -> Handler {
        Handler {
            start,
            end,
            catch,
            exception: Slot::new(0),
        }
    }

    #[test]
    fn the_innermost_region_guards_an_instruction() {
        let table = [handler(0, 10, 12), handler(3, 6, 8), handler(0, 2, 3)];
        assert_eq!(guarding(&table, 4).map(|h| h.catch), Some(8));
        assert_eq!(guarding(&table, 1).map(|h| h.catch), Some(3));
        assert_eq!(guarding(&table, 7).map(|h| h.catch), Some(12));
        assert_eq!(guarding(&table, 10), None);
        assert_eq!(guarding(&[], 0), None);
    }
}

//! The layout code a reference's object gets (`RefMake`'s `layout`): the
//! code of its elementary type, or, for a structure or an array of
//! structures or strings, of its byte layout (`ir::byte_layout`), which
//! the program keeps once per type. With it a `POINTER TO BYTE` reads and
//! writes the bytes of a record, as TwinCAT code copies records into byte
//! buffers (TcUnit's message queue in `FB_MemRingBuffer`).

use super::layout_code;
use crate::ir::byte_layout::ByteLayout;
use crate::ir::refs::FIRST_AGGREGATE_LAYOUT;
use crate::ir::type_table::TypeId;
use crate::sema::body::BodyBuilder;

impl BodyBuilder<'_> {
    /// The layout code of an object of type `t` (`RefMake`'s): its
    /// elementary type's, or its aggregate's byte layout, added to the
    /// program's on first use; 0 when it has neither.
    pub(in crate::sema) fn object_layout(&mut self, t: TypeId) -> u16 {
        match layout_code(self.types, t) {
            0 => self.aggregate_layout(t),
            code => code.into(),
        }
    }

    /// The code of the byte layout of aggregate `t` (0: it has none).
    fn aggregate_layout(&mut self, t: TypeId) -> u16 {
        let layouts = &mut self.out.byte_layouts;
        if let Some(i) = layouts.get_index_of(&t) {
            return FIRST_AGGREGATE_LAYOUT.saturating_add(i as u16);
        }
        let unions = &self.model.unions;
        let Some(layout) = ByteLayout::of(self.types, t, &|u| unions.contains_key(&u)) else {
            return 0;
        };
        // Past the last code a `u16` holds, objects go without bytes.
        let Some(code) = u16::try_from(layouts.len())
            .ok()
            .and_then(|i| FIRST_AGGREGATE_LAYOUT.checked_add(i))
        else {
            return 0;
        };
        layouts.insert(t, layout);
        code
    }
}

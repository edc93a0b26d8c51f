//! What each method's code block resets on entry: its outputs, result and
//! temporaries (its inputs are stored by the caller just before the call).

use super::Linker;

impl Linker<'_> {
    /// Sets the entry resets of every method block of every emitted FB.
    pub(super) fn set_method_resets(&mut self) {
        let model = self.model;
        for (key, fb) in &model.oop.fbs {
            let Some(&p) = model.pou_index.get(key) else {
                continue;
            };
            if !model.emitted.get(p).copied().unwrap_or(false) {
                continue;
            }
            for (v, code) in fb.versions.iter().zip(&fb.codes) {
                if v.resets.is_empty() {
                    continue;
                }
                let (init, strings) = self.entry_resets_of(p, Some(&v.resets));
                let block = &mut self.out.codes[code.index()];
                block.entry_init = init;
                block.entry_strings = strings;
            }
        }
    }
}

impl Linker<'_> {
    /// Puts the offsets of hidden method variables reached through
    /// interfaces into the instructions that carry their marks.
    pub(super) fn fill_oop_offsets(&mut self) {
        if self.out.oop_offsets.is_empty() {
            return;
        }
        use crate::ir::op::Op;
        use crate::sema::model::Storage;
        let mark = crate::sema::oop::calls::OFFSET_MARK;
        let model = self.model;
        let offsets: Vec<u32> = self
            .out
            .oop_offsets
            .iter()
            .map(
                |(p, key)| match model.pous[*p].vars.get(key).map(|v| v.storage) {
                    Some(Storage::Frame(o) | Storage::Ref(o)) => o,
                    _ => 0,
                },
            )
            .collect();
        for code in &mut self.out.codes {
            for op in &mut code.ops {
                if let Op::LoadInd { off, .. } | Op::StoreInd { off, .. } | Op::AddrAdd { off, .. } =
                    op
                    && *off & mark != 0
                {
                    *off = offsets.get((*off & !mark) as usize).copied().unwrap_or(0);
                }
            }
        }
    }
}

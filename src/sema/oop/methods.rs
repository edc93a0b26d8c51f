//! Method versions as code blocks of their FB: allocated before any body is
//! emitted (a caller may be emitted before the FB it calls through an
//! interface), filled when the FB's body is emitted, each with temporaries
//! of its own above the body's (a method calling another method of the same
//! instance keeps its temporaries).

use super::OopInfo;
use crate::diagnostics::Diagnostic;
use crate::ir::image::{CodeBlock, CodeKind};
use crate::ir::op::{CodeIdx, Op};
use crate::sema::body::BodyBuilder;
use crate::sema::declare::Declarer;
use crate::sema::emit::Fcx;
use crate::sema::model::VarInfo;
use crate::syntax::ast::Body;

/// The code being emitted in an FB that has methods.
#[derive(Debug, Clone)]
pub(crate) struct Scope {
    /// The FB's key (the instance's type).
    pub fb: String,
    /// The key of the FB whose source the code comes from (for `SUPER^`
    /// and access checks).
    pub origin: String,
    /// The method version, or `None` for the FB's body.
    pub version: Option<usize>,
    /// The code block (for the call graph).
    pub code: CodeIdx,
    /// Diagnostics reported before this FB's code was emitted (those after
    /// are checked for copies: inherited code is compiled once per FB).
    pub diags_before: usize,
}

/// Gives every method version a code block (an empty one until its FB is
/// emitted) and hands the OOP tables to the model.
pub(crate) fn allocate(declarer: &mut Declarer, mut info: OopInfo) {
    let mut keys: Vec<String> = info.fbs.keys().cloned().collect();
    keys.sort_by_key(|k| info.fbs[k].tid);
    for k in keys {
        let fb = info.fbs.get_mut(&k).expect("key from the map");
        for v in &fb.versions {
            let code = CodeIdx::new(declarer.out.codes.len() as u32);
            declarer.out.codes.push(CodeBlock {
                name: format!("{}.{}", fb.name, v.name.name),
                kind: CodeKind::FunctionBlock,
                ops: vec![Op::Ret],
                spans: vec![v.span],
                entry_init: Vec::new(),
                entry_strings: Vec::new(),
                frame: 0,
                frame_size: 0,
                handlers: Vec::new(),
            });
            fb.codes.push(code);
        }
    }
    declarer.model.oop = info;
}

impl BodyBuilder<'_> {
    /// Enters the body of POU being built, if it is an FB with methods.
    pub(in crate::sema) fn enter_oop_body(&mut self) {
        let p = self.block.pou;
        let key = self.model.pous[p].name.to_ascii_uppercase();
        if self.model.oop.fbs.contains_key(&key) {
            self.oop = Some(Scope {
                fb: key.clone(),
                origin: key,
                version: None,
                code: self.model.pous[p].code,
                diags_before: self.diags.len(),
            });
        }
    }

    /// A variable of the method being emitted (by its user key).
    pub(in crate::sema) fn oop_local(&self, key: &str) -> Option<&VarInfo> {
        let scope = self.oop.as_ref()?;
        let model = self.model;
        let v = &model.oop.fbs.get(&scope.fb)?.versions[scope.version?];
        let hidden = v.locals.get(key)?;
        model.pous.get(self.block.pou)?.vars.get(hidden)
    }

    /// Emits every method version of the FB being built into its block.
    pub(in crate::sema) fn emit_oop_methods(&mut self, pou: &crate::syntax::ast::Pou) {
        let Some(scope) = self.oop.clone() else {
            return;
        };
        let model = self.model;
        let Some(fb) = model.oop.fbs.get(&scope.fb) else {
            return;
        };
        let p = self.block.pou;
        let mut top = self.block.temp_max;
        for (vi, v) in fb.versions.iter().enumerate() {
            let code = fb.codes[vi];
            let mut sub = Fcx::new(p, top);
            sub.span = v.span;
            let outer = std::mem::replace(&mut self.block, sub);
            self.oop = Some(Scope {
                fb: scope.fb.clone(),
                origin: v.origin.clone(),
                version: Some(vi),
                code,
                diags_before: scope.diags_before,
            });
            let guard = v.guard.as_deref().and_then(|k| self.enter_guard(k));
            self.emit_method_computed_inits(pou, &v.resets);
            match &v.body {
                Body::St(stmts) => self.stmts(stmts),
                Body::Il(lines) => {
                    self.il_body(lines);
                }
                Body::Sfc(_) => self.diags.error(
                    "E915",
                    v.name.span,
                    "a METHOD body must be Structured Text or Instruction List",
                ),
            }
            let end = self.block.here();
            for j in std::mem::take(&mut self.block.returns) {
                self.block.patch(j, end);
            }
            if let Some(flag) = guard {
                self.leave_guard(flag);
            }
            let mut sub = std::mem::replace(&mut self.block, outer);
            sub.span = v.span;
            sub.emit(Op::Ret);
            top = top.max(sub.temp_max);
            for (at, callee) in std::mem::take(&mut sub.fixups) {
                self.out.fixups.push((code, at, callee));
            }
            let (consts, pins) = sub.take_tagged();
            self.pending_blocks.push((code, consts, pins));
            self.owned_blocks.push(code);
            let block = &mut self.out.codes[code.index()];
            block.ops = sub.ops;
            block.spans = sub.spans;
            block.handlers = sub.handlers;
        }
        self.block.temp_max = top;
        self.drop_inherited_copies(scope.diags_before);
        self.oop = Some(scope);
    }

    /// Code an FB inherits is compiled in every FB that has it, so an error
    /// in it would be reported by the parent and by each child: the copies
    /// (same code, same place) reported since `before` are dropped.
    fn drop_inherited_copies(&mut self, before: usize) {
        if self.diags.len() == before {
            return;
        }
        let all: Vec<Diagnostic> = self.diags.iter().cloned().collect();
        self.diags.truncate(before);
        for (i, d) in all.iter().enumerate().skip(before) {
            let copy = all[..i]
                .iter()
                .any(|o| o.code == d.code && o.span == d.span);
            if !copy {
                self.diags.push(d.clone());
            }
        }
    }
}

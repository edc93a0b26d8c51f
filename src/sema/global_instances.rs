//! Which declarations of a global variable list hold function block
//! instances or references to blocks, and in which order to declare them.
//! They are declared after the lists' other globals: laying out a block
//! emits its body, and that body may use any global (TcUnit's
//! `GVL_TcUnit` starts with `TcUnitRunner : FB_TcUnitRunner;`, whose body
//! reads the list's later variables, and declares a `POINTER TO
//! FB_TestSuite` before the message queue the suite's code writes to).
//! Among themselves, a declaration whose block's code names another list
//! instance (`GVL_TcUnit.GetCpuCounter`) comes after it; the written order
//! is kept wherever it works. Their memory comes after the other globals';
//! nothing else depends on the order.

use super::declare::Declarer;
use crate::syntax::ast::{PouKind, TypeSpec, VarBlock};
use std::collections::{HashMap, HashSet};

impl Declarer<'_> {
    /// The indexes of `block`'s declarations whose type names a user
    /// FUNCTION_BLOCK, directly or through arrays and references
    /// (`POINTER TO FB_TestSuite`): resolving one lays the block out.
    pub(super) fn instance_decls(&self, block: &VarBlock) -> Vec<usize> {
        (0..block.decls.len())
            .filter(|&d| self.block_behind(&block.decls[d].ty).is_some())
            .collect()
    }

    /// The order in which to declare the instances `lists` holds (each
    /// list with the indexes of its instance declarations), as (list,
    /// declaration) pairs: every instance after the instances its block's
    /// code names, the written order where nothing asks otherwise (a ring
    /// of such names keeps the written order).
    pub(super) fn instance_order(&self, lists: &[(&VarBlock, Vec<usize>)]) -> Vec<(usize, usize)> {
        let all: Vec<(usize, usize)> = lists
            .iter()
            .enumerate()
            .flat_map(|(l, (_, decls))| decls.iter().map(move |&d| (l, d)))
            .collect();
        let mut owner: HashMap<String, usize> = HashMap::new();
        for (n, &(l, d)) in all.iter().enumerate() {
            for name in &lists[l].0.decls[d].names {
                owner.entry(name.key()).or_insert(n);
            }
        }
        let mut named_by_fb: HashMap<usize, Vec<usize>> = HashMap::new();
        let deps: Vec<Vec<usize>> = all
            .iter()
            .enumerate()
            .map(|(n, &(l, d))| {
                let Some(p) = self.block_behind(&lists[l].0.decls[d].ty) else {
                    return Vec::new();
                };
                let named = named_by_fb
                    .entry(p)
                    .or_insert_with(|| self.instances_named_by(p, &owner));
                named.iter().copied().filter(|&o| o != n).collect()
            })
            .collect();
        let (order, _rings) = super::const_order::order(&deps);
        order.into_iter().map(|n| all[n]).collect()
    }

    /// The entries of `owner` that the code of FB `p` names: its body,
    /// methods and properties, and those of the blocks it extends or holds
    /// instances of (their bodies are emitted when it is laid out).
    fn instances_named_by(&self, p: usize, owner: &HashMap<String, usize>) -> Vec<usize> {
        let mut named = HashSet::new();
        let mut note = |name: &str| {
            if let Some(&o) = owner.get(&name.to_ascii_uppercase()) {
                named.insert(o);
            }
            false
        };
        let mut seen = HashSet::from([p]);
        let mut work = vec![p];
        while let Some(q) = work.pop() {
            let (u, i) = self.model.pous[q].ast;
            let crate::syntax::ast::Item::Pou(pou) = &self.units[u].items[i] else {
                continue;
            };
            super::body_names::any_name_or_member(&pou.body, &mut note);
            let mut held: Vec<&TypeSpec> = pou
                .var_blocks
                .iter()
                .flat_map(|b| b.decls.iter().map(|d| &d.ty))
                .collect();
            let mut parent = None;
            if let Some(oop) = &pou.oop {
                for m in &oop.methods {
                    super::body_names::any_name_or_member(&m.body, &mut note);
                    for accessor in m.property.iter().flatten() {
                        super::body_names::any_name_or_member(&accessor.body, &mut note);
                    }
                    held.extend(
                        m.var_blocks
                            .iter()
                            .flat_map(|b| b.decls.iter().map(|d| &d.ty)),
                    );
                }
                parent = oop.extends.as_ref().map(|e| e.key());
            }
            let inner = held.into_iter().filter_map(|t| self.fb_named(t));
            let parent = parent.and_then(|k| self.model.pou_index.get(&k).copied());
            for r in inner.chain(parent) {
                if seen.insert(r) {
                    work.push(r);
                }
            }
        }
        let mut named: Vec<usize> = named.into_iter().collect();
        named.sort_unstable();
        named
    }

    /// The user FUNCTION_BLOCK `spec` names, directly or through arrays
    /// and references (`POINTER TO FB_TestSuite`): resolving it lays the
    /// block out, which emits its body, so the globals that body may read
    /// must be declared before.
    fn block_behind(&self, spec: &TypeSpec) -> Option<usize> {
        match spec {
            TypeSpec::Ref { target, .. } => self.block_behind(target),
            TypeSpec::Array { elem, .. } => self.block_behind(elem),
            spec => self.fb_named(spec),
        }
    }

    /// The user FUNCTION_BLOCK `spec` names, directly or as the element
    /// type of an array.
    fn fb_named(&self, spec: &TypeSpec) -> Option<usize> {
        match spec {
            TypeSpec::Named(id) => {
                let key = id.key();
                if self.type_decls.contains_key(&key) {
                    return None;
                }
                let &p = self.model.pou_index.get(&key)?;
                (self.model.pous[p].kind == PouKind::FunctionBlock).then_some(p)
            }
            TypeSpec::Array { elem, .. } => self.fb_named(elem),
            _ => None,
        }
    }
}

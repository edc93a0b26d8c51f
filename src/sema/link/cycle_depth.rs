//! How deep a cycle of method calls through interfaces can nest. Such a
//! cycle is allowed with re-entry guards (`sema::oop::reentry`): each of
//! its methods runs at most once per instance at a time, so the cycle
//! nests at most once per instance of each method's block. That count,
//! taken from the program's variables, bounds the executor's stack as the
//! acyclic chains do (`call_depth`).

use super::Linker;
use super::recursion::strong_components;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
use crate::source::Span;
use std::collections::{BTreeMap, HashMap};

/// The deepest nesting of the guarded cycles: the levels they may add,
/// a description of the cycle that adds most, and where it is called.
pub(super) struct CycleNesting {
    pub levels: u64,
    pub what: String,
    pub span: Span,
}

impl Linker<'_> {
    /// The nesting the cycles of guarded methods may add to the acyclic
    /// chains (`None` without such a cycle).
    pub(super) fn cycle_nesting(&self) -> Option<CycleNesting> {
        let component = strong_components(&self.call_graph());
        // Guarded method code -> the block it runs on (ordered, so that
        // the message is the same from run to run).
        let mut owner: BTreeMap<usize, &str> = BTreeMap::new();
        for (key, fb) in &self.model.oop.fbs {
            for (v, code) in fb.versions.iter().zip(&fb.codes) {
                if v.guard.is_some() {
                    owner.insert(code.index(), key.as_str());
                }
            }
        }
        let mut counts = InstanceCounts::new(self);
        let mut total: BTreeMap<usize, (u64, Vec<usize>)> = BTreeMap::new();
        for (&code, fb) in &owner {
            let instances = counts.of(fb);
            let e = total.entry(component[code]).or_default();
            e.0 = e.0.saturating_add(instances);
            e.1.push(code);
        }
        let (levels, codes) = total.into_values().max_by_key(|(l, _)| *l)?;
        let names: Vec<&str> = codes
            .iter()
            .map(|&c| self.out.codes[c].name.as_str())
            .collect();
        let span = self
            .out
            .calls
            .iter()
            .find(|&&(_, b, _)| codes.contains(&b.index()))
            .map(|&(_, _, s)| s)?;
        Some(CycleNesting {
            levels,
            what: format!(
                "the cycle of calls through interfaces between {} may nest once per instance: {levels} times",
                names.join(", ")
            ),
            span,
        })
    }
}

/// How many instances of each function block the program holds (in its
/// global variables, program instances and FUNCTION frames, arrays
/// counted element by element).
struct InstanceCounts<'l> {
    types: &'l TypeTable,
    /// The types holding instances: (type, how many of it).
    roots: Vec<(TypeId, u64)>,
    /// Instances of a block inside a value of a type: (block, type).
    memo: HashMap<(TypeId, TypeId), u64>,
    /// Each block's type, by key.
    block_types: HashMap<String, TypeId>,
}

impl<'l> InstanceCounts<'l> {
    fn new(linker: &'l Linker<'_>) -> Self {
        let model = linker.model;
        let mut roots: Vec<(TypeId, u64)> = model.globals.values().map(|g| (g.ty, 1)).collect();
        for pou in &model.pous {
            match pou.kind {
                crate::syntax::ast::PouKind::Program => roots.push((pou.ty, 1)),
                crate::syntax::ast::PouKind::Function => {
                    roots.extend(pou.vars.values().map(|v| (v.ty, 1)));
                }
                _ => {}
            }
        }
        let block_types = model
            .pou_index
            .iter()
            .map(|(k, &p)| (k.clone(), model.pous[p].ty))
            .collect();
        Self {
            types: linker.types,
            roots,
            memo: HashMap::new(),
            block_types,
        }
    }

    /// The instances of block `key`.
    fn of(&mut self, key: &str) -> u64 {
        let Some(&block) = self.block_types.get(key) else {
            return 0;
        };
        let roots = self.roots.clone();
        roots.iter().fold(0u64, |sum, &(t, k)| {
            sum.saturating_add(self.inside(block, t).saturating_mul(k))
        })
    }

    /// The instances of `block` inside a value of type `t`.
    fn inside(&mut self, block: TypeId, t: TypeId) -> u64 {
        if t == block {
            return 1;
        }
        if let Some(&n) = self.memo.get(&(block, t)) {
            return n;
        }
        let n = match &self.types.get(t).kind {
            TypeKind::Struct { fields: members } | TypeKind::Pou { members, .. } => {
                let members: Vec<TypeId> = members.iter().map(|m| m.ty).collect();
                members
                    .into_iter()
                    .fold(0u64, |s, m| s.saturating_add(self.inside(block, m)))
            }
            TypeKind::Array { dims, elem } => {
                let len: u64 = dims.iter().map(|d| d.len()).product();
                let elem = *elem;
                self.inside(block, elem).saturating_mul(len)
            }
            _ => 0,
        };
        self.memo.insert((block, t), n);
        n
    }
}

//! What the instance-call pass knows of the FUNCTION_BLOCKs and PROGRAMs:
//! their ancestry, their `FB_init`/`FB_exit` and `call_after_init`
//! methods, and which ones hold members that need calls.

use super::Phase;
use crate::syntax::ast::{
    CompilationUnit, Expr, ExprKind, Ident, Initializer, Item, Pou, PouKind, TypeSpec, VarDecl,
    VarKind,
};
use crate::syntax::oop::Method;
use std::collections::{HashMap, HashSet};

/// One FUNCTION_BLOCK or PROGRAM.
pub(super) struct Block<'a> {
    /// Its declaration.
    pub pou: &'a Pou,
    /// Where it is: (unit, item).
    pub at: (usize, usize),
    /// The parent's key.
    pub parent: Option<String>,
    /// Its own methods.
    pub methods: &'a [Method],
}

impl<'a> Block<'a> {
    /// Its own method `key` (case-folded), if it declares one.
    pub fn method(&self, key: &str) -> Option<&'a Method> {
        self.methods.iter().find(|m| m.name.key() == key)
    }

    /// Its own methods declared after `{attribute 'call_after_init'}`.
    fn after_init(&self) -> impl Iterator<Item = &'a Ident> {
        self.methods
            .iter()
            .filter(|m| m.call_after_init)
            .map(|m| &m.name)
    }
}

/// The blocks by key, and which hold members that need calls (per phase,
/// computed once).
pub(super) struct Index<'a> {
    pub blocks: HashMap<String, Block<'a>>,
    /// The keys of the declared TYPEs, POUs and interfaces.
    types: HashSet<String>,
    /// The keys of the interfaces.
    interfaces: HashSet<String>,
    /// (phase's hidden method, block key) -> whether its members (own or
    /// inherited) need calls in that phase.
    tree: HashMap<(&'static str, String), bool>,
}

/// The key of a type name written `Name` or `Namespace.Name`.
fn type_key(name: &Ident) -> String {
    let last = name.name.rsplit('.').next().unwrap_or(&name.name);
    last.to_ascii_uppercase()
}

/// The sections whose instances live as long as their container.
pub(super) fn lives_with_instance(kind: VarKind) -> bool {
    matches!(kind, VarKind::Local | VarKind::Input | VarKind::Output)
}

/// The declared types of a block's own instance members, its methods'
/// VAR_INST variables included.
fn member_types(pou: &Pou) -> Vec<TypeSpec> {
    let methods = pou.oop.iter().flat_map(|o| &o.methods);
    pou.var_blocks
        .iter()
        .filter(|b| lives_with_instance(b.kind))
        .chain(
            methods
                .flat_map(|m| &m.var_blocks)
                .filter(|b| b.kind == VarKind::Inst),
        )
        .flat_map(|b| b.decls.iter().map(|d| d.ty.clone()))
        .collect()
}

/// The VAR_INST declarations of `pou`'s methods, renamed as the lowering
/// names them in the instance (`oop::lower::hidden_name`): instances that
/// live as long as the block's own.
pub(super) fn method_instance_decls(pou: &Pou) -> Vec<VarDecl> {
    let mut out = Vec::new();
    for m in pou.oop.iter().flat_map(|o| &o.methods) {
        for b in m.var_blocks.iter().filter(|b| b.kind == VarKind::Inst) {
            for d in &b.decls {
                let mut d = d.clone();
                for n in &mut d.names {
                    n.name =
                        crate::sema::oop::lower::hidden_name(&pou.name.name, &m.name.name, &n.name);
                }
                out.push(d);
            }
        }
    }
    out
}

impl<'a> Index<'a> {
    pub fn new(units: &'a [CompilationUnit]) -> Self {
        let mut blocks = HashMap::new();
        let items = units.iter().enumerate().flat_map(|(u, unit)| {
            unit.items
                .iter()
                .enumerate()
                .map(move |(i, it)| ((u, i), it))
        });
        for (at, item) in items {
            let Item::Pou(pou) = item else { continue };
            if pou.kind == PouKind::Function {
                continue;
            }
            let oop = pou.oop.as_deref();
            blocks.entry(pou.name.key()).or_insert(Block {
                pou,
                at,
                parent: oop.and_then(|o| o.extends.as_ref()).map(type_key),
                methods: oop.map_or(&[][..], |o| o.methods.as_slice()),
            });
        }
        let types = units
            .iter()
            .flat_map(|u| &u.items)
            .flat_map(|i| match i {
                Item::Types(t) => t.iter().map(|t| t.name.key()).collect(),
                Item::Pou(p) => vec![p.name.key()],
                Item::Interface(x) => vec![x.name.key()],
                _ => Vec::new(),
            })
            .collect();
        let interfaces = units
            .iter()
            .flat_map(|u| &u.items)
            .filter_map(|i| match i {
                Item::Interface(x) => Some(x.name.key()),
                _ => None,
            })
            .collect();
        let mut index = Index {
            blocks,
            types,
            interfaces,
            tree: HashMap::new(),
        };
        let keys: Vec<String> = index.blocks.keys().cloned().collect();
        for phase in [super::INIT, super::EXIT] {
            for k in &keys {
                index.needs_members(k, phase, 0);
            }
        }
        index
    }

    /// The ancestors of `key`, itself first (stops at a cycle, which the
    /// lowering reports).
    pub fn lineage(&self, key: &str) -> Vec<&Block<'a>> {
        let mut out: Vec<&Block<'a>> = Vec::new();
        let mut next = Some(key.to_string());
        while let Some(k) = next {
            let Some(b) = self.blocks.get(&k) else { break };
            if out.iter().any(|o| std::ptr::eq(o.pou, b.pou)) {
                break;
            }
            next = b.parent.clone();
            out.push(b);
        }
        out
    }

    /// The phase's method a call on an instance of `key` runs (its own or
    /// the nearest ancestor's).
    pub fn method_of(&self, key: &str, phase: Phase) -> Option<&'a Method> {
        self.lineage(key).iter().find_map(|b| b.method(phase.key))
    }

    /// Whether `key`'s members (own or inherited) need calls in `phase`:
    /// whether it has (or inherits) the phase's hidden method.
    pub fn has_tree(&self, key: &str, phase: Phase) -> bool {
        self.tree
            .get(&(phase.members, key.to_string()))
            .copied()
            .unwrap_or(false)
    }

    /// The methods to call on an instance of `key` right after its
    /// `FB_init` (its own and its ancestors', each name once, parents'
    /// first).
    pub fn after_init_of(&self, key: &str) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for b in self.lineage(key).iter().rev() {
            for m in b.after_init() {
                if !out.iter().any(|o| o.eq_ignore_ascii_case(&m.name)) {
                    out.push(m.name.clone());
                }
            }
        }
        out
    }

    /// Whether `d` declares interface variables bound to an instance by
    /// their initial value (`itf : I_Log := logger;`), which the start
    /// assigns.
    pub fn binds_interface(&self, d: &VarDecl) -> bool {
        let TypeSpec::Named(n) = &d.ty else {
            return false;
        };
        let value = matches!(&d.init, Some(Initializer::Expr(e)) if !matches!(e.kind, ExprKind::Literal(_)));
        value && self.interfaces.contains(&type_key(n))
    }

    /// Whether the block `b` (its own sections) binds interfaces.
    fn block_binds_interfaces(&self, b: &Block) -> bool {
        b.pou
            .var_blocks
            .iter()
            .filter(|v| lives_with_instance(v.kind))
            .flat_map(|v| &v.decls)
            .any(|d| self.binds_interface(d))
    }

    /// Whether a declared type is one the compiler knows without this
    /// pass (an elementary type, a standard block, a declared TYPE, POU or
    /// interface): an unknown name is reported once, as an unknown type,
    /// elsewhere.
    pub fn is_known_type(&self, ty: &TypeSpec) -> bool {
        match ty {
            TypeSpec::Named(n) => {
                let k = type_key(n);
                crate::elementary::ElemType::from_name(&k).is_some()
                    || crate::stdlib::lookup_native(&k).is_some()
                    || self.types.contains(&k)
            }
            TypeSpec::Array { elem, .. } => self.is_known_type(elem),
            _ => true,
        }
    }

    /// The block a declared type names, if it is a FUNCTION_BLOCK (through
    /// arrays: with their dimensions).
    pub fn block_type<'t>(&self, ty: &'t TypeSpec) -> Option<(String, Vec<&'t (Expr, Expr)>)> {
        match ty {
            TypeSpec::Named(n) => {
                let k = type_key(n);
                let b = self.blocks.get(&k)?;
                (b.pou.kind == PouKind::FunctionBlock).then_some((k, Vec::new()))
            }
            TypeSpec::Array { ranges, elem, .. } => {
                let (k, mut dims) = self.block_type(elem)?;
                let mut all: Vec<&(Expr, Expr)> = ranges.iter().collect();
                all.append(&mut dims);
                Some((k, all))
            }
            _ => None,
        }
    }

    /// Whether an instance of `key` needs calls in `phase`: the phase's
    /// method (or, at start, a `call_after_init` one) of its own or
    /// inherited, or members that need calls.
    fn needs_calls(&mut self, key: &str, phase: Phase, depth: usize) -> bool {
        let after_init = phase.key == super::INIT.key && !self.after_init_of(key).is_empty();
        self.method_of(key, phase).is_some() || after_init || self.needs_members(key, phase, depth)
    }

    /// Whether `key`'s members (its own or inherited) need calls.
    fn needs_members(&mut self, key: &str, phase: Phase, depth: usize) -> bool {
        let slot = (phase.members, key.to_string());
        if let Some(&known) = self.tree.get(&slot) {
            return known;
        }
        // Blocks nested deeper than this are refused elsewhere.
        if depth > 64 {
            return false;
        }
        self.tree.insert(slot.clone(), false);
        let binds = phase == super::INIT
            && self
                .lineage(key)
                .iter()
                .any(|b| self.block_binds_interfaces(b));
        let types: Vec<TypeSpec> = self
            .lineage(key)
            .iter()
            .flat_map(|b| member_types(b.pou))
            .collect();
        let mut needed = binds;
        for ty in &types {
            if let Some((k, _)) = self.block_type(ty)
                && self.needs_calls(&k, phase, depth + 1)
            {
                needed = true;
                break;
            }
        }
        self.tree.insert(slot, needed);
        needed
    }
}

//! Dependency order of the declarations of a CONSTANT block: a constant may
//! be used before its declaration (`A : INT := B * 2; B : INT := 21;`), so
//! the declarations are visited so that every constant comes after the
//! constants its initial value names. The order is found with an explicit
//! work list (a chain of 100 000 constants costs no stack) and keeps the
//! written order wherever it already works. A real cycle is one E121 naming
//! it.

use crate::syntax::ast::{Arg, Expr, ExprKind, Initializer, VarBlock};
use std::collections::HashMap;

/// Diagnostic code of a cycle of constants.
pub const CONSTANT_CYCLE: &str = "E121";

/// The order in which to declare `block.decls` (indices), and each cycle
/// found, as the indices of its declarations in dependency order.
pub fn dependency_order(block: &VarBlock) -> (Vec<usize>, Vec<Vec<usize>>) {
    let n = block.decls.len();
    if !block.constant {
        return ((0..n).collect(), Vec::new());
    }
    let mut owner: HashMap<String, usize> = HashMap::new();
    for (d, decl) in block.decls.iter().enumerate() {
        for name in &decl.names {
            owner.entry(name.key()).or_insert(d);
        }
    }
    let deps: Vec<Vec<usize>> = block
        .decls
        .iter()
        .enumerate()
        .map(|(d, decl)| {
            let mut names = Vec::new();
            if let Some(init) = &decl.init {
                init_names(init, &mut names);
            }
            let mut found: Vec<usize> = names
                .iter()
                .filter_map(|k| owner.get(k).copied())
                .filter(|&o| o != d)
                .collect();
            found.dedup();
            found
        })
        .collect();
    order(&deps)
}

/// Depth-first post-order over `deps` with an explicit stack; a back edge
/// is a cycle (reported once, its members then treated as declared).
pub(super) fn order(deps: &[Vec<usize>]) -> (Vec<usize>, Vec<Vec<usize>>) {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    let mut mark = vec![Mark::New; deps.len()];
    let mut out = Vec::with_capacity(deps.len());
    let mut cycles = Vec::new();
    for root in 0..deps.len() {
        if mark[root] != Mark::New {
            continue;
        }
        // (node, next dependency to visit)
        let mut stack = vec![(root, 0usize)];
        mark[root] = Mark::Open;
        while let Some(&mut (node, ref mut next)) = stack.last_mut() {
            if let Some(&dep) = deps[node].get(*next) {
                *next += 1;
                match mark[dep] {
                    Mark::New => {
                        mark[dep] = Mark::Open;
                        stack.push((dep, 0));
                    }
                    Mark::Open => {
                        let from = stack.iter().position(|&(n, _)| n == dep).unwrap_or(0);
                        cycles.push(stack[from..].iter().map(|&(n, _)| n).collect());
                    }
                    Mark::Done => {}
                }
            } else {
                mark[node] = Mark::Done;
                out.push(node);
                stack.pop();
            }
        }
    }
    (out, cycles)
}

/// Every plain name an initializer reads, as keys (upper case).
/// The declarations of a CONSTANT block that can be declared before any
/// TYPE is resolved: an elementary type and an initial value that names
/// nothing (`MaxN : UINT := 100;`).
pub(super) fn plain_constants(block: &VarBlock) -> Vec<usize> {
    use crate::syntax::ast::TypeSpec;
    if !block.constant {
        return Vec::new();
    }
    let plain = |d: &crate::syntax::ast::VarDecl| {
        let elementary = match &d.ty {
            TypeSpec::Named(id) => crate::elementary::ElemType::from_name(&id.name).is_some(),
            TypeSpec::String { len: None, .. } => true,
            _ => false,
        };
        let mut names = Vec::new();
        if let Some(init) = &d.init {
            init_names(init, &mut names);
        }
        elementary && d.location.is_none() && d.init_args.is_none() && names.is_empty()
    };
    (0..block.decls.len())
        .filter(|&d| plain(&block.decls[d]))
        .collect()
}

/// The declarations of a CONSTANT block whose values are structures or
/// arrays (`cstFullBeam : ST_Beam := (nTran := 1, ...)`) and whose initial
/// value names no variable of `variables` (the globals that are not
/// constants): declared early too, after the plain ones, so that a
/// structure's field default may copy one (`stBeam : ST_Beam :=
/// GVL.cstFullBeam;` in a TYPE, CODESYS initialising the global lists
/// first). `blocks` (type names that are blocks) are left to the rest.
pub(super) fn value_constants(
    block: &VarBlock,
    variables: &std::collections::HashSet<String>,
    blocks: &dyn Fn(&str) -> bool,
) -> Vec<usize> {
    use crate::syntax::ast::TypeSpec;
    if !block.constant {
        return Vec::new();
    }
    let value = |d: &crate::syntax::ast::VarDecl| {
        let aggregate = match &d.ty {
            TypeSpec::Named(id) => {
                crate::elementary::ElemType::from_name(&id.name).is_none() && !blocks(&id.key())
            }
            TypeSpec::Array { .. } | TypeSpec::Struct { .. } => true,
            _ => false,
        };
        let Some(init) = &d.init else {
            return false;
        };
        let mut names = Vec::new();
        init_names(init, &mut names);
        aggregate
            && d.location.is_none()
            && d.init_args.is_none()
            && names.iter().all(|n| !variables.contains(n))
    };
    (0..block.decls.len())
        .filter(|&d| value(&block.decls[d]))
        .collect()
}

/// The names (case-folded) the initial values of `block` read.
pub(super) fn names_read(block: &VarBlock) -> Vec<String> {
    let mut out = Vec::new();
    for init in block.decls.iter().filter_map(|d| d.init.as_ref()) {
        init_names(init, &mut out);
    }
    out
}

fn init_names(init: &Initializer, out: &mut Vec<String>) {
    let mut inits = vec![init];
    let mut exprs: Vec<&Expr> = Vec::new();
    while let Some(i) = inits.pop() {
        match i {
            Initializer::Expr(e) => exprs.push(e),
            Initializer::Array(elems, _) => {
                inits.extend(elems.iter().filter_map(|e| e.value.as_ref()))
            }
            Initializer::Struct(fields, _) => inits.extend(fields.iter().map(|(_, i)| i)),
        }
    }
    while let Some(e) = exprs.pop() {
        match &e.kind {
            ExprKind::Name(id) => out.push(id.key()),
            ExprKind::Literal(_) | ExprKind::Direct(_) => {}
            ExprKind::Member(b, _)
            | ExprKind::BitAccess(b, _)
            | ExprKind::Unary(_, b)
            | ExprKind::Paren(b)
            | ExprKind::Deref(b) => exprs.push(b),
            ExprKind::Index(b, idx) => {
                exprs.push(b);
                exprs.extend(idx.iter());
            }
            ExprKind::Binary(_, a, b) | ExprKind::Assign(a, b) => {
                exprs.push(a);
                exprs.push(b);
            }
            ExprKind::Call(c) => exprs.extend(c.args.iter().map(|a| match a {
                Arg::Positional(e)
                | Arg::Input { value: e, .. }
                | Arg::Output { target: e, .. } => e,
            })),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::order;

    #[test]
    fn written_order_is_kept_when_it_works() {
        let deps = vec![vec![], vec![0], vec![0, 1]];
        assert_eq!(order(&deps), (vec![0, 1, 2], vec![]));
    }

    #[test]
    fn a_reversed_chain_is_declared_base_first() {
        let deps = vec![vec![1], vec![2], vec![]];
        assert_eq!(order(&deps).0, vec![2, 1, 0]);
    }

    #[test]
    fn a_cycle_is_found_once() {
        let deps = vec![vec![1], vec![2], vec![0]];
        let (out, cycles) = order(&deps);
        assert_eq!(out.len(), 3);
        assert_eq!(cycles, vec![vec![0, 1, 2]]);
    }
}

//! The nesting limit of declarations: how deep types and function blocks
//! contain one another (`S0` holds an `S1`, which holds an `S2`, ...). The
//! declaration phase resolves and lays them out recursively, so before it
//! starts this pass measures the longest chain with an explicit work list
//! and refuses a program deeper than [`MAX_TYPE_NESTING`] with one E122,
//! instead of letting the recursion exhaust the compiling thread's stack.

use crate::diagnostics::Diagnostic;
use crate::syntax::ast::{CompilationUnit, Item, TypeSpec, VarDecl};
use std::collections::HashMap;

/// Most levels of types and blocks containing one another. Chains of
/// 20 000 structures, aliases or FB types compile; the compiling thread's
/// stack holds about twice this depth in a debug build.
pub const MAX_TYPE_NESTING: usize = 25_000;

/// Diagnostic code of declarations nested deeper than [`MAX_TYPE_NESTING`].
pub const TOO_DEEP: &str = "E122";

/// One TYPE or POU: its name's span and the names its declaration uses.
struct Node {
    span: crate::source::Span,
    name: String,
    uses: Vec<String>,
}

/// E122 for the outermost declaration of a chain deeper than the limit.
pub fn check(units: &[CompilationUnit]) -> Option<Diagnostic> {
    let nodes = collect(units);
    let index: HashMap<&str, usize> = nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.name.as_str(), i))
        .collect();
    let edges: Vec<Vec<usize>> = nodes
        .iter()
        .map(|n| {
            n.uses
                .iter()
                .filter_map(|u| index.get(u.as_str()).copied())
                .collect()
        })
        .collect();
    let depth = longest_chains(&edges);
    let (worst, &d) = depth.iter().enumerate().max_by_key(|&(_, d)| *d)?;
    (d > MAX_TYPE_NESTING).then(|| {
        Diagnostic::error(
            TOO_DEEP,
            nodes[worst].span,
            format!(
                "`{}` nests types or function blocks {d} levels deep, more than the limit of {MAX_TYPE_NESTING}",
                nodes[worst].name
            ),
        )
    })
}

/// Every TYPE and POU with the type names its declaration refers to.
fn collect(units: &[CompilationUnit]) -> Vec<Node> {
    let mut nodes = Vec::new();
    for unit in units {
        for item in &unit.items {
            match item {
                Item::Types(decls) => nodes.extend(decls.iter().map(|d| {
                    let mut uses = Vec::new();
                    spec_names(&d.ty, &mut uses);
                    Node {
                        span: d.name.span,
                        name: d.name.key(),
                        uses,
                    }
                })),
                Item::Pou(p) => {
                    let mut uses = Vec::new();
                    let decls = p.var_blocks.iter().flat_map(|b| b.decls.iter());
                    decls_names(decls, &mut uses);
                    nodes.push(Node {
                        span: p.name.span,
                        name: p.name.key(),
                        uses,
                    });
                }
                Item::Configuration(_) | Item::Globals(_) | Item::Interface(_) => {}
            }
        }
    }
    nodes
}

fn decls_names<'a>(decls: impl Iterator<Item = &'a VarDecl>, out: &mut Vec<String>) {
    for d in decls {
        spec_names(&d.ty, out);
    }
}

/// The named types a type specification refers to (without recursion into
/// other declarations; nested anonymous arrays and structures are walked
/// with a work list).
fn spec_names(spec: &TypeSpec, out: &mut Vec<String>) {
    let mut work = vec![spec];
    while let Some(s) = work.pop() {
        match s {
            TypeSpec::Named(id) => out.push(id.key()),
            TypeSpec::Subrange { base, .. } => out.push(base.key()),
            TypeSpec::Enum { base, .. } => out.extend(base.iter().map(|b| b.key())),
            TypeSpec::Array { elem, .. } | TypeSpec::OpenArray { elem, .. } => work.push(elem),
            TypeSpec::Struct { fields, .. } => work.extend(fields.iter().map(|f| &f.ty)),
            TypeSpec::String { .. } => {}
            // A reference does not contain its target: no nesting.
            TypeSpec::Ref { .. } => {}
        }
    }
}

/// The number of nodes on the longest chain of edges from each node
/// (memoised depth-first search with an explicit stack; an edge back into
/// the chain being explored is a cycle, reported elsewhere, and ignored).
pub(super) fn longest_chains(edges: &[Vec<usize>]) -> Vec<usize> {
    const UNSEEN: usize = 0;
    const OPEN: usize = usize::MAX;
    let mut depth = vec![UNSEEN; edges.len()];
    for root in 0..edges.len() {
        if depth[root] != UNSEEN {
            continue;
        }
        depth[root] = OPEN;
        let mut stack = vec![(root, 0usize)];
        while let Some(&mut (node, ref mut next)) = stack.last_mut() {
            if let Some(&to) = edges[node].get(*next) {
                *next += 1;
                if depth[to] == UNSEEN {
                    depth[to] = OPEN;
                    stack.push((to, 0));
                }
            } else {
                let below = edges[node]
                    .iter()
                    .map(|&to| depth[to])
                    .filter(|&d| d != OPEN)
                    .max()
                    .unwrap_or(0);
                depth[node] = below + 1;
                stack.pop();
            }
        }
    }
    depth
}

#[cfg(test)]
mod tests {
    use super::longest_chains;

    #[test]
    fn chains_are_measured_in_nodes() {
        assert_eq!(longest_chains(&[vec![1], vec![2], vec![]]), vec![3, 2, 1]);
        assert_eq!(
            longest_chains(&[vec![], vec![0], vec![1, 0]]),
            vec![1, 2, 3]
        );
    }

    #[test]
    fn a_cycle_does_not_loop() {
        let d = longest_chains(&[vec![1], vec![0]]);
        assert!(d.iter().all(|&d| d == 1 || d == 2), "{d:?}");
    }

    #[test]
    fn a_long_chain_costs_no_stack() {
        let n = 1_000_000;
        let edges: Vec<Vec<usize>> = (0..n)
            .map(|i| if i + 1 < n { vec![i + 1] } else { vec![] })
            .collect();
        assert_eq!(longest_chains(&edges)[0], n);
    }
}

//! The depth of inheritance (`EXTENDS` between function blocks, between
//! interfaces). Lowering object orientation copies every inherited
//! variable and method into each descendant, so a chain `n` deep costs
//! time and memory in `n²` (a 2 000-deep chain took 2 minutes and 6.8 GB
//! in a debug build, 10 000 did not finish). Before lowering, this pass
//! measures the longest chain with a work list and refuses one deeper
//! than [`MAX_EXTENDS_DEPTH`] with one E180.

use crate::diagnostics::Diagnostic;
use crate::syntax::ast::{CompilationUnit, Item};
use std::collections::HashMap;

/// Most levels of `EXTENDS`: far beyond any real class hierarchy, and a
/// chain this deep lowers in a fraction of a second.
pub const MAX_EXTENDS_DEPTH: usize = 256;

/// Diagnostic code of an inheritance chain deeper than the limit.
pub const TOO_DEEP: &str = "E180";

/// E180 for the most derived FB or interface of a chain deeper than the
/// limit (cycles are left to the lowering, which names them).
pub fn check(units: &[CompilationUnit]) -> Option<Diagnostic> {
    // Each FB and interface with the names it extends; FBs and interfaces
    // are kept apart (`I.` / `F.`) since only like extends like.
    let mut nodes: Vec<(&crate::syntax::ast::Ident, String, Vec<String>)> = Vec::new();
    for item in units.iter().flat_map(|u| &u.items) {
        match item {
            Item::Pou(p) => {
                let parent = p.oop.as_ref().and_then(|o| o.extends.as_ref());
                let uses = parent
                    .map(|e| format!("F.{}", e.key()))
                    .into_iter()
                    .collect();
                nodes.push((&p.name, format!("F.{}", p.name.key()), uses));
            }
            Item::Interface(i) => {
                let uses = i.extends.iter().map(|e| format!("I.{}", e.key())).collect();
                nodes.push((&i.name, format!("I.{}", i.name.key()), uses));
            }
            _ => {}
        }
    }
    if nodes.iter().all(|(_, _, uses)| uses.is_empty()) {
        return None;
    }
    let index: HashMap<&str, usize> = nodes
        .iter()
        .enumerate()
        .map(|(i, (_, name, _))| (name.as_str(), i))
        .collect();
    let edges: Vec<Vec<usize>> = nodes
        .iter()
        .map(|(_, _, uses)| {
            uses.iter()
                .filter_map(|u| index.get(u.as_str()).copied())
                .collect()
        })
        .collect();
    let depth = super::nesting::longest_chains(&edges);
    let (worst, &d) = depth.iter().enumerate().max_by_key(|&(_, d)| *d)?;
    // The chain counts declarations; its levels of EXTENDS are one fewer.
    let levels = d.saturating_sub(1);
    (levels > MAX_EXTENDS_DEPTH).then(|| {
        let name = nodes[worst].0;
        Diagnostic::error(
            TOO_DEEP,
            name.span,
            format!(
                "`{}` inherits through {levels} levels of EXTENDS, more than the limit of {MAX_EXTENDS_DEPTH}",
                name.name
            ),
        )
    })
}

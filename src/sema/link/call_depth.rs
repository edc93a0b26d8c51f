//! The deepest chain of nested calls. The executor runs a called POU by
//! calling itself (one native stack frame per level: about 400 bytes in
//! a release build, about 28 KB in a debug build), so a chain of FB and
//! function calls thousands deep would overflow the host thread's stack
//! and take the host process down. Recursion is refused (E409) but for
//! cycles of guarded methods (`cycle_depth`), so with those edges left out
//! the call graph is acyclic and its longest path, plus what the cycles
//! may add, is the deepest nesting the program can reach; beyond
//! [`MAX_CALL_DEPTH`] the program is refused with one E181 that names the
//! chain or the cycle.

use super::Linker;

/// Most nested calls a program may contain (a PROGRAM calling an FB is
/// one level). At about 400 bytes a level in a release build this stays
/// under half a megabyte of stack, well inside a 2 MiB host thread, and
/// it is far beyond the nesting of any real program.
pub const MAX_CALL_DEPTH: usize = 1000;

/// How many names of the chain the message shows at each end.
const SHOWN: usize = 4;

impl Linker<'_> {
    /// Reports a chain of nested calls deeper than [`MAX_CALL_DEPTH`]
    /// (run after the recursion check: the call graph is acyclic but for
    /// the cycles of guarded methods, whose back edges are skipped).
    pub(super) fn check_call_depth(&mut self) {
        let n = self.out.codes.len();
        let adj: Vec<Vec<usize>> = self
            .call_graph()
            .into_iter()
            .map(|edges| edges.into_iter().map(|(b, _)| b).collect())
            .collect();
        // depth[c]: blocks on the longest chain starting at c (itself
        // included); next[c]: the callee on that chain. Post-order walk
        // with an explicit stack (the chain may be thousands deep).
        let mut depth = vec![0usize; n];
        let mut next = vec![usize::MAX; n];
        let mut on_stack = vec![false; n];
        for start in 0..n {
            if depth[start] != 0 {
                continue;
            }
            on_stack[start] = true;
            let mut stack = vec![(start, 0usize)];
            while let Some(&mut (node, ref mut i)) = stack.last_mut() {
                if let Some(&to) = adj[node].get(*i) {
                    *i += 1;
                    // depth 0 and on the stack would be a cycle: E409
                    // reported it, or it is one of guarded methods
                    // (`cycle_nesting` counts it): the edge is skipped.
                    if depth[to] == 0 && !on_stack[to] {
                        on_stack[to] = true;
                        stack.push((to, 0));
                    }
                } else {
                    let best = adj[node].iter().copied().max_by_key(|&c| depth[c]);
                    depth[node] = 1 + best.map_or(0, |c| depth[c]);
                    next[node] = best.unwrap_or(usize::MAX);
                    on_stack[node] = false;
                    stack.pop();
                }
            }
        }
        let Some(top) = (0..n).max_by_key(|&c| depth[c]) else {
            return;
        };
        let levels = depth[top] - 1;
        if let Some(cycle) = self.cycle_nesting()
            && (levels as u64).saturating_add(cycle.levels) > MAX_CALL_DEPTH as u64
        {
            let message = format!(
                "calls may nest {} deep: {}; plcrun runs at most {MAX_CALL_DEPTH} nested calls",
                (levels as u64).saturating_add(cycle.levels),
                cycle.what
            );
            self.diags.error("E181", cycle.span, message);
            return;
        }
        if levels <= MAX_CALL_DEPTH {
            return;
        }
        let mut chain = vec![top];
        while let Some(&c) = chain.last() {
            if next[c] == usize::MAX {
                break;
            }
            chain.push(next[c]);
        }
        let names: Vec<&str> = chain
            .iter()
            .map(|&c| self.out.codes[c].name.as_str())
            .collect();
        let shown = if names.len() > 2 * SHOWN {
            format!(
                "{} -> ... -> {}",
                names[..SHOWN].join(" -> "),
                names[names.len() - SHOWN..].join(" -> ")
            )
        } else {
            names.join(" -> ")
        };
        // The first call of the chain: where the nesting starts.
        let span = self
            .out
            .calls
            .iter()
            .find(|&&(a, b, _)| a.index() == chain[0] && b.index() == chain[1])
            .map(|&(_, _, s)| s);
        if let Some(span) = span {
            self.diags.error(
                "E181",
                span,
                format!(
                    "calls nested {levels} deep ({shown}): plcrun runs at most {MAX_CALL_DEPTH} nested calls"
                ),
            );
        }
    }
}

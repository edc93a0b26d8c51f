//! Recursion check over the call graph (IEC 61131-3 forbids recursion),
//! with an explicit stack; the diagnostic names the whole cycle of calls.
//!
//! A cycle made of METHODs only — one a call through an interface closes,
//! since a call through an interface reaches every block implementing it —
//! is not refused: its methods get re-entry guards (`sema::oop::reentry`).
//! The first pass asks for them ([`Linker::guard_request`]), the second,
//! compiled with them, accepts the cycle.

use super::Linker;
use crate::ir::op::CodeIdx;
use crate::source::Span;
use std::collections::{BTreeMap, HashMap, HashSet};

impl Linker<'_> {
    /// Reports calls that form a cycle (IEC forbids recursion), except
    /// cycles of methods, whose guards it asks for or finds.
    pub(super) fn check_recursion(&mut self) {
        let mut adj = self.call_graph();
        let methods = self.method_keys();
        let component = strong_components(&adj);
        let cyclic = in_cycle(&adj, &component);
        let certain = self.own_instance_cycles(&adj);
        // The components that are cycles of methods only.
        let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for (c, &k) in component.iter().enumerate() {
            members.entry(k).or_default().push(c);
        }
        let mut of_methods: HashSet<usize> = HashSet::new();
        for (&k, codes) in &members {
            if !cyclic[codes[0]]
                || !codes
                    .iter()
                    .all(|c| methods.contains_key(c) && !certain[*c])
            {
                continue;
            }
            if codes.iter().all(|c| methods[c].1) {
                // Compiled with their guards (the second pass).
                of_methods.insert(k);
            } else if self.guarded.is_empty() {
                // The first pass: ask for the guards.
                of_methods.insert(k);
                self.guard_request
                    .extend(codes.iter().map(|c| methods[c].0.clone()));
            }
        }
        // Edges inside such a cycle are allowed: report the others.
        for (a, edges) in adj.iter_mut().enumerate() {
            if of_methods.contains(&component[a]) {
                edges.retain(|&(b, _)| component[b] != component[a]);
            }
        }
        self.report_first_cycle(&adj);
    }

    /// The call graph: for each code block, the blocks it calls and where.
    pub(super) fn call_graph(&self) -> Vec<Vec<(usize, Span)>> {
        let n = self.out.codes.len();
        let mut adj: Vec<Vec<(usize, Span)>> = vec![Vec::new(); n];
        for &(a, b, s) in &self.out.calls {
            if a.index() < n && b.index() < n {
                adj[a.index()].push((b.index(), s));
            }
        }
        adj
    }

    /// Whether each code block is in a cycle of calls on the caller's own
    /// instance: recursion for certain, whatever the instances are.
    fn own_instance_cycles(&self, adj: &[Vec<(usize, Span)>]) -> Vec<bool> {
        let own: Vec<Vec<(usize, Span)>> = adj
            .iter()
            .enumerate()
            .map(|(a, edges)| {
                let own = &self.out.own_instance_calls;
                edges
                    .iter()
                    .copied()
                    .filter(|&(b, _)| {
                        own.contains(&(CodeIdx::new(a as u32), CodeIdx::new(b as u32)))
                    })
                    .collect()
            })
            .collect();
        in_cycle(&own, &strong_components(&own))
    }

    /// Code block -> (`ORIGIN.METHOD`, compiled with a re-entry guard)
    /// of every method version.
    fn method_keys(&self) -> HashMap<usize, (String, bool)> {
        let mut keys = HashMap::new();
        for fb in self.model.oop.fbs.values() {
            for (v, code) in fb.versions.iter().zip(&fb.codes) {
                if v.name.name != crate::sema::oop::model::BODY {
                    let key = format!("{}.{}", v.origin, v.name.key());
                    keys.insert(code.index(), (key, v.guard.is_some()));
                }
            }
        }
        keys
    }

    /// E409 for the first cycle a depth-first walk of `adj` meets.
    fn report_first_cycle(&mut self, adj: &[Vec<(usize, Span)>]) {
        let n = adj.len();
        // 0 = unvisited, 1 = on stack, 2 = done
        let mut state = vec![0u8; n];
        for start in 0..n {
            if state[start] != 0 {
                continue;
            }
            let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
            state[start] = 1;
            while let Some(&mut (node, ref mut next)) = stack.last_mut() {
                if *next < adj[node].len() {
                    let (to, span) = adj[node][*next];
                    *next += 1;
                    match state[to] {
                        0 => {
                            state[to] = 1;
                            stack.push((to, 0));
                        }
                        1 => {
                            let name = self.out.codes[to].name.clone();
                            // The calls on the stack from `to` back to it.
                            let from = stack.iter().position(|&(c, _)| c == to).unwrap_or(0);
                            let mut ring: Vec<&str> = stack[from..]
                                .iter()
                                .map(|&(c, _)| self.out.codes[c].name.as_str())
                                .collect();
                            ring.push(&name);
                            let message = format!(
                                "recursive call of `{name}` (calls {}): IEC 61131-3 forbids recursion",
                                ring.join(" -> ")
                            );
                            self.diags.error("E409", span, message);
                            return;
                        }
                        _ => {}
                    }
                } else {
                    state[node] = 2;
                    stack.pop();
                }
            }
        }
    }
}

/// Whether each node of `adj` is on a cycle: its strongly connected
/// component (`component`, from [`strong_components`]) has other nodes,
/// or it calls itself.
fn in_cycle(adj: &[Vec<(usize, Span)>], component: &[usize]) -> Vec<bool> {
    let mut size: HashMap<usize, usize> = HashMap::new();
    for &k in component {
        *size.entry(k).or_default() += 1;
    }
    (0..adj.len())
        .map(|c| size[&component[c]] > 1 || adj[c].iter().any(|&(t, _)| t == c))
        .collect()
}

/// The strongly connected component of each node (Tarjan's algorithm,
/// with an explicit stack: call chains may be thousands deep).
pub(super) fn strong_components(adj: &[Vec<(usize, Span)>]) -> Vec<usize> {
    const NONE: usize = usize::MAX;
    let n = adj.len();
    let mut index = vec![NONE; n];
    let mut low = vec![0; n];
    let mut on_stack = vec![false; n];
    let mut component = vec![NONE; n];
    let mut stack = Vec::new();
    let mut next_index = 0;
    let mut next_component = 0;
    for start in 0..n {
        if index[start] != NONE {
            continue;
        }
        let mut walk: Vec<(usize, usize)> = vec![(start, 0)];
        index[start] = next_index;
        low[start] = next_index;
        next_index += 1;
        stack.push(start);
        on_stack[start] = true;
        while let Some(&mut (v, ref mut i)) = walk.last_mut() {
            if let Some(&(w, _)) = adj[v].get(*i) {
                *i += 1;
                if index[w] == NONE {
                    index[w] = next_index;
                    low[w] = next_index;
                    next_index += 1;
                    stack.push(w);
                    on_stack[w] = true;
                    walk.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            walk.pop();
            if let Some(&(parent, _)) = walk.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component[w] = next_component;
                    if w == v {
                        break;
                    }
                }
                next_component += 1;
            }
        }
    }
    component
}

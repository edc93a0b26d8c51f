//! Recursion check over the call graph (IEC 61131-3 forbids recursion),
//! with an explicit stack; the diagnostic names the whole cycle of calls.

use super::Linker;
use crate::source::Span;

impl Linker<'_> {
    /// Reports calls that form a cycle (IEC forbids recursion).
    pub(super) fn check_recursion(&mut self) {
        let n = self.out.codes.len();
        let mut adj: Vec<Vec<(usize, Span)>> = vec![Vec::new(); n];
        for &(a, b, s) in &self.out.calls {
            if a.index() < n {
                adj[a.index()].push((b.index(), s));
            }
        }
        // 0 = unvisited, 1 = on stack, 2 = done
        let mut state = vec![0u8; n];
        let mut reported = false;
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
                        1 if !reported => {
                            reported = true;
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

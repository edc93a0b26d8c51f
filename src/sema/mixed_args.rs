//! Positional arguments followed by formal ones, `F(1, 2, c := 3)`, as
//! CODESYS and TwinCAT accept them: the leading positional arguments go
//! to the inputs (and in-outs) in declaration order, the formal ones by
//! name. A compatibility extension (W487). A positional argument after a
//! formal one goes to the input of its own position in a CODESYS or
//! TwinCAT file (as TwinCAT compiles it), and is E411 elsewhere.

use super::body::BodyBuilder;
use super::calls::Param;
use crate::ir::type_table::MemberKind;
use crate::source::Span;
use crate::syntax::ast::{Arg, Expr};

impl BodyBuilder<'_> {
    /// The parameters the leading positional arguments of `args` (which
    /// mixes both kinds) go to, or `None` after an error.
    pub(super) fn mixed_arguments<'e>(
        &mut self,
        params: &[Param],
        args: &'e [Arg],
        callee: &str,
        span: Span,
    ) -> Option<Vec<(usize, &'e Expr)>> {
        // Each positional argument at its own position in the list: the
        // leading ones in every file, one after a formal one only in a
        // CODESYS / TwinCAT file (`CopyDocument(pDoc := s, SIZEOF(s))`,
        // as TwinCAT compiles it).
        let leading = args
            .iter()
            .take_while(|a| matches!(a, Arg::Positional(_)))
            .count();
        let positional: Vec<(usize, &Expr)> = args
            .iter()
            .enumerate()
            .filter_map(|(k, a)| match a {
                Arg::Positional(e) => Some((k, e)),
                _ => None,
            })
            .collect();
        if let Some(&(_, e)) = positional.get(leading)
            && !self.model.codesys_files.contains(&e.span.file)
        {
            self.diags.error(
                "E411",
                e.span,
                "a positional argument after a formal one (`name := value`): write the positional arguments first, or name this one",
            );
            return None;
        }
        let order: Vec<usize> = params
            .iter()
            .enumerate()
            .filter(|(_, p)| matches!(p.kind, MemberKind::Input | MemberKind::InOut))
            .map(|(i, _)| i)
            .collect();
        let last = positional.last().map_or(0, |&(k, _)| k + 1);
        if last > order.len() {
            self.diags.error(
                "E404",
                span,
                format!(
                    "`{callee}` takes {} input(s), a positional argument is given at position {last}",
                    order.len(),
                ),
            );
            return None;
        }
        self.diags.warning(
            "W487",
            span,
            format!(
                "positional and formal arguments mixed in a call of `{callee}` (a CODESYS extension): a positional one goes to the input of its position in declaration order ({} of them)",
                positional.len()
            ),
        );
        Some(positional.into_iter().map(|(k, e)| (order[k], e)).collect())
    }
}

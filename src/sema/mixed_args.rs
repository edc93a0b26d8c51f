//! Positional arguments followed by formal ones, `F(1, 2, c := 3)`, as
//! CODESYS and TwinCAT accept them: the leading positional arguments go
//! to the inputs (and in-outs) in declaration order, the formal ones by
//! name. A compatibility extension (W487); a positional argument after a
//! formal one stays E411.

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
        let leading: Vec<&Expr> = args
            .iter()
            .map_while(|a| match a {
                Arg::Positional(e) => Some(e),
                _ => None,
            })
            .collect();
        if let Some(late) = args[leading.len()..]
            .iter()
            .find(|a| matches!(a, Arg::Positional(_)))
        {
            let Arg::Positional(e) = late else {
                return None;
            };
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
        if leading.len() > order.len() {
            self.diags.error(
                "E404",
                span,
                format!(
                    "`{callee}` takes {} input(s), {} positional argument(s) given",
                    order.len(),
                    leading.len()
                ),
            );
            return None;
        }
        self.diags.warning(
            "W487",
            span,
            format!(
                "positional and formal arguments mixed in a call of `{callee}` (a CODESYS extension): the {} positional one(s) go to the first input(s) in declaration order",
                leading.len()
            ),
        );
        Some(order.into_iter().zip(leading).collect())
    }
}

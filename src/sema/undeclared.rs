//! One message per undeclared name: the first use of a name that is not
//! declared is reported (with the closest declared name, when one is
//! close), later uses in the same POU are not; and in a POU that already
//! has a syntax error before the use, an undeclared name is taken for a
//! consequence of it (the skipped text may have held the declaration) and
//! is not reported.

use super::body::BodyBuilder;
use super::suggest::with_suggestion;
use crate::syntax::ast::Ident;

use crate::syntax::recovery::SYNTAX_CODES;

impl BodyBuilder<'_> {
    /// Reports `id` as an undeclared variable unless that is a repeat or a
    /// consequence of a syntax error (see the module comment).
    pub(super) fn undeclared_variable(&mut self, id: &Ident) {
        self.undeclared_qualifier(id, None);
    }

    /// As [`Self::undeclared_variable`], for `id` written before `.member`:
    /// without a close name to suggest, the message says that `member` is
    /// no global either (`GVL.x` with a list that does not declare `x`).
    pub(super) fn undeclared_qualifier(&mut self, id: &Ident, member: Option<&Ident>) {
        let file = id.span.file;
        let (from, to) = self.pou_region(id);
        let at = id.span.start;
        let inside = |d: &crate::diagnostics::Diagnostic| {
            d.span.file == file && d.span.start >= from && d.span.start < to
        };
        let consequence = self
            .diags
            .iter()
            .any(|d| inside(d) && d.span.start < at && SYNTAX_CODES.contains(&d.code));
        let head = format!("undeclared variable `{}`", id.name);
        let repeat = self.diags.iter().any(|d| {
            inside(d)
                && d.code == "E201"
                && d.message
                    .get(..head.len())
                    .is_some_and(|m| m.eq_ignore_ascii_case(&head))
        });
        if consequence || repeat {
            return;
        }
        let pou = self.model.pous.get(self.block.pou);
        let names = pou
            .into_iter()
            .flat_map(|p| p.vars.values())
            .chain(self.model.globals.values())
            .map(|v| v.name.as_str())
            .chain(self.model.enum_values.keys().map(String::as_str));
        let mut message = with_suggestion(head.clone(), &id.name, names);
        if let Some(m) = member.filter(|_| message == head) {
            message.push_str(&format!(
                "; nor is `{}` a global variable (if `{}` is a global variable list, it does not declare `{}`)",
                m.name, id.name, m.name
            ));
        }
        self.diags.error("E201", id.span, message);
    }

    /// The byte range of the current POU in its file: from its name to the
    /// name of the next POU of the same file.
    fn pou_region(&self, id: &Ident) -> (u32, u32) {
        let Some(me) = self.model.pous.get(self.block.pou) else {
            return (0, u32::MAX);
        };
        let from = me.span.start.min(id.span.start);
        let to = self
            .model
            .pous
            .iter()
            .filter(|p| p.span.file == id.span.file && p.span.start > me.span.start)
            .map(|p| p.span.start)
            .min()
            .unwrap_or(u32::MAX);
        (from, to.max(id.span.start + 1))
    }

    /// True when POU `name` has a syntax error (its interface as the
    /// checker sees it may lack what the text declares).
    pub(super) fn pou_broken(&self, name: &str) -> bool {
        let Some(&p) = self.model.pou_index.get(&name.to_ascii_uppercase()) else {
            return false;
        };
        let me = &self.model.pous[p];
        let from = me.span.start;
        let to = self
            .model
            .pous
            .iter()
            .filter(|q| q.span.file == me.span.file && q.span.start > from)
            .map(|q| q.span.start)
            .min()
            .unwrap_or(u32::MAX);
        self.diags.iter().any(|d| {
            SYNTAX_CODES.contains(&d.code)
                && d.span.file == me.span.file
                && d.span.start >= from
                && d.span.start < to
        })
    }
}

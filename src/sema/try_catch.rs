//! `__TRY ... __CATCH(exc) ... __FINALLY ... __ENDTRY` lowered to code and
//! a handler table entry (`ir::handler`):
//!
//! ```text
//! start:  guarded statements
//! end:    JMP finally
//! catch:  __CATCH statements       (the executor enters here on a fault
//!                                   in start..end, `exc` already set)
//! finally: __FINALLY statements
//! ```
//!
//! Nothing runs on entry to the region: the table is read only when a
//! fault happens, so guarded code is as fast as any other.

use super::body::BodyBuilder;
use super::emit::{FinallyCopy, PendingFinally, Place};
use crate::elementary::ElemType;
use crate::ir::handler::Handler;
use crate::ir::op::{Op, Target};
use crate::ir::type_table::TypeKind;
use crate::source::Span;
use crate::syntax::ast::{Expr, ExprKind, Ident, Stmt};

impl BodyBuilder<'_> {
    /// Emits a `__TRY` statement (`catch` is `None` only after E112).
    pub(super) fn try_stmt(
        &mut self,
        body: &[Stmt],
        catch: Option<&(Ident, Vec<Stmt>)>,
        finally: Option<&[Stmt]>,
    ) {
        let start = self.block.here();
        self.enter_finally(finally);
        // Copies of the parts at this level and outside it are not this
        // `__TRY`'s to catch; those of inner parts are.
        let depth = self.block.finally.len();
        self.stmts(body);
        self.leave_finally(finally);
        let end = self.block.here();
        let to_finally = self.block.emit(Op::Jmp {
            t: Target::UNPATCHED,
        });
        let catch_at = self.block.here();
        if let Some((name, statements)) = catch {
            let exception = self.exception_slot(name);
            self.enter_finally(finally);
            self.stmts(statements);
            self.leave_finally(finally);
            if let Some(exception) = exception {
                let guarded = (start.index() as u32, end.index() as u32);
                let holes = self
                    .block
                    .finally_copies
                    .iter()
                    .filter(|c| c.level < depth && guarded.0 <= c.from && c.to <= guarded.1)
                    .map(|c| (c.from, c.to))
                    .collect();
                for (start, end) in without(guarded, holes) {
                    self.block.handlers.push(Handler {
                        start,
                        end,
                        catch: catch_at.index() as u32,
                        exception,
                    });
                }
            }
        }
        let finally_at = self.block.here();
        self.block.patch(to_finally, finally_at);
        if let Some(statements) = finally {
            self.stmts(statements);
        }
    }

    /// From here on, leaving the statements early runs `finally` first.
    fn enter_finally(&mut self, finally: Option<&[Stmt]>) {
        if let Some(stmts) = finally {
            self.block.finally.push(PendingFinally {
                stmts: stmts.to_vec(),
                loops: self.block.loops.len(),
            });
        }
    }

    /// The end of what `enter_finally` began.
    fn leave_finally(&mut self, finally: Option<&[Stmt]>) {
        if finally.is_some() {
            self.block.finally.pop();
        }
    }

    /// Before a RETURN (`loop_exit` None) or an EXIT or CONTINUE of the
    /// innermost loop (`Some(loops)`, the number of loops open): a copy of
    /// each `__FINALLY` part being left, innermost first, each emitted
    /// with only the parts outside it pending. A fault in a copy goes to
    /// the `__TRY`s around that part's own `__TRY`, as one in the part
    /// itself; the copies' diagnostics are dropped (the part's own
    /// emission reports them once).
    pub(super) fn run_finally_parts(&mut self, loop_exit: Option<usize>) {
        let pending = std::mem::take(&mut self.block.finally);
        for (level, part) in pending.iter().enumerate().rev() {
            if loop_exit.is_some_and(|loops| part.loops < loops) {
                break;
            }
            self.block.finally = pending[..level].to_vec();
            let diags = self.diags.len();
            let from = self.block.here().index() as u32;
            self.stmts(&part.stmts);
            let to = self.block.here().index() as u32;
            self.diags.truncate(diags);
            self.block
                .finally_copies
                .push(FinallyCopy { from, to, level });
        }
        self.block.finally = pending;
    }

    /// The frame slot of the `__CATCH` variable, or E413 when it is not a
    /// variable of the POU's own of a type that holds an exception code.
    fn exception_slot(&mut self, name: &Ident) -> Option<crate::ir::op::Slot> {
        let expr = Expr {
            kind: ExprKind::Name(name.clone()),
            span: name.span,
        };
        let place = self.place(&expr)?;
        if !holds_exception_code(&self.types.get(place.ty).kind) {
            let ty = self.types.name(place.ty).to_string();
            self.refuse_exception_variable(name.span, &format!("it is of type {ty}"));
            return None;
        }
        match place.place {
            Place::Frame(slot) if place.writable => Some(slot),
            _ => {
                self.refuse_exception_variable(
                    name.span,
                    "it is not a writable variable of this POU's own (VAR, VAR_TEMP, VAR_INST)",
                );
                None
            }
        }
    }

    fn refuse_exception_variable(&mut self, span: Span, why: &str) {
        self.diags.error(
            "E413",
            span,
            format!(
                "`__CATCH` variable refused: {why}; declare it `__SYSTEM.ExceptionCode` (or UDINT, DWORD) in the POU"
            ),
        );
    }
}

/// The ranges of `range` outside every one of `holes` (which lie inside
/// it), in order.
fn without((start, end): (u32, u32), mut holes: Vec<(u32, u32)>) -> Vec<(u32, u32)> {
    holes.sort_unstable();
    let mut out = Vec::new();
    let mut at = start;
    for (from, to) in holes {
        if from > at {
            out.push((at, from.min(end)));
        }
        at = at.max(to);
    }
    if at < end {
        out.push((at, end));
    }
    out
}

/// Whether a variable of this type takes an exception code as it is
/// stored (32 bits, unsigned): `__SYSTEM.ExceptionCode`, UDINT, DWORD.
fn holds_exception_code(kind: &TypeKind) -> bool {
    matches!(
        kind,
        TypeKind::Elem(ElemType::Udint | ElemType::Dword)
            | TypeKind::Enum {
                base: ElemType::Udint | ElemType::Dword,
                ..
            }
    )
}

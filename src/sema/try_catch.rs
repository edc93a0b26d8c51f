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
use super::emit::Place;
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
        self.stmts(body);
        let end = self.block.here();
        let to_finally = self.block.emit(Op::Jmp {
            t: Target::UNPATCHED,
        });
        let catch_at = self.block.here();
        if let Some((name, statements)) = catch {
            let exception = self.exception_slot(name);
            self.stmts(statements);
            // An empty guarded part cannot fault: no entry for it.
            if let Some(exception) = exception
                && start.index() < end.index()
            {
                self.block.handlers.push(Handler {
                    start: start.index() as u32,
                    end: end.index() as u32,
                    catch: catch_at.index() as u32,
                    exception,
                });
            }
        }
        let finally_at = self.block.here();
        self.block.patch(to_finally, finally_at);
        if let Some(statements) = finally {
            self.stmts(statements);
        }
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

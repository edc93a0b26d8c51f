//! `__TRY ... __CATCH(exc) ... __FINALLY ... __ENDTRY` (CODESYS V3,
//! TwinCAT 3): the statement as the parser builds it. The `__CATCH` part
//! is required: what a fault does after a `__FINALLY` with no `__CATCH`
//! before it is not documented by either vendor, so plcrun refuses the
//! form (E112) rather than guess.

use super::ast::{Ident, Stmt, StmtKind};
use super::construct::{State, compound};

/// The `__TRY` statement spanning `l..r`.
pub fn build(
    st: &State,
    body: Vec<Stmt>,
    catch: Option<(Ident, Vec<Stmt>)>,
    finally: Option<Vec<Stmt>>,
    l: usize,
    r: usize,
) -> Stmt {
    if catch.is_none() {
        st.error(
            "E112",
            st.span(l, r),
            "`__TRY` without `__CATCH(variable)`: plcrun needs the variable that receives the exception code",
        );
    }
    compound(
        st,
        StmtKind::Try {
            body,
            catch,
            finally,
        },
        l,
        r,
    )
}

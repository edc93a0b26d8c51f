//! `CLASS ... END_CLASS` (IEC 61131-3 edition 3): a function block without
//! a body. Its instances are variables whose methods (and properties) are
//! called; the instance itself cannot be called (E925, checked in
//! `src/sema/oop/class.rs`). A class declares no inputs or outputs (E927):
//! everything it offers goes through its methods.

use crate::syntax::ast::{Body, Ident, Pou, VarBlock, VarKind};
use crate::syntax::construct::State;
use crate::syntax::oop::{Method, Modifier};

/// A class: lowered as an FB with an empty body, marked as a class.
#[allow(clippy::too_many_arguments)]
pub fn class(
    st: &State,
    mods: Vec<Modifier>,
    name: Ident,
    extends: Option<Ident>,
    implements: Option<Vec<Ident>>,
    var_blocks: Vec<VarBlock>,
    methods: Vec<Method>,
    l: usize,
    r: usize,
) -> Pou {
    for b in &var_blocks {
        if matches!(b.kind, VarKind::Input | VarKind::Output | VarKind::InOut) {
            st.error(
                "E927",
                b.span,
                format!(
                    "a CLASS has no inputs or outputs: declare `{}`'s variables in VAR and reach them through methods",
                    name.name
                ),
            );
        }
    }
    let mut pou = crate::syntax::oop::fb(
        st,
        mods,
        name,
        extends,
        implements,
        var_blocks,
        methods,
        Body::St(Vec::new()),
        l,
        r,
    );
    if let Some(oop) = pou.oop.as_mut() {
        oop.is_class = true;
    }
    pou
}

//! Initial values computed at each call: `r : LREAL := EXPT(10, n);` in a
//! FUNCTION whose input is `n`, a VAR_TEMP from the block's inputs.
//!
//! CODESYS initialises a FUNCTION's variables, a METHOD's (but VAR_INST
//! and VAR_STAT) and a VAR_TEMP at every call, in declaration order, so
//! their initial values may read the call's inputs, call functions, or
//! read any variable as it is then (TwinCAT's vacuum valves:
//! `rMaxRatioAllowed : LREAL := EXPT(10, i_iOrdersMagnitude);`). An initial
//! value plcrun can fold into a constant stays one (a METHOD's: only from
//! constants, as its block's other variables are runtime values); any
//! other is assigned by the body before its first statement, as `r :=
//! EXPT(10, n);` would be, so its errors are those of that assignment. A later initial value
//! of the same block that reads such a variable is computed too: folding
//! it would read the variable's default.
//!
//! Static variables (an FB's or PROGRAM's VAR, VAR_OUTPUT...) keep their
//! rule: a constant, or what it reads folded (E205 otherwise).

use super::body::BodyBuilder;
use super::declare::Declarer;
use super::model::VarInfo;
use super::ref_inits::{every_call, init_assignment};
use crate::diagnostics::Diagnostics;
use crate::ir::type_table::TypeId;
use crate::syntax::ast::{Ident, Initializer, Pou, Stmt, VarBlock, VarDecl};
use indexmap::IndexMap;

impl Declarer<'_> {
    /// True when `decl` (of type `ty`, in `block` of `pou`, whose variables
    /// so far are `vars`) is a variable
    /// fresh at each call whose initial value is an expression that does
    /// not fold into a constant: the body computes it (recorded in the
    /// model), and the variable starts from its type's default.
    pub(super) fn defer_computed_init(
        &mut self,
        pou: &Pou,
        block: &VarBlock,
        decl: &VarDecl,
        ty: TypeId,
        vars: &IndexMap<String, VarInfo>,
        earlier: &[String],
    ) -> bool {
        let Some(init @ Initializer::Expr(_)) = &decl.init else {
            return false;
        };
        let method_local = self.method_local(pou, decl);
        if block.constant || !(every_call(pou, block) || method_local) {
            return false;
        }
        // Folded on the side: a failure here is no error of the program.
        let mut scratch = Diagnostics::new();
        let mut consts = self.consts();
        consts.diags = &mut scratch;
        // A METHOD's variables live in its block, whose earlier variables
        // (the method's inputs among them) hold runtime values.
        consts.same_block = if method_local { &[] } else { earlier };
        consts.globals_at_start = false;
        let folds = consts.resolve_init(init, ty, Some(vars)).is_some();
        if folds && !scratch.has_errors() {
            return false;
        }
        self.model.computed_inits.insert(decl.span);
        true
    }

    /// Whether `decl` of `pou` is a METHOD's variable set again at each of
    /// its calls (lowered into the block's variables, `oop::lower`).
    fn method_local(&self, pou: &Pou, decl: &VarDecl) -> bool {
        let Some(fb) = self.model.oop.fbs.get(&pou.name.key()) else {
            return false;
        };
        let Some(first) = decl.names.first().map(|n| n.key()) else {
            return false;
        };
        fb.versions.iter().any(|v| v.resets.contains(&first))
    }
}

impl BodyBuilder<'_> {
    /// Assigns the initial values of `pou` that are computed at each call,
    /// in declaration order, before its first statement.
    pub(super) fn emit_computed_inits(&mut self, pou: &Pou) {
        self.emit_computed_of(pou, &|b, _| every_call(pou, b));
    }

    /// Assigns the initial values computed at each call of the METHOD
    /// whose variables (reset on entry) are `resets`, before its first
    /// statement.
    pub(super) fn emit_method_computed_inits(&mut self, pou: &Pou, resets: &[String]) {
        self.emit_computed_of(pou, &|_, name| resets.contains(&name.key()));
    }

    /// Assigns the computed initial values of the variables of `pou` that
    /// `pick` takes (by block and name), in declaration order.
    fn emit_computed_of(&mut self, pou: &Pou, pick: &dyn Fn(&VarBlock, &Ident) -> bool) {
        let assignments: Vec<Stmt> = pou
            .var_blocks
            .iter()
            .flat_map(|b| b.decls.iter().map(move |d| (b, d)))
            .filter(|(_, d)| self.model.computed_inits.contains(&d.span))
            .filter_map(|(b, d)| match &d.init {
                Some(Initializer::Expr(e)) => Some((b, d, e)),
                _ => None,
            })
            .flat_map(|(b, d, e)| {
                d.names
                    .iter()
                    .filter(move |n| pick(b, n))
                    .map(move |n| init_assignment(n, e, d))
            })
            .collect();
        self.stmts(&assignments);
    }
}

//! A parameter named `EN` (in any case). In a call, `EN := value` is the
//! enable input every FUNCTION and FUNCTION_BLOCK has implicitly (edition
//! 3; docs/semantics.md "EN and ENO in bodies"): the body runs only when
//! it is TRUE. A POU that declares its own `EN` parameter is read as
//! CODESYS and TwinCAT read it (their ST has no implicit enable, and such
//! code declares `En : BOOL` inputs routinely): `EN :=` in a call sets that
//! parameter, and the POU has no implicit enable. Because IEC 61131-3
//! reads the same call as the enable, a FUNCTION's or FUNCTION_BLOCK's
//! input or in-out named `EN` gets warning W432. A METHOD has no enable
//! input, so its `EN` parameter is plainly a parameter; an output named
//! `EN` is read as `fb.EN` and conflicts with nothing.
//! (`ENO` declared as anything but a BOOL output is E428.)

use crate::diagnostics::Diagnostics;
use crate::syntax::ast::{CompilationUnit, Item, PouKind, VarBlock, VarKind};

/// The diagnostic code.
const W_EN_PARAM: &str = "W432";

/// Warns about every input or in-out named `EN` of a FUNCTION or
/// FUNCTION_BLOCK.
pub(super) fn check(units: &[CompilationUnit], diags: &mut Diagnostics) {
    for unit in units {
        for item in &unit.items {
            if let Item::Pou(pou) = item
                && pou.kind != PouKind::Program
            {
                check_blocks(&pou.var_blocks, diags);
            }
        }
    }
}

fn check_blocks(blocks: &[VarBlock], diags: &mut Diagnostics) {
    let params = blocks
        .iter()
        .filter(|b| matches!(b.kind, VarKind::Input | VarKind::InOut));
    for name in params.flat_map(|b| &b.decls).flat_map(|d| &d.names) {
        if name.key() != "EN" {
            continue;
        }
        diags.push(
            crate::diagnostics::Diagnostic::warning(
                W_EN_PARAM,
                name.span,
                format!(
                    "`{}` is an ordinary parameter here, as CODESYS and TwinCAT read it: `{} :=` in a call sets it",
                    name.name, name.name
                ),
            )
            .with_note(
                "IEC 61131-3 reads `EN :=` as the implicit enable input, which this POU no longer has; rename the parameter (e.g. `Enable`) to keep it",
            ),
        );
    }
}

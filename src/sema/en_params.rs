//! A parameter named `EN` (in any case). In a call, `EN := value` is the
//! enable input every FUNCTION and FUNCTION_BLOCK has implicitly (edition
//! 3; docs/semantics.md "EN and ENO in bodies"): the body runs only when
//! it is TRUE. A `VAR_INPUT en` of the POU's own would never receive the
//! value a call gives it, and CODESYS reads such a declaration as an
//! ordinary input where IEC reads the enable: the two readings run
//! differently, so the declaration is refused (E432) rather than read
//! either way in silence. The same holds for the parameters of a METHOD,
//! which has no enable input (`EN :=` in a method call is E403). A local
//! variable (`VAR`, `VAR_TEMP`) named `EN` is allowed: no call can give
//! it a value. (`ENO` declared as anything but a BOOL output is E428.)

use crate::diagnostics::Diagnostics;
use crate::syntax::ast::{CompilationUnit, Item, PouKind, VarBlock, VarKind};

/// The diagnostic code.
const E_EN_PARAM: &str = "E432";

/// Reports every parameter named `EN` of a FUNCTION, FUNCTION_BLOCK or
/// METHOD (also of an interface's method prototypes).
pub(super) fn check(units: &[CompilationUnit], diags: &mut Diagnostics) {
    for unit in units {
        for item in &unit.items {
            match item {
                Item::Pou(pou) => {
                    if pou.kind != PouKind::Program {
                        check_blocks(&pou.var_blocks, false, diags);
                    }
                    for m in pou.oop.iter().flat_map(|o| &o.methods) {
                        check_blocks(&m.var_blocks, true, diags);
                    }
                }
                Item::Interface(itf) => {
                    for m in &itf.methods {
                        check_blocks(&m.var_blocks, true, diags);
                    }
                }
                _ => {}
            }
        }
    }
}

fn check_blocks(blocks: &[VarBlock], method: bool, diags: &mut Diagnostics) {
    let params = blocks
        .iter()
        .filter(|b| matches!(b.kind, VarKind::Input | VarKind::InOut | VarKind::Output));
    for name in params.flat_map(|b| &b.decls).flat_map(|d| &d.names) {
        if name.key() != "EN" {
            continue;
        }
        let (message, note) = if method {
            (
                format!(
                    "`{}` cannot name a METHOD parameter: EN/ENO are implicit",
                    name.name
                ),
                "`EN :=` in a call is the enable input of FUNCTIONs and FUNCTION_BLOCKs, which methods do not have; rename the parameter (e.g. `Enable`)",
            )
        } else {
            (
                format!(
                    "`{}` cannot be declared as a parameter: EN/ENO are implicit",
                    name.name
                ),
                "EN is the enable input of every FUNCTION and FUNCTION_BLOCK (`EN := FALSE` in a call skips the body); rename the parameter (e.g. `Enable`)",
            )
        };
        diags.push(
            crate::diagnostics::Diagnostic::error(E_EN_PARAM, name.span, message).with_note(note),
        );
    }
}

//! Access to the members of a POU instance that are not part of its
//! interface: `x := inst.internal;`.
//!
//! IEC 61131-3 lets code outside a function block see only its inputs and
//! outputs. CoDeSys 2.3 and matiec also let it read the block's internal
//! variables (`VAR`), and library code (OSCAT) relies on it. plcrun reads
//! them with a compatibility warning (W320) and refuses to write them
//! (E420): the block owns its state, as in CODESYS. Temporaries (E421)
//! exist only during a call, so they are not visible from outside. An
//! in-out reads the variable the last call bound (`in_out_read.rs`, W325;
//! writing it from outside is E422).

use super::body::BodyBuilder;
use crate::ir::type_table::{Member, MemberKind, TypeDef, TypeId};
use crate::syntax::ast::Ident;

/// The read-only reason given to an FB's internal variable seen from
/// outside; `check_writable` reports writes of it as E420.
pub(super) const FB_INTERNAL: &str =
    "it is internal to the function block: from outside it can be read, not written";

impl BodyBuilder<'_> {
    /// A member of an instance that is not an input, output, step or action:
    /// a `VAR` is readable (W320), anything else is refused with its reason.
    pub(super) fn fb_member_outside(
        &mut self,
        def: &TypeDef,
        m: &Member,
        name: &Ident,
    ) -> Option<(u32, TypeId, bool, Option<&'static str>)> {
        if let Some(seen) = self.var_access_outside(def, m, name) {
            return seen;
        }
        match m.kind {
            MemberKind::Local => {
                self.diags.warning(
                    "W320",
                    name.span,
                    format!(
                        "`{}` is internal to {}: accessing it from outside is a CoDeSys/matiec \
                         extension (IEC 61131-3 shows only inputs and outputs)",
                        m.name, def.name
                    ),
                );
                Some((m.offset, m.ty, false, Some(FB_INTERNAL)))
            }
            MemberKind::Temp => {
                self.diags.error(
                    "E421",
                    name.span,
                    format!(
                        "`{}` is a VAR_TEMP of {}: it exists only during a call and cannot be \
                         accessed from outside",
                        m.name, def.name
                    ),
                );
                None
            }
            _ => {
                self.diags.error(
                    "E201",
                    name.span,
                    format!(
                        "`{}` is internal to {}: only inputs and outputs are visible from outside",
                        name.name, def.name
                    ),
                );
                None
            }
        }
    }
}

/// The code of a refused write: E420 for an FB's internal variable written
/// from outside, E401 for every other read-only place.
pub(super) fn write_refusal_code(reason: Option<&str>) -> &'static str {
    if reason == Some(FB_INTERNAL) {
        "E420"
    } else if reason == Some(super::in_out_read::IN_OUT_OUTSIDE) {
        "E422"
    } else {
        "E401"
    }
}

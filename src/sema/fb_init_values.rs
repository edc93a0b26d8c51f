//! Structured initial values of FB instances, `ton : TON := (PT :=
//! T#5S);`, `fb : FB_X := (limit := 10, name := 'a');` (CODESYS /
//! TwinCAT): each named input, output or local variable of the instance
//! starts with the given value instead of its declared one. In-outs,
//! externals, temporaries and a native block's hidden state cannot be
//! given one (E436).

use super::decl_consts::DeclConsts;
use super::model::{ConstInit, VarInfo};
use crate::ir::type_table::{MemberKind, TypeDef, TypeId, TypeKind, TypeTable};
use crate::stdlib::ParamDir;
use crate::syntax::ast::{Ident, Initializer};
use indexmap::IndexMap;

/// What an initial value may name in an instance: (name, index in the
/// instance's initial-value list, type, why it cannot be given one).
type Slot = (String, usize, TypeId, Option<&'static str>);

impl DeclConsts<'_> {
    /// The initial values `fields` of an instance of FB type `def` (a
    /// user FB or a native block), by member or pin index.
    pub(super) fn fb_instance_init(
        &mut self,
        fields: &[(Ident, Initializer)],
        def: &TypeDef,
        local: Option<&IndexMap<String, VarInfo>>,
    ) -> ConstInit {
        let slots = fb_slots(def);
        let mut out = Vec::new();
        for (name, value) in fields {
            let Some((_, k, ty, refused)) = slots
                .iter()
                .find(|(n, ..)| n.eq_ignore_ascii_case(&name.name))
            else {
                let names = slots.iter().map(|(n, ..)| n.as_str());
                let message = super::suggest::with_suggestion(
                    format!(
                        "`{}` has no input, output or variable `{}`",
                        def.name, name.name
                    ),
                    &name.name,
                    names,
                );
                self.diags.error("E201", name.span, message);
                continue;
            };
            if let Some(why) = refused {
                self.diags.error(
                    "E436",
                    name.span,
                    format!(
                        "`{}` of {} cannot be given an initial value in the instance's declaration: {why}",
                        name.name, def.name
                    ),
                );
                continue;
            }
            if let Some(ci) = self.resolve_init(value, *ty, local) {
                out.push((*k, ci));
            }
        }
        ConstInit::Struct(out)
    }
}

/// The members of FB type `def` an initial value may name (none for
/// other types).
fn fb_slots(def: &TypeDef) -> Vec<Slot> {
    match &def.kind {
        TypeKind::Pou { members, .. } => members
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let refused = match m.kind {
                    _ if m.constant => Some("it is a CONSTANT"),
                    MemberKind::Input | MemberKind::Output | MemberKind::Local => None,
                    MemberKind::InOut => Some("a VAR_IN_OUT is connected by each call"),
                    MemberKind::Temp => Some("a VAR_TEMP is reset at every call"),
                    MemberKind::External => Some("a VAR_EXTERNAL is the global's"),
                    _ => Some("it is not a variable"),
                };
                (m.name.clone(), k, m.ty, refused)
            })
            .collect(),
        TypeKind::NativeFb(fb) => crate::stdlib::interface(*fb)
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let refused = (p.dir == ParamDir::Hidden).then_some("it is the block's own state");
                (p.name.to_string(), k, TypeTable::elem(p.ty), refused)
            })
            .collect(),
        _ => Vec::new(),
    }
}

//! Incomplete located variables, `AT %I*` / `%Q*` / `%M*` (optionally
//! with a size, `%IW*`): declared in a PROGRAM or FUNCTION_BLOCK, they
//! live in the instance like any variable and get their address per
//! instance from the configuration's `VAR_CONFIG` (see `link/var_config.rs`).

use super::declare::Declarer;
use crate::elementary::ElemType;
use crate::ir::type_table::TypeId;
use crate::syntax::ast::{AddrSize, Area, DirectAddress, Pou, PouKind, VarBlock, VarKind};

/// True when an address of `size` can hold a value of type `elem` (the
/// rule of complete located variables: a bit holds a BOOL, a byte, word,
/// double or long word an elementary type of that width; TIME fits 32 bits).
pub(super) fn address_fits(size: AddrSize, elem: Option<ElemType>) -> bool {
    match (size, elem) {
        (AddrSize::Bit, Some(e)) => e == ElemType::Bool,
        (size, Some(e)) => {
            let bits = match size {
                AddrSize::Byte => 8,
                AddrSize::Word => 16,
                AddrSize::Dword => 32,
                _ => 64,
            };
            e.bits() == bits || (bits == 32 && e == ElemType::Time)
        }
        _ => false,
    }
}

/// The text kept for an incomplete address: `%I*`, `%QW*`, upper case.
pub(super) fn incomplete_text(a: &DirectAddress) -> String {
    let area = match a.area {
        Area::Input => 'I',
        Area::Output => 'Q',
        Area::Memory => 'M',
    };
    let size = match (a.explicit_size, a.size) {
        (false, _) => "",
        (true, AddrSize::Bit) => "X",
        (true, AddrSize::Byte) => "B",
        (true, AddrSize::Word) => "W",
        (true, AddrSize::Dword) => "D",
        (true, AddrSize::Lword) => "L",
    };
    format!("%{area}{size}*")
}

/// True for the text of an incomplete address as kept by [`incomplete_text`].
pub(super) fn is_incomplete(location: &str) -> bool {
    location.ends_with('*')
}

impl Declarer<'_> {
    /// Checks an incomplete address `a` declared for a variable of type
    /// `ty` in `block` of `pou`; returns the text to keep as its location,
    /// or `None` after an error (E207).
    pub(super) fn incomplete_address(
        &mut self,
        pou: &Pou,
        block: &VarBlock,
        a: &DirectAddress,
        ty: TypeId,
    ) -> Option<String> {
        let why = if pou.kind == PouKind::Function {
            Some("a FUNCTION's variables do not outlive a call")
        } else if matches!(
            block.kind,
            VarKind::InOut | VarKind::External | VarKind::Temp
        ) {
            Some("only VAR, VAR_INPUT and VAR_OUTPUT variables can have an address")
        } else {
            None
        };
        if let Some(why) = why {
            self.diags.error(
                "E207",
                a.span,
                format!("`{}` cannot be declared here: {why}", a.text),
            );
            return None;
        }
        // An array of scalars too: VAR_CONFIG gives each element its
        // address (`link/config_elements.rs`).
        let elem = self
            .types
            .scalar(ty)
            .or_else(|| match &self.types.get(ty).kind {
                crate::ir::type_table::TypeKind::Array { elem, .. } => self.types.scalar(*elem),
                _ => None,
            });
        if elem.is_none() || (a.explicit_size && !address_fits(a.size, elem)) {
            self.diags.error(
                "E207",
                a.span,
                format!(
                    "`{}` cannot hold a {}: the address size does not match the type",
                    a.text,
                    self.types.name(ty)
                ),
            );
            return None;
        }
        Some(incomplete_text(a))
    }
}

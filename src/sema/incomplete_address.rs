//! Incomplete located variables, `AT %I*` / `%Q*` / `%M*` (optionally
//! with a size, `%IW*`): declared in a PROGRAM or FUNCTION_BLOCK, they
//! live in the instance like any variable and get their address per
//! instance from the configuration's `VAR_CONFIG` (see `link/var_config.rs`).

use super::declare::Declarer;
use crate::elementary::ElemType;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};
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

/// One elementary value of a variable declared at an incomplete address.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Leaf {
    /// Its path below the variable: empty for the variable itself,
    /// `[2]`, `[1,0]`, `.nTran`, `.aRaw[3]`.
    pub(crate) path: String,
    /// Its slot offset from the variable's.
    pub(crate) offset: u32,
    /// Its elementary type.
    pub(crate) ty: TypeId,
}

/// Deepest nesting of arrays and structures followed.
const MAX_LEAF_DEPTH: usize = 32;

/// The elementary values a variable of type `ty` at an incomplete address
/// is made of, each of which gets an address: the variable itself when
/// elementary, the elements of an array in row-major order, the fields of
/// a structure in declaration order (TwinCAT maps a structure onto
/// consecutive I/O bytes), recursively. `None` when one of them cannot
/// have an address (a reference, an FB instance).
pub(crate) fn address_leaves(types: &TypeTable, ty: TypeId) -> Option<Vec<Leaf>> {
    let mut out = Vec::new();
    leaves_into(types, ty, String::new(), 0, 0, &mut out)?;
    Some(out)
}

fn leaves_into(
    types: &TypeTable,
    ty: TypeId,
    path: String,
    offset: u32,
    depth: usize,
    out: &mut Vec<Leaf>,
) -> Option<()> {
    if depth > MAX_LEAF_DEPTH {
        return None;
    }
    // A STRING is one too: placing it is E710, with the other values
    // that fit no address.
    if types.scalar(ty).is_some() {
        out.push(Leaf { path, offset, ty });
        return Some(());
    }
    match &types.get(ty).kind {
        TypeKind::Array { dims, elem } => {
            let stride = types.size(*elem);
            let count: u64 = dims.iter().map(|d| d.len()).product();
            for k in 0..count {
                let at = offset.checked_add(u32::try_from(k * u64::from(stride)).ok()?)?;
                let name = format!("{path}{}", element_suffix(dims, k));
                leaves_into(types, *elem, name, at, depth + 1, out)?;
            }
            Some(())
        }
        TypeKind::Struct { fields } => {
            for f in fields {
                let at = offset.checked_add(f.offset)?;
                leaves_into(
                    types,
                    f.ty,
                    format!("{path}.{}", f.name),
                    at,
                    depth + 1,
                    out,
                )?;
            }
            Some(())
        }
        _ => None,
    }
}

/// `[i,j]` for row-major element number `k` of an array of `dims`.
pub(crate) fn element_suffix(dims: &[crate::ir::type_table::Dim], mut k: u64) -> String {
    let mut index = vec![0i64; dims.len()];
    for (i, d) in dims.iter().enumerate().rev() {
        let n = d.len().max(1);
        index[i] = d.lo + (k % n) as i64;
        k /= n;
    }
    let text: Vec<String> = index.iter().map(|v| v.to_string()).collect();
    format!("[{}]", text.join(","))
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
        // An array or a structure too: each elementary value in it gets an
        // address of its own (`address_leaves`).
        let fits = address_leaves(&self.types, ty).is_some_and(|leaves| {
            !a.explicit_size
                || leaves
                    .iter()
                    .all(|l| address_fits(a.size, self.types.scalar(l.ty)))
        });
        if !fits {
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

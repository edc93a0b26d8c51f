//! The variables traced when the user names none: every program
//! instance's VAR_OUTPUTs and its `%Q` located variables, each expanded
//! into the single values it holds — the elements of an array (`a[1]`,
//! `grid[1,2]`), the fields of a structure (`s.x`), the outputs of an FB
//! instance (`t.Q`) — since a trace column holds one value.

use crate::ir::image::Image;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind};
use crate::stdlib::{ParamDir, interface};

/// A variable expanding into more columns than this is left out of the
/// default trace (named with a note), so that a large array output does not
/// bury the others; `--trace` can still name its elements.
pub const MAX_COLUMNS_PER_VARIABLE: usize = 256;

/// True for the names of the trace's own columns, `cycle` and `time`
/// (case-insensitive): a variable of that name is traced by its qualified
/// path (`P.time`).
pub fn is_trace_column(name: &str) -> bool {
    name.eq_ignore_ascii_case("cycle") || name.eq_ignore_ascii_case("time")
}

/// The default trace: its column names, and the variables left out.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DefaultTrace {
    /// The traced names, in declaration order.
    pub names: Vec<String>,
    /// Variables left out, with the number of values they hold.
    pub left_out: Vec<(String, usize)>,
}

/// The default trace of `image` (see the module documentation).
pub fn default_trace(image: &Image) -> DefaultTrace {
    let mut trace = DefaultTrace::default();
    // An S7-200 program's outputs are the bits of its Q image.
    if let Some(names) = super::s7_names::default_trace(image) {
        trace.names = names;
        return trace;
    }
    let qualify = image.programs.len() > 1;
    for inst in &image.programs {
        for m in image.types.members(inst.ty) {
            if m.kind == MemberKind::Output {
                // `cycle` and `time` are the trace's own columns.
                let clashes = is_trace_column(&m.name);
                let name = if qualify || clashes {
                    format!("{}.{}", inst.name, m.name)
                } else {
                    m.name.clone()
                };
                trace.add(image, name, m.ty);
            }
        }
    }
    // One name per %Q address: the declared name when there is one.
    let mut seen: Vec<u32> = Vec::new();
    let mut named: Vec<&crate::ir::image::RootVar> = image
        .globals
        .iter()
        .filter(|r| r.location.as_deref().is_some_and(|l| l.starts_with("%Q")))
        .collect();
    named.sort_by_key(|r| (r.name.starts_with('%'), r.addr));
    for r in named {
        let taken = trace.names.iter().any(|n| n.eq_ignore_ascii_case(&r.name));
        if seen.contains(&r.addr) || taken {
            continue;
        }
        seen.push(r.addr);
        trace.add(image, r.name.clone(), r.ty);
    }
    trace
}

impl DefaultTrace {
    /// Adds the single values of `name` (of type `ty`), or notes it as
    /// left out when it holds too many.
    fn add(&mut self, image: &Image, name: String, ty: TypeId) {
        let mut values = Vec::new();
        if leaves(image, name.clone(), ty, &mut values) {
            self.names.extend(values);
        } else {
            self.left_out.push((name, count(image, ty)));
        }
    }
}

/// Pushes the names of the single values inside `name`; false (and
/// nothing pushed past the limit) when there are more than
/// [`MAX_COLUMNS_PER_VARIABLE`].
fn leaves(image: &Image, name: String, ty: TypeId, out: &mut Vec<String>) -> bool {
    let start = out.len();
    let mut ok = true;
    walk(image, name, ty, &mut |leaf| {
        if out.len() - start >= MAX_COLUMNS_PER_VARIABLE {
            ok = false;
        } else {
            out.push(leaf);
        }
        ok
    });
    if !ok {
        out.truncate(start);
    }
    ok
}

/// How many single values a variable of `ty` holds (saturating), without
/// enumerating them.
fn count(image: &Image, ty: TypeId) -> usize {
    match &image.types.get(ty).kind {
        TypeKind::Elem(_)
        | TypeKind::Str { .. }
        | TypeKind::Enum { .. }
        | TypeKind::Subrange { .. } => 1,
        TypeKind::Array { dims, elem } => dims
            .iter()
            .map(|d| usize::try_from(d.len()).unwrap_or(usize::MAX))
            .fold(count(image, *elem), usize::saturating_mul),
        TypeKind::Struct { fields } => fields
            .iter()
            .fold(0, |n, f| n.saturating_add(count(image, f.ty))),
        TypeKind::Pou { members, .. } => members
            .iter()
            .filter(|m| m.kind == MemberKind::Output)
            .fold(0, |n, m| n.saturating_add(count(image, m.ty))),
        TypeKind::NativeFb(fb) => interface(*fb)
            .iter()
            .filter(|p| p.dir == ParamDir::Output)
            .count(),
        _ => 0,
    }
}

/// Calls `leaf` with the name of every single value inside `name`, in
/// declaration order, until it returns false; false when stopped.
fn walk(image: &Image, name: String, ty: TypeId, leaf: &mut dyn FnMut(String) -> bool) -> bool {
    match &image.types.get(ty).kind {
        TypeKind::Elem(_)
        | TypeKind::Str { .. }
        | TypeKind::Enum { .. }
        | TypeKind::Subrange { .. } => leaf(name),
        TypeKind::Array { dims, elem } => {
            let mut index: Vec<i64> = dims.iter().map(|d| d.lo).collect();
            if dims.iter().any(|d| d.hi < d.lo) {
                return true;
            }
            loop {
                let text: Vec<String> = index.iter().map(i64::to_string).collect();
                if !walk(image, format!("{name}[{}]", text.join(",")), *elem, leaf) {
                    return false;
                }
                // The last index runs fastest, as in memory.
                let mut k = dims.len();
                loop {
                    if k == 0 {
                        return true;
                    }
                    k -= 1;
                    if index[k] < dims[k].hi {
                        index[k] += 1;
                        break;
                    }
                    index[k] = dims[k].lo;
                }
            }
        }
        TypeKind::Struct { fields } => fields
            .iter()
            .all(|f| walk(image, format!("{name}.{}", f.name), f.ty, leaf)),
        TypeKind::Pou { members, .. } => members
            .iter()
            .filter(|m| m.kind == MemberKind::Output)
            .all(|m| walk(image, format!("{name}.{}", m.name), m.ty, leaf)),
        TypeKind::NativeFb(fb) => interface(*fb)
            .iter()
            .filter(|p| p.dir == ParamDir::Output)
            .all(|p| leaf(format!("{name}.{}", p.name))),
        _ => true,
    }
}

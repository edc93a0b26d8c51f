//! The variables traced when the user names none: every program
//! instance's VAR_OUTPUTs and its `%Q` located variables, each expanded
//! into the single values it holds — the elements of an array (`a[1]`,
//! `grid[1,2]`), the fields of a structure (`s.x`), the outputs of an FB
//! instance (`t.Q`) — since a trace column holds one value.

use crate::ir::image::Image;
use crate::ir::type_table::{Dim, MemberKind, TypeId, TypeKind};
use crate::stdlib::{ParamDir, interface};
use std::collections::HashMap;

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
/// enumerating them: each type counted once, children first, on a work
/// list (types nest tens of thousands of levels deep, and a structure
/// holding the same type twice at every level would take exponential time
/// counted as a tree).
fn count(image: &Image, ty: TypeId) -> usize {
    let mut counted: HashMap<TypeId, usize> = HashMap::new();
    let mut work = vec![(ty, false)];
    while let Some((t, children_done)) = work.pop() {
        if counted.contains_key(&t) {
            continue;
        }
        let kind = &image.types.get(t).kind;
        if !children_done {
            work.push((t, true));
            work.extend(parts(kind).map(|c| (c, false)));
            continue;
        }
        let sum = |counted: &HashMap<TypeId, usize>| {
            parts(kind).fold(0usize, |n, c| {
                n.saturating_add(counted.get(&c).copied().unwrap_or(0))
            })
        };
        let n = match kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. } => 1,
            TypeKind::Array { dims, .. } => dims
                .iter()
                .map(|d| usize::try_from(d.len()).unwrap_or(usize::MAX))
                .fold(sum(&counted), usize::saturating_mul),
            TypeKind::Struct { .. } | TypeKind::Pou { .. } => sum(&counted),
            TypeKind::NativeFb(fb) => interface(*fb)
                .iter()
                .filter(|p| p.dir == ParamDir::Output)
                .count(),
            _ => 0,
        };
        counted.insert(t, n);
    }
    counted.get(&ty).copied().unwrap_or(0)
}

/// The types whose values a value of `kind` is made of, as the default
/// trace sees it: an array's element, a structure's fields, an FB
/// instance's outputs.
fn parts(kind: &TypeKind) -> Box<dyn Iterator<Item = TypeId> + '_> {
    match kind {
        TypeKind::Array { elem, .. } => Box::new(std::iter::once(*elem)),
        TypeKind::Struct { fields } => Box::new(fields.iter().map(|f| f.ty)),
        TypeKind::Pou { members, .. } => Box::new(
            members
                .iter()
                .filter(|m| m.kind == MemberKind::Output)
                .map(|m| m.ty),
        ),
        _ => Box::new(std::iter::empty()),
    }
}

/// What is left to visit: a value, or the rest of an array's elements
/// (enumerated lazily: the walk may stop long before the end).
enum Visit<'a> {
    Value(String, TypeId),
    Elements {
        name: String,
        elem: TypeId,
        dims: &'a [Dim],
        index: Vec<i64>,
    },
}

/// Calls `leaf` with the name of every single value inside `name`, in
/// declaration order, until it returns false; false when stopped. A work
/// list, not recursion: the types may nest tens of thousands of levels.
fn walk(image: &Image, name: String, ty: TypeId, leaf: &mut dyn FnMut(String) -> bool) -> bool {
    let mut work = vec![Visit::Value(name, ty)];
    while let Some(visit) = work.pop() {
        let (name, ty) = match visit {
            Visit::Value(name, ty) => (name, ty),
            Visit::Elements {
                name,
                elem,
                dims,
                mut index,
            } => {
                let text: Vec<String> = index.iter().map(i64::to_string).collect();
                let element = format!("{name}[{}]", text.join(","));
                if next_index(dims, &mut index) {
                    work.push(Visit::Elements {
                        name,
                        elem,
                        dims,
                        index,
                    });
                }
                work.push(Visit::Value(element, elem));
                continue;
            }
        };
        let at = work.len();
        match &image.types.get(ty).kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. } => {
                let go_on = leaf(name);
                if !go_on {
                    return false;
                }
            }
            // An empty dimension: no elements.
            TypeKind::Array { dims, elem } if dims.iter().all(|d| d.hi >= d.lo) => {
                work.push(Visit::Elements {
                    name,
                    elem: *elem,
                    dims,
                    index: dims.iter().map(|d| d.lo).collect(),
                });
            }
            TypeKind::Struct { fields } => {
                for f in fields {
                    work.push(Visit::Value(format!("{name}.{}", f.name), f.ty));
                }
            }
            TypeKind::Pou { members, .. } => {
                for m in members.iter().filter(|m| m.kind == MemberKind::Output) {
                    work.push(Visit::Value(format!("{name}.{}", m.name), m.ty));
                }
            }
            TypeKind::NativeFb(fb) => {
                for p in interface(*fb).iter().filter(|p| p.dir == ParamDir::Output) {
                    if !leaf(format!("{name}.{}", p.name)) {
                        return false;
                    }
                }
            }
            _ => {}
        }
        // Pushed in order, popped in reverse: turn them around.
        work[at..].reverse();
    }
    true
}

/// Steps `index` to the next element (the last index runs fastest, as in
/// memory); false after the last one.
fn next_index(dims: &[Dim], index: &mut [i64]) -> bool {
    for k in (0..dims.len()).rev() {
        if index[k] < dims[k].hi {
            index[k] += 1;
            return true;
        }
        index[k] = dims[k].lo;
    }
    false
}

//! Naming variables from outside the program (trace, stimulus, `--set`,
//! the embedding API): `x`, `inst.ET`, `arr[3]`, `grid[1,2]`, `S1.X`,
//! `prog.x` for configuration instances, and located addresses `%IX0.1`.

use super::byte_view::ByteView;
use super::var_error::{PathProblem, ReadOnlyReason, VarError};
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind, step_layout};

/// A resolved variable: a handle for repeated access without looking the
/// name up again. Only [`crate::Plc::resolve`] makes one, and only the PLC
/// that made it accepts it.
#[derive(Debug, Clone, PartialEq)]
pub struct VarRef {
    /// The name as the user wrote it.
    pub(crate) name: String,
    /// Absolute slot address.
    pub(crate) addr: u32,
    /// Type.
    pub(crate) ty: TypeId,
    /// The identity of the PLC that resolved it.
    pub(crate) owner: u64,
    /// Why it cannot be written from outside, if it cannot.
    pub(crate) read_only: Option<ReadOnlyReason>,
    /// A part of the byte slots from `addr` (an S7-200 bit, word or double
    /// word of a byte image); `None` for a whole slot.
    pub(crate) view: Option<ByteView>,
}

impl VarRef {
    /// Whether `self` and `other` name the same value (the same slot and
    /// the same view of it; `V6.1` and `VB6` share a slot but are not the
    /// same value).
    pub(crate) fn same_place(&self, other: &VarRef) -> bool {
        self.addr == other.addr && self.view == other.view
    }

    /// The name as it was given to `resolve` (trimmed).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Why the variable cannot be written from outside (a CONSTANT, an
    /// SFC step or action flag), or `None` when it can.
    pub fn read_only(&self) -> Option<ReadOnlyReason> {
        self.read_only
    }
}

/// One step of a path.
#[derive(Debug, Clone, PartialEq)]
enum Seg {
    Member(String),
    Index(Vec<i64>),
}

fn parse_path(text: &str) -> Result<(String, Vec<Seg>), VarError> {
    let t = text.trim();
    let bad = |problem| VarError::BadPath {
        path: text.to_string(),
        problem,
    };
    if t.is_empty() {
        return Err(bad(PathProblem::Empty));
    }
    if t.starts_with('%') {
        return Ok((t.to_string(), Vec::new()));
    }
    let bytes: Vec<char> = t.chars().collect();
    let mut i = 0;
    let ident = |i: &mut usize| -> Result<String, VarError> {
        let start = *i;
        while *i < bytes.len() && (bytes[*i].is_alphanumeric() || bytes[*i] == '_') {
            *i += 1;
        }
        if start == *i {
            return Err(bad(PathProblem::NotAName));
        }
        Ok(bytes[start..*i].iter().collect())
    };
    let root = ident(&mut i)?;
    let mut segs = Vec::new();
    while i < bytes.len() {
        match bytes[i] {
            '.' => {
                i += 1;
                segs.push(Seg::Member(ident(&mut i)?));
            }
            '[' => {
                let close = bytes[i..]
                    .iter()
                    .position(|c| *c == ']')
                    .ok_or_else(|| bad(PathProblem::MissingBracket))?;
                let inner: String = bytes[i + 1..i + close].iter().collect();
                let mut idx = Vec::new();
                for part in inner.split(',') {
                    idx.push(part.trim().parse::<i64>().map_err(|_| {
                        bad(PathProblem::IndexNotAnInteger(part.trim().to_string()))
                    })?);
                }
                segs.push(Seg::Index(idx));
                i += close + 1;
            }
            c => return Err(bad(PathProblem::Unexpected(c))),
        }
    }
    Ok((root, segs))
}

/// Normalises a direct address text: `%I0.1` → `%IX0.1`, case-insensitive.
fn normalize(text: &str) -> String {
    let upper = text.trim().to_ascii_uppercase();
    let rest = &upper[1..];
    let mut chars = rest.chars();
    let area = chars.next().unwrap_or('?');
    let after: String = chars.collect();
    match after.chars().next() {
        Some('X' | 'B' | 'W' | 'D' | 'L') => format!("%{area}{after}"),
        _ => format!("%{area}X{after}"),
    }
}

/// Resolves `text` against the image, for the PLC `owner`; the error names
/// what is unknown.
pub fn resolve(image: &Image, text: &str, owner: u64) -> Result<VarRef, VarError> {
    if let Some(r) = super::s7_names::resolve(image, text, owner) {
        return r;
    }
    let (mut root, mut segs) = parse_path(text)?;
    if let Some(global) = list_qualified(image, &root, &segs) {
        // `GVL.count`: a global named with its list (TwinCAT, CODESYS),
        // as the program may name it.
        root = global;
        segs.remove(0);
    }
    let (mut addr, mut ty, mut read_only) = if root.starts_with('%') {
        let key = normalize(&root);
        // The text as declared, else the same place in the process image
        // (`%IX0.1` names a variable declared at `%I0.0.0.0.1`).
        let place = crate::address::parse(&root).ok();
        let r = image
            .globals
            .iter()
            .find(|r| r.location.as_deref() == Some(key.as_str()))
            .or_else(|| {
                let place = place?;
                image.globals.iter().find(|r| {
                    r.location
                        .as_deref()
                        .is_some_and(|l| crate::address::parse(l).ok() == Some(place))
                })
            })
            .ok_or_else(|| VarError::NotLocated {
                address: root.clone(),
            })?;
        (r.addr, r.ty, r.constant.then_some(ReadOnlyReason::Constant))
    } else {
        find_root(image, &root)?
    };
    let mut segs = segs.into_iter().peekable();
    while let Some(seg) = segs.next() {
        match seg {
            Seg::Member(m) => {
                // `inst.Method.var`: a method's local, kept in the
                // instance under its hidden name.
                let mut found = member(image, ty, &m);
                if found.is_none()
                    && let Some(Seg::Member(var)) = segs.peek()
                {
                    found = method_local(image, ty, &m, var);
                    if found.is_some() {
                        segs.next();
                    }
                }
                let Some((off, t, why)) = found else {
                    return Err(VarError::NoMember {
                        path: text.to_string(),
                        ty: image.types.name(ty).to_string(),
                        member: m,
                    });
                };
                addr += off;
                ty = t;
                read_only = read_only.or(why);
            }
            Seg::Index(idx) => {
                let TypeKind::Array { dims, elem } = &image.types.get(ty).kind else {
                    return Err(VarError::NotAnArray {
                        path: text.to_string(),
                        ty: image.types.name(ty).to_string(),
                    });
                };
                if idx.len() != dims.len() {
                    return Err(VarError::IndexCount {
                        path: text.to_string(),
                        dimensions: dims.len(),
                        given: idx.len(),
                    });
                }
                let mut linear: u64 = 0;
                for (i, d) in idx.iter().zip(dims) {
                    if *i < d.lo || *i > d.hi {
                        return Err(VarError::IndexOutOfBounds {
                            path: text.to_string(),
                            index: *i,
                            lo: d.lo,
                            hi: d.hi,
                        });
                    }
                    linear = linear * d.len() + (*i - d.lo) as u64;
                }
                addr += (linear * image.types.size(*elem) as u64) as u32;
                ty = *elem;
            }
        }
    }
    Ok(VarRef {
        name: text.trim().to_string(),
        addr,
        ty,
        owner,
        read_only,
        view: None,
    })
}

/// Why a member of kind `kind` (declared CONSTANT or not) cannot be
/// written from outside.
fn member_read_only(kind: MemberKind, constant: bool) -> Option<ReadOnlyReason> {
    match kind {
        _ if constant => Some(ReadOnlyReason::Constant),
        MemberKind::Step => Some(ReadOnlyReason::StepFlag),
        MemberKind::Action => Some(ReadOnlyReason::ActionFlag),
        _ => None,
    }
}

/// The global `root.global` names when `root` is no variable, program or
/// instance and `global` is a global variable: `root` is then the name of
/// its global variable list, which plcrun does not keep (any such name
/// qualifies, as in the program's own code).
fn list_qualified(image: &Image, root: &str, segs: &[Seg]) -> Option<String> {
    let Some(Seg::Member(global)) = segs.first() else {
        return None;
    };
    if root.starts_with('%') || find_root(image, root).is_ok() {
        return None;
    }
    image.global_named(global).map(|_| global.clone())
}

fn find_root(image: &Image, name: &str) -> Result<(u32, TypeId, Option<ReadOnlyReason>), VarError> {
    // A variable of the (single) program, then globals, then instance names.
    if image.programs.len() == 1 {
        let inst = &image.programs[0];
        if let Some(m) = image.member_named(inst.ty, name) {
            return Ok((
                inst.base + m.offset,
                m.ty,
                member_read_only(m.kind, m.constant),
            ));
        }
    }
    if let Some(r) = image.global_named(name) {
        return Ok((r.addr, r.ty, r.constant.then_some(ReadOnlyReason::Constant)));
    }
    if let Some(inst) = image
        .programs
        .iter()
        .find(|p| p.name.eq_ignore_ascii_case(name))
    {
        return Ok((inst.base, inst.ty, None));
    }
    Err(VarError::Unknown {
        name: name.to_string(),
    })
}

/// Offset and type of variable `var` of method `method` of the FB type
/// `ty` (stored as a member named `Origin__method__var`, `Origin` the FB
/// that declares the method).
fn method_local(
    image: &Image,
    ty: TypeId,
    method: &str,
    var: &str,
) -> Option<(u32, TypeId, Option<ReadOnlyReason>)> {
    if !matches!(image.types.get(ty).kind, TypeKind::Pou { .. }) {
        return None;
    }
    image
        .types
        .members(ty)
        .iter()
        .find(|m| {
            method_local_name(image, &m.name).is_some_and(|(mm, vv)| {
                mm.eq_ignore_ascii_case(method) && vv.eq_ignore_ascii_case(var)
            })
        })
        .map(|m| (m.offset, m.ty, member_read_only(m.kind, m.constant)))
}

/// The method and variable a hidden member name `Origin__Method__var`
/// stands for: `Origin.Method` must be a method of the program (a name
/// the user wrote with double underscores, which IEC forbids but some
/// tools accept, stays as it is).
pub(crate) fn method_local_name<'m>(image: &Image, member: &'m str) -> Option<(&'m str, &'m str)> {
    let mut parts = member.split("__");
    let (origin, method, var) = (parts.next()?, parts.next()?, parts.next()?);
    if parts.next().is_some() || [origin, method, var].iter().any(|p| p.is_empty()) {
        return None;
    }
    let is_method = |name: &str| {
        name.split_once('.')
            .is_some_and(|(o, m)| o.eq_ignore_ascii_case(origin) && m.eq_ignore_ascii_case(method))
    };
    image
        .codes
        .iter()
        .any(|c| is_method(&c.name))
        .then_some((method, var))
}

/// A member's name as paths show it: a method's local (hidden member
/// `Origin__Method__var`) as `Method.var`, which [`resolve`] accepts.
pub(crate) fn shown_member<'m>(image: &Image, member: &'m str) -> std::borrow::Cow<'m, str> {
    match method_local_name(image, member) {
        Some((method, var)) => format!("{method}.{var}").into(),
        None => member.into(),
    }
}

/// Offset and type of member `name` of `ty`, and why it cannot be
/// written from outside.
fn member(image: &Image, ty: TypeId, name: &str) -> Option<(u32, TypeId, Option<ReadOnlyReason>)> {
    use crate::ir::type_table::TypeTable;
    match &image.types.get(ty).kind {
        TypeKind::Struct { .. } | TypeKind::Pou { .. } => image
            .member_named(ty, name)
            .map(|m| (m.offset, m.ty, member_read_only(m.kind, m.constant))),
        TypeKind::NativeFb(fb) => crate::stdlib::interface(*fb)
            .iter()
            .enumerate()
            .find(|(_, p)| {
                p.dir != crate::stdlib::ParamDir::Hidden
                    && (p.name.eq_ignore_ascii_case(name)
                        || p.aliases.iter().any(|a| a.eq_ignore_ascii_case(name)))
            })
            .map(|(i, p)| (i as u32, TypeTable::elem(p.ty), None)),
        TypeKind::Step => match name.to_ascii_uppercase().as_str() {
            "X" => Some((
                step_layout::X,
                TypeTable::elem(ElemType::Bool),
                Some(ReadOnlyReason::StepFlag),
            )),
            "T" => Some((
                step_layout::T,
                TypeTable::elem(ElemType::Time),
                Some(ReadOnlyReason::StepFlag),
            )),
            _ => None,
        },
        _ => None,
    }
}

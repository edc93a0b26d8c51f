//! Reading and writing a PLC's variables from outside, by name or through
//! a resolved handle.

use super::engine::Plc;
use super::names::{self, VarRef};
use super::plc_value::Value;
use super::var_error::{ValueProblem, VarError};
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::type_table::{TypeId, TypeKind};
use crate::value::encode::is_canonical;
use crate::value::text::{Lit, parse_literal_text, parse_scalar};
use crate::vm::Machine;

impl Plc {
    /// Resolves a variable name (see `docs/cli.md` for the syntax).
    pub fn resolve(&self, name: &str) -> Result<VarRef, VarError> {
        let r = names::resolve(&self.image, name, self.id)?;
        match &self.image.types.get(r.ty).kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. } => Ok(r),
            _ => Err(VarError::NotAValue {
                path: name.to_string(),
                ty: self.image.types.name(r.ty).to_string(),
            }),
        }
    }

    /// Checks that `r` was resolved by this PLC.
    pub(super) fn owned(&self, r: &VarRef) -> Result<(), VarError> {
        if r.owner == self.id {
            Ok(())
        } else {
            Err(VarError::ForeignHandle {
                path: r.name.clone(),
            })
        }
    }

    /// Reads a resolved variable. A handle resolved by another PLC is an
    /// error.
    pub fn get(&self, r: &VarRef) -> Result<Value, VarError> {
        self.owned(r)?;
        Ok(self.value_at(r))
    }

    /// The value of a variable of this PLC (`r` resolved by it).
    #[inline]
    pub(super) fn value_at(&self, r: &VarRef) -> Value {
        if let Some(view) = r.view {
            let ty = self.image.types.scalar(r.ty).unwrap_or(ElemType::Lint);
            return Value::Scalar(ty, view.read(&self.machine.mem, r.addr));
        }
        value_in(&self.image, &self.machine, r.addr, r.ty)
    }

    /// Reads a variable by name.
    pub fn read(&self, name: &str) -> Result<Value, VarError> {
        self.get(&self.resolve(name)?)
    }

    /// Reads an integer variable by name.
    pub fn read_i64(&self, name: &str) -> Result<i64, VarError> {
        self.read(name)?
            .as_i64()
            .ok_or_else(|| VarError::NotAnInteger {
                path: name.to_string(),
            })
    }

    /// Decodes an IEC literal for the type of `r` (checks it fits).
    pub fn parse_value(&self, r: &VarRef, text: &str) -> Result<Value, VarError> {
        self.owned(r)?;
        parse_for(&self.image, r.ty, text)
    }

    /// Writes a value into a resolved variable. The value must be of the
    /// variable's type (as [`Self::parse_value`] or [`Self::get`] give it),
    /// and a handle resolved by another PLC is refused, as is a variable
    /// the program cannot write either (a CONSTANT, an SFC step flag:
    /// [`VarError::ReadOnly`]).
    ///
    /// This is a soft write: on a [forced](Self::force) variable it is
    /// accepted but the force wins; the variable takes the written value
    /// when it is unforced.
    pub fn set(&mut self, r: &VarRef, v: &Value) -> Result<(), VarError> {
        self.owned(r)?;
        self.writable(r)?;
        self.check_fits(r, v)?;
        if !self.forces.is_empty() && self.forces.hold_under(r, v) {
            return Ok(());
        }
        self.store(r, v);
        Ok(())
    }

    /// Refuses a value not of `r`'s type.
    pub(super) fn check_fits(&self, r: &VarRef, v: &Value) -> Result<(), VarError> {
        if self.fits(r, v) {
            Ok(())
        } else {
            Err(VarError::WrongValue {
                path: r.name.clone(),
                ty: self.image.types.name(r.ty).to_string(),
                value: v.to_literal(),
            })
        }
    }

    /// Refuses a write from outside to a variable the program cannot write.
    pub(super) fn writable(&self, r: &VarRef) -> Result<(), VarError> {
        match r.read_only {
            Some(why) => Err(VarError::ReadOnly {
                path: r.name.clone(),
                why,
            }),
            None => Ok(()),
        }
    }

    /// Stores a value of `r`'s type into a variable of this PLC (and into
    /// the process image when the variable is located there).
    pub(super) fn store(&mut self, r: &VarRef, v: &Value) {
        if let (Some(view), Value::Scalar(_, raw)) = (r.view, v) {
            view.write(&mut self.machine.mem, r.addr, *raw);
            return;
        }
        let slot = &mut self.machine.mem[r.addr as usize];
        match v {
            Value::Scalar(_, raw) => {
                *slot = *raw;
                self.io.stored(r.addr, *raw);
            }
            Value::Enum(_, x) => {
                *slot = *x as u64;
                self.io.stored(r.addr, *x as u64);
            }
            Value::String(s, _) => {
                if let Some(string) = self.machine.strings.get_mut(*slot as usize) {
                    string.set(s);
                }
            }
        }
    }

    /// Whether `v` is a value of `r`'s type, in the slot encoding the
    /// executor relies on.
    fn fits(&self, r: &VarRef, v: &Value) -> bool {
        match (&self.image.types.get(r.ty).kind, v) {
            (TypeKind::Str { .. }, Value::String(..)) => true,
            (TypeKind::Enum { values, .. }, Value::Enum(_, x)) => {
                values.iter().any(|(_, v)| v == x)
            }
            (TypeKind::Subrange { base, lo, hi }, Value::Scalar(t, raw)) => {
                t == base && (*lo..=*hi).contains(&(*raw as i64))
            }
            (TypeKind::Elem(e), Value::Scalar(t, raw)) => e == t && is_canonical(*t, *raw),
            _ => false,
        }
    }

    /// Writes a variable by name from an IEC literal (a soft write, as
    /// [`Self::set`]).
    pub fn write(&mut self, name: &str, literal: &str) -> Result<(), VarError> {
        let r = self.resolve(name)?;
        let v = self.parse_value(&r, literal)?;
        self.set(&r, &v)
    }
}

/// The value of the variable of type `ty` (a single value: elementary,
/// string, enumeration, subrange) at slot `addr` of machine `m`.
pub(super) fn value_in(image: &Image, m: &Machine, addr: u32, ty: TypeId) -> Value {
    let raw = m.mem.get(addr as usize).copied().unwrap_or(0);
    match &image.types.get(ty).kind {
        TypeKind::Str { wide, .. } => {
            let s = m
                .strings
                .get(raw as usize)
                .map(|s| s.text.clone())
                .unwrap_or_default();
            Value::String(s, *wide)
        }
        TypeKind::Enum { values, .. } => {
            let v = raw as i64;
            let name = values
                .iter()
                .find(|(_, x)| *x == v)
                .map(|(n, _)| n.clone())
                .unwrap_or_else(|| v.to_string());
            Value::Enum(name, v)
        }
        _ => Value::Scalar(image.types.scalar(ty).unwrap_or(ElemType::Lint), raw),
    }
}

/// Decodes IEC literal `text` as a value of type `ty` (checks it fits).
pub(super) fn parse_for(image: &Image, ty: TypeId, text: &str) -> Result<Value, VarError> {
    let t = text.trim();
    let bad = |problem| VarError::BadValue {
        literal: t.to_string(),
        ty: image.types.name(ty).to_string(),
        problem,
    };
    match &image.types.get(ty).kind {
        TypeKind::Str { wide, .. } => match parse_literal_text(t) {
            Ok((Lit::Str { value, .. }, _)) => Ok(Value::String(value, *wide)),
            _ => Err(bad(ValueProblem::NotAString)),
        },
        TypeKind::Enum { values, .. } => {
            let name = t.rsplit('#').next().unwrap_or(t);
            values
                .iter()
                .find(|(n, _)| n.eq_ignore_ascii_case(name))
                .map(|(n, v)| Value::Enum(n.clone(), *v))
                .ok_or_else(|| bad(ValueProblem::NotAnEnumValue))
        }
        TypeKind::Subrange { base, lo, hi } => {
            let raw = parse_scalar(t, *base).ok_or_else(|| bad(ValueProblem::Invalid))?;
            let v = raw as i64;
            if v < *lo || v > *hi {
                return Err(bad(ValueProblem::OutsideSubrange(v)));
            }
            Ok(Value::Scalar(*base, raw))
        }
        _ => {
            let e = image.types.scalar(ty).unwrap_or(ElemType::Lint);
            let raw = parse_scalar(t, e).ok_or_else(|| bad(ValueProblem::Invalid))?;
            Ok(Value::Scalar(e, raw))
        }
    }
}

/// Stores value `v` (of type `ty`, checked by the caller) into the slot
/// `addr` of machine `m` (memory and strings only: the caller keeps the
/// process image in step).
pub(super) fn store_in(m: &mut Machine, addr: u32, v: &Value) {
    let Some(slot) = m.mem.get_mut(addr as usize) else {
        return;
    };
    match v {
        Value::Scalar(_, raw) => *slot = *raw,
        Value::Enum(_, x) => *slot = *x as u64,
        Value::String(s, _) => {
            let id = *slot as usize;
            if let Some(string) = m.strings.get_mut(id) {
                string.set(s);
            }
        }
    }
}

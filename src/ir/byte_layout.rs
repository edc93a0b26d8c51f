//! The bytes of a structure, or of an array of structures or strings, as
//! CODESYS code sees them through a `POINTER TO BYTE`.
//!
//! TwinCAT code copies records by bytes: TcUnit queues its log messages
//! (a structure of strings) in Tc2_Utilities' `FB_MemRingBuffer`, which
//! takes `ADR(msg)` and `SIZEOF(msg)` and moves the bytes one by one.
//! plcrun's memory is typed slots, so a byte view of such an object needs
//! to know which slot each byte belongs to. A [`ByteLayout`] says so: the
//! fields in declaration order, one after another with no padding, each
//! as many bytes as `SIZEOF` gives it (so `SIZEOF(msg)` bytes cover the
//! whole record exactly), an elementary value by its width, a STRING[n] by
//! n+1 bytes, a WSTRING[n] by 2(n+1), a reference or pointer by 8.
//!
//! For example `STRUCT a : INT; s : STRING(3); END_STRUCT` has two runs:
//! bytes 0..2 are slot 0 (an INT), bytes 2..6 slot 1 (the string's
//! buffer).

use crate::elementary::ElemType;
use crate::ir::refs::elem_bytes;
use crate::ir::type_table::{TypeId, TypeKind, TypeTable};

/// Consecutive slots of one kind: `count` values of `width` bytes each,
/// the first at byte `byte` and slot `slot` of one period.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Run {
    /// First byte, from the start of the period.
    pub byte: u32,
    /// First slot, from the start of the period.
    pub slot: u32,
    /// What each slot holds: an elementary value (a reference as an LWORD
    /// of its 8 bytes), or a STRING/WSTRING's buffer id.
    pub elem: ElemType,
    /// Bytes per slot.
    pub width: u32,
    /// Number of slots.
    pub count: u32,
}

/// Where the bytes of an object of one aggregate type are: `repeat`
/// periods (the elements of an array of structures; 1 otherwise), each of
/// `period_bytes` bytes in `period_slots` slots laid out by `runs`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ByteLayout {
    /// The type laid out.
    pub whole: TypeId,
    /// The type of one period (`whole` itself, or the structure or string
    /// an array of them repeats).
    pub period: TypeId,
    /// The runs of one period, by increasing byte.
    pub runs: Vec<Run>,
    /// Bytes of one period.
    pub period_bytes: u32,
    /// Slots of one period.
    pub period_slots: u32,
    /// Number of periods.
    pub repeat: u32,
}

/// The most runs a period may have (a structure of more values than this,
/// counting arrays of elementary values as one, gets no layout).
const MAX_RUNS: usize = 1 << 16;

/// Where byte `k` of an object is: slot `slot` (from the object's start),
/// holding a value of `elem` of `width` bytes, whose byte `at` it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BytePlace {
    /// Slot, from the object's first.
    pub slot: u32,
    /// What the slot holds.
    pub elem: ElemType,
    /// Bytes of the slot's value.
    pub width: u32,
    /// Byte of the value (0: the lowest).
    pub at: u32,
}

impl ByteLayout {
    /// The layout of type `ty`, or `None` when it has none: a type that
    /// is neither a structure nor an array of structures or strings (those
    /// have simpler views), or that holds something without bytes of its
    /// own (an FB instance, a step, an interface) or a type `opaque`
    /// refuses (the checker's unions, whose slots are not their members).
    pub fn of(types: &TypeTable, ty: TypeId, opaque: &dyn Fn(TypeId) -> bool) -> Option<Self> {
        let (period, repeat) = match &types.get(ty).kind {
            TypeKind::Struct { .. } => (ty, 1),
            TypeKind::Array { dims, elem } => {
                let inner = types.innermost(*elem);
                if !matches!(
                    types.get(inner).kind,
                    TypeKind::Struct { .. } | TypeKind::Str { .. }
                ) {
                    return None;
                }
                let n: u64 = dims.iter().map(|d| d.len()).product();
                let per = types.size(*elem) as u64;
                // An array of arrays: one period is the innermost element.
                let inner_n = n * per / types.size(inner).max(1) as u64;
                (inner, u32::try_from(inner_n).ok()?)
            }
            _ => return None,
        };
        let mut runs = Vec::new();
        let period_bytes = append(types, period, 0, 0, opaque, &mut runs)?;
        (repeat > 0).then_some(())?;
        Some(ByteLayout {
            whole: ty,
            period,
            runs,
            period_bytes,
            period_slots: types.size(period),
            repeat,
        })
    }

    /// Bytes of the whole object.
    pub fn bytes(&self) -> u32 {
        self.period_bytes.saturating_mul(self.repeat)
    }

    /// Where byte `k` of the object is (`None` past its end).
    pub fn place(&self, k: u32) -> Option<BytePlace> {
        if self.period_bytes == 0 {
            return None;
        }
        let (p, b) = (k / self.period_bytes, k % self.period_bytes);
        if p >= self.repeat {
            return None;
        }
        let i = self.runs.partition_point(|r| r.byte <= b).checked_sub(1)?;
        let run = self.runs[i];
        let (n, at) = ((b - run.byte) / run.width, (b - run.byte) % run.width);
        (n < run.count).then_some(BytePlace {
            slot: p * self.period_slots + run.slot + n,
            elem: run.elem,
            width: run.width,
            at,
        })
    }

    /// The byte at which slot `s` starts, if a value starts there.
    pub fn byte_of_slot(&self, s: u32) -> Option<u32> {
        let (p, q) = (s / self.period_slots.max(1), s % self.period_slots.max(1));
        if p > self.repeat || (p == self.repeat && q != 0) {
            return None;
        }
        if q == 0 {
            return Some(p * self.period_bytes);
        }
        let i = self.runs.partition_point(|r| r.slot <= q).checked_sub(1)?;
        let run = self.runs[i];
        (q - run.slot < run.count)
            .then(|| p * self.period_bytes + run.byte + (q - run.slot) * run.width)
    }

    /// The slot that starts at byte `b`, if a value starts there.
    pub fn slot_of_byte(&self, b: u32) -> Option<u32> {
        if b == self.bytes() {
            return Some(self.repeat * self.period_slots);
        }
        let at = self.place(b)?;
        (at.at == 0).then_some(at.slot)
    }
}

/// Appends the runs of a `ty` starting at `byte` and `slot` of a period;
/// returns its bytes.
fn append(
    types: &TypeTable,
    ty: TypeId,
    byte: u32,
    slot: u32,
    opaque: &dyn Fn(TypeId) -> bool,
    runs: &mut Vec<Run>,
) -> Option<u32> {
    if opaque(ty) || runs.len() >= MAX_RUNS {
        return None;
    }
    let mut push = |elem: ElemType, width: u32, count: u32| {
        let run = Run {
            byte,
            slot,
            elem,
            width,
            count,
        };
        runs.push(run);
        width.checked_mul(count)
    };
    match &types.get(ty).kind {
        TypeKind::Elem(ElemType::String | ElemType::WString) => None,
        TypeKind::Elem(e) => push(*e, elem_bytes(*e), 1),
        TypeKind::Enum { base, .. } | TypeKind::Subrange { base, .. } => {
            push(*base, elem_bytes(*base), 1)
        }
        TypeKind::Str { wide, max } => {
            let (e, unit) = match wide {
                true => (ElemType::WString, 2),
                false => (ElemType::String, 1),
            };
            push(e, max.checked_add(1)?.checked_mul(unit)?, 1)
        }
        TypeKind::Ref { .. } => push(ElemType::Lword, 8, 1),
        TypeKind::Array { dims, elem } => {
            let n = u32::try_from(dims.iter().map(|d| d.len()).product::<u64>()).ok()?;
            let stride = types.size(*elem);
            let first = runs.len();
            let one = append(types, *elem, byte, slot, opaque, runs)?;
            // An array of one-slot values is one run of them.
            if runs.len() == first + 1 && stride == 1 && runs[first].count == 1 {
                runs[first].count = n;
                return one.checked_mul(n);
            }
            let mut total = one;
            for i in 1..n {
                let b = byte.checked_add(one.checked_mul(i)?)?;
                let s = slot.checked_add(stride.checked_mul(i)?)?;
                total = total.checked_add(append(types, *elem, b, s, opaque, runs)?)?;
            }
            Some(total)
        }
        TypeKind::Struct { fields } => {
            let mut total = 0u32;
            for f in fields {
                let b = byte.checked_add(total)?;
                total = total.checked_add(append(
                    types,
                    f.ty,
                    b,
                    slot.checked_add(f.offset)?,
                    opaque,
                    runs,
                )?)?;
            }
            Some(total)
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::type_table::{Dim, Member, TypeDef};

    fn structure(types: &mut TypeTable, fields: &[(&str, TypeId)]) -> TypeId {
        let mut members = Vec::new();
        let mut offset = 0;
        for (name, ty) in fields {
            members.push(Member::field(name, *ty, offset));
            offset += types.size(*ty);
        }
        types.intern(TypeDef {
            name: "ST".into(),
            kind: TypeKind::Struct { fields: members },
            size: offset,
        })
    }

    fn array(types: &mut TypeTable, elem: TypeId, n: i64) -> TypeId {
        let size = types.size(elem) * n as u32;
        types.intern(TypeDef {
            name: format!("ARRAY OF {}", elem.0),
            kind: TypeKind::Array {
                dims: vec![Dim { lo: 0, hi: n - 1 }],
                elem,
            },
            size,
        })
    }

    fn string(types: &mut TypeTable, max: u32) -> TypeId {
        types.intern(TypeDef {
            name: format!("STRING({max})"),
            kind: TypeKind::Str { wide: false, max },
            size: 1,
        })
    }

    #[test]
    fn fields_follow_one_another_without_padding() {
        let mut types = TypeTable::new();
        let s3 = string(&mut types, 3);
        let bytes = array(&mut types, TypeTable::elem(ElemType::Byte), 3);
        let st = structure(
            &mut types,
            &[
                ("a", TypeTable::elem(ElemType::Int)),
                ("s", s3),
                ("b", bytes),
                ("r", TypeTable::elem(ElemType::Real)),
            ],
        );
        let l = ByteLayout::of(&types, st, &|_| false).unwrap();
        // INT 2 + STRING(3) 4 + 3 BYTEs + REAL 4
        assert_eq!(l.bytes(), 13);
        let at = |k| l.place(k).map(|p| (p.slot, p.at));
        assert_eq!(at(1), Some((0, 1)));
        assert_eq!(at(2), Some((1, 0)));
        assert_eq!(at(5), Some((1, 3)));
        assert_eq!(at(7), Some((3, 0)));
        assert_eq!(at(9), Some((5, 0)));
        assert_eq!(at(12), Some((5, 3)));
        assert_eq!(at(13), None);
        assert_eq!(l.byte_of_slot(3), Some(7));
        assert_eq!(l.slot_of_byte(9), Some(5));
        assert_eq!(l.slot_of_byte(10), None);
    }

    #[test]
    fn arrays_of_structures_repeat_the_element() {
        let mut types = TypeTable::new();
        let s1 = string(&mut types, 1);
        let st = structure(
            &mut types,
            &[("s", s1), ("w", TypeTable::elem(ElemType::Word))],
        );
        let arr = array(&mut types, st, 4);
        let l = ByteLayout::of(&types, arr, &|_| false).unwrap();
        assert_eq!((l.bytes(), l.repeat, l.runs.len()), (16, 4, 2));
        assert_eq!(
            l.place(6).map(|p| (p.slot, p.elem)),
            Some((3, ElemType::Word))
        );
        assert_eq!(l.byte_of_slot(4), Some(8));
        assert_eq!(l.slot_of_byte(12), Some(6));
        assert_eq!(l.slot_of_byte(16), Some(8));
    }

    #[test]
    fn elementary_types_and_opaque_parts_have_no_layout() {
        let mut types = TypeTable::new();
        let int = TypeTable::elem(ElemType::Int);
        assert!(ByteLayout::of(&types, int, &|_| false).is_none());
        let st = structure(&mut types, &[("i", int)]);
        assert!(ByteLayout::of(&types, st, &|t| t == st).is_none());
    }
}

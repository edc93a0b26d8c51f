//! Incomplete addresses (`AT %I*`, `%QW*`...) that no `VAR_CONFIG` line
//! completes get an address of their own in the process image, as
//! TwinCAT's and CODESYS's I/O mapping would give them one: after the
//! highest address the program uses in that area (in that size's table
//! under `openplc`), BOOLs packed eight to a byte, other values aligned
//! to their size as the addressing convention numbers them. The order is
//! the order of the instances and of the declarations, so the same program
//! always gets the same addresses. `plcrun check --map` lists them.

use super::Linker;
use crate::address::{Addressing, Area, IoAddress, Width, parse};
use crate::elementary::ElemType;
use crate::ir::image::RootVar;
use crate::ir::type_table::{MemberKind, TypeId};
use crate::source::Span;
use std::collections::HashMap;

/// An incomplete address that can get no address of its own.
const NOT_PLACEABLE: &str = "E710";
/// The same in a CODESYS V3 / TwinCAT 3 file: the variable stays memory.
const UNLINKED: &str = "W710";

/// A variable declared with an incomplete address and not completed.
#[derive(Debug, Clone)]
pub(super) struct Unplaced {
    /// Its instance path (`MAIN.fbValve.bOpen`, `MAIN.aIn[3]`).
    pub(super) name: String,
    /// Its type (an array's element type for an element).
    pub(super) ty: TypeId,
    /// Its role.
    pub(super) kind: MemberKind,
    /// Its absolute slot.
    pub(super) slot: u32,
    /// The incomplete address as declared (`%I*`, `%QW*`).
    pub(super) declared: String,
    /// Where the address is written.
    pub(super) span: Span,
}

/// The area and, if written, the size of an incomplete address.
fn area_and_size(declared: &str) -> Option<(Area, Option<Width>)> {
    let mut chars = declared.strip_prefix('%')?.chars();
    let area = match chars.next()?.to_ascii_uppercase() {
        'I' => Area::Input,
        'Q' => Area::Output,
        'M' => Area::Memory,
        _ => return None,
    };
    let size = match chars.next()?.to_ascii_uppercase() {
        '*' => None,
        'X' => Some(Width::Bit),
        'B' => Some(Width::Byte),
        'W' => Some(Width::Word),
        'D' => Some(Width::Dword),
        'L' => Some(Width::Lword),
        _ => return None,
    };
    Some((area, size))
}

/// The size of address an elementary value of `e` takes.
fn width_of(e: ElemType) -> Option<Width> {
    Some(match e {
        ElemType::Bool => Width::Bit,
        _ => match e.bits() {
            8 => Width::Byte,
            16 => Width::Word,
            32 => Width::Dword,
            64 => Width::Lword,
            _ => return None,
        },
    })
}

/// Where the next addresses of one table go.
#[derive(Default, Clone, Copy)]
struct Cursor {
    /// The first byte no address reaches yet.
    next: usize,
    /// A byte being filled with BOOLs, and its next free bit.
    bits: Option<(usize, u8)>,
}

impl Linker<'_> {
    /// Gives each of `unplaced` an address after those of `located`;
    /// E710 for a variable no address can hold (a STRING, a structure).
    pub(super) fn place_automatically(
        &mut self,
        unplaced: Vec<Unplaced>,
        located: &[RootVar],
        addressing: Addressing,
    ) -> Vec<RootVar> {
        let mut cursors: HashMap<usize, Cursor> = HashMap::new();
        for at in located.iter().filter_map(|r| r.location.as_deref()) {
            let Some(spot) = parse(at).ok().and_then(|a| addressing.spot(&a).ok()) else {
                continue;
            };
            let c = cursors.entry(spot.table.index()).or_default();
            c.next = c.next.max(spot.end());
        }
        let mut placed = Vec::new();
        for u in unplaced {
            let elem = self.types.scalar(u.ty);
            let Some((area, declared)) = area_and_size(&u.declared) else {
                continue;
            };
            let width = match (elem.and_then(width_of), declared) {
                (Some(w), None) => w,
                (Some(w), Some(d)) if w == d => w,
                _ => {
                    self.unplaceable(&u);
                    continue;
                }
            };
            let table = addressing.table(area, width);
            let c = cursors.entry(table.index()).or_default();
            let address = next_address(c, area, width, addressing);
            placed.push(RootVar {
                name: u.name,
                ty: u.ty,
                addr: u.slot,
                kind: u.kind,
                location: Some(address.to_string()),
                constant: false,
            });
        }
        placed
    }
}

impl Linker<'_> {
    /// `u` can get no address (a STRING, or a type that does not fit the
    /// size written): E710; in a TwinCAT / CODESYS V3 file, which compile
    /// it as memory the program alone writes when no I/O is linked, W710.
    fn unplaceable(&mut self, u: &Unplaced) {
        let ty = self.types.name(u.ty).to_string();
        let head = format!("`{}` (AT {})", u.name, u.declared);
        if self.model.checked_files.contains(&u.span.file) {
            self.diags.warning(
                UNLINKED,
                u.span,
                format!("{head}: a {ty} gets no address in the process image; it stays an ordinary variable, which no I/O writes"),
            );
        } else {
            self.diags.error(
                NOT_PLACEABLE,
                u.span,
                format!("{head}: no VAR_CONFIG gives it an address, and a {ty} cannot get one automatically"),
            );
        }
    }
}

/// The next free address of `width` in the table `c` follows, moving it on.
fn next_address(c: &mut Cursor, area: Area, width: Width, addressing: Addressing) -> IoAddress {
    if width == Width::Bit {
        let (byte, bit) = match c.bits {
            Some((byte, bit)) if bit < 8 => (byte, bit),
            _ => {
                let byte = c.next;
                c.next += 1;
                (byte, 0)
            }
        };
        c.bits = Some((byte, bit + 1));
        return IoAddress {
            area,
            width,
            index: byte,
            bit,
        };
    }
    // Under `iec` and `openplc` the number counts addresses of this size
    // (`%IW3` is bytes 6-7); under `byte` it is the first byte.
    let scale = match addressing {
        Addressing::Byte => 1,
        Addressing::Iec | Addressing::OpenPlc => width.bytes(),
    };
    let index = c.next.div_ceil(scale);
    c.next = index * scale + width.bytes();
    IoAddress {
        area,
        width,
        index,
        bit: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bools_pack_into_bytes_and_words_align_to_their_size() {
        let mut c = Cursor {
            next: 3,
            bits: None,
        };
        let mut take = |w| next_address(&mut c, Area::Input, w, Addressing::Iec).to_string();
        assert_eq!(take(Width::Bit), "%IX3.0");
        assert_eq!(take(Width::Bit), "%IX3.1");
        // Byte 4 is the next free one: the word goes to bytes 4-5, %IW2.
        assert_eq!(take(Width::Word), "%IW2");
        assert_eq!(take(Width::Bit), "%IX3.2");
        assert_eq!(take(Width::Dword), "%ID2");
        let mut b = Cursor {
            next: 3,
            bits: None,
        };
        assert_eq!(
            next_address(&mut b, Area::Output, Width::Word, Addressing::Byte).to_string(),
            "%QW3"
        );
        assert_eq!(
            area_and_size("%QW*"),
            Some((Area::Output, Some(Width::Word)))
        );
        assert_eq!(area_and_size("%I*"), Some((Area::Input, None)));
    }
}

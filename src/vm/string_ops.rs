//! The string instructions, run out of line: they call into the string
//! table, the formatter and the parser, and keeping that code out of the
//! dispatch loop leaves its registers to the instructions that run often.

use super::json_of_symbol::json_of_symbol;
use super::symbol_from_json::symbol_from_json;
use super::{FaultKind, Machine, strings};
use crate::ir::image::Image;
use crate::ir::op::{Op, Slot, StrFn};

/// Runs one string instruction (`CmpStr`, `StrMov`, `StrConst`, `StrCall`,
/// `ToStr`, `FromStr`; anything else does nothing) on the frame at `fp`.
///
/// # Safety
/// Every frame operand of `op` (and the four argument slots of `StrCall`)
/// must lie inside the frame `fp` points to, as the link-time verifier
/// guarantees for the instructions of a block.
#[inline(never)]
pub(super) unsafe fn run(
    m: &mut Machine,
    img: &Image,
    fp: *mut u64,
    op: &Op,
) -> Result<(), FaultKind> {
    // SAFETY (both): the caller guarantees the slot lies in the frame.
    let r = |s: Slot| unsafe { *fp.add(s.index()) };
    let w = |s: Slot, v: u64| unsafe { *fp.add(s.index()) = v };
    match *op {
        Op::CmpStr { d, a, b, cmp } => {
            let x = &m.strings[r(a) as usize];
            let y = &m.strings[r(b) as usize];
            w(d, cmp.test(x.as_str().cmp(y.as_str())) as u64);
        }
        Op::StrMov { d, s } => {
            let (di, si) = (r(d) as usize, r(s) as usize);
            if di != si {
                let text = std::mem::take(&mut m.strings[si].text);
                m.strings[di].set(&text);
                m.strings[si].text = text;
            }
        }
        Op::StrConst { d, k } => {
            let di = r(d) as usize;
            m.strings[di].set(&img.str_consts[k.index()]);
        }
        Op::StrCall {
            d,
            a,
            f: StrFn::JsonOfSymbol,
        } => {
            let name = m.strings.get(r(a) as usize).map(|s| s.text.clone());
            let text = name.and_then(|name| {
                json_of_symbol(img, &m.refs, &m.mem, &m.strings, &name, r(a.offset(1)))
            });
            let s = m
                .strings
                .get_mut(r(d) as usize)
                .ok_or(FaultKind::BadAddress)?;
            s.set(text.as_deref().unwrap_or(""));
        }
        Op::StrCall {
            d,
            a,
            f: StrFn::SymbolFromJson,
        } => {
            let text = |i: u32| {
                m.strings
                    .get(r(a.offset(i)) as usize)
                    .map(|s| s.text.clone())
            };
            let ok = match (text(0), text(1)) {
                (Some(json), Some(name)) => symbol_from_json(
                    img,
                    &m.refs,
                    &mut m.mem,
                    &mut m.strings,
                    &json,
                    &name,
                    r(a.offset(2)),
                ),
                _ => false,
            };
            w(d, ok as u64);
        }
        Op::StrCall { d, a, f } => {
            let args = [r(a), r(a.offset(1)), r(a.offset(2)), r(a.offset(3))];
            if let Some(v) = strings::call(&mut m.strings, f, r(d), &args)? {
                w(d, v);
            }
        }
        Op::ToStr { d, a, ty } => {
            let text = crate::value::format::format_value(img.scalar_types[ty.index()], r(a));
            m.strings[r(d) as usize].set(&text);
        }
        Op::FromStr { d, a, ty } => {
            let text = m.strings[r(a) as usize].as_str();
            match crate::value::text::parse_scalar(text, img.scalar_types[ty.index()]) {
                Some(v) => w(d, v),
                None => return Err(FaultKind::ConversionOverflow),
            }
        }
        _ => {}
    }
    Ok(())
}

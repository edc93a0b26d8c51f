//! The dispatch loop.

use super::loop_kernels::{FrameArray, LoopExit, scan_flags, store_stride};
use super::{Fault, FaultKind, Interrupt, Machine, string_ops};
use crate::ir::image::Image;
use crate::ir::op::{Cmp, CodeIdx, Op, ShiftKind, Slot, wrap_s, wrap_u};
use crate::stdlib;
use crate::value::convert;
use std::sync::Arc;

#[inline(always)]
fn f32_of(x: u64) -> f32 {
    f32::from_bits(x as u32)
}

#[inline(always)]
fn of_f32(x: f32) -> u64 {
    x.to_bits() as u64
}

#[inline(always)]
fn f64_of(x: u64) -> f64 {
    f64::from_bits(x)
}

#[inline(always)]
fn of_f64(x: f64) -> u64 {
    x.to_bits()
}

#[inline(always)]
fn cmp_s(a: u64, b: u64, c: Cmp) -> u64 {
    c.test((a as i64).cmp(&(b as i64))) as u64
}

#[inline(always)]
fn cmp_f<T: PartialOrd>(a: T, b: T, c: Cmp) -> u64 {
    (match c {
        Cmp::Eq => a == b,
        Cmp::Ne => a != b,
        Cmp::Lt => a < b,
        Cmp::Le => a <= b,
        Cmp::Gt => a > b,
        Cmp::Ge => a >= b,
    }) as u64
}

fn shift(x: u64, n: u64, kind: ShiftKind, bits: u8) -> u64 {
    let bits = bits as u64;
    let mask = if bits == 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    };
    let x = x & mask;
    match kind {
        ShiftKind::Shl => {
            if n >= bits {
                0
            } else {
                (x << n) & mask
            }
        }
        ShiftKind::Shr => {
            if n >= bits {
                0
            } else {
                x >> n
            }
        }
        ShiftKind::Rol => {
            let n = n % bits;
            if n == 0 {
                x
            } else {
                ((x << n) | (x >> (bits - n))) & mask
            }
        }
        ShiftKind::Ror => {
            let n = n % bits;
            if n == 0 {
                x
            } else {
                ((x >> n) | (x << (bits - n))) & mask
            }
        }
    }
}

/// The slot of the `Operand` word at `ip` (verified to be there).
#[inline(always)]
fn operand_word(ip: *const Op) -> Slot {
    // SAFETY: the verifier guarantees an Operand word after a two-word
    // instruction, inside the block.
    match unsafe { *ip } {
        Op::Operand { s } => s,
        _ => Slot::new(0),
    }
}

/// Advances a FOR variable: the new (wrapped) value and whether the loop
/// goes on. The comparison uses the exact sum, so a sum past the type's
/// range ends the loop instead of wrapping around.
#[inline(always)]
pub(super) fn for_next(i: u64, step: i16, lim: i64, shift: u8) -> (u64, bool) {
    let sum = (i as i64).checked_add(step as i64);
    let v = wrap_s(i.wrapping_add(step as i64 as u64), shift);
    let go = match sum {
        Some(s) if step > 0 => s <= lim,
        Some(s) => s >= lim,
        None => false,
    };
    (v, go)
}

pub(crate) fn int_pow(base: i64, exp: i64) -> Option<u64> {
    if exp < 0 {
        return None;
    }
    let mut result: i64 = 1;
    let mut b = base;
    let mut e = exp as u64;
    while e > 0 {
        if e & 1 == 1 {
            result = result.wrapping_mul(b);
        }
        b = b.wrapping_mul(b);
        e >>= 1;
    }
    Some(result as u64)
}

/// Executes code block `code` at frame base `base` until it returns.
///
/// Frame operands are accessed without bounds checks: [`crate::ir::verify`]
/// proved at link time that every frame operand of every block lies inside
/// the block's frame and that every frame a block runs on lies inside memory
/// (`base + frame_size <= mem.len()`, re-checked below for frames reached
/// through run-time pointers). All memory goes through one raw pointer taken
/// with `Vec::as_mut_ptr`, which stays valid across nested calls because no
/// reference to the buffer is created while a block runs; addresses computed
/// at run time (pointers, absolute addresses) are checked against the length.
///
/// # Soundness
/// `img` must have passed [`crate::ir::verify::verify`] (callers hold a
/// `VerifiedImage`); `m` may hold any memory, since every frame is checked
/// against it on entry.
///
/// `DEBUG` chooses the variant: `false` is the plain executor, with no
/// trace of debugging in its code; `true` keeps the debugger's call stack
/// and gives it every statement start (see [`super::debug`]), and runs only
/// on a machine a debugger is attached to ([`Machine::run`] chooses).
///
/// `NATIVE` is `true` when the machine holds native code (`--engine
/// native`, docs/adr/0009-native-tier.md): a block compiled to machine
/// code runs there, every other block here. The interpreter-only variant
/// (`false`) has no trace of the native tier in its code.
pub(super) fn call<const DEBUG: bool, const NATIVE: bool>(
    m: &mut Machine,
    img: &Image,
    code: CodeIdx,
    base: usize,
) -> Result<(), Fault> {
    #[cfg(feature = "native")]
    if NATIVE
        && !DEBUG
        && let Some(done) = super::native::enter(m, img, code, base)
    {
        return done;
    }
    if !img.codes[code.index()].handlers.is_empty() {
        return guarded::<DEBUG, NATIVE>(m, img, code, base);
    }
    if DEBUG {
        m.debug_enter(code, base);
        let done = run::<true, NATIVE>(m, img, code, base, 0);
        m.debug_leave();
        return done;
    }
    run::<false, NATIVE>(m, img, code, base, 0)
}

/// [`call`] of a block with `__TRY` regions (`ir::handler`): a fault in a
/// region, at one of the block's own instructions or in a call made
/// there, that user code may catch ([`FaultKind::exception_code`]) writes
/// its code into the region's `__CATCH` variable and runs the block on
/// from the `__CATCH` statements, in the same frame. Out of line: the
/// blocks without a region (nearly all) pay one test per call for it.
#[cold]
#[inline(never)]
fn guarded<const DEBUG: bool, const NATIVE: bool>(
    m: &mut Machine,
    img: &Image,
    code: CodeIdx,
    base: usize,
) -> Result<(), Fault> {
    let handlers = &img.codes[code.index()].handlers;
    // The calls a fault unwinds through are noted from here on; those of
    // a caught fault are forgotten.
    let noted = m.callers().len();
    if DEBUG {
        m.debug_enter(code, base);
    }
    let mut resume = 0;
    let done = loop {
        let Err(fault) = run::<DEBUG, NATIVE>(m, img, code, base, resume) else {
            break Ok(());
        };
        // Where the fault left this block: the call it unwound through
        // (noted last), or its own instruction.
        let at = match m.callers().get(noted..).and_then(<[_]>::last) {
            Some(site) => site.pc,
            None => fault.pc,
        };
        let caught = fault
            .kind
            .exception_code()
            .zip(crate::ir::handler::guarding(handlers, at));
        let Some((value, handler)) = caught else {
            break Err(fault);
        };
        // The verifier proved the slot inside the frame; a frame outside
        // memory (the fault `run` gives before running anything) is no
        // place to write it.
        let Some(slot) = m.mem.get_mut(base + handler.exception.index()) else {
            break Err(fault);
        };
        *slot = u64::from(value);
        m.forget_callers(noted);
        resume = handler.catch as usize;
    };
    if DEBUG {
        m.debug_leave();
    }
    done
}

/// The dispatch loop of [`call`] (inlined into it: the plain variant is
/// this code).
#[inline(always)]
fn run<const DEBUG: bool, const NATIVE: bool>(
    m: &mut Machine,
    img: &Image,
    code: CodeIdx,
    base: usize,
    resume: usize,
) -> Result<(), Fault> {
    let block = &img.codes[code.index()];
    let len = m.mem.len();
    // `base` may come from a pointer slot: compared without overflow.
    if base > len || block.frame_size as usize > len - base {
        return Err(Fault {
            kind: FaultKind::BadAddress,
            code,
            pc: 0,
        });
    }
    // The interrupt word, polled through a pointer kept in a register:
    // the `Arc` in `m` keeps it alive, and it is only ever shared.
    let irq: *const Interrupt = Arc::as_ptr(m.interrupt());
    // Every call enters here: a check per call bounds call chains that
    // take time without looping (each function calling two others...).
    // SAFETY: see `irq`.
    if let Some(kind) = unsafe { (*irq).stop_request() } {
        return Err(Fault { kind, code, pc: 0 });
    }
    let mut mem: *mut u64 = m.mem.as_mut_ptr();
    // SAFETY: base + frame_size <= len was checked just above.
    let mut fp: *mut u64 = unsafe { mem.add(base) };
    macro_rules! r {
        ($s:expr) => {
            // SAFETY: frame operands are < frame_size (verified at link time).
            unsafe { *fp.add($s.index()) }
        };
    }
    macro_rules! w {
        ($s:expr, $v:expr) => {{
            let v = $v;
            // SAFETY: as for `r!`.
            unsafe { *fp.add($s.index()) = v }
        }};
    }
    // The same at a frame offset computed at run time (an element or a
    // MUX input), which the instruction has checked first.
    macro_rules! r_at {
        ($i:expr) => {
            // SAFETY: the offset was checked against a verified descriptor
            // (whose extent lies in the frame), a verified run, or the
            // frame size.
            unsafe { *fp.add($i as usize) }
        };
    }
    macro_rules! w_at {
        ($i:expr, $v:expr) => {{
            let v = $v;
            // SAFETY: as for `r_at!`.
            unsafe { *fp.add($i as usize) = v }
        }};
    }
    // A block resumed at a `__CATCH` (never instruction 0) keeps its
    // temporaries: it is the same call going on.
    if resume == 0 {
        for &(slot, value) in &block.entry_init {
            w!(slot, value);
        }
        for &(slot, k) in &block.entry_strings {
            let id = r!(slot) as usize;
            m.strings[id].set(&img.str_consts[k.index()]);
        }
    }
    let ops = &block.ops[..];
    // The instruction pointer: it points at the running instruction until
    // the end of its arm, which moves it on (a jump sets it and skips
    // that). One pointer, not the instruction and the next one: the loop
    // then keeps a register free for the memory pointer (see
    // docs/performance.md, "The dispatch loop's registers").
    let start: *const Op = ops.as_ptr();
    // SAFETY: a resumption point is a handler's `catch`, which the
    // verifier proved inside the block.
    let mut ip: *const Op = unsafe { start.add(resume) };
    macro_rules! pc {
        () => {
            // SAFETY: ip always points into `ops`.
            unsafe { ip.offset_from(start) as usize }
        };
    }
    macro_rules! fault {
        ($kind:expr) => {
            return Err(Fault {
                kind: $kind,
                code,
                pc: pc!() as u32,
            })
        };
    }
    // A checked absolute address.
    macro_rules! at {
        ($a:expr) => {{
            let a = $a as usize;
            if a >= len {
                fault!(FaultKind::BadAddress);
            }
            a
        }};
    }
    macro_rules! mload {
        ($a:expr) => {{
            let a = at!($a);
            // SAFETY: a < len.
            unsafe { *mem.add(a) }
        }};
    }
    macro_rules! mstore {
        ($a:expr, $v:expr) => {{
            let v = $v;
            let a = at!($a);
            // SAFETY: a < len.
            unsafe { *mem.add(a) = v }
        }};
    }
    // One backward jump (or a long copy): looks at the interrupt word. A
    // watchdog or abort fault names the instruction at `$pc` (by default
    // the one running).
    macro_rules! tick {
        () => {
            tick!(pc!())
        };
        ($pc:expr) => {{
            // SAFETY: see `irq`.
            if let Some(kind) = unsafe { (*irq).stop_request() } {
                return Err(Fault {
                    kind,
                    code,
                    pc: $pc as u32,
                });
            }
        }};
    }
    // Jumps (and skips the move to the next instruction).
    macro_rules! jump {
        ($t:expr) => {{
            // SAFETY: jump targets are inside the block (verified).
            let target = unsafe { start.add($t.index()) };
            if target <= ip {
                tick!();
            }
            ip = target;
            continue;
        }};
    }
    loop {
        if DEBUG {
            // The debugging variant only: the debugger sees the
            // instruction about to run and may stop there (its hook runs
            // at statement starts), read and write memory, or end the run.
            if let Err(kind) = m.debug_at(img, code, pc!()) {
                fault!(kind);
            }
            mem = m.mem.as_mut_ptr();
            // SAFETY: as at entry (same buffer, same length).
            fp = unsafe { mem.add(base) };
        }
        // SAFETY: blocks end with Ret and jump targets are inside the block
        // (verified), so ip never leaves `ops`.
        let op = unsafe { &*ip };
        match *op {
            Op::Nop => {}
            Op::LoadK { d, k } => w!(d, img.consts[k.index()]),
            Op::LoadI { d, imm } => w!(d, imm as i64 as u64),
            Op::Mov { d, s } => w!(d, r!(s)),
            Op::LoadAbs { d, abs } => w!(d, mload!(abs)),
            Op::StoreAbs { abs, s } => mstore!(abs, r!(s)),
            Op::LoadInd { d, p, off } => {
                let a = (r!(p) as usize).wrapping_add(off as usize);
                w!(d, mload!(a));
            }
            Op::StoreInd { p, off, s } => {
                let a = (r!(p) as usize).wrapping_add(off as usize);
                mstore!(a, r!(s));
            }
            Op::AddrOf { d, off } => w!(d, (base + off.index()) as u64),
            Op::AddrAdd { d, p, off } => w!(d, r!(p).wrapping_add(off as u64)),
            Op::LoadElem { d, idx, desc } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let i = (r!(idx) as i64).wrapping_sub(ad.lo) as u64;
                if i >= ad.len {
                    fault!(index_fault(r!(idx), ad));
                }
                w!(d, r_at!(ad.offset as u64 + i * ad.stride as u64));
            }
            Op::LoadElemU { d, idx, bias } => {
                // The index is proved in range; staying inside the frame is
                // still checked, so memory safety never rests on the proof.
                let at = (r!(idx) as i64).wrapping_add(bias as i64) as u64;
                if at >= block.frame_size as u64 {
                    fault!(FaultKind::BadAddress);
                }
                w!(d, r_at!(at));
            }
            Op::StoreElemU { idx, s, bias } => {
                let at = (r!(idx) as i64).wrapping_add(bias as i64) as u64;
                if at >= block.frame_size as u64 {
                    fault!(FaultKind::BadAddress);
                }
                w_at!(at, r!(s));
            }
            Op::StoreElem { idx, s, desc } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let i = (r!(idx) as i64).wrapping_sub(ad.lo) as u64;
                if i >= ad.len {
                    fault!(index_fault(r!(idx), ad));
                }
                w_at!(ad.offset as u64 + i * ad.stride as u64, r!(s));
            }
            Op::ElemAddr { d, idx, desc } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let i = (r!(idx) as i64).wrapping_sub(ad.lo) as u64;
                if i >= ad.len {
                    fault!(index_fault(r!(idx), ad));
                }
                w!(
                    d,
                    r!(d).wrapping_add(ad.offset as u64 + i * ad.stride as u64)
                );
            }
            Op::ElemRef { d, idx, desc } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let i = (r!(idx) as i64).wrapping_sub(ad.lo) as u64;
                if i >= ad.len {
                    fault!(index_fault(r!(idx), ad));
                }
                w!(d, (base + ad.offset as usize) as u64 + i * ad.stride as u64);
            }
            Op::IndexStep { acc, idx, desc } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let i = (r!(idx) as i64).wrapping_sub(ad.lo) as u64;
                if i >= ad.len {
                    fault!(index_fault(r!(idx), ad));
                }
                w!(acc, r!(acc).wrapping_mul(ad.len).wrapping_add(i));
            }
            Op::OpenIndexStep { acc, idx, bounds } => {
                let hi = bounds.offset(1);
                let (i, l, h) = (r!(idx) as i64, r!(bounds) as i64, r!(hi) as i64);
                if i < l || i > h {
                    fault!(FaultKind::IndexOutOfRange {
                        index: i,
                        lo: l,
                        hi: h
                    });
                }
                let len = h.wrapping_sub(l).wrapping_add(1) as u64;
                let k = i.wrapping_sub(l) as u64;
                w!(acc, r!(acc).wrapping_mul(len).wrapping_add(k));
            }

            Op::AddS { d, a, b, shift } => w!(d, wrap_s(r!(a).wrapping_add(r!(b)), shift)),
            Op::AddU { d, a, b, shift } => w!(d, wrap_u(r!(a).wrapping_add(r!(b)), shift)),
            Op::AddSI { d, a, imm, shift } => {
                w!(d, wrap_s(r!(a).wrapping_add(imm as i64 as u64), shift))
            }
            Op::SubS { d, a, b, shift } => w!(d, wrap_s(r!(a).wrapping_sub(r!(b)), shift)),
            Op::SubU { d, a, b, shift } => w!(d, wrap_u(r!(a).wrapping_sub(r!(b)), shift)),
            Op::MulS { d, a, b, shift } => w!(d, wrap_s(r!(a).wrapping_mul(r!(b)), shift)),
            Op::MulU { d, a, b, shift } => w!(d, wrap_u(r!(a).wrapping_mul(r!(b)), shift)),
            Op::DivS { d, a, b, shift } => {
                let y = r!(b) as i64;
                if y == 0 {
                    fault!(FaultKind::DivisionByZero);
                }
                w!(d, wrap_s((r!(a) as i64).wrapping_div(y) as u64, shift));
            }
            Op::DivU { d, a, b, shift } => {
                let y = r!(b);
                if y == 0 {
                    fault!(FaultKind::DivisionByZero);
                }
                w!(d, wrap_u(r!(a) / y, shift));
            }
            Op::ModS { d, a, b, shift } => {
                let y = r!(b) as i64;
                if y == 0 {
                    fault!(FaultKind::DivisionByZero);
                }
                w!(d, wrap_s((r!(a) as i64).wrapping_rem(y) as u64, shift));
            }
            Op::ModU { d, a, b, shift } => {
                let y = r!(b);
                if y == 0 {
                    fault!(FaultKind::DivisionByZero);
                }
                w!(d, wrap_u(r!(a) % y, shift));
            }
            Op::ModSI { d, a, imm, shift } => {
                w!(
                    d,
                    wrap_s((r!(a) as i64).wrapping_rem(imm as i64) as u64, shift)
                )
            }
            Op::NegS { d, a, shift } => w!(d, wrap_s(r!(a).wrapping_neg(), shift)),
            Op::PowS { d, a, b, shift } => match int_pow(r!(a) as i64, r!(b) as i64) {
                Some(v) => w!(d, wrap_s(v, shift)),
                None => fault!(FaultKind::NegativeExponent),
            },
            Op::AbsS { d, a, shift } => w!(d, wrap_s((r!(a) as i64).wrapping_abs() as u64, shift)),

            Op::AddF32 { d, a, b } => w!(d, of_f32(f32_of(r!(a)) + f32_of(r!(b)))),
            Op::SubF32 { d, a, b } => w!(d, of_f32(f32_of(r!(a)) - f32_of(r!(b)))),
            Op::MulF32 { d, a, b } => w!(d, of_f32(f32_of(r!(a)) * f32_of(r!(b)))),
            Op::DivF32 { d, a, b } => w!(d, of_f32(f32_of(r!(a)) / f32_of(r!(b)))),
            Op::NegF32 { d, a } => w!(d, of_f32(-f32_of(r!(a)))),
            Op::PowF32 { d, a, b } => w!(d, of_f32(f32_of(r!(a)).powf(f32_of(r!(b))))),
            Op::MathF32 { d, a, f } => w!(d, of_f32(f.apply_f32(f32_of(r!(a))))),
            Op::AddF64 { d, a, b } => w!(d, of_f64(f64_of(r!(a)) + f64_of(r!(b)))),
            Op::SubF64 { d, a, b } => w!(d, of_f64(f64_of(r!(a)) - f64_of(r!(b)))),
            Op::MulF64 { d, a, b } => w!(d, of_f64(f64_of(r!(a)) * f64_of(r!(b)))),
            Op::DivF64 { d, a, b } => w!(d, of_f64(f64_of(r!(a)) / f64_of(r!(b)))),
            Op::NegF64 { d, a } => w!(d, of_f64(-f64_of(r!(a)))),
            Op::PowF64 { d, a, b } => w!(d, of_f64(f64_of(r!(a)).powf(f64_of(r!(b))))),
            Op::MathF64 { d, a, f } => w!(d, of_f64(f.apply_f64(f64_of(r!(a))))),

            Op::And { d, a, b } => w!(d, r!(a) & r!(b)),
            Op::Or { d, a, b } => w!(d, r!(a) | r!(b)),
            Op::Xor { d, a, b } => w!(d, r!(a) ^ r!(b)),
            Op::NotB { d, a } => w!(d, r!(a) ^ 1),
            Op::NotW { d, a, shift } => w!(d, wrap_u(!r!(a), shift)),
            Op::AndN { d, a, b } => w!(d, r!(a) & (r!(b) ^ 1)),
            Op::OrN { d, a, b } => w!(d, r!(a) | (r!(b) ^ 1)),
            Op::Shift {
                d,
                a,
                b,
                kind,
                bits,
            } => w!(d, shift(r!(a), r!(b), kind, bits)),

            Op::CmpS { d, a, b, cmp } => w!(d, cmp_s(r!(a), r!(b), cmp)),
            Op::CmpU { d, a, b, cmp } => w!(d, cmp.test(r!(a).cmp(&r!(b))) as u64),
            Op::CmpF32 { d, a, b, cmp } => w!(d, cmp_f(f32_of(r!(a)), f32_of(r!(b)), cmp)),
            Op::CmpF64 { d, a, b, cmp } => w!(d, cmp_f(f64_of(r!(a)), f64_of(r!(b)), cmp)),
            Op::CmpSI { d, a, imm, cmp } => w!(d, cmp_s(r!(a), imm as i64 as u64, cmp)),

            Op::Convert { d, a, conv } => match convert::convert(conv, r!(a)) {
                Ok(v) => w!(d, v),
                Err(e) => fault!(FaultKind::from(e)),
            },
            Op::MulAddF32 { d, a, b } => {
                // SAFETY: the verifier checked that the operand word follows.
                let c = operand_word(unsafe { ip.add(1) });
                // The operand word is skipped: the arm's end moves past it.
                ip = unsafe { ip.add(1) };
                w!(d, of_f32(f32_of(r!(a)) * f32_of(r!(b)) + f32_of(r!(c))));
            }
            Op::MulAddF64 { d, a, b } => {
                // SAFETY: as above.
                let c = operand_word(unsafe { ip.add(1) });
                ip = unsafe { ip.add(1) };
                w!(d, of_f64(f64_of(r!(a)) * f64_of(r!(b)) + f64_of(r!(c))));
            }
            Op::Operand { .. } => {}
            Op::CMov { d, c, s } => {
                if r!(c) != 0 {
                    w!(d, r!(s))
                }
            }
            Op::MinMaxS { d, a, b, max } => {
                let (x, y) = (r!(a) as i64, r!(b) as i64);
                w!(d, (if (x < y) != max { x } else { y }) as u64);
            }
            Op::MinMaxU { d, a, b, max } => {
                let (x, y) = (r!(a), r!(b));
                w!(d, if (x < y) != max { x } else { y });
            }
            Op::MinMaxF32 { d, a, b, max } => {
                let (x, y) = (f32_of(r!(a)), f32_of(r!(b)));
                w!(d, of_f32(if max { x.max(y) } else { x.min(y) }));
            }
            Op::MinMaxF64 { d, a, b, max } => {
                let (x, y) = (f64_of(r!(a)), f64_of(r!(b)));
                w!(d, of_f64(if max { x.max(y) } else { x.min(y) }));
            }
            Op::Mux { d, k, first, n } => {
                let sel = r!(k) as i64;
                if sel < 0 || sel >= n as i64 {
                    fault!(FaultKind::MuxOutOfRange {
                        k: sel,
                        n: n as u32
                    });
                }
                w!(d, r_at!(first.get() as u64 + sel as u64));
            }
            Op::MulTimeF64 { d, a, b } => {
                let v = (r!(a) as i64) as f64 * f64_of(r!(b));
                match convert::f64_to_i64(v.round()) {
                    Some(x) => w!(d, x as u64),
                    None => fault!(FaultKind::ConversionOverflow),
                }
            }
            Op::DivTimeF64 { d, a, b } => {
                let y = f64_of(r!(b));
                if y == 0.0 {
                    fault!(FaultKind::DivisionByZero);
                }
                let v = (r!(a) as i64) as f64 / y;
                match convert::f64_to_i64(v.round()) {
                    Some(x) => w!(d, x as u64),
                    None => fault!(FaultKind::ConversionOverflow),
                }
            }

            Op::CmpStr { .. }
            | Op::StrMov { .. }
            | Op::StrConst { .. }
            | Op::StrCall { .. }
            | Op::ToStr { .. }
            | Op::FromStr { .. } => {
                // SAFETY: the instruction's frame operands lie inside the
                // frame at fp (verified at link time).
                if let Err(kind) = unsafe { string_ops::run(m, img, fp, op) } {
                    fault!(kind);
                }
            }

            Op::Jmp { t } => jump!(t),
            Op::Jz { c, t } => {
                if r!(c) == 0 {
                    jump!(t)
                }
            }
            Op::Jnz { c, t } => {
                if r!(c) != 0 {
                    jump!(t)
                }
            }
            Op::JnCmpSI { a, imm, cmp, t } => {
                if !cmp.test((r!(a) as i64).cmp(&(imm as i64))) {
                    jump!(t)
                }
            }
            Op::JnCmpS { a, b, cmp, t } => {
                if !cmp.test((r!(a) as i64).cmp(&(r!(b) as i64))) {
                    jump!(t)
                }
            }

            Op::FillElems {
                i,
                v,
                lim,
                desc,
                shift,
            } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let (start, last) = (r!(i) as i64, lim as i64);
                let after = wrap_s((last + 1) as u64, shift);
                let (a, b) = (start.wrapping_sub(ad.lo), last.wrapping_sub(ad.lo));
                if start <= last && after as i64 == last + 1 && a >= 0 && (b as u64) < ad.len {
                    let value = r!(v);
                    let first = ad.offset as usize + a as usize;
                    let count = (b - a) as usize + 1;
                    // SAFETY: offset + len <= frame_size (verified) and
                    // a <= b < len, so the range lies inside this frame.
                    unsafe { std::slice::from_raw_parts_mut(fp.add(first), count) }.fill(value);
                    w!(i, after);
                    // The loop this replaces looked at the word each turn.
                    tick!();
                }
            }
            Op::JzElem { idx, desc, t } | Op::JnzElem { idx, desc, t } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let i = (r!(idx) as i64).wrapping_sub(ad.lo) as u64;
                if i >= ad.len {
                    fault!(index_fault(r!(idx), ad));
                }
                let set = r_at!(ad.offset as u64 + i * ad.stride as u64) != 0;
                if set == matches!(*op, Op::JnzElem { .. }) {
                    jump!(t)
                }
            }
            Op::AddBr {
                d,
                b,
                imm,
                t,
                cmp,
                shift,
            } => {
                let v = wrap_s(r!(d).wrapping_add(r!(b)), shift);
                w!(d, v);
                if cmp.test((v as i64).cmp(&(imm as i64))) {
                    jump!(t)
                }
            }
            Op::JnCmpF32 { a, b, cmp, t } => {
                if cmp_f(f32_of(r!(a)), f32_of(r!(b)), cmp) == 0 {
                    jump!(t)
                }
            }
            Op::JnCmpF64 { a, b, cmp, t } => {
                if cmp_f(f64_of(r!(a)), f64_of(r!(b)), cmp) == 0 {
                    jump!(t)
                }
            }
            Op::ForNext {
                i,
                lim,
                t,
                step,
                shift,
            } => {
                let (v, go) = for_next(r!(i), step, lim as i64, shift);
                w!(i, v);
                if go {
                    jump!(t)
                }
            }
            Op::ForNextS {
                i,
                lim,
                t,
                step,
                shift,
            } => {
                let (v, go) = for_next(r!(i), step, r!(lim) as i64, shift);
                w!(i, v);
                if go {
                    jump!(t)
                }
            }
            Op::StoreStep { idx, s, desc } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                // SAFETY: the verifier checked that the AddBr stepping `idx`
                // back to this instruction follows it.
                let (b, imm, cmp, shift) = match unsafe { *ip.add(1) } {
                    Op::AddBr {
                        b, imm, cmp, shift, ..
                    } => (b, imm, cmp, shift),
                    // Excluded by the verifier.
                    _ => fault!(FaultKind::BadAddress),
                };
                let at = FrameArray { fp, desc: ad };
                if at.covers(idx.index()) || at.covers(s.index()) || at.covers(b.index()) {
                    // An operand is an element: every turn reads it again.
                    let mut j = r!(idx);
                    loop {
                        let i = (j as i64).wrapping_sub(ad.lo) as u64;
                        if i >= ad.len {
                            fault!(index_fault(j, ad));
                        }
                        let at = ad.offset as u64 + i * ad.stride as u64;
                        w_at!(at, r!(s));
                        if at == idx.get() as u64 {
                            // The element stored is the loop variable itself.
                            j = r!(idx);
                        }
                        j = wrap_s(j.wrapping_add(r!(b)), shift);
                        w!(idx, j);
                        if !cmp.test((j as i64).cmp(&(imm as i64))) {
                            break;
                        }
                        // The AddBr's jump back: a watchdog fault names it.
                        tick!(pc!() + 1);
                    }
                } else {
                    let (v, step) = (r!(s), r!(b));
                    // SAFETY: the descriptor's elements and the operand
                    // slots lie in the frame (verified); `irq`: see above.
                    match unsafe {
                        store_stride(&at, idx.index(), (v, step), (cmp, imm as i64, shift), &*irq)
                    } {
                        LoopExit::BadIndex(j) => fault!(index_fault(j, ad)),
                        // The AddBr's jump back: a watchdog fault names it.
                        LoopExit::Interrupted(kind) => {
                            return Err(Fault {
                                kind,
                                code,
                                pc: pc!() as u32 + 1,
                            });
                        }
                        LoopExit::Done | LoopExit::Found => {}
                    }
                }
                // SAFETY: the AddBr is not the block's last instruction (Ret
                // is); the arm's end moves past it.
                ip = unsafe { ip.add(1) };
            }
            Op::ForScan {
                i,
                lim,
                t,
                desc,
                step,
                shift,
                when,
            } => {
                // SAFETY: descriptor indexes are verified at link time.
                let ad = unsafe { img.arrays.get_unchecked(desc.index()) };
                let at = FrameArray { fp, desc: ad };
                // Where the scan goes on: after this instruction, or at the
                // element test `t` (a bad index) or just past it (found).
                // SAFETY: the descriptor's elements and `i` lie in the frame
                // (verified); `irq`: see above.
                let resume = match unsafe {
                    scan_flags(
                        &at,
                        i.index(),
                        (step as i16, lim as i64, shift),
                        when,
                        &*irq,
                    )
                } {
                    LoopExit::Done => None,
                    // The element test at `t` reports the bad index.
                    LoopExit::BadIndex(_) => Some(t.index()),
                    LoopExit::Found => Some(t.index() + 1),
                    LoopExit::Interrupted(kind) => fault!(kind),
                };
                if let Some(at) = resume {
                    // SAFETY: t + 1 < block length (verified with the partner test).
                    ip = unsafe { start.add(at) };
                    continue;
                }
            }
            // A fault unwinding through a call notes the caller's block,
            // instruction and base: nothing the normal path keeps for it.
            Op::CallFb { code: c, inst } => {
                if let Err(f) = call::<DEBUG, NATIVE>(m, img, c, base + inst.index()) {
                    m.unwound(code, pc!(), base);
                    return Err(f);
                }
            }
            Op::CallFbInd { code: c, p } => {
                let at = r!(p) as usize;
                if let Err(f) = call::<DEBUG, NATIVE>(m, img, c, at) {
                    m.unwound(code, pc!(), base);
                    return Err(f);
                }
            }
            Op::CallNative { fb, inst } => {
                // SAFETY: inst + pins(fb) <= frame_size (verified), so the
                // instance lies inside this frame.
                unsafe { stdlib::call_raw(fb, fp.add(inst.index()), m.now) }
            }
            Op::CallNativeInd { fb, p } => {
                let n = fb.instance_slots() as usize;
                let start = r!(p) as usize;
                if start > len || n > len - start {
                    fault!(FaultKind::BadAddress);
                }
                // SAFETY: start + n <= len was checked above (without overflow).
                unsafe { stdlib::call_raw(fb, mem.add(start), m.now) }
            }
            Op::CallFn { code: c } => {
                let frame = img.codes[c.index()].frame as usize;
                if let Err(f) = call::<DEBUG, NATIVE>(m, img, c, frame) {
                    m.unwound(code, pc!(), base);
                    return Err(f);
                }
            }
            Op::Clock { d } => w!(d, m.now as u64),
            Op::MemCopy { d, s, n } => {
                let (to, from, n) = (r!(d) as usize, r!(s) as usize, n as usize);
                if to > len || from > len || n > len - to || n > len - from {
                    fault!(FaultKind::BadAddress);
                }
                // SAFETY: both ranges lie inside memory (checked above);
                // `copy` allows overlap.
                unsafe { std::ptr::copy(mem.add(from), mem.add(to), n) };
                // A copy's time grows with the memory: straight-line code
                // made of big copies is stopped between two of them.
                tick!();
            }
            Op::Ret => return Ok(()),
            Op::Sfc { chart } => {
                if let Err(f) = super::chart::run::<DEBUG>(m, img, chart, base) {
                    m.unwound(code, pc!(), base);
                    return Err(f);
                }
                // The chart runtime indexes memory through references:
                // take fresh pointers (same buffer, same length).
                mem = m.mem.as_mut_ptr();
                // SAFETY: as at entry.
                fp = unsafe { mem.add(base) };
            }
            Op::CallHost { id } => {
                // SAFETY: the frame lies in memory (checked at entry), and
                // nothing else reaches it during the call (the host sees
                // only this slice and the string table).
                let frame =
                    unsafe { std::slice::from_raw_parts_mut(fp, block.frame_size as usize) };
                super::host::call(&m.host, &mut m.strings, m.now, id, frame, base).map_err(
                    |kind| Fault {
                        kind,
                        code,
                        pc: pc!() as u32,
                    },
                )?
            }
            // --- refs: checked references and pointers (out of line, so the
            // dispatch loop keeps its registers) ---
            Op::RefMake { .. }
            | Op::RefAddr { .. }
            | Op::RefIndex { .. }
            | Op::PtrAdd { .. }
            | Op::RefValid { .. }
            | Op::FaultNullItf
            | Op::FaultReentry
            | Op::FaultRaise { .. }
            | Op::RefLoad { .. }
            | Op::RefStore { .. }
            | Op::RefView { .. }
            | Op::PtrToInt { .. }
            | Op::IntToPtr { .. } => {
                // SAFETY: the instruction's frame operands lie inside the
                // frame at fp (verified at link time).
                if let Err(kind) = unsafe { super::refs::run(m, img, fp, op) } {
                    fault!(kind);
                }
            }
        }
        // SAFETY: the block ends with Ret, so an instruction that neither
        // returns nor jumps has a next one in `ops`.
        ip = unsafe { ip.add(1) };
    }
}

pub(crate) fn index_fault(raw: u64, ad: &crate::ir::image::ArrayDesc) -> FaultKind {
    if ad.stride == 0 {
        // Descriptors with stride 0 describe subranges, not arrays.
        return FaultKind::SubrangeViolation {
            value: raw as i64,
            lo: ad.lo,
            hi: ad.lo + ad.len as i64 - 1,
        };
    }
    FaultKind::IndexOutOfRange {
        index: raw as i64,
        lo: ad.lo,
        hi: ad.lo + ad.len as i64 - 1,
    }
}

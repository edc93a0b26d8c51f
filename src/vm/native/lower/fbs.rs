//! Standard FBs compiled inline: R_TRIG, F_TRIG, CTU and TON, the ones
//! programs call most. Each is the body in `stdlib/` written without
//! branches, with the same result in every slot it writes. An instance in
//! the frame works on held slots (inputs copied just before the call and
//! outputs read just after stay in registers); one reached through a
//! pointer on memory at its address. The others go through
//! `helpers::call_native`.

use super::{I64, Lower};
use crate::ir::op::{CounterRange, NativeFb, Op, Slot};
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{InstBuilder, MemFlagsData, Value};

/// Whether `op` is an inlined timer, which reads the cycle's clock.
pub(super) fn needs_clock(op: &Op) -> bool {
    matches!(
        op,
        Op::CallNative {
            fb: NativeFb::Ton,
            ..
        } | Op::CallNativeInd {
            fb: NativeFb::Ton,
            ..
        }
    )
}

/// Whether `fb` compiles inline.
pub(super) fn inlined(fb: NativeFb) -> bool {
    matches!(
        fb,
        NativeFb::RTrig | NativeFb::FTrig | NativeFb::Ctu(_) | NativeFb::Ton
    )
}

/// Where an instance's pins are.
#[derive(Clone, Copy)]
pub(super) enum Pins {
    /// Frame slots from this one (held like any slot).
    Frame(Slot),
    /// Memory from this machine address (checked by the caller).
    At(Value),
}

impl Lower<'_, '_> {
    /// Pin `k` of the instance at `p`.
    fn pin(&mut self, p: Pins, k: u32) -> Value {
        match p {
            Pins::Frame(s) => self.get(s.offset(k)),
            Pins::At(a) => {
                let flags = MemFlagsData::trusted();
                self.b.ins().load(I64, flags, a, 8 * k as i32)
            }
        }
    }

    /// Pin `k` of the instance at `p` becomes `v`.
    fn set_pin(&mut self, p: Pins, k: u32, v: Value) {
        match p {
            Pins::Frame(s) => self.set(s.offset(k), v),
            Pins::At(a) => {
                let flags = MemFlagsData::trusted();
                self.b.ins().store(flags, v, a, 8 * k as i32);
            }
        }
    }

    /// Compiles standard FB `fb` (one that is [`inlined`]) on the
    /// instance at `p` inline.
    pub(super) fn inline_fb(&mut self, fb: NativeFb, p: Pins) {
        match fb {
            // Q := CLK AND NOT M; M := CLK (F_TRIG: on NOT CLK).
            NativeFb::RTrig | NativeFb::FTrig => {
                let mut clk = self.pin(p, 0);
                if fb == NativeFb::FTrig {
                    clk = self.b.ins().bxor_imm_s(clk, 1);
                }
                let m = self.pin(p, 2);
                let not_m = self.b.ins().bnot(m);
                let both = self.b.ins().band(clk, not_m);
                let q = self.b.ins().band_imm_s(both, 1);
                self.set_pin(p, 1, q);
                self.set_pin(p, 2, clk);
            }
            NativeFb::Ctu(r) => self.ctu(p, r),
            NativeFb::Ton => self.ton(p),
            _ => unreachable!("not an inlined FB: {fb:?}"),
        }
    }

    /// CTU: CU, R, PV, Q, CV, CU_prev (`stdlib::counters::ctu`).
    fn ctu(&mut self, p: Pins, r: CounterRange) {
        let (lt, ge, max) = match r {
            CounterRange::Int => (
                IntCC::SignedLessThan,
                IntCC::SignedGreaterThanOrEqual,
                i16::MAX as i64,
            ),
            CounterRange::Dint => (
                IntCC::SignedLessThan,
                IntCC::SignedGreaterThanOrEqual,
                i32::MAX as i64,
            ),
            CounterRange::Lint => (
                IntCC::SignedLessThan,
                IntCC::SignedGreaterThanOrEqual,
                i64::MAX,
            ),
            CounterRange::Udint => (
                IntCC::UnsignedLessThan,
                IntCC::UnsignedGreaterThanOrEqual,
                u32::MAX as i64,
            ),
            CounterRange::Ulint => (
                IntCC::UnsignedLessThan,
                IntCC::UnsignedGreaterThanOrEqual,
                -1,
            ),
        };
        let cu = self.pin(p, 0);
        let prev = self.pin(p, 5);
        let not_prev = self.b.ins().bnot(prev);
        let edge = self.b.ins().band(cu, not_prev);
        let rising = self.b.ins().band_imm_s(edge, 1);
        let cv = self.pin(p, 4);
        let below = self.b.ins().icmp_imm_s(lt, cv, max);
        let rising = self.b.ins().icmp_imm_s(IntCC::NotEqual, rising, 0);
        let count = self.b.ins().band(rising, below);
        let up = self.b.ins().iadd_imm_s(cv, 1);
        let counted = self.b.ins().select(count, up, cv);
        let reset = self.pin(p, 1);
        let zero = self.b.ins().iconst(I64, 0);
        let cv = self.b.ins().select(reset, zero, counted);
        let pv = self.pin(p, 2);
        let q = self.b.ins().icmp(ge, cv, pv);
        let q = self.b.ins().uextend(I64, q);
        self.set_pin(p, 5, cu);
        self.set_pin(p, 4, cv);
        self.set_pin(p, 3, q);
    }

    /// TON: IN, PT, Q, ET, start, prev_IN (`stdlib::timers::ton`). IN
    /// and prev_IN go through the held slots; PT, Q, ET and start are
    /// read and written in memory, the timing only where IN is TRUE (most
    /// timers are idle most of the time).
    fn ton(&mut self, p: Pins) {
        // Defined at entry (`needs_clock`).
        let now = self.now();
        let input = self.pin(p, 0);
        let prev = self.pin(p, 5);
        let at = match p {
            Pins::Frame(s) => {
                let lo = u64::from(s.get()) + 1;
                self.drop_range(lo, lo + 4);
                let (base, off) = self.slot_at(s);
                self.b.ins().iadd_imm_s(base, i64::from(off))
            }
            Pins::At(a) => a,
        };
        let mem = Pins::At(at);
        let (on, off, join) = (
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
        );
        self.b.ins().brif(input, on, &[], off, &[]);
        self.b.switch_to_block(off);
        self.b.seal_block(off);
        let zero = self.b.ins().iconst(I64, 0);
        self.set_pin(mem, 2, zero);
        self.set_pin(mem, 3, zero);
        self.b.ins().jump(join, &[]);
        self.b.switch_to_block(on);
        self.b.seal_block(on);
        self.ton_on(mem, now, prev);
        self.b.ins().jump(join, &[]);
        self.b.switch_to_block(join);
        self.b.seal_block(join);
        let on = self.b.ins().icmp_imm_s(IntCC::NotEqual, input, 0);
        let on = self.b.ins().uextend(I64, on);
        self.set_pin(p, 5, on);
    }

    /// TON while IN is TRUE, on the pins in memory at `mem`.
    fn ton_on(&mut self, mem: Pins, now: Value, prev: Value) {
        let zero = self.b.ins().iconst(I64, 0);
        let starts = self.b.ins().icmp_imm_s(IntCC::Equal, prev, 0);
        let start = self.pin(mem, 4);
        let start = self.b.ins().select(starts, now, start);
        let q = self.pin(mem, 2);
        let q = self.b.ins().select(starts, zero, q);
        let timing = self.b.ins().icmp_imm_s(IntCC::Equal, q, 0);
        let pt = self.pin(mem, 1);
        let et = self.elapsed(now, start, pt);
        let done = self.b.ins().icmp(IntCC::SignedGreaterThanOrEqual, et, pt);
        let done = self.b.ins().uextend(I64, done);
        let old_et = self.pin(mem, 3);
        let et = self.b.ins().select(timing, et, old_et);
        let q = self.b.ins().select(timing, done, q);
        self.set_pin(mem, 2, q);
        self.set_pin(mem, 3, et);
        self.set_pin(mem, 4, start);
    }

    /// `(now - start).min(pt).max(0)` on signed values (`timers::elapsed`).
    fn elapsed(&mut self, now: Value, start: Value, pt: Value) -> Value {
        let d = self.b.ins().isub(now, start);
        let m = self.b.ins().smin(d, pt);
        let zero = self.b.ins().iconst(I64, 0);
        self.b.ins().smax(m, zero)
    }
}

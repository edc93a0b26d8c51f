//! Lowering S7-200 routines into Structured Text statements of the shared
//! AST. Each routine (the main program OB1, each subroutine `SBR n`) has
//! its own 9-level logic stack (`S7_<routine>_S0` is the top); a `CALL`
//! inlines the subroutine's body behind `IF top THEN`, after setting the
//! callee's top to 1 and the rest to 0, which leaves the caller's stack as
//! it was, as the CPU saves and restores it. Jumps, labels and returns are
//! a control variable (`S7_<routine>_J`: 0 running, -1 returned, n+1
//! jumping to label n) guarding each stretch of code between them, inside
//! a `REPEAT` when a jump goes backwards.

use super::build::At;
use super::instr::{Arith, Combine, CounterKind, Logic, Op, Rel, TimerKind};
use super::lines::Word;
use super::operands::{Area, Operand, OperandError, TIMERS, Width, parse_const, parse_operand};
use super::support::resolution_ms;
use super::views::{self, ViewError, bits_type, signed};
use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::Span;
use crate::syntax::ast::{BinaryOp, Expr, Stmt};
use std::collections::HashMap;

/// Depth of the logic stack.
pub(super) const STACK: usize = 9;

/// Subroutine nesting the CPU allows.
const MAX_NESTING: u32 = 8;

/// One instruction as read.
#[derive(Debug, Clone)]
pub(super) struct Instr {
    /// What it is.
    pub op: Op,
    /// Its mnemonic as written.
    pub mnemonic: String,
    /// Its operands as written.
    pub operands: Vec<Word>,
    /// The whole instruction.
    pub span: Span,
}

/// The main program or one subroutine.
#[derive(Debug, Clone)]
pub(super) struct Routine {
    /// `None` for the main program, `Some(n)` for `SBR n`.
    pub number: Option<u32>,
    /// Its instructions in order.
    pub instrs: Vec<Instr>,
    /// Where it starts.
    pub span: Span,
}

impl Routine {
    /// The name its generated variables carry (`OB1`, `SBR3`).
    pub(super) fn tag(&self) -> String {
        match self.number {
            None => "OB1".to_string(),
            Some(n) => format!("SBR{n}"),
        }
    }
}

/// A lowered routine.
#[derive(Debug, Clone)]
struct Lowered {
    /// Its statements (entry code for its control variable included).
    body: Vec<Stmt>,
    /// The deepest nesting of calls below it (0 when it calls nothing).
    depth: u32,
}

/// An operand with its text and place.
#[derive(Debug, Clone)]
struct Opd {
    op: Operand,
    text: String,
    span: Span,
}

/// The routine being lowered.
struct Emit {
    tag: String,
    seg: Vec<Stmt>,
    out: Vec<Stmt>,
    guarded: bool,
    depth: u32,
}

impl Emit {
    fn s(&self, at: At, i: usize) -> Expr {
        at.name(&format!("S7_{}_S{i}", self.tag))
    }

    fn j(&self, at: At) -> Expr {
        at.name(&format!("S7_{}_J", self.tag))
    }

    /// Ends the current stretch of code (guarded when the routine jumps).
    fn flush(&mut self, at: At) {
        let seg = std::mem::take(&mut self.seg);
        if seg.is_empty() {
            return;
        }
        if self.guarded {
            let cond = at.bin(BinaryOp::Eq, self.j(at), at.int(0));
            self.out.push(at.when(cond, seg));
        } else {
            self.out.extend(seg);
        }
    }

    /// Pushes `value` (which must not read the stack).
    fn push(&mut self, at: At, value: Expr) {
        self.shift_down(at);
        let top = self.s(at, 0);
        self.seg.push(at.assign(top, value));
    }

    /// Every level one down (the bottom one is lost); the top stays.
    fn shift_down(&mut self, at: At) {
        for i in (1..STACK).rev() {
            let (to, from) = (self.s(at, i), self.s(at, i - 1));
            self.seg.push(at.assign(to, from));
        }
    }

    /// Every level below the top one up; the bottom becomes 0.
    fn shift_up_below_top(&mut self, at: At) {
        for i in 1..STACK - 1 {
            let (to, from) = (self.s(at, i), self.s(at, i + 1));
            self.seg.push(at.assign(to, from));
        }
        let bottom = self.s(at, STACK - 1);
        self.seg.push(at.assign(bottom, at.boolean(false)));
    }

    /// `top := top op value`.
    fn combine(&mut self, at: At, op: BinaryOp, value: Expr) {
        let v = at.bin(op, self.s(at, 0), value);
        let top = self.s(at, 0);
        self.seg.push(at.assign(top, v));
    }

    /// `IF top THEN body END_IF`.
    fn when_top(&mut self, at: At, body: Vec<Stmt>) {
        if !body.is_empty() {
            let c = self.s(at, 0);
            self.seg.push(at.when(c, body));
        }
    }
}

/// Lowers the routines of one file.
pub(super) struct Lowering<'a> {
    sbrs: HashMap<u32, &'a Routine>,
    done: HashMap<u32, Lowered>,
    active: Vec<u32>,
    /// Every routine lowered (their stacks are declared).
    pub tags: Vec<String>,
    /// The routines with a control variable.
    pub jumps: Vec<String>,
    /// Number of EU/ED instructions (each has its memory bit).
    pub edges: u32,
    /// The highest Q byte used.
    pub q_max: Option<u32>,
    /// The timer kind each timer number is used as.
    timer_kinds: HashMap<u32, TimerKind>,
    /// Whether timers / counters are used.
    pub uses_timers: bool,
    /// See `uses_timers`.
    pub uses_counters: bool,
    diags: &'a mut Diagnostics,
}

fn err(code: &'static str, span: Span, msg: String) -> Diagnostic {
    Diagnostic::error(code, span, msg)
}

impl<'a> Lowering<'a> {
    /// A lowering of the subroutines `sbrs`.
    pub(super) fn new(sbrs: HashMap<u32, &'a Routine>, diags: &'a mut Diagnostics) -> Self {
        Lowering {
            sbrs,
            done: HashMap::new(),
            active: Vec::new(),
            tags: Vec::new(),
            jumps: Vec::new(),
            edges: 0,
            q_max: None,
            timer_kinds: HashMap::new(),
            uses_timers: false,
            uses_counters: false,
            diags,
        }
    }

    /// The statements of the main program.
    pub(super) fn main(&mut self, r: &Routine) -> Vec<Stmt> {
        self.routine(r).body
    }

    /// Lowers every subroutine no one calls too (its errors are reported).
    pub(super) fn uncalled(&mut self) {
        let mut numbers: Vec<u32> = self.sbrs.keys().copied().collect();
        numbers.sort_unstable();
        for n in numbers {
            if !self.done.contains_key(&n) {
                let _ = self.sbr(n, Span::default());
            }
        }
    }

    fn routine(&mut self, r: &Routine) -> Lowered {
        let tag = r.tag();
        let at = At(r.span);
        let last = r.instrs.len();
        let guarded = r.instrs.iter().enumerate().any(|(i, ins)| {
            matches!(ins.op, Op::Jmp | Op::Lbl | Op::Cret | Op::End)
                || (matches!(ins.op, Op::Ret | Op::Mend) && i + 1 < last)
        });
        let mut labels: HashMap<u32, usize> = HashMap::new();
        for (i, ins) in r.instrs.iter().enumerate() {
            if ins.op == Op::Lbl
                && let Ok(n) = self.number(ins, 255)
                && labels.insert(n, i).is_some()
            {
                self.diags.push(err(
                    "E860",
                    ins.span,
                    format!("label {n} is defined twice in {tag}"),
                ));
            }
        }
        let backward = r.instrs.iter().enumerate().any(|(i, ins)| {
            ins.op == Op::Jmp
                && self
                    .number(ins, 255)
                    .ok()
                    .and_then(|n| labels.get(&n))
                    .is_some_and(|&l| l < i)
        });
        let mut e = Emit {
            tag: tag.clone(),
            seg: Vec::new(),
            out: Vec::new(),
            guarded,
            depth: 0,
        };
        for (i, ins) in r.instrs.iter().enumerate() {
            if let Err(d) = self.instr(&mut e, ins, &labels, i + 1 == last) {
                self.diags.push(d);
            }
        }
        e.flush(at);
        let mut body = Vec::new();
        if guarded {
            body.push(at.assign(e.j(at), at.int(0)));
            self.jumps.push(tag.clone());
        }
        if backward {
            let until = at.bin(BinaryOp::Le, e.j(at), at.int(0));
            body.push(at.repeat(e.out, until));
        } else {
            body.extend(e.out);
        }
        self.tags.push(tag);
        Lowered {
            body,
            depth: e.depth,
        }
    }

    /// The lowered subroutine `n` (lowered once, inlined at each call).
    fn sbr(&mut self, n: u32, span: Span) -> Result<Lowered, Diagnostic> {
        if let Some(l) = self.done.get(&n) {
            return Ok(l.clone());
        }
        if self.active.contains(&n) {
            return Err(err(
                "E858",
                span,
                format!(
                    "subroutine {n} calls itself (directly or through others): the S7-200 forbids recursion"
                ),
            ));
        }
        let Some(r) = self.sbrs.get(&n).copied() else {
            return Err(err(
                "E857",
                span,
                format!("there is no subroutine {n} (SBR {n}) in this program"),
            ));
        };
        self.active.push(n);
        let l = self.routine(r);
        self.active.pop();
        self.done.insert(n, l.clone());
        Ok(l)
    }

    /// The operands of `ins`, exactly `n` of them, decoded.
    fn ops(&mut self, ins: &Instr, n: usize) -> Result<Vec<Opd>, Diagnostic> {
        if ins.operands.len() != n {
            return Err(err(
                "E852",
                ins.span,
                format!(
                    "`{}` takes {n} operand{}, found {}",
                    ins.mnemonic,
                    if n == 1 { "" } else { "s" },
                    ins.operands.len()
                ),
            ));
        }
        let mut out = Vec::with_capacity(n);
        for w in &ins.operands {
            let op = parse_operand(&w.text).map_err(|e| operand_error(ins, w, e))?;
            self.touch(op);
            out.push(Opd {
                op,
                text: w.text.clone(),
                span: w.span,
            });
        }
        Ok(out)
    }

    /// Notes the Q bytes an operand uses (for the default trace).
    fn touch(&mut self, op: Operand) {
        let last = match op {
            Operand::Bit {
                area: Area::Q,
                byte,
                ..
            } => byte,
            Operand::Mem {
                area: Area::Q,
                width,
                addr,
            } => addr + width.bytes() - 1,
            _ => return,
        };
        self.q_max = Some(self.q_max.map_or(last, |m| m.max(last)));
    }

    /// The single number operand of JMP, LBL, SBR, CALL (`3`, `K3`, `SBR_3`).
    fn number(&self, ins: &Instr, max: u32) -> Result<u32, Diagnostic> {
        let [w] = ins.operands.as_slice() else {
            return Err(err(
                "E852",
                ins.span,
                format!(
                    "`{}` takes 1 operand, found {}",
                    ins.mnemonic,
                    ins.operands.len()
                ),
            ));
        };
        routine_number(&w.text)
            .filter(|n| *n <= max)
            .ok_or_else(|| {
                err(
                    "E853",
                    w.span,
                    format!(
                        "`{}` needs a number from 0 to {max}, found `{}`",
                        ins.mnemonic, w.text
                    ),
                )
            })
    }

    fn instr(
        &mut self,
        e: &mut Emit,
        ins: &Instr,
        labels: &HashMap<u32, usize>,
        is_last: bool,
    ) -> Result<(), Diagnostic> {
        let at = At(ins.span);
        match ins.op {
            Op::Ld | Op::Ldn | Op::A | Op::An | Op::O | Op::On => {
                let o = self.ops(ins, 1)?;
                let mut v = views::read_bit(at, o[0].op).map_err(|x| view_error(ins, &o[0], x))?;
                if matches!(ins.op, Op::Ldn | Op::An | Op::On) {
                    v = at.not(v);
                }
                match ins.op {
                    Op::Ld | Op::Ldn => e.push(at, v),
                    Op::A | Op::An => e.combine(at, BinaryOp::And, v),
                    _ => e.combine(at, BinaryOp::Or, v),
                }
            }
            Op::Assign => {
                let o = self.ops(ins, 1)?;
                let s = views::write_bit(at, o[0].op, e.s(at, 0))
                    .map_err(|x| view_error(ins, &o[0], x))?;
                e.seg.push(s);
            }
            Op::Set | Op::Reset => {
                let body = self.set_reset(ins)?;
                e.when_top(at, body);
            }
            Op::Ald | Op::Old => {
                self.ops(ins, 0)?;
                let op = if ins.op == Op::Ald {
                    BinaryOp::And
                } else {
                    BinaryOp::Or
                };
                let second = e.s(at, 1);
                e.combine(at, op, second);
                e.shift_up_below_top(at);
            }
            Op::Lps => {
                self.ops(ins, 0)?;
                e.shift_down(at);
            }
            Op::Lrd => {
                self.ops(ins, 0)?;
                let (top, second) = (e.s(at, 0), e.s(at, 1));
                e.seg.push(at.assign(top, second));
            }
            Op::Lpp => {
                self.ops(ins, 0)?;
                let (top, second) = (e.s(at, 0), e.s(at, 1));
                e.seg.push(at.assign(top, second));
                e.shift_up_below_top(at);
            }
            Op::Not => {
                self.ops(ins, 0)?;
                let (top, v) = (e.s(at, 0), at.not(e.s(at, 0)));
                e.seg.push(at.assign(top, v));
            }
            Op::Eu | Op::Ed => self.edge(e, ins)?,
            Op::Compare(combine, w, rel) => {
                let o = self.ops(ins, 2)?;
                let conv = match w {
                    Width::B => "BYTE_TO_INT",
                    Width::W => "WORD_TO_INT",
                    Width::D => "DWORD_TO_DINT",
                };
                let a = views::read(at, o[0].op, w).map_err(|x| view_error(ins, &o[0], x))?;
                let b = views::read(at, o[1].op, w).map_err(|x| view_error(ins, &o[1], x))?;
                let op = match rel {
                    Rel::Eq => BinaryOp::Eq,
                    Rel::Ne => BinaryOp::Ne,
                    Rel::Lt => BinaryOp::Lt,
                    Rel::Le => BinaryOp::Le,
                    Rel::Gt => BinaryOp::Gt,
                    Rel::Ge => BinaryOp::Ge,
                };
                let c = at.bin(op, at.call(conv, vec![a]), at.call(conv, vec![b]));
                match combine {
                    Combine::Load => e.push(at, c),
                    Combine::And => e.combine(at, BinaryOp::And, c),
                    Combine::Or => e.combine(at, BinaryOp::Or, c),
                }
            }
            Op::Timer(kind) => {
                let s = self.timer(e, ins, kind)?;
                e.seg.push(s);
            }
            Op::Counter(kind) => {
                let s = self.counter(e, ins, kind)?;
                e.seg.push(s);
            }
            Op::Jmp => {
                let n = self.number(ins, 255)?;
                if !labels.contains_key(&n) {
                    return Err(err(
                        "E860",
                        ins.span,
                        format!("`JMP {n}`: there is no `LBL {n}` in {}", e.tag),
                    ));
                }
                let set = at.assign(e.j(at), at.int(i64::from(n) + 1));
                e.when_top(at, vec![set]);
                e.flush(at);
            }
            Op::Lbl => {
                let n = self.number(ins, 255)?;
                e.flush(at);
                let cond = at.bin(BinaryOp::Eq, e.j(at), at.int(i64::from(n) + 1));
                let clear = at.assign(e.j(at), at.int(0));
                e.out.push(at.when(cond, vec![clear]));
            }
            Op::Call => self.call(e, ins)?,
            Op::Sbr | Op::Nop => {}
            Op::Ret | Op::Mend => {
                self.ops(ins, 0)?;
                if !is_last {
                    let r = at.assign(e.j(at), at.int(-1));
                    e.seg.push(r);
                    e.flush(at);
                }
            }
            Op::Cret | Op::End => {
                self.ops(ins, 0)?;
                let r = at.assign(e.j(at), at.int(-1));
                e.when_top(at, vec![r]);
                e.flush(at);
            }
            _ => {
                let body = self.word_op(ins)?;
                e.when_top(at, body);
            }
        }
        Ok(())
    }

    /// `EU`/`ED`: the top becomes its rising / falling edge, against the
    /// instruction's own memory bit.
    fn edge(&mut self, e: &mut Emit, ins: &Instr) -> Result<(), Diagnostic> {
        let at = At(ins.span);
        self.ops(ins, 0)?;
        let mem = at.index("S7_E", self.edges);
        self.edges += 1;
        let top = e.s(at, 0);
        let edge = if ins.op == Op::Eu {
            at.bin(BinaryOp::And, top.clone(), at.not(mem.clone()))
        } else {
            at.bin(BinaryOp::And, at.not(top.clone()), mem.clone())
        };
        e.seg.push(at.assign(at.name("S7_X"), edge));
        e.seg.push(at.assign(mem, top.clone()));
        e.seg.push(at.assign(top, at.name("S7_X")));
        Ok(())
    }

    /// `CALL n`: the callee inlined behind the top of the stack.
    fn call(&mut self, e: &mut Emit, ins: &Instr) -> Result<(), Diagnostic> {
        let at = At(ins.span);
        let n = self.number(ins, 255)?;
        let callee = self.sbr(n, ins.span)?;
        let depth = callee.depth + 1;
        if e.tag == "OB1" && depth > MAX_NESTING {
            return Err(err(
                "E858",
                ins.span,
                format!(
                    "`CALL {n}` nests subroutines {depth} deep; the S7-200 allows {MAX_NESTING}"
                ),
            ));
        }
        e.depth = e.depth.max(depth);
        let mut body = Vec::with_capacity(STACK + callee.body.len());
        for i in 0..STACK {
            let name = at.name(&format!("S7_SBR{n}_S{i}"));
            body.push(at.assign(name, at.boolean(i == 0)));
        }
        body.extend(callee.body);
        e.when_top(at, body);
        Ok(())
    }

    /// `S`/`R bit, n` (and `R Tn, n`, `R Cn, n`): the statements run when
    /// the top of the stack is 1.
    fn set_reset(&mut self, ins: &Instr) -> Result<Vec<Stmt>, Diagnostic> {
        let at = At(ins.span);
        let o = self.ops(ins, 2)?;
        let count = match o[1].op {
            Operand::Const(n) if (1..=255).contains(&n) => n as u32,
            _ => {
                return Err(err(
                    "E856",
                    o[1].span,
                    format!(
                        "`{}`: the bit count must be a constant from 1 to 255, found `{}`",
                        ins.mnemonic, o[1].text
                    ),
                ));
            }
        };
        let set = ins.op == Op::Set;
        let mut out = Vec::new();
        match o[0].op {
            Operand::Bit { area, byte, bit } => {
                let first = byte * 8 + u32::from(bit);
                let last = first + count - 1;
                if last / 8 >= area.size() {
                    return Err(err(
                        "E855",
                        ins.span,
                        format!(
                            "`{} {}` goes past the end of {} (byte {})",
                            ins.mnemonic,
                            o[0].text,
                            area.letter(),
                            area.size() - 1
                        ),
                    ));
                }
                for b in first / 8..=last / 8 {
                    let lo = first.max(b * 8) - b * 8;
                    let hi = last.min(b * 8 + 7) - b * 8;
                    let mask: i64 = ((1i64 << (hi + 1)) - 1) & !((1i64 << lo) - 1);
                    let cell = at.index(area.image(), b);
                    let v = if set {
                        at.bin(BinaryOp::Or, cell.clone(), at.typed("BYTE", mask))
                    } else {
                        at.bin(BinaryOp::And, cell.clone(), at.typed("BYTE", !mask & 0xFF))
                    };
                    out.push(at.assign(cell, v));
                }
            }
            Operand::Timer(n) | Operand::Counter(n) if !set => {
                if n + count > TIMERS {
                    return Err(err(
                        "E855",
                        ins.span,
                        format!("`R {}, {count}` goes past the last one (255)", o[0].text),
                    ));
                }
                let timer = matches!(o[0].op, Operand::Timer(_));
                for k in n..n + count {
                    if timer {
                        out.push(at.assign(at.index("S7_T", k), at.int(0)));
                        out.push(at.assign(at.index("S7_TB", k), at.boolean(false)));
                        out.push(at.assign(at.index("S7_TRUN", k), at.boolean(false)));
                    } else {
                        out.push(at.assign(at.index("S7_C", k), at.int(0)));
                        out.push(at.assign(at.index("S7_CB", k), at.boolean(false)));
                    }
                }
            }
            _ => {
                return Err(view_error(
                    ins,
                    &o[0],
                    ViewError::Kind(if set {
                        "a bit of I, Q, M, V or SM"
                    } else {
                        "a bit of I, Q, M, V or SM, a timer or a counter"
                    }),
                ));
            }
        }
        Ok(out)
    }

    /// `TON`/`TONR`/`TOF Tn, PT`.
    fn timer(&mut self, e: &Emit, ins: &Instr, kind: TimerKind) -> Result<Stmt, Diagnostic> {
        let at = At(ins.span);
        let o = self.ops(ins, 2)?;
        let Operand::Timer(n) = o[0].op else {
            return Err(view_error(
                ins,
                &o[0],
                ViewError::Kind("a timer (T0..T255)"),
            ));
        };
        let res = resolution_ms(kind == TimerKind::Tonr, n).ok_or_else(|| {
            err(
                "E866",
                o[0].span,
                format!(
                    "`{}` cannot use {}: {}",
                    ins.mnemonic,
                    o[0].text,
                    if kind == TimerKind::Tonr {
                        "TONR timers are T0-T31 and T64-T95"
                    } else {
                        "TON and TOF timers are T32-T63 and T96-T255"
                    }
                ),
            )
        })?;
        let previous = *self.timer_kinds.entry(n).or_insert(kind);
        if previous != kind {
            return Err(err(
                "E865",
                o[0].span,
                format!(
                    "T{n} is used both as {previous:?} and as {kind:?}; the S7-200 forbids sharing a timer number"
                ),
            ));
        }
        self.uses_timers = true;
        let pt = self.preset(ins, &o[1])?;
        let k = match kind {
            TimerKind::Ton => 0,
            TimerKind::Tonr => 1,
            TimerKind::Tof => 2,
        };
        Ok(at.call_stmt(
            "S7_TIMER",
            vec![
                ("IN", e.s(at, 0)),
                ("KIND", at.int(k)),
                ("PT", pt),
                ("RES", at.typed("LINT", res)),
                ("NOW", at.name("S7_NOW")),
                ("CV", at.index("S7_T", n)),
                ("BIT", at.index("S7_TB", n)),
                ("RUN", at.index("S7_TRUN", n)),
                ("REM", at.index("S7_TREM", n)),
                ("LAST", at.index("S7_TLAST", n)),
            ],
        ))
    }

    /// A preset (PT, PV): an INT constant or word operand.
    fn preset(&self, ins: &Instr, o: &Opd) -> Result<Expr, Diagnostic> {
        let at = At(ins.span);
        match o.op {
            Operand::Const(v) if (-32768..=32767).contains(&v) => Ok(at.typed("INT", v)),
            Operand::Const(_) => Err(err(
                "E856",
                o.span,
                format!(
                    "`{}`: the preset `{}` is outside -32768..32767",
                    ins.mnemonic, o.text
                ),
            )),
            op => {
                let w = views::read(at, op, Width::W).map_err(|x| view_error(ins, o, x))?;
                Ok(at.call("WORD_TO_INT", vec![w]))
            }
        }
    }

    /// `CTU`/`CTD`/`CTUD Cn, PV`: inputs from the stack (top: reset or
    /// load; second: count down for CTD and CTUD, count up for CTU; third:
    /// count up for CTUD). The stack is left as it is.
    fn counter(&mut self, e: &Emit, ins: &Instr, kind: CounterKind) -> Result<Stmt, Diagnostic> {
        let at = At(ins.span);
        let o = self.ops(ins, 2)?;
        let Operand::Counter(n) = o[0].op else {
            return Err(view_error(
                ins,
                &o[0],
                ViewError::Kind("a counter (C0..C255)"),
            ));
        };
        self.uses_counters = true;
        let pv = self.preset(ins, &o[1])?;
        let f = at.boolean(false);
        let (k, cu, cd) = match kind {
            CounterKind::Ctu => (0, e.s(at, 1), f),
            CounterKind::Ctd => (1, f, e.s(at, 1)),
            CounterKind::Ctud => (2, e.s(at, 2), e.s(at, 1)),
        };
        Ok(at.call_stmt(
            "S7_COUNTER",
            vec![
                ("KIND", at.int(k)),
                ("CU", cu),
                ("CD", cd),
                ("RST", e.s(at, 0)),
                ("PV", pv),
                ("CV", at.index("S7_C", n)),
                ("BIT", at.index("S7_CB", n)),
                ("PCU", at.index("S7_CPU", n)),
                ("PCD", at.index("S7_CPD", n)),
            ],
        ))
    }

    /// The box instructions on bytes, words and double words: their
    /// statements, run when the top of the stack is 1.
    fn word_op(&mut self, ins: &Instr) -> Result<Vec<Stmt>, Diagnostic> {
        let at = At(ins.span);
        let rd = |o: &Opd, w: Width| views::read(at, o.op, w).map_err(|x| view_error(ins, o, x));
        let wr = |o: &Opd, w: Width, v: Expr| {
            views::write(at, o.op, w, v).map_err(|x| view_error(ins, o, x))
        };
        match ins.op {
            Op::Move(w) => {
                let o = self.ops(ins, 2)?;
                wr(&o[1], w, rd(&o[0], w)?)
            }
            Op::Logic(l, w) => {
                let o = self.ops(ins, 2)?;
                let op = match l {
                    Logic::And => BinaryOp::And,
                    Logic::Or => BinaryOp::Or,
                    Logic::Xor => BinaryOp::Xor,
                };
                wr(&o[1], w, at.bin(op, rd(&o[1], w)?, rd(&o[0], w)?))
            }
            Op::Invert(w) | Op::Inc(w) | Op::Dec(w) => {
                let o = self.in_place(ins)?;
                let v = rd(&o, w)?;
                let v = match ins.op {
                    Op::Invert(_) => at.not(v),
                    _ => {
                        let (to, from, _) = signed(w);
                        let op = if matches!(ins.op, Op::Inc(_)) {
                            BinaryOp::Add
                        } else {
                            BinaryOp::Sub
                        };
                        at.call(from, vec![at.bin(op, at.call(to, vec![v]), at.int(1))])
                    }
                };
                wr(&o, w, v)
            }
            Op::Arith(a, w) => {
                let o = self.ops(ins, 2)?;
                let (to, from, _) = signed(w);
                let in1 = at.call(to, vec![rd(&o[0], w)?]);
                let out = at.call(to, vec![rd(&o[1], w)?]);
                let op = match a {
                    Arith::Add => BinaryOp::Add,
                    Arith::Sub => BinaryOp::Sub,
                    Arith::Mul => BinaryOp::Mul,
                    Arith::Div => BinaryOp::Div,
                };
                let store = wr(&o[1], w, at.call(from, vec![at.bin(op, out, in1.clone())]))?;
                if a == Arith::Div {
                    Ok(divide(at, in1, store))
                } else {
                    Ok(store)
                }
            }
            Op::Mul | Op::Div => self.mul_div(ins),
            Op::Shift(left, rotate, w) => {
                let o = self.ops(ins, 2)?;
                let n = match o[1].op {
                    Operand::Const(n) if (0..=255).contains(&n) => n,
                    _ => {
                        return Err(err(
                            "E856",
                            o[1].span,
                            format!(
                                "`{}`: N must be a constant from 0 to 255, found `{}`",
                                ins.mnemonic, o[1].text
                            ),
                        ));
                    }
                };
                let bits = 8 * i64::from(w.bytes());
                let v = rd(&o[0], w)?;
                let value = match (rotate, left) {
                    (true, true) => at.call("ROL", vec![v, at.int(n % bits)]),
                    (true, false) => at.call("ROR", vec![v, at.int(n % bits)]),
                    // Shifting by the width or more leaves 0, as on the CPU.
                    (false, _) if n >= bits => at.typed(bits_type(w), 0),
                    (false, true) => at.call("SHL", vec![v, at.int(n)]),
                    (false, false) => at.call("SHR", vec![v, at.int(n)]),
                };
                wr(&o[0], w, value)
            }
            Op::Swap => {
                let o = self.ops(ins, 1)?;
                let v = rd(&o[0], Width::W)?;
                let swapped = at.bin(
                    BinaryOp::Or,
                    at.call("SHL", vec![v.clone(), at.int(8)]),
                    at.call("SHR", vec![v, at.int(8)]),
                );
                wr(&o[0], Width::W, swapped)
            }
            Op::Convert(from, to) => {
                let o = self.ops(ins, 2)?;
                let v = rd(&o[0], from)?;
                let (value, range) = match (from, to) {
                    (Width::B, _) => (
                        at.call("INT_TO_WORD", vec![at.call("BYTE_TO_INT", vec![v])]),
                        None,
                    ),
                    (Width::W, Width::D) => (
                        at.call(
                            "DINT_TO_DWORD",
                            vec![at.call("INT_TO_DINT", vec![at.call("WORD_TO_INT", vec![v])])],
                        ),
                        None,
                    ),
                    (Width::W, _) => {
                        let x = at.call("WORD_TO_INT", vec![v]);
                        (at.call("INT_TO_BYTE", vec![x.clone()]), Some((x, 0, 255)))
                    }
                    (Width::D, _) => {
                        let x = at.call("DWORD_TO_DINT", vec![v]);
                        let as_int = at.call("DINT_TO_INT", vec![x.clone()]);
                        (
                            at.call("INT_TO_WORD", vec![as_int]),
                            Some((x, -32768, 32767)),
                        )
                    }
                };
                let store = wr(&o[1], to, value)?;
                let Some((x, lo, hi)) = range else {
                    return Ok(store);
                };
                // Out of range: SM1.1 (overflow) set and OUT left as it was.
                let fits = at.bin(
                    BinaryOp::And,
                    at.bin(BinaryOp::Ge, x.clone(), at.int(lo)),
                    at.bin(BinaryOp::Le, x, at.int(hi)),
                );
                Ok(vec![
                    at.assign(
                        at.bit(at.index(Area::Sm.image(), 1), 1),
                        at.not(fits.clone()),
                    ),
                    at.when(fits, store),
                ])
            }
            Op::Fill => self.fill(ins),
            Op::BlockMove(w) => self.block_move(ins, w),
            _ => Err(err(
                "E851",
                ins.span,
                format!("instruction `{}` is not supported here", ins.mnemonic),
            )),
        }
    }

    /// The operand of `INVW OUT`-style instructions (also written `IN, OUT`
    /// with both the same).
    fn in_place(&mut self, ins: &Instr) -> Result<Opd, Diagnostic> {
        let n = ins.operands.len().clamp(1, 2);
        let mut o = self.ops(ins, n)?;
        if n == 2 && o[0].op != o[1].op {
            return Err(err(
                "E854",
                ins.span,
                format!(
                    "`{}` works in place: IN and OUT must be the same operand",
                    ins.mnemonic
                ),
            ));
        }
        Ok(o.remove(0))
    }

    /// `MUL IN1, OUT` and `DIV IN1, OUT` (OUT a double word whose low word
    /// is the other factor or the dividend).
    fn mul_div(&mut self, ins: &Instr) -> Result<Vec<Stmt>, Diagnostic> {
        let at = At(ins.span);
        let o = self.ops(ins, 2)?;
        let Operand::Mem {
            area,
            width: Width::D,
            addr,
        } = o[1].op
        else {
            return Err(view_error(
                ins,
                &o[1],
                ViewError::Kind("a double-word operand (VD, MD …)"),
            ));
        };
        let low = Operand::Mem {
            area,
            width: Width::W,
            addr: addr + 2,
        };
        let int = |op: Operand| -> Result<Expr, Diagnostic> {
            let w = views::read(at, op, Width::W).map_err(|x| view_error(ins, &o[0], x))?;
            Ok(at.call("WORD_TO_INT", vec![w]))
        };
        let in1 = int(o[0].op)?;
        let other = int(low)?;
        let dint = |e: Expr| at.call("INT_TO_DINT", vec![e]);
        let as_dword = |e: Expr| at.call("WORD_TO_DWORD", vec![at.call("INT_TO_WORD", vec![e])]);
        if ins.op == Op::Mul {
            let v = at.call(
                "DINT_TO_DWORD",
                vec![at.bin(BinaryOp::Mul, dint(in1), dint(other))],
            );
            return views::write(at, o[1].op, Width::D, v).map_err(|x| view_error(ins, &o[1], x));
        }
        let rem = as_dword(at.bin(BinaryOp::Mod, other.clone(), in1.clone()));
        let quot = as_dword(at.bin(BinaryOp::Div, other, in1.clone()));
        let v = at.bin(BinaryOp::Or, at.call("SHL", vec![rem, at.int(16)]), quot);
        let store =
            views::write(at, o[1].op, Width::D, v).map_err(|x| view_error(ins, &o[1], x))?;
        Ok(divide(at, in1, store))
    }

    /// `FILL IN, OUT, N`: N words from OUT set to IN.
    fn fill(&mut self, ins: &Instr) -> Result<Vec<Stmt>, Diagnostic> {
        let at = At(ins.span);
        let o = self.ops(ins, 3)?;
        let value = views::read(at, o[0].op, Width::W).map_err(|x| view_error(ins, &o[0], x))?;
        let (area, addr) = mem_of(ins, &o[1], Width::W)?;
        let n = count(ins, &o[2])?;
        let end = addr + 2 * n;
        if end > area.size() {
            return Err(err(
                "E855",
                ins.span,
                format!(
                    "`{}` fills up to {}B{}, past the end of {}",
                    ins.mnemonic,
                    area.letter(),
                    end - 1,
                    area.letter()
                ),
            ));
        }
        let mut out = vec![at.assign(at.name(views::SCRATCH_WORD), value)];
        let hi = at.call(
            "WORD_TO_BYTE",
            vec![at.call("SHR", vec![at.name(views::SCRATCH_WORD), at.int(8)])],
        );
        let lo = at.call("WORD_TO_BYTE", vec![at.name(views::SCRATCH_WORD)]);
        for i in 0..n {
            out.push(at.assign(at.index(area.image(), addr + 2 * i), hi.clone()));
            out.push(at.assign(at.index(area.image(), addr + 2 * i + 1), lo.clone()));
        }
        Ok(out)
    }

    /// `BMB`/`BMW`/`BMD IN, OUT, N`: N elements copied, lowest address first.
    fn block_move(&mut self, ins: &Instr, w: Width) -> Result<Vec<Stmt>, Diagnostic> {
        let at = At(ins.span);
        let o = self.ops(ins, 3)?;
        let (from_area, from) = mem_of(ins, &o[0], w)?;
        let (to_area, to) = mem_of(ins, &o[1], w)?;
        let n = count(ins, &o[2])?;
        let bytes = n * w.bytes();
        for (area, start, opd) in [(from_area, from, &o[0]), (to_area, to, &o[1])] {
            if start + bytes > area.size() {
                return Err(err(
                    "E855",
                    opd.span,
                    format!(
                        "`{}` with N = {n} goes past the end of {}",
                        ins.mnemonic,
                        area.letter()
                    ),
                ));
            }
        }
        Ok((0..bytes)
            .map(|k| {
                at.assign(
                    at.index(to_area.image(), to + k),
                    at.index(from_area.image(), from + k),
                )
            })
            .collect())
    }
}

/// `IF divisor <> 0 THEN store END_IF`, and SM1.3 (divide by zero) set to
/// whether the divisor is 0; OUT is left as it was then.
fn divide(at: At, divisor: Expr, store: Vec<Stmt>) -> Vec<Stmt> {
    let zero = at.bin(BinaryOp::Eq, divisor.clone(), at.int(0));
    vec![
        at.assign(at.bit(at.index(Area::Sm.image(), 1), 3), zero),
        at.when(at.bin(BinaryOp::Ne, divisor, at.int(0)), store),
    ]
}

/// The area and address of a memory operand of width `w`.
fn mem_of(ins: &Instr, o: &Opd, w: Width) -> Result<(Area, u32), Diagnostic> {
    match o.op {
        Operand::Mem { area, width, addr } if width == w => Ok((area, addr)),
        _ => Err(view_error(
            ins,
            o,
            ViewError::Kind(match w {
                Width::B => "a byte operand (VB, IB, QB, MB, SMB)",
                Width::W => "a word operand (VW, IW, QW, MW, SMW)",
                Width::D => "a double-word operand (VD, ID, QD, MD, SMD)",
            }),
        )),
    }
}

/// A count operand: a constant from 1 to 255.
fn count(ins: &Instr, o: &Opd) -> Result<u32, Diagnostic> {
    match o.op {
        Operand::Const(n) if (1..=255).contains(&n) => Ok(n as u32),
        _ => Err(err(
            "E856",
            o.span,
            format!(
                "`{}`: N must be a constant from 1 to 255, found `{}`",
                ins.mnemonic, o.text
            ),
        )),
    }
}

/// A subroutine or label number: `3`, `K3`, `SBR_3`, `SBR3`.
pub(super) fn routine_number(text: &str) -> Option<u32> {
    let t = text.trim().to_ascii_uppercase();
    let t = t
        .strip_prefix("SBR_")
        .or_else(|| t.strip_prefix("SBR"))
        .unwrap_or(&t);
    let v = parse_const(t)?;
    u32::try_from(v).ok()
}

fn operand_error(ins: &Instr, w: &Word, e: OperandError) -> Diagnostic {
    match e {
        OperandError::NotAnOperand => err(
            "E853",
            w.span,
            format!("`{}`: `{}` is not an S7-200 operand", ins.mnemonic, w.text),
        ),
        OperandError::Unsupported(what) => err(
            "E861",
            w.span,
            format!(
                "`{}`: `{}` uses {what}, which plcrun does not support",
                ins.mnemonic, w.text
            ),
        ),
        OperandError::OutOfRange(t) => err(
            "E855",
            w.span,
            format!("`{}`: `{t}` is outside its memory area", ins.mnemonic),
        ),
    }
}

fn view_error(ins: &Instr, o: &Opd, e: ViewError) -> Diagnostic {
    match e {
        ViewError::Kind(what) => err(
            "E854",
            o.span,
            format!("`{}`: `{}` must be {what}", ins.mnemonic, o.text),
        ),
        ViewError::ConstRange(v, w) => err(
            "E856",
            o.span,
            format!(
                "`{}`: the constant {v} does not fit a {}",
                ins.mnemonic,
                bits_type(w)
            ),
        ),
    }
}

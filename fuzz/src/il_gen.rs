//! A structure-aware generator of Instruction List programs that
//! type-check by construction, driven by `arbitrary` bytes (the IL
//! counterpart of [`super::st_gen`]; every byte string gives a program).
//!
//! The program is a FUNCTION, a FUNCTION_BLOCK and a PROGRAM, all three
//! written in IL. The generator tracks the type of the current result
//! (CR) through every line, so each operator gets an operand of the CR's
//! type: chains of `LD`/`LDN`, arithmetic (`ADD`...`MOD`), Boolean
//! operators with and without `N` (`ANDN`, `ORN`: the `AndN`/`OrN`
//! fusions), comparisons turning the CR into a BOOL, deferred operations
//! `OP( ... )` nested, `NOT`, function calls with the CR as first argument
//! (conversions, `ABS`, `MAX`, `LIMIT`, `SEL`, the user function) and in
//! formal form, stores (`ST`, `STN`, `S`, `R`, into variables and array
//! elements), forward conditional jumps (`JMPC`/`JMPCN` over a block, an
//! IF/ELSE made of two jumps), counted loops closed by a backward `JMPC`
//! (bounded: the counter is written only by its loop), `CAL`/`CALC`/
//! `CALCN` of timers, counters, edge detectors, bistables and the user
//! block with `=>` outputs, the function block input operators (`IN`,
//! `PT`, `CU`, `CD`, `PV`, `R`, `S1`, `R1`, `CLK`, `LD` on a down
//! counter), and `RETC`/`RETCN` in the FUNCTION and the FUNCTION_BLOCK.
//!
//! An untyped literal in the CR is never combined with another literal,
//! so constant folding cannot overflow a type; divisions by a variable
//! and narrowing conversions may fault at run time, the same way in both
//! builds of the differential check.
//!
//! Shared by the `gen_il_diff` fuzz target and `tests/fuzz_smoke.rs`.

use super::st_gen::{Array, GenProgram, PROGRAM_ARRAYS, PROGRAM_WRITES, Ty};
use arbitrary::{Result, Unstructured};

/// Most statements in one list, most nesting of blocks and loops, of
/// deferred operations and of operators in one chain.
const MAX_STMTS: usize = 5;
const MAX_NEST: u32 = 3;
const MAX_DEFER: u32 = 2;
const MAX_OPS: usize = 4;

/// The PROGRAM's inputs: name and type.
const INPUTS: [(&str, Ty); 5] = [
    ("ib0", Ty::Bool),
    ("ib1", Ty::Bool),
    ("ii0", Ty::Int),
    ("id0", Ty::Dint),
    ("ir0", Ty::Real),
];

/// The numeric types of the generator.
const NUMERIC: [Ty; 4] = [Ty::Int, Ty::Dint, Ty::Real, Ty::Lreal];

const FUNCTION_HEAD: &str = "FUNCTION IlMix : DINT
VAR_INPUT a : DINT; b : INT; c : BOOL; END_VAR
VAR t : DINT; u : INT; v : BOOL; END_VAR
";

const FB_HEAD: &str = "FUNCTION_BLOCK IlAcc
VAR_INPUT x : INT; y : BOOL; END_VAR
VAR_OUTPUT total : DINT; flag : BOOL; END_VAR
VAR
  n : INT; m : DINT; q : REAL; w0, w1, w2 : DINT;
  buf : ARRAY[0..7] OF INT; hits : ARRAY[1..8] OF BOOL;
END_VAR
";

const PROGRAM_HEAD: &str = "PROGRAM GenIl
VAR_INPUT ib0, ib1 : BOOL; ii0 : INT; id0 : DINT; ir0 : REAL; END_VAR
VAR_OUTPUT ob0 : BOOL; oi0 : INT; od0 : DINT; END_VAR
VAR
  xb0, xb1, xb2 : BOOL; xi0, xi1, xi2 : INT; xd0, xd1, xd2 : DINT;
  xr0, xr1 : REAL; xl0, xl1 : LREAL; et0 : TIME;
  ab : ARRAY[1..10] OF BOOL; ai : ARRAY[0..9] OF INT;
  ad : ARRAY[-3..6] OF DINT; ar : ARRAY[1..8] OF REAL;
  w0, w1, w2 : DINT;
  t0 : TON; t1 : TOF; p0 : TP; c0 : CTU; d0 : CTD; e0 : R_TRIG; f0 : F_TRIG;
  s0 : SR; r0 : RS; acc0, acc1 : IlAcc;
END_VAR
";

/// What one POU body may use.
#[derive(Debug, Clone)]
struct Scope {
    /// Readable scalars by type.
    read: Vec<(Ty, &'static str)>,
    /// Writable scalars by type.
    write: Vec<(Ty, &'static str)>,
    arrays: Vec<Array>,
    /// Loop counters (DINT) by loop depth.
    counters: Vec<&'static str>,
    /// Whether the PROGRAM's blocks and the user FUNCTION are here.
    blocks: bool,
    /// Whether `RETC`/`RETCN` may end the body early.
    returns: bool,
}

/// Generates one IL program and its input schedule from `u`.
pub fn generate(u: &mut Unstructured<'_>) -> Result<GenProgram> {
    let mut g = Gen {
        u,
        out: String::new(),
        labels: 0,
        depth: 0,
        loop_arrays: Vec::new(),
    };
    g.out.push_str(FUNCTION_HEAD);
    let f = function_scope();
    g.stmts(&f, 1)?;
    // The result is always written last, from a chain of its type.
    g.chain(Ty::Dint, &f, 0)?;
    g.line(1, "ST IlMix");
    g.out.push_str("END_FUNCTION\n\n");
    g.out.push_str(FB_HEAD);
    g.stmts(&fb_scope(), 1)?;
    g.out.push_str("END_FUNCTION_BLOCK\n\n");
    g.out.push_str(PROGRAM_HEAD);
    let p = program_scope();
    g.stmts(&p, 1)?;
    // A final store, so that a label is never the body's last line.
    g.store(&p, 1)?;
    g.out.push_str("END_PROGRAM\n");
    let n = g.u.int_in_range(1..=6)?;
    let mut cycles = Vec::with_capacity(n);
    for _ in 0..n {
        let mut writes = Vec::new();
        for (name, ty) in INPUTS {
            if g.u.ratio(1, 2)? {
                writes.push((name.to_string(), g.literal(ty)?));
            }
        }
        cycles.push(writes);
    }
    Ok(GenProgram {
        source: g.out,
        cycles,
    })
}

fn function_scope() -> Scope {
    let write = vec![(Ty::Dint, "t"), (Ty::Int, "u"), (Ty::Bool, "v")];
    let mut read = vec![(Ty::Dint, "a"), (Ty::Int, "b"), (Ty::Bool, "c")];
    read.extend(write.iter().copied());
    Scope {
        read,
        write,
        arrays: Vec::new(),
        counters: Vec::new(),
        blocks: false,
        returns: true,
    }
}

fn fb_scope() -> Scope {
    let write = vec![
        (Ty::Dint, "total"),
        (Ty::Bool, "flag"),
        (Ty::Int, "n"),
        (Ty::Dint, "m"),
        (Ty::Real, "q"),
    ];
    let mut read = vec![(Ty::Int, "x"), (Ty::Bool, "y")];
    read.extend(write.iter().copied());
    Scope {
        read,
        write,
        arrays: vec![
            Array {
                name: "buf",
                ty: Ty::Int,
                lo: 0,
                len: 8,
            },
            Array {
                name: "hits",
                ty: Ty::Bool,
                lo: 1,
                len: 8,
            },
        ],
        counters: vec!["w0", "w1", "w2"],
        blocks: false,
        returns: true,
    }
}

fn program_scope() -> Scope {
    let write = PROGRAM_WRITES.to_vec();
    let mut read: Vec<(Ty, &'static str)> = INPUTS.iter().map(|(n, t)| (*t, *n)).collect();
    read.extend(write.iter().copied());
    read.extend([
        (Ty::Bool, "t0.Q"),
        (Ty::Bool, "t1.Q"),
        (Ty::Bool, "p0.Q"),
        (Ty::Bool, "c0.Q"),
        (Ty::Int, "c0.CV"),
        (Ty::Bool, "d0.Q"),
        (Ty::Int, "d0.CV"),
        (Ty::Bool, "e0.Q"),
        (Ty::Bool, "f0.Q"),
        (Ty::Bool, "s0.Q1"),
        (Ty::Bool, "r0.Q1"),
        (Ty::Dint, "acc0.total"),
        (Ty::Bool, "acc1.flag"),
    ]);
    Scope {
        read,
        write,
        arrays: PROGRAM_ARRAYS.to_vec(),
        counters: vec!["w0", "w1", "w2"],
        blocks: true,
        returns: false,
    }
}

/// The generator's state: the bytes, the text so far, the next label
/// number and the current loop depth (which picks the loop counter, so
/// nested loops never share one).
struct Gen<'a, 'b> {
    u: &'a mut Unstructured<'b>,
    out: String,
    labels: u32,
    depth: usize,
    /// The array each open loop walks, innermost last.
    loop_arrays: Vec<Option<&'static str>>,
}

/// Whether the CR holds an untyped literal (`LD 5`): its next operand must
/// not be a literal too (the pair would be folded at compile time).
type Literal = bool;

impl Gen<'_, '_> {
    fn line(&mut self, nest: u32, text: &str) {
        for _ in 0..nest {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn label(&mut self) -> String {
        self.labels += 1;
        format!("L{}", self.labels)
    }

    fn stmts(&mut self, s: &Scope, nest: u32) -> Result<()> {
        let n = self.u.int_in_range(1..=MAX_STMTS)?;
        for _ in 0..n {
            if self.u.is_empty() {
                break;
            }
            self.stmt(s, nest)?;
        }
        Ok(())
    }

    /// One statement: a group of lines that starts with a load (so the
    /// CR's type never depends on the path that reached it).
    fn stmt(&mut self, s: &Scope, nest: u32) -> Result<()> {
        let deep = nest > MAX_NEST;
        match self.u.int_in_range(0..=13)? {
            0..=3 => self.store(s, nest),
            4 => self.store_elem(s, nest),
            5 if !deep => self.skip_block(s, nest),
            6 if !deep => self.if_else(s, nest),
            7 | 8 if !deep && self.depth < s.counters.len() => self.counted_loop(s, nest),
            9 | 10 if s.blocks => self.block_call(s, nest),
            11 if s.blocks => self.fb_input_operator(s, nest),
            12 if s.returns => {
                self.chain(Ty::Bool, s, 0)?;
                let op = *self.u.choose(&["RETC", "RETCN"])?;
                self.line(nest, op);
                Ok(())
            }
            _ => self.store(s, nest),
        }
    }

    /// A chain of some type stored into a variable of that type (a BOOL
    /// with `ST`, `STN`, `S` or `R`).
    fn store(&mut self, s: &Scope, nest: u32) -> Result<()> {
        let (ty, name) = *self.u.choose(&s.write)?;
        self.chain_at(ty, s, 0, nest)?;
        let op = if ty == Ty::Bool {
            *self.u.choose(&["ST", "ST", "STN", "S", "R"])?
        } else {
            "ST"
        };
        self.line(nest, &format!("{op} {name}"));
        Ok(())
    }

    fn store_elem(&mut self, s: &Scope, nest: u32) -> Result<()> {
        if s.arrays.is_empty() {
            return self.store(s, nest);
        }
        let a = *self.u.choose(&s.arrays)?;
        self.chain_at(a.ty, s, 0, nest)?;
        let idx = self.index(&a, s)?;
        self.line(nest, &format!("ST {}[{idx}]", a.name));
        Ok(())
    }

    /// `<BOOL> JMPC L` over a block, then `L:`.
    fn skip_block(&mut self, s: &Scope, nest: u32) -> Result<()> {
        self.chain_at(Ty::Bool, s, 0, nest)?;
        let l = self.label();
        let op = *self.u.choose(&["JMPC", "JMPCN"])?;
        self.line(nest, &format!("{op} {l}"));
        self.stmts(s, nest + 1)?;
        self.line(nest, &format!("{l}:"));
        Ok(())
    }

    /// An IF/ELSE: `JMPCN else`, the THEN block, `JMP end`, `else:`, the
    /// ELSE block, `end:`.
    fn if_else(&mut self, s: &Scope, nest: u32) -> Result<()> {
        self.chain_at(Ty::Bool, s, 0, nest)?;
        let (otherwise, end) = (self.label(), self.label());
        self.line(nest, &format!("JMPCN {otherwise}"));
        self.stmts(s, nest + 1)?;
        self.line(nest + 1, &format!("JMP {end}"));
        self.line(nest, &format!("{otherwise}:"));
        self.stmts(s, nest + 1)?;
        self.line(nest, &format!("{end}:"));
        Ok(())
    }

    /// `LD lo ST w`, `top:` body, `LD w ADD k ST w LE hi JMPC top`: at
    /// most a dozen rounds, the counter written by its loop only; the body
    /// may leave through a forward jump past the loop.
    fn counted_loop(&mut self, s: &Scope, nest: u32) -> Result<()> {
        let w = s.counters[self.depth];
        let a = if s.arrays.is_empty() {
            None
        } else {
            Some(*self.u.choose(&s.arrays)?)
        };
        let (lo, hi) = match &a {
            Some(a) => {
                // One loop in eight runs one past the end (a fault).
                let past = i64::from(self.u.ratio(1, 8)?);
                (
                    a.lo,
                    a.lo + a.len - 1 - self.u.int_in_range(0i64..=2)? + past,
                )
            }
            None => (0, 4),
        };
        let step = self.u.int_in_range(1i64..=3)?;
        let (top, exit) = (self.label(), self.label());
        self.line(nest, &format!("LD {}", lit_int(lo)));
        self.line(nest, &format!("ST {w}"));
        self.line(nest, &format!("{top}:"));
        self.depth += 1;
        self.loop_arrays.push(a.map(|a| a.name));
        if self.u.arbitrary()? {
            self.stmts(s, nest + 1)?;
        }
        if let Some(a) = &a {
            // An element store indexed by the counter (may run one past
            // the end: a fault, the same in both builds).
            self.chain_at(a.ty, s, 0, nest + 1)?;
            self.line(nest + 1, &format!("ST {}[{w}]", a.name));
        }
        if self.u.ratio(1, 4)? {
            self.chain_at(Ty::Bool, s, 0, nest + 1)?;
            self.line(nest + 1, &format!("JMPC {exit}"));
        }
        self.depth -= 1;
        self.loop_arrays.pop();
        for text in [
            format!("LD {w}"),
            format!("ADD {step}"),
            format!("ST {w}"),
            format!("LE {}", lit_int(hi)),
            format!("JMPC {top}"),
        ] {
            self.line(nest + 1, &text);
        }
        self.line(nest, &format!("{exit}:"));
        Ok(())
    }

    /// `CAL`, `CALC` or `CALCN` of one of the PROGRAM's blocks.
    fn block_call(&mut self, s: &Scope, nest: u32) -> Result<()> {
        let call = match self.u.int_in_range(0..=2)? {
            0 => "CAL".to_string(),
            _ => {
                self.chain_at(Ty::Bool, s, 0, nest)?;
                (*self.u.choose(&["CALC", "CALCN"])?).to_string()
            }
        };
        let b1 = self.bool_operand(s)?;
        let b2 = self.bool_operand(s)?;
        let args = match self.u.int_in_range(0..=8)? {
            0..=2 => {
                let inst = *self.u.choose(&["t0", "t1", "p0"])?;
                let ms = self.u.int_in_range(0..=40)?;
                let out = if self.u.arbitrary()? {
                    let q = self.bool_target(s)?;
                    format!(", Q => {q}, ET => et0")
                } else {
                    String::new()
                };
                format!("{inst}(IN := {b1}, PT := T#{ms}ms{out})")
            }
            3 => {
                let pv = self.operand(Ty::Int, s, false)?;
                let out = if self.u.arbitrary()? {
                    ", CV => xi2".to_string()
                } else {
                    String::new()
                };
                format!("c0(CU := {b1}, R := {b2}, PV := {pv}{out})")
            }
            4 => {
                let pv = self.u.int_in_range(0..=6)?;
                format!("d0(CD := {b1}, LD := {b2}, PV := {pv})")
            }
            5 => format!("{}(CLK := {b1})", self.u.choose(&["e0", "f0"])?),
            6 => format!("s0(S1 := {b1}, R := {b2})"),
            7 => format!("r0(S := {b1}, R1 := {b2})"),
            _ => {
                let inst = *self.u.choose(&["acc0", "acc1"])?;
                let x = self.operand(Ty::Int, s, false)?;
                let out = if self.u.arbitrary()? {
                    ", total => xd2".to_string()
                } else {
                    String::new()
                };
                format!("{inst}(x := {x}, y := {b1}{out})")
            }
        };
        self.line(nest, &format!("{call} {args}"));
        Ok(())
    }

    /// A function block input operator (IEC Table 53): the CR stored into
    /// the input and the instance called.
    fn fb_input_operator(&mut self, s: &Scope, nest: u32) -> Result<()> {
        let (ty, op, inst) = *self.u.choose(&[
            (Ty::Bool, "IN", "t0"),
            (Ty::Bool, "IN", "t1"),
            (Ty::Bool, "IN", "p0"),
            (Ty::Bool, "CU", "c0"),
            (Ty::Bool, "R", "c0"),
            (Ty::Int, "PV", "c0"),
            (Ty::Bool, "CD", "d0"),
            (Ty::Bool, "LD", "d0"),
            (Ty::Int, "PV", "d0"),
            (Ty::Bool, "CLK", "e0"),
            (Ty::Bool, "CLK", "f0"),
            (Ty::Bool, "S1", "s0"),
            (Ty::Bool, "R", "s0"),
            (Ty::Bool, "S", "r0"),
            (Ty::Bool, "R1", "r0"),
        ])?;
        if op == "PV" && self.u.arbitrary()? {
            let pv = self.u.int_in_range(0..=6)?;
            self.line(nest, &format!("LD INT#{pv}"));
        } else {
            self.chain_at(ty, s, 0, nest)?;
        }
        self.line(nest, &format!("{op} {inst}"));
        if self.u.arbitrary()? {
            let ms = self.u.int_in_range(0..=30)?;
            self.line(nest, &format!("LD T#{ms}ms"));
            let timer = *self.u.choose(&["t0", "t1", "p0"])?;
            self.line(nest, &format!("PT {timer}"));
        }
        Ok(())
    }

    fn chain_at(&mut self, ty: Ty, s: &Scope, defer: u32, nest: u32) -> Result<()> {
        let mut lines = String::new();
        std::mem::swap(&mut lines, &mut self.out);
        let r = self.chain(ty, s, defer);
        std::mem::swap(&mut lines, &mut self.out);
        for l in lines.lines() {
            self.line(nest, l.trim_start());
        }
        r
    }

    /// Lines leaving a CR of type `ty` (unindented; [`Self::chain_at`]
    /// indents them).
    fn chain(&mut self, ty: Ty, s: &Scope, defer: u32) -> Result<()> {
        let n = self.u.int_in_range(0..=MAX_OPS)?;
        // An untyped literal left in the CR would take the type of a jump
        // at the next label (`LD 5`, `ST x`, `L:` reached by a JMPC gives
        // 5 the type BOOL, refused): a load that ends a chain is typed.
        let lit = self.start(ty, s, defer, n > 0)?;
        self.ops(ty, s, defer, lit, n)
    }

    /// The first line(s) of a chain of type `ty`; whether the CR is then
    /// an untyped literal.
    fn start(&mut self, ty: Ty, s: &Scope, defer: u32, untyped: bool) -> Result<Literal> {
        if ty == Ty::Bool {
            return match self.u.int_in_range(0..=3)? {
                0 if defer < MAX_DEFER => {
                    let other = *self.u.choose(&NUMERIC)?;
                    let lit = self.chain_start_plain(other, s, true)?;
                    let n = self.u.int_in_range(0..=MAX_OPS)?;
                    self.ops(other, s, defer + 1, lit, n)?;
                    self.compare(other, s, defer, lit)?;
                    Ok(false)
                }
                1 => {
                    let b = self.bool_operand(s)?;
                    self.line(0, &format!("LDN {b}"));
                    Ok(false)
                }
                _ => self.chain_start_plain(ty, s, untyped),
            };
        }
        match self.u.int_in_range(0..=9)? {
            // A conversion from another numeric type.
            0 if defer < MAX_DEFER => {
                let from = *self.u.choose(&NUMERIC)?;
                if from != ty {
                    self.chain(from, s, defer + 1)?;
                    self.line(0, &format!("{}_TO_{}", from.name(), ty.name()));
                    return Ok(false);
                }
                self.chain_start_plain(ty, s, untyped)
            }
            // MAX/MIN with the CR as first argument.
            1 => {
                let lit = self.chain_start_plain(ty, s, true)?;
                let f = *self.u.choose(&["MAX", "MIN"])?;
                let b = self.operand(ty, s, lit)?;
                self.line(0, &format!("{f} {b}"));
                Ok(false)
            }
            // LIMIT(lo, x, hi): the CR is the lower bound.
            2 if ty != Ty::Bool => {
                let (lo, hi) = (self.u.int_in_range(-20..=0)?, self.u.int_in_range(0..=20)?);
                let x = self.variable(ty, s)?;
                let (lo, hi) = if matches!(ty, Ty::Real | Ty::Lreal) {
                    (format!("{lo}.0"), format!("{hi}.0"))
                } else {
                    (lo.to_string(), hi.to_string())
                };
                self.line(0, &format!("LD {lo}"));
                self.line(0, &format!("LIMIT {x}, {hi}"));
                Ok(false)
            }
            // SEL(g, a, b): the CR is the selector.
            3 => {
                let g = self.bool_operand(s)?;
                let a = self.variable(ty, s)?;
                let b = self.operand(ty, s, false)?;
                self.line(0, &format!("LD {g}"));
                self.line(0, &format!("SEL {a}, {b}"));
                Ok(false)
            }
            // The user function, with the CR first or in formal form.
            4 if ty == Ty::Dint && s.blocks && defer < MAX_DEFER => {
                let b = self.operand(Ty::Int, s, false)?;
                let c = self.bool_operand(s)?;
                if self.u.arbitrary()? {
                    self.chain(Ty::Dint, s, defer + 1)?;
                    self.line(0, &format!("IlMix {b}, {c}"));
                } else {
                    // The CR is not an argument of a formal call; a load
                    // before it keeps a body from starting with the call
                    // (a body is IL when its first line is an operator).
                    let a = self.operand(Ty::Dint, s, false)?;
                    self.line(0, "LD 0");
                    self.line(0, &format!("IlMix(a := {a}, b := {b}, c := {c})"));
                }
                Ok(false)
            }
            5 => {
                let lit = self.chain_start_plain(ty, s, untyped)?;
                self.line(0, "ABS");
                Ok(lit)
            }
            _ => self.chain_start_plain(ty, s, untyped),
        }
    }

    /// `LD operand`; whether the operand is an untyped literal (a
    /// literal is written with its type unless `untyped`).
    fn chain_start_plain(&mut self, ty: Ty, s: &Scope, untyped: bool) -> Result<Literal> {
        if self.u.ratio(1, 5)? {
            let l = self.literal(ty)?;
            if untyped || ty == Ty::Bool {
                self.line(0, &format!("LD {l}"));
                return Ok(ty != Ty::Bool);
            }
            self.line(0, &format!("LD {}#{l}", ty.name()));
            return Ok(false);
        }
        let v = self.operand(ty, s, true)?;
        self.line(0, &format!("LD {v}"));
        Ok(false)
    }

    /// `n` operators keeping the CR's type `ty`.
    fn ops(&mut self, ty: Ty, s: &Scope, defer: u32, mut lit: Literal, n: usize) -> Result<()> {
        for _ in 0..n {
            if self.u.is_empty() {
                break;
            }
            let op = self.operator(ty)?;
            let division = matches!(op, "DIV" | "MOD");
            if division && self.u.ratio(9, 10)? {
                // Mostly a divisor that cannot be zero (a division by zero
                // ends the run: the rest of the program goes untested).
                let d = *self.u.choose(&[1i64, 2, 3, 7, -5])?;
                let d = match ty {
                    Ty::Real | Ty::Lreal => format!("{d}.0"),
                    _ => d.to_string(),
                };
                let d = if lit { format!("{}#{d}", ty.name()) } else { d };
                self.line(0, &format!("{op} {d}"));
            } else if !division && defer < MAX_DEFER && self.u.ratio(1, 5)? {
                // `OP(` with the operand on the same line or a new load.
                if self.u.arbitrary()? {
                    let first = self.operand(ty, s, true)?;
                    self.line(0, &format!("{op}( {first}"));
                    let n = self.u.int_in_range(0..=MAX_OPS)?;
                    self.ops(ty, s, defer + 1, false, n)?;
                } else {
                    self.line(0, &format!("{op}("));
                    self.chain(ty, s, defer + 1)?;
                }
                self.line(0, ")");
            } else if ty == Ty::Bool && self.u.ratio(1, 6)? {
                self.line(0, "NOT");
            } else {
                let b = self.operand(ty, s, lit)?;
                self.line(0, &format!("{op} {b}"));
            }
            lit = false;
        }
        Ok(())
    }

    /// An operator of type `ty` to type `ty`.
    fn operator(&mut self, ty: Ty) -> Result<&'static str> {
        Ok(match ty {
            Ty::Bool => *self
                .u
                .choose(&["AND", "ANDN", "OR", "ORN", "XOR", "XORN", "&", "&N"])?,
            Ty::Int | Ty::Dint => *self
                .u
                .choose(&["ADD", "SUB", "MUL", "ADD", "SUB", "DIV", "MOD"])?,
            Ty::Real | Ty::Lreal => *self.u.choose(&["ADD", "SUB", "MUL", "ADD", "DIV"])?,
        })
    }

    /// A comparison turning a CR of type `ty` into a BOOL, sometimes
    /// deferred (`GT( ... )`).
    fn compare(&mut self, ty: Ty, s: &Scope, defer: u32, lit: Literal) -> Result<()> {
        let op = *self.u.choose(&["GT", "GE", "EQ", "NE", "LE", "LT"])?;
        if defer < MAX_DEFER && self.u.ratio(1, 4)? {
            self.line(0, &format!("{op}("));
            self.chain(ty, s, defer + 1)?;
            self.line(0, ")");
        } else {
            let b = self.operand(ty, s, lit)?;
            self.line(0, &format!("{op} {b}"));
        }
        Ok(())
    }

    /// An operand of type `ty`: a variable, an element or a literal
    /// (never a literal when `no_literal`).
    fn operand(&mut self, ty: Ty, s: &Scope, no_literal: bool) -> Result<String> {
        let arrays: Vec<Array> = s.arrays.iter().filter(|a| a.ty == ty).copied().collect();
        if !arrays.is_empty() && self.u.ratio(1, 4)? {
            let a = *self.u.choose(&arrays)?;
            let idx = self.index(&a, s)?;
            return Ok(format!("{}[{idx}]", a.name));
        }
        if !no_literal && self.u.ratio(1, 3)? {
            return self.literal(ty);
        }
        self.variable(ty, s)
    }

    fn variable(&mut self, ty: Ty, s: &Scope) -> Result<String> {
        let vars: Vec<&str> = s
            .read
            .iter()
            .filter(|(t, _)| *t == ty)
            .map(|(_, n)| *n)
            .collect();
        if vars.is_empty() {
            // A typed literal is never folded with an untyped one.
            return Ok(format!("{}#{}", ty.name(), self.literal(ty)?));
        }
        Ok(self.u.choose(&vars)?.to_string())
    }

    fn bool_operand(&mut self, s: &Scope) -> Result<String> {
        self.operand(Ty::Bool, s, false)
    }

    fn bool_target(&mut self, s: &Scope) -> Result<&'static str> {
        let bools: Vec<&str> = s
            .write
            .iter()
            .filter(|(t, _)| *t == Ty::Bool)
            .map(|(_, n)| *n)
            .collect();
        Ok(*self.u.choose(&bools)?)
    }

    /// An index into `a`: the innermost loop counter when that loop walks
    /// `a`, a constant in range, or an INT variable (folded into the
    /// range, or as it is: may fault).
    fn index(&mut self, a: &Array, s: &Scope) -> Result<String> {
        Ok(match self.u.int_in_range(0..=9)? {
            // The innermost counter, in range of the array it walks.
            0..=3 if self.loop_arrays.last().is_some_and(|l| *l == Some(a.name)) => {
                s.counters[self.depth - 1].to_string()
            }
            4 => {
                let ints: Vec<&str> = s
                    .read
                    .iter()
                    .filter(|(t, n)| *t == Ty::Int && !n.contains('.'))
                    .map(|(_, n)| *n)
                    .collect();
                match self.u.choose(&ints) {
                    // Folded into the range, or as it is (may fault).
                    Ok(v) if self.u.ratio(3, 4)? => {
                        format!("{} + ABS({v} MOD {})", a.lo, a.len)
                    }
                    Ok(v) => v.to_string(),
                    Err(_) => lit_int(a.lo),
                }
            }
            _ => lit_int(self.u.int_in_range(a.lo..=a.lo + a.len - 1)?),
        })
    }

    fn literal(&mut self, ty: Ty) -> Result<String> {
        Ok(match ty {
            Ty::Bool => (if self.u.arbitrary()? { "TRUE" } else { "FALSE" }).into(),
            Ty::Int => {
                let v: i16 = if self.u.ratio(9, 10)? {
                    self.u.int_in_range(-20..=20)?
                } else {
                    self.u.arbitrary()?
                };
                v.to_string()
            }
            Ty::Dint => {
                let v: i32 = if self.u.ratio(9, 10)? {
                    self.u.int_in_range(-100..=100)?
                } else {
                    self.u.arbitrary()?
                };
                v.to_string()
            }
            Ty::Real | Ty::Lreal => {
                let q = self.u.int_in_range(-400i32..=400)?;
                format!("{:.2}", f64::from(q) / 4.0)
            }
        })
    }
}

/// An integer literal as IL writes it.
fn lit_int(v: i64) -> String {
    v.to_string()
}

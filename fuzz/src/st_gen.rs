//! A structure-aware generator of Structured Text programs that type-check
//! by construction, driven by `arbitrary` bytes: every byte string gives a
//! program (running out of bytes only makes it smaller). The programs are
//! shaped so that the executor's fused superinstructions and the bounds
//! proofs are reached: FOR loops with constant bounds over arrays (bounds
//! proofs, the fill idiom, `ForScan`), counted WHILE loops storing into an
//! array (`AddBr`, `StoreStep`), comparisons in conditions (compare-and-
//! branch), `a AND NOT b`, `x * y + c` on reals, calls of a user FUNCTION,
//! a user FUNCTION_BLOCK and standard blocks. Loops are bounded by
//! construction, so a run always ends; out-of-range indexes, divisions by
//! zero and narrowing conversions may fault, the same way in both builds.
//!
//! Shared by the `gen_diff` fuzz target and `tests/fuzz_smoke.rs`.

use arbitrary::{Result, Unstructured};
use std::fmt::Write;

/// The elementary types the generator uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ty {
    /// BOOL.
    Bool,
    /// INT (16 bits, signed).
    Int,
    /// DINT (32 bits, signed).
    Dint,
    /// REAL (32-bit float).
    Real,
    /// LREAL (64-bit float).
    Lreal,
}

impl Ty {
    const ALL: [Ty; 5] = [Ty::Bool, Ty::Int, Ty::Dint, Ty::Real, Ty::Lreal];

    /// The IEC name of the type.
    pub fn name(self) -> &'static str {
        match self {
            Ty::Bool => "BOOL",
            Ty::Int => "INT",
            Ty::Dint => "DINT",
            Ty::Real => "REAL",
            Ty::Lreal => "LREAL",
        }
    }
}

/// One array of a scope: `name : ARRAY[lo..lo+len-1] OF ty`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Array {
    pub(crate) name: &'static str,
    pub(crate) ty: Ty,
    pub(crate) lo: i64,
    pub(crate) len: i64,
}

/// The scalars every generated PROGRAM declares and may write (ST and IL
/// alike).
pub(crate) const PROGRAM_WRITES: [(Ty, &str); 16] = [
    (Ty::Bool, "xb0"),
    (Ty::Bool, "xb1"),
    (Ty::Bool, "xb2"),
    (Ty::Bool, "ob0"),
    (Ty::Int, "xi0"),
    (Ty::Int, "xi1"),
    (Ty::Int, "xi2"),
    (Ty::Int, "oi0"),
    (Ty::Dint, "xd0"),
    (Ty::Dint, "xd1"),
    (Ty::Dint, "xd2"),
    (Ty::Dint, "od0"),
    (Ty::Real, "xr0"),
    (Ty::Real, "xr1"),
    (Ty::Lreal, "xl0"),
    (Ty::Lreal, "xl1"),
];

/// The arrays every generated PROGRAM declares (ST and IL alike: `ab`,
/// `ai`, `ad`, `ar` of the program's VAR block).
pub(crate) const PROGRAM_ARRAYS: [Array; 4] = [
    Array {
        name: "ab",
        ty: Ty::Bool,
        lo: 1,
        len: 10,
    },
    Array {
        name: "ai",
        ty: Ty::Int,
        lo: 0,
        len: 10,
    },
    Array {
        name: "ad",
        ty: Ty::Dint,
        lo: -3,
        len: 10,
    },
    Array {
        name: "ar",
        ty: Ty::Real,
        lo: 1,
        len: 8,
    },
];

/// The names visible in one POU body.
#[derive(Debug, Clone)]
struct Scope {
    /// Readable scalars by type (inputs first).
    read: Vec<(Ty, String)>,
    /// Writable scalars by type.
    write: Vec<(Ty, String)>,
    arrays: Vec<Array>,
    /// FOR control variables by nesting depth (INT).
    for_vars: Vec<&'static str>,
    /// WHILE/REPEAT counters by nesting depth (DINT).
    counters: Vec<&'static str>,
    /// Whether the PROGRAM's standard and user blocks are here.
    blocks: bool,
}

/// An input written before a cycle: variable name and IEC literal.
pub type InputWrite = (String, String);

/// A generated program and what to feed it.
#[derive(Debug, Clone)]
pub struct GenProgram {
    /// ST source of the FUNCTION, the FUNCTION_BLOCK and the PROGRAM.
    pub source: String,
    /// For each cycle, the inputs to write before it.
    pub cycles: Vec<Vec<InputWrite>>,
}

/// Most statements in one list, most nesting of statements and of
/// expressions: small enough that a program runs in well under a
/// millisecond per cycle.
const MAX_STMTS: usize = 5;
const MAX_DEPTH: u32 = 3;
const MAX_EXPR_DEPTH: u32 = 4;

/// The PROGRAM's inputs: name and type.
const INPUTS: [(&str, Ty); 5] = [
    ("ib0", Ty::Bool),
    ("ib1", Ty::Bool),
    ("ii0", Ty::Int),
    ("id0", Ty::Dint),
    ("ir0", Ty::Real),
];

/// Generates one program and its input schedule from `u`.
pub fn generate(u: &mut Unstructured<'_>) -> Result<GenProgram> {
    let mut g = Gen { u, depth: 0 };
    let mut src = String::new();
    src.push_str(FUNCTION_HEAD);
    let mix = g.expr(Ty::Dint, &function_scope(), 0)?;
    let _ = write!(src, "Mix := {mix};\nEND_FUNCTION\n\n");
    src.push_str(FB_HEAD);
    let fb = fb_scope();
    g.stmts(&fb, &mut src, 1)?;
    src.push_str("END_FUNCTION_BLOCK\n\n");
    src.push_str(PROGRAM_HEAD);
    let prog = program_scope();
    g.stmts(&prog, &mut src, 1)?;
    src.push_str("END_PROGRAM\n");
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
        source: src,
        cycles,
    })
}

const FUNCTION_HEAD: &str = "FUNCTION Mix : DINT
VAR_INPUT a : DINT; b : INT; c : BOOL; END_VAR
";

const FB_HEAD: &str = "FUNCTION_BLOCK Acc
VAR_INPUT x : INT; y : BOOL; END_VAR
VAR_OUTPUT total : DINT; flag : BOOL; END_VAR
VAR
  n : INT; m : DINT; q : REAL; k0, k1, k2 : INT; w0, w1, w2 : DINT;
  buf : ARRAY[0..7] OF INT; hits : ARRAY[1..8] OF BOOL;
END_VAR
";

const PROGRAM_HEAD: &str = "PROGRAM Gen
VAR_INPUT ib0, ib1 : BOOL; ii0 : INT; id0 : DINT; ir0 : REAL; END_VAR
VAR_OUTPUT ob0 : BOOL; oi0 : INT; od0 : DINT; END_VAR
VAR
  xb0, xb1, xb2 : BOOL; xi0, xi1, xi2 : INT; xd0, xd1, xd2 : DINT;
  xr0, xr1 : REAL; xl0, xl1 : LREAL;
  ab : ARRAY[1..10] OF BOOL; ai : ARRAY[0..9] OF INT;
  ad : ARRAY[-3..6] OF DINT; ar : ARRAY[1..8] OF REAL;
  k0, k1, k2 : INT; w0, w1, w2 : DINT;
  t0 : TON; c0 : CTU; e0 : R_TRIG; acc0, acc1 : Acc;
END_VAR
";

fn names(list: &[(Ty, &str)]) -> Vec<(Ty, String)> {
    list.iter().map(|(t, n)| (*t, n.to_string())).collect()
}

fn function_scope() -> Scope {
    Scope {
        read: names(&[(Ty::Dint, "a"), (Ty::Int, "b"), (Ty::Bool, "c")]),
        write: Vec::new(),
        arrays: Vec::new(),
        for_vars: Vec::new(),
        counters: Vec::new(),
        blocks: false,
    }
}

fn fb_scope() -> Scope {
    let write = names(&[
        (Ty::Dint, "total"),
        (Ty::Bool, "flag"),
        (Ty::Int, "n"),
        (Ty::Dint, "m"),
        (Ty::Real, "q"),
    ]);
    let mut read = names(&[(Ty::Int, "x"), (Ty::Bool, "y")]);
    read.extend(write.iter().cloned());
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
        for_vars: vec!["k0", "k1", "k2"],
        counters: vec!["w0", "w1", "w2"],
        blocks: false,
    }
}

fn program_scope() -> Scope {
    let write = names(&PROGRAM_WRITES);
    let mut read: Vec<(Ty, String)> = INPUTS.iter().map(|(n, t)| (*t, n.to_string())).collect();
    read.extend(write.iter().cloned());
    read.extend(names(&[
        (Ty::Bool, "t0.Q"),
        (Ty::Bool, "c0.Q"),
        (Ty::Int, "c0.CV"),
        (Ty::Bool, "e0.Q"),
        (Ty::Dint, "acc0.total"),
        (Ty::Bool, "acc1.flag"),
    ]));
    Scope {
        read,
        write,
        arrays: PROGRAM_ARRAYS.to_vec(),
        for_vars: vec!["k0", "k1", "k2"],
        counters: vec!["w0", "w1", "w2"],
        blocks: true,
    }
}

/// The generator's state: the bytes and the current loop depth (which
/// picks the loop variables, so nested loops never share one).
struct Gen<'a, 'b> {
    u: &'a mut Unstructured<'b>,
    depth: usize,
}

impl Gen<'_, '_> {
    fn stmts(&mut self, s: &Scope, out: &mut String, nest: u32) -> Result<()> {
        let n = self.u.int_in_range(1..=MAX_STMTS)?;
        for _ in 0..n {
            if self.u.is_empty() {
                break;
            }
            self.stmt(s, out, nest)?;
        }
        Ok(())
    }

    fn indent(out: &mut String, nest: u32) {
        for _ in 0..nest {
            out.push_str("  ");
        }
    }

    fn stmt(&mut self, s: &Scope, out: &mut String, nest: u32) -> Result<()> {
        let deep = nest >= MAX_DEPTH;
        let kind = self.u.int_in_range(0..=13)?;
        Self::indent(out, nest);
        match kind {
            0..=3 => self.assign(s, out)?,
            4 => self.assign_elem(s, out)?,
            5 if !deep => self.if_stmt(s, out, nest)?,
            6 if !deep => self.case_stmt(s, out, nest)?,
            7 | 8 if !deep && self.depth < s.for_vars.len() => self.for_loop(s, out, nest)?,
            9 if !deep && self.depth < s.counters.len() => self.while_loop(s, out, nest)?,
            10 if !deep && self.depth < s.counters.len() => self.repeat_loop(s, out, nest)?,
            11 if s.blocks => self.block_call(s, out)?,
            12 if self.depth > 0 => {
                let c = self.expr(Ty::Bool, s, 1)?;
                let _ = writeln!(out, "IF {c} THEN EXIT; END_IF;");
            }
            _ => self.assign(s, out)?,
        }
        Ok(())
    }

    fn assign(&mut self, s: &Scope, out: &mut String) -> Result<()> {
        let (ty, name) = self.u.choose(&s.write)?.clone();
        let e = self.expr(ty, s, 0)?;
        let _ = writeln!(out, "{name} := {e};");
        Ok(())
    }

    fn assign_elem(&mut self, s: &Scope, out: &mut String) -> Result<()> {
        if s.arrays.is_empty() {
            return self.assign(s, out);
        }
        let a = *self.u.choose(&s.arrays)?;
        let idx = self.index(&a, s)?;
        let e = self.expr(a.ty, s, 1)?;
        let _ = writeln!(out, "{}[{idx}] := {e};", a.name);
        Ok(())
    }

    fn if_stmt(&mut self, s: &Scope, out: &mut String, nest: u32) -> Result<()> {
        let c = self.cond(s)?;
        let _ = writeln!(out, "IF {c} THEN");
        self.stmts(s, out, nest + 1)?;
        if self.u.ratio(1, 3)? {
            let c = self.cond(s)?;
            Self::indent(out, nest);
            let _ = writeln!(out, "ELSIF {c} THEN");
            self.stmts(s, out, nest + 1)?;
        }
        if self.u.ratio(1, 2)? {
            Self::indent(out, nest);
            out.push_str("ELSE\n");
            self.stmts(s, out, nest + 1)?;
        }
        Self::indent(out, nest);
        out.push_str("END_IF;\n");
        Ok(())
    }

    /// A condition: often a comparison (fused compare-and-branch) or a
    /// BOOL element, sometimes negated.
    fn cond(&mut self, s: &Scope) -> Result<String> {
        let c = match self.u.int_in_range(0..=3)? {
            0 => {
                let ty = *self.u.choose(&[Ty::Int, Ty::Dint, Ty::Real, Ty::Lreal])?;
                self.compare(ty, s, 1)?
            }
            1 if s.arrays.iter().any(|a| a.ty == Ty::Bool) => {
                let bools: Vec<Array> = s
                    .arrays
                    .iter()
                    .filter(|a| a.ty == Ty::Bool)
                    .cloned()
                    .collect();
                let a = *self.u.choose(&bools)?;
                let idx = self.index(&a, s)?;
                format!("{}[{idx}]", a.name)
            }
            _ => self.expr(Ty::Bool, s, 1)?,
        };
        Ok(if self.u.ratio(1, 4)? {
            format!("NOT ({c})")
        } else {
            c
        })
    }

    fn case_stmt(&mut self, s: &Scope, out: &mut String, nest: u32) -> Result<()> {
        let sel = self.expr(Ty::Int, s, 1)?;
        let _ = writeln!(out, "CASE {sel} OF");
        let arms = self.u.int_in_range(1..=3)?;
        let mut next = self.u.int_in_range(-3i64..=3)?;
        for _ in 0..arms {
            Self::indent(out, nest + 1);
            if self.u.arbitrary()? {
                let hi = next + self.u.int_in_range(1i64..=3)?;
                let _ = writeln!(out, "{next}..{hi}:");
                next = hi + 1;
            } else {
                let _ = writeln!(out, "{next}, {}:", next + 2);
                next += 3;
            }
            self.stmts(s, out, nest + 2)?;
        }
        if self.u.arbitrary()? {
            Self::indent(out, nest + 1);
            out.push_str("ELSE\n");
            self.stmts(s, out, nest + 2)?;
        }
        Self::indent(out, nest);
        out.push_str("END_CASE;\n");
        Ok(())
    }

    /// A FOR loop with constant bounds (the shapes the optimizer knows:
    /// a fill, a scan of a BOOL array, element accesses by the control
    /// variable), sometimes running past an array's bounds.
    fn for_loop(&mut self, s: &Scope, out: &mut String, nest: u32) -> Result<()> {
        let k = s.for_vars[self.depth];
        let a = if s.arrays.is_empty() {
            None
        } else {
            Some(*self.u.choose(&s.arrays)?)
        };
        let (mut lo, mut hi) = match &a {
            Some(a) => (a.lo, a.lo + a.len - 1),
            None => (0, 5),
        };
        if self.u.ratio(1, 3)? {
            lo += self.u.int_in_range(-1i64..=3)?;
            hi -= self.u.int_in_range(-1i64..=3)?;
        }
        let step = *self.u.choose(&[1i64, 1, 1, 2, 3, -1, -2])?;
        if step < 0 {
            std::mem::swap(&mut lo, &mut hi);
        }
        let by = if step == 1 && self.u.arbitrary()? {
            String::new()
        } else {
            format!(" BY {}", lit_int(step))
        };
        let _ = writeln!(out, "FOR {k} := {} TO {}{by} DO", lit_int(lo), lit_int(hi));
        self.depth += 1;
        let shape = self.u.int_in_range(0..=3)?;
        match (&a, shape) {
            // The fill idiom: one store of a constant or a variable.
            (Some(a), 0) => {
                let v = if self.u.arbitrary()? {
                    self.literal(a.ty)?
                } else {
                    self.scalar(a.ty, s)?
                };
                Self::indent(out, nest + 1);
                let _ = writeln!(out, "{}[{k}] := {v};", a.name);
            }
            // A scan: the body starts with a test of a BOOL element.
            (Some(a), 1) if a.ty == Ty::Bool => {
                let not = if self.u.arbitrary()? { "NOT " } else { "" };
                Self::indent(out, nest + 1);
                let _ = writeln!(out, "IF {not}{}[{k}] THEN", a.name);
                self.stmts(s, out, nest + 2)?;
                Self::indent(out, nest + 1);
                out.push_str("END_IF;\n");
            }
            // Element reads and writes by the control variable.
            (Some(a), 2) => {
                let e = self.expr(a.ty, s, 2)?;
                Self::indent(out, nest + 1);
                let _ = writeln!(out, "{}[{k}] := {e};", a.name);
                self.stmts(s, out, nest + 1)?;
            }
            _ => self.stmts(s, out, nest + 1)?,
        }
        if self.u.ratio(1, 8)? {
            Self::indent(out, nest + 1);
            let c = self.expr(Ty::Bool, s, 2)?;
            let _ = writeln!(out, "IF {c} THEN CONTINUE; END_IF;");
            self.stmts(s, out, nest + 1)?;
        }
        self.depth -= 1;
        Self::indent(out, nest);
        out.push_str("END_FOR;\n");
        Ok(())
    }

    /// `w := lo; WHILE w <= hi DO body; w := w + step; END_WHILE;`: the
    /// counted loop whose step and test fuse (and whose store into an
    /// array indexed by `w`, right before the step, fuses with them).
    fn while_loop(&mut self, s: &Scope, out: &mut String, nest: u32) -> Result<()> {
        let w = s.counters[self.depth];
        let a = if s.arrays.is_empty() {
            None
        } else {
            Some(*self.u.choose(&s.arrays)?)
        };
        let (lo, hi) = match &a {
            Some(a) => (a.lo, a.lo + a.len - 1 + self.u.int_in_range(-2i64..=1)?),
            None => (0, 4),
        };
        let step = self.u.int_in_range(1i64..=3)?;
        let _ = writeln!(out, "{w} := {};", lit_int(lo));
        Self::indent(out, nest);
        let _ = writeln!(out, "WHILE {w} <= {} DO", lit_int(hi));
        self.depth += 1;
        if self.u.arbitrary()? {
            self.stmts(s, out, nest + 1)?;
        }
        if let Some(a) = &a {
            let v = self.scalar(a.ty, s)?;
            Self::indent(out, nest + 1);
            let _ = writeln!(out, "{}[{w}] := {v};", a.name);
        }
        self.depth -= 1;
        Self::indent(out, nest + 1);
        let _ = writeln!(out, "{w} := {w} + {step};");
        Self::indent(out, nest);
        out.push_str("END_WHILE;\n");
        Ok(())
    }

    fn repeat_loop(&mut self, s: &Scope, out: &mut String, nest: u32) -> Result<()> {
        let w = s.counters[self.depth];
        let lo = self.u.int_in_range(-3i64..=3)?;
        let hi = lo + self.u.int_in_range(0i64..=6)?;
        let _ = writeln!(out, "{w} := {};", lit_int(lo));
        Self::indent(out, nest);
        out.push_str("REPEAT\n");
        self.depth += 1;
        self.stmts(s, out, nest + 1)?;
        self.depth -= 1;
        Self::indent(out, nest + 1);
        let _ = writeln!(out, "{w} := {w} + 1;");
        Self::indent(out, nest);
        let _ = writeln!(out, "UNTIL {w} > {} END_REPEAT;", lit_int(hi));
        Ok(())
    }

    fn block_call(&mut self, s: &Scope, out: &mut String) -> Result<()> {
        match self.u.int_in_range(0..=4)? {
            0 => {
                let c = self.expr(Ty::Bool, s, 2)?;
                let ms = self.u.int_in_range(0..=50)?;
                let _ = writeln!(out, "t0(IN := {c}, PT := T#{ms}ms);");
            }
            1 => {
                let c = self.expr(Ty::Bool, s, 2)?;
                let r = self.expr(Ty::Bool, s, 2)?;
                let pv = self.u.int_in_range(0..=5)?;
                let _ = writeln!(out, "c0(CU := {c}, R := {r}, PV := {pv});");
            }
            2 => {
                let c = self.expr(Ty::Bool, s, 2)?;
                let _ = writeln!(out, "e0(CLK := {c});");
            }
            n => {
                let x = self.expr(Ty::Int, s, 2)?;
                let y = self.expr(Ty::Bool, s, 2)?;
                let inst = if n == 3 { "acc0" } else { "acc1" };
                let _ = writeln!(out, "{inst}(x := {x}, y := {y});");
            }
        }
        Ok(())
    }

    /// An index into `a`: the innermost loop variable, a constant (in
    /// range or just outside), or any INT expression.
    fn index(&mut self, a: &Array, s: &Scope) -> Result<String> {
        let ints: Vec<&String> = s
            .read
            .iter()
            .filter(|(t, _)| *t == Ty::Int)
            .map(|(_, n)| n)
            .collect();
        Ok(match self.u.int_in_range(0..=5)? {
            0..=2 if self.depth > 0 => s.for_vars[self.depth - 1].to_string(),
            // A variable: folded into the range, or as it is (may fault).
            3 if !ints.is_empty() => {
                let v = self.u.choose(&ints)?.to_string();
                if self.u.ratio(1, 4)? {
                    v
                } else {
                    format!("{} + ABS({v} MOD {})", lit_int(a.lo), a.len)
                }
            }
            // Constant indexes are checked at compile time: in range only.
            _ => lit_int(self.u.int_in_range(a.lo..=a.lo + a.len - 1)?),
        })
    }

    /// A variable (or an array element) of type `ty`, or a literal.
    fn scalar(&mut self, ty: Ty, s: &Scope) -> Result<String> {
        let vars: Vec<&String> = s
            .read
            .iter()
            .filter(|(t, _)| *t == ty)
            .map(|(_, n)| n)
            .collect();
        if vars.is_empty() || self.u.ratio(1, 5)? {
            return self.literal(ty);
        }
        Ok(self.u.choose(&vars)?.to_string())
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
                lit_int(v.into())
            }
            Ty::Dint => {
                let v: i32 = if self.u.ratio(9, 10)? {
                    self.u.int_in_range(-100..=100)?
                } else {
                    self.u.arbitrary()?
                };
                lit_int(v.into())
            }
            Ty::Real | Ty::Lreal => {
                let q = self.u.int_in_range(-400i32..=400)?;
                let v = f64::from(q) / 4.0;
                let text = if self.u.ratio(1, 8)? {
                    format!("{v:.2}E{}", self.u.int_in_range(-3..=3)?)
                } else {
                    format!("{v:.2}")
                };
                if v < 0.0 { format!("({text})") } else { text }
            }
        })
    }

    fn compare(&mut self, ty: Ty, s: &Scope, depth: u32) -> Result<String> {
        let a = self.expr(ty, s, depth + 1)?;
        let b = if self.u.arbitrary()? {
            self.literal(ty)?
        } else {
            self.expr(ty, s, depth + 1)?
        };
        let op = *self.u.choose(&["<", "<=", ">", ">=", "=", "<>"])?;
        Ok(format!("{a} {op} {b}"))
    }

    /// An expression of type `ty`.
    fn expr(&mut self, ty: Ty, s: &Scope, depth: u32) -> Result<String> {
        if depth >= MAX_EXPR_DEPTH || self.u.ratio(1, 3)? {
            return self.leaf(ty, s);
        }
        let d = depth + 1;
        Ok(match ty {
            Ty::Bool => match self.u.int_in_range(0..=6)? {
                0 => format!("NOT {}", self.leaf(ty, s)?),
                1 => format!("{} AND NOT {}", self.expr(ty, s, d)?, self.leaf(ty, s)?),
                2 => format!("{} OR NOT {}", self.expr(ty, s, d)?, self.leaf(ty, s)?),
                3 => {
                    let other = *self.u.choose(&[Ty::Int, Ty::Dint, Ty::Real, Ty::Lreal])?;
                    format!("({})", self.compare(other, s, d)?)
                }
                _ => {
                    let op = *self.u.choose(&["AND", "OR", "XOR", "=", "<>"])?;
                    format!("({} {op} {})", self.expr(ty, s, d)?, self.expr(ty, s, d)?)
                }
            },
            Ty::Int | Ty::Dint => self.int_expr(ty, s, d)?,
            Ty::Real | Ty::Lreal => self.real_expr(ty, s, d)?,
        })
    }

    fn int_expr(&mut self, ty: Ty, s: &Scope, d: u32) -> Result<String> {
        let (wide, narrow) = if ty == Ty::Int {
            ("INT", "DINT")
        } else {
            ("DINT", "INT")
        };
        Ok(match self.u.int_in_range(0..=9)? {
            0 => format!("ABS({})", self.expr(ty, s, d)?),
            1 => format!("-{}", self.leaf(ty, s)?),
            2 => format!("{narrow}_TO_{wide}({})", self.expr(other_int(ty), s, d)?),
            3 => {
                let src = *self.u.choose(&[Ty::Real, Ty::Lreal])?;
                format!("{}_TO_{wide}({})", src.name(), self.expr(src, s, d)?)
            }
            4 => {
                let f = *self.u.choose(&["MIN", "MAX"])?;
                format!("{f}({}, {})", self.expr(ty, s, d)?, self.expr(ty, s, d)?)
            }
            5 => format!(
                "LIMIT({}, {}, {})",
                self.literal(ty)?,
                self.expr(ty, s, d)?,
                self.literal(ty)?
            ),
            6 => format!(
                "SEL({}, {}, {})",
                self.expr(Ty::Bool, s, d)?,
                self.expr(ty, s, d)?,
                self.expr(ty, s, d)?
            ),
            7 if ty == Ty::Dint && s.blocks => format!(
                "Mix(a := {}, b := {}, c := {})",
                self.expr(Ty::Dint, s, d)?,
                self.expr(Ty::Int, s, d)?,
                self.expr(Ty::Bool, s, d)?
            ),
            8 => {
                let op = *self.u.choose(&["/", "MOD"])?;
                // Mostly a divisor that cannot be zero.
                let b = if self.u.ratio(4, 5)? {
                    lit_int(*self.u.choose(&[1i64, 2, 3, 7, -5])?)
                } else {
                    self.expr(ty, s, d)?
                };
                format!("({} {op} {b})", self.expr(ty, s, d)?)
            }
            _ => {
                let op = *self.u.choose(&["+", "-", "*", "+", "-"])?;
                format!("({} {op} {})", self.expr(ty, s, d)?, self.expr(ty, s, d)?)
            }
        })
    }

    fn real_expr(&mut self, ty: Ty, s: &Scope, d: u32) -> Result<String> {
        Ok(match self.u.int_in_range(0..=6)? {
            // Multiply-add, both operand orders.
            0 => format!(
                "{} * {} + {}",
                self.leaf(ty, s)?,
                self.leaf(ty, s)?,
                self.expr(ty, s, d)?
            ),
            1 => format!(
                "{} + {} * {}",
                self.leaf(ty, s)?,
                self.leaf(ty, s)?,
                self.leaf(ty, s)?
            ),
            2 => {
                let src = *self.u.choose(&[Ty::Int, Ty::Dint])?;
                format!("{}_TO_{}({})", src.name(), ty.name(), self.expr(src, s, d)?)
            }
            3 => {
                let other = if ty == Ty::Real { Ty::Lreal } else { Ty::Real };
                format!(
                    "{}_TO_{}({})",
                    other.name(),
                    ty.name(),
                    self.expr(other, s, d)?
                )
            }
            4 => format!("ABS({})", self.expr(ty, s, d)?),
            _ => {
                let op = *self.u.choose(&["+", "-", "*", "/"])?;
                format!("({} {op} {})", self.expr(ty, s, d)?, self.expr(ty, s, d)?)
            }
        })
    }

    /// A variable, an element of an array of type `ty`, or a literal.
    fn leaf(&mut self, ty: Ty, s: &Scope) -> Result<String> {
        let arrays: Vec<Array> = s.arrays.iter().filter(|a| a.ty == ty).cloned().collect();
        if !arrays.is_empty() && self.u.ratio(1, 4)? {
            let a = *self.u.choose(&arrays)?;
            let idx = self.index(&a, s)?;
            return Ok(format!("{}[{idx}]", a.name));
        }
        if self.depth > 0 && ty == Ty::Int && self.u.ratio(1, 4)? {
            return Ok(s.for_vars[self.depth - 1].to_string());
        }
        self.scalar(ty, s)
    }
}

fn other_int(ty: Ty) -> Ty {
    if ty == Ty::Int { Ty::Dint } else { Ty::Int }
}

/// An integer literal, parenthesized when negative.
fn lit_int(v: i64) -> String {
    if v < 0 {
        format!("({v})")
    } else {
        v.to_string()
    }
}

/// Every type the generator knows (for tests that walk them).
pub fn types() -> &'static [Ty] {
    &Ty::ALL
}

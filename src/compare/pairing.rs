//! Which variables the comparison drives and which it compares.
//!
//! Inputs are what both programs read from outside: each program
//! instance's `VAR_INPUT`s and the `%I` located variables. An input of A is
//! paired with B's input of the same name (case-insensitive) or with the
//! one `--map` names. Compared outputs are A's default trace outputs
//! (`VAR_OUTPUT`s and `%Q` variables) that B also traces by default under
//! the same name, plus every `--map` pair that is not an input pair (any
//! readable value: `--map X1.X=X1` compares a step flag with a bit).
//! `--ignore NAME` removes an input (it is then not driven) or an output.

use super::error::{CompareError, Side};
use crate::elementary::ElemType;
use crate::ir::type_table::MemberKind;
use crate::runtime::engine::Plc;
use crate::runtime::plc_value::Value;
use crate::runtime::variables::{VarInfo, VarShape};

/// How a comparison pairs and judges the two programs.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct CompareOptions {
    /// `(A name, B name)` pairs, for inputs and outputs (see [`parse_map`]).
    pub map: Vec<(String, String)>,
    /// Inputs not to drive and outputs not to compare (A's or B's name).
    pub ignore: Vec<String>,
    /// How many cycles B may follow A by (0: equal at every cycle); see
    /// `docs/compare.md` for the exact rule.
    pub lag: u64,
}

/// Parses one `--map` item: `A.x=B.y` or `x=y` (a leading `A.` on the left
/// and `B.` on the right are dropped).
///
/// ```
/// assert_eq!(plcrun::parse_map("A.X1.X=B.X1").unwrap(), ("X1.X".into(), "X1".into()));
/// assert_eq!(plcrun::parse_map("out=Q1").unwrap(), ("out".into(), "Q1".into()));
/// assert!(plcrun::parse_map("nothing").is_err());
/// ```
pub fn parse_map(item: &str) -> Result<(String, String), CompareError> {
    let bad = || CompareError::BadMap {
        item: item.to_string(),
    };
    let (a, b) = item.split_once('=').ok_or_else(bad)?;
    let a = a.trim();
    let b = b.trim();
    let a = a.strip_prefix("A.").unwrap_or(a).trim();
    let b = b.strip_prefix("B.").unwrap_or(b).trim();
    if a.is_empty() || b.is_empty() {
        return Err(bad());
    }
    Ok((a.to_string(), b.to_string()))
}

/// What values the random generator gives an input.
#[derive(Debug, Clone, PartialEq)]
pub enum InputKind {
    /// BOOL: every change flips it.
    Bool,
    /// An integer, bit string or subrange: a new value in `lo..=hi`.
    Int {
        /// Lowest value drawn.
        lo: i64,
        /// Highest value drawn.
        hi: i64,
    },
    /// REAL or LREAL: a new whole number in -100..=100.
    Real,
    /// TIME or LTIME: a new multiple of 10 ms in 0..=1 s.
    Time {
        /// LTIME (literal prefix `LT#`).
        long: bool,
    },
    /// An enumeration: a new value among these names.
    Enum(Vec<String>),
    /// Not generated (STRING, dates...): stays at its initial value under
    /// random stimulus; a stimulus CSV may still set it.
    Fixed,
}

/// One driven input or one compared output, named in each program.
#[derive(Debug, Clone, PartialEq)]
pub struct PairedVar {
    /// The name in program A.
    pub a: String,
    /// The name in program B.
    pub b: String,
    /// A's type name.
    pub type_name: String,
    /// What the generator draws (inputs only; [`InputKind::Fixed`] for outputs).
    pub kind: InputKind,
}

/// The driven inputs and compared outputs of a pair of programs, and
/// what was left out (for the report).
#[derive(Debug, Clone, PartialEq)]
pub struct Pairing {
    /// Driven inputs, in A's declaration order (mapped ones first).
    pub inputs: Vec<PairedVar>,
    /// Compared outputs.
    pub outputs: Vec<PairedVar>,
    /// Inputs of one program only (`A.x`, `B.y`): not driven.
    pub unpaired_inputs: Vec<String>,
    /// Default outputs of one program only: not compared.
    pub unpaired_outputs: Vec<String>,
    /// Names removed by `--ignore`.
    pub ignored: Vec<String>,
}

impl Pairing {
    /// The index of the driven input named `name` in A or B.
    pub fn input_index(&self, name: &str) -> Option<usize> {
        let name = name.trim();
        self.inputs
            .iter()
            .position(|p| p.a.eq_ignore_ascii_case(name))
            .or_else(|| {
                self.inputs
                    .iter()
                    .position(|p| p.b.eq_ignore_ascii_case(name))
            })
    }

    /// Pairs the variables of `a` and `b` as described in the module docs.
    pub(crate) fn new(a: &Plc, b: &Plc, options: &CompareOptions) -> Result<Pairing, CompareError> {
        let a_in = program_inputs(a);
        let b_in = program_inputs(b);
        let a_out = a.default_trace();
        let b_out = b.default_trace();
        let mut p = Pairing {
            inputs: Vec::new(),
            outputs: Vec::new(),
            unpaired_inputs: Vec::new(),
            unpaired_outputs: Vec::new(),
            ignored: Vec::new(),
        };
        for (x, y) in &options.map {
            let xa = resolve_info(a, Side::A, x)?;
            resolve_info(b, Side::B, y)?;
            if p.has_a(x) {
                return Err(CompareError::MappedTwice { name: x.clone() });
            }
            if p.has_b(y) {
                return Err(CompareError::MappedTwice { name: y.clone() });
            }
            let x_in = find(&a_in, x);
            let y_in = find(&b_in, y);
            match (x_in, y_in) {
                (Some(xi), Some(yi)) => p.push_input(xi, yi)?,
                (None, None) => p.outputs.push(output(x, y, &xa)),
                _ => {
                    return Err(CompareError::InputMappedToNonInput {
                        a: x.clone(),
                        b: y.clone(),
                    });
                }
            }
        }
        for xi in &a_in {
            if p.has_a(&xi.path) {
                continue;
            }
            match find(&b_in, &xi.path).filter(|y| !p.has_b(&y.path)) {
                Some(yi) => p.push_input(xi, yi)?,
                None => p.unpaired_inputs.push(format!("A.{}", xi.path)),
            }
        }
        for yi in &b_in {
            if !p.has_b(&yi.path) {
                p.unpaired_inputs.push(format!("B.{}", yi.path));
            }
        }
        for x in &a_out {
            if p.has_a(x) {
                continue;
            }
            match b_out.iter().find(|y| y.eq_ignore_ascii_case(x)) {
                Some(y) if !p.has_b(y) => {
                    let info = resolve_info(a, Side::A, x)?;
                    p.outputs.push(output(x, y, &info));
                }
                _ => p.unpaired_outputs.push(format!("A.{x}")),
            }
        }
        for y in &b_out {
            if !p.has_b(y) {
                p.unpaired_outputs.push(format!("B.{y}"));
            }
        }
        p.apply_ignore(options)?;
        p.check_not_empty(&a_in, &b_in, &a_out, &b_out)?;
        Ok(p)
    }

    fn has_a(&self, name: &str) -> bool {
        self.inputs
            .iter()
            .chain(&self.outputs)
            .any(|v| v.a.eq_ignore_ascii_case(name))
    }

    fn has_b(&self, name: &str) -> bool {
        self.inputs
            .iter()
            .chain(&self.outputs)
            .any(|v| v.b.eq_ignore_ascii_case(name))
    }

    fn push_input(&mut self, xi: &VarInfo, yi: &VarInfo) -> Result<(), CompareError> {
        if xi.type_name != yi.type_name {
            return Err(CompareError::InputTypesDiffer {
                a: (xi.path.clone(), xi.type_name.clone()),
                b: (yi.path.clone(), yi.type_name.clone()),
            });
        }
        self.inputs.push(PairedVar {
            a: xi.path.clone(),
            b: yi.path.clone(),
            type_name: xi.type_name.clone(),
            kind: kind_of(&xi.shape),
        });
        Ok(())
    }

    /// Removes the ignored names; each must name something.
    fn apply_ignore(&mut self, options: &CompareOptions) -> Result<(), CompareError> {
        for name in &options.ignore {
            let name = name.trim();
            let hit =
                |v: &PairedVar| v.a.eq_ignore_ascii_case(name) || v.b.eq_ignore_ascii_case(name);
            // Unpaired names are listed as `A.x` / `B.y`.
            let keep = |u: &String| !u[2..].eq_ignore_ascii_case(name);
            let hits = self.inputs.iter().filter(|v| hit(v)).count()
                + self.outputs.iter().filter(|v| hit(v)).count()
                + self.unpaired_inputs.iter().filter(|u| !keep(u)).count()
                + self.unpaired_outputs.iter().filter(|u| !keep(u)).count();
            if hits == 0 {
                return Err(CompareError::UnknownIgnore {
                    name: name.to_string(),
                });
            }
            self.inputs.retain(|v| !hit(v));
            self.outputs.retain(|v| !hit(v));
            self.unpaired_inputs.retain(keep);
            self.unpaired_outputs.retain(keep);
            self.ignored.push(name.to_string());
        }
        Ok(())
    }

    fn check_not_empty(
        &self,
        a_in: &[VarInfo],
        b_in: &[VarInfo],
        a_out: &[String],
        b_out: &[String],
    ) -> Result<(), CompareError> {
        let any_input = !a_in.is_empty() || !b_in.is_empty();
        if self.inputs.is_empty() && any_input && self.ignored.is_empty() {
            return Err(CompareError::NoCommonInputs {
                a: a_in.iter().map(|v| v.path.clone()).collect(),
                b: b_in.iter().map(|v| v.path.clone()).collect(),
            });
        }
        if self.outputs.is_empty() {
            return Err(CompareError::NoComparedOutputs {
                a: a_out.to_vec(),
                b: b_out.to_vec(),
            });
        }
        Ok(())
    }
}

fn find<'a>(list: &'a [VarInfo], name: &str) -> Option<&'a VarInfo> {
    list.iter()
        .find(|v| v.path.eq_ignore_ascii_case(name.trim()))
}

fn output(x: &str, y: &str, info: &VarInfo) -> PairedVar {
    PairedVar {
        a: x.trim().to_string(),
        b: y.trim().to_string(),
        type_name: info.type_name.clone(),
        kind: InputKind::Fixed,
    }
}

/// The listing of `name` in `plc`, or why it names no value.
fn resolve_info(plc: &Plc, side: Side, name: &str) -> Result<VarInfo, CompareError> {
    let r = plc
        .resolve(name)
        .map_err(|error| CompareError::UnknownName {
            side,
            name: name.to_string(),
            error,
        })?;
    let value = plc.get(&r).map_err(|error| CompareError::UnknownName {
        side,
        name: name.to_string(),
        error,
    })?;
    let listed = plc
        .variables()
        .into_iter()
        .find(|v| v.path.eq_ignore_ascii_case(name.trim()));
    Ok(listed.unwrap_or_else(|| VarInfo {
        path: name.trim().to_string(),
        type_name: type_name_of(&value),
        shape: VarShape::Elementary(ElemType::Bool),
        direction: crate::runtime::variables::Direction::Local,
        address: None,
        writable: r.read_only().is_none(),
    }))
}

fn type_name_of(v: &Value) -> String {
    match v {
        Value::Scalar(t, _) => t.name().to_string(),
        Value::String(_, wide) => if *wide { "WSTRING" } else { "STRING" }.to_string(),
        Value::Enum(..) => "enumeration".to_string(),
    }
}

/// The values `plc` reads from outside: its program instances' VAR_INPUTs
/// (every single value inside them) and its `%I` located variables.
pub(crate) fn program_inputs(plc: &Plc) -> Vec<VarInfo> {
    let image = plc.image();
    let qualify = image.programs.len() > 1;
    let mut tops: Vec<String> = Vec::new();
    for inst in &image.programs {
        for m in image.types.members(inst.ty) {
            if m.kind == MemberKind::Input {
                tops.push(if qualify {
                    format!("{}.{}", inst.name, m.name)
                } else {
                    m.name.clone()
                });
            }
        }
    }
    let inside = |path: &str, top: &str| {
        path.len() >= top.len()
            && path[..top.len()].eq_ignore_ascii_case(top)
            && matches!(path.as_bytes().get(top.len()), None | Some(b'.' | b'['))
    };
    plc.variables()
        .into_iter()
        .filter(|v| v.writable)
        .filter(|v| {
            v.address.as_deref().is_some_and(|a| a.starts_with("%I"))
                || tops.iter().any(|t| inside(&v.path, t))
        })
        .collect()
}

/// What the generator draws for a value of this shape.
fn kind_of(shape: &VarShape) -> InputKind {
    match shape {
        VarShape::Elementary(ElemType::Bool) => InputKind::Bool,
        VarShape::Elementary(ElemType::Real | ElemType::Lreal) => InputKind::Real,
        VarShape::Elementary(ElemType::Time) => InputKind::Time { long: false },
        VarShape::Elementary(ElemType::Ltime) => InputKind::Time { long: true },
        VarShape::Elementary(e) if !matches!(e, ElemType::Char | ElemType::Wchar) => {
            match e.int_range() {
                Some((lo, hi)) => int_kind(lo.max(-100) as i64, hi.min(100) as i64),
                None => InputKind::Fixed,
            }
        }
        VarShape::Subrange { lo, hi, .. } => {
            let (l, h) = ((*lo).max(-100), (*hi).min(100));
            if l < h {
                int_kind(l, h)
            } else {
                int_kind(*lo, (*hi).min(lo.saturating_add(200)))
            }
        }
        VarShape::Enum { values } if values.len() >= 2 => InputKind::Enum(values.clone()),
        _ => InputKind::Fixed,
    }
}

fn int_kind(lo: i64, hi: i64) -> InputKind {
    if lo < hi {
        InputKind::Int { lo, hi }
    } else {
        InputKind::Fixed
    }
}

//! What a host needs to build an HMI or a debugger over a running PLC: the
//! list of every single value it can read by path, with its type, section,
//! located address and whether it can be written; and the active steps of
//! every chart.
//!
//! ```
//! use plcrun::{Direction, Options, Plc, VarShape};
//!
//! let src = "PROGRAM P
//! VAR_INPUT go AT %IX0.1 : BOOL; END_VAR
//! VAR_OUTPUT n : INT; END_VAR
//! VAR CONSTANT limit : INT := 10; END_VAR
//! IF go AND n < limit THEN n := n + 1; END_IF
//! END_PROGRAM";
//! let plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
//! let vars = plc.variables();
//! let go = vars.iter().find(|v| v.path == "go").unwrap();
//! assert_eq!(go.type_name, "BOOL");
//! assert_eq!(go.direction, Direction::Input);
//! assert_eq!(go.address.as_deref(), Some("%IX0.1"));
//! let limit = vars.iter().find(|v| v.path == "limit").unwrap();
//! assert!(!limit.writable);
//! assert!(matches!(limit.shape, VarShape::Elementary(_)));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::engine::Plc;
use super::names;
use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::type_table::{MemberKind, TypeId, TypeKind, step_layout};
use crate::stdlib::{ParamDir, interface};

/// The section a variable is declared in, as seen from its owner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Direction {
    /// VAR_INPUT (of the program, or of the FB instance it belongs to).
    Input,
    /// VAR_OUTPUT.
    Output,
    /// VAR, VAR_TEMP: internal.
    Local,
    /// VAR_GLOBAL, a located variable of a program's VAR section, or a
    /// direct address used without a declaration.
    Global,
    /// An SFC step's flag (`S1.X`, `S1.T`).
    Step,
    /// An SFC action's flag (`A1.Q`, `A1.A`).
    Action,
}

impl Direction {
    /// The section's name as the web monitor's API and the Python package
    /// spell it: `input`, `output`, `local`, `global`, `step`, `action`.
    pub fn name(self) -> &'static str {
        match self {
            Direction::Input => "input",
            Direction::Output => "output",
            Direction::Local => "local",
            Direction::Global => "global",
            Direction::Step => "step",
            Direction::Action => "action",
        }
    }
}

/// What kind of value a variable holds.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum VarShape {
    /// An elementary type (BOOL, INT, REAL, TIME...).
    Elementary(ElemType),
    /// STRING or WSTRING of at most `max` characters.
    String {
        /// WSTRING.
        wide: bool,
        /// Maximum length.
        max: u32,
    },
    /// An enumeration, with its value names in declaration order.
    Enum {
        /// The values' names.
        values: Vec<String>,
    },
    /// An integer subrange.
    Subrange {
        /// Base integer type.
        base: ElemType,
        /// Lower bound.
        lo: i64,
        /// Upper bound.
        hi: i64,
    },
}

/// One variable as [`Plc::variables`] lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct VarInfo {
    /// The path that reads it (`n`, `t1.ET`, `arr[2]`, `S1.X`, `P.x`).
    pub path: String,
    /// Its type's name (`INT`, `STRING[20]`, `Color`).
    pub type_name: String,
    /// What it holds.
    pub shape: VarShape,
    /// Its section.
    pub direction: Direction,
    /// Its located address as declared (normalised: `%IX0.1`,
    /// `%IX0.0.0.0.1`), if any.
    pub address: Option<String>,
    /// Whether the host may write it ([`Plc::write`], forcing); CONSTANTs
    /// and SFC flags may only be read.
    pub writable: bool,
}

/// The active steps of one chart instance, as [`Plc::chart_states`] gives
/// them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChartState {
    /// The instance that owns the chart (`Chariot`, `Main.seq`).
    pub path: String,
    /// The PROGRAM or FUNCTION_BLOCK whose body the chart is (what
    /// [`crate::ChartPicture::from_sources`] draws).
    pub pou: String,
    /// Names of its active steps, in declaration order.
    pub active: Vec<String>,
}

impl Plc {
    /// Every single value the host can read by path (array elements,
    /// structure fields and FB instance variables expanded), program
    /// variables first, then globals and undeclared located addresses.
    /// Names are qualified by the program instance when there are several.
    pub fn variables(&self) -> Vec<VarInfo> {
        let image: &Image = &self.image;
        let mut leaves: Vec<(String, TypeId, Direction)> = Vec::new();
        let qualify = image.programs.len() > 1;
        for inst in &image.programs {
            for m in image.types.members(inst.ty) {
                let Some(dir) = direction(m.kind) else {
                    continue;
                };
                let path = if qualify {
                    format!("{}.{}", inst.name, m.name)
                } else {
                    m.name.clone()
                };
                walk(image, path, m.ty, dir, &mut leaves);
            }
        }
        // A set: an S7-200 program lists tens of thousands of bytes, and a
        // linear search per variable made the listing quadratic.
        let mut taken: std::collections::HashSet<u32> = std::collections::HashSet::new();
        let mut out = Vec::new();
        for (path, _, dir) in leaves {
            self.push_info(path, dir, &mut taken, &mut out);
        }
        let mut globals: Vec<_> = image.globals.iter().collect();
        // Declared names before bare addresses at the same slot.
        globals.sort_by_key(|r| r.name.starts_with('%'));
        for r in globals {
            let mut leaves = Vec::new();
            // A located VAR_INPUT / VAR_OUTPUT of a program keeps its section.
            let dir = match r.kind {
                MemberKind::Input => Direction::Input,
                MemberKind::Output => Direction::Output,
                _ => Direction::Global,
            };
            walk(image, r.name.clone(), r.ty, dir, &mut leaves);
            for (path, _, dir) in leaves {
                self.push_info(path, dir, &mut taken, &mut out);
            }
        }
        out
    }

    /// Adds the listing of `path` unless its slot is listed already.
    fn push_info(
        &self,
        path: String,
        dir: Direction,
        taken: &mut std::collections::HashSet<u32>,
        out: &mut Vec<VarInfo>,
    ) {
        let Ok(r) = names::resolve(&self.image, &path, self.id) else {
            return;
        };
        if taken.contains(&r.addr) {
            return;
        }
        let Some(shape) = shape(&self.image, r.ty) else {
            return;
        };
        taken.insert(r.addr);
        let address = self
            .image
            .globals
            .iter()
            .find(|g| g.addr == r.addr && g.location.is_some())
            .and_then(|g| g.location.clone());
        out.push(VarInfo {
            type_name: self.image.types.name(r.ty).to_string(),
            shape,
            direction: dir,
            address,
            writable: r.read_only.is_none(),
            path,
        });
    }

    /// The active steps of every chart: each SFC program instance and each
    /// SFC function block instance inside them, in declaration order.
    pub fn chart_states(&self) -> Vec<ChartState> {
        let mut out = Vec::new();
        for inst in &self.image.programs {
            self.charts_in(inst.name.clone(), inst.ty, inst.base, &mut out);
        }
        out
    }

    /// The active steps of the chart owned by instance `path` (a program
    /// instance name, `Main.seq`), or `None` when it names no chart.
    pub fn active_steps(&self, path: &str) -> Option<Vec<String>> {
        self.chart_states()
            .into_iter()
            .find(|c| c.path.eq_ignore_ascii_case(path.trim()))
            .map(|c| c.active)
    }

    /// Pushes the chart states of the instance of `ty` at `base`, then of
    /// the FB instances inside it.
    fn charts_in(&self, path: String, ty: TypeId, base: u32, out: &mut Vec<ChartState>) {
        let image = &self.image;
        match &image.types.get(ty).kind {
            TypeKind::Pou { members, .. } => {
                let steps: Vec<_> = members
                    .iter()
                    .filter(|m| m.kind == MemberKind::Step)
                    .collect();
                if !steps.is_empty() {
                    let active = steps
                        .iter()
                        .filter(|m| {
                            let at = (base + m.offset + step_layout::X) as usize;
                            self.machine.mem.get(at).is_some_and(|&x| x != 0)
                        })
                        .map(|m| m.name.clone())
                        .collect();
                    out.push(ChartState {
                        path: path.clone(),
                        pou: image.types.name(ty).to_string(),
                        active,
                    });
                }
                for m in members {
                    if matches!(
                        m.kind,
                        MemberKind::Input | MemberKind::Output | MemberKind::Local
                    ) {
                        self.charts_in(format!("{path}.{}", m.name), m.ty, base + m.offset, out);
                    }
                }
            }
            TypeKind::Array { dims, elem } => {
                if !matches!(image.types.get(*elem).kind, TypeKind::Pou { .. }) {
                    return;
                }
                let size = image.types.size(*elem);
                let total: u64 = dims.iter().map(|d| d.len()).product();
                for k in 0..total {
                    let at = base + (k as u32) * size;
                    self.charts_in(format!("{path}[{}]", index_text(dims, k)), *elem, at, out);
                }
            }
            _ => {}
        }
    }
}

/// The indexes of the `k`-th element of an array (the last index runs
/// fastest, as in memory), as `1,2`.
fn index_text(dims: &[crate::ir::type_table::Dim], k: u64) -> String {
    let mut rest = k;
    let mut idx = vec![0i64; dims.len()];
    for (i, d) in dims.iter().enumerate().rev() {
        idx[i] = d.lo + (rest % d.len()) as i64;
        rest /= d.len();
    }
    let text: Vec<String> = idx.iter().map(i64::to_string).collect();
    text.join(",")
}

/// The listed section of a member kind (`None`: not listed).
fn direction(kind: MemberKind) -> Option<Direction> {
    match kind {
        MemberKind::Input => Some(Direction::Input),
        MemberKind::Output => Some(Direction::Output),
        MemberKind::Local | MemberKind::Temp => Some(Direction::Local),
        MemberKind::Step => Some(Direction::Step),
        MemberKind::Action => Some(Direction::Action),
        MemberKind::Field => None,
        MemberKind::InOut | MemberKind::External | MemberKind::Hidden => None,
    }
}

/// What a single-value type holds (`None` for aggregates).
fn shape(image: &Image, ty: TypeId) -> Option<VarShape> {
    Some(match &image.types.get(ty).kind {
        TypeKind::Elem(e) => VarShape::Elementary(*e),
        TypeKind::Str { wide, max } => VarShape::String {
            wide: *wide,
            max: *max,
        },
        TypeKind::Enum { values, .. } => VarShape::Enum {
            values: values.iter().map(|(n, _)| n.clone()).collect(),
        },
        TypeKind::Subrange { base, lo, hi } => VarShape::Subrange {
            base: *base,
            lo: *lo,
            hi: *hi,
        },
        _ => return None,
    })
}

/// Pushes every single value inside `path` (of type `ty`, in section
/// `dir`), with the section of the innermost member that declares it, in
/// declaration order. An explicit work list, not recursion: a structure
/// may nest tens of thousands of levels (the declaration limit, E122),
/// and a host may call this on a small stack.
fn walk(
    image: &Image,
    path: String,
    ty: TypeId,
    dir: Direction,
    out: &mut Vec<(String, TypeId, Direction)>,
) {
    // Children are pushed in reverse so that they pop in order.
    let mut work = vec![(path, ty, dir)];
    while let Some((path, ty, dir)) = work.pop() {
        let at = work.len();
        match &image.types.get(ty).kind {
            TypeKind::Elem(_)
            | TypeKind::Str { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Subrange { .. } => out.push((path, ty, dir)),
            TypeKind::Array { dims, elem } => {
                let total: u64 = dims.iter().map(|d| d.len()).product();
                for k in 0..total {
                    let p = format!("{path}[{}]", index_text(dims, k));
                    work.push((p, *elem, dir));
                }
            }
            TypeKind::Struct { fields } => {
                for f in fields {
                    let d = direction(f.kind).unwrap_or(dir);
                    work.push((format!("{path}.{}", f.name), f.ty, d));
                }
            }
            TypeKind::Pou { members, .. } => {
                for m in members {
                    if let Some(d) = direction(m.kind) {
                        let name = super::names::shown_member(image, &m.name);
                        work.push((format!("{path}.{name}"), m.ty, d));
                    }
                }
            }
            TypeKind::NativeFb(fb) => {
                for p in interface(*fb) {
                    let d = match p.dir {
                        ParamDir::Input => Direction::Input,
                        ParamDir::Output => Direction::Output,
                        _ => continue,
                    };
                    out.push((
                        format!("{path}.{}", p.name),
                        crate::ir::type_table::TypeTable::elem(p.ty),
                        d,
                    ));
                }
            }
            TypeKind::Step => {
                for flag in ["X", "T"] {
                    let ty = if flag == "X" {
                        ElemType::Bool
                    } else {
                        ElemType::Time
                    };
                    out.push((
                        format!("{path}.{flag}"),
                        crate::ir::type_table::TypeTable::elem(ty),
                        Direction::Step,
                    ));
                }
            }
            _ => {}
        }
        work[at..].reverse();
    }
}

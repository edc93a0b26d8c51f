//! The signatures of the IEC standard functions plcrun provides, for
//! hover, completion and signature help (IEC 61131-3 tables 22-37; the
//! input names are the standard's).

/// One standard function's interface.
#[derive(Debug, Clone, PartialEq)]
pub struct StdFunction {
    /// Its name.
    pub name: String,
    /// Its inputs: name and type (generic types as the standard writes
    /// them, `ANY_NUM`...).
    pub inputs: Vec<(String, String)>,
    /// The type of its result.
    pub result: String,
    /// What it computes, in one line.
    pub summary: &'static str,
    /// True when more inputs of the last kind may follow (`ADD`, `MAX`,
    /// `MUX`, `CONCAT`...).
    pub extensible: bool,
}

impl StdFunction {
    /// `NAME(IN1 : T, IN2 : T) : R`.
    pub fn signature(&self) -> String {
        let mut params: Vec<String> = self
            .inputs
            .iter()
            .map(|(n, t)| format!("{n} : {t}"))
            .collect();
        if self.extensible {
            params.push("...".to_string());
        }
        format!("{}({}) : {}", self.name, params.join(", "), self.result)
    }
}

/// (name, inputs, result, summary, extensible). Inputs are written
/// `NAME:TYPE` separated by spaces.
const TABLE: &[(&str, &str, &str, &str, bool)] = &[
    (
        "ADD",
        "IN1:ANY_MAGNITUDE IN2:ANY_MAGNITUDE",
        "ANY_MAGNITUDE",
        "sum of the inputs",
        true,
    ),
    (
        "MUL",
        "IN1:ANY_NUM IN2:ANY_NUM",
        "ANY_NUM",
        "product of the inputs",
        true,
    ),
    (
        "SUB",
        "IN1:ANY_MAGNITUDE IN2:ANY_MAGNITUDE",
        "ANY_MAGNITUDE",
        "IN1 - IN2",
        false,
    ),
    (
        "DIV",
        "IN1:ANY_NUM IN2:ANY_NUM",
        "ANY_NUM",
        "IN1 / IN2 (integers: truncated toward zero; a zero divisor faults)",
        false,
    ),
    (
        "MOD",
        "IN1:ANY_INT IN2:ANY_INT",
        "ANY_INT",
        "remainder of IN1 / IN2, with the sign of IN1",
        false,
    ),
    (
        "EXPT",
        "IN1:ANY_REAL IN2:ANY_NUM",
        "ANY_REAL",
        "IN1 raised to the power IN2",
        false,
    ),
    ("MOVE", "IN:ANY", "ANY", "IN, unchanged", false),
    (
        "AND",
        "IN1:ANY_BIT IN2:ANY_BIT",
        "ANY_BIT",
        "bitwise AND",
        true,
    ),
    (
        "OR",
        "IN1:ANY_BIT IN2:ANY_BIT",
        "ANY_BIT",
        "bitwise OR",
        true,
    ),
    (
        "XOR",
        "IN1:ANY_BIT IN2:ANY_BIT",
        "ANY_BIT",
        "bitwise exclusive OR",
        true,
    ),
    ("NOT", "IN:ANY_BIT", "ANY_BIT", "bitwise complement", false),
    ("ABS", "IN:ANY_NUM", "ANY_NUM", "absolute value", false),
    ("SQRT", "IN:ANY_REAL", "ANY_REAL", "square root", false),
    ("LN", "IN:ANY_REAL", "ANY_REAL", "natural logarithm", false),
    ("LOG", "IN:ANY_REAL", "ANY_REAL", "logarithm base 10", false),
    (
        "EXP",
        "IN:ANY_REAL",
        "ANY_REAL",
        "e raised to the power IN",
        false,
    ),
    ("SIN", "IN:ANY_REAL", "ANY_REAL", "sine (radians)", false),
    ("COS", "IN:ANY_REAL", "ANY_REAL", "cosine (radians)", false),
    ("TAN", "IN:ANY_REAL", "ANY_REAL", "tangent (radians)", false),
    (
        "ASIN",
        "IN:ANY_REAL",
        "ANY_REAL",
        "arc sine, in radians",
        false,
    ),
    (
        "ACOS",
        "IN:ANY_REAL",
        "ANY_REAL",
        "arc cosine, in radians",
        false,
    ),
    (
        "ATAN",
        "IN:ANY_REAL",
        "ANY_REAL",
        "arc tangent, in radians",
        false,
    ),
    (
        "TRUNC",
        "IN:ANY_REAL",
        "ANY_INT",
        "IN with its fraction dropped (toward zero)",
        false,
    ),
    (
        "SEL",
        "G:BOOL IN0:ANY IN1:ANY",
        "ANY",
        "IN0 when G is FALSE, IN1 when TRUE",
        false,
    ),
    (
        "MAX",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "ANY_ELEMENTARY",
        "the largest input",
        true,
    ),
    (
        "MIN",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "ANY_ELEMENTARY",
        "the smallest input",
        true,
    ),
    (
        "LIMIT",
        "MN:ANY_ELEMENTARY IN:ANY_ELEMENTARY MX:ANY_ELEMENTARY",
        "ANY_ELEMENTARY",
        "IN clamped to MN..MX",
        false,
    ),
    (
        "MUX",
        "K:ANY_INT IN0:ANY IN1:ANY",
        "ANY",
        "the input numbered K (0-based); K out of range faults",
        true,
    ),
    (
        "GT",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "BOOL",
        "IN1 > IN2 (> IN3 ...)",
        true,
    ),
    (
        "GE",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "BOOL",
        "IN1 >= IN2 (>= IN3 ...)",
        true,
    ),
    (
        "EQ",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "BOOL",
        "all inputs equal",
        true,
    ),
    (
        "LE",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "BOOL",
        "IN1 <= IN2 (<= IN3 ...)",
        true,
    ),
    (
        "LT",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "BOOL",
        "IN1 < IN2 (< IN3 ...)",
        true,
    ),
    (
        "NE",
        "IN1:ANY_ELEMENTARY IN2:ANY_ELEMENTARY",
        "BOOL",
        "IN1 <> IN2",
        false,
    ),
    (
        "SHL",
        "IN:ANY_BIT N:ANY_INT",
        "ANY_BIT",
        "IN shifted left by N bits, zeros shifted in",
        false,
    ),
    (
        "SHR",
        "IN:ANY_BIT N:ANY_INT",
        "ANY_BIT",
        "IN shifted right by N bits, zeros shifted in",
        false,
    ),
    (
        "ROL",
        "IN:ANY_BIT N:ANY_INT",
        "ANY_BIT",
        "IN rotated left by N bits",
        false,
    ),
    (
        "ROR",
        "IN:ANY_BIT N:ANY_INT",
        "ANY_BIT",
        "IN rotated right by N bits",
        false,
    ),
    ("ADD_TIME", "IN1:TIME IN2:TIME", "TIME", "IN1 + IN2", false),
    ("SUB_TIME", "IN1:TIME IN2:TIME", "TIME", "IN1 - IN2", false),
    (
        "MUL_TIME",
        "IN1:TIME IN2:ANY_NUM",
        "TIME",
        "IN1 * IN2",
        false,
    ),
    (
        "DIV_TIME",
        "IN1:TIME IN2:ANY_NUM",
        "TIME",
        "IN1 / IN2",
        false,
    ),
    (
        "ADD_TOD_TIME",
        "IN1:TOD IN2:TIME",
        "TOD",
        "time of day IN1 + IN2",
        false,
    ),
    (
        "ADD_DT_TIME",
        "IN1:DT IN2:TIME",
        "DT",
        "date and time IN1 + IN2",
        false,
    ),
    (
        "SUB_DATE_DATE",
        "IN1:DATE IN2:DATE",
        "TIME",
        "IN1 - IN2",
        false,
    ),
    (
        "SUB_TOD_TIME",
        "IN1:TOD IN2:TIME",
        "TOD",
        "IN1 - IN2",
        false,
    ),
    ("SUB_TOD_TOD", "IN1:TOD IN2:TOD", "TIME", "IN1 - IN2", false),
    ("SUB_DT_TIME", "IN1:DT IN2:TIME", "DT", "IN1 - IN2", false),
    ("SUB_DT_DT", "IN1:DT IN2:DT", "TIME", "IN1 - IN2", false),
    (
        "CONCAT_DATE_TOD",
        "IN1:DATE IN2:TOD",
        "DT",
        "the date and time of day joined",
        false,
    ),
    ("LEN", "IN:ANY_STRING", "INT", "length of the string", false),
    (
        "LEFT",
        "IN:ANY_STRING L:ANY_INT",
        "ANY_STRING",
        "the first L characters",
        false,
    ),
    (
        "RIGHT",
        "IN:ANY_STRING L:ANY_INT",
        "ANY_STRING",
        "the last L characters",
        false,
    ),
    (
        "MID",
        "IN:ANY_STRING L:ANY_INT P:ANY_INT",
        "ANY_STRING",
        "L characters from position P (1-based)",
        false,
    ),
    (
        "CONCAT",
        "IN1:ANY_STRING IN2:ANY_STRING",
        "ANY_STRING",
        "the strings joined",
        true,
    ),
    (
        "INSERT",
        "IN1:ANY_STRING IN2:ANY_STRING P:ANY_INT",
        "ANY_STRING",
        "IN2 inserted after position P of IN1",
        false,
    ),
    (
        "DELETE",
        "IN:ANY_STRING L:ANY_INT P:ANY_INT",
        "ANY_STRING",
        "IN without the L characters from position P",
        false,
    ),
    (
        "REPLACE",
        "IN1:ANY_STRING IN2:ANY_STRING L:ANY_INT P:ANY_INT",
        "ANY_STRING",
        "IN1 with L characters from position P replaced by IN2",
        false,
    ),
    (
        "FIND",
        "IN1:ANY_STRING IN2:ANY_STRING",
        "INT",
        "position of IN2 in IN1 (1-based), 0 when absent",
        false,
    ),
    (
        "PLC_CLOCK",
        "",
        "TIME",
        "the cycle's virtual clock (plcrun)",
        false,
    ),
];

/// The elementary type names a `*_TO_*` conversion may name.
const CONVERTIBLE: &[&str] = &[
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "REAL", "LREAL",
    "BYTE", "WORD", "DWORD", "LWORD", "TIME", "LTIME", "DATE", "TOD", "DT", "STRING", "WSTRING",
];

fn from_row(row: &(&str, &str, &str, &'static str, bool)) -> StdFunction {
    let (name, inputs, result, summary, extensible) = *row;
    StdFunction {
        name: name.to_string(),
        inputs: inputs
            .split_whitespace()
            .filter_map(|p| p.split_once(':'))
            .map(|(n, t)| (n.to_string(), t.to_string()))
            .collect(),
        result: result.to_string(),
        summary,
        extensible,
    }
}

/// The standard function `name` (any case), conversions included.
pub fn std_function(name: &str) -> Option<StdFunction> {
    let upper = name.to_ascii_uppercase();
    if let Some(row) = TABLE.iter().find(|r| r.0 == upper) {
        return Some(from_row(row));
    }
    let (from, to) = upper.split_once("_TO_")?;
    let known = |t: &str| CONVERTIBLE.contains(&t) || t == "BCD";
    if !known(from) || !known(to) || from == to {
        return None;
    }
    let ty = |t: &str| if t == "BCD" { "ANY_BIT" } else { t }.to_string();
    Some(StdFunction {
        name: upper.clone(),
        inputs: vec![("IN".to_string(), ty(from))],
        result: ty(to),
        summary: "type conversion",
        extensible: false,
    })
}

/// Every standard function of the table (not the `*_TO_*` family).
pub fn std_functions() -> impl Iterator<Item = StdFunction> {
    TABLE.iter().map(from_row)
}

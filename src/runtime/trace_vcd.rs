//! The trace as a VCD (Value Change Dump, IEEE 1364) waveform, for GTKWave,
//! Surfer and other wave viewers.
//!
//! The header is deterministic (no `$date`): the same program and stimulus
//! give the same bytes. Each traced name becomes a variable in nested
//! `$scope module` blocks that follow its instance path (`main.t1.Q` is `Q`
//! in scope `t1` in scope `main`; a name without a dot, or a direct address
//! such as `%QX0.1`, sits at the top). Variables:
//!
//! | traced type | declared as | value |
//! |---|---|---|
//! | BOOL (SFC `.X` flags too) | `wire 1` | `0` / `1` |
//! | SINT, INT, DINT, LINT | `integer 8/16/32/64` | two's complement |
//! | USINT..ULINT, BYTE..LWORD, CHAR, WCHAR | `wire` of the type's width | binary |
//! | REAL, LREAL | `real 64` | the value (`NaN`, `inf`, `-inf`) |
//! | TIME, LTIME, DATE, TOD, DT (and the L forms) | `integer 64` | nanoseconds |
//! | enumeration | `integer` or `wire` of its storage width | the ordinal |
//! | STRING, WSTRING | `string 1` (a GTKWave extension Surfer reads too) | see below |
//!
//! A string value is written after `s` with every character outside `!`..`~`
//! (space, control, non-ASCII), `\` and `"` as `\xHH` per UTF-8 byte, and
//! the empty string as `""` (a VCD value cannot be empty or hold blanks).
//!
//! Time: one timestamp per cycle (per changed cycle with `changes_only`)
//! holding the values that changed since the previous one; the first holds
//! every value in `$dumpvars`. Timestamps are the cycle's clock in units of
//! [`VcdTimescale`]. Forced values are written as the values they are; VCD
//! has no mark for them.

use crate::elementary::ElemType;
use crate::ir::image::Image;
use crate::ir::type_table::TypeKind;
use crate::value::text::parse_scalar;
use std::fmt::Write as _;
use std::io::{self, Write};

use super::names::VarRef;
use super::trace::TraceCell;

/// How one traced column is declared in a VCD file: what the value is and
/// how to read it from its [`TraceCell`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VcdSignal {
    /// A value of an elementary (non-string) type.
    Elementary(ElemType),
    /// An enumeration stored as integers of this type; the cell's JSON
    /// holds the ordinal.
    Enum(ElemType),
    /// A STRING or WSTRING; the cell's JSON holds the plain text.
    String,
}

impl VcdSignal {
    /// The VCD variable type and width.
    fn declaration(self) -> (&'static str, u32) {
        match self {
            VcdSignal::String => ("string", 1),
            VcdSignal::Elementary(ElemType::Bool) => ("wire", 1),
            VcdSignal::Elementary(ElemType::Real | ElemType::Lreal) => ("real", 64),
            VcdSignal::Elementary(ty) | VcdSignal::Enum(ty) => {
                let width = bit_width(ty);
                if is_signed(ty) {
                    ("integer", width)
                } else {
                    ("wire", width)
                }
            }
        }
    }
}

/// The VCD type of a resolved variable of `image`.
pub(crate) fn vcd_signal(image: &Image, r: &VarRef) -> VcdSignal {
    match &image.types.get(r.ty).kind {
        TypeKind::Str { .. } => VcdSignal::String,
        TypeKind::Enum { base, .. } => VcdSignal::Enum(*base),
        _ => VcdSignal::Elementary(image.types.scalar(r.ty).unwrap_or(ElemType::Lint)),
    }
}

/// Storage width in bits of an integer-like type.
fn bit_width(ty: ElemType) -> u32 {
    use ElemType::*;
    match ty {
        Bool => 1,
        Sint | Usint | Byte | Char => 8,
        Int | Uint | Word | Wchar => 16,
        Dint | Udint | Dword | Real => 32,
        _ => 64,
    }
}

/// Whether the type's values are signed (two's complement).
fn is_signed(ty: ElemType) -> bool {
    use ElemType::*;
    matches!(
        ty,
        Sint | Int | Dint | Lint | Time | Ltime | Date | Ldate | Tod | Ltod | Dt | Ldt
    )
}

/// The unit of a VCD file's timestamps: 1, 10 or 100 of s, ms, us or ns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VcdTimescale {
    unit_ns: i64,
}

/// The units a `$timescale` can name, largest first, in nanoseconds.
const UNITS: [(i64, &str); 12] = [
    (100_000_000_000, "100 s"),
    (10_000_000_000, "10 s"),
    (1_000_000_000, "1 s"),
    (100_000_000, "100 ms"),
    (10_000_000, "10 ms"),
    (1_000_000, "1 ms"),
    (100_000, "100 us"),
    (10_000, "10 us"),
    (1_000, "1 us"),
    (100, "100 ns"),
    (10, "10 ns"),
    (1, "1 ns"),
];

impl VcdTimescale {
    /// One nanosecond: exact for any clock (the wall clock of a real-time
    /// run included).
    pub const NANOSECOND: VcdTimescale = VcdTimescale { unit_ns: 1 };

    /// The largest unit that divides the base tick `cycle_ns` and the first
    /// cycle's time `start_ns` (both in nanoseconds), so that every cycle
    /// of a virtual-time run, at `start + k × cycle`, has an exact
    /// timestamp: a 10 ms cycle gives `10 ms`, 2.5 ms gives `100 us`,
    /// 1.5 µs gives `100 ns`... in steps of 1, 10, 100 (`10 ns` and `100
    /// ns` included).
    ///
    /// ```
    /// use plcrun::VcdTimescale;
    /// assert_eq!(VcdTimescale::for_cycle(10_000_000, 0).to_string(), "10 ms");
    /// assert_eq!(VcdTimescale::for_cycle(2_500_000, 0).to_string(), "100 us");
    /// assert_eq!(VcdTimescale::for_cycle(10_000_000, 5).to_string(), "1 ns");
    /// ```
    pub fn for_cycle(cycle_ns: i64, start_ns: i64) -> VcdTimescale {
        let fits = |unit: i64| cycle_ns % unit == 0 && start_ns % unit == 0;
        UNITS
            .iter()
            .find(|(unit, _)| fits(*unit))
            .map_or(Self::NANOSECOND, |(unit_ns, _)| VcdTimescale {
                unit_ns: *unit_ns,
            })
    }

    /// The unit in nanoseconds.
    pub fn unit_ns(self) -> i64 {
        self.unit_ns
    }
}

impl std::fmt::Display for VcdTimescale {
    /// As the `$timescale` command writes it: `10 ms`, `1 ns`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match UNITS.iter().find(|(u, _)| *u == self.unit_ns) {
            Some((_, text)) => f.write_str(text),
            None => write!(f, "{} ns", self.unit_ns),
        }
    }
}

/// The VCD form of one trace: header, identifiers, last values.
pub(crate) struct VcdSink<W: Write> {
    out: W,
    names: Vec<String>,
    signals: Vec<VcdSignal>,
    timescale: VcdTimescale,
    changes_only: bool,
    /// Identifier code of each column.
    ids: Vec<String>,
    /// The last value written for each column, as written (without id).
    last: Vec<String>,
    header_written: bool,
    last_time: Option<i64>,
    /// Scratch: the values of the row being written.
    values: Vec<String>,
    /// Scratch: the text of one timestamp block.
    block: String,
}

impl<W: Write> VcdSink<W> {
    pub(crate) fn new(
        out: W,
        names: Vec<String>,
        signals: Vec<VcdSignal>,
        timescale: VcdTimescale,
        changes_only: bool,
    ) -> Self {
        let ids = (0..names.len()).map(identifier).collect();
        VcdSink {
            out,
            names,
            signals,
            timescale,
            changes_only,
            ids,
            last: Vec::new(),
            header_written: false,
            last_time: None,
            values: Vec::new(),
            block: String::new(),
        }
    }

    /// Writes one cycle's values at clock `time_ns`.
    pub(crate) fn row(&mut self, time_ns: i64, cells: &[TraceCell]) -> io::Result<()> {
        if self.signals.len() != self.names.len() {
            return Err(invalid_input(format!(
                "the VCD trace has {} column types for {} traced names (make it with TraceWriter::vcd)",
                self.signals.len(),
                self.names.len()
            )));
        }
        let stamp = self.timestamp(time_ns)?;
        self.values.resize(cells.len(), String::new());
        for (i, (cell, signal)) in cells.iter().zip(&self.signals).enumerate() {
            let text = &mut self.values[i];
            text.clear();
            encode(text, *signal, cell).map_err(|problem| {
                io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!(
                        "cannot write `{}` = {} to the VCD trace: {problem}",
                        self.names[i], cell.text
                    ),
                )
            })?;
        }
        self.write_header()?;
        self.block.clear();
        let first = self.last_time.is_none();
        if first {
            let _ = writeln!(self.block, "#{stamp}\n$dumpvars");
            for (value, id) in self.values.iter().zip(&self.ids) {
                push_change(&mut self.block, value, id);
            }
            self.block.push_str("$end\n");
            self.last.clone_from(&self.values);
        } else {
            let _ = writeln!(self.block, "#{stamp}");
            let mut changed = false;
            for ((value, last), id) in self.values.iter().zip(&mut self.last).zip(&self.ids) {
                if value != last {
                    changed = true;
                    push_change(&mut self.block, value, id);
                    last.clone_from(value);
                }
            }
            if self.changes_only && !changed {
                self.last_time = Some(time_ns);
                return Ok(());
            }
        }
        self.last_time = Some(time_ns);
        self.out.write_all(self.block.as_bytes())
    }

    /// `time_ns` in units of the timescale; an error when it is not a
    /// whole number of units or goes back.
    fn timestamp(&self, time_ns: i64) -> io::Result<i64> {
        let unit = self.timescale.unit_ns;
        if time_ns < 0 || time_ns % unit != 0 {
            return Err(invalid_input(format!(
                "the clock {time_ns} ns is not a whole number of the VCD timescale ({})",
                self.timescale
            )));
        }
        if self.last_time.is_some_and(|last| time_ns <= last) {
            return Err(invalid_input(format!(
                "the clock {time_ns} ns does not advance past the previous row's"
            )));
        }
        Ok(time_ns / unit)
    }

    /// The header, once (also for an empty trace, from [`Self::finish`]).
    fn write_header(&mut self) -> io::Result<()> {
        if self.header_written {
            return Ok(());
        }
        self.header_written = true;
        let mut text = String::new();
        let _ = writeln!(
            text,
            "$version plcrun {} $end\n$timescale {} $end",
            env!("CARGO_PKG_VERSION"),
            self.timescale
        );
        let tree = ScopeTree::of(&self.names);
        tree.write(&mut text, &self.signals, &self.ids, 0);
        text.push_str("$enddefinitions $end\n");
        self.out.write_all(text.as_bytes())
    }

    pub(crate) fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    /// Writes the header if no row came, flushes, and hands the output back.
    pub(crate) fn finish(mut self) -> io::Result<W> {
        self.write_header()?;
        self.out.flush()?;
        Ok(self.out)
    }
}

fn invalid_input(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// A value change line: `1!`, `b101 "`, `r2.5 #`, `sab $`.
fn push_change(block: &mut String, value: &str, id: &str) {
    block.push_str(value);
    if value.len() > 1 || !matches!(value, "0" | "1") {
        block.push(' ');
    }
    block.push_str(id);
    block.push('\n');
}

/// The compact identifier code of column `index`: `!` to `~`, then two
/// characters, and so on (base 94 over the printable characters).
fn identifier(index: usize) -> String {
    const FIRST: u8 = b'!';
    const RADIX: usize = (b'~' - b'!' + 1) as usize;
    let mut id = Vec::new();
    let mut n = index;
    loop {
        id.push(FIRST + (n % RADIX) as u8);
        n /= RADIX;
        if n == 0 {
            break;
        }
        n -= 1;
    }
    id.reverse();
    String::from_utf8(id).unwrap_or_default()
}

/// Writes the value of `cell` as VCD (without the identifier): `1`, `b101`,
/// `r2.5`, `sab`. The error says why the cell does not fit the signal.
fn encode(out: &mut String, signal: VcdSignal, cell: &TraceCell) -> Result<(), String> {
    match signal {
        VcdSignal::String => {
            let text = cell.json.as_str().ok_or("not a string")?;
            out.push('s');
            push_escaped(out, text);
        }
        VcdSignal::Enum(ty) => {
            let ordinal = cell.json.as_i64().ok_or("not an enumeration ordinal")?;
            push_bits(out, ordinal as u64, ty)?;
        }
        VcdSignal::Elementary(ElemType::Bool) => {
            out.push(if cell.json.as_bool().ok_or("not a BOOL")? {
                '1'
            } else {
                '0'
            });
        }
        VcdSignal::Elementary(ElemType::Real | ElemType::Lreal) => {
            let value = match &cell.json {
                serde_json::Value::Number(n) => n.as_f64().ok_or("not a number")?,
                serde_json::Value::String(s) if s == "NaN" => f64::NAN,
                serde_json::Value::String(s) if s == "INF" => f64::INFINITY,
                serde_json::Value::String(s) if s == "-INF" => f64::NEG_INFINITY,
                _ => return Err("not a real number".into()),
            };
            // `{:?}` is the shortest exact text, with an exponent when long.
            let _ = write!(out, "r{value:?}");
        }
        VcdSignal::Elementary(ty) => {
            let raw = match &cell.json {
                serde_json::Value::Number(n) => n
                    .as_i64()
                    .map(|v| v as u64)
                    .or_else(|| n.as_u64())
                    .ok_or("not an integer")?,
                _ => parse_scalar(&cell.text, ty)
                    .or_else(|| lone_surrogate(ty, &cell.text))
                    .ok_or("not a value of the traced type")?,
            };
            push_bits(out, raw, ty)?;
        }
    }
    Ok(())
}

/// A WCHAR that is half of a surrogate pair, printed as its code unit
/// (`"$D800"`), which is no character a literal can hold.
fn lone_surrogate(ty: ElemType, text: &str) -> Option<u64> {
    let hex = text.strip_prefix("\"$")?.strip_suffix('"')?;
    (ty == ElemType::Wchar && hex.len() == 4)
        .then(|| u64::from_str_radix(hex, 16).ok())
        .flatten()
}

/// `b` and the binary digits of `raw` in the width of `ty`, without leading
/// zeros (VCD fills a shorter value with zeros on the left). A value that
/// does not fit the width is refused rather than cut.
fn push_bits(out: &mut String, raw: u64, ty: ElemType) -> Result<(), String> {
    let width = bit_width(ty);
    let bits = if width == 64 {
        raw
    } else {
        let mask = (1u64 << width) - 1;
        let fits = if is_signed(ty) {
            let v = raw as i64;
            let half = 1i64 << (width - 1);
            (-half..half).contains(&v)
        } else {
            raw <= mask
        };
        if !fits {
            return Err(format!("does not fit in {width} bits"));
        }
        raw & mask
    };
    let _ = write!(out, "b{bits:b}");
    Ok(())
}

/// A string value without blanks: see the module docs.
fn push_escaped(out: &mut String, text: &str) {
    if text.is_empty() {
        out.push_str("\"\"");
        return;
    }
    for c in text.chars() {
        if c.is_ascii_graphic() && c != '\\' && c != '"' {
            out.push(c);
        } else {
            let mut buf = [0u8; 4];
            for byte in c.encode_utf8(&mut buf).bytes() {
                let _ = write!(out, "\\x{byte:02X}");
            }
        }
    }
}

/// The scopes of the traced names: each node holds its variables (column
/// numbers) and sub-scopes, in order of first appearance.
#[derive(Default)]
struct ScopeTree {
    vars: Vec<(usize, String)>,
    scopes: Vec<(String, ScopeTree)>,
}

impl ScopeTree {
    fn of(names: &[String]) -> ScopeTree {
        let mut root = ScopeTree::default();
        for (column, name) in names.iter().enumerate() {
            let mut parts = split_path(name);
            let var = parts.pop().unwrap_or_default();
            let mut node = &mut root;
            for scope in parts {
                let at = match node.scopes.iter().position(|(s, _)| *s == scope) {
                    Some(at) => at,
                    None => {
                        node.scopes.push((scope, ScopeTree::default()));
                        node.scopes.len() - 1
                    }
                };
                node = &mut node.scopes[at].1;
            }
            node.vars.push((column, var));
        }
        root
    }

    fn write(&self, out: &mut String, signals: &[VcdSignal], ids: &[String], depth: usize) {
        let indent = "  ".repeat(depth);
        for (column, var) in &self.vars {
            let (kind, width) = signals[*column].declaration();
            let _ = writeln!(
                out,
                "{indent}$var {kind} {width} {} {var} $end",
                ids[*column]
            );
        }
        for (scope, tree) in &self.scopes {
            let _ = writeln!(out, "{indent}$scope module {scope} $end");
            tree.write(out, signals, ids, depth + 1);
            let _ = writeln!(out, "{indent}$upscope $end");
        }
    }
}

/// `main.t1.Q` → `["main", "t1", "Q"]`; dots inside brackets do not split,
/// a direct address (`%QX0.1`) is one part; blanks are dropped (a VCD name
/// has none).
fn split_path(name: &str) -> Vec<String> {
    let compact: String = name.chars().filter(|c| !c.is_whitespace()).collect();
    if compact.starts_with('%') {
        return vec![compact];
    }
    let mut parts = vec![String::new()];
    let mut depth = 0usize;
    for c in compact.chars() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            '.' if depth == 0 => {
                parts.push(String::new());
                continue;
            }
            _ => {}
        }
        if let Some(last) = parts.last_mut() {
            last.push(c);
        }
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;
    use ElemType::{
        Bool, Byte, Char, Date, Dt, Int, Lint, Lreal, Ltime, Lword, Real, Sint, Time, Tod, Ulint,
        Usint, Wchar, Word,
    };

    fn cell(ty: ElemType, raw: u64) -> TraceCell {
        TraceCell::from_value(ty, raw)
    }

    fn encoded(signal: VcdSignal, cell: &TraceCell) -> String {
        let mut out = String::new();
        encode(&mut out, signal, cell).unwrap();
        out
    }

    #[test]
    fn identifiers_are_compact_and_distinct() {
        assert_eq!(identifier(0), "!");
        assert_eq!(identifier(93), "~");
        assert_eq!(identifier(94), "!!");
        assert_eq!(identifier(94 + 94 * 94), "!!!");
        let ids: std::collections::HashSet<String> = (0..20_000).map(identifier).collect();
        assert_eq!(ids.len(), 20_000);
    }

    #[test]
    fn timescales_follow_the_cycle() {
        let ts = |cycle, start| VcdTimescale::for_cycle(cycle, start).to_string();
        assert_eq!(ts(10_000_000, 0), "10 ms");
        assert_eq!(ts(1_000_000_000, 0), "1 s");
        assert_eq!(ts(60_000_000_000, 0), "10 s");
        assert_eq!(ts(2_500_000, 0), "100 us");
        assert_eq!(ts(1_500, 0), "100 ns");
        assert_eq!(ts(20, 0), "10 ns");
        assert_eq!(ts(7, 0), "1 ns");
        assert_eq!(ts(10_000_000, 1_000_000), "1 ms");
        assert_eq!(VcdTimescale::NANOSECOND.to_string(), "1 ns");
    }

    #[test]
    fn every_elementary_text_encodes_exactly() {
        let cases: &[(ElemType, i128, &str)] = &[
            (Sint, -128, "b10000000"),
            (Sint, 5, "b101"),
            (Int, -1, "b1111111111111111"),
            (
                Lint,
                i64::MIN as i128,
                "b1000000000000000000000000000000000000000000000000000000000000000",
            ),
            (Usint, 255, "b11111111"),
            (Ulint, u64::MAX as i128, &format!("b{}", "1".repeat(64))),
            (Byte, 0, "b0"),
            (Word, 0xA5, "b10100101"),
            (Lword, 1 << 63, &format!("b1{}", "0".repeat(63))),
            (Time, -2_000_000, &format!("b{:b}", -2_000_000i64 as u64)),
            (Time, i64::MIN as i128, &format!("b1{}", "0".repeat(63))),
            (Ltime, i64::MAX as i128, &format!("b{}", "1".repeat(63))),
            (
                Date,
                -86_400_000_000_000,
                &format!("b{:b}", -86_400_000_000_000i64 as u64),
            ),
            (Ltime, 1, "b1"),
            (
                Date,
                86_400_000_000_000,
                &format!("b{:b}", 86_400_000_000_000u64),
            ),
            (
                Tod,
                3_600_000_000_000,
                &format!("b{:b}", 3_600_000_000_000u64),
            ),
            (
                Dt,
                86_400_000_000_001,
                &format!("b{:b}", 86_400_000_000_001u64),
            ),
            (Char, 0xE9, "b11101001"),
            (Wchar, 0xD800, "b1101100000000000"),
            (Wchar, 0xE9, "b11101001"),
        ];
        for (ty, v, expected) in cases {
            assert_eq!(
                encoded(VcdSignal::Elementary(*ty), &cell(*ty, *v as u64)),
                *expected,
                "{ty:?} {v}"
            );
        }
        assert_eq!(encoded(VcdSignal::Elementary(Bool), &cell(Bool, 1)), "1");
        let real = |ty, raw| encoded(VcdSignal::Elementary(ty), &cell(ty, raw));
        assert_eq!(real(Real, u64::from(0.1f32.to_bits())), "r0.1");
        assert_eq!(real(Lreal, 1e300f64.to_bits()), "r1e300");
        assert_eq!(real(Lreal, f64::NAN.to_bits()), "rNaN");
        assert_eq!(real(Real, u64::from(f32::NEG_INFINITY.to_bits())), "r-inf");
    }

    #[test]
    fn strings_have_no_blanks() {
        let s = |text: &str| encoded(VcdSignal::String, &TraceCell::from_string(text, false));
        assert_eq!(s(""), "s\"\"");
        assert_eq!(s("a b"), "sa\\x20b");
        assert_eq!(s("\"\""), "s\\x22\\x22");
        assert_eq!(s("é\\"), "s\\xC3\\xA9\\x5C");
    }

    #[test]
    fn a_value_wider_than_its_column_is_refused() {
        let mut out = String::new();
        assert!(encode(&mut out, VcdSignal::Elementary(Sint), &cell(Int, 300)).is_err());
        assert!(encode(&mut out, VcdSignal::Elementary(Bool), &cell(Int, 1)).is_err());
        assert!(encode(&mut out, VcdSignal::String, &cell(Int, 1)).is_err());
    }

    #[test]
    fn paths_split_into_scopes() {
        assert_eq!(split_path("main.t1.Q"), ["main", "t1", "Q"]);
        assert_eq!(split_path("grid[1, 2].x"), ["grid[1,2]", "x"]);
        assert_eq!(split_path("%QX0.1"), ["%QX0.1"]);
        assert_eq!(split_path("n"), ["n"]);
    }

    fn write(
        names: &[&str],
        signals: &[VcdSignal],
        rows: &[(i64, Vec<TraceCell>)],
        changes_only: bool,
    ) -> String {
        let names = names.iter().map(|n| n.to_string()).collect();
        let mut sink = VcdSink::new(
            Vec::new(),
            names,
            signals.to_vec(),
            VcdTimescale::for_cycle(10_000_000, 0),
            changes_only,
        );
        for (time, cells) in rows {
            sink.row(*time, cells).unwrap();
        }
        String::from_utf8(sink.finish().unwrap()).unwrap()
    }

    #[test]
    fn a_whole_file() {
        let signals = [
            VcdSignal::Elementary(Bool),
            VcdSignal::Elementary(Int),
            VcdSignal::Elementary(Bool),
        ];
        let rows = vec![
            (0, vec![cell(Bool, 0), cell(Int, 3), cell(Bool, 1)]),
            (10_000_000, vec![cell(Bool, 1), cell(Int, 3), cell(Bool, 1)]),
            (20_000_000, vec![cell(Bool, 1), cell(Int, 3), cell(Bool, 1)]),
            (
                30_000_000,
                vec![cell(Bool, 1), cell(Int, -1i64 as u64), cell(Bool, 0)],
            ),
        ];
        let names = ["start", "main.t1.ET", "main.t1.Q"];
        let header = "$timescale 10 ms $end\n\
                      $var wire 1 ! start $end\n\
                      $scope module main $end\n\
                      \x20 $scope module t1 $end\n\
                      \x20   $var integer 16 \" ET $end\n\
                      \x20   $var wire 1 # Q $end\n\
                      \x20 $upscope $end\n\
                      $upscope $end\n\
                      $enddefinitions $end\n";
        let version = env!("CARGO_PKG_VERSION");
        let header = format!("$version plcrun {version} $end\n{header}");
        let body =
            "#0\n$dumpvars\n0!\nb11 \"\n1#\n$end\n#1\n1!\n#2\n#3\nb1111111111111111 \"\n0#\n";
        assert_eq!(
            write(&names, &signals, &rows, false),
            format!("{header}{body}")
        );
        let changes = "#0\n$dumpvars\n0!\nb11 \"\n1#\n$end\n#1\n1!\n#3\nb1111111111111111 \"\n0#\n";
        assert_eq!(
            write(&names, &signals, &rows, true),
            format!("{header}{changes}")
        );
    }

    #[test]
    fn an_empty_trace_is_a_header() {
        let text = write(&["x"], &[VcdSignal::Enum(Int)], &[], false);
        assert!(
            text.ends_with("$var integer 16 ! x $end\n$enddefinitions $end\n"),
            "{text}"
        );
    }

    #[test]
    fn times_off_the_timescale_or_going_back_are_errors() {
        let mut sink = VcdSink::new(
            Vec::new(),
            vec!["x".into()],
            vec![VcdSignal::Elementary(Bool)],
            VcdTimescale::for_cycle(10_000_000, 0),
            false,
        );
        assert!(sink.row(5, &[cell(Bool, 1)]).is_err());
        sink.row(0, &[cell(Bool, 1)]).unwrap();
        assert!(sink.row(0, &[cell(Bool, 1)]).is_err());
        assert!(sink.row(-10_000_000, &[cell(Bool, 1)]).is_err());
    }
}

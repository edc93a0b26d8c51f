//! Text helpers shared by the independent program models (`tests/support/*_models.rs`):
//! reading a cycle-keyed stimulus CSV, formatting trace values as IEC
//! literals, and comparing a model's trace with a committed expected file.
//!
//! Nothing here uses the plcrun engine: the expected traces in `programs/`
//! must be derived independently of it.
#![allow(dead_code)]

use std::path::PathBuf;

/// The virtual cycle time used by every committed scenario.
pub const CYCLE_MS: u64 = 10;

/// A cycle-keyed stimulus file: header `cycle,NAME,...`, then rows whose
/// non-empty cells are applied at the start of the first cycle whose number is
/// >= the row's cycle.
#[derive(Debug, Clone)]
pub struct Stimulus {
    pub names: Vec<String>,
    pub rows: Vec<(u64, Vec<Option<String>>)>,
}

impl Stimulus {
    pub fn parse(text: &str) -> Stimulus {
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let header: Vec<&str> = lines
            .next()
            .expect("stimulus has a header")
            .split(',')
            .map(str::trim)
            .collect();
        assert_eq!(header[0], "cycle", "model stimuli are cycle-keyed");
        let names = header[1..].iter().map(ToString::to_string).collect();
        let mut rows: Vec<(u64, Vec<Option<String>>)> = Vec::new();
        for line in lines {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            assert_eq!(cells.len(), header.len(), "bad stimulus row: {line}");
            let cycle: u64 = cells[0].parse().expect("cycle is an integer");
            if let Some((last, _)) = rows.last() {
                assert!(*last <= cycle, "stimulus rows must be in cycle order");
            }
            let values = cells[1..]
                .iter()
                .map(|c| (!c.is_empty()).then(|| c.to_string()))
                .collect();
            rows.push((cycle, values));
        }
        Stimulus { names, rows }
    }

    /// The (name, value) assignments due at the start of `cycle`, given that
    /// the rows before `*next` were applied already; advances `*next`.
    pub fn due(&self, cycle: u64, next: &mut usize) -> Vec<(String, String)> {
        let mut out = Vec::new();
        while *next < self.rows.len() && self.rows[*next].0 <= cycle {
            for (name, value) in self.names.iter().zip(&self.rows[*next].1) {
                if let Some(v) = value {
                    out.push((name.clone(), v.clone()));
                }
            }
            *next += 1;
        }
        out
    }
}

/// Parses an IEC BOOL literal as the stimulus accepts it.
pub fn parse_bool(text: &str) -> bool {
    match text.to_ascii_uppercase().as_str() {
        "TRUE" | "1" => true,
        "FALSE" | "0" => false,
        other => panic!("not a BOOL literal: {other}"),
    }
}

/// Parses the small subset of duration literals our stimuli use
/// (`T#100ms`, `T#5s`, `T#1s500ms`) into milliseconds.
pub fn parse_time_ms(text: &str) -> u64 {
    let upper = text.to_ascii_uppercase();
    let body = upper
        .strip_prefix("T#")
        .or_else(|| upper.strip_prefix("TIME#"))
        .expect("duration literal starts with T#");
    let mut total = 0u64;
    let mut rest = body.replace('_', "");
    while !rest.is_empty() {
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        rest = rest[digits.len()..].to_string();
        let unit: String = rest.chars().take_while(char::is_ascii_alphabetic).collect();
        rest = rest[unit.len()..].to_string();
        let n: u64 = digits.parse().expect("duration digits");
        total += n * match unit.as_str() {
            "D" => 86_400_000,
            "H" => 3_600_000,
            "M" => 60_000,
            "S" => 1_000,
            "MS" => 1,
            other => panic!("unsupported duration unit {other}"),
        };
    }
    total
}

/// Formats a duration in milliseconds as plcrun prints it: largest unit
/// first, zero parts omitted, `T#0s` for zero.
pub fn format_time_ms(ms: u64) -> String {
    if ms == 0 {
        return "T#0s".to_string();
    }
    let mut out = String::from("T#");
    let mut rest = ms;
    for (unit, size) in [
        ("d", 86_400_000),
        ("h", 3_600_000),
        ("m", 60_000),
        ("s", 1_000),
        ("ms", 1),
    ] {
        if rest >= size {
            out.push_str(&format!("{}{unit}", rest / size));
            rest %= size;
        }
    }
    out
}

pub fn bool_lit(b: bool) -> &'static str {
    if b { "TRUE" } else { "FALSE" }
}

/// Renders a trace as CSV text: header `cycle,time,NAME...`, one row per cycle.
pub fn trace_csv(names: &[&str], rows: &[Vec<String>]) -> String {
    let mut out = String::from("cycle,time");
    for n in names {
        out.push(',');
        out.push_str(n);
    }
    out.push('\n');
    for (k, row) in rows.iter().enumerate() {
        out.push_str(&format!("{k},{}", format_time_ms(k as u64 * CYCLE_MS)));
        for v in row {
            out.push(',');
            out.push_str(v);
        }
        out.push('\n');
    }
    out
}

/// The changes of a boolean trace: for every cycle, the list of `NAME+`/`NAME-`
/// (rising/falling compared with the previous row; the first row compares
/// with all FALSE). Cycles with no change are omitted.
pub fn bool_changes(names: &[&str], rows: &[Vec<bool>]) -> Vec<(usize, String)> {
    let mut prev = vec![false; names.len()];
    let mut out = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        let mut parts = Vec::new();
        for (i, (&now, &before)) in row.iter().zip(&prev).enumerate() {
            if now != before {
                parts.push(format!("{}{}", names[i], if now { "+" } else { "-" }));
            }
        }
        if !parts.is_empty() {
            out.push((k, parts.join(" ")));
        }
        prev.clone_from(row);
    }
    out
}

pub fn repo_path(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(relative)
}

pub fn read_repo_file(relative: &str) -> String {
    let path = repo_path(relative);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

/// Compares `actual` with the committed file `relative`. With the environment
/// variable `PLCRUN_BLESS_MODELS=1` the file is (re)written from the model
/// instead -- only ever do that after checking the change by hand.
pub fn check_or_bless(relative: &str, actual: &str) {
    if std::env::var_os("PLCRUN_BLESS_MODELS").is_some_and(|v| v == "1") {
        std::fs::write(repo_path(relative), actual).expect("write expected file");
        return;
    }
    let expected = read_repo_file(relative);
    if expected == actual {
        return;
    }
    let line = expected
        .lines()
        .zip(actual.lines())
        .position(|(e, a)| e != a)
        .map(|i| {
            format!(
                "first difference at line {}:\n  file:  {}\n  model: {}",
                i + 1,
                expected.lines().nth(i).unwrap_or(""),
                actual.lines().nth(i).unwrap_or("")
            )
        })
        .unwrap_or_else(|| {
            format!(
                "line counts differ: file {} lines, model {} lines",
                expected.lines().count(),
                actual.lines().count()
            )
        });
    panic!("{relative} does not match its independent model; {line}");
}

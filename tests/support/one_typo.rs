//! The "one typo, one error" measure (issue #13 point 3), shared by
//! `tests/one_typo.rs` (a sampled run with a threshold) and
//! `examples/one_typo.rs` (the full figure for docs/robustness.md).
//!
//! Method: a program that compiles cleanly is lexed with plcrun's own
//! lexer; at a chosen token, one of three typos is made in the source
//! text: the token is deleted, duplicated (written twice, separated by a
//! space) or replaced by another token from [`REPLACEMENTS`] (chosen from
//! the position, so a run is reproducible). The mutant is checked
//! (`plcrun::check`, parse and semantic analysis). A mutant that still
//! compiles without error is "silent" (the typo made another valid
//! program, e.g. `+` replaced by `-`) and is counted apart; every other
//! mutant scores when it gives exactly one error and that error is on the
//! line of the typo.
#![allow(dead_code)]

use plcrun::syntax::lexer;
use plcrun::syntax::token::Tok;
use plcrun::{CheckOptions, Diagnostics, FileId, Severity, SourceMap, check};

/// The three kinds of typo.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Typo {
    /// The token is removed.
    Delete,
    /// The token is written twice.
    Duplicate,
    /// The token is replaced by another one.
    Replace,
}

/// Tokens a typo replaces another with: punctuation, operators, keywords,
/// a name and a literal.
pub const REPLACEMENTS: [&str; 16] = [
    ";", ":=", "(", ")", ",", ":", "+", "=", "IF", "END_IF", "THEN", "x_typo", "1", ".", "[",
    "END_VAR",
];

/// What happened to one mutant.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// Exactly one error, on the altered line.
    One,
    /// The mutant compiles: the typo made another valid program.
    Silent,
    /// Several errors, or one on another line.
    Miss {
        /// How many errors.
        errors: usize,
        /// Their lines.
        lines: Vec<usize>,
        /// The first few, as `line: [code] message`.
        first: Vec<String>,
    },
}

/// The tally of a run.
#[derive(Debug, Default, Clone)]
pub struct Tally {
    /// Mutants with exactly one error on the right line.
    pub one: usize,
    /// Mutants that still compile.
    pub silent: usize,
    /// Mutants with more errors or errors elsewhere.
    pub miss: usize,
    /// A few misses, described, for the report.
    pub examples: Vec<String>,
}

impl Tally {
    /// Mutants that gave at least one error.
    pub fn detected(&self) -> usize {
        self.one + self.miss
    }

    /// The proportion of detected mutants with exactly one error on the
    /// altered line, in percent.
    pub fn percent(&self) -> f64 {
        if self.detected() == 0 {
            return 100.0;
        }
        100.0 * self.one as f64 / self.detected() as f64
    }

    /// Adds another tally.
    pub fn add(&mut self, other: &Tally) {
        self.one += other.one;
        self.silent += other.silent;
        self.miss += other.miss;
        self.examples.extend(other.examples.iter().cloned());
    }
}

/// The tokens of `text` as byte ranges (line ends of IL are not tokens).
pub fn token_spans(text: &str) -> Vec<(usize, usize)> {
    let mut diags = Diagnostics::new();
    lexer::lex(FileId(0), text, &mut diags)
        .into_iter()
        .filter(|(l, tok, r)| *tok != Tok::Eol && r > l)
        .map(|(l, _, r)| (l, r))
        .collect()
}

/// `text` with `typo` made at token `(l, r)`; `choice` picks the replacement.
pub fn mutate(text: &str, (l, r): (usize, usize), typo: Typo, choice: usize) -> String {
    let token = &text[l..r];
    match typo {
        Typo::Delete => format!("{}{}", &text[..l], &text[r..]),
        Typo::Duplicate => format!("{}{token} {token}{}", &text[..l], &text[r..]),
        Typo::Replace => {
            let mut pick = REPLACEMENTS[choice % REPLACEMENTS.len()];
            if pick.eq_ignore_ascii_case(token) {
                pick = REPLACEMENTS[(choice + 1) % REPLACEMENTS.len()];
            }
            format!("{}{pick}{}", &text[..l], &text[r..])
        }
    }
}

/// 1-based line of byte `offset`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// Checks `text` (named `name`) and returns its errors as (line, `[code] message`).
pub fn errors(name: &str, text: &str) -> Vec<(usize, String)> {
    let mut sources = SourceMap::new();
    sources.add(name, text.to_string());
    let report = check(&sources, &CheckOptions::default());
    report
        .diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| {
            (
                line_of(text, d.span.start as usize),
                format!("[{}] {}", d.code, d.message),
            )
        })
        .collect()
}

/// The lines of the errors of `text`.
pub fn error_lines(name: &str, text: &str) -> Vec<usize> {
    errors(name, text).into_iter().map(|e| e.0).collect()
}

/// Checks one mutant whose typo is on byte `at`.
pub fn judge(name: &str, mutant: &str, at: usize) -> Outcome {
    let found = errors(name, mutant);
    let lines: Vec<usize> = found.iter().map(|e| e.0).collect();
    let line = line_of(mutant, at);
    match lines.as_slice() {
        [] => Outcome::Silent,
        [one] if *one == line => Outcome::One,
        _ => Outcome::Miss {
            errors: lines.len(),
            lines,
            first: found
                .iter()
                .take(3)
                .map(|(l, m)| format!("{l}: {m}"))
                .collect(),
        },
    }
}

/// Measures `text` (which must compile): every `stride`-th token, starting
/// at `offset`, gets each of the three typos.
pub fn measure(name: &str, text: &str, stride: usize, offset: usize) -> Tally {
    assert!(
        error_lines(name, text).is_empty(),
        "{name} must compile before it is mutated"
    );
    let spans = token_spans(text);
    let mut tally = Tally::default();
    for (i, &span) in spans.iter().enumerate().skip(offset).step_by(stride.max(1)) {
        for typo in [Typo::Delete, Typo::Duplicate, Typo::Replace] {
            let mutant = mutate(text, span, typo, i);
            match judge(name, &mutant, span.0) {
                Outcome::One => tally.one += 1,
                Outcome::Silent => tally.silent += 1,
                Outcome::Miss {
                    errors,
                    mut lines,
                    first,
                } => {
                    tally.miss += 1;
                    if tally.examples.len() < 30 {
                        lines.truncate(12);
                        tally.examples.push(format!(
                            "{name}: {typo:?} `{}` at line {}: {errors} errors on lines {lines:?}...\n    {}",
                            &text[span.0..span.1],
                            line_of(text, span.0),
                            first.join("\n    ")
                        ));
                    }
                }
            }
        }
    }
    tally
}

/// The programs of `programs/` (IEC text: `.st`, `.il`, `.sfc`, and S7-200
/// `.awl`) that compile with the default options, as (name, text).
pub fn shipped_programs() -> Vec<(String, String)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/programs");
    let mut out = Vec::new();
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("programs/ is readable")
        .filter_map(Result::ok)
        .map(|e| e.path())
        .collect();
    entries.sort();
    for path in entries {
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !["st", "il", "sfc", "awl"].contains(&ext) {
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let bytes = std::fs::read(&path).expect("program readable");
        let text = String::from_utf8_lossy(&bytes).into_owned();
        // Programs that need an option (`--grafcet`) are left out.
        if error_lines(&name, &text).is_empty() {
            out.push((name, text));
        }
    }
    out
}

/// Larger generated programs: `n` function blocks, functions and a
/// program using them, in ST, and an IL program of the same shape.
pub fn generated_programs(n: usize) -> Vec<(String, String)> {
    let mut st = String::new();
    st.push_str("TYPE\n  Mode : (Idle, Run, Stop);\n  Point : STRUCT\n    x : INT;\n    y : INT;\n  END_STRUCT;\nEND_TYPE\n\n");
    for i in 0..n {
        st.push_str(&format!(
            "FUNCTION Scale{i} : INT\nVAR_INPUT\n  v : INT;\n  k : INT;\nEND_VAR\nIF k > 0 THEN\n  Scale{i} := v * k + {i};\nELSE\n  Scale{i} := v - {i};\nEND_IF;\nEND_FUNCTION\n\n"
        ));
        st.push_str(&format!(
            "FUNCTION_BLOCK Unit{i}\nVAR_INPUT\n  start : BOOL;\n  limit : INT := {};\nEND_VAR\nVAR_OUTPUT\n  count : INT;\n  done : BOOL;\nEND_VAR\nVAR\n  mode : Mode := Idle;\n  p : Point;\n  hist : ARRAY[0..7] OF INT;\n  t : TON;\n  j : INT;\nEND_VAR\nCASE mode OF\n  Idle:\n    IF start THEN\n      mode := Run;\n    END_IF;\n  Run:\n    count := count + 1;\n    p.x := Scale{i}(v := count, k := 2);\n    FOR j := 0 TO 7 DO\n      hist[j] := hist[j] + p.x MOD 3;\n    END_FOR;\n    IF count >= limit THEN\n      mode := Stop;\n    END_IF;\nELSE\n  done := TRUE;\n  WHILE p.y < 3 DO\n    p.y := p.y + 1;\n  END_WHILE;\nEND_CASE;\nt(IN := done, PT := T#10ms);\nEND_FUNCTION_BLOCK\n\n",
            10 + i
        ));
    }
    st.push_str("PROGRAM Main\nVAR\n  go : BOOL := TRUE;\n  total : INT;\n");
    for i in 0..n {
        st.push_str(&format!("  u{i} : Unit{i};\n"));
    }
    st.push_str("END_VAR\n");
    for i in 0..n {
        st.push_str(&format!(
            "u{i}(start := go, limit := {});\ntotal := total + u{i}.count;\n",
            5 + i
        ));
    }
    st.push_str("IF total > 1000 THEN\n  total := 0;\nELSIF NOT go THEN\n  total := -1;\nEND_IF;\nEND_PROGRAM\n");

    let mut il =
        String::from("PROGRAM Lines\nVAR\n  a : INT;\n  b : INT;\n  c : BOOL;\n  t1 : TON;\n");
    for i in 0..n {
        il.push_str(&format!("  m{i} : BOOL;\n"));
    }
    il.push_str("END_VAR\n");
    for i in 0..n {
        il.push_str(&format!(
            "  LD a\n  ADD {i}\n  ST a\n  LD m{i}\n  AND c\n  OR( b\n  GT 3\n  )\n  ST m{i}\n  JMPC skip{i}\n  LD b\n  ADD 1\n  ST b\nskip{i}:\n  CAL t1(IN := c, PT := T#5ms)\n"
        ));
    }
    il.push_str("  LD t1.Q\n  ST c\nEND_PROGRAM\n");
    vec![
        ("generated.st".to_string(), st),
        ("generated.il".to_string(), il),
    ]
}

//! The seed corpus, collected from the repository instead of kept twice:
//! the source files under `programs/`, `tests/` and `examples/`, and the
//! programs written as string literals inside the Rust tests.

use std::path::{Path, PathBuf};

/// The front-end a seed is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// ST, IL or SFC text (one parser).
    Iec,
    /// Instruction List text (also [`Kind::Iec`], but named `.il`).
    Il,
    /// S7-200 STL.
    S7,
    /// PLCopen TC6 XML.
    PlcOpen,
}

impl Kind {
    /// The first byte of a whole-pipeline input (`check`, `run`) that
    /// makes it read as this kind (see `targets::named`).
    pub fn prefix(self) -> u8 {
        match self {
            Kind::Iec => b'0',
            Kind::Il => b'1',
            Kind::S7 => b'2',
            Kind::PlcOpen => b'3',
        }
    }

    /// The fuzz targets whose corpus takes this kind's seeds as they are.
    pub fn targets(self) -> &'static [&'static str] {
        match self {
            Kind::Iec | Kind::Il => &["lex", "parse"],
            Kind::S7 => &["lex", "s7"],
            Kind::PlcOpen => &["plcopen"],
        }
    }
}

/// One seed: where it came from, its kind and its bytes.
#[derive(Debug, Clone)]
pub struct Seed {
    /// `path` or `path#n` for the n-th literal of a Rust file.
    pub origin: String,
    /// Its front-end.
    pub kind: Kind,
    /// The text.
    pub bytes: Vec<u8>,
}

fn kind_of(path: &Path) -> Option<Kind> {
    match path.extension()?.to_str()? {
        "st" | "sfc" | "exp" | "EXP" => Some(Kind::Iec),
        "il" => Some(Kind::Il),
        "awl" | "stl" => Some(Kind::S7),
        "xml" => Some(Kind::PlcOpen),
        _ => None,
    }
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            walk(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// Every seed under `root` (the repository): source files by extension,
/// and string literals of `.rs` files that hold a POU, a type or a
/// PLCopen project.
pub fn collect(root: &Path) -> Vec<Seed> {
    let mut files = Vec::new();
    for dir in ["programs", "tests", "examples"] {
        walk(&root.join(dir), &mut files);
    }
    let mut seeds = Vec::new();
    for path in files {
        let origin = path
            .strip_prefix(root)
            .unwrap_or(&path)
            .display()
            .to_string();
        let Ok(bytes) = std::fs::read(&path) else {
            continue;
        };
        if path.extension().is_some_and(|e| e == "rs") {
            let text = String::from_utf8_lossy(&bytes);
            for (n, lit) in string_literals(&text).into_iter().enumerate() {
                if let Some(kind) = literal_kind(&lit) {
                    seeds.push(Seed {
                        origin: format!("{origin}#{n}"),
                        kind,
                        bytes: lit.into_bytes(),
                    });
                }
            }
        } else if let Some(kind) = kind_of(&path) {
            seeds.push(Seed {
                origin,
                kind,
                bytes,
            });
        }
    }
    seeds
}

/// The kind of a string literal worth seeding with, if any.
fn literal_kind(lit: &str) -> Option<Kind> {
    let upper = lit.to_ascii_uppercase();
    if upper.contains("<PROJECT") {
        Some(Kind::PlcOpen)
    } else if upper.contains("NETWORK") && upper.contains("LD ") {
        Some(Kind::S7)
    } else if [
        "END_PROGRAM",
        "END_FUNCTION",
        "END_TYPE",
        "END_CONFIGURATION",
    ]
    .iter()
    .any(|end| upper.contains(end))
    {
        Some(Kind::Iec)
    } else {
        None
    }
}

/// The contents of the string literals of Rust source `text`: plain
/// literals with their escapes undone, raw literals as written.
fn string_literals(text: &str) -> Vec<String> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            // A comment: skip to the end of the line.
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            // A character literal such as '"' must not open a string.
            b'\'' if b.get(i + 2) == Some(&b'\'') => i += 3,
            b'\'' if b.get(i + 1) == Some(&b'\\') && b.get(i + 3) == Some(&b'\'') => i += 4,
            b'r' if matches!(b.get(i + 1), Some(b'#' | b'"'))
                && (i == 0 || !b[i - 1].is_ascii_alphanumeric()) =>
            {
                let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
                let open = i + 1 + hashes;
                if b.get(open) != Some(&b'"') {
                    i += 1;
                    continue;
                }
                let close: String = std::iter::once('"')
                    .chain(std::iter::repeat_n('#', hashes))
                    .collect();
                match text[open + 1..].find(&close) {
                    Some(len) => {
                        out.push(text[open + 1..open + 1 + len].to_string());
                        i = open + 1 + len + close.len();
                    }
                    None => break,
                }
            }
            b'"' => {
                let (lit, end) = plain_literal(text, i + 1);
                out.push(lit);
                i = end;
            }
            _ => i += 1,
        }
    }
    out
}

/// A plain string literal starting after its quote at `start`: its value
/// and the index after its closing quote.
fn plain_literal(text: &str, start: usize) -> (String, usize) {
    let mut value = String::new();
    let mut chars = text[start..].char_indices().peekable();
    while let Some((at, c)) = chars.next() {
        match c {
            '"' => return (value, start + at + 1),
            '\\' => match chars.next() {
                Some((_, 'n')) => value.push('\n'),
                Some((_, 't')) => value.push('\t'),
                Some((_, 'r')) => value.push('\r'),
                Some((_, '0')) => value.push('\0'),
                Some((_, '\n')) => {
                    // A line continuation also drops the next line's indent.
                    while chars.peek().is_some_and(|(_, c)| c.is_whitespace()) {
                        chars.next();
                    }
                }
                Some((_, other)) => value.push(other),
                None => break,
            },
            c => value.push(c),
        }
    }
    (value, text.len())
}

/// The corpus of each target: `(target, file name, bytes)`. The
/// whole-pipeline targets take every seed behind its kind's prefix byte;
/// `gen_diff`, whose inputs are the generator's choices, starts from 32
/// pseudo-random inputs of 0.5 to 4 KiB (a fixed sequence), and
/// `engines_agree` from every fourth of them.
pub fn corpora(seeds: &[Seed]) -> Vec<(&'static str, String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut state: u64 = 0x2545_F491_4F6C_DD1D;
    for n in 0..32 {
        let bytes: Vec<u8> = (0..512 * (n % 8 + 1))
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 24) as u8
            })
            .collect();
        if n % 4 == 0 {
            out.push(("engines_agree", format!("random{n:02}"), bytes.clone()));
        }
        out.push(("gen_diff", format!("random{n:02}"), bytes));
    }
    for (n, seed) in seeds.iter().enumerate() {
        let name = format!("seed{n:04}");
        for target in seed.kind.targets() {
            out.push((*target, name.clone(), seed.bytes.clone()));
        }
        let mut prefixed = vec![seed.kind.prefix()];
        prefixed.extend_from_slice(&seed.bytes);
        out.push(("check", name.clone(), prefixed.clone()));
        out.push(("run", name, prefixed));
    }
    // The network servers' request paths take protocol frames, not
    // programs: their seeds are written in the target's file.
    for (name, bytes) in super::targets::modbus_seeds() {
        out.push(("modbus", name, bytes));
    }
    #[cfg(feature = "opcua")]
    for (name, bytes) in super::targets::opcua_write_seeds() {
        out.push(("opcua_write", name, bytes));
    }
    out
}

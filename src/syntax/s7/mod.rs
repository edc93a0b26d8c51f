//! The Siemens S7-200 STL front-end (docs/s7-200.md): a `.awl`/`.stl` file,
//! or a text whose first line of code is a `NETWORK` header, a Micro/WIN
//! block header or an S7-200 instruction, is read as the statement list of
//! STEP 7-Micro/WIN (or of the older listings) and lowered into the same AST
//! as IL, ST and SFC: one PROGRAM `OB1` whose memory areas are arrays of
//! BYTE shared by every bit, byte, word and double-word view.

mod build;
mod instr;
mod lines;
mod lower;
mod operands;
mod program;
mod support;
mod views;

use crate::diagnostics::{Diagnostic, Diagnostics};
use crate::source::FileId;
use crate::syntax::ast::CompilationUnit;
use instr::{Lookup, Op, lookup};
use lines::{Line, Word};
use lower::{Instr, Routine, routine_number};

/// The IEC keywords that make a text IEC source, not S7-200 STL.
const IEC_KEYWORDS: &[&str] = &[
    "PROGRAM",
    "FUNCTION",
    "FUNCTION_BLOCK",
    "CONFIGURATION",
    "TYPE",
    "VAR_GLOBAL",
    "ACTION",
];

/// Whether the file `name` with content `text` is S7-200 STL: by its
/// extension (`.awl`, `.stl`), else by its first line of code (a `NETWORK`
/// header, a Micro/WIN `ORGANIZATION_BLOCK`/`SUBROUTINE_BLOCK`, or an S7-200
/// instruction such as `LD I0.0`) in a text with no IEC POU keyword.
pub fn recognise(name: &str, text: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    if lower.ends_with(".awl") || lower.ends_with(".stl") {
        return true;
    }
    let mut first = None;
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("").trim();
        let Some(word) = code.split_whitespace().next() else {
            continue;
        };
        let word = word.to_ascii_uppercase();
        if IEC_KEYWORDS.contains(&word.as_str()) {
            return false;
        }
        if first.is_none() {
            first = Some((word, code.to_string()));
        }
    }
    let Some((word, code)) = first else {
        return false;
    };
    if lines::is_network(&word) || word == "ORGANIZATION_BLOCK" || word == "SUBROUTINE_BLOCK" {
        return true;
    }
    // An instruction with an S7 operand: `LD I0.0`, `LDW= VW0, 5`.
    let mut parts = code
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|s| !s.is_empty());
    let _ = parts.next();
    matches!(lookup(&word), Lookup::Known(_))
        && parts.next().is_some_and(|op| {
            operands::parse_operand(op).is_ok_and(|o| !matches!(o, operands::Operand::Const(_)))
        })
}

/// Parses and lowers one S7-200 STL file. Never panics; every instruction
/// or operand it cannot run is a coded diagnostic (E850–E866, W850).
pub fn parse(file: FileId, text: &str, diags: &mut Diagnostics) -> CompilationUnit {
    let routines = routines(file, text, diags);
    program::build(file, text, &routines, diags)
}

/// Splits the lines into the main program and the subroutines.
fn routines(file: FileId, text: &str, diags: &mut Diagnostics) -> Vec<Routine> {
    let start = crate::source::Span::new(file, 0, 0);
    let mut out = vec![Routine {
        number: None,
        instrs: Vec::new(),
        span: start,
    }];
    // Where instructions go: a routine, or nowhere (an unsupported block).
    let mut current = Some(0);
    let mut in_vars = false;
    let mut ended_main = false;
    for line in lines::lines(file, text) {
        match line {
            Line::Network => {}
            Line::Block(head, rest) => match head.text.as_str() {
                "VAR_INPUT" | "VAR_OUTPUT" | "VAR_IN_OUT" | "VAR" | "VAR_TEMP" => {
                    diags.push(Diagnostic::error(
                        "E864",
                        head.span,
                        "subroutine parameters and local variables (L memory) are not supported",
                    ));
                    in_vars = true;
                }
                "END_VAR" => in_vars = false,
                "ORGANIZATION_BLOCK" => current = Some(0),
                "SUBROUTINE_BLOCK" => {
                    current = start_routine(&mut out, &head, &rest, diags);
                }
                "INTERRUPT_BLOCK" => {
                    diags.push(Diagnostic::error(
                        "E864",
                        head.span,
                        "interrupt routines (INTERRUPT_BLOCK) are not supported",
                    ));
                    current = None;
                }
                _ => {}
            },
            Line::Instr { .. } if in_vars => {}
            Line::Instr {
                mnemonic,
                operands,
                span,
            } => {
                let op = match lookup(&mnemonic.text) {
                    Lookup::Known(op) => op,
                    Lookup::Unsupported => {
                        diags.push(Diagnostic::error(
                            "E851",
                            mnemonic.span,
                            format!(
                                "the S7-200 instruction `{}` is not supported by plcrun",
                                mnemonic.text
                            ),
                        ));
                        continue;
                    }
                    Lookup::Unknown => {
                        diags.push(Diagnostic::error(
                            "E850",
                            mnemonic.span,
                            format!("`{}` is not an S7-200 instruction", mnemonic.text),
                        ));
                        continue;
                    }
                };
                if op == Op::Sbr {
                    current = start_routine(&mut out, &mnemonic, &operands, diags);
                    continue;
                }
                let Some(i) = current else {
                    continue;
                };
                if i == 0 && ended_main {
                    diags.push(Diagnostic::warning(
                        "W850",
                        span,
                        "this instruction follows MEND and never runs",
                    ));
                    ended_main = false;
                }
                if i == 0 && op == Op::Mend {
                    ended_main = true;
                }
                out[i].instrs.push(Instr {
                    op,
                    mnemonic: mnemonic.text,
                    operands,
                    span,
                });
            }
        }
    }
    out
}

/// Starts subroutine `SBR n` (from `SBR n`, `SBR Kn` or a Micro/WIN
/// `SUBROUTINE_BLOCK SBR_n:SBRn` header); its index in `out`, or `None`
/// when the number is missing or taken (reported).
fn start_routine(
    out: &mut Vec<Routine>,
    head: &Word,
    rest: &[Word],
    diags: &mut Diagnostics,
) -> Option<usize> {
    let number = rest
        .first()
        .and_then(|w| w.text.split(':').find_map(routine_number));
    let Some(n) = number.filter(|n| *n <= 255) else {
        diags.push(Diagnostic::error(
            "E862",
            head.span,
            "`SBR` needs the subroutine's number (`SBR 0`, `SBR K0`)",
        ));
        return None;
    };
    if out.iter().any(|r| r.number == Some(n)) {
        diags.push(Diagnostic::error(
            "E859",
            head.span,
            format!("subroutine {n} is defined twice"),
        ));
        return None;
    }
    out.push(Routine {
        number: Some(n),
        instrs: Vec::new(),
        span: head.span,
    });
    Some(out.len() - 1)
}

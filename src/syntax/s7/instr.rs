//! The S7-200 STL mnemonics this front-end knows: the English (SIMATIC
//! international) set as STEP 7-Micro/WIN writes it, the German forms the
//! seed listings use (`U`/`UN` for `A`/`AN`, `UNDW`/`UNDD` for
//! `ANDW`/`ANDD`, `UB>=` for `AB>=`), and the instructions the CPU has that
//! plcrun does not model (refused with a diagnostic naming them).

use super::operands::Width;

/// How a comparison combines with the top of the logic stack.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Combine {
    /// `LD…`: push the result.
    Load,
    /// `A…`: AND it into the top.
    And,
    /// `O…`: OR it into the top.
    Or,
}

/// A comparison relation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Rel {
    /// `=` (also `==`).
    Eq,
    /// `<>`.
    Ne,
    /// `<`.
    Lt,
    /// `<=`.
    Le,
    /// `>`.
    Gt,
    /// `>=`.
    Ge,
}

/// A word-logic operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Logic {
    /// `AND…`
    And,
    /// `OR…`
    Or,
    /// `XOR…`
    Xor,
}

/// An integer operation of the two-operand form `IN1, OUT` (OUT := OUT op IN1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Arith {
    /// `+I`, `+D`
    Add,
    /// `-I`, `-D`
    Sub,
    /// `*I`, `*D`
    Mul,
    /// `/I`, `/D`
    Div,
}

/// A timer kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum TimerKind {
    /// On-delay.
    Ton,
    /// Retentive on-delay.
    Tonr,
    /// Off-delay.
    Tof,
}

/// A counter kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum CounterKind {
    /// Up.
    Ctu,
    /// Down.
    Ctd,
    /// Up/down.
    Ctud,
}

/// A supported instruction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Op {
    /// `LD bit`
    Ld,
    /// `LDN bit`
    Ldn,
    /// `A bit` (German `U`)
    A,
    /// `AN bit` (German `UN`)
    An,
    /// `O bit`
    O,
    /// `ON bit`
    On,
    /// `= bit`
    Assign,
    /// `S bit, n`
    Set,
    /// `R bit, n` (also timers and counters)
    Reset,
    /// `ALD`
    Ald,
    /// `OLD`
    Old,
    /// `LPS`
    Lps,
    /// `LRD`
    Lrd,
    /// `LPP`
    Lpp,
    /// `NOT`
    Not,
    /// `EU`
    Eu,
    /// `ED`
    Ed,
    /// `LDB= …`, `AW< …`, `OD>= …`
    Compare(Combine, Width, Rel),
    /// `TON`, `TONR`, `TOF`
    Timer(TimerKind),
    /// `CTU`, `CTD`, `CTUD`
    Counter(CounterKind),
    /// `MOVB`, `MOVW`, `MOVD` (and `MOVR`, a double-word move)
    Move(Width),
    /// `FILL IN, OUT, N` (N words)
    Fill,
    /// `BMB`, `BMW`, `BMD`
    BlockMove(Width),
    /// `ANDB` … `XORD`
    Logic(Logic, Width),
    /// `INVB`, `INVW`, `INVD`
    Invert(Width),
    /// `+I` … `/D`
    Arith(Arith, Width),
    /// `MUL IN1, OUT` (16 × 16 → 32 bits)
    Mul,
    /// `DIV IN1, OUT` (32-bit OUT: remainder high word, quotient low word)
    Div,
    /// `INCB`, `INCW`, `INCD`
    Inc(Width),
    /// `DECB`, `DECW`, `DECD`
    Dec(Width),
    /// `SLB`/`SRB`/`RLB`/`RRB` … `OUT, N`: shift (left or right) or
    /// rotate (`true`) by a constant N.
    Shift(bool, bool, Width),
    /// `SWAP IN`: exchange the two bytes of a word.
    Swap,
    /// `BTI ITB ITD DTI IN, OUT`: integer conversions between widths.
    Convert(Width, Width),
    /// `JMP n`
    Jmp,
    /// `LBL n`
    Lbl,
    /// `CALL n`
    Call,
    /// `SBR n`
    Sbr,
    /// `RET`
    Ret,
    /// `CRET`
    Cret,
    /// `MEND`
    Mend,
    /// `END`
    End,
    /// `NOP`
    Nop,
}

/// What a mnemonic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Lookup {
    /// A supported instruction.
    Known(Op),
    /// An S7-200 instruction plcrun does not model.
    Unsupported,
    /// Not an S7-200 mnemonic.
    Unknown,
}

/// Instructions of the S7-200 that are refused (a coded diagnostic, never
/// a silent skip).
const UNSUPPORTED: &[&str] = &[
    "STOP", "WDR", "LSCR", "SCRT", "SCRE", "CSCRE", "FOR", "NEXT", "SHRB", "+R", "-R", "*R", "/R",
    "SQRT", "SIN", "COS", "TAN", "LN", "EXP", "PID", "BCDI", "IBCD", "DTR", "TRUNC", "ROUND",
    "ATCH", "DTCH", "ENI", "DISI", "CRETI", "RETI", "HDEF", "HSC", "PLS", "XMT", "RCV", "NETR",
    "NETW", "ATT", "FND=", "FND<>", "FND<", "FND>", "LIFO", "FIFO", "SEG", "DECO", "ENCO", "ATH",
    "HTA", "ITA", "DTA", "RTA", "TODR", "TODW", "AENO", "BIR", "BIW", "LDR=", "LDR<>", "LDR<",
    "LDR<=", "LDR>", "LDR>=", "AR=", "OR=", "LDS=", "LDS<>", "SCAT", "SCPY", "SLEN", "SSCPY",
    "SFND", "CFND", "STR", "TON_IEC",
];

/// Parses a comparison mnemonic (`LDW>=`, `AB=`, `UB>=`, `OD<>`).
fn comparison(m: &str) -> Option<Op> {
    let (combine, rest) = if let Some(r) = m.strip_prefix("LD") {
        (Combine::Load, r)
    } else if let Some(r) = m.strip_prefix('A').or_else(|| m.strip_prefix('U')) {
        (Combine::And, r)
    } else if let Some(r) = m.strip_prefix('O') {
        (Combine::Or, r)
    } else {
        return None;
    };
    let width = match rest.as_bytes().first()? {
        b'B' => Width::B,
        b'W' => Width::W,
        b'D' => Width::D,
        _ => return None,
    };
    let rel = match &rest[1..] {
        "=" | "==" => Rel::Eq,
        "<>" => Rel::Ne,
        "<" => Rel::Lt,
        "<=" => Rel::Le,
        ">" => Rel::Gt,
        ">=" => Rel::Ge,
        _ => return None,
    };
    Some(Op::Compare(combine, width, rel))
}

/// Looks a mnemonic up (case-insensitive).
pub(super) fn lookup(mnemonic: &str) -> Lookup {
    let m = mnemonic.to_ascii_uppercase();
    if UNSUPPORTED.contains(&m.as_str()) {
        return Lookup::Unsupported;
    }
    if let Some(op) = comparison(&m) {
        return Lookup::Known(op);
    }
    use Width::{B, D, W};
    let op = match m.as_str() {
        // The immediate forms read and write the same images here: there is
        // no physical I/O between the image and the program.
        "LD" | "LDI" => Op::Ld,
        "LDN" | "LDNI" => Op::Ldn,
        "A" | "U" | "AI" | "UI" => Op::A,
        "AN" | "UN" | "ANI" | "UNI" => Op::An,
        "O" | "OI" => Op::O,
        "ON" | "ONI" => Op::On,
        "=" | "=I" => Op::Assign,
        "S" | "SI" => Op::Set,
        "R" | "RI" => Op::Reset,
        "ALD" | "ULD" => Op::Ald,
        "OLD" => Op::Old,
        "LPS" => Op::Lps,
        "LRD" => Op::Lrd,
        "LPP" => Op::Lpp,
        "NOT" => Op::Not,
        "EU" => Op::Eu,
        "ED" => Op::Ed,
        "TON" => Op::Timer(TimerKind::Ton),
        "TONR" => Op::Timer(TimerKind::Tonr),
        "TOF" => Op::Timer(TimerKind::Tof),
        "CTU" => Op::Counter(CounterKind::Ctu),
        "CTD" => Op::Counter(CounterKind::Ctd),
        "CTUD" => Op::Counter(CounterKind::Ctud),
        "MOVB" => Op::Move(B),
        "MOVW" => Op::Move(W),
        "MOVD" | "MOVR" => Op::Move(D),
        "FILL" => Op::Fill,
        "BMB" => Op::BlockMove(B),
        "BMW" => Op::BlockMove(W),
        "BMD" => Op::BlockMove(D),
        "ANDB" | "UNDB" => Op::Logic(Logic::And, B),
        "ANDW" | "UNDW" => Op::Logic(Logic::And, W),
        "ANDD" | "UNDD" => Op::Logic(Logic::And, D),
        "ORB" | "ODERB" => Op::Logic(Logic::Or, B),
        "ORW" | "ODERW" => Op::Logic(Logic::Or, W),
        "ORD" | "ODERD" => Op::Logic(Logic::Or, D),
        "XORB" => Op::Logic(Logic::Xor, B),
        "XORW" => Op::Logic(Logic::Xor, W),
        "XORD" => Op::Logic(Logic::Xor, D),
        "INVB" => Op::Invert(B),
        "INVW" => Op::Invert(W),
        "INVD" => Op::Invert(D),
        "+I" => Op::Arith(Arith::Add, W),
        "-I" => Op::Arith(Arith::Sub, W),
        "*I" => Op::Arith(Arith::Mul, W),
        "/I" => Op::Arith(Arith::Div, W),
        "+D" => Op::Arith(Arith::Add, D),
        "-D" => Op::Arith(Arith::Sub, D),
        "*D" => Op::Arith(Arith::Mul, D),
        "/D" => Op::Arith(Arith::Div, D),
        "MUL" => Op::Mul,
        "DIV" => Op::Div,
        "INCB" => Op::Inc(B),
        "INCW" => Op::Inc(W),
        "INCD" => Op::Inc(D),
        "DECB" => Op::Dec(B),
        "DECW" => Op::Dec(W),
        "DECD" => Op::Dec(D),
        "SLB" => Op::Shift(true, false, B),
        "SLW" => Op::Shift(true, false, W),
        "SLD" => Op::Shift(true, false, D),
        "SRB" => Op::Shift(false, false, B),
        "SRW" => Op::Shift(false, false, W),
        "SRD" => Op::Shift(false, false, D),
        "RLB" => Op::Shift(true, true, B),
        "RLW" => Op::Shift(true, true, W),
        "RLD" => Op::Shift(true, true, D),
        "RRB" => Op::Shift(false, true, B),
        "RRW" => Op::Shift(false, true, W),
        "RRD" => Op::Shift(false, true, D),
        "SWAP" => Op::Swap,
        "BTI" => Op::Convert(B, W),
        "ITB" => Op::Convert(W, B),
        "ITD" => Op::Convert(W, D),
        "DTI" => Op::Convert(D, W),
        "JMP" => Op::Jmp,
        "LBL" => Op::Lbl,
        "CALL" => Op::Call,
        "SBR" => Op::Sbr,
        "RET" => Op::Ret,
        "CRET" => Op::Cret,
        "MEND" => Op::Mend,
        "END" => Op::End,
        "NOP" => Op::Nop,
        _ => return Lookup::Unknown,
    };
    Lookup::Known(op)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn english_and_german_forms() {
        assert_eq!(lookup("U"), Lookup::Known(Op::A));
        assert_eq!(
            lookup("undd"),
            Lookup::Known(Op::Logic(Logic::And, Width::D))
        );
        assert_eq!(
            lookup("UB>="),
            Lookup::Known(Op::Compare(Combine::And, Width::B, Rel::Ge))
        );
        assert_eq!(
            lookup("LDW<>"),
            Lookup::Known(Op::Compare(Combine::Load, Width::W, Rel::Ne))
        );
        assert_eq!(lookup("SHRB"), Lookup::Unsupported);
        assert_eq!(lookup("FOO"), Lookup::Unknown);
    }
}

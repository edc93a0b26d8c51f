//! Tc2_Utilities' `FB_FormatString` with its `T_Arg` arguments (`F_INT`,
//! `F_LREAL`, `F_STRING`...) and `FB_MemRingBuffer`, as plcrun's TwinCAT
//! library provides them (docs/twincat.md). Expected texts worked out by
//! hand from the format rules (C's printf where Beckhoff's manual follows
//! it); the ring buffer's sizes from its layout (a 4-byte length before
//! each record).

use crate::support::plc::{lit, run};
use crate::support::twincat::{compile_ok, pou};

/// The outputs of FB_FormatString for each `(format, arguments)`.
fn formatted(cases: &[(&str, &str)]) -> Vec<String> {
    let decl = "PROGRAM P\nVAR\n  fb : FB_FormatString;\n  n : INT := -42; u : UDINT := 255; w : WORD := 16#BEEF; b : BYTE := 65;\n  r : REAL := 3.14159; l : LREAL := -0.000123; s : STRING(80) := 'abc'; bo : BOOL := TRUE;\n  out : ARRAY[1..10] OF T_MaxString; err : ARRAY[1..10] OF UDINT;\nEND_VAR";
    let body: String = cases
        .iter()
        .enumerate()
        .map(|(i, (format, args))| {
            let k = i + 1;
            format!(
                "fb(sFormat := '{format}'{args}); out[{k}] := fb.sOut; err[{k}] := fb.nErrId;\n"
            )
        })
        .collect();
    let main = pou("P", decl, &body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    (1..=cases.len())
        .map(|k| {
            let e = lit(&plc, &format!("err[{k}]"));
            let o = lit(&plc, &format!("out[{k}]"));
            if e == "0" {
                o
            } else {
                format!("{o} error {e}")
            }
        })
        .collect()
}

#[test]
fn integers_in_every_base_with_flags_width_and_precision() {
    let got = formatted(&[
        (
            "n=%d u=%u x=%x X=%#X o=%o b=%b",
            ", arg1 := F_INT(n), arg2 := F_UDINT(u), arg3 := F_UDINT(u), arg4 := F_WORD(w), arg5 := F_BYTE(b), arg6 := F_BYTE(b)",
        ),
        (
            "[%5d][%-5d][%05d][%+d][%.4d]",
            ", arg1 := F_INT(n), arg2 := F_INT(n), arg3 := F_INT(n), arg4 := F_INT(n), arg5 := F_INT(n)",
        ),
        // A negative value as %u and %x: its bits in its own width.
        ("%u %x", ", arg1 := F_INT(n), arg2 := F_INT(n)"),
        (
            "%c%c bo=%d 100%%",
            ", arg1 := F_BYTE(b), arg2 := F_BYTE(b), arg3 := F_BOOL(bo)",
        ),
    ]);
    assert_eq!(
        got,
        [
            "'n=-42 u=255 x=ff X=0XBEEF o=101 b=1000001'",
            "'[  -42][-42  ][-0042][-42][-0042]'",
            "'65494 ffd6'",
            "'AA bo=1 100%'",
        ]
    );
}

#[test]
fn reals_strings_and_the_errors_of_a_bad_format() {
    let got = formatted(&[
        (
            "r=%f r2=%.2f l=%e r3=%08.3f %+.1f",
            ", arg1 := F_REAL(r), arg2 := F_REAL(r), arg3 := F_LREAL(l), arg4 := F_REAL(r), arg5 := F_REAL(r)",
        ),
        (
            "s=%s [%6s] [%-6s] [%.2s]",
            ", arg1 := F_STRING(s), arg2 := F_STRING(s), arg3 := F_STRING(s), arg4 := F_STRING(s)",
        ),
        (":%02.0f %s", ", arg1 := F_REAL(r), arg2 := F_STRING(s)"),
        // An unknown type letter: bError, nErrId 16#8000 + its position.
        ("bad %q", ", arg1 := F_INT(n)"),
        // A string where a number is wanted, and an argument missing.
        ("%d", ", arg1 := F_STRING(s)"),
        ("%d %d", ", arg1 := F_INT(n)"),
    ]);
    assert_eq!(
        got,
        [
            "'r=3.141590 r2=3.14 l=-1.230000e-04 r3=0003.142 +3.1'",
            "'s=abc [   abc] [abc   ] [ab]'",
            "':03 abc'",
            "'bad ' error 32774",
            "'' error 32770",
            "'-42 ' error 32773",
        ]
    );
}

#[test]
fn a_ring_buffer_keeps_records_of_any_length_in_order_across_its_end() {
    let decl = "PROGRAM P\nVAR\n  rb : FB_MemRingBuffer; buf : ARRAY[0..19] OF BYTE;\n  a : DINT := 16#01020304; b : STRING(5) := 'xy'; c : INT := 7;\n  ra : DINT; rs : STRING(5); rc : INT;\n  ok : ARRAY[1..6] OF BOOL; n1, n2, s1, need : UDINT;\nEND_VAR";
    let body = "rb.A_Reset();
rb.A_AddTail(pWrite := ADR(a), cbWrite := SIZEOF(a), pBuffer := ADR(buf), cbBuffer := SIZEOF(buf)); ok[1] := rb.bOk;
rb.A_AddTail(pWrite := ADR(b), cbWrite := SIZEOF(b)); ok[2] := rb.bOk; n1 := rb.nCount; s1 := rb.cbSize;
rb.A_AddTail(pWrite := ADR(c), cbWrite := SIZEOF(c)); ok[3] := rb.bOk;
rb.A_RemoveHead(pRead := ADR(ra), cbRead := SIZEOF(ra)); ok[4] := rb.bOk;
rb.A_AddTail(pWrite := ADR(c), cbWrite := SIZEOF(c)); ok[5] := rb.bOk;
rb.A_GetHead(pRead := ADR(rc), cbRead := SIZEOF(rc)); ok[6] := rb.bOk; need := rb.cbReturn;
rb.A_RemoveHead(pRead := ADR(rs), cbRead := SIZEOF(rs));
rb.A_RemoveHead(pRead := ADR(rc), cbRead := SIZEOF(rc)); n2 := rb.nCount;";
    let main = pou("P", decl, body, "");
    let mut plc = compile_ok(&[("P.TcPOU", &main)]);
    run(&mut plc, 1);
    let ok: Vec<String> = (1..=6).map(|k| lit(&plc, &format!("ok[{k}]"))).collect();
    // The third record (4 + 2 bytes) does not fit behind 18 of 20 bytes;
    // once the first is removed it does, across the buffer's end. Reading
    // the 6-byte string record into an INT fails and says 6 bytes.
    assert_eq!(ok, ["TRUE", "TRUE", "FALSE", "TRUE", "TRUE", "FALSE"]);
    assert_eq!(
        (lit(&plc, "n1"), lit(&plc, "s1")),
        ("2".into(), "18".into())
    );
    assert_eq!(lit(&plc, "ra"), "16909060");
    assert_eq!(lit(&plc, "need"), "6");
    assert_eq!(
        (lit(&plc, "rs"), lit(&plc, "rc")),
        ("'xy'".into(), "7".into())
    );
    assert_eq!(lit(&plc, "n2"), "0");
}

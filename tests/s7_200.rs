//! The S7-200 STL front-end (docs/s7-200.md): every supported instruction
//! on small programs with hand-derived expected values, the overlapping
//! memory views, the logic stack, the timers at their resolutions, the
//! counters' S7-200 semantics, both operand styles, the diagnostics, and
//! the embedding interface (read, write, force) with S7-200 names.

use plcrun::{Options, Plc};

fn plc(src: &str) -> Plc {
    match Plc::compile_files(&[("t.awl", src)], &Options::default()) {
        Ok(p) => p,
        Err(e) => panic!("{e}"),
    }
}

fn lit(plc: &Plc, name: &str) -> String {
    plc.read(name)
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .to_literal()
}

fn int(plc: &Plc, name: &str) -> i64 {
    plc.read_i64(name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn on(plc: &Plc, name: &str) -> bool {
    lit(plc, name) == "TRUE"
}

fn set(plc: &mut Plc, name: &str, v: &str) {
    plc.write(name, v).unwrap_or_else(|e| panic!("{name}: {e}"));
}

fn cycle(plc: &mut Plc) {
    plc.run_cycle().expect("cycle runs");
}

/// The codes and `line:col` of the diagnostics of `src`.
fn diagnostics(src: &str) -> Vec<(String, usize, usize)> {
    let err = match Plc::compile_files(&[("t.awl", src)], &Options::default()) {
        Ok(_) => return Vec::new(),
        Err(e) => e,
    };
    let file = &err.sources.files()[0];
    err.diagnostics
        .iter()
        .map(|d| {
            let (l, c) = file.line_col(d.span.start);
            (d.code.to_string(), l, c)
        })
        .collect()
}

#[test]
fn recognised_by_extension_or_content() {
    use plcrun::syntax::s7::recognise;
    assert!(recognise("x.awl", ""));
    assert!(recognise("X.STL", "anything"));
    assert!(recognise("x.txt", "// c\nNETWORK 1 // t\nLD I0.0\n"));
    assert!(recognise("x.txt", "NETWORK12\n= Q0.0\n"));
    assert!(recognise("x", "LD I0.0\n= Q0.1\n"));
    assert!(recognise("x", "LDW= VW10, 5\n= Q0.1\n"));
    assert!(recognise("x", "ORGANIZATION_BLOCK MAIN:OB1\n"));
    assert!(!recognise(
        "x.il",
        "PROGRAM P\nVAR x : BOOL; END_VAR\nLD x\nST x\nEND_PROGRAM\n"
    ));
    assert!(!recognise("x.st", "PROGRAM P x := 1; END_PROGRAM"));
    assert!(!recognise("x", "LD x\n"));
}

#[test]
fn views_overlap_big_endian_from_the_program_and_from_outside() {
    let mut p = plc("NETWORK 1\nLD SM0.1\nMOVD 16#12345678, VD4\n");
    cycle(&mut p);
    assert_eq!(int(&p, "VB4"), 0x12);
    assert_eq!(int(&p, "VB7"), 0x78);
    assert_eq!(int(&p, "VW4"), 0x1234);
    assert_eq!(int(&p, "VW5"), 0x3456);
    assert_eq!(int(&p, "VW6"), 0x5678);
    assert!(on(&p, "V4.4")); // 0x12 = 0001_0010
    assert!(on(&p, "V4.1"));
    assert!(!on(&p, "V4.0"));
    set(&mut p, "VW6", "16#ABCD");
    assert_eq!(int(&p, "VB6"), 0xAB);
    assert_eq!(int(&p, "VD4"), 0x1234_ABCD);
    set(&mut p, "V7.1", "TRUE"); // 0xCD | 0x02 = 0xCF
    assert_eq!(int(&p, "VB7"), 0xCF);
    assert_eq!(int(&p, "VD4"), 0x1234_ABCF);
    set(&mut p, "V4.4", "FALSE");
    assert_eq!(int(&p, "VD4"), 0x0234_ABCF);
    // Written from outside, read by the program's own views.
    let mut q = plc("NETWORK 1\nLD V10.3\n= Q0.0\nLD SM0.0\nMOVW VW10, VW20\n");
    set(&mut q, "VD8", "16#00000800"); // VB10 = 16#08: V10.3
    cycle(&mut q);
    assert!(on(&q, "Q0.0"));
    assert_eq!(int(&q, "VW20"), 0x0800);
    assert_eq!(int(&q, "VB20"), 0x08);
}

#[test]
fn german_areas_are_the_english_ones() {
    let mut p = plc("NETWORK 1\nLD E0.4\nU E1.0\n= A0.2\nLD SM0.0\nMOVB EB0, VB2\n");
    set(&mut p, "I0.4", "TRUE");
    set(&mut p, "IB1", "1");
    cycle(&mut p);
    assert!(on(&p, "Q0.2"));
    assert!(on(&p, "A0.2"));
    assert_eq!(int(&p, "VB2"), 0x10);
    assert_eq!(int(&p, "EB0"), 0x10);
}

const STACK_PROGRAM: &str = "
NETWORK 1 // Q0.0 = I0.0 AND (I0.1 OR (I0.2 AND I0.3))
LD I0.0
LD I0.1
LD I0.2
A I0.3
OLD
ALD
= Q0.0
NETWORK 2 // a branch: LPS, LRD, LPP
LD I0.0
LPS
A I0.5
= Q0.1
LRD
A I0.6
= Q0.2
LPP
AN I0.7
= Q0.3
NETWORK 3
LD I0.1
O I0.2
ON I0.3
NOT
= Q0.4
NETWORK 4
LDN I0.4
= Q0.5
";

#[test]
fn logic_stack_ald_old_lps_lrd_lpp_not() {
    let mut p = plc(STACK_PROGRAM);
    for ib in 0..256u32 {
        set(&mut p, "IB0", &ib.to_string());
        cycle(&mut p);
        let i = |n: u32| ib & (1 << n) != 0;
        let want = [
            i(0) && (i(1) || (i(2) && i(3))),
            i(0) && i(5),
            i(0) && i(6),
            i(0) && !i(7),
            !(i(1) || i(2) || !i(3)),
            !i(4),
        ];
        for (k, w) in want.iter().enumerate() {
            assert_eq!(on(&p, &format!("Q0.{k}")), *w, "IB0 = {ib:#x}, Q0.{k}");
        }
    }
}

#[test]
fn the_stack_has_nine_levels_and_loses_the_bottom() {
    let eight = "LDN SM0.0\n".repeat(8);
    let nine = "LDN SM0.0\n".repeat(9);
    let src = format!(
        "NETWORK 1\nLD SM0.0\n{eight}{}= Q0.0\nNETWORK 2\nLD SM0.0\n{nine}{}= Q0.1\n",
        "OLD\n".repeat(8),
        "OLD\n".repeat(9)
    );
    let mut p = plc(&src);
    cycle(&mut p);
    assert!(
        on(&p, "Q0.0"),
        "a 1 pushed down eight levels is still there"
    );
    assert!(!on(&p, "Q0.1"), "pushed down nine levels it is lost");
}

#[test]
fn eu_and_ed_are_edges_of_the_top() {
    let mut p = plc("NETWORK 1\nLD I0.0\nEU\n= Q0.0\nLD I0.0\nED\n= Q0.1\n");
    let mut got = Vec::new();
    for i0 in [false, true, true, false, false, true] {
        set(&mut p, "I0.0", if i0 { "TRUE" } else { "FALSE" });
        cycle(&mut p);
        got.push((on(&p, "Q0.0"), on(&p, "Q0.1")));
    }
    let f = false;
    let t = true;
    assert_eq!(got, [(f, f), (t, f), (f, f), (f, t), (f, f), (t, f)]);
}

#[test]
fn set_and_reset_bit_counts_cross_bytes_in_both_styles() {
    for (s, r) in [("S V0.6, 4", "R V0.7, 2"), ("S V0.6 K4", "R V0.7 K2")] {
        let mut p = plc(&format!("NETWORK 1\nLD I0.0\n{s}\nLD I0.1\n{r}\n"));
        cycle(&mut p);
        assert_eq!(int(&p, "VW0"), 0, "nothing while the top is 0");
        set(&mut p, "I0.0", "TRUE");
        cycle(&mut p);
        assert_eq!((int(&p, "VB0"), int(&p, "VB1")), (0xC0, 0x03));
        set(&mut p, "I0.0", "FALSE");
        set(&mut p, "I0.1", "TRUE");
        cycle(&mut p);
        assert_eq!((int(&p, "VB0"), int(&p, "VB1")), (0x40, 0x02));
    }
}

#[test]
fn sm0_0_is_always_on_and_sm0_1_only_in_the_first_scan() {
    let mut p = plc("NETWORK 1\nLD SM0.1\n= Q0.0\nLD SM0.0\n= Q0.1\n");
    cycle(&mut p);
    assert!(on(&p, "Q0.0") && on(&p, "Q0.1") && on(&p, "SM0.1"));
    cycle(&mut p);
    assert!(!on(&p, "Q0.0") && on(&p, "Q0.1"));
}

/// Runs `cycles` 10 ms cycles with I0.0 given per cycle; the (bit, CV)
/// of `timer` after each.
fn timer_trace(src: &str, timer: &str, inputs: &[bool]) -> Vec<(bool, i64)> {
    let mut p = plc(src);
    inputs
        .iter()
        .map(|i| {
            set(&mut p, "I0.0", if *i { "TRUE" } else { "FALSE" });
            cycle(&mut p);
            (on(&p, timer), int(&p, &format!("{timer}.CV")))
        })
        .collect()
}

#[test]
fn ton_counts_at_the_resolution_of_its_number() {
    // T32: 1 ms; 10 ms cycles, PT 25: 0, 10, 20, 30 (on).
    let t = timer_trace("NETWORK 1\nLD I0.0\nTON T32, 25\n", "T32", &[true; 4]);
    assert_eq!(t, [(false, 0), (false, 10), (false, 20), (true, 30)]);
    // T33: 10 ms, PT 3 (listing form K3); off resets.
    let t = timer_trace(
        "NETWORK 1\nLD I0.0\nTON T33 K3\n",
        "T33",
        &[true, true, true, true, true, false, true],
    );
    assert_eq!(
        t,
        [
            (false, 0),
            (false, 1),
            (false, 2),
            (true, 3),
            (true, 4),
            (false, 0),
            (false, 0)
        ]
    );
    // T37: 100 ms, PT 2: one count per ten 10 ms cycles.
    let t = timer_trace("NETWORK 1\nLD I0.0\nTON T37, +2\n", "T37", &[true; 21]);
    assert_eq!(t[9], (false, 0));
    assert_eq!(t[10], (false, 1));
    assert_eq!(t[19], (false, 1));
    assert_eq!(t[20], (true, 2));
}

#[test]
fn tonr_keeps_its_value_until_reset() {
    let src = "NETWORK 1\nLD I0.0\nTONR T1, 4\nLD I0.1\nR T1, 1\n";
    let t = timer_trace(
        src,
        "T1",
        &[true, true, true, true, false, false, true, true],
    );
    assert_eq!(
        t,
        [
            (false, 0),
            (false, 1),
            (false, 2),
            (false, 3),
            (false, 3),
            (false, 3),
            (false, 3),
            (true, 4)
        ]
    );
    let mut p = plc(src);
    set(&mut p, "I0.0", "TRUE");
    for _ in 0..6 {
        cycle(&mut p);
    }
    assert!(on(&p, "T1"));
    set(&mut p, "I0.0", "FALSE");
    set(&mut p, "I0.1", "TRUE");
    cycle(&mut p);
    assert!(!on(&p, "T1"));
    assert_eq!(int(&p, "T1.CV"), 0);
}

#[test]
fn tof_holds_its_bit_for_pt_after_the_input_falls() {
    let t = timer_trace(
        "NETWORK 1\nLD I0.0\nTOF T34, 3\n",
        "T34",
        &[false, true, true, false, false, false, false, false],
    );
    assert_eq!(
        t,
        [
            (false, 0),
            (true, 0),
            (true, 0),
            (true, 0),
            (true, 1),
            (true, 2),
            (false, 3),
            (false, 3)
        ]
    );
}

#[test]
fn a_timer_is_a_bit_and_a_word() {
    let mut p = plc(
        "NETWORK 1\nLD I0.0\nTON T33, 2\nLD T33\n= Q0.0\nLDW>= T33, 1\n= Q0.1\nLD SM0.0\nMOVW T33, VW0\n",
    );
    set(&mut p, "I0.0", "TRUE");
    cycle(&mut p);
    cycle(&mut p);
    assert!(!on(&p, "Q0.0") && on(&p, "Q0.1"));
    assert_eq!(int(&p, "VW0"), 1);
    cycle(&mut p);
    assert!(on(&p, "Q0.0"));
}

#[test]
fn ctu_counts_rising_edges_saturates_and_resets() {
    let src = "NETWORK 1\nLD I0.0\nLD I0.1\nCTU C0, 3\nLD C0\n= Q0.0\n";
    let mut p = plc(src);
    let pulse = |p: &mut Plc| {
        set(p, "I0.0", "TRUE");
        cycle(p);
        set(p, "I0.0", "FALSE");
        cycle(p);
    };
    for n in 1..=3 {
        pulse(&mut p);
        assert_eq!(int(&p, "C0.CV"), n);
    }
    assert!(on(&p, "Q0.0") && on(&p, "C0"));
    set(&mut p, "C0.CV", "32766");
    pulse(&mut p);
    pulse(&mut p);
    assert_eq!(int(&p, "C0.CV"), 32767, "CTU stops at 32767");
    set(&mut p, "I0.1", "TRUE");
    cycle(&mut p);
    assert_eq!(int(&p, "C0.CV"), 0);
    assert!(!on(&p, "C0"));
}

#[test]
fn ctd_loads_counts_down_to_zero_and_stops() {
    let mut p = plc("NETWORK 1\nLD I0.0\nLD I0.1\nCTD C1, 2\n");
    set(&mut p, "I0.1", "TRUE");
    cycle(&mut p);
    assert_eq!((int(&p, "C1.CV"), on(&p, "C1")), (2, false));
    set(&mut p, "I0.1", "FALSE");
    let mut seen = Vec::new();
    for _ in 0..3 {
        set(&mut p, "I0.0", "TRUE");
        cycle(&mut p);
        set(&mut p, "I0.0", "FALSE");
        cycle(&mut p);
        seen.push((int(&p, "C1.CV"), on(&p, "C1")));
    }
    assert_eq!(seen, [(1, false), (0, true), (0, true)]);
}

#[test]
fn ctud_counts_both_ways_and_wraps() {
    let mut p = plc("NETWORK 1\nLD I0.0\nLD I0.2\nLD I0.1\nCTUD C2, 2\n");
    let edge = |p: &mut Plc, input: &str| {
        set(p, input, "TRUE");
        cycle(p);
        set(p, input, "FALSE");
        cycle(p);
    };
    edge(&mut p, "I0.0");
    edge(&mut p, "I0.0");
    assert_eq!((int(&p, "C2.CV"), on(&p, "C2")), (2, true));
    edge(&mut p, "I0.2");
    assert_eq!((int(&p, "C2.CV"), on(&p, "C2")), (1, false));
    set(&mut p, "C2.CV", "32767");
    edge(&mut p, "I0.0");
    assert_eq!(int(&p, "C2.CV"), -32768);
    edge(&mut p, "I0.2");
    assert_eq!(int(&p, "C2.CV"), 32767);
    edge(&mut p, "I0.1");
    assert_eq!(int(&p, "C2.CV"), 0);
}

#[test]
fn moves_fills_and_block_moves() {
    let mut p = plc("NETWORK 1
LD SM0.0
MOVB 16#AB, VB0
MOVW 16#0100, VW2
MOVW -2, VW4
MOVD 16#01020304, VD6
FILL KHBEEF VW20 K3
MOVD 16#11223344, VD40
BMB VB40, VB50, 3
BMW VW40, VW60, 2
BMD VD40, VD70, 1
LD I0.0
MOVW K7 VW10
");
    cycle(&mut p);
    assert_eq!(int(&p, "VB0"), 0xAB);
    assert_eq!(int(&p, "VW2"), 0x0100);
    assert_eq!(int(&p, "VW4"), 0xFFFE);
    assert_eq!(int(&p, "VD6"), 0x0102_0304);
    for a in [20, 22, 24] {
        assert_eq!(int(&p, &format!("VW{a}")), 0xBEEF);
    }
    assert_eq!(int(&p, "VW26"), 0);
    assert_eq!(int(&p, "VD50"), 0x1122_3300);
    assert_eq!(int(&p, "VD60"), 0x1122_3344);
    assert_eq!(int(&p, "VD70"), 0x1122_3344);
    assert_eq!(int(&p, "VW10"), 0, "a box does not run while the top is 0");
    set(&mut p, "I0.0", "TRUE");
    cycle(&mut p);
    assert_eq!(int(&p, "VW10"), 7);
}

#[test]
fn word_logic_english_and_german() {
    let mut p = plc("NETWORK 1
LD SM0.1
MOVB 16#F0, VB0
ANDB 16#3C, VB0
MOVB 16#F0, VB1
ORB 16#0F, VB1
MOVW 16#FF00, VW2
XORW 16#0FF0, VW2
MOVW 16#1234, VW4
INVW VW4
MOVD 16#F0F0F0F0, VD8
UNDD 16#FF00FF00, VD8
MOVD 16#0000FFFF, VD12
ODERD 16#FFFF0000, VD12
MOVD 16#00000000, VD16
INVD VD16
MOVB 16#0F, VB20
INVB VB20
MOVW 16#00FF, VW22
ANDW 16#0FF0, VW22
MOVW 16#00FF, VW24
UNDW KHF00 VW24
MOVW 16#000F, VW26
ORW 16#00F0, VW26
MOVD 1, VD28
ORD 16#100, VD28
MOVD 16#FFFF, VD32
XORD 16#FF, VD32
MOVB 16#FF, VB36
XORB 16#0F, VB36
");
    cycle(&mut p);
    let want = [
        ("VB0", 0x30),
        ("VB1", 0xFF),
        ("VW2", 0xF0F0),
        ("VW4", 0xEDCB),
        ("VD8", 0xF000_F000),
        ("VD12", 0xFFFF_FFFF),
        ("VD16", 0xFFFF_FFFF),
        ("VB20", 0xF0),
        ("VW22", 0x00F0),
        ("VW24", 0x0000),
        ("VW26", 0x00FF),
        ("VD28", 0x101),
        ("VD32", 0xFF00),
        ("VB36", 0xF0),
    ];
    for (name, v) in want {
        assert_eq!(int(&p, name), v, "{name}");
    }
}

#[test]
fn integer_arithmetic_is_out_op_in1() {
    let mut p = plc("NETWORK 1
LD SM0.1
MOVW 10, VW0
+I 5, VW0
MOVW 10, VW2
-I 15, VW2
MOVW -3, VW4
*I 7, VW4
MOVW 17, VW6
/I 5, VW6
MOVD 100000, VD10
+D 1, VD10
MOVD 5, VD14
-D 7, VD14
MOVD -6, VD18
*D 100000, VD18
MOVD 1000001, VD22
/D -10, VD22
MOVW 32767, VW26
+I 1, VW26
MOVD 0, VD28
MOVW 300, VW30
MUL 400, VD28
MOVD 0, VD32
MOVW 17, VW34
DIV 5, VD32
MOVW 9, VW36
/I 0, VW36
MOVB 255, VB38
INCB VB38
MOVW -1, VW40
INCW VW40
MOVD 0, VD42
DECD VD42
MOVB 0, VB46
DECB VB46
MOVW 0, VW48
DECW VW48
MOVD 41, VD50
INCD VD50
");
    cycle(&mut p);
    let word = |v: i64| v & 0xFFFF;
    let dword = |v: i64| v & 0xFFFF_FFFF;
    assert_eq!(int(&p, "VW0"), 15);
    assert_eq!(int(&p, "VW2"), word(-5));
    assert_eq!(int(&p, "VW4"), word(-21));
    assert_eq!(int(&p, "VW6"), 3);
    assert_eq!(int(&p, "VD10"), 100_001);
    assert_eq!(int(&p, "VD14"), dword(-2));
    assert_eq!(int(&p, "VD18"), dword(-600_000));
    assert_eq!(int(&p, "VD22"), dword(-100_000));
    assert_eq!(int(&p, "VW26"), 0x8000, "+I wraps");
    assert_eq!(int(&p, "VD28"), 120_000);
    assert_eq!(int(&p, "VW32"), 2, "DIV: remainder in the high word");
    assert_eq!(int(&p, "VW34"), 3, "DIV: quotient in the low word");
    assert_eq!(int(&p, "VW36"), 9, "division by zero leaves OUT");
    assert!(on(&p, "SM1.3"), "and sets SM1.3");
    assert_eq!(int(&p, "VB38"), 0);
    assert_eq!(int(&p, "VW40"), 0);
    assert_eq!(int(&p, "VD42"), dword(-1));
    assert_eq!(int(&p, "VB46"), 255);
    assert_eq!(int(&p, "VW48"), 0xFFFF);
    assert_eq!(int(&p, "VD50"), 42);
}

#[test]
fn comparisons_load_and_or() {
    let mut p = plc("NETWORK 1
LDB= VB0, 5
= Q0.0
LDB< VB0, 200
= Q0.1
LDW< VW2, 1
= Q0.2
LDW<> VW2, -1
= Q0.3
LDW<= VW2, -1
= Q0.4
LDW> VW2, -2
= Q0.5
LDW>= VW2, 0
= Q0.6
LDD= VD4, 70000
= Q0.7
LD SM0.0
AW= VW2, -1
= Q1.0
LDN SM0.0
OW= VW2, -1
= Q1.1
LD SM0.0
UB>= VB0, K6
= Q1.2
LDD< VD4, 0
OD> VD4, 69999
= Q1.3
LDB>= VB10, 16#80
= Q1.4
");
    set(&mut p, "VB0", "5");
    set(&mut p, "VW2", "16#FFFF");
    set(&mut p, "VD4", "70000");
    set(&mut p, "VB10", "16#90");
    cycle(&mut p);
    let want = [
        true, true, true, false, true, true, false, true, true, true, false, true, true,
    ];
    let names = [
        "Q0.0", "Q0.1", "Q0.2", "Q0.3", "Q0.4", "Q0.5", "Q0.6", "Q0.7", "Q1.0", "Q1.1", "Q1.2",
        "Q1.3", "Q1.4",
    ];
    for (n, w) in names.iter().zip(want) {
        assert_eq!(on(&p, n), w, "{n}");
    }
}

#[test]
fn jumps_forward_and_backward() {
    let mut p = plc("NETWORK 1
LD I0.0
JMP 3
NETWORK 2
LD SM0.0
= Q0.0
NETWORK 3
LBL 3
LD SM0.0
= Q0.1
NETWORK 4 // a loop: VW0 counts up to 5 within one scan
LBL 1
LD SM0.0
+I 1, VW0
LDW< VW0, 5
JMP 1
");
    cycle(&mut p);
    assert!(on(&p, "Q0.0") && on(&p, "Q0.1"));
    assert_eq!(int(&p, "VW0"), 5);
    set(&mut p, "Q0.0", "FALSE");
    set(&mut p, "I0.0", "TRUE");
    cycle(&mut p);
    assert!(!on(&p, "Q0.0"), "jumped over");
    assert!(on(&p, "Q0.1"));
    assert_eq!(int(&p, "VW0"), 6);
}

#[test]
fn subroutines_start_with_a_one_on_top_and_keep_the_callers_stack() {
    let mut p = plc("NETWORK 1
LD SM0.0
LDN SM0.0
CALL SBR_1
= Q0.0 // not called: the top is 0, and stays 0
OLD
= Q0.1 // the caller's second level is still 1
NETWORK 2
LD SM0.0
CALL 2
= Q0.2
MEND
SBR 1
= V0.0
RET
SBR K2
MOVB 1, VB1 // runs: the top is 1 on entry
LD I0.0
CRET
LD SM0.0
MOVB 2, VB1
END
MOVB 3, VB1
RET
");
    cycle(&mut p);
    assert!(!on(&p, "V0.0") && !on(&p, "Q0.0"));
    assert!(on(&p, "Q0.1") && on(&p, "Q0.2"));
    assert_eq!(
        int(&p, "VB1"),
        2,
        "END ends the subroutine when the top is 1"
    );
    set(&mut p, "I0.0", "TRUE");
    cycle(&mut p);
    assert_eq!(int(&p, "VB1"), 1, "CRET returned");
}

#[test]
fn both_operand_styles_mean_the_same() {
    let micro_win = "NETWORK 1\nLD I0.0\nTON T37, +50\nLD SM0.0\nMOVW 16#0100, VW20\nFILL +0, VW10, 2\nS V72.0, 2\nCALL SBR_0\nMEND\nSBR 0\nLD SM0.0\nMOVW VW20, VW30\nRET\n";
    let listing = "NETWORK1 // listing form\n 0 LD I0.0\n 2 TON T37 K50\nNETWORK2\n LD SM0.0\n MOVW KH0100 VW20\n FILL K0 VW10 K2\n S V72.0 K2\n CALL K0\n MEND\n SBR K0\n LD SM0.0\n MOVW VW20 VW30\n RET\n";
    let mut a = plc(micro_win);
    let mut b = plc(listing);
    for p in [&mut a, &mut b] {
        set(p, "VW10", "16#FFFF");
        set(p, "VW12", "16#FFFF");
        set(p, "I0.0", "TRUE");
        for _ in 0..501 {
            cycle(p);
        }
    }
    for name in ["T37", "T37.CV", "VW20", "VW10", "VW12", "VB72", "VW30"] {
        assert_eq!(lit(&a, name), lit(&b, name), "{name}");
    }
    assert_eq!(int(&a, "VB72"), 0x03);
    assert_eq!(int(&a, "VW30"), 0x0100);
    assert!(on(&a, "T37"));
}

#[test]
fn forcing_a_bit_leaves_the_other_bits_of_its_byte() {
    let mut p = plc("NETWORK 1\nLD SM0.0\nMOVB 16#F0, VB0\nLD I0.1\n= Q0.0\n");
    p.force("V0.0", "TRUE").expect("forced");
    p.force("I0.1", "TRUE").expect("forced");
    cycle(&mut p);
    assert_eq!(
        int(&p, "VB0"),
        0xF1,
        "the program wrote F0, the force keeps bit 0"
    );
    assert!(on(&p, "Q0.0"));
    assert!(p.is_forced(&p.resolve("V0.0").unwrap()));
    assert!(!p.is_forced(&p.resolve("V0.1").unwrap()));
    assert!(!p.is_forced(&p.resolve("VB0").unwrap()));
    p.unforce("V0.0").unwrap();
    cycle(&mut p);
    assert_eq!(int(&p, "VB0"), 0xF0);
}

#[test]
fn s7_names_out_of_their_area_are_refused() {
    let p = plc("NETWORK 1\nLD I0.0\n= Q0.0\n");
    assert!(p.resolve("VW4095").is_err());
    assert!(p.resolve("VB4095").is_ok());
    assert!(p.resolve("Q16.0").is_err());
    assert!(p.resolve("T256").is_err());
}

#[test]
fn coded_diagnostics_with_line_and_column() {
    let d = |src: &str| diagnostics(src);
    assert_eq!(d("NETWORK 1\nLD I0.0\nFOO V0.0\n"), [("E850".into(), 3, 1)]);
    assert_eq!(
        d("NETWORK 1\n  SHRB V0.0, V1.0, 4\n"),
        [("E851".into(), 2, 3)]
    );
    assert_eq!(d("LD I0.0\nMOVW VW0\n"), [("E852".into(), 2, 1)]);
    assert_eq!(d("LD I0.0\n= X0.0\n"), [("E853".into(), 2, 3)]);
    assert_eq!(d("LD I0.0\nMOVW VB0, VW2\n"), [("E854".into(), 2, 6)]);
    assert_eq!(d("LD I0.0\n= V4096.0\n"), [("E855".into(), 2, 3)]);
    assert_eq!(d("LD I0.0\nMOVB 256, VB0\n"), [("E856".into(), 2, 6)]);
    assert_eq!(d("LD I0.0\nCALL SBR_4\n"), [("E857".into(), 2, 1)]);
    assert_eq!(
        d("LD SM0.0\nCALL 1\nMEND\nSBR 1\nCALL 1\nRET\n"),
        [("E858".into(), 5, 1)]
    );
    assert_eq!(d("SBR 1\nRET\nSBR 1\nRET\n"), [("E859".into(), 3, 1)]);
    assert_eq!(d("LD I0.0\nJMP 7\n"), [("E860".into(), 2, 1)]);
    assert_eq!(d("LD I0.0\nMOVW AC0, VW0\n"), [("E861".into(), 2, 6)]);
    assert_eq!(d("SBR\nRET\n"), [("E862".into(), 1, 1)]);
    assert_eq!(d("LD I0.0\nTONR T37, 5\n"), [("E866".into(), 2, 6)]);
    assert_eq!(
        d("LD I0.0\nTON T40, 5\nTOF T40, 5\n"),
        [("E865".into(), 3, 5)]
    );
}

#[test]
fn code_after_mend_is_a_warning_and_every_code_is_documented() {
    let report = plcrun::check(
        &{
            let mut m = plcrun::SourceMap::new();
            m.add("t.awl", "LD SM0.0\n= Q0.0\nMEND\nLD SM0.0\n= Q0.1\n");
            m
        },
        &plcrun::CheckOptions::default(),
    );
    let codes: Vec<&str> = report.diagnostics.iter().map(|d| d.code).collect();
    assert_eq!(codes, ["W850"]);
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/diagnostics.md"))
        .expect("docs/diagnostics.md");
    for code in [
        "E850", "E851", "E852", "E853", "E854", "E855", "E856", "E857", "E858", "E859", "E860",
        "E861", "E862", "E864", "E865", "E866", "W850",
    ] {
        assert!(doc.contains(&format!("## {code}")), "{code} undocumented");
    }
}

#[test]
fn the_default_trace_is_the_q_bits_used() {
    let plc = plc("NETWORK 1\nLD I0.0\n= Q1.2\n");
    let names = plc.default_trace();
    assert_eq!(names.len(), 16);
    assert_eq!(names[0], "Q0.0");
    assert_eq!(names[15], "Q1.7");
}

#[test]
fn a_stimulus_drives_s7_inputs_through_a_session() {
    use plcrun::{Session, parse_stimulus};
    let mut s = Session::new(plc(
        "NETWORK 1\nLD I0.0\nA E0.1\n= Q0.0\nLD SM0.0\nINCW VW10\n",
    ));
    s.set_trace(&["Q0.0", "VW10", "I0.0"])
        .expect("S7 names trace");
    let stimulus = parse_stimulus("cycle,I0.0,E0.1\n0,FALSE,TRUE\n2,TRUE,TRUE\n").expect("csv");
    s.bind_stimulus(stimulus).expect("S7 names as columns");
    let mut q = Vec::new();
    for _ in 0..4 {
        s.step().expect("cycle");
        q.push(on(s.plc(), "Q0.0"));
    }
    assert_eq!(q, [false, false, true, true]);
    assert_eq!(int(s.plc(), "VW10"), 4);
}

#[test]
fn shifts_rotates_swap_and_conversions() {
    let mut p = plc("NETWORK 1
LD SM0.1
MOVB 16#81, VB0
SLB VB0, 1
MOVW 16#8001, VW2
SRW VW2, 4
MOVD 16#80000001, VD4
RLD VD4, 4
MOVB 16#81, VB8
RRB VB8, 1
MOVW 16#1234, VW10
SWAP VW10
MOVW 16#FFFF, VW12
SLW VW12, 16
MOVB 200, VB14
BTI VB14, VW16
MOVW -2, VW18
ITD VW18, VD20
MOVD 40000, VD24
MOVW 7, VW28
DTI VD24, VW28
MOVW 300, VW30
MOVB 9, VB32
ITB VW30, VB32
MOVW 100, VW34
ITB VW34, VB36
");
    cycle(&mut p);
    let want = [
        ("VB0", 0x02),
        ("VW2", 0x0800),
        ("VD4", 0x0000_0018),
        ("VB8", 0xC0),
        ("VW10", 0x3412),
        ("VW12", 0),
        ("VW16", 200),
        ("VD20", 0xFFFF_FFFE),
        ("VW28", 7),
        ("VB32", 9),
        ("VB36", 100),
    ];
    for (name, v) in want {
        assert_eq!(int(&p, name), v, "{name}");
    }
    assert!(!on(&p, "SM1.1"), "the last conversion fitted");
    let mut q = plc("NETWORK 1\nLD SM0.0\nMOVD 40000, VD0\nDTI VD0, VW4\n");
    cycle(&mut q);
    assert!(on(&q, "SM1.1"), "DTI out of range sets SM1.1");
    assert_eq!(int(&q, "VW4"), 0);
}

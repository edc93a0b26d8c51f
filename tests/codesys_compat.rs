//! CODESYS behaviours beyond IEC 61131-3 edition 3 that real libraries
//! (OSCAT among them) rely on: each is accepted with its compatibility
//! warning (W350-W359) and computes as worked out by hand beside each case.

use crate::support::plc;

use plc::{compile, error_codes, lit, program, run};

/// Compiles `decls`/`body` as a program, runs `cycles` cycles and checks
/// `(variable, literal)`; returns the warning codes.
fn check(
    prelude: &str,
    decls: &str,
    body: &str,
    cycles: u64,
    expect: &[(&str, &str)],
) -> Vec<String> {
    let mut plc = compile(&program(prelude, decls, body));
    run(&mut plc, cycles);
    for (name, value) in expect {
        assert_eq!(lit(&plc, name), *value, "{name}\n{body}");
    }
    plc.warnings().iter().map(|d| d.code.to_string()).collect()
}

#[test]
fn bit_strings_compute_as_unsigned_integers_of_their_width() {
    let w = check(
        "",
        "b : BYTE := 250; w : WORD := 16#FFFF; d : DWORD := 7; l : LWORD := 0;
         r1 : BYTE; r2 : WORD; r3, r4 : DWORD; r5 : LWORD; r6 : BYTE;",
        // 250 + 10 = 260 wraps to 4; 65535 + 2 wraps to 1; 7 MOD 4 = 3,
        // 3 * 3 = 9, 9 / 2 = 4, 4 - 1 = 3; 0 - 1 wraps to 2^32 - 1;
        // LWORD 0 - 1 wraps to 2^64 - 1; 250 / 7 = 35.
        "r1 := b + 10; r2 := w + 2; r3 := d MOD 4 * 3 / 2 - 1; r4 := r3 - r3 - 1;
         r5 := l - 1; r6 := b / BYTE#7;",
        1,
        &[
            ("r1", "16#4"),
            ("r2", "16#1"),
            ("r3", "16#3"),
            ("r4", "16#FFFFFFFF"),
            ("r5", "16#FFFFFFFFFFFFFFFF"),
            ("r6", "16#23"),
        ],
    );
    assert!(w.iter().all(|c| c == "W350"), "{w:?}");
    assert_eq!(w.len(), 10, "{w:?}"); // one per operator
}

#[test]
fn bit_strings_mix_with_unsigned_and_wider_signed_integers() {
    let w = check(
        "",
        "w : WORD := 65000; u : UINT := 1000; b : BYTE := 200; i : INT := -300;
         r1 : UINT; r2 : INT; r3 : INT; r4 : UDINT; r5 : WORD;",
        // WORD + UINT computes in UINT: 66000 wraps to 464; BYTE + INT in
        // INT: 200 - 300 = -100; BYTE into INT keeps 200; WORD into UDINT
        // keeps 65000; UINT into WORD keeps 1000.
        "r1 := w + u; r2 := b + i; r3 := b; r4 := w; r5 := u;",
        1,
        &[
            ("r1", "464"),
            ("r2", "-100"),
            ("r3", "200"),
            ("r4", "65000"),
            ("r5", "16#3E8"),
        ],
    );
    assert_eq!(w, ["W350", "W350", "W351", "W351", "W351"]);
}

/// A bit string compared with an integer of no common IEC type (PMPS:
/// `nActiveID <> nRequestID` with a DWORD and a UDINT) compares as the
/// unsigned integer of its width, with W350; a comparison IEC types
/// already (`w = 16#FFFF`) gives no warning.
#[test]
fn a_bit_string_compares_with_an_integer_as_its_unsigned_value() {
    let w = check(
        "",
        "d : DWORD := 16#FFFF_FFFF; u : UDINT := 4294967295; b : BYTE := 7; i : DINT := -1;
         w : WORD := 16#FFFF; r1, r2, r3, r4 : BOOL;",
        "r1 := d = u; r2 := b < u; r3 := b <> i; r4 := w = 16#FFFF;",
        1,
        &[
            ("r1", "TRUE"),
            ("r2", "TRUE"),
            ("r3", "TRUE"),
            ("r4", "TRUE"),
        ],
    );
    assert_eq!(w, ["W350", "W350", "W350"]);
}

#[test]
fn narrowing_and_signed_mixes_stay_errors() {
    // BYTE into SINT could lose values; WORD + INT has no common type
    // holding both; a bit string does not narrow into a shorter one.
    for (decls, body) in [
        ("b : BYTE; s : SINT;", "s := b;"),
        ("w : WORD; i : INT; r : INT;", "r := w + i;"),
        ("d : DWORD; u : UINT;", "u := d;"),
    ] {
        let codes = error_codes(&[("t.st", &program("", decls, body))]);
        assert!(!codes.is_empty(), "{body} must not compile");
    }
}

#[test]
fn shift_counts_may_be_expressions_and_bit_strings() {
    let w = check(
        "",
        "d : DWORD := 16#12345678; n : INT := 1; b : BYTE := 2; r1, r2 : DWORD;",
        // SHL by n + 1 = 2: 0x48D159E0; SHR by SHL(b, 2) = 8: 0x00123456.
        "r1 := SHL(d, n + 1); r2 := SHR(d, SHL(b, 2));",
        1,
        &[("r1", "16#48D159E0"), ("r2", "16#123456")],
    );
    assert_eq!(w, ["W352"]);
}

#[test]
fn constant_inputs_are_set_by_the_caller_and_never_folded() {
    let prelude = "FUNCTION SCALE2 : INT
VAR_INPUT x : INT; END_VAR
VAR_INPUT CONSTANT k : INT := 3; lim : INT; END_VAR
SCALE2 := LIMIT(-lim, x * k, lim);
END_FUNCTION
FUNCTION_BLOCK ACC
VAR_INPUT CONSTANT inc : INT := 1; END_VAR
VAR_OUTPUT total : INT; END_VAR
total := total + inc;
END_FUNCTION_BLOCK";
    // 5 * 3 = 15 (k defaults to 3); 5 * 10 = 50 limited to 20; the FB
    // counts by 4 twice = 8 and by its default 1 twice = 2.
    let w = check(
        prelude,
        "r1, r2, t1, t2 : INT; a, b : ACC;",
        "r1 := SCALE2(x := 5, lim := 100); r2 := SCALE2(x := 5, k := 10, lim := 20);
         a(inc := 4); b(); t1 := a.total; t2 := b.total;",
        2,
        &[("r1", "15"), ("r2", "20"), ("t1", "8"), ("t2", "2")],
    );
    assert_eq!(w, ["W353", "W353", "W353"]);
}

#[test]
fn a_constant_input_is_not_written_in_the_body() {
    let src = "FUNCTION_BLOCK F
VAR_INPUT CONSTANT k : INT := 3; END_VAR
k := 4;
END_FUNCTION_BLOCK
PROGRAM P VAR f : F; END_VAR f(); END_PROGRAM";
    let codes = error_codes(&[("t.st", src)]);
    assert_eq!(
        codes.first().map(|c| c.0.as_str()),
        Some("E401"),
        "{codes:?}"
    );
}

#[test]
fn time_without_arguments_is_the_clock_the_timers_see() {
    let prelude = "FUNCTION NOW_MS : DWORD
VAR tx : TIME; END_VAR
tx := TIME();
NOW_MS := TIME_TO_DWORD(tx);
END_FUNCTION";
    // The default cycle is 10 ms; the clock reads 0, 10, 20 ms in cycles
    // 1..3, and a TON started in cycle 1 has run the same 20 ms.
    let w = check(
        prelude,
        "ms : DWORD; t : TIME; tm : TON; et : TIME;",
        "ms := NOW_MS(); t := TIME(); tm(IN := TRUE, PT := T#1s); et := tm.ET;",
        3,
        &[("ms", "16#14"), ("t", "T#20ms"), ("et", "T#20ms")],
    );
    assert_eq!(w, ["W354", "W354"]);
}

#[test]
fn array_initial_values_may_omit_the_brackets() {
    let prelude = "TYPE MONTHS : STRUCT
    days : ARRAY[1..4] OF INT := 0, 31, 59, 90;
    names : ARRAY[0..2] OF STRING(3) := 'jan', 'feb', 'mar';
END_STRUCT
END_TYPE";
    // Element by element as written; `2(7)` repeats 7 twice.
    let w = check(
        prelude,
        "m : MONTHS; a : ARRAY[0..4] OF INT := 1, 2(7), 3, 4; d3, a1, a2, a4 : INT; n2 : STRING(3);",
        "d3 := m.days[3]; a1 := a[1]; a2 := a[2]; a4 := a[4]; n2 := m.names[2];",
        1,
        &[
            ("d3", "59"),
            ("a1", "7"),
            ("a2", "7"),
            ("a4", "4"),
            ("n2", "'mar'"),
        ],
    );
    assert_eq!(w, ["W355", "W355", "W355"]);
}

#[test]
fn on_and_step_are_names_where_no_name_follows() {
    let prelude = "FUNCTION_BLOCK RAMP
VAR_INPUT on : BOOL; step : INT := 1; END_VAR
VAR_OUTPUT y : INT; END_VAR
IF on THEN y := y + step; END_IF
END_FUNCTION_BLOCK";
    // Two cycles with ON = TRUE and STEP = 5: y = 10; FOR 0..10 BY 5
    // runs 3 times.
    let w = check(
        prelude,
        "r : RAMP; ON : BOOL := TRUE; Step : INT := 5; i, n, y : INT;",
        "r(on := ON, step := Step); y := r.y;
         n := 0; FOR i := 0 TO 10 BY Step DO n := n + 1; END_FOR",
        2,
        &[("y", "10"), ("n", "3")],
    );
    assert!(!w.is_empty() && w.iter().all(|c| c == "W356"), "{w:?}");
}

#[test]
fn step_stays_a_keyword_in_charts() {
    let src = "PROGRAM P
VAR step : INT; END_VAR
INITIAL_STEP s0 : END_STEP
TRANSITION FROM s0 TO s1 := TRUE; END_TRANSITION
STEP s1 : END_STEP
TRANSITION FROM s1 TO s0 := TRUE; END_TRANSITION
END_PROGRAM";
    let mut plc = plc::compile(src);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "s1.X"), "TRUE");
}

#[test]
fn functionblock_is_read_as_function_block() {
    let prelude = "FUNCTIONBLOCK COUNTER
VAR_OUTPUT n : INT; END_VAR
n := n + 1;
END_FUNCTIONBLOCK";
    // Three calls count to 3.
    let w = check(
        prelude,
        "c : COUNTER; k : INT;",
        "c(); k := c.n;",
        3,
        &[("k", "3")],
    );
    assert_eq!(w, ["W357", "W357"]);
}

#[test]
fn a_local_constant_sizes_an_array_declared_above_it() {
    let prelude = "FUNCTION_BLOCK RING
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT top : INT; END_VAR
VAR buf : ARRAY[0..n] OF INT; i : INT; END_VAR
VAR CONSTANT n : INT := 3; END_VAR
buf[i] := x + i; top := buf[n]; i := (i + 1) MOD (n + 1);
END_FUNCTION_BLOCK";
    // The array has n + 1 = 4 elements; the 4th call writes buf[3] = 7 + 3
    // (an index beyond the array would fault).
    check(
        prelude,
        "r : RING; k : INT;",
        "r(x := 7); k := r.top;",
        4,
        &[("k", "10")],
    );
}

#[test]
fn bit_strings_mix_with_reals_and_index_arrays() {
    let w = check(
        "",
        "b : BYTE := 3; r : REAL := 0.5; x : REAL; a : ARRAY[0..3] OF INT := [10, 20, 30, 40]; k : INT;",
        // 0.5 * 3 = 1.5 (BYTE as USINT widens to REAL); a[3] = 40.
        "x := r * b; k := a[b];",
        1,
        &[("x", "1.5"), ("k", "40")],
    );
    assert_eq!(w, ["W350", "W358"]);
}

//! The native tier's frame cache (values held in registers across
//! instructions, docs/adr/0009-native-tier.md) against the interpreter:
//! every place where memory must be current again — a helper, a call, an
//! access through an address that lands on a held slot, a fault, the
//! return — and the inlined standard FBs at their edges. Each program
//! runs on both engines and every variable is compared after every cycle
//! (`differential::check_engines`), faults included.

use crate::fuzz::differential::{self, Verdict};
use crate::fuzz::st_gen::GenProgram;
use plcrun::{Engine, Options, Plc};

/// Runs `source` for `cycles` cycles on both engines; the code of the
/// cycle that faulted, if one did. Every block must compile natively.
fn agree(source: &str, cycles: usize) -> Option<&'static str> {
    if cfg!(all(feature = "native", target_arch = "x86_64")) {
        let options = Options {
            engine: Engine::Native,
            ..Options::default()
        };
        let plc = Plc::compile_files(&[("p.st", source)], &options).expect("compiles");
        let report = plc.native_report().expect("a report");
        assert!(
            report.fell_back.is_empty(),
            "{:?}\n{source}",
            report.fell_back
        );
    }
    let program = GenProgram {
        source: source.to_string(),
        cycles: vec![Vec::new(); cycles],
    };
    match differential::check_engines(&program) {
        Verdict::Agree { fault, .. } => fault,
        other => panic!("{other:?}\n{source}"),
    }
}

#[test]
fn values_reach_memory_before_helpers_and_calls() {
    // Changed in registers, then read by an out-of-line conversion, a
    // function with an in-out, an FB reading its input, a standard FB
    // through the helper (TOF is not inlined) and a string helper.
    let source = "FUNCTION Bump : DINT VAR_IN_OUT v : DINT; END_VAR
           v := v * 3 + 1; Bump := v; END_FUNCTION
         FUNCTION_BLOCK Acc VAR_INPUT x : DINT; END_VAR VAR_OUTPUT s : DINT; END_VAR
           s := s + x; END_FUNCTION_BLOCK
         PROGRAM P
         VAR n, m, k, r : DINT; f : REAL; l : LINT; a : Acc; t : TOF; s : STRING; q : BOOL; END_VAR
           n := n + 1; m := n * 7; f := DINT_TO_REAL(m) / 3.0; l := REAL_TO_LINT(f);
           k := n + 5; r := Bump(k); k := k + r;
           m := m + 1; a(x := m); m := a.s - m;
           q := (n MOD 3) = 0; t(IN := q, PT := T#0s); q := t.Q AND q;
           s := DINT_TO_STRING(k); n := n + LEN(s);
         END_PROGRAM";
    assert_eq!(agree(source, 40), None);
}

#[test]
fn accesses_through_addresses_see_held_values() {
    // A pointer into the frame read and written between register
    // writes of the slot it points to; a constant-index element next to
    // a computed one; an FB instance in an array reached by address.
    let source = "PROGRAM P
         VAR x, y, z, i : DINT; p : POINTER TO DINT; a : ARRAY[0..4] OF DINT;
             rt : ARRAY[0..1] OF R_TRIG; c : INT; END_VAR
           p := ADR(x);
           x := x + 2; y := p^; p^ := y * 5; z := x + 1;
           p := ADR(a[2]); a[2] := a[2] + 1; i := (i + 1) MOD 5;
           a[i] := a[i] + 10; z := z + a[2]; p^ := p^ + 100; y := a[2] - y;
           rt[i MOD 2](CLK := (x MOD 3) = 0); IF rt[i MOD 2].Q THEN c := c + 1; END_IF;
         END_PROGRAM";
    assert_eq!(agree(source, 30), None);
}

#[test]
fn element_addresses_made_in_the_block_write_over_held_elements() {
    // `sa[1]` by a constant index is a plain slot, held; `sa[k]` and
    // `cnt[k]` go through an element address (`ElemRef`) whose range is
    // known when translating: held slots in it must be written back and
    // dropped around the access.
    let source = "TYPE S : STRUCT x : DINT; y : DINT; END_STRUCT END_TYPE
         PROGRAM P
         VAR sa : ARRAY[0..3] OF S; cnt : ARRAY[0..3] OF CTU; n, k, z : DINT; END_VAR
           n := n + 1; k := n MOD 4;
           sa[1].x := sa[1].x + 1; sa[1].y := n;
           sa[k].x := sa[k].x * 2 + sa[1].y; sa[k].y := sa[k].y - 1;
           z := sa[1].x + sa[1].y + sa[k].x;
           cnt[1].PV := 3; cnt[k](CU := (n MOD 2) = 0, R := cnt[1].Q);
           z := z + INT_TO_DINT(cnt[1].CV) + INT_TO_DINT(cnt[k].CV);
         END_PROGRAM";
    assert_eq!(agree(source, 30), None);
}

#[test]
fn a_fault_after_values_changed_in_registers_leaves_the_interpreters_memory() {
    // Division by zero, an index out of range and a conversion overflow,
    // each after other variables changed in the same cycle (and in a
    // loop, whose values are held across its back edge).
    let cases = [
        "PROGRAM P VAR n, d, s, q : DINT; END_VAR
           n := n + 1; s := s + n * 2; d := 5 - n; q := 100 / d; s := s + q; END_PROGRAM",
        "PROGRAM P VAR a : ARRAY[0..9] OF INT; i, n, s : INT; END_VAR
           n := n + 1; FOR i := 0 TO n DO s := s + i; a[i] := s; END_FOR; END_PROGRAM",
        "PROGRAM P VAR n : DINT := 100; s : SINT; t : DINT; END_VAR
           t := t + n; n := n + 10; s := DINT_TO_SINT(n); t := t - 1; END_PROGRAM",
    ];
    for source in cases {
        assert!(agree(source, 40).is_some(), "no fault:\n{source}");
    }
}

#[test]
fn inlined_standard_fbs_match_at_their_edges() {
    // CTU saturating at the top of INT, counting UDINT and DINT,
    // reset in between; R_TRIG and F_TRIG on every kind of edge; TON
    // started, completed, interrupted and given a shorter PT.
    let source = "PROGRAM P
         VAR n : DINT; i : DINT; ci : CTU_INT; cu : CTU_UDINT; cd : CTU_DINT; c : CTU;
             r : R_TRIG; f : F_TRIG; t : TON; u : TON; b : BOOL; e : DINT; q : DINT; END_VAR
           n := n + 1;
           FOR i := 1 TO 70000 DO
             b := NOT b;
             ci(CU := b, R := n = 3, PV := 30000);
             cd(CU := b, R := FALSE, PV := 123456);
             c(CU := b, R := ci.Q AND (n = 5), PV := 10);
           END_FOR;
           cu(CU := (n MOD 2) = 0, R := n = 9, PV := 4294967295);
           r(CLK := (n MOD 3) = 0); f(CLK := (n MOD 4) < 2);
           IF r.Q THEN e := e + 1; END_IF; IF f.Q THEN e := e + 10; END_IF;
           t(IN := (n MOD 7) <> 0, PT := T#3ms);
           u(IN := (n MOD 11) < 8, PT := DINT_TO_TIME(5 - n MOD 4));
           q := TIME_TO_DINT(t.ET) + TIME_TO_DINT(u.ET);
         END_PROGRAM";
    assert_eq!(agree(source, 30), None);
}

#[test]
fn loops_hold_their_variables_and_poll_where_the_interpreter_polls() {
    // Nested loops with reals and integers kept across back edges, an
    // element store inside, SIN and SQRT (a helper and an inline root).
    let source = "PROGRAM P
         VAR i, j, s : DINT; x, acc : REAL; v : ARRAY[0..15] OF REAL; END_VAR
           FOR i := 0 TO 15 DO
             j := 0;
             WHILE j < i DO x := x + 0.25; j := j + 1; s := s + j; END_WHILE;
             v[i] := SQRT(ABS(x - 3.0)) + SIN(x);
             acc := acc + v[i] * 0.5;
           END_FOR;
           IF acc > 1000.0 THEN acc := 0.0; END_IF;
         END_PROGRAM";
    assert_eq!(agree(source, 25), None);
}

#[test]
fn proved_element_accesses_take_the_checked_path_around_held_slots() {
    // Loops whose index the compiler proves in range: the fast check
    // passes for arrays from 0 or 1, and for an array from 10 or -3 the
    // element-0 position lies on other (held) variables, so some
    // accesses go through the full checks on the cold path. Held
    // scalars change in the same loops.
    let source = "PROGRAM P
         VAR
           a, b, c : DINT;
           lo10 : ARRAY[10..19] OF DINT;
           one : ARRAY[1..8] OF REAL;
           neg : ARRAY[-3..3] OF DINT;
           zero : ARRAY[0..4] OF LREAL;
           i : DINT; s : DINT; r : REAL; l : LREAL;
         END_VAR
           FOR i := 10 TO 19 DO
             lo10[i] := lo10[i] + i + a; a := a + 1; b := b + lo10[i];
           END_FOR;
           FOR i := 1 TO 8 DO
             one[i] := one[i] * 0.5 + r; r := r + 0.25; c := c + 1;
           END_FOR;
           FOR i := -3 TO 3 DO
             neg[i] := neg[i] - i * s + 1; s := s + neg[i] MOD 7;
           END_FOR;
           FOR i := 0 TO 4 DO
             zero[i] := zero[i] + l; l := l + zero[i] * 0.125 + 1.0;
           END_FOR;
         END_PROGRAM";
    assert_eq!(agree(source, 30), None);
}

//! `ARRAY[*]` parameters (CODESYS and TwinCAT): a VAR_IN_OUT that takes
//! arrays of any bounds, indexed against the argument's bounds, measured
//! with `LOWER_BOUND` / `UPPER_BOUND` and passed on; and a FOR loop whose
//! control variable is an element or field of a local (TcUnit's
//! `FOR Offset[1] := ...`). Expected values derived by hand.

use crate::support::plc;

use plc::{compile_files, error_codes, first_fault, line_col, lit, run_once};

const SUM: &str = "
FUNCTION SumOf : DINT
VAR_IN_OUT xs : ARRAY[*] OF INT; END_VAR
VAR i : DINT; END_VAR
SumOf := 0;
FOR i := LOWER_BOUND(xs, 1) TO UPPER_BOUND(xs, 1) DO
    SumOf := SumOf + xs[i];
END_FOR
END_FUNCTION
";

#[test]
fn one_function_sums_arrays_of_any_bounds() {
    let src = format!(
        "{SUM}
FUNCTION Span : DINT
VAR_IN_OUT ys : ARRAY[*] OF INT; END_VAR
(* Passed on: the bounds travel with it. *)
Span := SumOf(ys) * 100 + UPPER_BOUND(ys, 1) - LOWER_BOUND(ys, 1) + 1;
END_FUNCTION
PROGRAM Main
VAR
    a : ARRAY[1..4] OF INT := [1, 2, 3, 4];
    b : ARRAY[-2..2] OF INT := [10, 20, 30, 40, 50];
    sa, sb, span_b, lo_b, hi_a : DINT;
END_VAR
sa := SumOf(a);
sb := SumOf(xs := b);
span_b := Span(b);
lo_b := LOWER_BOUND(b, 1);
hi_a := UPPER_BOUND(a, 1);
END_PROGRAM
"
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "sa"), "10");
    assert_eq!(lit(&plc, "sb"), "150");
    // 150 * 100 + (2 - -2 + 1)
    assert_eq!(lit(&plc, "span_b"), "15005");
    assert_eq!(lit(&plc, "lo_b"), "-2");
    assert_eq!(lit(&plc, "hi_a"), "4");
}

#[test]
fn a_block_writes_a_two_dimensional_argument_through_its_bounds() {
    let src = "
FUNCTION_BLOCK FB_Fill
VAR_IN_OUT grid : ARRAY[*, *] OF REAL; END_VAR
VAR_INPUT v : REAL; END_VAR
VAR i, j : DINT; END_VAR
FOR i := LOWER_BOUND(grid, 1) TO UPPER_BOUND(grid, 1) DO
    FOR j := LOWER_BOUND(grid, 2) TO UPPER_BOUND(grid, 2) DO
        grid[i, j] := v * DINT_TO_REAL(i * 10 + j);
    END_FOR
END_FOR
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    g : ARRAY[0..1, 3..5] OF REAL;
    h : ARRAY[1..1, 1..2] OF REAL;
    fill : FB_Fill;
END_VAR
fill(grid := g, v := 0.5);
fill(grid := h, v := 2.0);
END_PROGRAM
";
    let plc = run_once(src);
    // g[i, j] = 0.5 * (10 i + j); h[i, j] = 2 * (10 i + j).
    assert_eq!(lit(&plc, "g[0,3]"), "1.5");
    assert_eq!(lit(&plc, "g[0,5]"), "2.5");
    assert_eq!(lit(&plc, "g[1,3]"), "6.5");
    assert_eq!(lit(&plc, "g[1,4]"), "7.0");
    assert_eq!(lit(&plc, "h[1,2]"), "24.0");
}

#[test]
fn a_method_compares_arrays_the_way_tcunit_does() {
    // TcUnit's AssertArray2dEquals_*: bounds copied into arrays, then
    // walked with array elements as FOR control variables.
    let src = "
FUNCTION_BLOCK FB_Cmp
METHOD Equal : BOOL
VAR_IN_OUT
    Expecteds : ARRAY[*, *] OF INT;
    Actuals : ARRAY[*, *] OF INT;
END_VAR
VAR
    Size : ARRAY[1..2] OF DINT;
    Offset : ARRAY[1..2] OF DINT;
END_VAR
Size[1] := UPPER_BOUND(Expecteds, 1) - LOWER_BOUND(Expecteds, 1) + 1;
Size[2] := UPPER_BOUND(Expecteds, 2) - LOWER_BOUND(Expecteds, 2) + 1;
IF Size[1] <> UPPER_BOUND(Actuals, 1) - LOWER_BOUND(Actuals, 1) + 1
   OR Size[2] <> UPPER_BOUND(Actuals, 2) - LOWER_BOUND(Actuals, 2) + 1 THEN
    RETURN;
END_IF
Equal := TRUE;
FOR Offset[1] := 0 TO Size[1] - 1 DO
    FOR Offset[2] := 0 TO Size[2] - 1 DO
        IF Expecteds[LOWER_BOUND(Expecteds, 1) + Offset[1], LOWER_BOUND(Expecteds, 2) + Offset[2]]
           <> Actuals[LOWER_BOUND(Actuals, 1) + Offset[1], LOWER_BOUND(Actuals, 2) + Offset[2]] THEN
            Equal := FALSE;
        END_IF
    END_FOR
END_FOR
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    cmp : FB_Cmp;
    a : ARRAY[1..2, 1..3] OF INT := [1, 2, 3, 4, 5, 6];
    b : ARRAY[0..1, 7..9] OF INT := [1, 2, 3, 4, 5, 6];
    c : ARRAY[0..1, 7..9] OF INT := [1, 2, 3, 4, 5, 7];
    d : ARRAY[1..3, 1..2] OF INT := [1, 2, 3, 4, 5, 6];
    ab, ac, ad : BOOL;
END_VAR
ab := cmp.Equal(a, b);
ac := cmp.Equal(a, c);
ad := cmp.Equal(a, d);
END_PROGRAM
";
    let plc = run_once(src);
    assert_eq!(lit(&plc, "ab"), "TRUE");
    assert_eq!(lit(&plc, "ac"), "FALSE"); // last element differs
    assert_eq!(lit(&plc, "ad"), "FALSE"); // 2x3 against 3x2
}

#[test]
fn an_index_outside_the_arguments_bounds_faults_where_it_is_written() {
    let src = "
FUNCTION Get : INT
VAR_IN_OUT xs : ARRAY[*] OF INT; END_VAR
VAR_INPUT i : DINT; END_VAR
Get := xs[i];
END_FUNCTION
PROGRAM Main
VAR a : ARRAY[1..4] OF INT := [1, 2, 3, 4]; k : DINT := 1; v : INT; END_VAR
v := Get(a, k);
k := k + 2;
END_PROGRAM
";
    // k is 1, then 3, then 5: the third cycle faults.
    let fault = first_fault(src);
    assert_eq!(fault.code(), "R002", "{fault}");
    assert_eq!(fault.cycle, 2);
    assert_eq!(fault.pou, "Get");
    assert_eq!(line_col(&fault.location), (5, 8));
    assert!(fault.to_string().contains("index 5"), "{fault}");
    assert!(fault.to_string().contains("[1..4]"), "{fault}");
}

#[test]
fn an_open_array_anywhere_but_a_var_in_out_is_refused() {
    let src = "
TYPE T_Open : ARRAY[*] OF INT; END_TYPE
FUNCTION F : INT
VAR_INPUT bad : ARRAY[*] OF INT; END_VAR
F := 0;
END_FUNCTION
PROGRAM Main
VAR v : ARRAY[*] OF INT; END_VAR
END_PROGRAM
";
    let codes: Vec<_> = error_codes(&[("t.st", src)]);
    assert_eq!(
        codes,
        [
            ("E211".to_string(), "2:15".to_string()),
            ("E211".to_string(), "4:17".to_string()),
            ("E211".to_string(), "8:9".to_string()),
        ]
    );
}

#[test]
fn an_open_array_is_indexed_measured_or_passed_on_and_nothing_else() {
    let src = "
FUNCTION F : INT
VAR_IN_OUT xs : ARRAY[*] OF INT; ys : ARRAY[*] OF INT; END_VAR
VAR r : REAL; n : DINT; END_VAR
xs := ys;
n := SIZEOF(xs);
n := LOWER_BOUND(xs, 2);
n := UPPER_BOUND(r, 1);
n := xs[1, 2];
END_FUNCTION
PROGRAM Main
VAR
    a : ARRAY[1..4] OF INT;
    b : ARRAY[1..4] OF DINT;
    c : ARRAY[1..2, 1..2] OF INT;
    v : INT;
END_VAR
v := F(a, b);
v := F(a, c);
v := F(a, a);
END_PROGRAM
";
    let codes: Vec<String> = error_codes(&[("t.st", src)])
        .into_iter()
        .map(|(c, at)| format!("{c} {at}"))
        .collect();
    assert_eq!(
        codes,
        [
            "E307 5:1",   // a whole open array is not assigned
            "E307 6:13",  // nor measured in bytes
            "E308 7:22",  // it has one dimension
            "E302 8:18",  // a REAL has no bounds
            "E404 9:6",   // two indexes for one dimension
            "E301 18:11", // DINT elements for INT
            "E301 19:11", // two dimensions for one
        ]
    );
}

#[test]
fn a_for_loop_counts_with_an_element_or_a_field_of_a_local() {
    let src = "
TYPE S : STRUCT n : INT; END_STRUCT END_TYPE
PROGRAM Main
VAR off : ARRAY[1..2] OF DINT; s : S; total, count : DINT; END_VAR
FOR off[1] := 0 TO 2 DO
    FOR off[2] := 1 TO 3 DO
        total := total + off[1] * 10 + off[2];
    END_FOR
END_FOR
FOR s.n := 5 TO 1 BY -2 DO
    count := count + s.n;
END_FOR
END_PROGRAM
";
    let plc = run_once(src);
    // 3 * (0 + 10 + 20) + 3 * (1 + 2 + 3); 5 + 3 + 1; the counters end past their limits.
    assert_eq!(lit(&plc, "total"), "108");
    assert_eq!(lit(&plc, "count"), "9");
    assert_eq!(lit(&plc, "off[1]"), "3");
    assert_eq!(lit(&plc, "s.n"), "-1");
}

#[test]
fn a_for_counter_at_a_computed_index_or_written_in_the_loop_is_refused() {
    let src = "
PROGRAM Main
VAR a : ARRAY[1..2] OF DINT; k : INT := 1; END_VAR
FOR a[k] := 1 TO 2 DO
    a[2] := 0;
END_FOR
FOR a[1] := 1 TO 2 DO
    a[1] := 0;
END_FOR
END_PROGRAM
";
    assert_eq!(
        error_codes(&[("t.st", src)]),
        [
            ("E407".to_string(), "4:5".to_string()),
            ("E401".to_string(), "8:5".to_string()),
        ]
    );
}

#[test]
fn open_array_parameters_survive_a_plcopen_round_trip() {
    // The exporter writes `<dimension lower="*" upper="*"/>`, which the
    // reader turns back into `ARRAY[*]`.
    let src = format!(
        "{SUM}
PROGRAM Main
VAR a : ARRAY[3..5] OF INT := [7, 8, 9]; s : DINT; END_VAR
s := SumOf(a);
END_PROGRAM
"
    );
    let mut sources = plcrun::SourceMap::new();
    sources.add("sum.st", src.clone());
    let xml = plcrun::export_plcopen(&sources).expect("exports");
    assert!(xml.contains(r#"<dimension lower="*" upper="*"/>"#), "{xml}");
    let mut plc = compile_files(&[("sum.xml", xml.as_str())]);
    plc::run(&mut plc, 1);
    assert_eq!(lit(&plc, "s"), "24");
}

#[test]
fn the_native_engine_leaves_open_array_indexing_to_the_interpreter() {
    // The native tier does not lower OpenIndexStep yet: the block that
    // indexes an ARRAY[*] runs in the interpreter, the others natively,
    // with the same results.
    let src = format!(
        "{SUM}
PROGRAM Main
VAR a : ARRAY[3..5] OF INT := [7, 8, 9]; s : DINT; n : DINT; END_VAR
s := SumOf(a);
n := n + 1;
END_PROGRAM
"
    );
    let options = plcrun::Options {
        engine: plcrun::Engine::Native,
        ..plcrun::Options::default()
    };
    let mut plc = plcrun::Plc::compile_files(&[("p.st", src.as_str())], &options).unwrap();
    plc::run(&mut plc, 2);
    assert_eq!(lit(&plc, "s"), "24");
    assert_eq!(lit(&plc, "n"), "2");
    let report = plc.native_report().expect("a report");
    if cfg!(all(feature = "native", target_arch = "x86_64")) {
        assert!(report.compiled.iter().any(|b| b == "Main"), "{report:?}");
        assert!(
            report
                .fell_back
                .iter()
                .any(|f| f.block == "SumOf" && f.reason.contains("ARRAY[*]")),
            "{report:?}"
        );
    }
}

//! Generic inputs of user POUs (CODESYS V3, TwinCAT 3; issue #25): a
//! VAR_INPUT declared `ANY` or `ANY_<class>` in a FUNCTION, FUNCTION_BLOCK
//! or METHOD is the structure `TypeClass` / `pValue` / `diSize` the call
//! fills; `__SYSTEM.TYPE_CLASS` and its values; the argument refused
//! outside its class or without a byte layout. Expected values worked out
//! by hand from CODESYS's type class numbers (TYPE_BOOL 0, TYPE_INT 7,
//! TYPE_LREAL 15, TYPE_STRING 16, TYPE_TIME 18, TYPE_ARRAY 26...) and
//! plcrun's SIZEOF (docs/semantics.md §23).

use crate::support::{graphic, plc};

use plc::{compile_files, error_codes, first_fault, line_col, lit, run, run_once};

/// TwinCAT's MEMCPY (Tc2_System), written out for plain ST sources: a
/// TwinCAT project gets plcrun's own (docs/twincat.md).
const MEMCPY: &str = "
FUNCTION MEMCPY : UDINT
VAR_INPUT destAddr : ULINT; srcAddr : ULINT; n : UDINT; END_VAR
VAR d : POINTER TO BYTE; s : POINTER TO BYTE; i : UDINT; END_VAR
d := destAddr;
s := srcAddr;
FOR i := 1 TO n DO
    d^ := s^;
    d := d + 1;
    s := s + 1;
END_FOR
MEMCPY := n;
END_FUNCTION
";

/// Written as TcUnit's AssertEquals is: the type classes compared, a CASE
/// on the class, the bytes copied into a typed local, the locals
/// compared; any other class compared byte by byte.
const EQUAL: &str = "
FUNCTION Equal : BOOL
VAR_INPUT Expected : ANY; Actual : ANY; END_VAR
VAR
    b1, b2 : BOOL;
    i1, i2 : INT;
    r1, r2 : LREAL;
    s1, s2 : STRING(255);
    t1, t2 : TIME;
    k : DINT;
END_VAR
Equal := FALSE;
IF Expected.TypeClass <> Actual.TypeClass THEN
    RETURN;
END_IF
CASE Expected.TypeClass OF
    __SYSTEM.TYPE_CLASS.TYPE_BOOL:
        MEMCPY(ADR(b1), Expected.pValue, DINT_TO_UDINT(Expected.diSize));
        MEMCPY(ADR(b2), Actual.pValue, DINT_TO_UDINT(Actual.diSize));
        Equal := b1 = b2;
    TYPE_CLASS.TYPE_INT:
        MEMCPY(ADR(i1), Expected.pValue, DINT_TO_UDINT(Expected.diSize));
        MEMCPY(ADR(i2), Actual.pValue, DINT_TO_UDINT(Actual.diSize));
        Equal := i1 = i2;
    TYPE_CLASS.TYPE_LREAL:
        MEMCPY(ADR(r1), Expected.pValue, DINT_TO_UDINT(Expected.diSize));
        MEMCPY(ADR(r2), Actual.pValue, DINT_TO_UDINT(Actual.diSize));
        Equal := r1 = r2;
    TYPE_CLASS.TYPE_STRING:
        MEMCPY(ADR(s1), Expected.pValue, DINT_TO_UDINT(Expected.diSize));
        MEMCPY(ADR(s2), Actual.pValue, DINT_TO_UDINT(Actual.diSize));
        Equal := s1 = s2;
    TYPE_CLASS.TYPE_TIME:
        MEMCPY(ADR(t1), Expected.pValue, DINT_TO_UDINT(Expected.diSize));
        MEMCPY(ADR(t2), Actual.pValue, DINT_TO_UDINT(Actual.diSize));
        Equal := t1 = t2;
ELSE
    IF Expected.diSize <> Actual.diSize THEN
        RETURN;
    END_IF
    FOR k := 0 TO Expected.diSize - 1 DO
        IF Expected.pValue[k] <> Actual.pValue[k] THEN
            RETURN;
        END_IF
    END_FOR
    Equal := TRUE;
END_CASE
END_FUNCTION
";

#[test]
fn an_assert_equals_written_as_tcunit_s_compares_bool_int_lreal_string_time_and_literals() {
    let src = format!(
        "{MEMCPY}{EQUAL}
PROGRAM Main
VAR
    b : BOOL := TRUE; b2 : BOOL := TRUE;
    i : INT := -7; j : INT := 5;
    r : LREAL := 2.5;
    s : STRING := 'abc'; s2 : STRING(20) := 'abc'; s3 : STRING(20) := 'abd';
    t : TIME := T#1500ms;
    w1 : WORD := 16#1234; w2 : WORD := 16#1234; w3 : WORD := 16#1235;
    eq_bool, ne_int, eq_int_lit, eq_real_lit, eq_str, ne_str, eq_time_lit,
    ne_classes, eq_lits, eq_words, ne_words, ne_bool_lit : BOOL;
END_VAR
eq_bool := Equal(b, b2);
ne_int := Equal(i, j);
eq_int_lit := Equal(Expected := -7, Actual := i);
eq_real_lit := Equal(2.5, r);
eq_str := Equal(s, s2);
ne_str := Equal(s2, s3);
eq_time_lit := Equal(t, T#1.5s);
ne_classes := Equal(i, r);
eq_lits := Equal(7, 3 + 4);
eq_words := Equal(w1, w2);
ne_words := Equal(w1, w3);
ne_bool_lit := Equal(b, FALSE);
END_PROGRAM
"
    );
    let plc = run_once(&src);
    for (name, want) in [
        ("eq_bool", "TRUE"),
        ("ne_int", "FALSE"),
        ("eq_int_lit", "TRUE"),
        ("eq_real_lit", "TRUE"),
        ("eq_str", "TRUE"),
        ("ne_str", "FALSE"),
        ("eq_time_lit", "TRUE"),
        ("ne_classes", "FALSE"),
        ("eq_lits", "TRUE"),
        ("eq_words", "TRUE"),
        ("ne_words", "FALSE"),
        ("ne_bool_lit", "FALSE"),
    ] {
        assert_eq!(lit(&plc, name), want, "{name}");
    }
}

/// `Info(x)` = type class × 1000 + size in bytes.
const INFO: &str = "
FUNCTION Info : DINT
VAR_INPUT x : ANY; END_VAR
Info := UDINT_TO_DINT(x.TypeClass) * 1000 + x.diSize;
END_FUNCTION
";

#[test]
fn the_callee_sees_the_argument_s_type_class_and_size() {
    let src = format!(
        "{INFO}
TYPE E_Mode : (Idle, Run); END_TYPE
TYPE T_Small : INT(0..9); END_TYPE
PROGRAM Main
VAR
    x : BOOL; bt : BYTE; w : WORD; si : SINT; i : INT; ud : UDINT; li : LINT;
    re : REAL; lr : LREAL; s : STRING(80); ws : WSTRING(10);
    t : TIME; lt : LTIME; d : DATE; dt1 : DT; tod1 : TOD;
    a : ARRAY[1..3] OF INT; m : E_Mode; sm : T_Small;
    r : ARRAY[0..20] OF DINT;
END_VAR
r[0] := Info(x);
r[1] := Info(bt);
r[2] := Info(w);
r[3] := Info(si);
r[4] := Info(i);
r[5] := Info(ud);
r[6] := Info(li);
r[7] := Info(re);
r[8] := Info(lr);
r[9] := Info(s);
r[10] := Info(ws);
r[11] := Info(t);
r[12] := Info(lt);
r[13] := Info(d);
r[14] := Info(dt1);
r[15] := Info(tod1);
r[16] := Info(a);
r[17] := Info(m);
r[18] := Info(sm);
r[19] := Info('hello');
r[20] := Info(100000);
END_PROGRAM
"
    );
    let plc = run_once(&src);
    let want = [
        "1", "2001", "3002", "6001", "7002", "12004", "9008", "14004", "15008", "16081", "17022",
        "18008", "37008", "19008", "20008", "21008", "26006", "25004", "24002", "16006", "8004",
    ];
    for (k, w) in want.iter().enumerate() {
        assert_eq!(lit(&plc, &format!("r[{k}]")), *w, "r[{k}]");
    }
}

#[test]
fn the_value_is_reached_through_a_typed_pointer_and_written_back_to_the_caller_s_variable() {
    let src = "
FUNCTION Twice : DINT
VAR_INPUT x : ANY_INT; END_VAR
VAR p : POINTER TO INT; END_VAR
p := x.pValue;
Twice := INT_TO_DINT(p^) * 2;
(* The caller's variable itself: a literal's temporary takes the write. *)
p^ := 42;
END_FUNCTION
PROGRAM Main
VAR i : INT := 21; seen, lit2 : DINT; END_VAR
seen := Twice(i);
lit2 := Twice(5);
END_PROGRAM
";
    let plc = run_once(src);
    assert_eq!(lit(&plc, "seen"), "42");
    assert_eq!(lit(&plc, "lit2"), "10");
    assert_eq!(lit(&plc, "i"), "42");
}

#[test]
fn function_blocks_and_methods_take_generic_inputs_and_pass_them_on() {
    let src = format!(
        "{INFO}
FUNCTION_BLOCK FB_Probe
VAR_INPUT v : ANY_NUM; END_VAR
VAR_OUTPUT cls : DINT; size : DINT; END_VAR
cls := UDINT_TO_DINT(v.TypeClass);
size := v.diSize;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Log
VAR_OUTPUT last : DINT; END_VAR
METHOD Note : DINT
VAR_INPUT x : ANY; END_VAR
(* An ANY input passed on to another ANY input. *)
Note := Info(x);
last := x.diSize;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION Outer : DINT
VAR_INPUT n : ANY_INT; END_VAR
Outer := Info(n);
END_FUNCTION
PROGRAM Main
VAR
    probe : FB_Probe; log : FB_Log;
    r : REAL := 1.5; u : USINT := 3; s : STRING(5) := 'ab';
    pc, ps, ln, ll, o : DINT;
END_VAR
probe(v := r);
pc := probe.cls;
ps := probe.size;
probe(v := u);
ln := log.Note(s);
ll := log.last;
o := Outer(u);
END_PROGRAM
"
    );
    let plc = run_once(&src);
    assert_eq!(lit(&plc, "pc"), "14");
    assert_eq!(lit(&plc, "ps"), "4");
    assert_eq!(lit(&plc, "probe.cls"), "10");
    assert_eq!(lit(&plc, "probe.size"), "1");
    assert_eq!(lit(&plc, "ln"), "16006");
    assert_eq!(lit(&plc, "ll"), "6");
    assert_eq!(lit(&plc, "o"), "10001");
}

#[test]
fn type_class_values_compare_and_select_in_all_three_spellings() {
    let src = "
FUNCTION Kind : INT
VAR_INPUT x : ANY; END_VAR
Kind := 0;
IF x.TypeClass = __SYSTEM.TYPE_CLASS.TYPE_INT THEN
    Kind := 1;
ELSIF x.TypeClass = TYPE_CLASS.TYPE_LREAL THEN
    Kind := 2;
END_IF
CASE x.TypeClass OF
    TYPE_CLASS.TYPE_STRING, TYPE_CLASS.TYPE_WSTRING: Kind := 3;
END_CASE
END_FUNCTION
PROGRAM Main
VAR
    i : INT; r : LREAL; s : STRING; b : BOOL;
    k1, k2, k3, k4 : INT;
    c : __SYSTEM.TYPE_CLASS := TYPE_CLASS.TYPE_TIME;
    n : DINT;
END_VAR
k1 := Kind(i);
k2 := Kind(r);
k3 := Kind(s);
k4 := Kind(b);
n := UDINT_TO_DINT(c);
END_PROGRAM
";
    let plc = run_once(src);
    assert_eq!(lit(&plc, "k1"), "1");
    assert_eq!(lit(&plc, "k2"), "2");
    assert_eq!(lit(&plc, "k3"), "3");
    assert_eq!(lit(&plc, "k4"), "0");
    assert_eq!(lit(&plc, "n"), "18");
}

#[test]
fn a_generic_type_anywhere_but_a_function_block_or_method_input_is_refused() {
    let src = "
TYPE S : STRUCT a : ANY; END_STRUCT END_TYPE
FUNCTION F : ANY_NUM
VAR_INPUT ok : ANY_NUM; END_VAR
VAR_OUTPUT o : ANY; END_VAR
VAR_IN_OUT io : ANY_INT; END_VAR
VAR l : ANY_BIT; END_VAR
F := 0;
END_FUNCTION
PROGRAM Main
VAR_INPUT p : ANY; END_VAR
VAR g : ARRAY[1..2] OF ANY_REAL; END_VAR
END_PROGRAM
";
    let codes = error_codes(&[("t.st", src)]);
    let want: Vec<(String, String)> = ["2:21", "3:14", "5:16", "6:17", "7:9", "11:15", "12:24"]
        .iter()
        .map(|lc| ("E212".to_string(), lc.to_string()))
        .collect();
    assert_eq!(codes, want);
}

#[test]
fn an_argument_outside_the_class_or_without_bytes_is_refused_at_the_argument() {
    let src = "
TYPE Pt : STRUCT x, y : INT; END_STRUCT END_TYPE
FUNCTION Num : DINT
VAR_INPUT v : ANY_NUM; END_VAR
Num := v.diSize;
END_FUNCTION
FUNCTION Whole : DINT
VAR_INPUT v : ANY; END_VAR
Whole := v.diSize;
END_FUNCTION
FUNCTION OnlyInt : DINT
VAR_INPUT v : ANY_INT; END_VAR
OnlyInt := v.diSize;
END_FUNCTION
FUNCTION PassOn : DINT
VAR_INPUT v : ANY; END_VAR
PassOn := OnlyInt(v);
END_FUNCTION
PROGRAM Main
VAR
    s : STRING; p : Pt; t : TON; c : CHAR; q : POINTER TO INT;
    ss : ARRAY[1..2] OF STRING; n : DINT;
END_VAR
n := Num(s);
n := Whole(p);
n := Whole(t);
n := Whole(c);
n := Whole(q);
n := Whole(ss);
n := Num(T#1s);
n := Whole();
END_PROGRAM
";
    let codes = error_codes(&[("t.st", src)]);
    let want: Vec<(String, String)> = [
        ("E439", "17:19"),
        ("E439", "24:10"),
        ("E440", "25:12"),
        ("E440", "26:12"),
        ("E440", "27:12"),
        ("E440", "28:12"),
        ("E440", "29:12"),
        ("E439", "30:10"),
        ("E404", "31:6"),
    ]
    .iter()
    .map(|(c, lc)| (c.to_string(), lc.to_string()))
    .collect();
    assert_eq!(codes, want);
}

#[test]
fn reading_past_the_argument_or_through_an_input_never_bound_faults() {
    let past = "
FUNCTION Peek : BYTE
VAR_INPUT v : ANY; END_VAR
Peek := v.pValue[v.diSize];
END_FUNCTION
PROGRAM Main
VAR i : INT; b : BYTE; END_VAR
b := Peek(i);
END_PROGRAM
";
    let fault = first_fault(past);
    assert_eq!(fault.code(), "R031", "{fault}");
    assert_eq!(fault.pou, "Peek");
    assert_eq!(line_col(&fault.location), (4, 9));
    let unbound = "
FUNCTION_BLOCK FB_Read
VAR_INPUT v : ANY; END_VAR
VAR_OUTPUT first : BYTE; END_VAR
first := v.pValue^;
END_FUNCTION_BLOCK
PROGRAM Main
VAR r : FB_Read; END_VAR
r();
END_PROGRAM
";
    let fault = first_fault(unbound);
    assert_eq!(fault.code(), "R030", "{fault}");
    assert_eq!(line_col(&fault.location), (5, 10));
}

/// A TwinCAT function using plcrun's MEMCPY and the Base Interfaces
/// library's `IBaseLibrary.TypeClass`, as TcUnit's AssertEquals does.
#[test]
fn twincat_code_names_the_classes_through_ibaselibrary() {
    let f = "<?xml version=\"1.0\" encoding=\"utf-8\"?>
<TcPlcObject Version=\"1.1.0.1\">
  <POU Name=\"F_Same\" Id=\"{00000000-0000-0000-0000-000000000001}\" SpecialFunc=\"None\">
    <Declaration><![CDATA[FUNCTION F_Same : BOOL
VAR_INPUT
    Expected : ANY;
    Actual : ANY;
END_VAR
VAR
    i1, i2 : INT;
    cls : IBaseLibrary.TypeClass;
END_VAR]]></Declaration>
    <Implementation>
      <ST><![CDATA[cls := UDINT_TO_INT(Expected.TypeClass);
IF UDINT_TO_INT(Expected.TypeClass) = IBaseLibrary.TypeClass.TYPE_INT
   AND Expected.TypeClass = Actual.TypeClass THEN
    MEMCPY(destAddr := ADR(i1), srcAddr := Expected.pValue, n := SIZEOF(INT));
    MEMCPY(destAddr := ADR(i2), srcAddr := Actual.pValue, n := SIZEOF(INT));
    F_Same := i1 = i2;
END_IF
CASE cls OF
    IBaseLibrary.TypeClass.TYPE_INTERFACE: F_Same := FALSE;
END_CASE]]></ST>
    </Implementation>
  </POU>
</TcPlcObject>
";
    let main = "PROGRAM MAIN
VAR a : INT := 3; b : INT := 3; c : INT := 4; same, differ : BOOL; END_VAR
same := F_Same(a, b);
differ := F_Same(a, c);
END_PROGRAM
";
    let mut plc = compile_files(&[("F_Same.TcPOU", f), ("main.st", main)]);
    run(&mut plc, 1);
    assert_eq!(lit(&plc, "same"), "TRUE");
    assert_eq!(lit(&plc, "differ"), "FALSE");
}

/// PLCopen XML's generic type elements (`<ANY_NUM/>`) declare a generic
/// input.
#[test]
fn a_plcopen_input_typed_with_a_generic_element_is_generic() {
    let pous = r#"<pou name="F_Size" pouType="function">
  <interface>
    <returnType><DINT/></returnType>
    <inputVars><variable name="v"><type><ANY_NUM/></type></variable></inputVars>
  </interface>
  <body><ST><xhtml:p>F_Size := v.diSize;</xhtml:p></ST></body>
</pou>
<pou name="MAIN" pouType="program">
  <interface>
    <localVars>
      <variable name="x"><type><LREAL/></type></variable>
      <variable name="n"><type><DINT/></type></variable>
    </localVars>
  </interface>
  <body><ST><xhtml:p>n := F_Size(x);</xhtml:p></ST></body>
</pou>"#;
    let xml = graphic::project(pous);
    let trace = graphic::trace_text(&xml, "n", "", 1);
    assert_eq!(trace, "cycle,time,n\n0,T#0s,8\n");
}

/// `__SYSTEM.TYPE_CLASS` and the Base Interfaces' `TypeClass` are two
/// enumerations: compared directly they do not mix (E306); TcUnit compares
/// `UDINT_TO_INT(x.TypeClass)` with the latter's values.
#[test]
fn a_type_class_and_a_base_interfaces_type_class_are_not_compared_directly() {
    let f = "<?xml version=\"1.0\" encoding=\"utf-8\"?>
<TcPlcObject Version=\"1.1.0.1\">
  <POU Name=\"F\" Id=\"{00000000-0000-0000-0000-000000000001}\" SpecialFunc=\"None\">
    <Declaration><![CDATA[FUNCTION F : BOOL
VAR_INPUT
    x : ANY;
END_VAR]]></Declaration>
    <Implementation>
      <ST><![CDATA[F := x.TypeClass = IBaseLibrary.TypeClass.TYPE_INT;]]></ST>
    </Implementation>
  </POU>
</TcPlcObject>
";
    let main = "PROGRAM MAIN\nVAR i : INT; b : BOOL; END_VAR\nb := F(i);\nEND_PROGRAM\n";
    let codes = error_codes(&[("F.TcPOU", f), ("main.st", main)]);
    assert_eq!(codes, [("E306".to_string(), "9:25".to_string())]);
}

/// A METHOD's generic input must be given (it has no initial value); a
/// constant is passed through a temporary, so a write through the
/// pointer leaves it alone.
#[test]
fn a_method_s_generic_input_must_be_given_and_a_constant_is_passed_as_a_copy() {
    let missing = "
FUNCTION_BLOCK FB_M
METHOD Put : DINT
VAR_INPUT v : ANY; n : INT; END_VAR
Put := v.diSize;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR m : FB_M; d : DINT; END_VAR
d := m.Put(n := 1);
END_PROGRAM
";
    assert_eq!(
        error_codes(&[("t.st", missing)]),
        [("E404".to_string(), "10:6".to_string())]
    );
    let constant = "
FUNCTION Clear : BOOL
VAR_INPUT v : ANY_INT; END_VAR
VAR p : POINTER TO INT; END_VAR
p := v.pValue;
p^ := 0;
Clear := TRUE;
END_FUNCTION
PROGRAM Main
VAR CONSTANT k : INT := 7; END_VAR
VAR seen : INT; done : BOOL; END_VAR
done := Clear(k);
seen := k;
END_PROGRAM
";
    let plc = run_once(constant);
    assert_eq!(lit(&plc, "done"), "TRUE");
    assert_eq!(lit(&plc, "seen"), "7");
}

/// A method with a generic input called through an interface: each
/// implementing block's input receives the argument's fields; a generic
/// input left out is E404.
#[test]
fn a_generic_input_of_an_interface_method_is_passed_to_the_implementing_block() {
    let src = "
INTERFACE I_Log
METHOD Put : DINT
VAR_INPUT v : ANY; tag : INT; END_VAR
END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Sizes IMPLEMENTS I_Log
VAR_OUTPUT last : DINT; END_VAR
METHOD Put : DINT
VAR_INPUT v : ANY; tag : INT; END_VAR
last := v.diSize;
Put := UDINT_TO_DINT(v.TypeClass) * 1000 + tag;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_First IMPLEMENTS I_Log
VAR_OUTPUT first : BYTE; END_VAR
METHOD Put : DINT
VAR_INPUT v : ANY; tag : INT; END_VAR
first := v.pValue^;
Put := tag;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    sizes : FB_Sizes; firsts : FB_First; log : I_Log;
    w : WORD := 16#1234; a, b : DINT;
END_VAR
log := sizes;
a := log.Put(w, 5);
log := firsts;
b := log.Put(v := w, tag := 6);
END_PROGRAM
";
    let plc = run_once(src);
    assert_eq!(lit(&plc, "a"), "3005");
    assert_eq!(lit(&plc, "sizes.last"), "2");
    assert_eq!(lit(&plc, "b"), "6");
    // The low byte first: little-endian, as CODESYS lays a WORD out.
    assert_eq!(lit(&plc, "firsts.first"), "16#34");
    let missing = src.replace("b := log.Put(v := w, tag := 6);", "b := log.Put(tag := 6);");
    assert_eq!(
        error_codes(&[("t.st", &missing)]),
        [("E404".to_string(), "31:6".to_string())]
    );
}

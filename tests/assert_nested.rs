//! `AssertArrayEquals` over multi-dimensional arrays and arrays of
//! structures (docs/testing.md): equal values pass, the first differing
//! element is reported by its path with both values, in text and JUnit.

use plcrun::{SourceMap, TestOptions, TestOutcome, TestReport, run_tests};

fn report(text: &str) -> TestReport {
    let mut sources = SourceMap::new();
    sources.add("t.st", text);
    run_tests(&sources, &TestOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

const SRC: &str = "TYPE Pt : STRUCT x, y : INT; tag : STRING; END_STRUCT; END_TYPE
TYPE Path : STRUCT pts : ARRAY[0..1] OF Pt; closed : BOOL; END_STRUCT; END_TYPE
PROGRAM TEST_Nested
VAR e, a : ARRAY[1..2, 0..2] OF INT; pe, pa : ARRAY[1..3] OF Pt;
    qe, qa : ARRAY[1..2] OF Path; i, j : INT; END_VAR
FOR i := 1 TO 2 DO FOR j := 0 TO 2 DO e[i,j] := i * 10 + j; a[i,j] := i * 10 + j; END_FOR; END_FOR;
AssertArrayEquals(e, a, 'same grid');
a[2,1] := 99; a[2,2] := 98;
AssertArrayEquals(e, a, 'grid');
pe[3].tag := 'a'; pa[3].tag := 'a';
AssertArrayEquals(pe, pa, 'same points');
pa[3].tag := 'b'; pa[3].y := 4;
AssertArrayEquals(Expected := pe, Actual := pa, Message := 'points');
qa[2].pts[1].y := 7;
AssertArrayEquals(qe, qa, 'paths');
END_PROGRAM
";

#[test]
fn the_first_differing_element_is_named_by_its_path() {
    let r = report(SRC);
    assert_eq!(r.cases[0].outcome(), TestOutcome::Failed);
    let got: Vec<_> = r.cases[0]
        .failures
        .iter()
        .map(|f| {
            (
                f.element.clone().unwrap_or_default(),
                f.expected.clone(),
                f.actual.clone(),
                f.message.clone(),
            )
        })
        .collect();
    let want = [
        ("[2,1]", "21", "99", "grid"),
        ("[3].y", "0", "4", "points"),
        ("[2].pts[1].y", "0", "7", "paths"),
    ];
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert_eq!((g.0.as_str(), g.1.as_str(), g.2.as_str(), g.3.as_str()), w);
    }
    let text = r.to_text();
    assert!(
        text.contains("t.st:9:1: cycle 0: element [2,1]: expected 21, actual 99: grid"),
        "{text}"
    );
    let xml = r.to_junit("plcrun");
    assert!(
        xml.contains("element [3].y: expected 0, actual 4: points"),
        "{xml}"
    );
}

#[test]
fn equal_nested_arrays_pass() {
    let src = "TYPE Pt : STRUCT x, y : INT; END_STRUCT; END_TYPE
PROGRAM TEST_Same
VAR e, a : ARRAY[1..2, 1..2] OF Pt; END_VAR
e[2,2].x := 3; a[2,2].x := 3;
AssertArrayEquals(e, a);
END_PROGRAM
";
    let r = report(src);
    assert_eq!(r.cases[0].outcome(), TestOutcome::Passed, "{}", r.to_text());
}

#[test]
fn nested_arrays_of_other_types_are_refused() {
    let src = "PROGRAM TEST_Shapes
VAR e : ARRAY[1..2, 1..2] OF INT; a : ARRAY[1..2, 1..3] OF INT; END_VAR
AssertArrayEquals(e, a);
END_PROGRAM
";
    let mut sources = SourceMap::new();
    sources.add("t.st", src);
    match run_tests(&sources, &TestOptions::default()) {
        Err(plcrun::TestError::Compile(e)) => {
            assert!(e.diagnostics.iter().any(|d| d.code == "E482"))
        }
        other => panic!("expected E482, got {other:?}"),
    }
}

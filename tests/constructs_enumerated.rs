//! Nothing silently ignored (issue #13 point 4): every construct of the
//! grammar either runs (and does what it says: each program below checks
//! a value it computes with the construct) or is refused with an error
//! that names it.
//!
//! The list of constructs is read from the sources, not written here: the
//! keywords of the grammar (`grammars/plc.lalrpop`), the words refused by
//! name (`UNSUPPORTED` in `src/syntax/parser.rs`), and the statement and
//! expression kinds of the AST (`src/syntax/ast.rs`). A construct added
//! without a row in [`ROWS`] makes `every_construct_has_a_row` fail.

use crate::support::plc;

use plcrun::{Options, Plc, Severity};

/// One program exercising some constructs.
struct Row {
    /// Keywords, refused words and AST kinds (`Stmt::If`, `Expr::Member`)
    /// the program exercises.
    covers: &'static [&'static str],
    /// The program.
    source: &'static str,
    /// After three cycles: variable and value (IEC literal).
    expect: &'static [(&'static str, &'static str)],
}

const ROWS: &[Row] = &[
    Row {
        covers: &[
            "PROGRAM",
            "END_PROGRAM",
            "VAR",
            "END_VAR",
            "Stmt::Assign",
            "Stmt::Empty",
            "Expr::Literal",
            "Expr::Name",
            "Expr::Binary",
            "Expr::Unary",
            "Expr::Paren",
            "NOT",
            "AND",
            "OR",
            "XOR",
            "MOD",
        ],
        source: "PROGRAM P\nVAR\n  a : INT; b : BOOL; c : INT;\nEND_VAR\n;\na := -(7 MOD 4) + 2 ** 3;\nb := NOT (FALSE AND TRUE) XOR (FALSE OR FALSE);\nc := a * 2 - 1;\nEND_PROGRAM\n",
        expect: &[("a", "5"), ("b", "TRUE"), ("c", "9")],
    },
    Row {
        covers: &["UNION", "END_UNION"],
        // The members share the bytes: 16#11223344 is 44 33 22 11.
        source: "TYPE U : UNION dw : DWORD; b : ARRAY[0..3] OF BYTE; END_UNION END_TYPE\nPROGRAM P\nVAR\n  u : U; low : BYTE;\nEND_VAR\nu.dw := 16#11223344;\nlow := u.b[0];\nEND_PROGRAM\n",
        expect: &[("low", "16#44")],
    },
    Row {
        covers: &["AND_THEN", "OR_ELSE"],
        // The right operands would fault (division by zero, index 9 of
        // 0..2) if they were evaluated: short-circuit means they are not.
        source: "PROGRAM P\nVAR\n  z : INT; arr : ARRAY[0..2] OF INT; i : INT := 9; a : BOOL; o : BOOL; both : BOOL;\nEND_VAR\na := FALSE AND_THEN (10 / z > 1);\no := TRUE OR_ELSE (arr[i] > 0);\nboth := TRUE AND_THEN NOT FALSE;\nEND_PROGRAM\n",
        expect: &[("a", "FALSE"), ("o", "TRUE"), ("both", "TRUE")],
    },
    Row {
        covers: &[
            "FUNCTION",
            "END_FUNCTION",
            "FUNCTION_BLOCK",
            "END_FUNCTION_BLOCK",
            "VAR_INPUT",
            "VAR_OUTPUT",
            "VAR_IN_OUT",
            "VAR_TEMP",
            "RETURN",
            "Stmt::Call",
            "Stmt::Return",
            "Expr::Call",
            "Expr::Member",
        ],
        source: "FUNCTION Twice : INT\nVAR_INPUT x : INT; END_VAR\nVAR_TEMP t : INT; END_VAR\nt := x;\nTwice := 2 * t;\nRETURN;\nTwice := 0;\nEND_FUNCTION\n\
            FUNCTION_BLOCK Acc\nVAR_INPUT inc : INT; END_VAR\nVAR_OUTPUT total : INT; END_VAR\nVAR_IN_OUT io : INT; END_VAR\ntotal := total + inc;\nio := io + 1;\nEND_FUNCTION_BLOCK\n\
            PROGRAM P\nVAR\n  acc : Acc; n : INT; y : INT; calls : INT;\nEND_VAR\nacc(inc := 2, io := calls);\nn := acc.total;\ny := Twice(21);\nEND_PROGRAM\n",
        expect: &[("n", "6"), ("y", "42"), ("calls", "3")],
    },
    Row {
        covers: &[
            "VAR_GLOBAL",
            "VAR_EXTERNAL",
            "CONSTANT",
            "RETAIN",
            "NON_RETAIN",
            "PERSISTENT",
            "AT",
            "Expr::Direct",
            "Expr::BitAccess",
        ],
        source: "VAR_GLOBAL CONSTANT\n  K : INT := 3;\nEND_VAR\nVAR_GLOBAL\n  g : INT := 1;\nEND_VAR\n\
            PROGRAM P\nVAR_EXTERNAL\n  g : INT;\nEND_VAR\nVAR RETAIN\n  r : INT;\nEND_VAR\nVAR NON_RETAIN\n  nr : INT;\nEND_VAR\nVAR PERSISTENT\n  pr : INT;\nEND_VAR\nVAR\n  q AT %QX0.0 : BOOL;\n  w : WORD := 16#0004;\n  bit2 : BOOL;\n  m : BOOL;\nEND_VAR\n\
            g := g + K;\nr := g; nr := g; pr := g;\nbit2 := w.2;\nq := bit2;\nm := %QX0.0;\nEND_PROGRAM\n",
        expect: &[("g", "10"), ("r", "10"), ("bit2", "TRUE"), ("m", "TRUE")],
    },
    Row {
        covers: &[
            "TYPE",
            "END_TYPE",
            "STRUCT",
            "END_STRUCT",
            "ARRAY",
            "OF",
            "STRING",
            "WSTRING",
            "Expr::Index",
        ],
        source: "TYPE\n  Pt : STRUCT x : INT; y : INT; END_STRUCT;\n  Row3 : ARRAY[1..3] OF INT;\n  Small : INT (0..10);\n  Colour : (Red, Green);\nEND_TYPE\n\
            PROGRAM P\nVAR\n  p : Pt; r : Row3; s : STRING[10] := 'ab'; w : WSTRING := \"cd\"; n : INT; sm : Small := 4; c : Colour := Green; isg : BOOL;\nEND_VAR\n\
            p.x := 2; r[2] := p.x + sm; n := r[2] + LEN(s) + LEN(w); isg := c = Green;\nEND_PROGRAM\n",
        expect: &[("n", "10"), ("isg", "TRUE")],
    },
    Row {
        covers: &[
            "IF",
            "THEN",
            "ELSIF",
            "ELSE",
            "END_IF",
            "CASE",
            "END_CASE",
            "Stmt::If",
            "Stmt::Case",
        ],
        source: "PROGRAM P\nVAR\n  i : INT := 2; a : INT; b : INT;\nEND_VAR\n\
            IF i = 1 THEN a := 10; ELSIF i = 2 THEN a := 20; ELSE a := 30; END_IF;\n\
            CASE i OF 1: b := 1; 2, 3: b := 2; ELSE b := 3; END_CASE;\nEND_PROGRAM\n",
        expect: &[("a", "20"), ("b", "2")],
    },
    Row {
        covers: &[
            "FOR",
            "TO",
            "BY",
            "DO",
            "END_FOR",
            "WHILE",
            "END_WHILE",
            "REPEAT",
            "UNTIL",
            "END_REPEAT",
            "EXIT",
            "CONTINUE",
            "Stmt::For",
            "Stmt::While",
            "Stmt::Repeat",
            "Stmt::Exit",
            "Stmt::Continue",
        ],
        source: "PROGRAM P\nVAR\n  i : INT; s : INT; w : INT; r : INT;\nEND_VAR\ns := 0; w := 0; r := 0;\n\
            FOR i := 1 TO 10 BY 1 DO\n  IF i = 2 THEN CONTINUE; END_IF;\n  IF i > 4 THEN EXIT; END_IF;\n  s := s + i;\nEND_FOR;\n\
            WHILE w < 5 DO w := w + 1; END_WHILE;\nREPEAT r := r + 2; UNTIL r >= 6 END_REPEAT;\nEND_PROGRAM\n",
        expect: &[("s", "8"), ("w", "5"), ("r", "6")],
    },
    Row {
        covers: &["Expr::Assign"],
        // Each cycle steps i in the condition; at 3 it starts again.
        source: "PROGRAM P\nVAR\n  i : INT; wraps : INT;\nEND_VAR\n\
            IF (i := i + 1) = 3 THEN i := 0; wraps := wraps + 1; END_IF\nEND_PROGRAM\n",
        expect: &[("i", "0"), ("wraps", "1")],
    },
    Row {
        covers: &["__TRY", "__CATCH", "__FINALLY", "__ENDTRY", "Stmt::Try"],
        source: "PROGRAM P\nVAR\n  e : __SYSTEM.ExceptionCode; d : INT; q : INT; f : INT;\nEND_VAR\n\
            __TRY q := 1 / d; q := 5; __CATCH(e) q := q + 7; __FINALLY f := f + 1; __ENDTRY\nEND_PROGRAM\n",
        expect: &[("q", "21"), ("f", "3"), ("e", "RTSEXCPT_DIVIDEBYZERO")],
    },
    Row {
        covers: &[
            "CONFIGURATION",
            "END_CONFIGURATION",
            "RESOURCE",
            "END_RESOURCE",
            "ON",
            "TASK",
            "WITH",
        ],
        source: "PROGRAM Count\nVAR\n  n : INT;\nEND_VAR\nn := n + 1;\nEND_PROGRAM\n\
            CONFIGURATION Cell\nRESOURCE Cpu ON PLC\nTASK Fast (INTERVAL := T#10ms, PRIORITY := 1);\nPROGRAM c1 WITH Fast : Count;\nEND_RESOURCE\nEND_CONFIGURATION\n",
        expect: &[("c1.n", "3")],
    },
    Row {
        covers: &[
            "INITIAL_STEP",
            "STEP",
            "END_STEP",
            "TRANSITION",
            "END_TRANSITION",
            "FROM",
            "ACTION",
            "END_ACTION",
        ],
        source: "PROGRAM P\nVAR\n  n : INT; go : BOOL := TRUE;\nEND_VAR\n\
            INITIAL_STEP Start:\nEND_STEP\nSTEP Work:\n  Inc(N);\nEND_STEP\n\
            TRANSITION FROM Start TO Work := go;\nEND_TRANSITION\n\
            ACTION Inc:\n  n := n + 1;\nEND_ACTION\nEND_PROGRAM\n",
        // The transition is cleared in the first cycle (docs/sfc.md): Work
        // is active, and its N action runs, in all three.
        expect: &[("n", "3")],
    },
    // Words other dialects use: each runs or is refused by name.
    Row {
        covers: &["R_EDGE", "F_EDGE"],
        // x toggles every cycle: TRUE, FALSE, TRUE: two rising edges, one falling.
        source: "FUNCTION_BLOCK E\nVAR_INPUT\n  r : BOOL R_EDGE;\n  f : BOOL F_EDGE;\nEND_VAR\nVAR_OUTPUT\n  nr : INT; nf : INT;\nEND_VAR\nIF r THEN nr := nr + 1; END_IF;\nIF f THEN nf := nf + 1; END_IF;\nEND_FUNCTION_BLOCK\n\
            PROGRAM P\nVAR\n  e : E; x : BOOL; a : INT; b : INT;\nEND_VAR\nx := NOT x;\ne(r := x, f := x);\na := e.nr;\nb := e.nf;\nEND_PROGRAM\n",
        expect: &[("a", "2"), ("b", "1")],
    },
    Row {
        covers: &["VAR_ACCESS"],
        source: "PROGRAM P\nVAR\n  x : INT;\nEND_VAR\nx := 1;\nEND_PROGRAM\nCONFIGURATION C\nRESOURCE R ON PLC\nPROGRAM p1 : P;\nEND_RESOURCE\nVAR_ACCESS\n  ax : p1.x : INT READ_WRITE;\nEND_VAR\nEND_CONFIGURATION\n",
        expect: &[],
    },
    Row {
        covers: &["VAR_CONFIG"],
        // VAR_CONFIG gives p1.x its initial value 5; three cycles add 3.
        source: "PROGRAM P\nVAR\n  x : INT;\nEND_VAR\nx := x + 1;\nEND_PROGRAM\nCONFIGURATION C\nRESOURCE R ON PLC\nPROGRAM p1 : P;\nEND_RESOURCE\nVAR_CONFIG\n  p1.x : INT := 5;\nEND_VAR\nEND_CONFIGURATION\n",
        expect: &[("p1.x", "8")],
    },
    Row {
        covers: &["METHOD", "END_METHOD"],
        source: "FUNCTION_BLOCK F\nVAR\n  n : INT;\nEND_VAR\nMETHOD Inc : INT\nn := n + 1;\nInc := n;\nEND_METHOD\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR\n  f : F; v : INT;\nEND_VAR\nv := f.Inc();\nEND_PROGRAM\n",
        expect: &[("v", "3")],
    },
    Row {
        covers: &["VAR_INST"],
        // The method's VAR_INST n is kept between calls: three cycles count 3.
        source: "FUNCTION_BLOCK F\nMETHOD Inc : INT\nVAR_INST\n  n : INT;\nEND_VAR\nn := n + 1;\nInc := n;\nEND_METHOD\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR\n  f : F; v : INT;\nEND_VAR\nv := f.Inc();\nEND_PROGRAM\n",
        expect: &[("v", "3")],
    },
    Row {
        covers: &["VAR_STAT"],
        // One static for both instances: two calls a cycle, three cycles: 6.
        source: "FUNCTION_BLOCK F\nVAR_STAT\n  n : INT;\nEND_VAR\nMETHOD Inc : INT\nn := n + 1;\nInc := n;\nEND_METHOD\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR\n  a, b : F; v : INT;\nEND_VAR\na.Inc();\nv := b.Inc();\nEND_PROGRAM\n",
        expect: &[("v", "6")],
    },
    Row {
        covers: &["INTERFACE", "END_INTERFACE", "IMPLEMENTS"],
        // A call through the interface variable reaches F's method.
        source: "INTERFACE I\nMETHOD M : INT\nEND_METHOD\nEND_INTERFACE\nFUNCTION_BLOCK F IMPLEMENTS I\nVAR\n  n : INT;\nEND_VAR\nMETHOD M : INT\nn := n + 1;\nM := n;\nEND_METHOD\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR\n  f : F; itf : I; v : INT;\nEND_VAR\nitf := f;\nv := itf.M();\nEND_PROGRAM\n",
        expect: &[("v", "3")],
    },
    Row {
        covers: &[
            "PROPERTY",
            "END_PROPERTY",
            "GET",
            "END_GET",
            "SET",
            "END_SET",
        ],
        // SET stores twice the value written, GET reads it back halved plus one.
        source: "FUNCTION_BLOCK F\nVAR\n  n : INT;\nEND_VAR\nPROPERTY Value : INT\nGET\nValue := n / 2 + 1;\nEND_GET\nSET\nn := Value * 2;\nEND_SET\nEND_PROPERTY\nEND_FUNCTION_BLOCK\nPROGRAM P\nVAR\n  f : F; v : INT;\nEND_VAR\nf.Value := 20;\nv := f.Value;\nEND_PROGRAM\n",
        expect: &[("v", "21"), ("f.n", "40")],
    },
    Row {
        covers: &["CLASS", "END_CLASS"],
        source: "CLASS C\nVAR\n  n : INT;\nEND_VAR\nMETHOD Inc : INT\nn := n + 1;\nInc := n;\nEND_METHOD\nEND_CLASS\nPROGRAM P\nVAR\n  c : C; x : INT;\nEND_VAR\nx := c.Inc();\nEND_PROGRAM\n",
        expect: &[("x", "3")],
    },
    Row {
        covers: &[
            "EXTENDS",
            "ABSTRACT",
            "FINAL",
            "PUBLIC",
            "PRIVATE",
            "PROTECTED",
            "INTERNAL",
            "SUPER^",
            "THIS^",
        ],
        // B's Bump adds 100 to A's (SUPER^); Get reads the inherited n
        // through THIS^ and adds the private Hidden (1) and protected Base (10).
        source: "FUNCTION_BLOCK ABSTRACT A\nVAR\n  n : INT;\nEND_VAR\nMETHOD PUBLIC Bump : INT\nn := n + 1;\nBump := n;\nEND_METHOD\nMETHOD PROTECTED Base : INT\nBase := 10;\nEND_METHOD\nEND_FUNCTION_BLOCK\n\
            FUNCTION_BLOCK FINAL B EXTENDS A\nMETHOD PUBLIC Bump : INT\nBump := SUPER^.Bump() + 100;\nEND_METHOD\nMETHOD PRIVATE Hidden : INT\nHidden := 1;\nEND_METHOD\nMETHOD INTERNAL Get : INT\nGet := THIS^.n + Hidden() + Base();\nEND_METHOD\nEND_FUNCTION_BLOCK\n\
            PROGRAM P\nVAR\n  b : B; v : INT; g : INT;\nEND_VAR\nv := b.Bump();\ng := b.Get();\nEND_PROGRAM\n",
        expect: &[("v", "103"), ("g", "14")],
    },
    Row {
        covers: &["POINTER", "REF_TO", "Expr::Deref", "Stmt::RefAssign"],
        // Each cycle adds 1 through r^ and 1 through rr: x is 6 after three;
        // y was read through p^ between the two (x = 5).
        source: "PROGRAM P\nVAR\n  x : INT;\n  p : POINTER TO INT;\n  r : REF_TO INT;\n  rr : REFERENCE TO INT;\n  y : INT;\nEND_VAR\nr := REF(x);\nr^ := r^ + 1;\np := ADR(x);\ny := p^ * 10;\nrr REF= x;\nrr := rr + 1;\nEND_PROGRAM\n",
        expect: &[("x", "6"), ("y", "50")],
    },
    Row {
        covers: &["NAMESPACE", "USING"],
        source: "NAMESPACE N\nFUNCTION F : INT\nF := 1;\nEND_FUNCTION\nEND_NAMESPACE\nUSING N;\nPROGRAM P\nVAR\n  x : INT;\nEND_VAR\nx := F();\nEND_PROGRAM\n",
        expect: &[],
    },
    Row {
        covers: &["OVERLAP"],
        source: "PROGRAM P\nVAR\n  x : INT;\nEND_VAR\nINITIAL_STEP S:\nEND_STEP\nSTEP T:\nEND_STEP\nTRANSITION FROM S TO T := TRUE;\nEND_TRANSITION\nTRANSITION FROM T TO S := TRUE;\nEND_TRANSITION\nEND_PROGRAM\n(* OVERLAP *)\nTYPE E : OVERLAP; END_TYPE\n",
        expect: &[],
    },
];

/// Quoted words between `start` and the next `end` in `text`.
fn quoted_after(text: &str, start: &str, end: &str) -> Vec<String> {
    let Some(from) = text.find(start) else {
        return Vec::new();
    };
    let rest = &text[from..];
    let block = &rest[..rest.find(end).unwrap_or(rest.len())];
    block
        .split('"')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// Variant names of `pub enum name` in `text`, prefixed `prefix::`.
fn variants(text: &str, name: &str, prefix: &str) -> Vec<String> {
    let Some(from) = text.find(&format!("pub enum {name} {{")) else {
        return Vec::new();
    };
    let body = &text[from..];
    let body = &body[..body.find("\n}").unwrap_or(body.len())];
    body.lines()
        .skip(1)
        .filter(|l| l.starts_with("    ") && !l.starts_with("     "))
        .filter_map(|l| {
            let word: String = l
                .trim()
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric())
                .collect();
            word.chars()
                .next()
                .is_some_and(|c| c.is_ascii_uppercase())
                .then(|| format!("{prefix}::{word}"))
        })
        .collect()
}

/// Every construct the sources define.
fn constructs() -> Vec<String> {
    let grammar = include_str!("../grammars/plc.lalrpop");
    let parser = include_str!("../src/syntax/parser.rs");
    let ast = include_str!("../src/syntax/ast.rs");
    let mut all: Vec<String> = grammar
        .lines()
        .filter(|l| l.contains("=> Tok::Kw("))
        .filter_map(|l| l.split('"').nth(1).map(str::to_string))
        .collect();
    all.extend(quoted_after(parser, "const UNSUPPORTED", "];"));
    all.extend(variants(ast, "StmtKind", "Stmt"));
    all.extend(variants(ast, "ExprKind", "Expr"));
    all.sort();
    all.dedup();
    all
}

#[test]
fn every_construct_has_a_row() {
    let all = constructs();
    assert!(all.len() > 80, "the enumeration found too little: {all:?}");
    let missing: Vec<&String> = all
        .iter()
        .filter(|c| !ROWS.iter().any(|r| r.covers.contains(&c.as_str())))
        .collect();
    assert!(
        missing.is_empty(),
        "constructs without a row in tests/constructs_enumerated.rs: {missing:?}"
    );
}

#[test]
fn every_construct_runs_or_is_refused_by_name() {
    for row in ROWS {
        match Plc::compile_files(&[("test.st", row.source)], &Options::default()) {
            Ok(mut plc) => {
                plc::run(&mut plc, 3);
                for (var, want) in row.expect {
                    assert_eq!(
                        plc::lit(&plc, var),
                        *want,
                        "{var} after three cycles, in the program for {:?}",
                        row.covers
                    );
                }
            }
            Err(e) => {
                let errors: Vec<String> = e
                    .diagnostics
                    .iter()
                    .filter(|d| d.severity == Severity::Error)
                    .map(|d| format!("[{}] {}", d.code, d.message))
                    .collect();
                // Refused: fine, if an error names a construct of the row
                // that this program is about (and not something else).
                let named = row.covers.iter().any(|c| {
                    errors
                        .iter()
                        .any(|m| m.to_ascii_uppercase().contains(&format!("`{c}`")))
                });
                assert!(
                    named && row.expect.is_empty(),
                    "the program for {:?} is refused without naming them: {errors:#?}",
                    row.covers
                );
            }
        }
    }
}

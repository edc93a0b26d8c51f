//! RETAIN and PERSISTENT through the library: what is retained (program
//! variables, globals, FB types, arrays, structures, strings, native FB
//! internals), save and restore round trips of every elementary type, the
//! fingerprint check and its message, partial restores, damaged files,
//! the background saver and the warm reset.

use plcrun::{Damage, Options, Plc, RestoreMode, RetainError, RetainSaver, Value};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

fn compile(src: &str) -> Plc {
    match Plc::compile_files(&[("t.st", src)], &Options::default()) {
        Ok(plc) => plc,
        Err(e) => panic!("{e}"),
    }
}

/// A fresh path in a directory of its own.
fn temp_path(name: &str) -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("plcrun-retain-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn names(plc: &Plc) -> Vec<String> {
    plc.retained().into_iter().map(|r| r.name).collect()
}

const ALL_TYPES: &str = "
TYPE Color : (Red, Green, Blue); END_TYPE
TYPE Pct : INT(0..100); END_TYPE
PROGRAM P
VAR RETAIN
  b : BOOL; si : SINT; i : INT; di : DINT; li : LINT;
  usi : USINT; ui : UINT; udi : UDINT; uli : ULINT;
  bt : BYTE; w : WORD; dw : DWORD; lw : LWORD;
  r : REAL; lr : LREAL; t : TIME; lt : LTIME;
  d : DATE; ld : LDATE; tod1 : TOD; ltod1 : LTOD; dt1 : DT; ldt1 : LDT;
  s : STRING[12]; ws : WSTRING[6]; c : Color; p : Pct;
END_VAR
END_PROGRAM
";

const VALUES: &[(&str, &str)] = &[
    ("b", "TRUE"),
    ("si", "-128"),
    ("i", "-32768"),
    ("di", "2147483647"),
    ("li", "-9223372036854775808"),
    ("usi", "255"),
    ("ui", "65535"),
    ("udi", "4294967295"),
    ("uli", "18446744073709551615"),
    ("bt", "16#A5"),
    ("w", "16#BEEF"),
    ("dw", "16#DEADBEEF"),
    ("lw", "16#0123456789ABCDEF"),
    ("r", "-1.5E-7"),
    ("lr", "3.141592653589793"),
    ("t", "T#1d2h3m4s5ms"),
    ("lt", "LTIME#-1s500ms"),
    ("d", "D#2024-02-29"),
    ("ld", "LDATE#1970-01-01"),
    ("tod1", "TOD#23:59:59.999"),
    ("ltod1", "LTOD#12:00:00.000000001"),
    ("dt1", "DT#2001-09-09-01:46:40"),
    ("ldt1", "LDT#2262-04-11-23:47:16.854775807"),
    ("s", "'it$'s $N ok'"),
    ("ws", "\"\u{e9}t\u{e9} $\"\""),
    ("c", "Blue"),
    ("p", "99"),
];

#[test]
fn every_elementary_type_survives_a_save_and_restore() {
    let mut plc = compile(ALL_TYPES);
    for (name, literal) in VALUES {
        plc.write(name, literal)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    let expected: Vec<Value> = VALUES.iter().map(|(n, _)| plc.read(n).unwrap()).collect();
    let path = temp_path("all.json");
    plc.save_retain(&path).unwrap();

    let mut fresh = compile(ALL_TYPES);
    assert_ne!(fresh.read("di").unwrap(), expected[3]);
    let report = fresh.restore_retain(&path, RestoreMode::Exact).unwrap();
    assert_eq!(report.restored, VALUES.len());
    assert!(report.differences.is_empty());
    for ((name, _), want) in VALUES.iter().zip(&expected) {
        assert_eq!(&fresh.read(name).unwrap(), want, "{name}");
    }
    // The file is readable JSON with IEC literals.
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains(r#"{"name":"P.w","type":"WORD","value":"16#BEEF"}"#),
        "{text}"
    );
    assert!(
        text.contains(r#"{"name":"P.s","type":"STRING[12]","value":"'it$'s $N ok'"}"#),
        "{text}"
    );
    assert!(
        text.contains(r#""type":"ENUM(Red,Green,Blue)","value":"Blue""#),
        "{text}"
    );
    assert!(
        text.contains(r#""type":"INT(0..100)","value":"99""#),
        "{text}"
    );
}

#[test]
fn arrays_structures_globals_and_located_variables_are_retained_whole() {
    let src = "
TYPE Pt : STRUCT x : INT; tag : STRING[4]; END_STRUCT END_TYPE
VAR_GLOBAL RETAIN g_total : LINT; g_grid : ARRAY[1..2, 0..1] OF BOOL; END_VAR
VAR_GLOBAL g_plain : INT; END_VAR
PROGRAM P
VAR RETAIN arr : ARRAY[1..3] OF INT; pts : ARRAY[0..1] OF Pt; m AT %MW4 : UINT; END_VAR
VAR plain : INT; END_VAR
arr[2] := arr[2] + 1; pts[1].tag := 'ab'; g_total := g_total + 10; g_grid[2, 1] := TRUE;
m := m + 16; plain := plain + 1;
END_PROGRAM";
    let mut plc = compile(src);
    assert_eq!(
        names(&plc),
        [
            "g_total",
            "g_grid[1,0]",
            "g_grid[1,1]",
            "g_grid[2,0]",
            "g_grid[2,1]",
            "m",
            "P.arr[1]",
            "P.arr[2]",
            "P.arr[3]",
            "P.pts[0].x",
            "P.pts[0].tag",
            "P.pts[1].x",
            "P.pts[1].tag",
        ]
    );
    for _ in 0..3 {
        plc.run_cycle().unwrap();
    }
    let path = temp_path("whole.json");
    plc.save_retain(&path).unwrap();
    let mut fresh = compile(src);
    fresh.restore_retain(&path, RestoreMode::Exact).unwrap();
    fresh.run_cycle().unwrap();
    assert_eq!(fresh.read_i64("arr[2]").unwrap(), 4);
    assert_eq!(fresh.read("pts[1].tag").unwrap().as_str(), Some("ab"));
    assert_eq!(fresh.read_i64("g_total").unwrap(), 40);
    assert_eq!(fresh.read("g_grid[2,1]").unwrap().as_bool(), Some(true));
    assert_eq!(fresh.read_i64("%MW4").unwrap(), 64);
    assert_eq!(fresh.read_i64("plain").unwrap(), 1);
}

const FB_SRC: &str = "
FUNCTION_BLOCK Acc
VAR_INPUT add : DINT; END_VAR
VAR RETAIN total : DINT; END_VAR
VAR scratch : DINT; c : CTU; t : TON; END_VAR
VAR NON_RETAIN never : DINT; END_VAR
total := total + add; scratch := scratch + 1; never := never + 1;
c(CU := NOT c.CU, PV := 1000);
t(IN := TRUE, PT := T#1s);
END_FUNCTION_BLOCK
PROGRAM P
VAR RETAIN kept : Acc; END_VAR
VAR loose : Acc; END_VAR
kept(add := 1); loose(add := 2);
END_PROGRAM";

#[test]
fn fb_instances_keep_their_internals_and_fb_types_retain_their_retain_variables() {
    let mut plc = compile(FB_SRC);
    let listed = names(&plc);
    // The whole retained instance, native blocks' hidden state included,
    // but not what its type declares NON_RETAIN.
    for n in [
        "P.kept.add",
        "P.kept.total",
        "P.kept.scratch",
        "P.kept.c.CV",
        "P.kept.t.START",
    ] {
        assert!(listed.iter().any(|l| l == n), "{n} in {listed:?}");
    }
    assert!(!listed.iter().any(|l| l == "P.kept.never"), "{listed:?}");
    // An instance declared without RETAIN keeps only its type's RETAIN variables.
    let loose: Vec<&String> = listed.iter().filter(|l| l.starts_with("P.loose")).collect();
    assert_eq!(loose, ["P.loose.total"]);

    for _ in 0..30 {
        plc.run_cycle().unwrap();
    }
    assert_eq!(plc.read("kept.t.ET").unwrap().to_literal(), "T#290ms");
    let path = temp_path("fb.json");
    plc.save_retain(&path).unwrap();

    let mut fresh = compile(FB_SRC);
    fresh.restore_retain(&path, RestoreMode::Exact).unwrap();
    assert_eq!(fresh.read_i64("kept.c.CV").unwrap(), 15);
    fresh.run_cycle().unwrap();
    assert_eq!(fresh.read_i64("kept.total").unwrap(), 31);
    assert_eq!(fresh.read_i64("kept.c.CV").unwrap(), 16);
    assert_eq!(fresh.read_i64("loose.total").unwrap(), 62);
    // The timer goes on from its elapsed time although the clock restarted at 0.
    assert_eq!(fresh.read("kept.t.ET").unwrap().to_literal(), "T#300ms");
    // Not retained: start again.
    assert_eq!(fresh.read_i64("loose.c.CV").unwrap(), 1);
}

#[test]
fn persistent_variables_are_retained_and_marked() {
    let src = "
VAR_GLOBAL PERSISTENT RETAIN g1 : INT; END_VAR
VAR_GLOBAL RETAIN PERSISTENT g2 : INT; END_VAR
PROGRAM P
VAR PERSISTENT p : DINT; END_VAR
VAR RETAIN r : DINT; END_VAR
p := p + 1; r := r + 2; g1 := g1 + 3; g2 := g2 + 4;
END_PROGRAM";
    let mut plc = compile(src);
    let flags: Vec<(String, bool)> = plc
        .retained()
        .into_iter()
        .map(|r| (r.name, r.persistent))
        .collect();
    let want = [("g1", true), ("g2", true), ("P.p", true), ("P.r", false)];
    let want: Vec<(String, bool)> = want.iter().map(|(n, p)| (n.to_string(), *p)).collect();
    assert_eq!(flags, want);
    plc.run_cycle().unwrap();
    let path = temp_path("persistent.json");
    plc.save_retain(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains(r#"{"name":"P.p","type":"DINT","value":"1","persistent":true}"#),
        "{text}"
    );
    let mut fresh = compile(src);
    fresh.restore_retain(&path, RestoreMode::Exact).unwrap();
    fresh.run_cycle().unwrap();
    assert_eq!(fresh.read_i64("p").unwrap(), 2);
    assert_eq!(fresh.read_i64("g2").unwrap(), 8);
}

const V1: &str = "PROGRAM P VAR RETAIN a : INT; b : INT; old : BOOL; END_VAR
a := a + 1; b := b + 2; END_PROGRAM";
const V2: &str = "PROGRAM P VAR RETAIN a : INT; b : DINT; fresh : TIME; END_VAR
a := a + 1; END_PROGRAM";

#[test]
fn a_file_of_another_program_version_is_refused_with_what_differs() {
    let mut v1 = compile(V1);
    v1.run_cycle().unwrap();
    let path = temp_path("v1.json");
    v1.save_retain(&path).unwrap();

    let mut v2 = compile(V2);
    let err = v2.restore_retain(&path, RestoreMode::Exact).unwrap_err();
    let RetainError::Mismatch {
        differences,
        fitting,
        ..
    } = &err
    else {
        panic!("{err:?}");
    };
    assert_eq!(differences.not_in_file, ["P.fresh"]);
    assert_eq!(differences.not_in_program, ["P.old"]);
    assert_eq!(differences.changed_type.len(), 1);
    assert_eq!(*fitting, 1);
    let msg = err.to_string();
    assert!(msg.contains("does not fit this program"), "{msg}");
    assert!(msg.contains("not in the file: P.fresh"), "{msg}");
    assert!(
        msg.contains("no longer retained by the program: P.old"),
        "{msg}"
    );
    assert!(
        msg.contains("changed type: P.b (file INT, program DINT)"),
        "{msg}"
    );
    // Nothing was restored.
    assert_eq!(v2.read_i64("a").unwrap(), 0);

    let report = v2.restore_retain(&path, RestoreMode::Partial).unwrap();
    assert_eq!(report.restored, 1);
    assert_eq!(&report.differences, differences);
    assert_eq!(v2.read_i64("a").unwrap(), 1);
    assert_eq!(v2.read_i64("b").unwrap(), 0);
}

#[test]
fn a_missing_file_is_told_apart_and_damaged_files_say_what_is_wrong() {
    let mut plc = compile(V1);
    let missing = plc.restore_retain(temp_path("none.json"), RestoreMode::Exact);
    assert!(missing.unwrap_err().is_missing_file());

    plc.run_cycle().unwrap();
    let path = temp_path("good.json");
    plc.save_retain(&path).unwrap();
    let good = std::fs::read_to_string(&path).unwrap();

    let damaged = |text: &str| {
        let p = temp_path("bad.json");
        std::fs::write(&p, text).unwrap();
        match compile(V1).restore_retain(&p, RestoreMode::Partial) {
            Err(RetainError::Damaged { damage, .. }) => damage,
            other => panic!("{other:?}"),
        }
    };
    assert!(matches!(
        damaged(&good[..good.len() / 2]),
        Damage::Json { .. }
    ));
    assert!(matches!(damaged(""), Damage::Json { line: 1, .. }));
    assert!(matches!(
        damaged(&good.replace("\"P.old\"", "\"P.older\"")),
        Damage::Fingerprint
    ));
    assert!(matches!(
        damaged(&good.replace("plcrun-retain", "other")),
        Damage::NotRetainData { .. }
    ));
    assert!(matches!(
        damaged(&good.replace("\"version\": 1", "\"version\": 7")),
        Damage::Version { version: 7 }
    ));
    let bad_value = damaged(&good.replace(r#""value":"2""#, r#""value":"two""#));
    assert!(
        matches!(&bad_value, Damage::BadValue { name, .. } if name == "P.b"),
        "{bad_value:?}"
    );
    let p = temp_path("bad.json");
    std::fs::write(&p, "{").unwrap();
    let msg = compile(V1)
        .restore_retain(&p, RestoreMode::Exact)
        .unwrap_err()
        .to_string();
    assert!(
        msg.starts_with(&format!("retain file `{}` line 1 column", p.display())),
        "{msg}"
    );
}

#[test]
fn the_background_saver_writes_the_newest_snapshot_and_refuses_another_plc() {
    let src = "PROGRAM P VAR RETAIN n : DINT; s : STRING[30]; END_VAR
               n := n + 1; s := CONCAT('n=', DINT_TO_STRING(n)); END_PROGRAM";
    let mut plc = compile(src);
    let path = temp_path("saver.json");
    let saver = RetainSaver::new(&plc, &path).unwrap();
    for _ in 0..500 {
        plc.run_cycle().unwrap();
        saver.offer(&plc).unwrap();
    }
    assert!(matches!(
        saver.offer(&compile(src)),
        Err(RetainError::ForeignPlc)
    ));
    saver.flush();
    let written = saver.saves();
    assert!(written >= 1);
    assert_eq!(written + saver.replaced(), 500);
    saver.finish().unwrap();
    let mut fresh = compile(src);
    fresh.restore_retain(&path, RestoreMode::Exact).unwrap();
    assert_eq!(fresh.read_i64("n").unwrap(), 500);
    assert_eq!(fresh.read("s").unwrap().as_str(), Some("n=500"));
}

#[test]
fn a_save_into_a_missing_directory_is_an_error_naming_the_file() {
    let plc = compile(V1);
    let path = temp_path("x").join("no/such/dir/r.json");
    let err = plc.save_retain(&path).unwrap_err();
    assert!(matches!(err, RetainError::Write { .. }));
    assert!(err.to_string().contains("no/such/dir/r.json"), "{err}");
    let saver = RetainSaver::new(&plc, &path).unwrap();
    saver.offer(&plc).unwrap();
    assert!(matches!(saver.finish(), Err(RetainError::Write { .. })));
}

#[test]
fn warm_reset_keeps_retained_values_and_reinitialises_the_rest() {
    let src = "
FUNCTION_BLOCK Cnt VAR RETAIN n : INT; END_VAR VAR m : INT; END_VAR n := n + 1; m := m + 1;
END_FUNCTION_BLOCK
PROGRAM P
VAR RETAIN kept : INT; ks : STRING[8] := 'init'; c : CTU; END_VAR
VAR lost : INT := 7; ls : STRING[8] := 'init'; f : Cnt; d : CTU; END_VAR
kept := kept + 1; lost := lost + 1; ks := 'run'; ls := 'run';
f(); c(CU := NOT c.CU, PV := 100); d(CU := NOT d.CU, PV := 100);
END_PROGRAM";
    let mut plc = compile(src);
    for _ in 0..4 {
        plc.run_cycle().unwrap();
    }
    assert_eq!(plc.cycle(), 4);
    plc.reset_warm();
    assert_eq!(
        plc.cycle(),
        0,
        "the cycle count restarts, as after a cold reset"
    );
    assert_eq!(plc.read_i64("kept").unwrap(), 4);
    assert_eq!(plc.read("ks").unwrap().as_str(), Some("run"));
    assert_eq!(plc.read_i64("c.CV").unwrap(), 2);
    assert_eq!(plc.read_i64("f.n").unwrap(), 4);
    assert_eq!(plc.read_i64("lost").unwrap(), 7);
    assert_eq!(plc.read("ls").unwrap().as_str(), Some("init"));
    assert_eq!(plc.read_i64("f.m").unwrap(), 0);
    assert_eq!(plc.read_i64("d.CV").unwrap(), 0);
    plc.run_cycle().unwrap();
    assert_eq!(plc.read_i64("kept").unwrap(), 5);
    assert_eq!(plc.read_i64("lost").unwrap(), 8);
}

#[test]
fn a_program_without_retain_saves_an_empty_list() {
    let mut plc = compile("PROGRAM P VAR x : INT; END_VAR x := x + 1; END_PROGRAM");
    assert!(plc.retained().is_empty());
    let path = temp_path("empty.json");
    plc.save_retain(&path).unwrap();
    let report = plc.restore_retain(&path, RestoreMode::Exact).unwrap();
    assert_eq!(report.restored, 0);
}

#[test]
fn output_and_input_blocks_can_be_retained_too() {
    let src = "
FUNCTION_BLOCK F
VAR_INPUT RETAIN setpoint : REAL; END_VAR
VAR_OUTPUT RETAIN hours : UDINT; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
hours := hours + 1;
END_FUNCTION_BLOCK
PROGRAM P
VAR_OUTPUT RETAIN o : INT; END_VAR
VAR f : F; END_VAR
o := o + 1; f(setpoint := 2.5);
END_PROGRAM";
    let mut plc = compile(src);
    assert_eq!(names(&plc), ["P.o", "P.f.setpoint", "P.f.hours"]);
    plc.run_cycle().unwrap();
    let path = temp_path("io.json");
    plc.save_retain(&path).unwrap();
    let mut fresh = compile(src);
    fresh.restore_retain(&path, RestoreMode::Exact).unwrap();
    assert_eq!(fresh.read_i64("o").unwrap(), 1);
    assert_eq!(fresh.read_i64("f.hours").unwrap(), 1);
    assert_eq!(fresh.read("f.setpoint").unwrap().as_f64(), Some(2.5));
}

//! VCD traces read back by an independent VCD parser (the `vcd` crate) and
//! compared, value by value and cycle by cycle, with the CSV trace of the
//! same run.

use crate::support::cli;
use crate::support::library;

use cli::{plcrun, plcrun_ok, temp_file};
use library::{repo_files, repo_text};
use plcrun::{
    Options, Plc, Session, TraceFormat, TraceWriter, VcdTimescale, parse_stimulus,
    parse_time_literal,
};
use std::collections::HashMap;

/// Every elementary type the trace shows, an enumeration, a string, an
/// array element and FB instances nested two deep.
const KINDS: &str = "
TYPE Color : (Red, Green := 5, Blue); END_TYPE
FUNCTION_BLOCK Inner
VAR_OUTPUT Q : BOOL; n : INT; END_VAR
VAR t : TON; END_VAR
t(IN := TRUE, PT := T#30ms);
Q := t.Q;
n := n - 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Outer
VAR_OUTPUT busy : BOOL; END_VAR
VAR inner : Inner; END_VAR
inner();
busy := NOT inner.Q;
END_FUNCTION_BLOCK
PROGRAM main
VAR_OUTPUT
  b : BOOL; si : SINT; i : INT; di : DINT; li : LINT;
  us : USINT; ui : UINT; udi : UDINT; uli : ULINT;
  bt : BYTE; w : WORD; dw : DWORD; lw : LWORD;
  r : REAL; lr : LREAL; tm : TIME; ltm : LTIME; c : Color; s : STRING;
  arr : ARRAY[1..2] OF INT;
END_VAR
VAR k : INT; outer : Outer; END_VAR
k := k + 1;
IF k MOD 3 = 0 THEN b := NOT b; END_IF;
si := si - 50; i := i - 3000; di := di * 3 - 7; li := li - 1000000000000;
us := us + 100; ui := ui + 30000; udi := udi + 3000000000; uli := uli - 1;
bt := bt XOR 16#A5; w := ROL(w, 3) OR 1; dw := NOT dw; lw := ROR(lw, 1) XOR 16#8000000000000001;
r := r + 0.1; lr := lr - 1.0E300; tm := tm - T#1ms; ltm := ltm + LT#1h;
IF k MOD 2 = 0 THEN c := Green; ELSIF k MOD 5 = 0 THEN c := Red; ELSE c := Blue; END_IF;
IF k MOD 4 = 2 THEN s := 'a b, \"c\"'; ELSIF k MOD 4 = 3 THEN s := ''; ELSE s := 'x'; END_IF;
IF k > 6 THEN arr[2] := k; END_IF;
outer();
END_PROGRAM
";

const KINDS_TRACE: &str = "b,si,i,di,li,us,ui,udi,uli,bt,w,dw,lw,r,lr,tm,ltm,c,s,arr[2],\
                           outer.busy,outer.inner.Q,outer.inner.n,outer.inner.t.ET";

/// One VCD variable: its path (scopes and name joined by dots), type and
/// width.
#[derive(Debug, Clone)]
struct Signal {
    path: String,
    var_type: vcd::VarType,
    width: u32,
}

/// A value as the VCD file holds it, decoded by the test.
#[derive(Debug, Clone, PartialEq)]
enum Wave {
    Bit(bool),
    Int(i128),
    Real(f64),
    Text(String),
}

/// A VCD file read back: the timescale in ns, the variables by path, and
/// for each timestamp (in ns) the value of every variable after it.
struct Waves {
    unit_ns: i64,
    signals: Vec<Signal>,
    /// `(time_ns, values by path)`, one per timestamp, in order.
    samples: Vec<(i64, HashMap<String, Wave>)>,
}

fn collect_vars(items: &[vcd::ScopeItem], prefix: &str, out: &mut Vec<(vcd::IdCode, Signal)>) {
    for item in items {
        match item {
            vcd::ScopeItem::Var(v) => out.push((
                v.code,
                Signal {
                    path: format!("{prefix}{}", v.reference),
                    var_type: v.var_type,
                    width: v.size,
                },
            )),
            vcd::ScopeItem::Scope(s) => {
                assert_eq!(s.scope_type, vcd::ScopeType::Module);
                collect_vars(&s.items, &format!("{prefix}{}.", s.identifier), out);
            }
            _ => {}
        }
    }
}

fn unescape(text: &str) -> String {
    if text == "\"\"" {
        return String::new();
    }
    let mut bytes = Vec::new();
    let raw = text.as_bytes();
    let mut i = 0;
    while i < raw.len() {
        if raw[i] == b'\\' && raw.get(i + 1) == Some(&b'x') {
            let hex = std::str::from_utf8(&raw[i + 2..i + 4]).unwrap();
            bytes.push(u8::from_str_radix(hex, 16).unwrap());
            i += 4;
        } else {
            bytes.push(raw[i]);
            i += 1;
        }
    }
    String::from_utf8(bytes).unwrap()
}

fn read_vcd(text: &str) -> Waves {
    let mut parser = vcd::Parser::new(text.as_bytes());
    let header = parser.parse_header().expect("a VCD header");
    assert!(header.date.is_none(), "no $date: the file is deterministic");
    let (count, unit) = header.timescale.expect("a $timescale");
    let unit_ns = i64::from(count)
        * match unit {
            vcd::TimescaleUnit::S => 1_000_000_000,
            vcd::TimescaleUnit::MS => 1_000_000,
            vcd::TimescaleUnit::US => 1_000,
            vcd::TimescaleUnit::NS => 1,
            other => panic!("unexpected unit {other:?}"),
        };
    let mut vars = Vec::new();
    collect_vars(&header.items, "", &mut vars);
    let by_code: HashMap<vcd::IdCode, Signal> = vars.iter().cloned().collect();
    let mut current: HashMap<String, Wave> = HashMap::new();
    let mut samples: Vec<(i64, HashMap<String, Wave>)> = Vec::new();
    let mut time: Option<i64> = None;
    for command in parser {
        let command = command.expect("a well-formed VCD command");
        let mut set = |code: vcd::IdCode, wave: Wave| {
            let signal = &by_code[&code];
            current.insert(signal.path.clone(), wave);
        };
        match command {
            vcd::Command::Timestamp(t) => {
                if let Some(t) = time {
                    samples.push((t, current.clone()));
                }
                time = Some(t as i64 * unit_ns);
            }
            vcd::Command::ChangeScalar(code, v) => set(code, Wave::Bit(v == vcd::Value::V1)),
            vcd::Command::ChangeVector(code, bits) => {
                let signal = by_code[&code].clone();
                let mut raw: u128 = 0;
                for bit in bits.iter() {
                    assert!(matches!(bit, vcd::Value::V0 | vcd::Value::V1), "{bit:?}");
                    raw = (raw << 1) | u128::from(bit == vcd::Value::V1);
                }
                let width = signal.width;
                assert!(
                    bits.len() as u32 <= width,
                    "{} wider than declared",
                    signal.path
                );
                let value = if signal.var_type == vcd::VarType::Integer
                    && raw >> (width - 1) & 1 == 1
                    && bits.len() as u32 == width
                {
                    raw as i128 - (1i128 << width)
                } else {
                    raw as i128
                };
                set(code, Wave::Int(value));
            }
            vcd::Command::ChangeReal(code, v) => set(code, Wave::Real(v)),
            vcd::Command::ChangeString(code, s) => set(code, Wave::Text(unescape(&s))),
            vcd::Command::Begin(_) | vcd::Command::End(_) => {}
            other => panic!("unexpected command {other:?}"),
        }
    }
    if let Some(t) = time {
        samples.push((t, current));
    }
    Waves {
        unit_ns,
        signals: vars.into_iter().map(|(_, s)| s).collect(),
        samples,
    }
}

/// The enumeration ordinals of the test programs.
fn ordinal(name: &str) -> i128 {
    match name {
        "Red" => 0,
        "Green" => 5,
        "Blue" => 6,
        _ => panic!("unknown enumeration value {name}"),
    }
}

/// Decodes an IEC string literal of the CSV (`'a b'`, `$$`, `$'`).
fn string_literal(text: &str) -> String {
    let inner = &text[1..text.len() - 1];
    inner.replace("$'", "'").replace("$$", "$")
}

/// Checks that the CSV cell `text` is the value `wave` of `signal`.
fn same(signal: &Signal, text: &str, wave: &Wave, context: &str) {
    let path = &signal.path;
    match wave {
        Wave::Bit(b) => assert_eq!(text, if *b { "TRUE" } else { "FALSE" }, "{context}"),
        Wave::Int(v) => {
            let expected: i128 = if let Some(hex) = text.strip_prefix("16#") {
                i128::from_str_radix(hex, 16).unwrap()
            } else if let Some(body) = text.strip_prefix("LT#") {
                i128::from(parse_time_literal(&format!("T#{body}")).unwrap())
            } else if text.starts_with("T#") {
                i128::from(parse_time_literal(text).unwrap())
            } else if let Ok(n) = text.parse::<i128>() {
                n
            } else {
                ordinal(text)
            };
            assert_eq!(*v, expected, "{context}: {path} = {text}");
        }
        Wave::Real(v) => {
            let expected = match text {
                "NaN" => f64::NAN,
                _ if signal.path.ends_with("lr") => text.parse::<f64>().unwrap(),
                // A REAL: the CSV's shortest text is the f32.
                _ => f64::from(text.parse::<f32>().unwrap()),
            };
            if signal.path.ends_with("lr") {
                assert_eq!(v.to_bits(), expected.to_bits(), "{context}: {path}");
            } else {
                assert_eq!(
                    (*v as f32).to_bits(),
                    (expected as f32).to_bits(),
                    "{context}"
                );
            }
        }
        Wave::Text(s) => assert_eq!(*s, string_literal(text), "{context}: {path}"),
    }
}

/// A run's two traces: CSV and VCD, each by its own session.
fn traces(
    files: &[(&str, &str)],
    stimulus: Option<&str>,
    trace: &[&str],
    cycles: u64,
    changes_only: bool,
) -> (String, String) {
    let run = |format: TraceFormat| {
        let plc = Plc::compile_files(files, &Options::default()).expect("compiles");
        let mut session = Session::new(plc);
        if let Some(text) = stimulus {
            session
                .bind_stimulus(parse_stimulus(text).unwrap())
                .unwrap();
        }
        session.set_trace(trace).unwrap();
        let names = session.trace_names().to_vec();
        let mut writer = if format == TraceFormat::Vcd {
            let timescale =
                VcdTimescale::for_cycle(session.plc().cycle_time(), session.plc().time());
            TraceWriter::vcd(
                Vec::new(),
                names,
                session.vcd_signals(),
                timescale,
                changes_only,
            )
        } else {
            TraceWriter::new(Vec::new(), format, names, changes_only)
        };
        session.run(cycles, &mut writer).unwrap();
        String::from_utf8(writer.finish().unwrap()).unwrap()
    };
    (run(TraceFormat::Csv), run(TraceFormat::Vcd))
}

/// Compares every value at every row of the CSV with the VCD's, and the
/// rows with the timestamps (one per CSV row).
fn compare(csv_text: &str, vcd_text: &str, cycle_ns: i64) -> usize {
    let waves = read_vcd(vcd_text);
    let mut reader = csv::Reader::from_reader(csv_text.as_bytes());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let names = &header[2..];
    let signal_of: HashMap<String, Signal> = waves
        .signals
        .iter()
        .map(|s| (s.path.clone(), s.clone()))
        .collect();
    assert_eq!(waves.signals.len(), names.len());
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), waves.samples.len(), "one timestamp per CSV row");
    let mut compared = 0;
    for (row, (time_ns, values)) in rows.iter().zip(&waves.samples) {
        let cycle: i64 = row[0].parse().unwrap();
        assert_eq!(*time_ns, cycle * cycle_ns, "timestamp of cycle {cycle}");
        assert_eq!(
            i128::from(parse_time_literal(&row[1]).unwrap()),
            i128::from(*time_ns)
        );
        assert_eq!(time_ns % waves.unit_ns, 0);
        for (name, text) in names.iter().zip(row.iter().skip(2)) {
            let path: String = name.chars().filter(|c| !c.is_whitespace()).collect();
            let signal = &signal_of[&path];
            let wave = values
                .get(&path)
                .unwrap_or_else(|| panic!("{path} has no value at cycle {cycle}"));
            same(signal, text, wave, &format!("cycle {cycle}"));
            compared += 1;
        }
    }
    compared
}

#[test]
fn every_type_at_every_cycle_matches_the_csv() {
    let trace: Vec<&str> = KINDS_TRACE.split(',').collect();
    let (csv, vcd) = traces(&[("kinds.st", KINDS)], None, &trace, 40, false);
    assert_eq!(compare(&csv, &vcd, 10_000_000), 40 * trace.len());
    assert!(vcd.contains("$timescale 10 ms $end"), "{vcd}");
    for declaration in [
        "$var wire 1 ! b $end",
        "$var integer 8 \" si $end",
        "$var integer 64 % li $end",
        "$var wire 64 ) uli $end",
        "$var wire 8 * bt $end",
        "$var real 64 . r $end",
        "$var integer 64 0 tm $end",
        "$var string 1 3 s $end",
        "$var integer 16 4 arr[2] $end",
    ] {
        assert!(vcd.contains(declaration), "{declaration} in\n{vcd}");
    }
    // outer.inner.t.ET → scope outer, scope inner, scope t, variable ET.
    assert!(
        vcd.contains(
            "$scope module outer $end\n  $var wire 1 5 busy $end\n  \
             $scope module inner $end\n    $var wire 1 6 Q $end\n    \
             $var integer 16 7 n $end\n    $scope module t $end\n      \
             $var integer 64 8 ET $end\n    $upscope $end\n  $upscope $end\n$upscope $end\n"
        ),
        "{vcd}"
    );
}

#[test]
fn changes_only_has_a_timestamp_per_changed_cycle() {
    let trace = ["b", "outer.inner.Q", "outer.busy"];
    let (csv, vcd) = traces(&[("kinds.st", KINDS)], None, &trace, 30, true);
    let rows = compare(&csv, &vcd, 10_000_000) / trace.len();
    assert!(rows < 30 && rows > 5, "{csv}");
}

#[test]
fn the_chariot_steps_are_wires() {
    let files = repo_files(&["programs/chariot.sfc"]);
    let files: Vec<(&str, &str)> = files
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    let stimulus = repo_text("programs/chariot.csv");
    let trace = [
        "Dcy", "FcA", "FcB", "KMAV", "KMAR", "VOM", "INIT.X", "AV.X", "ATT.X", "ATT.T", "AR.X",
    ];
    for changes_only in [false, true] {
        let (csv, vcd) = traces(&files, Some(&stimulus), &trace, 120, changes_only);
        assert!(compare(&csv, &vcd, 10_000_000) > 0);
        assert!(
            vcd.contains("$scope module AV $end\n  $var wire 1 ( X $end\n"),
            "{vcd}"
        );
    }
}

#[test]
fn the_same_run_gives_the_same_bytes() {
    let trace: Vec<&str> = KINDS_TRACE.split(',').collect();
    let (_, first) = traces(&[("kinds.st", KINDS)], None, &trace, 10, false);
    let (_, second) = traces(&[("kinds.st", KINDS)], None, &trace, 10, false);
    assert_eq!(first, second);
}

#[test]
fn the_command_line_writes_vcd_with_the_cycle_as_timescale() {
    let source = temp_file(
        "count.st",
        "PROGRAM count\nVAR_OUTPUT n : INT; q : BOOL; END_VAR\nn := n + 1; q := n MOD 2 = 0;\nEND_PROGRAM\n",
    );
    let vcd = plcrun_ok(&[
        &source,
        "--cycles",
        "4",
        "--cycle-time",
        "2500us",
        "--format",
        "vcd",
    ]);
    let waves = read_vcd(&vcd);
    assert_eq!(waves.unit_ns, 100_000);
    assert_eq!(
        vcd.split("$enddefinitions $end\n").nth(1),
        Some(
            "#0\n$dumpvars\nb1 !\n0\"\n$end\n#25\nb10 !\n1\"\n#50\nb11 !\n0\"\n#75\nb100 !\n1\"\n"
        )
    );
    let csv = plcrun_ok(&[&source, "--cycles", "4", "--cycle-time", "2500us"]);
    compare(&csv, &vcd, 2_500_000);
    let changes = plcrun_ok(&[
        &source,
        "--cycles",
        "4",
        "--format",
        "vcd",
        "--changes-only",
        "--trace",
        "n",
    ]);
    assert!(changes.ends_with("#3\nb100 !\n"), "{changes}");
}

#[test]
fn a_forced_value_is_written_as_its_value() {
    let source = temp_file(
        "forced.st",
        "PROGRAM p\nVAR_OUTPUT n : INT; END_VAR\nn := n + 1;\nEND_PROGRAM\n",
    );
    let vcd = plcrun_ok(&[
        &source, "--cycles", "2", "--format", "vcd", "--force", "n=7",
    ]);
    assert!(vcd.ends_with("#0\n$dumpvars\nb111 !\n$end\n#1\n"), "{vcd}");
}

#[test]
fn an_unknown_format_is_refused() {
    let source = temp_file(
        "unknown.st",
        "PROGRAM p\nVAR_OUTPUT n : INT; END_VAR\nEND_PROGRAM\n",
    );
    let (status, _, err) = plcrun(&[&source, "--cycles", "2", "--format", "fst"]);
    assert_ne!(status, 0);
    assert!(err.contains("vcd"), "{err}");
}

/// GTKWave's own reader, where it is installed (`apt-get install gtkwave`):
/// `vcd2fst` converts the file, which it only does for a file it reads.
#[test]
fn gtkwave_reads_it_when_installed() {
    let Ok(status) = std::process::Command::new("vcd2fst").arg("--help").output() else {
        eprintln!("vcd2fst not installed: GTKWave check not run");
        return;
    };
    assert!(status.status.success() || !status.stdout.is_empty() || !status.stderr.is_empty());
    let trace: Vec<&str> = KINDS_TRACE.split(',').collect();
    let (_, vcd) = traces(&[("kinds.st", KINDS)], None, &trace, 10, false);
    let input = temp_file("gtkwave.vcd", &vcd);
    let output = format!("{input}.fst");
    let converted = std::process::Command::new("vcd2fst")
        .args([&input, &output])
        .output()
        .expect("vcd2fst runs");
    assert!(converted.status.success(), "{converted:?}");
    let back = std::process::Command::new("fst2vcd")
        .arg(&output)
        .output()
        .expect("fst2vcd runs");
    let text = String::from_utf8_lossy(&back.stdout);
    assert!(text.contains("$var integer 64 8 ET $end"), "{text}");
    assert!(text.contains("$var string"), "{text}");
}

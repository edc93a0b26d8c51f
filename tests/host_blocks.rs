//! Host extension points: FUNCTIONs and FUNCTION_BLOCKs declared by the
//! host with an IEC interface and implemented in Rust, called from ST, IL
//! and SFC like standard ones.

use plcrun::{ElemType, FaultKind, HostBlocks, HostDeclError, HostSignature, Options, PinDir, Plc};
use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};

/// A ramp: each call while `run` adds `inc` to `value` (per instance).
fn ramp() -> HostSignature {
    HostSignature::block("Ramp")
        .input("run", ElemType::Bool)
        .input("inc", ElemType::Int)
        .output("value", ElemType::Int)
        .output("calls", ElemType::Dint)
}

/// `Scale(x, k) = x * k` on REAL.
fn scale() -> HostSignature {
    HostSignature::function("Scale", ElemType::Real)
        .input("x", ElemType::Real)
        .input("k", ElemType::Real)
}

fn hosts() -> HostBlocks {
    let mut hosts = HostBlocks::new();
    hosts
        .block(ramp(), || {
            // The instance's own state, kept by the closure.
            let (mut value, mut calls) = (0i64, 0i64);
            move |io| {
                calls += 1;
                if io.get_bool("run")? {
                    value += io.get_i64("inc")?;
                }
                io.set_i64("value", value)?;
                io.set_i64("calls", calls)?;
                Ok(())
            }
        })
        .unwrap();
    hosts
        .function(scale(), |io| {
            let v = io.get_f64("x")? * io.get_f64("k")?;
            io.set_f64("Scale", v)?;
            Ok(())
        })
        .unwrap();
    hosts
}

fn options(hosts: HostBlocks) -> Options {
    Options {
        hosts,
        ..Options::default()
    }
}

fn compile(src: &str, hosts: HostBlocks) -> Plc {
    Plc::compile_files(&[("p.st", src)], &options(hosts)).unwrap_or_else(|e| panic!("{e}"))
}

fn read(plc: &Plc, name: &str) -> String {
    plc.read(name).expect("readable").to_literal()
}

fn cycles(plc: &mut Plc, n: usize) {
    for _ in 0..n {
        plc.run_cycle().unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn a_host_block_keeps_state_per_instance_from_st() {
    let src = "
PROGRAM P
VAR a : Ramp; b : Ramp; go : BOOL := TRUE; y : REAL; END_VAR
a(run := go, inc := 2);
b(run := TRUE, inc := 5);
b(run := FALSE, inc := 5);
y := Scale(INT_TO_REAL(a.value), 0.5);
END_PROGRAM";
    let mut plc = compile(src, hosts());
    assert!(plc.warnings().is_empty(), "{:?}", plc.warnings());
    cycles(&mut plc, 3);
    assert_eq!(read(&plc, "P.a.value"), "6");
    assert_eq!(read(&plc, "P.a.calls"), "3");
    assert_eq!(read(&plc, "P.b.value"), "15");
    assert_eq!(read(&plc, "P.b.calls"), "6");
    assert_eq!(read(&plc, "P.y"), "3.0");
    plc.write("P.go", "FALSE").unwrap();
    cycles(&mut plc, 1);
    assert_eq!(read(&plc, "P.a.value"), "6");
}

#[test]
fn a_host_block_and_function_are_called_from_il() {
    let src = "
PROGRAM P
VAR r : Ramp; v : INT; y : REAL; END_VAR
    CAL r(run := TRUE, inc := 3)
    LD r.value
    ST v
    LD 1.5
    Scale 4.0
    ST y
END_PROGRAM";
    let mut plc = compile(src, hosts());
    cycles(&mut plc, 2);
    assert_eq!(read(&plc, "P.v"), "6");
    assert_eq!(read(&plc, "P.y"), "6.0");
}

#[test]
fn a_host_block_runs_in_an_sfc_action() {
    let src = "
PROGRAM P
VAR go : BOOL; r : Ramp; END_VAR
INITIAL_STEP S0 : END_STEP
STEP S1 : Tick(N); END_STEP
ACTION Tick:
  r(run := TRUE, inc := 1);
END_ACTION
TRANSITION FROM S0 TO S1 := go; END_TRANSITION
TRANSITION FROM S1 TO S0 := NOT go; END_TRANSITION
END_PROGRAM";
    let mut plc = compile(src, hosts());
    cycles(&mut plc, 2);
    assert_eq!(read(&plc, "P.r.value"), "0");
    plc.write("P.go", "TRUE").unwrap();
    cycles(&mut plc, 4);
    // S1 active from the call after go rose; Tick runs each call after.
    let v: i64 = plc.read_i64("P.r.value").unwrap();
    assert!((3..=4).contains(&v), "{v}");
}

#[test]
fn calls_are_type_checked_like_calls_to_iec_pous() {
    let cases = [
        // A BOOL where an INT input is declared.
        "a(run := TRUE, inc := TRUE);",
        // A STRING argument to a REAL input of the function.
        "y := Scale('x', 1.0);",
        // A pin the block does not have.
        "a(run := TRUE, speed := 1);",
        // Writing an output pin from outside.
        "a.value := 1;",
        // The function's result assigned to a BOOL.
        "ok := Scale(1.0, 2.0);",
    ];
    for body in cases {
        let src =
            format!("PROGRAM P VAR a : Ramp; y : REAL; ok : BOOL; END_VAR {body} END_PROGRAM");
        let err = Plc::compile_files(&[("p.st", &src)], &options(hosts()))
            .err()
            .unwrap_or_else(|| panic!("`{body}` compiled"));
        let codes: Vec<&str> = err.diagnostics.iter().map(|d| d.code).collect();
        assert!(
            codes.iter().all(|c| c.starts_with('E') && c.len() == 4),
            "{body}: {codes:?}"
        );
        // The error points into the user's file, not into the host's.
        let first = err.diagnostics.iter().next().unwrap();
        assert!(
            err.sources.location(first.span).starts_with("p.st"),
            "{body}: {err}"
        );
    }
    // Without the registration the names are unknown.
    let src = "PROGRAM P VAR a : Ramp; END_VAR END_PROGRAM";
    assert!(Plc::compile_files(&[("p.st", src)], &Options::default()).is_err());
}

#[test]
fn a_panicking_host_function_becomes_a_runtime_fault() {
    let mut hosts = HostBlocks::new();
    hosts
        .function(
            HostSignature::function("Risky", ElemType::Int).input("x", ElemType::Int),
            |io| {
                let x = io.get_i64("x")?;
                if x > 2 {
                    panic!("x is {x}, too big");
                }
                io.set_i64("Risky", x * 10)?;
                Ok(())
            },
        )
        .unwrap();
    let src = "PROGRAM P VAR n : INT; r : INT; END_VAR n := n + 1; r := Risky(n); END_PROGRAM";
    let mut plc = compile(src, hosts);
    cycles(&mut plc, 2);
    assert_eq!(read(&plc, "P.r"), "20");
    let fault = plc.run_cycle().expect_err("the host function panics");
    match &fault.fault.kind {
        FaultKind::HostFunction(h) => {
            assert_eq!(h.name, "Risky");
            assert!(h.message.contains("x is 3, too big"), "{}", h.message);
        }
        other => panic!("unexpected fault {other:?}"),
    }
    assert_eq!(fault.cycle, 2);
    assert!(
        fault.to_string().contains("host function `Risky` failed"),
        "{fault}"
    );
    // The PLC's memory is intact and readable after the fault.
    assert_eq!(read(&plc, "P.n"), "3");
    assert_eq!(read(&plc, "P.r"), "20");
}

#[test]
fn a_host_error_and_a_bad_pin_access_are_runtime_faults() {
    let mut hosts = HostBlocks::new();
    hosts
        .block(
            HostSignature::block("Bad").output("q", ElemType::Int),
            || {
                |io: &mut plcrun::HostIo<'_>| {
                    io.set_i64("q", 100_000)?; // does not fit INT
                    Ok(())
                }
            },
        )
        .unwrap();
    let src = "PROGRAM P VAR b : Bad; END_VAR b(); END_PROGRAM";
    let mut plc = compile(src, hosts);
    let fault = plc.run_cycle().expect_err("out of range");
    match &fault.fault.kind {
        FaultKind::HostFunction(h) => {
            assert_eq!(h.name, "Bad");
            assert!(
                h.message.contains("100000 does not fit pin `q`"),
                "{}",
                h.message
            );
        }
        other => panic!("unexpected fault {other:?}"),
    }
}

#[test]
fn a_host_function_is_shared_by_every_call() {
    let count = Arc::new(AtomicU32::new(0));
    let seen = count.clone();
    let mut hosts = HostBlocks::new();
    hosts
        .function(
            HostSignature::function("Tick", ElemType::Udint),
            move |io| {
                let n = seen.fetch_add(1, Ordering::Relaxed) + 1;
                io.set_i64("Tick", n.into())?;
                Ok(())
            },
        )
        .unwrap();
    let src = "PROGRAM P VAR a, b : UDINT; END_VAR a := Tick(); b := Tick(); END_PROGRAM";
    let mut plc = compile(src, hosts);
    cycles(&mut plc, 3);
    assert_eq!(count.load(Ordering::Relaxed), 6);
    assert_eq!(read(&plc, "P.b"), "6");
}

#[test]
fn bad_declarations_are_refused_at_registration() {
    let mut hosts = HostBlocks::new();
    let ok = |_: &mut plcrun::HostIo<'_>| -> plcrun::HostResult { Ok(()) };
    assert!(matches!(
        hosts.function(HostSignature::function("1x", ElemType::Int), ok),
        Err(HostDeclError::BadName { .. })
    ));
    let twice = HostSignature::block("B")
        .input("a", ElemType::Int)
        .output("A", ElemType::Int);
    assert!(matches!(
        hosts.block(twice, move || ok),
        Err(HostDeclError::DuplicatePin { .. })
    ));
    let with_output = HostSignature::function("F", ElemType::Int).output("q", ElemType::Int);
    assert!(matches!(
        hosts.function(with_output, ok),
        Err(HostDeclError::FunctionOutput { .. })
    ));
    hosts.block(HostSignature::block("B"), move || ok).unwrap();
    let err = hosts
        .function(HostSignature::function("b", ElemType::Int), ok)
        .expect_err("a second `B`");
    assert_eq!(err, HostDeclError::DuplicatePou { name: "b".into() });
    assert!(err.to_string().contains("registered twice"));
    assert_eq!(hosts.signatures().count(), 1);
}

#[test]
fn a_host_pou_named_like_a_user_pou_is_a_compile_error() {
    let src =
        "FUNCTION_BLOCK Ramp END_FUNCTION_BLOCK PROGRAM P VAR r : Ramp; END_VAR r(); END_PROGRAM";
    let err = Plc::compile_files(&[("p.st", src)], &options(hosts()))
        .err()
        .expect("two POUs named Ramp");
    assert!(err.diagnostics.has_errors(), "{err}");
}

#[test]
fn signatures_list_their_pins() {
    let pins = scale().pins();
    assert_eq!(pins.len(), 3);
    assert_eq!(pins[0].dir, PinDir::Result);
    assert_eq!(pins[0].name, "Scale");
    assert_eq!(pins[2].ty, ElemType::Real);
}

#[test]
fn each_host_body_is_one_host_instruction_and_calls_are_ordinary_calls() {
    let plc = compile(
        "PROGRAM P VAR n : INT; END_VAR n := n + 1; END_PROGRAM",
        hosts(),
    );
    assert_eq!(plc.image().instruction_count("CallHost"), Some(2));
    assert_eq!(plc.image().instruction_count("CallFb"), Some(0));
    let used = compile(
        "PROGRAM P VAR r : Ramp; y : REAL; END_VAR r(run := TRUE, inc := 1); y := Scale(1.0, 2.0); END_PROGRAM",
        hosts(),
    );
    assert_eq!(used.image().instruction_count("CallHost"), Some(2));
    assert_eq!(used.image().instruction_count("CallFb"), Some(1));
    assert_eq!(used.image().instruction_count("CallFn"), Some(1));
}

#[test]
fn a_plc_with_host_code_can_move_to_another_thread() {
    fn assert_send<T: Send>(_: &T) {}
    let mut plc = compile(
        "PROGRAM P VAR r : Ramp; END_VAR r(run := TRUE, inc := 4); END_PROGRAM",
        hosts(),
    );
    assert_send(&plc);
    let plc = std::thread::spawn(move || {
        plc.run_cycle().unwrap();
        plc
    })
    .join()
    .unwrap();
    assert_eq!(read(&plc, "P.r.value"), "4");
}

#[test]
fn after_an_online_change_host_instances_keep_their_state() {
    let v1 = "PROGRAM P VAR r : Ramp; END_VAR r(run := TRUE, inc := 2); END_PROGRAM";
    let v2 = "PROGRAM P VAR r : Ramp; n : INT; END_VAR r(run := TRUE, inc := 2); n := n + 1; END_PROGRAM";
    let registered = hosts();
    let mut plc = compile(v1, registered.clone());
    cycles(&mut plc, 3);
    let report = plc
        .online_change_files(&[("p.st", v2)], &options(registered))
        .unwrap();
    assert!(report.kept.contains(&"P.r".to_string()), "{report}");
    // The pins (PLC memory) and the closure's own state are carried.
    assert_eq!(read(&plc, "P.r.value"), "6");
    cycles(&mut plc, 1);
    assert_eq!(read(&plc, "P.r.value"), "8");
    assert_eq!(read(&plc, "P.r.calls"), "4");
    // Registered anew (other code under the same name): a fresh instance.
    let report = plc
        .online_change_files(&[("p.st", v1)], &options(hosts()))
        .unwrap();
    assert!(report.dropped.contains(&"P.n".to_string()), "{report}");
    cycles(&mut plc, 1);
    assert_eq!(read(&plc, "P.r.value"), "2");
    assert_eq!(read(&plc, "P.r.calls"), "1");
}

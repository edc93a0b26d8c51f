//! Every entry point of the C ABI, called as C would call it: the
//! successful paths, and for each the failures C code can cause (NULL
//! pointers, invalid and freed handles, unknown names, wrong types,
//! numbers out of range, small buffers, compile errors, runtime faults).
//! The panic path is tested inside the crate (src/guard.rs), where an
//! entry point that panics can exist for the test alone.

use plcrun_capi::status::*;
use plcrun_capi::*;
use std::ffi::{CStr, c_char, c_int};
use std::ptr::{null, null_mut};

const MAIN: &str = "\
TYPE Color : (Red, Green, Blue); END_TYPE
TYPE Small : INT (0..10); END_TYPE
PROGRAM Main
VAR_INPUT
    b : BOOL; i : INT; s : SINT; u : USINT; r : REAL; l : LREAL; d : DINT := 12;
    t : TIME; w : WORD; big : ULINT := 18446744073709551615; c : Color; sr : Small;
    txt : STRING := 'hi'; day : DATE; k : INT := 1;
END_VAR
VAR_OUTPUT q : DINT; arr : ARRAY[1..3] OF INT; END_VAR
q := d / k;
arr[2] := i;
END_PROGRAM
";

fn last_error() -> String {
    // SAFETY: plc_last_error never returns NULL; the text is read before
    // the next call on this thread.
    unsafe { CStr::from_ptr(plc_last_error()) }
        .to_str()
        .unwrap()
        .to_string()
}

/// Compiles `files` (name, text) with `options`, giving the status and
/// the handle.
fn create_with(files: &[(&str, &str)], options: *const PlcOptions) -> (c_int, PlcHandle) {
    let owned: Vec<(std::ffi::CString, std::ffi::CString)> = files
        .iter()
        .map(|(n, t)| {
            (
                std::ffi::CString::new(*n).unwrap(),
                std::ffi::CString::new(*t).unwrap(),
            )
        })
        .collect();
    let sources: Vec<PlcSource> = owned
        .iter()
        .map(|(n, t)| PlcSource {
            name: n.as_ptr(),
            text: t.as_ptr(),
        })
        .collect();
    let mut plc = PlcHandle { id: 77 };
    let status = unsafe { plc_create(sources.as_ptr(), sources.len(), options, &mut plc) };
    (status, plc)
}

fn main_plc() -> PlcHandle {
    let (status, plc) = create_with(&[("main.st", MAIN)], null());
    assert_eq!(status, PLC_OK, "{}", last_error());
    plc
}

fn literal(plc: PlcHandle, path: &CStr) -> String {
    let mut buf = [0 as c_char; 128];
    let status =
        unsafe { plc_get_literal(plc, path.as_ptr(), buf.as_mut_ptr(), buf.len(), null_mut()) };
    assert_eq!(status, PLC_OK, "{}", last_error());
    unsafe { CStr::from_ptr(buf.as_ptr()) }
        .to_str()
        .unwrap()
        .to_string()
}

#[test]
fn version_and_status_texts() {
    let v = unsafe { CStr::from_ptr(plc_version()) }.to_str().unwrap();
    assert_eq!(v, env!("CARGO_PKG_VERSION"));
    assert_eq!(plc_abi_version(), PLC_ABI_VERSION);
    let text = |s| {
        unsafe { CStr::from_ptr(plc_status_text(s)) }
            .to_str()
            .unwrap()
    };
    assert_eq!(text(PLC_OK), "success");
    assert_eq!(
        text(PLC_E_BUFFER_TOO_SMALL),
        "the output buffer is too small"
    );
    assert_eq!(text(12345), "unknown status");
}

#[test]
fn options_have_defaults_and_are_checked() {
    let mut o = PlcOptions {
        cycle_time_ns: 0,
        program: c"x".as_ptr(),
        watchdog_ns: 0,
    };
    assert_eq!(unsafe { plc_options_init(&mut o) }, PLC_OK);
    assert_eq!(
        (o.cycle_time_ns, o.program, o.watchdog_ns),
        (10_000_000, null(), 1_000_000_000)
    );
    assert_eq!(unsafe { plc_options_init(null_mut()) }, PLC_E_NULL_ARGUMENT);
    assert_eq!(last_error(), "`options` is NULL");

    o.cycle_time_ns = 250_000_000;
    let (status, plc) = create_with(&[("main.st", MAIN)], &o);
    assert_eq!(status, PLC_OK);
    let mut tick = 0;
    assert_eq!(unsafe { plc_cycle_time_ns(plc, &mut tick) }, PLC_OK);
    assert_eq!(tick, 250_000_000);
    assert_eq!(plc_free(plc), PLC_OK);

    o.cycle_time_ns = -1;
    let (status, plc) = create_with(&[("main.st", MAIN)], &o);
    assert_eq!((status, plc.id), (PLC_E_INVALID_ARGUMENT, 0));
    assert_eq!(last_error(), "cycle_time_ns must be positive, not -1");
}

#[test]
fn choosing_the_program_among_several() {
    let two = "PROGRAM A VAR_OUTPUT x : INT; END_VAR x := 1; END_PROGRAM\n\
               PROGRAM B VAR_OUTPUT x : INT; END_VAR x := 2; END_PROGRAM\n";
    let (status, _) = create_with(&[("two.st", two)], null());
    assert_eq!(status, PLC_E_COMPILE);
    let mut o = PlcOptions {
        cycle_time_ns: 0,
        program: null(),
        watchdog_ns: 0,
    };
    unsafe { plc_options_init(&mut o) };
    o.program = c"B".as_ptr();
    let (status, plc) = create_with(&[("two.st", two)], &o);
    assert_eq!(status, PLC_OK, "{}", last_error());
    assert_eq!(plc_run_cycle(plc), PLC_OK);
    assert_eq!(literal(plc, c"x"), "2");
    plc_free(plc);
}

#[test]
fn create_refuses_null_empty_and_non_utf8_arguments() {
    let mut plc = PlcHandle { id: 5 };
    let src = PlcSource {
        name: c"a.st".as_ptr(),
        text: c"PROGRAM P END_PROGRAM".as_ptr(),
    };
    assert_eq!(
        unsafe { plc_create(null(), 1, null(), &mut plc) },
        PLC_E_NULL_ARGUMENT
    );
    assert_eq!((last_error().as_str(), plc.id), ("`sources` is NULL", 0));
    assert_eq!(
        unsafe { plc_create(&src, 1, null(), null_mut()) },
        PLC_E_NULL_ARGUMENT
    );
    assert_eq!(last_error(), "`out` is NULL");
    assert_eq!(
        unsafe { plc_create(&src, 0, null(), &mut plc) },
        PLC_E_INVALID_ARGUMENT
    );
    assert_eq!(last_error(), "no source file given");
    let no_name = PlcSource {
        name: null(),
        text: src.text,
    };
    assert_eq!(
        unsafe { plc_create(&no_name, 1, null(), &mut plc) },
        PLC_E_NULL_ARGUMENT
    );
    assert_eq!(last_error(), "`sources[0].name` is NULL");
    let latin1 = b"PROGRAM P (* \xe9 *) END_PROGRAM\0";
    let bad = PlcSource {
        name: src.name,
        text: latin1.as_ptr().cast(),
    };
    assert_eq!(
        unsafe { plc_create(&bad, 1, null(), &mut plc) },
        PLC_E_INVALID_ARGUMENT
    );
    assert_eq!(last_error(), "`sources[0].text` is not UTF-8 (byte 13)");
}

#[test]
fn a_compile_error_gives_the_diagnostics_as_text() {
    let source = "PROGRAM P\nVAR x : INT; END_VAR\nx := undefined_thing + 1;\nEND_PROGRAM\n";
    let (status, plc) = create_with(&[("broken.st", source)], null());
    assert_eq!((status, plc.id), (PLC_E_COMPILE, 0));
    let text = last_error();
    assert!(text.contains("broken.st:3:6"), "{text}");
    assert!(text.contains("undefined_thing"), "{text}");
    assert!(text.contains("error[E"), "{text}");
}

#[test]
fn warnings_are_kept_with_the_plc() {
    let source = "PROGRAM P\nVAR x : INT; END_VAR\n{ a pragma } x := 1;\nEND_PROGRAM\n";
    let (status, plc) = create_with(&[("w.st", source)], null());
    assert_eq!(status, PLC_OK);
    let mut needed = 0;
    assert_eq!(
        unsafe { plc_warnings(plc, null_mut(), 0, &mut needed) },
        PLC_E_BUFFER_TOO_SMALL
    );
    let mut buf = vec![0 as c_char; needed];
    assert_eq!(
        unsafe { plc_warnings(plc, buf.as_mut_ptr(), needed, null_mut()) },
        PLC_OK
    );
    let text = unsafe { CStr::from_ptr(buf.as_ptr()) }.to_str().unwrap();
    assert!(text.contains("W001") && text.contains("w.st:3:1"), "{text}");
    let main = main_plc();
    let mut buf = [1 as c_char; 4];
    assert_eq!(
        unsafe { plc_warnings(main, buf.as_mut_ptr(), 4, &mut needed) },
        PLC_OK
    );
    assert_eq!((buf[0], needed), (0, 1));
    plc_free(plc);
    plc_free(main);
}

#[test]
fn cycles_advance_the_clock() {
    let plc = main_plc();
    let (mut cycle, mut time) = (9u64, 9i64);
    assert_eq!(unsafe { plc_cycle(plc, &mut cycle) }, PLC_OK);
    assert_eq!(cycle, 0);
    for _ in 0..3 {
        assert_eq!(plc_run_cycle(plc), PLC_OK);
    }
    assert_eq!(unsafe { plc_cycle(plc, &mut cycle) }, PLC_OK);
    assert_eq!(unsafe { plc_time_ns(plc, &mut time) }, PLC_OK);
    assert_eq!((cycle, time), (3, 30_000_000));
    assert_eq!(literal(plc, c"q"), "12");
    plc_free(plc);
}

#[test]
fn literals_by_path_and_by_handle() {
    let plc = main_plc();
    let cases: &[(&CStr, &CStr, &str)] = &[
        (c"b", c"TRUE", "TRUE"),
        (c"i", c"-7", "-7"),
        (c"r", c"2.5", "2.5"),
        (c"t", c"T#1s500ms", "T#1s500ms"),
        (c"w", c"16#BEEF", "16#BEEF"),
        (c"c", c"Color#Blue", "Blue"),
        (c"txt", c"'plc'", "'plc'"),
        (c"day", c"D#2024-02-29", "D#2024-02-29"),
    ];
    for (path, lit, want) in cases {
        assert_eq!(
            unsafe { plc_set_literal(plc, path.as_ptr(), lit.as_ptr()) },
            PLC_OK,
            "{}",
            last_error()
        );
        assert_eq!(literal(plc, path), *want);
    }
    let mut var = PlcVar { id: 0 };
    assert_eq!(
        unsafe { plc_resolve(plc, c"arr[2]".as_ptr(), &mut var) },
        PLC_OK
    );
    assert_eq!(plc_run_cycle(plc), PLC_OK);
    let mut buf = [0 as c_char; 16];
    assert_eq!(
        unsafe { plc_var_get_literal(plc, var, buf.as_mut_ptr(), 16, null_mut()) },
        PLC_OK
    );
    assert_eq!(
        unsafe { CStr::from_ptr(buf.as_ptr()) }.to_str().unwrap(),
        "-7"
    );
    assert_eq!(
        unsafe { plc_var_set_literal(plc, var, c"99".as_ptr()) },
        PLC_OK
    );
    assert_eq!(literal(plc, c"arr[2]"), "99");
    // The same path resolves to the same handle.
    let mut again = PlcVar { id: 0 };
    assert_eq!(
        unsafe { plc_resolve(plc, c" arr[2] ".as_ptr(), &mut again) },
        PLC_OK
    );
    assert_eq!(again, var);
    plc_free(plc);
}

#[test]
fn bad_literals_and_unknown_names() {
    let plc = main_plc();
    assert_eq!(
        unsafe { plc_set_literal(plc, c"i".as_ptr(), c"TRUE".as_ptr()) },
        PLC_E_BAD_VALUE
    );
    assert_eq!(last_error(), "`TRUE` is not a valid INT value");
    assert_eq!(
        unsafe { plc_set_literal(plc, c"sr".as_ptr(), c"11".as_ptr()) },
        PLC_E_BAD_VALUE
    );
    assert_eq!(
        unsafe { plc_set_literal(plc, c"c".as_ptr(), c"Purple".as_ptr()) },
        PLC_E_BAD_VALUE
    );
    let unknown: &[(&CStr, &str)] = &[
        (c"nope", "unknown variable `nope`"),
        (c"arr[4]", "`arr[4]`: index 4 is outside [1..3]"),
        (c"arr", "`arr` is a ARRAY[1..3] OF INT, not a single value"),
        (c"b.x", "`b.x`: BOOL has no member `x`"),
        (c"", "empty variable name"),
    ];
    let mut buf = [0 as c_char; 8];
    let (mut flag, mut n, mut x, mut var) = (false, 0i64, 0f64, PlcVar { id: 0 });
    for (path, message) in unknown {
        let p = path.as_ptr();
        let statuses = unsafe {
            [
                plc_get_literal(plc, p, buf.as_mut_ptr(), 8, null_mut()),
                plc_set_literal(plc, p, c"1".as_ptr()),
                plc_get_bool(plc, p, &mut flag),
                plc_set_bool(plc, p, true),
                plc_get_i64(plc, p, &mut n),
                plc_set_i64(plc, p, 1),
                plc_get_f64(plc, p, &mut x),
                plc_set_f64(plc, p, 1.0),
                plc_resolve(plc, p, &mut var),
            ]
        };
        assert_eq!(statuses, [PLC_E_UNKNOWN_VARIABLE; 9], "{path:?}");
        assert_eq!(last_error(), *message);
    }
    plc_free(plc);
}

#[test]
fn typed_scalars_by_path_and_by_handle() {
    let plc = main_plc();
    let (mut flag, mut n, mut x) = (false, 0i64, 0f64);
    unsafe {
        assert_eq!(plc_set_bool(plc, c"b".as_ptr(), true), PLC_OK);
        assert_eq!(plc_get_bool(plc, c"b".as_ptr(), &mut flag), PLC_OK);
        assert!(flag);
        assert_eq!(plc_set_i64(plc, c"s".as_ptr(), -128), PLC_OK);
        assert_eq!(plc_get_i64(plc, c"s".as_ptr(), &mut n), PLC_OK);
        assert_eq!(n, -128);
        assert_eq!(plc_set_i64(plc, c"t".as_ptr(), 1_500_000_000), PLC_OK);
        assert_eq!(literal(plc, c"t"), "T#1s500ms");
        assert_eq!(plc_set_i64(plc, c"c".as_ptr(), 1), PLC_OK);
        assert_eq!(literal(plc, c"c"), "Green");
        assert_eq!(plc_get_i64(plc, c"c".as_ptr(), &mut n), PLC_OK);
        assert_eq!(n, 1);
        assert_eq!(plc_set_i64(plc, c"w".as_ptr(), 0xFFFF), PLC_OK);
        assert_eq!(literal(plc, c"w"), "16#FFFF");
        assert_eq!(plc_set_i64(plc, c"sr".as_ptr(), 10), PLC_OK);
        assert_eq!(plc_set_f64(plc, c"r".as_ptr(), 0.1), PLC_OK);
        assert_eq!(plc_get_f64(plc, c"r".as_ptr(), &mut x), PLC_OK);
        assert_eq!(x, f64::from(0.1f32));
        assert_eq!(plc_set_f64(plc, c"l".as_ptr(), 0.1), PLC_OK);
        assert_eq!(plc_get_f64(plc, c"l".as_ptr(), &mut x), PLC_OK);
        assert_eq!(x, 0.1);

        let (mut vb, mut vi, mut vr) = (PlcVar { id: 0 }, PlcVar { id: 0 }, PlcVar { id: 0 });
        assert_eq!(plc_resolve(plc, c"b".as_ptr(), &mut vb), PLC_OK);
        assert_eq!(plc_resolve(plc, c"i".as_ptr(), &mut vi), PLC_OK);
        assert_eq!(plc_resolve(plc, c"l".as_ptr(), &mut vr), PLC_OK);
        assert_eq!(plc_var_set_bool(plc, vb, false), PLC_OK);
        assert_eq!(plc_var_get_bool(plc, vb, &mut flag), PLC_OK);
        assert!(!flag);
        assert_eq!(plc_var_set_i64(plc, vi, 32767), PLC_OK);
        assert_eq!(plc_var_get_i64(plc, vi, &mut n), PLC_OK);
        assert_eq!(n, 32767);
        assert_eq!(plc_var_set_f64(plc, vr, -2.25), PLC_OK);
        assert_eq!(plc_var_get_f64(plc, vr, &mut x), PLC_OK);
        assert_eq!(x, -2.25);
    }
    plc_free(plc);
}

#[test]
fn typed_scalars_check_types_and_ranges() {
    let plc = main_plc();
    let (mut flag, mut n, mut x) = (false, 0i64, 0f64);
    unsafe {
        assert_eq!(
            plc_get_bool(plc, c"i".as_ptr(), &mut flag),
            PLC_E_WRONG_TYPE
        );
        assert_eq!(last_error(), "`i` is a INT, not a BOOL");
        assert_eq!(plc_set_bool(plc, c"txt".as_ptr(), true), PLC_E_WRONG_TYPE);
        assert_eq!(last_error(), "`txt` is a STRING, not a BOOL");
        assert_eq!(plc_get_i64(plc, c"b".as_ptr(), &mut n), PLC_E_WRONG_TYPE);
        assert_eq!(plc_get_i64(plc, c"r".as_ptr(), &mut n), PLC_E_WRONG_TYPE);
        assert_eq!(plc_set_i64(plc, c"l".as_ptr(), 1), PLC_E_WRONG_TYPE);
        assert_eq!(last_error(), "`l` is a LREAL, not an integer");
        assert_eq!(plc_set_i64(plc, c"day".as_ptr(), 1), PLC_E_WRONG_TYPE);
        assert_eq!(plc_get_f64(plc, c"i".as_ptr(), &mut x), PLC_E_WRONG_TYPE);
        assert_eq!(plc_set_f64(plc, c"d".as_ptr(), 1.0), PLC_E_WRONG_TYPE);
        assert_eq!(last_error(), "`d` is a DINT, not a REAL or LREAL");

        assert_eq!(plc_set_i64(plc, c"s".as_ptr(), 128), PLC_E_OUT_OF_RANGE);
        assert_eq!(last_error(), "128 does not fit `s` (SINT)");
        assert_eq!(plc_set_i64(plc, c"u".as_ptr(), -1), PLC_E_OUT_OF_RANGE);
        assert_eq!(last_error(), "-1 does not fit `u` (USINT)");
        assert_eq!(plc_set_i64(plc, c"sr".as_ptr(), 11), PLC_E_OUT_OF_RANGE);
        assert_eq!(plc_set_i64(plc, c"c".as_ptr(), 3), PLC_E_OUT_OF_RANGE);
        assert_eq!(plc_set_f64(plc, c"r".as_ptr(), 1e300), PLC_E_OUT_OF_RANGE);
        assert_eq!(
            plc_get_i64(plc, c"big".as_ptr(), &mut n),
            PLC_E_OUT_OF_RANGE
        );
        assert_eq!(
            last_error(),
            "`big` holds 18446744073709551615, more than int64_t holds: read it as a literal"
        );
        // Nothing was written by the refused calls.
        assert_eq!(literal(plc, c"s"), "0");
        assert_eq!(literal(plc, c"sr"), "0");
    }
    plc_free(plc);
}

#[test]
fn text_out_reports_the_size_and_refuses_small_buffers() {
    let plc = main_plc();
    unsafe { plc_set_literal(plc, c"txt".as_ptr(), c"'hello'".as_ptr()) };
    let mut needed = 0usize;
    // Asking for the size.
    assert_eq!(
        unsafe { plc_get_literal(plc, c"txt".as_ptr(), null_mut(), 0, &mut needed) },
        PLC_E_BUFFER_TOO_SMALL
    );
    assert_eq!(needed, 8);
    // One byte short: "" in the buffer, the size in needed.
    let mut buf = [b'x' as c_char; 7];
    needed = 0;
    assert_eq!(
        unsafe { plc_get_literal(plc, c"txt".as_ptr(), buf.as_mut_ptr(), 7, &mut needed) },
        PLC_E_BUFFER_TOO_SMALL
    );
    assert_eq!((buf[0], needed), (0, 8));
    assert_eq!(last_error(), "the text needs 8 bytes, the buffer has 7");
    // Exactly enough.
    let mut buf = [b'x' as c_char; 8];
    assert_eq!(
        unsafe { plc_get_literal(plc, c"txt".as_ptr(), buf.as_mut_ptr(), 8, &mut needed) },
        PLC_OK
    );
    assert_eq!(
        unsafe { CStr::from_ptr(buf.as_ptr()) }.to_bytes(),
        b"'hello'"
    );
    // A capacity with no buffer is a NULL argument.
    assert_eq!(
        unsafe { plc_get_literal(plc, c"txt".as_ptr(), null_mut(), 8, &mut needed) },
        PLC_E_NULL_ARGUMENT
    );
    assert_eq!(last_error(), "`buf` is NULL");
    plc_free(plc);
}

#[test]
fn a_runtime_fault_names_its_location_and_stops_the_plc() {
    let plc = main_plc();
    assert_eq!(plc_run_cycle(plc), PLC_OK);
    unsafe { plc_set_i64(plc, c"k".as_ptr(), 0) };
    assert_eq!(plc_run_cycle(plc), PLC_E_RUNTIME_FAULT);
    let message = last_error();
    assert!(
        message.starts_with("error[R001]: runtime fault in cycle 1 at main.st:10:"),
        "{message}"
    );
    assert!(
        message.contains("(in Main)") && message.contains("q := d / k;"),
        "{message}"
    );
    assert!(
        message.to_lowercase().contains("division by zero"),
        "{message}"
    );

    let mut faulted = false;
    assert_eq!(unsafe { plc_is_faulted(plc, &mut faulted) }, PLC_OK);
    assert!(faulted);
    let mut buf = [0 as c_char; 512];
    assert_eq!(
        unsafe { plc_fault_message(plc, buf.as_mut_ptr(), 512, null_mut()) },
        PLC_OK
    );
    assert_eq!(
        unsafe { CStr::from_ptr(buf.as_ptr()) }.to_str().unwrap(),
        message
    );
    // No more cycles; the variables stay readable and writable.
    assert_eq!(plc_run_cycle(plc), PLC_E_FAULTED);
    assert!(last_error().starts_with(
        "the PLC is stopped on an earlier fault: error[R001]: runtime fault in cycle 1"
    ));
    let mut cycle = 0;
    assert_eq!(unsafe { plc_cycle(plc, &mut cycle) }, PLC_OK);
    assert_eq!(cycle, 1);
    assert_eq!(literal(plc, c"k"), "0");
    assert_eq!(unsafe { plc_set_i64(plc, c"k".as_ptr(), 2) }, PLC_OK);
    // A PLC that never faulted says so.
    let fresh = main_plc();
    assert_eq!(unsafe { plc_is_faulted(fresh, &mut faulted) }, PLC_OK);
    assert!(!faulted);
    let mut needed = 0;
    assert_eq!(
        unsafe { plc_fault_message(fresh, buf.as_mut_ptr(), 512, &mut needed) },
        PLC_OK
    );
    assert_eq!((buf[0], needed), (0, 1));
    plc_free(plc);
    plc_free(fresh);
}

/// Calls every entry point that takes a PLC handle with `plc` (and valid
/// other arguments), giving their statuses.
fn every_call(plc: PlcHandle, var: PlcVar) -> Vec<c_int> {
    let mut buf = [0 as c_char; 64];
    let (b, p) = (buf.as_mut_ptr(), c"b".as_ptr());
    let (mut flag, mut n, mut x, mut u, mut v) = (false, 0i64, 0f64, 0u64, PlcVar { id: 0 });
    unsafe {
        vec![
            plc_warnings(plc, b, 64, null_mut()),
            plc_run_cycle(plc),
            plc_is_faulted(plc, &mut flag),
            plc_fault_message(plc, b, 64, null_mut()),
            plc_cycle(plc, &mut u),
            plc_time_ns(plc, &mut n),
            plc_cycle_time_ns(plc, &mut n),
            plc_resolve(plc, p, &mut v),
            plc_get_literal(plc, p, b, 64, null_mut()),
            plc_set_literal(plc, p, c"TRUE".as_ptr()),
            plc_get_bool(plc, p, &mut flag),
            plc_set_bool(plc, p, true),
            plc_get_i64(plc, c"i".as_ptr(), &mut n),
            plc_set_i64(plc, c"i".as_ptr(), 1),
            plc_get_f64(plc, c"l".as_ptr(), &mut x),
            plc_set_f64(plc, c"l".as_ptr(), 1.0),
            plc_var_get_literal(plc, var, b, 64, null_mut()),
            plc_var_set_literal(plc, var, c"TRUE".as_ptr()),
            plc_var_get_bool(plc, var, &mut flag),
            plc_var_set_bool(plc, var, true),
            plc_var_get_i64(plc, var, &mut n),
            plc_var_set_i64(plc, var, 1),
            plc_var_get_f64(plc, var, &mut x),
            plc_var_set_f64(plc, var, 1.0),
            plc_free(plc),
        ]
    }
}

#[test]
fn invalid_and_freed_handles_are_refused_by_every_entry_point() {
    let live = main_plc();
    let mut var = PlcVar { id: 0 };
    assert_eq!(
        unsafe { plc_resolve(live, c"b".as_ptr(), &mut var) },
        PLC_OK
    );
    for bogus in [0, 1 << 32, u64::MAX, live.id + 1000, live.id ^ (1 << 40)] {
        let statuses = every_call(PlcHandle { id: bogus }, var);
        assert_eq!(
            statuses,
            vec![PLC_E_INVALID_HANDLE; statuses.len()],
            "{bogus:#x}"
        );
        assert!(last_error().contains("is not valid"), "{}", last_error());
    }
    // Freed: the handle and its variable handles are dead, and a second
    // free is refused; a new PLC in the same slot does not revive them.
    assert_eq!(plc_free(live), PLC_OK);
    let statuses = every_call(live, var);
    assert_eq!(statuses, vec![PLC_E_INVALID_HANDLE; statuses.len()]);
    let next = main_plc();
    assert_ne!(next.id, live.id);
    assert_eq!(plc_run_cycle(live), PLC_E_INVALID_HANDLE);
    let mut flag = false;
    assert_eq!(
        unsafe { plc_var_get_bool(next, var, &mut flag) },
        PLC_E_INVALID_HANDLE
    );
    plc_free(next);
}

#[test]
fn a_variable_handle_belongs_to_its_plc() {
    let (one, two) = (main_plc(), main_plc());
    let mut var = PlcVar { id: 0 };
    assert_eq!(unsafe { plc_resolve(one, c"i".as_ptr(), &mut var) }, PLC_OK);
    let mut n = 0;
    assert_eq!(
        unsafe { plc_var_get_i64(two, var, &mut n) },
        PLC_E_INVALID_HANDLE
    );
    assert!(
        last_error().contains("was not resolved by this PLC"),
        "{}",
        last_error()
    );
    for bogus in [0, var.id + 1, var.id & 0xFFFF_FFFF] {
        assert_eq!(
            unsafe { plc_var_get_i64(one, PlcVar { id: bogus }, &mut n) },
            PLC_E_INVALID_HANDLE
        );
    }
    assert_eq!(plc_var_set_i64(one, var, 5), PLC_OK);
    assert_eq!(literal(one, c"i"), "5");
    assert_eq!(literal(two, c"i"), "0");
    plc_free(one);
    plc_free(two);
}

#[test]
fn null_pointers_are_refused_by_every_entry_point() {
    let plc = main_plc();
    let mut var = PlcVar { id: 0 };
    assert_eq!(unsafe { plc_resolve(plc, c"b".as_ptr(), &mut var) }, PLC_OK);
    let (mut flag, mut n, mut x) = (false, 0i64, 0f64);
    let mut buf = [0 as c_char; 8];
    let (p, b) = (c"b".as_ptr(), buf.as_mut_ptr());
    let statuses = unsafe {
        [
            plc_options_init(null_mut()),
            plc_warnings(plc, null_mut(), 8, null_mut()),
            plc_is_faulted(plc, null_mut()),
            plc_fault_message(plc, null_mut(), 8, null_mut()),
            plc_cycle(plc, null_mut()),
            plc_time_ns(plc, null_mut()),
            plc_cycle_time_ns(plc, null_mut()),
            // (A failed resolve stores a zero handle: not into `var`.)
            plc_resolve(plc, null(), &mut PlcVar { id: 9 }),
            plc_resolve(plc, p, null_mut()),
            plc_get_literal(plc, null(), b, 8, null_mut()),
            plc_get_literal(plc, p, null_mut(), 8, null_mut()),
            plc_set_literal(plc, null(), c"TRUE".as_ptr()),
            plc_set_literal(plc, p, null()),
            plc_get_bool(plc, null(), &mut flag),
            plc_get_bool(plc, p, null_mut()),
            plc_set_bool(plc, null(), true),
            plc_get_i64(plc, null(), &mut n),
            plc_get_i64(plc, c"i".as_ptr(), null_mut()),
            plc_set_i64(plc, null(), 1),
            plc_get_f64(plc, null(), &mut x),
            plc_get_f64(plc, c"l".as_ptr(), null_mut()),
            plc_set_f64(plc, null(), 1.0),
            plc_var_get_literal(plc, var, null_mut(), 8, null_mut()),
            plc_var_set_literal(plc, var, null()),
            plc_var_get_bool(plc, var, null_mut()),
            plc_var_get_i64(plc, var, null_mut()),
            plc_var_get_f64(plc, var, null_mut()),
        ]
    };
    assert_eq!(statuses, [PLC_E_NULL_ARGUMENT; 27]);
    // Non-UTF-8 text is refused too.
    let bad = c"\xff".as_ptr();
    assert_eq!(
        unsafe { plc_set_literal(plc, p, bad) },
        PLC_E_INVALID_ARGUMENT
    );
    assert_eq!(
        unsafe { plc_get_bool(plc, bad, &mut flag) },
        PLC_E_INVALID_ARGUMENT
    );
    assert_eq!(last_error(), "`path` is not UTF-8 (byte 0)");
    // The PLC is unharmed.
    assert_eq!(plc_run_cycle(plc), PLC_OK);
    assert_eq!(plc_free(plc), PLC_OK);
}

#[test]
fn plcs_live_on_other_threads_and_errors_are_per_thread() {
    let plc = main_plc();
    let worker = std::thread::spawn(move || {
        let mut statuses = Vec::new();
        for _ in 0..50 {
            statuses.push(plc_run_cycle(plc));
        }
        statuses.push(unsafe { plc_set_i64(plc, c"nothing".as_ptr(), 1) });
        (statuses, last_error())
    });
    // Meanwhile, on this thread: other PLCs, and the same one.
    let other = main_plc();
    for _ in 0..50 {
        assert_eq!(plc_run_cycle(other), PLC_OK);
        assert_eq!(unsafe { plc_set_i64(plc, c"i".as_ptr(), 3) }, PLC_OK);
    }
    assert_eq!(last_error(), "");
    let (statuses, message) = worker.join().unwrap();
    assert_eq!(statuses[..50], [PLC_OK; 50]);
    assert_eq!(statuses[50], PLC_E_UNKNOWN_VARIABLE);
    assert_eq!(message, "unknown variable `nothing`");
    let mut cycle = 0;
    assert_eq!(unsafe { plc_cycle(plc, &mut cycle) }, PLC_OK);
    assert_eq!(cycle, 50);
    plc_free(plc);
    plc_free(other);
}

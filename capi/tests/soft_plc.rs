//! The soft-PLC entry points of the C ABI, called as C would call them:
//! the faulted state and the resets, forcing and soft writes, the process
//! image, retained data, the watchdog and the stop token (an abort from
//! another thread while a runaway cycle runs), the addressing convention.
//! For each, the failures C code can cause: NULL pointers, invalid and
//! freed handles, bad addresses, wrong widths, read-only refusals, small
//! buffers.

use plcrun_capi::status::*;
use plcrun_capi::*;
use std::ffi::{CStr, CString, c_char, c_int};
use std::ptr::{null, null_mut};

const IO: &str = "\
PROGRAM Io
VAR
    sw AT %IX0.3 : BOOL;
    level AT %IW1 : INT;
    lamp AT %QX0.1 : BOOL;
    copy AT %QW2 : INT;
    big AT %QL1 : LINT;
    m AT %MD0 : DINT;
    n : DINT;
    z : DINT;
END_VAR
VAR CONSTANT limit : INT := 10; END_VAR
VAR RETAIN kept : DINT; END_VAR
lamp := sw;
copy := level * 2;
big := 1;
n := n + 1;
kept := kept + 1;
m := m + 1;
IF n > limit THEN n := n / z; END_IF;
END_PROGRAM
";

const SFC: &str = "PROGRAM Seq
VAR_INPUT go : BOOL; END_VAR
INITIAL_STEP Idle : END_STEP
TRANSITION FROM Idle TO Run := go; END_TRANSITION
STEP Run : END_STEP
TRANSITION FROM Run TO Idle := NOT go; END_TRANSITION
END_PROGRAM
";

const RUNAWAY: &str =
    "PROGRAM Spin VAR x : DINT; END_VAR WHILE TRUE DO x := x + 1; END_WHILE; END_PROGRAM";

fn last_error() -> String {
    // SAFETY: never NULL; read before the next call on this thread.
    unsafe { CStr::from_ptr(plc_last_error()) }
        .to_str()
        .unwrap()
        .to_string()
}

fn create(name: &str, text: &str) -> PlcHandle {
    let (name, text) = (CString::new(name).unwrap(), CString::new(text).unwrap());
    let source = PlcSource {
        name: name.as_ptr(),
        text: text.as_ptr(),
    };
    // No wall-clock watchdog unless a test sets one: these tests are about
    // the entry points, and scripts/memcheck runs them under valgrind, where
    // a cycle can take seconds.
    let mut options = PlcOptions {
        cycle_time_ns: 0,
        program: null(),
        watchdog_ns: 0,
    };
    assert_eq!(unsafe { plc_options_init(&mut options) }, PLC_OK);
    options.watchdog_ns = 0;
    let mut plc = PlcHandle { id: 0 };
    let status = unsafe { plc_create(&source, 1, &options, &mut plc) };
    assert_eq!(status, PLC_OK, "{}", last_error());
    plc
}

fn literal(plc: PlcHandle, path: &CStr) -> String {
    let mut buf = [0 as c_char; 64];
    let status = unsafe { plc_get_literal(plc, path.as_ptr(), buf.as_mut_ptr(), 64, null_mut()) };
    assert_eq!(status, PLC_OK, "{}", last_error());
    unsafe { CStr::from_ptr(buf.as_ptr()) }
        .to_str()
        .unwrap()
        .to_string()
}

fn cycle(plc: PlcHandle) {
    assert_eq!(plc_run_cycle(plc), PLC_OK, "{}", last_error());
}

/// A fresh path in the temporary directory.
fn temp_file(name: &str) -> CString {
    let path = std::env::temp_dir().join(format!("plcrun-capi-{}-{name}", std::process::id()));
    let _ = std::fs::remove_file(&path);
    CString::new(path.to_str().unwrap()).unwrap()
}

#[test]
fn the_image_is_read_and_written_by_address() {
    let plc = create("io.st", IO);
    unsafe {
        assert_eq!(plc_image_write_bit(plc, c"%IX0.3".as_ptr(), true), PLC_OK);
        assert_eq!(plc_image_write_word(plc, c"%IW1".as_ptr(), 21), PLC_OK);
        cycle(plc);
        let (mut bit, mut byte, mut word, mut dword, mut lword) = (false, 0u8, 0u16, 0u32, 0u64);
        assert_eq!(
            plc_image_read_bit(plc, c"%QX0.1".as_ptr(), &mut bit),
            PLC_OK
        );
        assert_eq!(
            plc_image_read_word(plc, c"%QW2".as_ptr(), &mut word),
            PLC_OK
        );
        assert_eq!(
            plc_image_read_byte(plc, c"%QB4".as_ptr(), &mut byte),
            PLC_OK
        );
        assert_eq!(
            plc_image_read_dword(plc, c"%QD1".as_ptr(), &mut dword),
            PLC_OK
        );
        assert_eq!(
            plc_image_read_lword(plc, c"%ql1".as_ptr(), &mut lword),
            PLC_OK
        );
        assert_eq!((bit, byte, word, dword, lword), (true, 42, 42, 42, 1));
        // %M is the host's too; the program counts it up.
        assert_eq!(plc_image_write_dword(plc, c"%MD0".as_ptr(), 100), PLC_OK);
        assert_eq!(plc_image_write_byte(plc, c"%IB0".as_ptr(), 0), PLC_OK);
        assert_eq!(
            plc_image_write_lword(plc, c"%ML0".as_ptr(), 0),
            PLC_E_ADDRESS_OUT_OF_RANGE
        );
        cycle(plc);
        assert_eq!(literal(plc, c"m"), "101");
        assert_eq!(
            plc_image_read_bit(plc, c"%QX0.1".as_ptr(), &mut bit),
            PLC_OK
        );
        assert!(!bit);
        // The Moeller form names the same bit.
        assert_eq!(
            plc_image_read_bit(plc, c"%I0.0.0.0.3".as_ptr(), &mut bit),
            PLC_OK
        );
        assert!(!bit);
    }
    plc_free(plc);
}

#[test]
fn bad_addresses_wrong_widths_and_q_writes_are_refused() {
    let plc = create("io.st", IO);
    let mut word = 0u16;
    let mut bit = false;
    unsafe {
        for text in [c"hello", c"%IX0.9", c"%I1.0.0.0.1", c"%ZW0"] {
            assert_eq!(
                plc_image_read_word(plc, text.as_ptr(), &mut word),
                PLC_E_BAD_ADDRESS,
                "{text:?}"
            );
        }
        assert_eq!(
            plc_image_read_bit(plc, c"%IX0.9".as_ptr(), &mut bit),
            PLC_E_BAD_ADDRESS
        );
        assert_eq!(last_error(), "`%IX0.9`: bit 9 is not in 0..7");
        assert_eq!(
            plc_image_read_word(plc, c"%IW100".as_ptr(), &mut word),
            PLC_E_ADDRESS_OUT_OF_RANGE
        );
        assert!(last_error().contains("(4 bytes,"), "{}", last_error());
        assert_eq!(
            plc_image_write_word(plc, c"%IX0.1".as_ptr(), 1),
            PLC_E_WRONG_TYPE
        );
        assert_eq!(last_error(), "`%IX0.1` is not a word (W) address");
        assert_eq!(
            plc_image_write_bit(plc, c"%QX0.1".as_ptr(), true),
            PLC_E_READ_ONLY
        );
        assert!(last_error().contains("%Q is written by the program"));
        // NULL and invalid handles.
        assert_eq!(
            plc_image_read_word(plc, null(), &mut word),
            PLC_E_NULL_ARGUMENT
        );
        assert_eq!(
            plc_image_read_word(plc, c"%QW2".as_ptr(), null_mut()),
            PLC_E_NULL_ARGUMENT
        );
        assert_eq!(plc_image_write_bit(plc, null(), true), PLC_E_NULL_ARGUMENT);
        assert_eq!(
            plc_image_read_word(PlcHandle { id: 0 }, c"%QW2".as_ptr(), &mut word),
            PLC_E_INVALID_HANDLE
        );
    }
    plc_free(plc);
}

#[test]
fn whole_areas_are_copied_in_and_out() {
    let plc = create("io.st", IO);
    let mut size = 0usize;
    unsafe {
        let sizes: Vec<usize> = [PLC_AREA_INPUT, PLC_AREA_OUTPUT, PLC_AREA_MEMORY]
            .iter()
            .map(|a| {
                assert_eq!(plc_image_area_size(plc, *a, &mut size), PLC_OK);
                size
            })
            .collect();
        assert_eq!(sizes, [4, 16, 4]);
        // %IW1 (bytes 2-3) := 7 through the area, %IX0.3 := 1.
        assert_eq!(
            plc_image_write_area(plc, PLC_AREA_INPUT, 0, [8u8, 0, 7, 0].as_ptr(), 4),
            PLC_OK
        );
        cycle(plc);
        let mut out = [0xAAu8; 16];
        assert_eq!(
            plc_image_read_area(plc, PLC_AREA_OUTPUT, 0, out.as_mut_ptr(), 16),
            PLC_OK
        );
        assert_eq!(out, [2, 0, 0, 0, 14, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0]);
        let mut part = [0u8; 2];
        assert_eq!(
            plc_image_read_area(plc, PLC_AREA_OUTPUT, 4, part.as_mut_ptr(), 2),
            PLC_OK
        );
        assert_eq!(part, [14, 0]);
        // Refusals.
        assert_eq!(
            plc_image_write_area(plc, PLC_AREA_OUTPUT, 0, part.as_ptr(), 2),
            PLC_E_READ_ONLY
        );
        assert_eq!(
            plc_image_write_area(plc, PLC_AREA_INPUT, 3, part.as_ptr(), 2),
            PLC_E_ADDRESS_OUT_OF_RANGE
        );
        assert_eq!(
            last_error(),
            "bytes 3 .. 3+2 are outside the %I area (4 bytes)"
        );
        assert_eq!(
            plc_image_read_area(plc, PLC_AREA_MEMORY, usize::MAX, part.as_mut_ptr(), 2),
            PLC_E_ADDRESS_OUT_OF_RANGE
        );
        assert_eq!(
            plc_image_area_size(plc, 7, &mut size),
            PLC_E_INVALID_ARGUMENT
        );
        assert_eq!(
            plc_image_area_size(plc, -1, &mut size),
            PLC_E_INVALID_ARGUMENT
        );
        assert_eq!(
            plc_image_area_size(plc, PLC_AREA_INPUT, null_mut()),
            PLC_E_NULL_ARGUMENT
        );
        assert_eq!(
            plc_image_read_area(plc, PLC_AREA_INPUT, 0, null_mut(), 1),
            PLC_E_NULL_ARGUMENT
        );
        assert_eq!(
            plc_image_write_area(plc, PLC_AREA_INPUT, 0, null(), 1),
            PLC_E_NULL_ARGUMENT
        );
        // Nothing to copy: NULL is fine.
        assert_eq!(
            plc_image_read_area(plc, PLC_AREA_INPUT, 4, null_mut(), 0),
            PLC_OK
        );
        assert_eq!(
            plc_image_write_area(plc, PLC_AREA_MEMORY, 0, null(), 0),
            PLC_OK
        );
    }
    plc_free(plc);
}

/// The force number `index` as (path, value).
fn force_at(plc: PlcHandle, index: usize) -> (c_int, String, String) {
    let (mut path, mut value) = ([0 as c_char; 32], [0 as c_char; 32]);
    let status = unsafe {
        plc_force_at(
            plc,
            index,
            path.as_mut_ptr(),
            32,
            null_mut(),
            value.as_mut_ptr(),
            32,
            null_mut(),
        )
    };
    let text = |b: &[c_char]| {
        unsafe { CStr::from_ptr(b.as_ptr()) }
            .to_str()
            .unwrap()
            .to_string()
    };
    (status, text(&path), text(&value))
}

#[test]
fn forcing_soft_writes_and_the_force_list() {
    let plc = create("io.st", IO);
    unsafe {
        assert_eq!(plc_force(plc, c"n".as_ptr(), c"-3".as_ptr()), PLC_OK);
        // A forced input keeps its value whatever the host writes.
        assert_eq!(plc_force(plc, c"sw".as_ptr(), c"TRUE".as_ptr()), PLC_OK);
        assert_eq!(plc_image_write_bit(plc, c"%IX0.3".as_ptr(), false), PLC_OK);
        assert_eq!(plc_soft_write(plc, c"n".as_ptr(), c"5".as_ptr()), PLC_OK);
        cycle(plc);
        assert_eq!(literal(plc, c"n"), "-3"); // the program's n + 1 overridden
        assert_eq!(literal(plc, c"lamp"), "TRUE");
        let mut count = 0usize;
        assert_eq!(plc_force_count(plc, &mut count), PLC_OK);
        assert_eq!(count, 2);
        assert_eq!(force_at(plc, 0), (PLC_OK, "n".into(), "-3".into()));
        assert_eq!(force_at(plc, 1), (PLC_OK, "sw".into(), "TRUE".into()));
        assert_eq!(force_at(plc, 2).0, PLC_E_INVALID_ARGUMENT);
        assert_eq!(last_error(), "no force number 2: 2 variables are forced");
        // Too small a buffer: both hold "", both sizes are given.
        let (mut path, mut value) = ([b'x' as c_char; 2], [b'x' as c_char; 4]);
        let (mut path_needed, mut value_needed) = (0usize, 0usize);
        let status = plc_force_at(
            plc,
            1,
            path.as_mut_ptr(),
            2,
            &mut path_needed,
            value.as_mut_ptr(),
            4,
            &mut value_needed,
        );
        assert_eq!(status, PLC_E_BUFFER_TOO_SMALL);
        assert_eq!((path[0], value[0], path_needed, value_needed), (0, 0, 3, 5));
        // Sizes only.
        let status = plc_force_at(
            plc,
            0,
            null_mut(),
            0,
            &mut path_needed,
            null_mut(),
            0,
            null_mut(),
        );
        assert_eq!((status, path_needed), (PLC_E_BUFFER_TOO_SMALL, 2));
        assert_eq!(
            plc_force_at(
                plc,
                0,
                null_mut(),
                8,
                null_mut(),
                value.as_mut_ptr(),
                4,
                null_mut()
            ),
            PLC_E_NULL_ARGUMENT
        );
        // Unforcing takes the last soft write.
        let mut was = false;
        assert_eq!(plc_unforce(plc, c"n".as_ptr(), &mut was), PLC_OK);
        assert!(was);
        assert_eq!(literal(plc, c"n"), "5");
        assert_eq!(plc_unforce(plc, c"n".as_ptr(), &mut was), PLC_OK);
        assert!(!was);
        assert_eq!(plc_unforce(plc, c"n".as_ptr(), null_mut()), PLC_OK);
        assert_eq!(plc_unforce_all(plc), PLC_OK);
        assert_eq!(plc_force_count(plc, &mut count), PLC_OK);
        assert_eq!(count, 0);
        assert_eq!(
            plc_soft_write(plc, c"sw".as_ptr(), c"FALSE".as_ptr()),
            PLC_OK
        );
        cycle(plc);
        assert_eq!(literal(plc, c"lamp"), "FALSE");
    }
    plc_free(plc);
}

#[test]
fn forcing_refuses_unknown_names_wrong_values_and_read_only_variables() {
    let plc = create("io.st", IO);
    let seq = create("seq.sfc", SFC);
    cycle(seq);
    unsafe {
        assert_eq!(
            plc_force(plc, c"nope".as_ptr(), c"1".as_ptr()),
            PLC_E_UNKNOWN_VARIABLE
        );
        assert_eq!(
            plc_unforce(plc, c"nope".as_ptr(), null_mut()),
            PLC_E_UNKNOWN_VARIABLE
        );
        assert_eq!(
            plc_force(plc, c"n".as_ptr(), c"'text'".as_ptr()),
            PLC_E_BAD_VALUE
        );
        let message = last_error();
        assert!(
            message.contains("`n`") && message.contains("'text'"),
            "{message}"
        );
        assert_eq!(
            plc_soft_write(plc, c"n".as_ptr(), c"TRUE".as_ptr()),
            PLC_E_BAD_VALUE
        );
        assert_eq!(
            plc_force(plc, c"limit".as_ptr(), c"1".as_ptr()),
            PLC_E_READ_ONLY
        );
        assert!(last_error().contains("CONSTANT"), "{}", last_error());
        assert_eq!(
            plc_set_literal(plc, c"limit".as_ptr(), c"1".as_ptr()),
            PLC_E_READ_ONLY
        );
        assert_eq!(
            plc_force(seq, c"Run.X".as_ptr(), c"TRUE".as_ptr()),
            PLC_E_READ_ONLY
        );
        assert_eq!(
            plc_soft_write(seq, c"Run.X".as_ptr(), c"TRUE".as_ptr()),
            PLC_E_READ_ONLY
        );
        assert_eq!(literal(seq, c"Idle.X"), "TRUE");
        // NULL arguments.
        let mut count = 0usize;
        let statuses = [
            plc_force(plc, null(), c"1".as_ptr()),
            plc_force(plc, c"n".as_ptr(), null()),
            plc_unforce(plc, null(), null_mut()),
            plc_soft_write(plc, null(), c"1".as_ptr()),
            plc_soft_write(plc, c"n".as_ptr(), null()),
            plc_force_count(plc, null_mut()),
        ];
        assert_eq!(statuses, [PLC_E_NULL_ARGUMENT; 6]);
        assert_eq!(plc_force_count(plc, &mut count), PLC_OK);
        assert_eq!(count, 0);
    }
    plc_free(plc);
    plc_free(seq);
}

#[test]
fn retained_values_round_trip_through_a_file() {
    let plc = create("io.st", IO);
    let file = temp_file("round-trip.json");
    for _ in 0..3 {
        cycle(plc);
    }
    unsafe {
        assert_eq!(plc_retain_save(plc, file.as_ptr()), PLC_OK);
        assert_eq!(plc_reset_cold(plc), PLC_OK);
        assert_eq!(
            (literal(plc, c"kept"), literal(plc, c"n")),
            ("0".into(), "0".into())
        );
        let mut restored = 0usize;
        assert_eq!(
            plc_retain_restore(plc, file.as_ptr(), false, &mut restored),
            PLC_OK
        );
        assert_eq!(restored, 1);
        assert_eq!(
            (literal(plc, c"kept"), literal(plc, c"n")),
            ("3".into(), "0".into())
        );
        assert_eq!(
            plc_retain_restore(plc, file.as_ptr(), false, null_mut()),
            PLC_OK
        );

        // Another program's file: refused, naming what differs.
        let other = create(
            "io.st",
            "PROGRAM Io VAR RETAIN kept : INT; extra : BOOL; END_VAR kept := 7; END_PROGRAM",
        );
        cycle(other);
        assert_eq!(
            plc_retain_restore(other, file.as_ptr(), false, &mut restored),
            PLC_E_RETAIN_MISMATCH
        );
        let message = last_error();
        assert!(
            message.contains("kept") && message.contains("does not fit"),
            "{message}"
        );
        assert_eq!(literal(other, c"kept"), "7");
        assert_eq!(
            plc_retain_restore(other, file.as_ptr(), true, &mut restored),
            PLC_OK
        );
        assert_eq!(restored, 0);
        plc_free(other);

        // Missing, damaged and unwritable files.
        let missing = temp_file("missing.json");
        assert_eq!(
            plc_retain_restore(plc, missing.as_ptr(), false, null_mut()),
            PLC_E_RETAIN_FILE
        );
        assert!(
            last_error().starts_with("cannot read retain file"),
            "{}",
            last_error()
        );
        std::fs::write(missing.to_str().unwrap(), "not json").unwrap();
        assert_eq!(
            plc_retain_restore(plc, missing.as_ptr(), false, null_mut()),
            PLC_E_RETAIN_FILE
        );
        std::fs::remove_file(missing.to_str().unwrap()).unwrap();
        assert_eq!(
            plc_retain_save(plc, c"/nonexistent-plcrun-dir/retain.json".as_ptr()),
            PLC_E_RETAIN_FILE
        );
        assert_eq!(plc_retain_save(plc, null()), PLC_E_NULL_ARGUMENT);
        assert_eq!(
            plc_retain_restore(plc, null(), false, null_mut()),
            PLC_E_NULL_ARGUMENT
        );
    }
    std::fs::remove_file(file.to_str().unwrap()).unwrap();
    plc_free(plc);
}

#[test]
fn a_reset_clears_the_fault_and_cycles_run_again() {
    let plc = create("io.st", IO);
    unsafe { plc_set_literal(plc, c"n".as_ptr(), c"9".as_ptr()) };
    cycle(plc); // kept = 1, n = 10
    assert_eq!(plc_run_cycle(plc), PLC_E_RUNTIME_FAULT); // n = 11 > limit: n / z
    assert!(last_error().starts_with("error[R001]"), "{}", last_error());
    assert_eq!(plc_run_cycle(plc), PLC_E_FAULTED);
    let mut faulted = false;
    assert_eq!(unsafe { plc_is_faulted(plc, &mut faulted) }, PLC_OK);
    assert!(faulted);
    // Warm: the fault goes, the retained value stays.
    assert_eq!(plc_reset_warm(plc), PLC_OK);
    assert_eq!(unsafe { plc_is_faulted(plc, &mut faulted) }, PLC_OK);
    assert!(!faulted);
    assert_eq!(
        (literal(plc, c"kept"), literal(plc, c"n")),
        ("2".into(), "0".into())
    );
    cycle(plc);
    assert_eq!(literal(plc, c"kept"), "3");
    // Cold: everything back to its initial value.
    assert_eq!(plc_reset_cold(plc), PLC_OK);
    assert_eq!(literal(plc, c"kept"), "0");
    let mut cycle_number = 7;
    assert_eq!(unsafe { plc_cycle(plc, &mut cycle_number) }, PLC_OK);
    assert_eq!(cycle_number, 0);
    cycle(plc);
    plc_free(plc);
    assert_eq!(plc_reset_cold(plc), PLC_E_INVALID_HANDLE);
    assert_eq!(plc_reset_warm(plc), PLC_E_INVALID_HANDLE);
}

#[test]
fn the_watchdog_stops_a_runaway_cycle() {
    let plc = create("spin.st", RUNAWAY);
    unsafe {
        assert_eq!(
            plc_set_watchdog_ms(plc, c"nope".as_ptr(), 5),
            PLC_E_UNKNOWN_TASK
        );
        assert_eq!(last_error(), "no task `nope` (the tasks are: default)");
        assert_eq!(plc_set_watchdog_ms(plc, null(), -1), PLC_E_INVALID_ARGUMENT);
        assert_eq!(plc_set_watchdog_ms(plc, c"DEFAULT".as_ptr(), 20), PLC_OK);
        assert_eq!(
            plc_set_watchdog_ms(PlcHandle { id: 0 }, null(), 20),
            PLC_E_INVALID_HANDLE
        );
    }
    assert_eq!(plc_run_cycle(plc), PLC_E_RUNTIME_FAULT);
    let message = last_error();
    assert!(
        message.starts_with("error[R008]") && message.contains("limit 20 ms"),
        "{message}"
    );
    plc_free(plc);
}

#[test]
fn a_stop_token_aborts_a_runaway_cycle_from_another_thread() {
    let plc = create("spin.st", RUNAWAY);
    assert_eq!(unsafe { plc_set_watchdog_ms(plc, null(), 0) }, PLC_OK);
    let mut token = PlcStop { id: 0 };
    assert_eq!(unsafe { plc_stop_token(plc, &mut token) }, PLC_OK);
    let runner = std::thread::spawn(move || (plc_run_cycle(plc), last_error()));
    // The cycle holds the PLC's lock for ever; the abort does not need it.
    std::thread::sleep(std::time::Duration::from_millis(50));
    assert_eq!(plc_abort(token), PLC_OK);
    let (status, message) = runner.join().unwrap();
    assert_eq!(status, PLC_E_RUNTIME_FAULT);
    assert!(message.starts_with("error[R009]"), "{message}");
    let mut faulted = false;
    assert_eq!(unsafe { plc_is_faulted(plc, &mut faulted) }, PLC_OK);
    assert!(faulted);
    assert_eq!(plc_run_cycle(plc), PLC_E_FAULTED);
    // An abort with no cycle running aborts the next one as it starts.
    assert_eq!(plc_reset_cold(plc), PLC_OK);
    assert_eq!(plc_abort(token), PLC_OK);
    assert_eq!(plc_run_cycle(plc), PLC_E_RUNTIME_FAULT);
    assert!(last_error().starts_with("error[R009]"));
    // The token outlives its PLC, until freed.
    assert_eq!(plc_free(plc), PLC_OK);
    assert_eq!(plc_abort(token), PLC_OK);
    assert_eq!(plc_stop_token_free(token), PLC_OK);
    assert_eq!(plc_stop_token_free(token), PLC_E_INVALID_HANDLE);
    assert_eq!(plc_abort(token), PLC_E_INVALID_HANDLE);
    for bogus in [0, 1, u64::MAX, token.id ^ (1 << 40)] {
        assert_eq!(plc_abort(PlcStop { id: bogus }), PLC_E_INVALID_HANDLE);
        assert!(last_error().contains("stop token"), "{}", last_error());
    }
    // A token for a freed PLC cannot be made; NULL is refused.
    let mut other = PlcStop { id: 5 };
    assert_eq!(
        unsafe { plc_stop_token(plc, &mut other) },
        PLC_E_INVALID_HANDLE
    );
    assert_eq!(other.id, 0);
    assert_eq!(
        unsafe { plc_stop_token(plc, null_mut()) },
        PLC_E_NULL_ARGUMENT
    );
}

#[test]
fn every_new_entry_point_refuses_an_invalid_or_freed_handle() {
    let plc = create("io.st", IO);
    assert_eq!(plc_free(plc), PLC_OK);
    let (mut count, mut bit, mut word) = (0usize, false, 0u16);
    let mut code: c_int = -1;
    let mut byte = [0u8; 1];
    let mut buf = [0 as c_char; 8];
    for h in [plc, PlcHandle { id: 0 }, PlcHandle { id: u64::MAX }] {
        let statuses = unsafe {
            [
                plc_reset_cold(h),
                plc_reset_warm(h),
                plc_force(h, c"n".as_ptr(), c"1".as_ptr()),
                plc_unforce(h, c"n".as_ptr(), null_mut()),
                plc_unforce_all(h),
                plc_soft_write(h, c"n".as_ptr(), c"1".as_ptr()),
                plc_force_count(h, &mut count),
                plc_force_at(
                    h,
                    0,
                    buf.as_mut_ptr(),
                    8,
                    null_mut(),
                    null_mut(),
                    0,
                    null_mut(),
                ),
                plc_image_read_bit(h, c"%QX0.1".as_ptr(), &mut bit),
                plc_image_write_word(h, c"%IW1".as_ptr(), 1),
                plc_image_read_word(h, c"%QW2".as_ptr(), &mut word),
                plc_image_area_size(h, PLC_AREA_INPUT, &mut count),
                plc_image_read_area(h, PLC_AREA_INPUT, 0, byte.as_mut_ptr(), 1),
                plc_image_write_area(h, PLC_AREA_INPUT, 0, byte.as_ptr(), 1),
                plc_retain_save(h, c"/tmp/never-written.json".as_ptr()),
                plc_retain_restore(h, c"/tmp/never-read.json".as_ptr(), false, null_mut()),
                plc_set_watchdog_ms(h, null(), 5),
                plc_stop_token(h, &mut PlcStop { id: 0 }),
                plc_set_addressing(h, PLC_ADDRESSING_OPENPLC),
                plc_addressing(h, &mut code),
            ]
        };
        assert_eq!(statuses, [PLC_E_INVALID_HANDLE; 20], "{:#x}", h.id);
    }
    assert!(!std::path::Path::new("/tmp/never-written.json").exists());
}

/// The warnings of a PLC as text.
fn warnings(plc: PlcHandle) -> String {
    let mut needed = 0usize;
    assert_eq!(
        unsafe { plc_warnings(plc, null_mut(), 0, &mut needed) },
        PLC_E_BUFFER_TOO_SMALL
    );
    let mut buf = vec![0 as c_char; needed];
    assert_eq!(
        unsafe { plc_warnings(plc, buf.as_mut_ptr(), needed, null_mut()) },
        PLC_OK
    );
    unsafe { CStr::from_ptr(buf.as_ptr()) }
        .to_str()
        .unwrap()
        .to_string()
}

const OPENPLC_STYLE: &str = "PROGRAM Tank
VAR
    pump AT %QX0.0 : BOOL;
    level AT %QW0 : UINT;
    echo AT %QW1 : UINT;
    setpoint AT %MW0 : UINT;
END_VAR
pump := TRUE;
level := 16#ABCD;
echo := setpoint + 1;
END_PROGRAM
";

#[test]
fn the_addressing_convention_is_set_and_read_from_c() {
    let plc = create("tank.st", OPENPLC_STYLE);
    let mut code: c_int = -1;
    unsafe {
        // An ST source: iec, and %QW0 shares byte 0 with the coil.
        assert_eq!(plc_addressing(plc, &mut code), PLC_OK);
        assert_eq!(code, PLC_ADDRESSING_IEC);
        assert!(warnings(plc).contains("W204"), "{}", warnings(plc));
        assert_eq!(plc_set_addressing(plc, PLC_ADDRESSING_OPENPLC), PLC_OK);
        assert_eq!(plc_addressing(plc, &mut code), PLC_OK);
        assert_eq!(code, PLC_ADDRESSING_OPENPLC);
        assert_eq!(warnings(plc), "");
        assert_eq!(plc_image_write_word(plc, c"%MW0".as_ptr(), 41), PLC_OK);
        cycle(plc);
        let (mut level, mut echo, mut pump) = (0u16, 0u16, false);
        assert_eq!(
            plc_image_read_word(plc, c"%QW0".as_ptr(), &mut level),
            PLC_OK
        );
        assert_eq!(
            plc_image_read_word(plc, c"%QW1".as_ptr(), &mut echo),
            PLC_OK
        );
        assert_eq!(
            plc_image_read_bit(plc, c"%QX0.0".as_ptr(), &mut pump),
            PLC_OK
        );
        assert_eq!((level, echo, pump), (0xABCD, 42, true));
        // Under byte, %QW1 is bytes 1-2: the overlaps are back.
        assert_eq!(plc_set_addressing(plc, PLC_ADDRESSING_BYTE), PLC_OK);
        assert!(
            warnings(plc).contains("byte addressing"),
            "{}",
            warnings(plc)
        );
        // Refusals.
        assert_eq!(plc_set_addressing(plc, 3), PLC_E_INVALID_ARGUMENT);
        assert!(
            last_error().contains("PLC_ADDRESSING_OPENPLC 1"),
            "{}",
            last_error()
        );
        assert_eq!(plc_addressing(plc, null_mut()), PLC_E_NULL_ARGUMENT);
        assert_eq!(plc_addressing(plc, &mut code), PLC_OK);
        assert_eq!(code, PLC_ADDRESSING_BYTE);
    }
    plc_free(plc);
    assert_eq!(
        plc_set_addressing(plc, PLC_ADDRESSING_IEC),
        PLC_E_INVALID_HANDLE
    );
}

#[test]
fn the_tables_of_each_size_are_copied_in_and_out() {
    let plc = create("tank.st", OPENPLC_STYLE);
    let mut size = 0usize;
    unsafe {
        assert_eq!(plc_set_addressing(plc, PLC_ADDRESSING_OPENPLC), PLC_OK);
        let size_of = |area, width, size: &mut usize| {
            assert_eq!(plc_image_table_size(plc, area, width, size), PLC_OK);
            *size
        };
        assert_eq!(size_of(PLC_AREA_OUTPUT, PLC_WIDTH_BIT, &mut size), 1);
        assert_eq!(size_of(PLC_AREA_OUTPUT, PLC_WIDTH_WORD, &mut size), 4);
        assert_eq!(size_of(PLC_AREA_MEMORY, PLC_WIDTH_WORD, &mut size), 2);
        // The area functions reach the byte table, empty here.
        assert_eq!(plc_image_area_size(plc, PLC_AREA_OUTPUT, &mut size), PLC_OK);
        assert_eq!(size, 0);
        // %MW0 := 9 through its table; the program echoes 10 to %QW1.
        assert_eq!(
            plc_image_write_table(
                plc,
                PLC_AREA_MEMORY,
                PLC_WIDTH_WORD,
                0,
                [9u8, 0].as_ptr(),
                2
            ),
            PLC_OK
        );
        cycle(plc);
        let mut words = [0u8; 4];
        assert_eq!(
            plc_image_read_table(
                plc,
                PLC_AREA_OUTPUT,
                PLC_WIDTH_WORD,
                0,
                words.as_mut_ptr(),
                4
            ),
            PLC_OK
        );
        assert_eq!(words, [0xCD, 0xAB, 10, 0]);
        let mut coils = [0u8; 1];
        assert_eq!(
            plc_image_read_table(
                plc,
                PLC_AREA_OUTPUT,
                PLC_WIDTH_BIT,
                0,
                coils.as_mut_ptr(),
                1
            ),
            PLC_OK
        );
        assert_eq!(coils, [1]);
        // Refusals.
        assert_eq!(
            plc_image_write_table(plc, PLC_AREA_OUTPUT, PLC_WIDTH_WORD, 0, words.as_ptr(), 2),
            PLC_E_READ_ONLY
        );
        assert_eq!(
            plc_image_read_table(
                plc,
                PLC_AREA_OUTPUT,
                PLC_WIDTH_WORD,
                3,
                words.as_mut_ptr(),
                2
            ),
            PLC_E_ADDRESS_OUT_OF_RANGE
        );
        assert!(
            last_error().contains("%QW addresses (4 bytes)"),
            "{}",
            last_error()
        );
        assert_eq!(
            plc_image_table_size(plc, PLC_AREA_OUTPUT, 5, &mut size),
            PLC_E_INVALID_ARGUMENT
        );
        assert_eq!(
            plc_image_table_size(plc, PLC_AREA_OUTPUT, PLC_WIDTH_WORD, null_mut()),
            PLC_E_NULL_ARGUMENT
        );
        assert_eq!(
            plc_image_read_table(plc, PLC_AREA_OUTPUT, PLC_WIDTH_WORD, 0, null_mut(), 2),
            PLC_E_NULL_ARGUMENT
        );
        // Under iec every size of an area is the area.
        assert_eq!(plc_set_addressing(plc, PLC_ADDRESSING_IEC), PLC_OK);
        assert_eq!(size_of(PLC_AREA_OUTPUT, PLC_WIDTH_BIT, &mut size), 4);
        assert_eq!(plc_image_area_size(plc, PLC_AREA_OUTPUT, &mut size), PLC_OK);
        assert_eq!(size, 4);
    }
    plc_free(plc);
    assert_eq!(
        unsafe { plc_image_table_size(plc, PLC_AREA_INPUT, PLC_WIDTH_BIT, &mut size) },
        PLC_E_INVALID_HANDLE
    );
}

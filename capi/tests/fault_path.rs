//! The C ABI's fault message names the faulting instance and its callers
//! (one `note:` line each), both from `plc_run_cycle`'s last error and from
//! `plc_fault_message`.

use plcrun_capi::status::*;
use plcrun_capi::*;
use std::ffi::{CStr, CString, c_char};
use std::ptr::{null, null_mut};

const SRC: &str = "FUNCTION_BLOCK Pump
VAR_INPUT k : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
q := 100 / k;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Station
VAR pumps : ARRAY[1..2] OF Pump; END_VAR
pumps[2](k := 0);
END_FUNCTION_BLOCK
PROGRAM Main
VAR st : Station; END_VAR
st();
END_PROGRAM
";

#[test]
fn the_fault_message_has_the_instance_path_and_the_callers() {
    let (name, text) = (CString::new("main.st").unwrap(), CString::new(SRC).unwrap());
    let source = PlcSource {
        name: name.as_ptr(),
        text: text.as_ptr(),
    };
    let mut plc = PlcHandle { id: 0 };
    assert_eq!(unsafe { plc_create(&source, 1, null(), &mut plc) }, PLC_OK);
    assert_eq!(plc_run_cycle(plc), PLC_E_RUNTIME_FAULT);
    // SAFETY: plc_last_error never returns NULL.
    let reported = unsafe { CStr::from_ptr(plc_last_error()) }
        .to_string_lossy()
        .into_owned();
    assert!(
        reported.contains("(in Main.st.pumps[2] : Pump): division by zero"),
        "{reported}"
    );
    assert!(
        reported.ends_with(
            "\n  = note: called from Main.st : Station at main.st:8:1\
             \n  = note: called from Main at main.st:12:1"
        ),
        "{reported}"
    );
    let mut buf = [0 as c_char; 512];
    let status = unsafe { plc_fault_message(plc, buf.as_mut_ptr(), buf.len(), null_mut()) };
    assert_eq!(status, PLC_OK);
    // SAFETY: the buffer holds a NUL-terminated text.
    let kept = unsafe { CStr::from_ptr(buf.as_ptr()) }.to_string_lossy();
    assert_eq!(kept, reported);
    assert_eq!(plc_free(plc), PLC_OK);
}

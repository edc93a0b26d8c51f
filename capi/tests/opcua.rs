//! `plc_opcua_start` / `plc_opcua_port` / `plc_opcua_stop`, called as C
//! would call them, with the host running the cycles (`plc_run_cycle`):
//! an async-opcua client reads a computed output, writes an input as a
//! logged-in user and sees the program react after the next cycles; bad
//! arguments get their statuses.

#[path = "../../tests/support/opcua_client.rs"]
mod opcua_client;

use async_opcua::types::{NodeId, StatusCode, Variant};
use opcua_client::{Security, connect};
use plcrun_capi::status::*;
use plcrun_capi::*;
use std::ffi::{CStr, CString};
use std::ptr::{null, null_mut};
use std::time::Duration;

const SRC: &str = "PROGRAM P
VAR_INPUT setpoint : INT; END_VAR
VAR_OUTPUT doubled : INT; END_VAR
doubled := setpoint * 2;
END_PROGRAM";

fn last_error() -> String {
    // SAFETY: never NULL; read before the next call on this thread.
    unsafe { CStr::from_ptr(plc_last_error()) }
        .to_string_lossy()
        .into_owned()
}

fn create() -> PlcHandle {
    let (name, text) = (CString::new("p.st").unwrap(), CString::new(SRC).unwrap());
    let source = PlcSource {
        name: name.as_ptr(),
        text: text.as_ptr(),
    };
    let mut plc = PlcHandle { id: 0 };
    assert_eq!(
        unsafe { plc_create(&source, 1, null(), &mut plc) },
        PLC_OK,
        "{}",
        last_error()
    );
    plc
}

#[test]
fn a_c_host_serves_its_plc_and_sees_client_writes_after_its_cycles() {
    let dir = std::env::temp_dir().join(format!("plcrun-capi-opcua-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let users = dir.join("users");
    plcrun::opcua::Users::add_to_file(&users, "op", "pw").unwrap();
    let c = |p: &std::path::Path| CString::new(p.to_str().unwrap()).unwrap();
    let (users_c, pki_c) = (c(&users), c(&dir.join("pki")));
    let plc = create();
    let mut port = 0u16;
    assert_eq!(
        unsafe { plc_opcua_port(plc, &mut port, null_mut()) },
        PLC_E_INVALID_ARGUMENT
    );
    let bad = CString::new("not an address").unwrap();
    let status = unsafe { plc_opcua_start(plc, bad.as_ptr(), null(), pki_c.as_ptr(), 0) };
    assert_eq!(status, PLC_E_SERVER);
    assert!(last_error().contains("E950"), "{}", last_error());
    let addr = CString::new("127.0.0.1:0").unwrap();
    let status = unsafe { plc_opcua_start(plc, addr.as_ptr(), users_c.as_ptr(), null(), 0) };
    assert_eq!(status, PLC_E_NULL_ARGUMENT);
    let status =
        unsafe { plc_opcua_start(plc, addr.as_ptr(), users_c.as_ptr(), pki_c.as_ptr(), 8) };
    assert_eq!(status, PLC_E_INVALID_ARGUMENT);
    let status = unsafe {
        plc_opcua_start(
            plc,
            addr.as_ptr(),
            users_c.as_ptr(),
            pki_c.as_ptr(),
            PLC_OPCUA_TRUST_CLIENTS,
        )
    };
    assert_eq!(status, PLC_OK, "{}", last_error());
    let mut ns = 0u16;
    assert_eq!(unsafe { plc_opcua_port(plc, &mut port, &mut ns) }, PLC_OK);
    assert!(port > 0 && ns > 0);
    let url = format!("opc.tcp://127.0.0.1:{port}/");
    let id = |p: &str| NodeId::new(ns, p);
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    // The host's cycle loop, on this thread, between client calls.
    let cycles = |n: usize| {
        for _ in 0..n {
            assert_eq!(plc_run_cycle(plc), PLC_OK, "{}", last_error());
        }
    };
    rt.block_on(async {
        let client = connect(
            &url,
            Security::Encrypt,
            Some(("op", "pw")),
            &dir.join("client"),
        )
        .await
        .unwrap();
        assert_eq!(
            client.write(&id("setpoint"), Variant::Int16(8)).await,
            StatusCode::Good
        );
        // Nothing changes until the host runs cycles.
        tokio::time::sleep(Duration::from_millis(50)).await;
        assert_eq!(
            client.read(&id("doubled")).await.value,
            Some(Variant::Int16(0))
        );
        cycles(2); // the write lands after the first; the second computes
        let v = client
            .read_until(&id("doubled"), Duration::from_secs(5), |v| {
                *v == Variant::Int16(16)
            })
            .await;
        assert_eq!(v, Some(Variant::Int16(16)));
        client.close().await;
    });
    assert_eq!(plc_opcua_stop(plc), PLC_OK);
    assert_eq!(
        unsafe { plc_opcua_port(plc, &mut port, null_mut()) },
        PLC_E_INVALID_ARGUMENT
    );
    assert_eq!(plc_free(plc), PLC_OK);
    std::fs::remove_dir_all(&dir).unwrap();
}

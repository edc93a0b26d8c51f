//! The OPC UA server through the library (`plcrun::opcua::OpcUaServer` on
//! a real-time runner), driven by the `async-opcua` client: a computed
//! output read, an input written and the program reacting, a
//! subscription receiving changes, writes refused without login, to a
//! CONSTANT and to an unknown NodeId, a forced variable staying forced.

use crate::support::opcua_client;

use async_opcua::types::{AttributeId, NodeId, StatusCode, Variant};
use opcua_client::{Security, connect};
use plcrun::opcua::{OpcUaConfig, OpcUaServer, Users};
use plcrun::{Options, Plc, RunThread, Session, StopHandle, TaskRunner, TraceFormat, TraceWriter};
use std::path::PathBuf;
use std::time::Duration;

const SRC: &str = "
TYPE Mode : (Idle, Run, Fault); END_TYPE
PROGRAM Main
VAR_INPUT setpoint : INT; END_VAR
VAR_OUTPUT doubled : INT; ticks : DINT; END_VAR
VAR CONSTANT limit : INT := 10; END_VAR
VAR held : INT; seq : ARRAY[0..3] OF INT; mode : Mode; delay : TIME := T#1500ms; END_VAR
doubled := setpoint * 2;
ticks := ticks + 1;
seq[ticks MOD 4] := setpoint;
END_PROGRAM";

/// A PLC served in real time, and what the test needs to stop it.
struct Served {
    server: Option<OpcUaServer>,
    stop: StopHandle,
    run: Option<RunThread<std::io::Sink>>,
    dir: PathBuf,
}

impl Served {
    fn url(&self) -> String {
        self.server.as_ref().unwrap().endpoint_url()
    }

    fn id(&self, path: &str) -> NodeId {
        NodeId::new(self.server.as_ref().unwrap().namespace_index(), path)
    }

    fn client_pki(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        self.stop.stop();
        if let Some(run) = self.run.take() {
            let _ = run.join();
        }
        drop(self.server.take());
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Compiles SRC, forces `held` to 7, adds user `op` (password `pw`) and
/// serves it with a 10 ms task.
fn serve(name: &str, insecure: bool) -> Served {
    let dir = std::env::temp_dir().join(format!("plcrun-opcua-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let users = dir.join("users");
    Users::add_to_file(&users, "op", "pw").unwrap();
    let mut plc = Plc::compile_files(&[("main.st", SRC)], &Options::default()).unwrap();
    plc.force("held", "7").unwrap();
    let stop = plc.stop_handle();
    let config = OpcUaConfig {
        users: Users::load(&users).unwrap(),
        pki_dir: dir.join("server-pki"),
        allow_insecure: insecure,
        trust_client_certs: true,
        ..OpcUaConfig::default()
    };
    let (server, mut exchange) = OpcUaServer::bind("127.0.0.1:0", &plc, config).unwrap();
    let mut session = Session::new(plc);
    exchange.exchange(session.plc_mut());
    let mut runner = TaskRunner::real_time(session.plc());
    runner.set_between_ticks(exchange.into_between_ticks());
    let trace = TraceWriter::new(std::io::sink(), TraceFormat::Csv, Vec::new(), false);
    let run = runner.spawn(session, None, trace);
    Served {
        server: Some(server),
        stop,
        run: Some(run),
        dir,
    }
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap()
}

#[test]
fn a_written_input_is_seen_by_the_program_in_a_later_cycle() {
    let s = serve("write", false);
    runtime().block_on(async {
        let c = connect(
            &s.url(),
            Security::Encrypt,
            Some(("op", "pw")),
            &s.client_pki("c"),
        )
        .await
        .unwrap();
        assert_eq!(
            c.read(&s.id("doubled")).await.value,
            Some(Variant::Int16(0))
        );
        assert_eq!(
            c.write(&s.id("setpoint"), Variant::Int16(21)).await,
            StatusCode::Good
        );
        let v = c
            .read_until(&s.id("doubled"), Duration::from_secs(5), |v| {
                *v == Variant::Int16(42)
            })
            .await;
        assert_eq!(
            v,
            Some(Variant::Int16(42)),
            "the program never saw the write"
        );
        // Any integer that fits is taken; one that does not is refused.
        assert_eq!(
            c.write(&s.id("setpoint"), Variant::Int64(-3)).await,
            StatusCode::Good
        );
        assert_eq!(
            c.write(&s.id("setpoint"), Variant::Int32(40_000)).await,
            StatusCode::BadOutOfRange
        );
        assert_eq!(
            c.write(&s.id("setpoint"), Variant::Boolean(true)).await,
            StatusCode::BadTypeMismatch
        );
        let v = c
            .read_until(&s.id("doubled"), Duration::from_secs(5), |v| {
                *v == Variant::Int16(-6)
            })
            .await;
        assert_eq!(v, Some(Variant::Int16(-6)));
        // The array of the last four setpoints, as one array Variable
        // (four cycles after the write, every element holds it).
        let all = |v: &Variant| match v {
            Variant::Array(a) => a.values == vec![Variant::Int16(-3); 4],
            _ => false,
        };
        let seq = c
            .read_until(&s.id("seq"), Duration::from_secs(5), all)
            .await;
        assert!(seq.as_ref().is_some_and(all), "{seq:?}");
        // TIME is a Duration in milliseconds; writes take milliseconds.
        assert_eq!(
            c.read(&s.id("delay")).await.value,
            Some(Variant::Double(1500.0))
        );
        assert_eq!(
            c.write(&s.id("delay"), Variant::Double(250.0)).await,
            StatusCode::Good
        );
        let v = c
            .read_until(&s.id("delay"), Duration::from_secs(5), |v| {
                *v == Variant::Double(250.0)
            })
            .await;
        assert_eq!(v, Some(Variant::Double(250.0)));
        c.close().await;
    });
}

#[test]
fn anonymous_clients_read_but_cannot_write() {
    let s = serve("anonymous", false);
    runtime().block_on(async {
        let c = connect(&s.url(), Security::Sign, None, &s.client_pki("c"))
            .await
            .unwrap();
        let ticks = c.read(&s.id("ticks")).await;
        assert!(matches!(ticks.value, Some(Variant::Int32(_))), "{ticks:?}");
        // The server counts the session (/metrics shows it).
        let stats = s.server.as_ref().unwrap().stats();
        assert_eq!((stats.sessions, stats.sessions_total), (1, 1));
        assert_eq!(
            c.write(&s.id("setpoint"), Variant::Int16(5)).await,
            StatusCode::BadUserAccessDenied
        );
        // The node says so: writable, but not by this user.
        let access = c
            .read_attribute(&s.id("setpoint"), AttributeId::AccessLevel)
            .await;
        assert_eq!(access.value, Some(Variant::Byte(3)));
        let user = c
            .read_attribute(&s.id("setpoint"), AttributeId::UserAccessLevel)
            .await;
        assert_eq!(user.value, Some(Variant::Byte(1)));
        tokio::time::sleep(Duration::from_millis(100)).await;
        assert_eq!(
            c.read(&s.id("doubled")).await.value,
            Some(Variant::Int16(0))
        );
        c.close().await;
    });
}

#[test]
fn constants_unknown_nodes_and_forced_variables() {
    let s = serve("refusals", false);
    runtime().block_on(async {
        let c = connect(
            &s.url(),
            Security::Encrypt,
            Some(("op", "pw")),
            &s.client_pki("c"),
        )
        .await
        .unwrap();
        assert_eq!(c.read(&s.id("limit")).await.value, Some(Variant::Int16(10)));
        assert_eq!(
            c.write(&s.id("limit"), Variant::Int16(3)).await,
            StatusCode::BadNotWritable
        );
        let unknown = c.read(&s.id("no_such_variable")).await;
        assert_eq!(unknown.status, Some(StatusCode::BadNodeIdUnknown));
        assert_eq!(
            c.write(&s.id("no_such_variable"), Variant::Int16(1)).await,
            StatusCode::BadNodeIdUnknown
        );
        // A write to a forced variable is accepted; the force wins.
        assert_eq!(c.read(&s.id("held")).await.value, Some(Variant::Int16(7)));
        assert_eq!(
            c.write(&s.id("held"), Variant::Int16(99)).await,
            StatusCode::Good
        );
        let ticks0 = c.read(&s.id("ticks")).await.value;
        c.read_until(&s.id("ticks"), Duration::from_secs(5), |v| {
            Some(v) != ticks0.as_ref()
        })
        .await;
        tokio::time::sleep(Duration::from_millis(100)).await;
        assert_eq!(c.read(&s.id("held")).await.value, Some(Variant::Int16(7)));
        // Enumerations are Int32, with EnumStrings; a value not declared is refused.
        assert_eq!(c.read(&s.id("mode")).await.value, Some(Variant::Int32(0)));
        assert_eq!(
            c.write(&s.id("mode"), Variant::Int32(7)).await,
            StatusCode::BadOutOfRange
        );
        let names = c.read(&s.id("mode#EnumStrings")).await.value.unwrap();
        let Variant::Array(names) = names else {
            panic!("EnumStrings is not an array")
        };
        assert_eq!(names.values.len(), 3);
        c.close().await;
    });
}

#[test]
fn a_subscription_receives_each_change() {
    let s = serve("subscribe", false);
    runtime().block_on(async {
        let c = connect(&s.url(), Security::Encrypt, None, &s.client_pki("c"))
            .await
            .unwrap();
        let seen = c
            .subscribe(&[s.id("ticks")], Duration::from_millis(50))
            .await;
        tokio::time::sleep(Duration::from_secs(1)).await;
        let values: Vec<i32> = seen
            .lock()
            .unwrap()
            .iter()
            .filter_map(|(_, dv)| match dv.value {
                Some(Variant::Int32(x)) => Some(x),
                _ => None,
            })
            .collect();
        assert!(values.len() >= 5, "too few notifications: {values:?}");
        assert!(values.windows(2).all(|w| w[0] < w[1]), "{values:?}");
        c.close().await;
    });
}

#[test]
fn wrong_passwords_and_insecure_logins_are_refused() {
    let s = serve("logins", false);
    runtime().block_on(async {
        let bad = connect(
            &s.url(),
            Security::Encrypt,
            Some(("op", "nope")),
            &s.client_pki("c"),
        )
        .await;
        assert!(bad.is_err(), "a wrong password was accepted");
        let none = connect(&s.url(), Security::None, None, &s.client_pki("c")).await;
        assert!(
            none.is_err(),
            "SecurityPolicy None was served without being asked for"
        );
    });
    drop(s);
    let s = serve("insecure", true);
    runtime().block_on(async {
        let c = connect(&s.url(), Security::None, None, &s.client_pki("c"))
            .await
            .expect("None is served when asked for");
        assert!(
            c.read(&s.id("ticks"))
                .await
                .status
                .is_none_or(|st| st.is_good())
        );
        c.close().await;
        let login = connect(
            &s.url(),
            Security::None,
            Some(("op", "pw")),
            &s.client_pki("c"),
        )
        .await;
        assert!(login.is_err(), "a password was accepted in clear");
    });
}

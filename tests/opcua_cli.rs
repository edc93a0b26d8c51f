//! `plcrun --opcua`: CHARIOT (programs/chariot.sfc) served in real time,
//! browsed, read, written and subscribed to by the `async-opcua` client;
//! `plcrun opcua-user add`; bad flags are usage errors with a code.

use crate::support::opcua_client;

use async_opcua::types::{
    BrowseDescription, BrowseDirection, BrowsePath, BrowseResultMask, NodeId, ObjectId,
    QualifiedName, ReferenceTypeId, RelativePath, RelativePathElement, StatusCode, Variant,
};
use opcua_client::{Client, Security, connect};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

fn plcrun() -> Command {
    Command::new(env!("CARGO_BIN_EXE_plcrun"))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("plcrun-opcua-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Adds a user with `plcrun opcua-user add`, the password on stdin.
fn add_user(file: &Path, name: &str, password: &str) {
    let mut child = plcrun()
        .args(["opcua-user", "add"])
        .arg(file)
        .arg(name)
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    writeln!(child.stdin.take().unwrap(), "{password}").unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The endpoint URL and namespace index a `--opcua` child announces on
/// standard error (the rest is drained on a thread).
fn announced(child: &mut Child) -> (String, u16) {
    let mut err = BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    loop {
        line.clear();
        assert!(err.read_line(&mut line).unwrap() > 0, "no announcement");
        if let Some(rest) = line.trim().strip_prefix("opcua: listening on ") {
            let (url, tail) = rest.split_once(' ').unwrap();
            let ns = tail.split("ns=").nth(1).unwrap().split(' ').next().unwrap();
            let out = (url.to_string(), ns.parse().unwrap());
            std::thread::spawn(move || std::io::copy(&mut err, &mut std::io::sink()));
            return out;
        }
    }
}

/// The browse names of the nodes `node` references hierarchically.
async fn children(c: &Client, node: NodeId) -> Vec<(String, NodeId)> {
    let d = BrowseDescription {
        node_id: node,
        browse_direction: BrowseDirection::Forward,
        reference_type_id: ReferenceTypeId::HierarchicalReferences.into(),
        include_subtypes: true,
        node_class_mask: 0,
        result_mask: BrowseResultMask::All as u32,
    };
    let results = c.session.browse(&[d], 1000, None).await.unwrap();
    results[0]
        .references
        .clone()
        .unwrap_or_default()
        .into_iter()
        .map(|r| (r.browse_name.name.as_ref().to_string(), r.node_id.node_id))
        .collect()
}

#[test]
fn chariot_is_browsed_read_written_and_subscribed_to() {
    let dir = temp_dir("chariot");
    let users = dir.join("users");
    add_user(&users, "operator", "s3cret");
    let mut child = plcrun()
        .args([
            "programs/chariot.sfc",
            "--realtime",
            "--opcua",
            "127.0.0.1:0",
        ])
        .arg("--opcua-users")
        .arg(&users)
        .arg("--opcua-pki")
        .arg(dir.join("pki"))
        .args(["--opcua-trust-clients", "--trace", "kmav", "--changes-only"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (url, ns) = announced(&mut child);
    let id = |path: &str| NodeId::new(ns, path);
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(async {
        let c = connect(
            &url,
            Security::Encrypt,
            Some(("operator", "s3cret")),
            &dir.join("client"),
        )
        .await
        .unwrap();
        // Browse: Objects > CHARIOT > the chart's variables and steps.
        let objects = children(&c, ObjectId::ObjectsFolder.into()).await;
        let (_, folder) = objects
            .iter()
            .find(|(n, _)| n == "CHARIOT")
            .expect("CHARIOT folder");
        let inside: Vec<String> = children(&c, folder.clone())
            .await
            .into_iter()
            .map(|(n, _)| n)
            .collect();
        for name in [
            "Dcy", "FcA", "FcB", "tX3", "KMAV", "KMAR", "VOM", "INIT", "AV", "ATT", "AR",
        ] {
            assert!(
                inside.iter().any(|n| n == name),
                "{name} missing from {inside:?}"
            );
        }
        let step: Vec<String> = children(&c, id("INIT"))
            .await
            .into_iter()
            .map(|(n, _)| n)
            .collect();
        assert!(
            step.contains(&"X".to_string()) && step.contains(&"T".to_string()),
            "{step:?}"
        );
        // TranslateBrowsePaths: Objects/CHARIOT/INIT/X is INIT.X.
        let element = |name: &str| RelativePathElement {
            reference_type_id: ReferenceTypeId::HierarchicalReferences.into(),
            is_inverse: false,
            include_subtypes: true,
            target_name: QualifiedName::new(ns, name),
        };
        let path = BrowsePath {
            starting_node: ObjectId::ObjectsFolder.into(),
            relative_path: RelativePath {
                elements: Some(vec![element("CHARIOT"), element("INIT"), element("X")]),
            },
        };
        let found = c
            .session
            .translate_browse_paths_to_node_ids(&[path])
            .await
            .unwrap();
        let targets = found[0].targets.clone().unwrap_or_default();
        assert_eq!(targets.len(), 1, "{found:?}");
        assert_eq!(targets[0].target_id.node_id, id("INIT.X"));
        // Read: the initial step is active; step flags are read-only.
        assert_eq!(
            c.read(&id("INIT.X")).await.value,
            Some(Variant::Boolean(true))
        );
        assert_eq!(
            c.write(&id("INIT.X"), Variant::Boolean(false)).await,
            StatusCode::BadNotWritable
        );
        assert_eq!(
            c.read(&id("tX3")).await.value,
            Some(Variant::Double(600_000.0))
        );
        // Subscribe to the contactors, then play the operator and the plant.
        let seen = c
            .subscribe(&[id("KMAV"), id("KMAR")], Duration::from_millis(20))
            .await;
        assert_eq!(
            c.write(&id("tX3"), Variant::Double(300.0)).await,
            StatusCode::Good
        );
        assert_eq!(
            c.write(&id("FcA"), Variant::Boolean(true)).await,
            StatusCode::Good
        );
        assert_eq!(
            c.write(&id("Dcy"), Variant::Boolean(true)).await,
            StatusCode::Good
        );
        let on = c
            .read_until(&id("KMAV"), Duration::from_secs(5), |v| {
                *v == Variant::Boolean(true)
            })
            .await;
        assert_eq!(on, Some(Variant::Boolean(true)), "KMAV never came on");
        for (name, value) in [("Dcy", false), ("FcA", false), ("FcB", true)] {
            assert_eq!(
                c.write(&id(name), Variant::Boolean(value)).await,
                StatusCode::Good
            );
        }
        let back = c
            .read_until(&id("KMAR"), Duration::from_secs(5), |v| {
                *v == Variant::Boolean(true)
            })
            .await;
        assert_eq!(back, Some(Variant::Boolean(true)), "KMAR never came on");
        tokio::time::sleep(Duration::from_millis(200)).await;
        let changes: Vec<(String, bool)> = seen
            .lock()
            .unwrap()
            .iter()
            .filter_map(|(n, dv)| match (&n.identifier, &dv.value) {
                (async_opcua::types::Identifier::String(s), Some(Variant::Boolean(b))) => {
                    Some((s.as_ref().to_string(), *b))
                }
                _ => None,
            })
            .collect();
        let kmav: Vec<bool> = changes
            .iter()
            .filter(|(n, _)| n == "KMAV")
            .map(|(_, b)| *b)
            .collect();
        let kmar: Vec<bool> = changes
            .iter()
            .filter(|(n, _)| n == "KMAR")
            .map(|(_, b)| *b)
            .collect();
        assert_eq!(kmav, [false, true, false], "{changes:?}");
        assert_eq!(kmar, [false, true], "{changes:?}");
        c.close().await;
    });
    child.kill().unwrap();
    child.wait().unwrap();
    // The certificate made on first start is kept.
    assert!(dir.join("pki/own/cert.der").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_opcua_settings_are_usage_errors_with_a_code() {
    let dir = temp_dir("bad");
    let run = |extra: &[&str]| {
        let out = plcrun()
            .args(["programs/chariot.sfc", "--cycles", "1"])
            .args(extra)
            .arg("--opcua-pki")
            .arg(dir.join("pki"))
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };
    let (code, err) = run(&["--opcua", "not an address"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("E950"), "{err}");
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = taken.local_addr().unwrap().to_string();
    let (code, err) = run(&["--opcua", &addr]);
    assert_eq!(code, Some(2));
    assert!(err.contains("E951"), "{err}");
    let missing = dir.join("no-such-users-file");
    let (code, err) = run(&[
        "--opcua",
        "127.0.0.1:0",
        "--opcua-users",
        missing.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(2));
    assert!(err.contains("E952"), "{err}");
    let (code, err) = run(&["--opcua", "127.0.0.1:0", "--opcua-expose", "nothing*"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("E954"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_virtual_time_run_with_an_idle_server_traces_as_without() {
    let dir = temp_dir("virtual");
    let run = |extra: &[&str]| {
        let out = plcrun()
            .args(["programs/chariot.sfc", "--cycles", "130", "--stimulus"])
            .arg("programs/chariot.csv")
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let pki = dir.join("pki");
    let plain = run(&[]);
    let served = run(&[
        "--opcua",
        "127.0.0.1:0",
        "--opcua-pki",
        pki.to_str().unwrap(),
    ]);
    assert!(plain.lines().count() > 100);
    assert_eq!(plain, served);
    std::fs::remove_dir_all(&dir).unwrap();
}

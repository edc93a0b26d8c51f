//! An OPC UA client for the tests, on the `async-opcua` client crate (an
//! implementation independent of plcrun's server code): connect, read,
//! write, browse, subscribe.

#![allow(dead_code)]

use async_opcua::client::{ClientBuilder, DataChangeCallback, IdentityToken, Session};
use async_opcua::crypto::SecurityPolicy;
use async_opcua::types::{
    AttributeId, DataValue, MessageSecurityMode, MonitoredItemCreateRequest, NodeId, ReadValueId,
    StatusCode, TimestampsToReturn, UserTokenPolicy, Variant, WriteValue,
};
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A connected session and its event loop.
pub struct Client {
    pub session: Arc<Session>,
    event_loop: tokio::task::JoinHandle<StatusCode>,
}

/// How to connect.
#[derive(Clone, Copy)]
pub enum Security {
    /// Basic256Sha256, signed and encrypted.
    Encrypt,
    /// Basic256Sha256, signed.
    Sign,
    /// SecurityPolicy None.
    None,
}

/// Connects to `url` with `security`, as `user` (`None`: anonymous); the
/// client's own certificate is made in `pki`.
pub async fn connect(
    url: &str,
    security: Security,
    user: Option<(&str, &str)>,
    pki: &Path,
) -> Result<Client, String> {
    let mut client = ClientBuilder::new()
        .application_name("plcrun test client")
        .application_uri("urn:plcrun:test-client")
        .product_uri("urn:plcrun:test-client")
        .create_sample_keypair(true)
        .trust_server_certs(true)
        .pki_dir(pki)
        .session_retry_limit(0)
        .client()
        .map_err(|e| format!("{e:?}"))?;
    let (policy, mode) = match security {
        Security::Encrypt => (
            SecurityPolicy::Basic256Sha256,
            MessageSecurityMode::SignAndEncrypt,
        ),
        Security::Sign => (SecurityPolicy::Basic256Sha256, MessageSecurityMode::Sign),
        Security::None => (SecurityPolicy::None, MessageSecurityMode::None),
    };
    let identity = match user {
        Some((name, password)) => IdentityToken::new_user_name(name, password),
        None => IdentityToken::Anonymous,
    };
    let endpoint = (url, policy.to_uri(), mode, UserTokenPolicy::anonymous());
    let (session, event_loop) = client
        .connect_to_matching_endpoint(endpoint, identity)
        .await
        .map_err(|e| e.to_string())?;
    let mut event_loop = event_loop.spawn();
    // A refused session ends the event loop (no retries) while
    // `wait_for_connection` would go on waiting: the first of the two
    // decides, so that a refusal is seen at once, not after the timeout.
    let outcome = tokio::time::timeout(Duration::from_secs(20), async {
        tokio::select! {
            connected = session.wait_for_connection() => connected,
            _ = &mut event_loop => false,
        }
    })
    .await
    .map_err(|_| "no connection in 20 s".to_string())?;
    if !outcome {
        return Err("the session was refused".into());
    }
    Ok(Client {
        session,
        event_loop,
    })
}

impl Client {
    /// Reads one node's value.
    pub async fn read(&self, id: &NodeId) -> DataValue {
        self.read_attribute(id, AttributeId::Value).await
    }

    /// Reads one attribute of one node.
    pub async fn read_attribute(&self, id: &NodeId, attribute: AttributeId) -> DataValue {
        let item = ReadValueId {
            node_id: id.clone(),
            attribute_id: attribute as u32,
            ..Default::default()
        };
        let mut values = self
            .session
            .read(&[item], TimestampsToReturn::Both, 0.0)
            .await
            .expect("read answered");
        values.remove(0)
    }

    /// Writes one node's value; the status the server gave.
    pub async fn write(&self, id: &NodeId, value: Variant) -> StatusCode {
        let item = WriteValue {
            node_id: id.clone(),
            attribute_id: AttributeId::Value as u32,
            value: DataValue::new_now(value),
            ..Default::default()
        };
        self.session.write(&[item]).await.expect("write answered")[0]
    }

    /// Polls `id` until its value satisfies `done` (or `wait` passes);
    /// the last value read.
    pub async fn read_until(
        &self,
        id: &NodeId,
        wait: Duration,
        done: impl Fn(&Variant) -> bool,
    ) -> Option<Variant> {
        let until = tokio::time::Instant::now() + wait;
        loop {
            let v = self.read(id).await.value;
            if v.as_ref().is_some_and(&done) || tokio::time::Instant::now() > until {
                return v;
            }
            tokio::time::sleep(Duration::from_millis(10)).await;
        }
    }

    /// Subscribes to the values of `ids` (sampling and publishing every
    /// `interval`); the values received, shared with the callback.
    pub async fn subscribe(
        &self,
        ids: &[NodeId],
        interval: Duration,
    ) -> Arc<Mutex<Vec<(NodeId, DataValue)>>> {
        let seen: Arc<Mutex<Vec<(NodeId, DataValue)>>> = Arc::default();
        let sink = seen.clone();
        let id = self
            .session
            .create_subscription(
                interval,
                100,
                10,
                0,
                0,
                true,
                DataChangeCallback::new(move |value, item| {
                    sink.lock()
                        .unwrap()
                        .push((item.item_to_monitor().node_id.clone(), value));
                }),
            )
            .await
            .expect("subscription made");
        let items: Vec<MonitoredItemCreateRequest> = ids
            .iter()
            .map(|n| {
                let mut r: MonitoredItemCreateRequest = n.clone().into();
                r.requested_parameters.sampling_interval = interval.as_secs_f64() * 1000.0;
                r.requested_parameters.queue_size = 100;
                r
            })
            .collect();
        let created = self
            .session
            .create_monitored_items(id, TimestampsToReturn::Both, items)
            .await
            .expect("monitored items made");
        for c in &created {
            assert!(c.result.status_code.is_good(), "{:?}", c.result.status_code);
        }
        seen
    }

    /// Closes the session.
    pub async fn close(self) {
        let _ = self.session.disconnect().await;
        let _ = self.event_loop.await;
    }
}

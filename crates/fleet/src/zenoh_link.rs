//! The Zenoh transport of an agent (feature `zenoh`): a peer-mode session with
//! multicast scouting off and explicit listen/connect endpoints. Each message goes out as
//! JSON (encoding `application/json`) on `PREFIX/MISSION/UAV/KIND`; the agent subscribes to
//! `PREFIX/MISSION/*/*` and skips its own key. Every other sample is handed over as it came,
//! its bytes and its key's last two chunks ([`Arrival`]), for the agent's check on arrival
//! ([`mason_mission::agent::Agent::admit`]): nothing is decoded here.
//!
//! An agent also answers queries on `PREFIX/MISSION/UAV/scene` with the wall it builds
//! ([`ZenohLink::serve_scene`]): how a client that is not a teammate (the ROS 2 bridge) learns
//! where each brick goes. A query is not a sample: the teammates' subscriptions never see it.

use crate::error::{FleetError, FleetResult};
use crate::network::Network;
use crate::transport::Transport;
use mason_mission::agent::{Arrival, Message, MessageKind, SampleKey};
use std::collections::HashMap;
use std::sync::mpsc;
use std::time::Instant;
use zenoh::bytes::Encoding;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::query::Queryable;
use zenoh::{Session, Wait};

/// How long a dropped connection waits before it is tried again at first, and at most (ms).
const RETRY_MS: (u32, u32) = (100, 1000);

/// One agent's Zenoh session.
pub struct ZenohLink {
    session: Session,
    prefix: String,
    publishers: HashMap<&'static str, Publisher<'static>>,
    rx: mpsc::Receiver<Arrival>,
    _subscriber: Subscriber<()>,
    scene: Option<Queryable<()>>,
}

/// The last chunk of the key an agent answers scene queries on.
pub const SCENE_KIND: &str = "scene";

fn json_list(items: &[String]) -> String {
    serde_json::to_string(items).expect("strings")
}

/// The session's configuration: peer mode, no multicast scouting, the given endpoints.
pub fn config(net: &Network) -> FleetResult<zenoh::Config> {
    let mut c = zenoh::Config::default();
    let mut set = |key: &str, value: String| {
        c.insert_json5(key, &value)
            .map_err(|e| FleetError::Network(format!("zenoh configuration {key} = {value}: {e}")))
    };
    set("mode", "\"peer\"".into())?;
    set("scouting/multicast/enabled", "false".into())?;
    set("listen/endpoints", json_list(&net.listen))?;
    set("connect/endpoints", json_list(&net.connect))?;
    set(
        "connect/retry",
        format!(
            "{{\"period_init_ms\": {}, \"period_max_ms\": {}, \"period_increase_factor\": 2}}",
            RETRY_MS.0, RETRY_MS.1
        ),
    )?;
    Ok(c)
}

impl ZenohLink {
    /// Opens the session for UAV `me` (exit 2 if an endpoint is refused, e.g. a port in use).
    pub fn open(net: &Network, me: usize) -> FleetResult<Self> {
        let session = zenoh::open(config(net)?).wait().map_err(|e| {
            FleetError::Network(format!(
                "zenoh: cannot open a session (listen {:?}, connect {:?}): {e}",
                net.listen, net.connect
            ))
        })?;
        let prefix = format!("{}/{}", net.prefix, net.mission);
        let (tx, rx) = mpsc::channel();
        let own = format!("{prefix}/{me}/");
        let subscriber = session
            .declare_subscriber(format!("{prefix}/*/*"))
            .callback(move |sample| {
                let key = sample.key_expr().as_str();
                if !key.starts_with(&own) {
                    let bytes = sample.payload().to_bytes().into_owned();
                    let _ = tx.send(Arrival::bytes(SampleKey::parse(key), bytes));
                }
            })
            .wait()
            .map_err(|e| {
                FleetError::Network(format!("zenoh: cannot subscribe to {prefix}/*/*: {e}"))
            })?;
        Ok(ZenohLink {
            session,
            prefix: format!("{prefix}/{me}"),
            publishers: HashMap::new(),
            rx,
            _subscriber: subscriber,
            scene: None,
        })
    }

    /// Answers every query on `PREFIX/MISSION/UAV/scene` with `scene` (JSON, e.g.
    /// [`mason_report::wall_scene_json`]) for as long as the session is open.
    pub fn serve_scene(&mut self, scene: &serde_json::Value) -> FleetResult<()> {
        let key = format!("{}/{SCENE_KIND}", self.prefix);
        let bytes = serde_json::to_vec(scene).expect("a JSON value serialises");
        let reply_key = key.clone();
        let queryable = self
            .session
            .declare_queryable(&key)
            .callback(move |query| {
                let _ = query
                    .reply(&reply_key, bytes.clone())
                    .encoding(Encoding::APPLICATION_JSON)
                    .wait();
            })
            .wait()
            .map_err(|e| FleetError::Network(format!("zenoh: cannot serve {key}: {e}")))?;
        self.scene = Some(queryable);
        Ok(())
    }

    fn publisher(&mut self, kind: MessageKind) -> Option<&Publisher<'static>> {
        let key = kind.key();
        if !self.publishers.contains_key(key) {
            let p = self
                .session
                .declare_publisher(format!("{}/{key}", self.prefix))
                .encoding(Encoding::APPLICATION_JSON)
                .wait()
                .ok()?;
            self.publishers.insert(key, p);
        }
        self.publishers.get(key)
    }

    /// Closes the session (pending messages are flushed).
    pub fn close(self) {
        let ZenohLink {
            session,
            publishers,
            _subscriber,
            scene,
            ..
        } = self;
        drop(scene);
        drop(_subscriber);
        drop(publishers);
        let _ = session.close().wait();
    }
}

impl Transport for ZenohLink {
    fn send(&mut self, m: &Message) {
        let bytes = serde_json::to_vec(m).expect("a message serialises");
        if let Some(p) = self.publisher(m.kind) {
            // Best effort: a message lost here is repaired by the next heartbeat.
            let _ = p.put(bytes).wait();
        }
    }

    fn recv(&mut self, deadline: Instant) -> Vec<Arrival> {
        let wait = deadline.saturating_duration_since(Instant::now());
        let mut out = Vec::new();
        if let Ok(a) = self.rx.recv_timeout(wait) {
            out.push(a);
            out.extend(self.rx.try_iter());
        }
        out
    }
}
